#!/usr/bin/env python3
"""Smoothness of mu_s along the interference: single shear runs of the WSP
sphere at log-spaced delta, the point-to-point wiggle of each numerics and of
each inception reading of the same ramps (docs/design.md sections 4.4, 4.5).

validate-smoothness.py CLI OUT.csv OUT.md [--omegas A:B:N] [--edge-refine 0,2]
                       [--jobs 2] [--work DIR]

The WSP sphere (E = 74 GPa, nu = 0.33, Y = 325 MPa, R' = 10.5 mm, slip
normal step) at N log-spaced omega/omega_c from A to B (default 0.5:60:20),
one `stiction asperity --shear` run each, one thread, --jobs of them at a
time, for each --edge-refine value (0: the default numerics; 2: the band
around the contact edge).  Each run keeps its ramp (shear.csv) in
WORK/e<K>/<omega>/, and WORK/version holds the program that made them: a
second call with the same program takes the finished runs instead of running
them again (an interrupted validation loses at most the runs under way).

The wiggle at an inner point is half the second difference of ln mu_s,
(ln mu_(i-1) - 2 ln mu_i + ln mu_(i+1)) / 2: the point's distance from the
straight line through its neighbours in (ln delta, ln mu_s) for evenly
log-spaced delta, which a smooth mu_s(delta) keeps near zero.  Read on each
ramp as run (the solver's criterion) and offline at the first crossing of the
fraction of the contact at its shear limit through 0.90 ... 0.99 and where the
secant stiffness falls to 0.1 / 0.05 of the first (tools/ramp_read.py), so
the table says which part of the wiggle is the Q(ux) curve and which part is
where inception is declared.

Writes OUT.csv (via OUT.csv.tmp; one row a run) and the report OUT.md; exits
1 if a run fails (the smoothness itself is a target, not a check).
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor, as_completed

from ramp_read import load_shear_csv, readings
from vreport import Report
from wsp_case import WSP, write_csv, wsp_mu

FRACTIONS = (0.90, 0.95, 0.98, 0.99)
STIFFNESS = (0.1, 0.05)
READINGS = ["as run"] + ["f >= %.2f" % x for x in FRACTIONS] + ["KT <= %g KT1" % a
                                                                   for a in STIFFNESS]
GOAL = 1.0  # per cent: the largest wiggle a table can take with little smoothing


def omegas(spec):
    try:
        a, b, n = spec.split(":")
        a, b, n = float(a), float(b), int(n)
    except ValueError:
        sys.exit("validate-smoothness.py: --omegas %r: A:B:N expected" % spec)
    if not (0.0 < a < b and n >= 3):
        sys.exit("validate-smoothness.py: --omegas %r: 0 < A < B and N >= 3 expected" % spec)
    return [a * (b / a) ** (i / (n - 1)) for i in range(n)]


def version(cli):
    """The whole of `stiction --version`: program, commit and BLAS kernels.
    Not refdata.binary_version (program and commit only): other kernels move
    the last bits, and those move a band run past 20 omega_c by up to 2 %
    (docs/design.md section 4.5), so kept runs are reused under the same
    kernels only."""
    p = subprocess.run([cli, "--version"], capture_output=True, text=True)
    return p.stdout.strip()


def one_run(cli, work, k, w):
    """The run at omega w with --edge-refine k: (json or None, ramp, wall s,
    taken from an earlier call, failure reason)."""
    d = os.path.join(work, "e%d" % k, "%.10g" % w)  # the delta run, every digit
    res = os.path.join(d, "result.json")
    if os.path.exists(res):
        with open(res) as f:
            j = json.load(f)
        return j, load_shear_csv(os.path.join(d, "shear.csv")), j["_wall_s"], True, ""
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(os.path.dirname(d), exist_ok=True)
    t0 = time.time()
    p = subprocess.run([cli, "asperity", "--shear", "--json", "--threads", "1", "--delta",
                        "%.10g" % w, "--edge-refine", str(k), "--out", d] + WSP,
                       capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        return None, None, wall, False, (p.stderr.strip().splitlines() or
                                         ["exit %d" % p.returncode])[-1]
    j = json.loads(p.stdout)
    j["_wall_s"] = wall
    with open(res + ".tmp", "w") as f:
        json.dump(j, f)
    os.replace(res + ".tmp", res)
    return j, load_shear_csv(os.path.join(d, "shear.csv")), wall, False, ""


def wiggles(v):
    """Half second differences of ln v at the inner points (None where a
    neighbour has no value)."""
    out = []
    for i in range(1, len(v) - 1):
        if None in (v[i - 1], v[i], v[i + 1]):
            out.append(None)
        else:
            out.append(50.0 * (math.log(v[i - 1]) - 2.0 * math.log(v[i]) + math.log(v[i + 1])))
    return out


def summary(w):
    """(largest |wiggle|, rms, points above GOAL, points read) over the inner points."""
    x = [abs(a) for a in w if a is not None]
    if not x:
        return None
    return max(x), math.sqrt(sum(a * a for a in x) / len(x)), sum(a > GOAL for a in x), len(x)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("report")
    ap.add_argument("--omegas", default="0.5:60:20")
    ap.add_argument("--edge-refine", default="0,2")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work")
    a = ap.parse_args()
    ws = omegas(a.omegas)
    try:
        ks = [int(k) for k in a.edge_refine.split(",")]
    except ValueError:
        sys.exit("validate-smoothness.py: --edge-refine %r: a list of 0, 1, 2 expected"
                 % a.edge_refine)
    if a.jobs < 1:
        sys.exit("validate-smoothness.py: --jobs %d: must be >= 1" % a.jobs)
    work = a.work or os.path.join(os.path.dirname(os.path.abspath(a.out)), "smoothness-runs")
    ver = version(a.cli)
    stamp = os.path.join(work, "version")
    if os.path.exists(stamp) and open(stamp).read() != ver:
        shutil.rmtree(work)  # another program's runs: not this one's answers
    os.makedirs(work, exist_ok=True)
    with open(stamp, "w") as f:
        f.write(ver)

    jobs = [(k, w) for k in ks for w in ws]
    runs = {}
    t0 = time.time()
    with ThreadPoolExecutor(max_workers=a.jobs) as pool:
        futs = {pool.submit(one_run, a.cli, work, k, w): (k, w) for k, w in jobs}
        for n, fut in enumerate(as_completed(futs), 1):
            k, w = futs[fut]
            j, pts, wall, old, why = fut.result()
            runs[(k, w)] = (j, pts, wall, why)
            state = ("taken from an earlier run" if old else "%.0f s" % wall) if j else \
                "FAILED: " + why
            print("[%d/%d, %.0f s] edge refine %d, %.4g omega_c: %s%s" % (
                n, len(jobs), time.time() - t0, k, w,
                "mu_s %.5f, " % j["mu_s"] if j else "", state), flush=True)

    cols = ["edge_refine", "omega_over_omega_c", "mu_s", "wsp_fit", "wiggle_pct",
            "Q_still_rising", "ux_slide_over_omega_c", "a0_over_a_max", "wall_s", "reason"]
    cols += ["read_" + r.replace(" ", "_").replace(">=", "ge").replace("<=", "le")
             for r in READINGS[1:]]
    rows, read, wig = [], {}, {}  # wig[k]: as run, at every point (None at the ends)
    for k in ks:
        per = []
        for w in ws:
            j, pts, wall, why = runs[(k, w)]
            if j is None:
                per.append([None] * len(READINGS))
                continue
            per.append(readings(pts, j["mu_s"], FRACTIONS, STIFFNESS))
        read[k] = per
        wig[k] = [None] + wiggles([p[0] for p in per]) + [None]
        for i, w in enumerate(ws):
            j, pts, wall, why = runs[(k, w)]
            r = {"edge_refine": k, "omega_over_omega_c": "%.6g" % w, "wsp_fit": "%.5f" % wsp_mu(w),
                 "wall_s": "%.1f" % wall, "reason": j["reason"] if j else why}
            if j:
                r.update({"mu_s": "%.6f" % j["mu_s"],
                          "Q_still_rising": int(bool(j.get("Q_still_rising"))),
                          "ux_slide_over_omega_c": "%.4f" % j["ux_at_slide_over_omega_c"],
                          "a0_over_a_max": "%.4f" % (j["a_mm"] / j["a_max_mm"])})
                if wig[k][i] is not None:
                    r["wiggle_pct"] = "%+.2f" % wig[k][i]
                for name, v in zip(cols[-len(READINGS) + 1:], per[i][1:]):
                    r[name] = "" if v is None else "%.6f" % v
            rows.append(r)
    write_csv(a.out, cols, rows)

    rep = Report("Smoothness of mu_s along the interference",
                 "tools/validate-smoothness.py (`stiction asperity --shear` runs)")
    rep.out("The Wu-Shi-Polycarpou sphere (slip normal step) at %d log-spaced omega/omega_c from "
            "%g to %g, one single run each (one thread, %d at a time), with the default numerics"
            "%s. wiggle: half the second difference of ln mu_s, in per cent (a smooth mu_s(delta) "
            "keeps it near zero). a0/a_max: the preload's contact radius over the radius the mesh "
            "is sized for, which sets where the contact edge falls between the surface nodes."
            % (len(ws), ws[0], ws[-1], a.jobs,
               "" if ks == [0] else " and " + ", ".join("--edge-refine %d" % k for k in ks if k)))
    rep.out("")
    head = "| omega/omega_c | WSP fit |"
    for k in ks:
        lab = "default" if k == 0 else "edge refine %d" % k
        head += " mu_s, %s | wiggle | vs fit | a0/a_max | s |" % lab
    rep.out(head)
    rep.out("|---|---|" + "---|---|---|---|---|" * len(ks))
    for i, w in enumerate(ws):
        line = "| %.4g | %.4f |" % (w, wsp_mu(w))
        for k in ks:
            j, pts, wall, why = runs[(k, w)]
            wi = wig[k][i]
            if j is None:
                line += " failed | | | | |"
                continue
            line += " %.5f%s | %s | %+.1f %% | %.3f | %.0f |" % (
                j["mu_s"], "*" if j.get("Q_still_rising") else "",
                "%+.2f %%" % wi if wi is not None else "", 100 * (j["mu_s"] / wsp_mu(w) - 1),
                j["a_mm"] / j["a_max_mm"], wall)
        rep.out(line)
    rep.out("")
    rep.out("\\* Q still rising past inception (docs/design.md section 4.4).")
    rep.out("")
    rep.out("The same ramps read at other inception rules (tools/ramp_read.py): the largest "
            "|wiggle|, its rms over the inner points and how many exceed %g %%." % GOAL)
    rep.out("")
    rep.out("| numerics | " + " | ".join(READINGS) + " |")
    rep.out("|---|" + "---|" * len(READINGS))
    for k in ks:
        cells = []
        for r in range(len(READINGS)):
            s = summary(wiggles([p[r] for p in read[k]]))
            cells.append("—" if s is None else "%.2f %% (rms %.2f), %d of %d" % s)
        rep.out("| %s | %s |" % ("default" if k == 0 else "edge refine %d" % k, " | ".join(cells)))
    rep.out("")
    for k in ks:
        for w in ws:
            j, pts, wall, why = runs[(k, w)]
            if j is None:
                rep.check("edge refine %d, %.4g omega_c: the run converges" % (k, w),
                          "solver outcome", "converged", why, False)
    fails = sum(runs[(k, w)][0] is None for k in ks for w in ws)
    rep.check("every run converges", "solver outcome", "converged",
              "%d of %d" % (len(jobs) - fails, len(jobs)), fails == 0)
    if 0 in ks:
        s = summary(wig[0])
        if s:
            rep.target("single default run: mu_s along delta without point-to-point wiggle",
                       "every inner point within %g %%" % GOAL,
                       "largest %.2f %%, %d of %d above" % (s[0], s[2], s[3]), s[2] == 0)
    return rep.write(a.report)


if __name__ == "__main__":
    sys.exit(main())
