#!/usr/bin/env python3
"""Elastic junction growth of the FE tangential step against the elastic
half-space boundary elements (`stiction halfspace`; docs/design.md §5.6).

validate-growth.py CLI OUT.csv OUT.md [--omegas 0.5,1,3] [--n 6,6.6] [--cells 256]
                   [--foot-rows 0.6,0]

The WSP sphere (E = 74 GPa, nu = 0.33, R' = 10.5 mm) kept elastic (Y-su just
below E) with tau_c = 325/sqrt(3) MPa, the shear strength of the WSP check,
at delta = omega x omega_c of the WSP sphere (Y = 325 MPa): slip normal step,
then the ramp to full slip with no separation.  The growth is
Q_max / (tau_c pi a0^2) - 1 for the FE (a0 its preload radius) and A / A0 - 1
for the half-space.  FE runs at several --elements-per-contact values (the
node placement moves with it, docs/design.md §4.5) and junction readings
(--foot-rows: 0 the three axis lines, the default; 0.6 the node rows), one
thread each, one at a time.  Writes OUT.csv (via OUT.csv.tmp) and the report OUT.md; exits 1 if a run fails or an FE
growth is more than 3 % (of the area) from the reference (the bound of
tests/test_shear.c test_elastic_growth_bem).
"""
import argparse
import json
import math
import subprocess
import sys
import time

from vreport import Report
from wsp_case import WSP_SPHERE, write_csv

TAU = 325.0 / math.sqrt(3.0)
BASE = WSP_SPHERE + ["--t-over-R", "0"]
TOL = 0.03


def run(cmd):
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        return None, wall, (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
    j = json.loads(p.stdout)
    return (j[0] if isinstance(j, list) else j), wall, ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("report")
    ap.add_argument("--omegas", default="0.5,1,3")
    ap.add_argument("--n", default="6,6.6")
    ap.add_argument("--cells", default="256")
    ap.add_argument("--foot-rows", default="0,0.6")
    a = ap.parse_args()
    # omega_c of the WSP sphere (Y = 325 MPa), from the closed forms
    f, _, why = run([a.cli, "formulas", "--json", "--Y-su", "325"] + BASE)
    if f is None:
        print("formulas failed: " + why)
        return 1
    wc = f["omega_c_mm"]
    cols = ["omega_over_omega_c", "delta_mm", "model", "elements_per_contact", "foot_rows",
            "growth_pct",
            "error_pct", "mu_s", "a_lead_over_a0", "a_trail_over_a0", "a_side_over_a0",
            "dofs", "wall_s", "reason"]
    rows = []
    for w in [float(x) for x in a.omegas.split(",")]:
        d = w * wc
        b, wall, why = run([a.cli, "halfspace", "--json", "--delta-mm", "%.10g" % d,
                            "--tau-c", "%.10g" % TAU, "--cells", a.cells, "--steps", "2"] + BASE)
        if b is None:
            rows.append({"omega_over_omega_c": w, "model": "half-space", "reason": why})
            print("omega %g: half-space FAILED: %s" % (w, why))
            continue
        ref = b["area_growth"]
        rows.append({"omega_over_omega_c": w, "delta_mm": "%.6g" % d, "model": "half-space",
                     "growth_pct": "%+.2f" % (100 * ref), "mu_s": "%.5f" % b["mu_s"],
                     "a_lead_over_a0": "%.4f" % b["a_lead_over_a0"],
                     "a_trail_over_a0": "%.4f" % b["a_trail_over_a0"],
                     "a_side_over_a0": "%.4f" % b["a_side_over_a0"], "wall_s": "%.1f" % wall})
        print("omega %g: half-space growth %+.2f %% (trail %+.1f %%, %s cells, %.1f s)"
              % (w, 100 * ref, 100 * (b["a_trail_over_a0"] - 1), a.cells, wall), flush=True)
        for n in a.n.split(","):
            for fr in a.foot_rows.split(","):
                j, wall, why = run([a.cli, "asperity", "--shear", "--model", "3d", "--contact",
                                    "slip", "--threads", "1", "--Y-su", "70000", "--tau-c",
                                    "%.10g" % TAU, "--delta-mm", "%.10g" % d,
                                    "--elements-per-contact", n, "--foot-rows", fr,
                                    "--json"] + BASE)
                good = j is not None and j.get("converged") and j.get("Q_max_N") is not None
                r = {"omega_over_omega_c": w, "delta_mm": "%.6g" % d, "model": "FE",
                     "elements_per_contact": n, "foot_rows": fr, "wall_s": "%.1f" % wall,
                     "reason": (j or {}).get("reason", why)}
                if good:
                    g = j["Q_max_N"] / (j["tau_c_MPa"] * math.pi * j["a_mm"] ** 2) - 1
                    r.update({"growth_pct": "%+.2f" % (100 * g),
                              "error_pct": "%+.2f" % (100 * (g - ref)),
                              "mu_s": "%.5f" % j["mu_s"], "dofs": j["dofs"]})
                    print("  FE n = %s, foot rows %s: growth %+.2f %% (error %+.2f %%), mu_s "
                          "%.4f, %d DOFs, %.0f s" % (n, fr, 100 * g, 100 * (g - ref), j["mu_s"],
                                                     j["dofs"], wall), flush=True)
                else:
                    print("  FE n = %s, foot rows %s: FAILED: %s" % (n, fr, r["reason"]))
                rows.append(r)
    write_csv(a.out, cols, rows)
    rep = Report("Elastic junction growth: FE tangential step against the half-space",
                 "tools/validate-growth.py (`stiction asperity --shear`, `stiction halfspace`)")
    rep.out("The WSP sphere kept elastic, tau_c = %.1f MPa, slip normal step, then the ramp to "
            "full slip; growth = Q_max / (tau_c pi a0^2) - 1 (FE) and A / A0 - 1 (half-space "
            "boundary elements, %s cells). FE at two node placements, each read on the three "
            "axis lines (the default) and on the node rows within 0.6 a0." % (TAU, a.cells))
    rep.out("")
    ref = {}
    for r in rows:
        if r["model"] == "half-space":
            ref[r["omega_over_omega_c"]] = r.get("growth_pct")
            if not r.get("growth_pct"):
                rep.check("%g omega_c: half-space run" % r["omega_over_omega_c"], "-", "converges",
                          r["reason"], False)
            continue
        w = r["omega_over_omega_c"]
        name = "%g omega_c, %s elements per contact, %s: growth" % (
            w, r["elements_per_contact"],
            "node rows %s a0" % r["foot_rows"] if float(r["foot_rows"]) > 0 else "axis lines")
        src = "elastic half-space, boundary elements"
        if r.get("growth_pct") and ref.get(w):
            rep.check(name, src + " (%s %%)" % ref[w], "3 % of the area",
                      "%s %% (error %s %%)" % (r["growth_pct"], r["error_pct"]),
                      abs(float(r["error_pct"])) <= 100 * TOL)
        else:
            rep.check(name, src, "converges", r["reason"], False)
    return rep.write(a.report)


if __name__ == "__main__":
    sys.exit(main())
