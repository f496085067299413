#!/usr/bin/env python3
"""make bench: the cost of the FE friction tables.

1. Per bundled table (data/tables/*.h5): points done, the build's wall time,
   CPU seconds per point computed (mean, range, by t/R), Newton iterations and
   factorizations per point, read from the points' own records; the points
   copied from another's run (one material: t/R means nothing there).
   The normal grid of each table (axisymmetric load curves for the preload's
   P and A): curves and CPU seconds per curve, from the curves' records.
   The wall time of reading the table, which rebuilds its mu_s surrogate
   (from the stored hyperparameters when its points are those they were
   fitted to, else by a search), with the surrogate's leave-one-out error.
   What refining it in place would cost (`table info --placements-max 8
   --refine-err X`): the points computed again and their recorded CPU time.
2. What keeping a point's members saves (table format 6 on): one thesis-family
   point (8 omega_c_su, t/R 0.025, Eco/Esu 2) built with one placement, then
   refined in place to two, against the two-placement build from scratch:
   CPU seconds of each, the members taken, and whether the refined point
   equals the fresh one (every stored number but the timings).
3. What sharing one normal loading run per (t/R, Eco/Esu) column could save:
   one table point at the thesis family's settings run by `stiction asperity
   --shear` with the normal step and the shear ramp timed apart (the normal
   step's share of a point is the most that sharing it could save).

Usage: bench-tables.py CLI [TABLE ...]"""
import csv
import glob
import io
import json
import statistics
import os
import subprocess
import sys
import tempfile
import time


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr))
    return p.stdout


def table_costs(cli, path):
    t0 = time.monotonic()
    info = json.loads(run([cli, "table", "info", path, "--json"]))
    read_s = time.monotonic() - t0
    rows = [r for r in csv.DictReader(io.StringIO(run([cli, "table", "info", path, "--points"])))
            if r["state"] == "done"]
    print("%s: %d points, %d done, %d failed, %d pending; build %.1f min wall"
          % (path, info["points"], info["done"], info["failed"], info["pending"],
             info["build_wall_s"] / 60))
    if "loo_rms_rel" in info:
        print("  read, with the mu_s surrogate (%s): %.2f s wall; its leave-one-out error "
              "%.2f %% rms, gamma %.2f"
              % ("stored fit" if info.get("fit_reused") else "searched", read_s,
                 100 * info["loo_rms_rel"], info["gamma"]))
    copies = [r for r in rows if r.get("source", r["index"]) != r["index"]]
    rows = [r for r in rows if r.get("source", r["index"]) == r["index"]]  # the runs
    if copies:
        print("  one material (Eco/Esu 1, layers alike): %d points hold the first t/R's run, "
              "computed once" % len(copies))
    if not rows:
        return
    cpu = [float(r["cpu_s"]) for r in rows]
    print("  CPU s per point: mean %.1f, min %.1f, max %.1f; total %.1f CPU min"
          % (statistics.mean(cpu), min(cpu), max(cpu), sum(cpu) / 60))
    print("  %-8s %7s %12s %12s %10s %10s" % ("t/R", "points", "CPU s mean", "CPU s max",
                                               "Newton", "factor."))
    for t in sorted({float(r["t_over_R"]) for r in rows}):
        sel = [r for r in rows if float(r["t_over_R"]) == t]
        c = [float(r["cpu_s"]) for r in sel]
        print("  %-8g %7d %12.1f %12.1f %10.0f %10.0f"
              % (t, len(sel), statistics.mean(c), max(c),
                 statistics.mean(int(r["newton_iterations"]) for r in sel),
                 statistics.mean(int(r["factorizations"]) for r in sel)))


def refine_costs(cli, path):
    """the points a refinement up to 8 placements would compute again"""
    parts = []
    for x in (0.04, 0.08):
        p = subprocess.run([cli, "table", "info", path, "--placements-max", "8",
                            "--refine-err", str(x), "--json"], capture_output=True, text=True)
        if p.returncode != 0:  # a table refined further already: nothing to plan
            return
        r = json.loads(p.stdout)["refine_plan"]
        parts.append("%d points at %g (their first members %.0f CPU s)"
                     % (r["points"], x, r["their_cpu_s"]))
    print("  refined in place up to 8 placements: " + "; ".join(parts)
          + "; the members added cost at least as much again")


