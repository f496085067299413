#!/usr/bin/env python3
"""The homogeneous Wu-Shi-Polycarpou sphere under
combined loading against the WSP fit mu_s = 0.3 coth(0.57 (omega/omega_c)^0.41)
(Wu, Shi & Polycarpou 2012; thesis eq. 4.1), within 5 %.

validate-shear.py CLI OUT.csv [--levels 0,1] [--omegas 0.5,1,3,6,12,24,48,72]

E = 74 GPa, nu = 0.33, Y = 325 MPa, R' = 10.5 mm, slip normal step, shear
criterion, 3D model.  One `stiction asperity --shear --json` run per
(level, omega), one at a time (each uses the machine's threads).  Writes
OUT.csv (OUT.csv.part holds the rows done so far; OUT.csv appears at the end) with mu_s, the fit, the
error, Q_max/Pc, ux at slide, wall time, DOFs, Newton iterations and
factorizations; a failed run is a row with its reason and no numbers.
Exit status 1 if any run failed or missed the 5 % band.
"""
import argparse
import json
import subprocess
import sys
import time

from wsp_case import WSP, write_progress, wsp_mu as wsp_fit
TOL = 0.05  # the band on mu_s against the fit


def run(cli, level, omega):
    cmd = [cli, "asperity", "--shear", "--model", "3d", "--mesh", str(level),
           "--delta", "%g" % omega, "--json"] + WSP
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    try:
        j = json.loads(p.stdout)
    except ValueError:
        j = {}
    if p.returncode != 0:
        j["reason"] = (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
        j["converged"] = False
    return j, wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("--levels", default="0,1")
    ap.add_argument("--omegas", default="0.5,1,3,6,12,24,48,72")
    a = ap.parse_args()
    cols = ["level", "omega_over_omega_c", "mu_s", "mu_s_wsp_fit", "error_pct", "mu_s_preload",
            "Q_max_over_P_c", "P_over_P_c", "ux_at_slide_over_omega_c", "dofs",
            "shear_increments", "newton_iterations", "factorizations", "wall_s", "converged",
            "reason"]
    rows, ok = [], True
    for lv in [int(x) for x in a.levels.split(",")]:
        for w in [float(x) for x in a.omegas.split(",")]:
            j, wall = run(a.cli, lv, w)
            fit = wsp_fit(w)
            good = bool(j.get("converged")) and j.get("mu_s") is not None
            err = 100.0 * (j["mu_s"] / fit - 1.0) if good else float("nan")
            ok &= good and abs(err) <= 100 * TOL
            r = {"level": lv, "omega_over_omega_c": w, "mu_s_wsp_fit": "%.5f" % fit,
                 "wall_s": "%.1f" % wall, "converged": int(good), "reason": j.get("reason", "")}
            for k in ("mu_s", "mu_s_preload", "Q_max_over_P_c", "P_over_P_c",
                      "ux_at_slide_over_omega_c"):
                r[k] = "%.5f" % j[k] if good else ""
            for k in ("dofs", "shear_increments", "newton_iterations", "factorizations"):
                r[k] = j.get(k, "")
            r["error_pct"] = "%+.2f" % err if good else ""
            rows.append(r)
            print("level %d omega/omega_c %5g: mu_s %s fit %.4f error %s %% wall %.0f s %s" %
                  (lv, w, r["mu_s"] or "-", fit, r["error_pct"] or "-", wall,
                   "" if good else "FAILED: " + r["reason"]), flush=True)
            write_progress(a.out, cols, rows)  # what is done so far
    write_progress(a.out, cols, rows, done=True)
    print("WSP check (|error| <= 5 %%): %s" % ("ok" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
