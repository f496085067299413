#!/usr/bin/env python3
"""make bench, mu_s against the converged references: work-precision of one
default run and of a node-placement ensemble.

bench-references.py CLI [--placements K,...] [--only CASE,...] [--level L]

For every held case with a stored reference at mesh level L (default 1: four
node placements one full refinement finer than the default mesh,
data/fe/references.csv, tools/references.py): a fresh default run
(`stiction asperity ARGS --shear`, no numerical option, the solver's default
threads), one with the edge band (`--edge-refine 2`, docs/design.md §2.7) and
fresh `--placements K` runs (default K = 2 and 4; members
concurrently, one thread each), each with its mu_s, printed error, error against the
reference, wall and CPU time.  Targets: within 2 % of the reference and the
printed error at least as large as the actual error, in <= 20 s wall for the
homogeneous sphere and <= 40 s for a coated one.  The runs are one at a time,
so the times are those of one run on the machine as loaded.
"""
import argparse
import sys

from references import held_set, stored_refs
from shearrun import run_shear

TARGET = 0.02
WALL = {"wsp": 20.0, "thesis": 40.0}


def measure(cli, args):
    """(mu_s, printed error, wall s, cpu s) or (None, reason, wall s, cpu s)"""
    j, wall, cpu, extra = run_shear(cli, args)
    if j is None or not j.get("converged", True):
        return None, extra if j is None else j.get("reason", "not converged"), wall, cpu
    return j["mu_s"], j["mu_s_err"], wall, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--placements", default="2,4", help="ensemble sizes, comma-separated")
    ap.add_argument("--only", default="", help="case ids, comma-separated")
    ap.add_argument("--level", type=int, default=1)
    a = ap.parse_args()
    refs = stored_refs()
    only = set(a.only.split(",")) if a.only else None
    cases = [c for c in held_set() if (c[0], a.level) in refs and (not only or c[0] in only)]
    if not cases:
        sys.exit("bench-references.py: no held case with a level-%d reference%s" % (
            a.level, " among %s" % a.only if only else ""))
    ks = [int(x) for x in a.placements.split(",") if x]
    runs = [("one default run", []), ("one band run", ["--edge-refine", "2"])]
    runs += [("%d placements" % k, ["--placements", str(k)]) for k in ks]
    print("mu_s against the converged references (data/fe/references.csv, level %d, four "
          "placements): %s" % (a.level, ", ".join(r[0] for r in runs)))
    print("%-18s %-13s  %-16s %-13s %8s %4s %7s %7s" % (
        "case", "reference", "run", "mu_s", "error", "cov", "wall s", "CPU s"))
    tally = {r[0]: [0, 0, 0, 0] for r in runs}  # runs, within 2 %, covered, in time
    for c in cases:
        ref = refs[(c[0], a.level)]
        mu_r = float(ref["mu_s"])
        for name, extra in runs:
            mu, se, wall, cpu = measure(a.cli, c[5] + extra)
            t = tally[name]
            t[0] += 1
            head = "%-18s %7.4f±%.4f  %-16s" % (c[0], mu_r, float(ref["mu_s_err"]), name)
            if mu is None:
                print(head + " failed after %.0f s: %s" % (wall, se), flush=True)
                continue
            err = mu / mu_r - 1
            cov = abs(mu - mu_r) <= se
            fast = wall <= WALL[c[1]]
            t[1] += abs(err) <= TARGET
            t[2] += cov
            t[3] += fast
            print(head + " %7.4f±%.4f %+7.2f%% %4s %7.1f %7.1f" % (
                mu, se, 100 * err, "yes" if cov else "no", wall, cpu), flush=True)
    print("(error: against the reference; cov: the printed error (one standard error) at least "
          "as large as the error; wall s: the whole process, CPU s: user + system of it)")
    for name, _ in runs:
        n, w, cv, f = tally[name]
        print("%s: within %g %% in %d of %d, printed error covers in %d of %d, within the time "
              "(%g s homogeneous, %g s coated) in %d of %d; target (all three in every case): "
              "%s" % (name, 100 * TARGET, w, n, cv, n, WALL["wsp"], WALL["thesis"], f, n,
                      "met" if w == cv == f == n else "NOT met"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