def curve_costs(cli, path):
    info = json.loads(run([cli, "table", "info", path, "--json"]))
    g = info.get("normal_grid", {})
    if not g.get("curves"):
        print("  normal grid: none (preload from the 3D points)")
        return
    out = run([cli, "table", "info", path])
    line = [l.strip() for l in out.splitlines() if l.strip().startswith("normal grid")]
    print("  " + (line[0] if line else "normal grid: %d curves" % g["curves"]))


def build_point(cli, out, extra):
    cfg = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples",
                       "thesis-table.ini")
    t0 = time.monotonic()
    r = json.loads(run([cli, "table", "build", "--config", cfg, "--deltas", "8", "--t-over-R",
                        "0.025", "--E-ratio", "2", "--placements", "1", "--normal-level", "-1",
                        "--jobs", "1", "--quiet", "--json", "--out", out] + extra))
    return r["this_run"], time.monotonic() - t0


def point_row(cli, path):
    row = [r for r in csv.DictReader(io.StringIO(run([cli, "table", "info", path, "--points"])))
           if r["state"] == "done"][0]
    return {k: v for k, v in row.items() if k not in ("wall_s", "cpu_s")}


def member_reuse(cli):
    print("\nkeeping a point's members (thesis family, 8 omega_c_su, t/R 0.025, Eco/Esu 2, one "
          "thread):")
    refine = ["--placements-max", "2", "--refine-err", "0.001"]
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "refined.h5"), os.path.join(d, "fresh.h5")
        one, w1 = build_point(cli, a, ["--placements-max", "0"])
        ref, w2 = build_point(cli, a, refine)
        fresh, w3 = build_point(cli, b, refine)
        cpu = lambda r: r["cpu_s_per_point"] * r["computed"]
        print("  one placement: %.1f CPU s (%.1f s wall)" % (cpu(one), w1))
        print("  refined in place to two: %.1f CPU s (%.1f s wall), %d member taken from the file"
              % (cpu(ref), w2, ref["members_taken"]))
        print("  two placements from scratch: %.1f CPU s (%.1f s wall)" % (cpu(fresh), w3))
        same = point_row(cli, a) == point_row(cli, b)
        print("  the refined point equals the fresh one in every stored number but the "
              "timings: %s" % ("yes" if same else "NO"))
        if not same:
            sys.exit("member reuse: the refined point differs from the fresh build")


def normal_share(cli):
    print("\nnormal step versus shear ramp of one point (thesis family, t/R 0.025, "
          "Eco/Esu 2, stick, one placement, one thread):")
    print("  %-10s %10s %10s %12s" % ("delta/wc", "normal s", "ramp s", "normal share"))
    for d in (1, 10, 30):
        out = json.loads(run([cli, "asperity", "--t-over-R", "0.025", "--E-ratio", "2",
                              "--contact", "stick", "--delta", str(d), "--shear", "--threads",
                              "1", "--json"]))
        normal = out["wall_s"]
        ramp = out["shear_wall_s"]
        print("  %-10g %10.1f %10.1f %11.0f %%" % (d, normal, ramp,
                                                  100 * normal / (normal + ramp)))


def main():
    cli = sys.argv[1]
    tables = sys.argv[2:] or sorted(glob.glob("data/tables/*.h5"))
    for t in tables:
        table_costs(cli, t)
        refine_costs(cli, t)
        curve_costs(cli, t)
    member_reuse(cli)
    normal_share(cli)
    print("  solver reuse kept: none. A shared normal loading run per column could save at "
          "most the share above, and only on one mesh fit for every contact of the column "
          "(a 3D mesh level costs 5-10x the one below, docs/design.md 2.6); the preload's P "
          "and A come from the normal grid instead, at the CPU s per curve listed per table. "
          "Work skipped instead: the plane where the coating is the substrate is computed "
          "once, as the uncoated sphere (the copies above), and a point's finished placement "
          "members are kept for a resumed or refined build (measured above).")


if __name__ == "__main__":
    main()
