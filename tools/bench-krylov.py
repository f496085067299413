#!/usr/bin/env python3
"""make bench fragment: Newton-Krylov against a factorization per Newton step.

bench-krylov.py CLI

Runs the 3D half model (level 0) with --krylov off (CHOLMOD factorization of
every tangent) and --krylov auto (PCG preconditioned with the last factor,
asperity/linsolve.c) and prints, per case: wall time, Newton iterations,
factorizations, PCG iterations, element-loop evaluations, and the largest
relative difference of P, a and the first-yield interferences between the
two (they must agree: the PCG tolerance is below the Newton tests').
"""
import json
import os
import subprocess
import sys
import time

HERTZ = ["--R", "10.09", "--E-su", "74000", "--nu", "0.32", "--Y-su", "70000", "--Y-co", "70000"]
CASES = [
    ("3D Hertz a/R=0.01, level 0", HERTZ + ["--delta-mm", "0.001", "--model", "3d", "--mesh", "0"]),
    ("3D coated stick d=10wc t/R=.025 Eco/Esu=2", ["--delta", "10", "--t-over-R", "0.025",
                                                    "--E-ratio", "2", "--contact", "stick",
                                                    "--model", "3d", "--mesh", "0"]),
    ("3D slip curve d=1..60wc (12 pts), level 0", ["--delta", "1:60:12", "--model", "3d",
                                                    "--mesh", "0"]),
]
KEYS = ["P_N", "a_mm", "first_yield_delta_over_omega_c_su", "delta_c1_over_omega_c_su",
        "delta_c2_over_omega_c_su"]


def run(cli, args):
    t0 = time.time()
    pr = subprocess.run([cli, "asperity", "--json"] + args, capture_output=True, text=True)
    wall = time.time() - t0
    if pr.returncode != 0:
        raise RuntimeError("stiction asperity %s failed: %s" % (" ".join(args), pr.stderr.strip()))
    j = json.loads(pr.stdout)
    return (j if isinstance(j, list) else [j]), wall


def maxdiff(a, b):
    d = 0.0
    for x, y in zip(a, b):
        for k in KEYS:
            if x.get(k) is None or y.get(k) is None:
                if (x.get(k) is None) != (y.get(k) is None):
                    return float("inf")
                continue
            d = max(d, abs(x[k] / y[k] - 1) if y[k] else abs(x[k]))
    return d


def main(cli):
    print("Newton-Krylov (--krylov auto) against a factorization per step (--krylov off)")
    print("%-44s %-5s %8s %7s %7s %7s %7s %10s" % ("case", "mode", "wall s", "Newton", "factor",
                                                   "PCG", "elem", "max rel d"))
    for name, args in CASES:
        ref = None
        for mode in ("off", "auto"):
            j, w = run(cli, args + ["--krylov", mode])
            last = j[-1]
            d = "-" if ref is None else "%.1e" % maxdiff(j, ref)
            ref = ref or j
            print("%-44s %-5s %8.2f %7d %7d %7d %7d %10s" % (
                name, mode, w, last["newton_iterations"], last["factorizations"],
                last.get("krylov_iterations", 0), last["assemblies"], d))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2 or not os.access(sys.argv[1], os.X_OK):
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
