#!/usr/bin/env python3
"""Numerical stress scan: the FE solver at the edges of the parameter space.

validate-stress.py CLI OUT.csv OUT.md [--only NAME,...]

Each case is one `stiction asperity --json` run (normal step, or normal step
and shear ramp) at an extreme of the moduli, thicknesses, Poisson's ratios,
loads or τc.  A case passes when the run converges to finite, positive
numbers (μs for a shear case, P for a normal one), or, for a case that must be
refused, when the CLI exits 2 with a message naming the parameter.  Any other
outcome (a failed run, a crash, a NaN) fails the scan; the reason is in the
CSV.  The cases and what they found: docs/design.md §4.9 (the
thin-coating shear case needs the junction reading inside the cut-back
step).  Writes OUT.csv (OUT.csv.part while running).
Exit status 1 if any case failed.
"""
import argparse
import json
import math
import subprocess
import sys
import time

from vreport import Report
from wsp_case import write_progress

SHEAR = ["--shear", "--model", "3d"]
COATED = ["--t-over-R", "0.025", "--E-ratio", "2", "--contact", "stick"]
THIN = ["--t-over-R", "0.001", "--E-ratio", "4", "--contact", "stick"]

# name, arguments after `stiction asperity --json`, expected: "ok" or "refused:<text>"
CASES = [
    ("normal nu 0.05", ["--delta", "30", "--nu", "0.05"], "ok"),
    ("normal nu 0.49", ["--delta", "30", "--nu", "0.49"], "ok"),
    ("normal E/Y 10000", ["--delta", "30", "--E-over-Y", "10000"], "ok"),
    ("normal t/R 1e-4", ["--delta", "10", "--t-over-R", "1e-4", "--E-ratio", "4",
                         "--contact", "stick"], "ok"),
    ("normal t/R 0.2", ["--delta", "10", "--t-over-R", "0.2", "--E-ratio", "4",
                        "--contact", "stick"], "ok"),
    ("normal Eco/Esu 0.2", ["--delta", "10", "--t-over-R", "0.025", "--E-ratio", "0.2",
                            "--contact", "stick"], "ok"),
    ("normal Eco/Esu 50", ["--delta", "10", "--t-over-R", "0.025", "--E-ratio", "50",
                           "--contact", "stick"], "ok"),
    ("normal stick to 100", ["--delta", "1:100:5", "--contact", "stick"], "ok"),
    ("normal E/Y 100 too deep", ["--delta", "30", "--E-over-Y", "100"], "refused:delta"),
    ("shear delta 0.1", SHEAR + ["--delta", "0.1"], "ok"),
    ("shear delta 100", SHEAR + ["--delta", "100"], "ok"),
    ("shear nu 0.05", SHEAR + ["--delta", "3", "--nu", "0.05"], "ok"),
    ("shear nu 0.49", SHEAR + ["--delta", "3", "--nu", "0.49"], "ok"),
    ("shear E/Y 100", SHEAR + ["--delta", "0.5", "--E-over-Y", "100"], "ok"),
    ("shear E/Y 10000", SHEAR + ["--delta", "3", "--E-over-Y", "10000"], "ok"),
    ("shear Eco/Esu 0.2", SHEAR + ["--delta", "10", "--t-over-R", "0.025", "--E-ratio", "0.2",
                                   "--contact", "stick"], "ok"),
    ("shear Eco/Esu 10", SHEAR + ["--delta", "10", "--t-over-R", "0.025", "--E-ratio", "10",
                                  "--contact", "stick"], "ok"),
    ("shear thin hard coating", SHEAR + ["--delta", "10"] + THIN, "ok"),
    ("shear t/R 0.1", SHEAR + ["--delta", "10", "--t-over-R", "0.1", "--E-ratio", "2",
                               "--contact", "stick"], "ok"),
    ("shear nu-co 0.2", SHEAR + ["--delta", "10", "--nu-co", "0.2"] + COATED, "ok"),
    ("shear tau-c 1", SHEAR + ["--delta", "3", "--tau-c", "1"], "ok"),
    ("shear tau-c 5000", SHEAR + ["--delta", "3", "--tau-c", "5000"], "ok"),
    ("shear stiffness 0.5", SHEAR + ["--delta", "3", "--criterion", "stiffness",
                                     "--alpha", "0.5"], "ok"),
    ("shear load 0.3", SHEAR + ["--load", "0.3"], "ok"),
    ("shear load 100", SHEAR + ["--load", "100"] + COATED, "ok"),
]


def run(cli, args):
    t0 = time.time()
    p = subprocess.run([cli, "asperity", "--json"] + args, capture_output=True, text=True)
    wall = time.time() - t0
    try:
        j = json.loads(p.stdout) if p.stdout.strip() else None
    except ValueError:
        j = None
    err = (p.stderr.strip().splitlines() or [""])[-1]
    return p.returncode, j, err, wall


def judge(expect, rc, j, err, shear):
    """(passed, value, reason)"""
    if expect.startswith("refused:"):
        word = expect.split(":", 1)[1]
        ok = rc == 2 and word in err and j is None
        return ok, "", err if ok else "expected a refusal naming '%s': exit %d, %s" % (
            word, rc, err)
    if rc != 0 or j is None:
        return False, "", "exit %d: %s" % (rc, err)
    last = j[-1] if isinstance(j, list) else j
    key = "mu_s" if shear else "P_N"
    v = last.get(key)
    good = bool(last.get("converged")) and isinstance(v, (int, float)) and math.isfinite(v) \
        and v > 0.0
    return good, "%.6g" % v if good else "", last.get("reason") or ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("report")
    ap.add_argument("--only", default="", help="comma-separated case names (substrings)")
    a = ap.parse_args()
    sel = [s for s in a.only.split(",") if s]
    cols = ["case", "arguments", "expected", "passed", "value", "shear_cutbacks", "wall_s",
            "reason"]
    rows = []
    for name, args, expect in CASES:
        if sel and not any(s in name for s in sel):
            continue
        shear = "--shear" in args
        rc, j, err, wall = run(a.cli, args)
        good, val, why = judge(expect, rc, j, err, shear)
        last = (j[-1] if isinstance(j, list) else j) if j else {}
        rows.append({"case": name, "arguments": " ".join(args), "expected": expect,
                     "passed": int(good), "value": val,
                     "shear_cutbacks": last.get("shear_cutbacks", "") if shear else "",
                     "wall_s": "%.1f" % wall, "reason": why})
        print("%-26s %-4s %-10s %6.1f s  %s" % (name, "ok" if good else "FAIL", val or "-", wall,
                                               why[:100]), flush=True)
        write_progress(a.out, cols, rows)
    write_progress(a.out, cols, rows, done=True)
    rep = Report("Numerical stability at the edges of the parameter space",
                 "tools/validate-stress.py (`stiction asperity --json` runs)")
    rep.out("Each case converges to finite, positive numbers (mu_s for a shear case, P for a "
            "normal one) or is refused by name (exit 2, the parameter named).")
    rep.out("")
    for r in rows:
        rep.check("%s (`%s`)" % (r["case"], r["arguments"]), "the run itself", r["expected"],
                  "%s %s (%s s)" % (r["value"] or "-", r["reason"][:80], r["wall_s"]),
                  bool(r["passed"]))
    return rep.write(a.report)


if __name__ == "__main__":
    sys.exit(main())
