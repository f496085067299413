#!/usr/bin/env python3
"""Other readings of kept shear ramps: mu_s of each reference member read
offline from its ramp under candidate inception criteria, and how each
reading agrees between the two mesh levels (docs/design.md section 4.4).

ramp-readings.py [--ramps CSV] [--members CSV] [--thresholds 0.95,0.98,0.99]
                 [--kt 0.05] [--csv OUT] [--single DIR]

The ramps are the rows of data/fe/reference-ramps.csv (one per accepted
ramp point of a member: ux, Q, P, the fraction of the contact area at its
shear limit, ...); the members' own mu_s, as their runs read it, come from
data/fe/reference-members.csv.  For each member:

  as run   the run's own mu_s (the solver's criterion);
  f >= X   the first crossing of the limit fraction through X, interpolated
           linearly between the two ramp points around it: the largest Q up
           to the crossing over P at the crossing;
  KT a     the first increment whose secant stiffness is at most a times the
           first increment's: Q over P at its end (Brizmer, Kligerman &
           Etsion 2007);
  at ux    Q over P at a common ux per case: the smallest of the members'
           last ux at level 0 and level 1, so every ramp of the case reaches it.

A member whose ramp never reaches a reading has none; the count shows it.
Per case and reading the table gives the level-0 mean, the level-1 mean
(each over the level's largest evenly spaced set of members, 4, 8, 16, ...),
their difference (%), and the level-1 members' standard deviation (%): the
question is which reading converges with the mesh.  --csv writes every
member's readings.

--single DIR reads fresh single runs of the held cases instead, each in
DIR/CASE/ (the output of `stiction asperity ARGS --shear --json` as run.json
and the --out directory's shear.csv; ARGS the case's arguments in
tools/references.py plus any numerical option, e.g. --edge-refine 2), and
gives per case and reading the run's difference from the level-1 members'
mean read the same way, and how many cases fall within 2 %.
"""
import argparse
import csv
import json
import math
import os
import sys
from collections import defaultdict

from ramp_read import at_ux, load_shear_csv, readings
from references import MEMBERS_CSV, RAMPS_CSV, complete, held_set
from wsp_case import write_csv


def load_ramps(path):
    ramps = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            key = (r["case"], int(r["mesh_level"]), int(r["member"]))
            ramps[key].append(tuple(float(r[c]) for c in
                                    ("ux_mm", "Q_N", "P_N", "limit_fraction")))
    for pts in ramps.values():
        pts.sort(key=lambda p: p[0])
    return ramps


def evenly_spaced(v):
    """The first K of a level's members in member order, K the largest evenly
    spaced set (4, 8, 16, ...; all of them below 4), as references.csv takes
    them: the members past it sample the node phase unevenly."""
    return v[:complete(len(v)) or len(v)]


def load_members(path):
    with open(path) as f:
        return {(r["case"], int(r["mesh_level"]), int(r["member"])): float(r["mu_s"])
                for r in csv.DictReader(f)}


