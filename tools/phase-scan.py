#!/usr/bin/env python3
"""mu_s of one shear case against the node-placement phase (docs/design.md
section 4.5).

phase-scan.py CLI OUT.csv CASE DELTA [K] [-- EXTRA...]

CASE: "wsp" (the Wu-Shi-Polycarpou sphere, slip normal step) or "T/E" (a
coated sphere of the thesis family, t/R T, Eco/Esu E, stick normal step, the
CLI's default materials); DELTA in omega_c_su.  Runs K (default 8) single
`stiction asperity --shear --json` meshes with elements per contact
N_j = 6 + j T / K, T = a_max / a0 (one node spacing at the preload edge;
a0 of the N = 6 run, as `--placements` spaces its members), and writes one row per run: the phase psi = a0 N / a_max mod 1 of the
preload edge between the surface node lines, with a0 from the axisymmetric
default mesh (`stiction asperity --delta DELTA --json`), and mu_s.  Rows are
appended to OUT.csv (header written when it is new), so several cases can
share a file.  EXTRA goes to every shear run.
"""
import csv
import json
import os
import subprocess
import sys

from wsp_case import WSP


def run(cli, args):
    p = subprocess.run([cli, "asperity"] + args + ["--json"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(args), p.stderr.strip()))
    return json.loads(p.stdout)


def main():
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    if len(argv) not in (4, 5):
        sys.exit(__doc__)
    cli, out, case, delta = argv[:4]
    k = int(argv[4]) if len(argv) == 5 else 8
    if case == "wsp":
        args = WSP + ["--delta", delta]
    else:
        t, e = case.split("/")
        args = ["--t-over-R", t, "--E-ratio", e, "--contact", "stick", "--delta", delta]
    a0 = run(cli, args)["a_mm"]  # the axisymmetric default mesh
    cols = ["case", "delta_over_omega_c", "foot_rows", "elements_per_contact", "a0_mm",
            "a_max_mm", "psi", "mu_s", "mu_s_preload", "P_over_P_c"]
    new = not os.path.exists(out)
    first = run(cli, args + ["--shear", "--elements-per-contact", "6"] + extra)
    period = first["a_max_mm"] / first["a_mm"]
    with open(out, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        if new:
            w.writeheader()
        for j in range(k):
            n = 6.0 + j * period / k
            r = first if j == 0 else run(cli, args + ["--shear", "--elements-per-contact",
                                                      "%.6f" % n] + extra)
            w.writerow({"case": case, "delta_over_omega_c": delta, "foot_rows": r["foot_rows"],
                        "elements_per_contact": "%.6f" % r["elements_per_contact"],
                        "a0_mm": "%.9g" % a0, "a_max_mm": "%.9g" % r["a_max_mm"],
                        "psi": "%.4f" % ((a0 * r["elements_per_contact"] / r["a_max_mm"]) % 1.0),
                        "mu_s": "%.6f" % r["mu_s"], "mu_s_preload": "%.6f" % r["mu_s_preload"],
                        "P_over_P_c": "%.6f" % r["P_over_P_c"]})
            f.flush()
            print("%s %s: N %.4f psi %.3f mu_s %.5f" % (case, delta, r["elements_per_contact"],
                                                      (a0 * r["elements_per_contact"] /
                                                       r["a_max_mm"]) % 1.0, r["mu_s"]),
                  flush=True)


if __name__ == "__main__":
    main()