def stats(v):
    v = [x for x in v if x is not None]
    if not v:
        return None, None, 0
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else 0.0
    return m, sd, len(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ramps", default=RAMPS_CSV)
    ap.add_argument("--members", default=MEMBERS_CSV)
    ap.add_argument("--thresholds", default="0.95,0.98,0.99")
    ap.add_argument("--kt", type=float, default=0.05)
    ap.add_argument("--csv", help="write every member's readings here too")
    ap.add_argument("--single", help="compare the single runs in this directory instead")
    a = ap.parse_args()
    try:
        xs = [float(t) for t in a.thresholds.split(",")]
    except ValueError:
        sys.exit("ramp-readings.py: --thresholds %r: a comma-separated list of numbers in "
                 "(0, 1] expected" % a.thresholds)
    if any(not 0.0 < x <= 1.0 for x in xs):
        sys.exit("ramp-readings.py: --thresholds %r: each must be in (0, 1]" % a.thresholds)
    if not 0.0 < a.kt < 1.0:
        sys.exit("ramp-readings.py: --kt %g: must be in (0, 1)" % a.kt)
    ramps = load_ramps(a.ramps)
    members = load_members(a.members)
    if a.single:
        return single(a.single, ramps, members, xs, a.kt)
    cases = [c[0] for c in held_set() if any(k[0] == c[0] for k in ramps)]
    order = {c: n for n, c in enumerate(cases)}
    names = ["as run"] + ["f>=%g" % x for x in xs] + ["KT %g" % a.kt, "at ux"]
    read = {}  # (case, level) -> list of per-member reading lists
    ucommon = {}
    for (c, lev, j), pts in ramps.items():
        ucommon[c] = min(ucommon.get(c, pts[-1][0]), pts[-1][0])
    cols = ["case", "mesh_level", "member"] + [n.replace(" ", "_").replace(">=", "_")
                                               for n in names]
    rows = []
    for (c, lev, j), pts in sorted(ramps.items(), key=lambda kv: (order.get(kv[0][0], -1),
                                                                   kv[0][1], kv[0][2])):
        r = readings(pts, members.get((c, lev, j)), xs, [a.kt]) + [at_ux(pts, ucommon[c])]
        read.setdefault((c, lev), []).append(r)
        rows.append(dict(zip(cols, [c, lev, j] + ["" if v is None else "%.6f" % v
                                                  for v in r])))
    if a.csv:
        write_csv(a.csv, cols, rows)
    for key, v in read.items():  # appended in member order
        read[key] = evenly_spaced(v)
    print("Each cell: level-0 mean / level-1 mean, their difference (%), and the level-1 "
          "members' standard deviation (%); (n/K) where only n of the K level-1 members reach the "
          "reading.")
    print("'at ux' reads every member at the case's common ux (in um).\n")
    print("| case | " + " | ".join(names) + " |")
    print("|---" * (len(names) + 1) + "|")
    for c in cases:
        cells = []
        for k in range(len(names)):
            s = [stats([r[k] for r in read.get((c, lev), [])]) for lev in (0, 1)]
            if s[0][0] is None or s[1][0] is None:
                one = s[0] if s[0][0] is not None else s[1]
                cells.append("%.4f (one level)" % one[0] if one[0] is not None else "—")
                continue
            d = 100.0 * (s[0][0] / s[1][0] - 1.0)
            cell = "%.4f / %.4f, %+.1f, %.1f" % (s[0][0], s[1][0], d, 100.0 * s[1][1] / s[1][0])
            used = [len(read[(c, lev)]) for lev in (0, 1)]
            if s[1][2] < used[1]:
                cell += " (%d/%d)" % (s[1][2], used[1])
            elif s[0][2] < used[0]:
                cell += " (level 0: %d/%d)" % (s[0][2], used[0])
            cells.append(cell)
        label = c + (" (%.3g um)" % (1e3 * ucommon[c]))
        print("| " + label + " | " + " | ".join(cells) + " |")


def single(path, ramps, members, xs, kt):
    """Fresh single runs (path/CASE/run.json, shear.csv) against the level-1
    members' mean under each reading; cases whose level-1 members are not
    all kept, or that have no run, are left out."""
    names = ["as run"] + ["f>=%g" % x for x in xs] + ["KT %g" % kt]
    within = [[0, 0] for _ in names]
    print("Each cell: the single run's difference from the level-1 members' mean read the "
          "same way (%); (n/K) where only n of K members reach the reading.\n")
    print("| case | " + " | ".join(names) + " |")
    print("|---" * (len(names) + 1) + "|")
    for c in [h[0] for h in held_set()]:
        stored = sorted(j for (cc, lev, j) in members if cc == c and lev == 1)
        lev1 = evenly_spaced(stored)
        run = os.path.join(path, c, "run.json")
        if not os.path.exists(run) or not lev1 or any((c, 1, j) not in ramps for j in stored):
            continue
        with open(run) as f:
            mu = json.load(f)["mu_s"]
        pts = load_shear_csv(os.path.join(path, c, "shear.csv"))
        mine = readings(pts, mu, xs, [kt])
        refs = [readings(ramps[(c, 1, j)], members[(c, 1, j)], xs, [kt]) for j in lev1]
        cells = []
        for k in range(len(names)):
            m, _, n = stats([r[k] for r in refs])
            if m is None or mine[k] is None:
                cells.append("—")
                continue
            d = 100.0 * (mine[k] / m - 1.0)
            cells.append("%+.2f" % d + (" (%d/%d)" % (n, len(refs)) if n < len(refs) else ""))
            if n == len(refs):
                within[k][0] += abs(d) <= 2.0
                within[k][1] += 1
        print("| " + c + " | " + " | ".join(cells) + " |")
    print("| within 2 % | " + " | ".join("%d of %d" % tuple(w) for w in within) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
