#!/usr/bin/env python3
"""Converged references of mu_s for the held set of shear cases: node-placement
ensembles on the default 3D mesh (level 0) and one full refinement finer
(level 1), stored in data/fe/ (docs/design.md section 4.6).

references.py CLI WORKDIR [--levels 0,1] [--jobs N] [--only CASE,...]
              [--members K] [--max-runs M] [--retry-failed] [--no-ramp-reruns]
              [--collect]

Held set: the Wu-Shi-Polycarpou sphere (wsp_case.WSP, slip normal step) at
omega/omega_c 0.5, 1, 3, 6, 12, 24, 48, 72, and the coated spheres of the
thesis family (the CLI's default materials, stick normal step) at t/R 0.005
and 0.05, Eco/Esu 2 and 4, delta/omega_c_su 1 and 30.

Each (case, level) is a node-placement ensemble of K = 4 members (--members
8, 16, ... for more), the members run one by one as single `stiction
asperity --shear --mesh L --threads 1 --json` meshes with elements per
contact N_j = N_0 + phase(j) T (T = a_max / a0 of member 0).  Members 0-3
sit at phases 0, 1/4, 1/2, 3/4 (the spacing of `--placements 4`), members
4-7 halfway between them (1/8, 3/8, 5/8, 7/8), members 8-15 halfway
between those, so the first K members, K a power of two, are always K
evenly spaced placements and an ensemble grows without running its members
again.  A run stopped at any moment
keeps every finished member (WORKDIR/CASE-LLEVEL/mJ.json, written by rename,
with the stiction version and commit that made it)
and the next run goes on from there.  Each member's ramp, shear.csv of
`--out`, is kept beside it as mJ.shear.csv, so a reading of the ramp other
than the one the run made (another inception criterion) can be taken from
it later without running the member again; collected, the ramps are the
rows of data/fe/reference-ramps.csv.  A member that fails is recorded
(mJ.fail, its reason) and not rerun without --retry-failed.  Members run
cheapest first (level 0 before level 1, level 0 in the held set's
order, finer levels by the cost of their level-0 members), N at a time, a
member j > 0 once its member 0 is done.

Every finished member is a row of data/fe/reference-members.csv; every
(case, level) whose first 4 members are done is a row of
data/fe/references.csv, over its largest complete evenly spaced set (the
first 4, 8, 16, ... members): the members' mean, their standard error of
the mean, extremes, mean P/Pc, and the CPU time.  Member 0 at level 0 is
the default single run.  A member whose row and ramp are both stored in
data/fe counts as done (a stored member without its ramp runs again, to keep
it, unless --no-ramp-reruns; if its results then equal its stored row, the
row stays, with the run time and build it names); a member j > 0 is placed
from its member 0's run in WORKDIR, or else from member 0's stored row.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

from refdata import binary_version
from wsp_case import WSP, write_csv

K = 4  # the members of an ensemble unless --members says more
MAX_MEMBERS = 64


def phase(j):
    """member j's offset in elements per contact, as a fraction of the
    period: 0, 1/4, 1/2, 3/4, then 1/8, 3/8, 5/8, 7/8, then 1/16, 3/16, ..."""
    if j < 4:
        return j / 4.0
    m = 1 << (j.bit_length() - 1)
    return (2 * (j - m) + 1) / (2.0 * m)


def complete(n):
    """the largest evenly spaced set (4, 8, 16, ... members) within the first
    n members; 0 below 4"""
    if n < 4:
        return 0
    k = 4
    while 2 * k <= n:
        k *= 2
    return k


HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data", "fe")
MEMBERS_CSV = os.path.join(DATA, "reference-members.csv")
REFS_CSV = os.path.join(DATA, "references.csv")
RAMPS_CSV = os.path.join(DATA, "reference-ramps.csv")
# the columns of `asperity --shear --out`'s shear.csv kept for each member
RAMP_COLS = ["ux_mm", "Q_N", "P_N", "A_mm2", "slip_fraction", "limit_fraction", "n_contact",
             "a_lead_mm", "a_trail_mm", "a_side_mm"]

WSP_OMEGAS = ["0.5", "1", "3", "6", "12", "24", "48", "72"]
COATED = [(t, e, d) for d in ("1", "30") for t in ("0.005", "0.05") for e in ("2", "4")]


def held_set():
    """[(case id, family, delta, t/R, Eco/Esu, asperity arguments)]"""
    cases = [("wsp-%s" % w, "wsp", w, "0", "1", WSP + ["--delta", w]) for w in WSP_OMEGAS]
    cases += [("coated-%s-%s-%s" % (t, e, d), "thesis", d, t, e,
               ["--t-over-R", t, "--E-ratio", e, "--contact", "stick", "--delta", d])
              for t, e, d in COATED]
    return cases


def stored_refs():
    """{(case, mesh level): row} of data/fe/references.csv"""
    with open(REFS_CSV) as f:
        return {(r["case"], int(r["mesh_level"])): r for r in csv.DictReader(f)}


def load(path):
    with open(path) as f:
        return json.load(f)


def write_atomic(path, text):
    with open(path + ".tmp", "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(path + ".tmp", path)


def stored_members(need_ramp=True):
    """{(case, level, member): row} of data/fe/reference-members.csv whose
    ramp is in data/fe/reference-ramps.csv too (every row: need_ramp 0)"""
    if not os.path.exists(MEMBERS_CSV):
        return {}
    with open(MEMBERS_CSV) as f:
        rows = {(r["case"], int(r["mesh_level"]), int(r["member"])): r
                for r in csv.DictReader(f)}
    ramps = set()
    if os.path.exists(RAMPS_CSV):
        with open(RAMPS_CSV) as f:
            ramps = {(r["case"], int(r["mesh_level"]), int(r["member"]))
                     for r in csv.DictReader(f)}
    return {k: r for k, r in rows.items() if k in ramps or not need_ramp}


class Member:
    """member j of a case's ensemble at a mesh level; stored: the rows of
    stored_members(), whose members count as done and place the others"""
    def __init__(self, work, case, level, j, stored=None):
        self.case, self.level, self.j = case, level, j
        self.row = (stored or {}).get((case[0], level, j))
        self.row0 = (stored or {}).get((case[0], level, 0))
        self.dir = os.path.join(work, "%s-L%d" % (case[0], level))
        self.json = os.path.join(self.dir, "m%d.json" % j)
        self.fail = os.path.join(self.dir, "m%d.fail" % j)
        self.m0 = os.path.join(self.dir, "m0.json")
        self.run = os.path.join(self.dir, "m%d.run" % j)
        self.curve = os.path.join(self.dir, "m%d.shear.csv" % j)

    def done(self):
        return os.path.exists(self.json) or self.row is not None

    def failed(self):
        return os.path.exists(self.fail)

    def keep_curve(self):
        """keep the ramp's shear.csv beside the member (a ramp that failed
        too: the points it reached), drop the field files"""
        src = os.path.join(self.run, "shear.csv")
        if os.path.exists(src):
            os.replace(src, self.curve)
        shutil.rmtree(self.run, ignore_errors=True)

    def ready(self):
        return self.j == 0 or os.path.exists(self.m0) or self.row0 is not None

    def command(self, cli):
        cmd = [cli, "asperity"] + self.case[5] + ["--shear", "--model", "3d", "--mesh",
                                                  str(self.level), "--threads", "1", "--json",
                                                  "--progress-every", "0", "--out", self.run]
        if self.j > 0:
            if os.path.exists(self.m0):
                r0 = load(self.m0)
                n0, a0, amax = r0["elements_per_contact"], r0["a_mm"], r0["a_max_mm"]
            else:
                n0, a0, amax = (float(self.row0[k]) for k in
                                ("elements_per_contact", "a0_mm", "a_max_mm"))
            n = n0 + phase(self.j) * amax / a0
            cmd += ["--elements-per-contact", "%.6f" % n]
        return cmd


def cost_order(work, cases, level, stored):
    """cases cheapest first at a level > 0: by their level-0 members' run time
    (the finer mesh costs 10-20 times as much), unknown ones last"""
    if level == 0:
        return cases

    def cost(c):
        t = []
        for m in (Member(work, c, 0, j, stored) for j in range(K)):
            if os.path.exists(m.json):
                t.append(load(m.json).get("run_wall_s", 0.0))
            elif m.row is not None:
                t.append(float(m.row["wall_s"]))
        return sum(t) / len(t) if t else float("inf")
    return sorted(cases, key=cost)


def schedule(cli, members, jobs, max_runs, done=lambda: None):
    """Run the members, at most jobs at a time, each once its member 0 is done;
    done() after each finished one.  Each member records the version of the
    binary it started with (the binary may be rebuilt while a schedule runs)."""
    pending = [m for m in members if not m.done() and not m.failed()]
    running, started = [], 0
    while pending or running:
        for m, p, t0, ver in list(running):
            if p.poll() is None:
                continue
            running.remove((m, p, t0, ver))
            out, err = p.communicate()
            m.keep_curve()
            if p.returncode == 0:
                r = json.loads(out)
                r["run_wall_s"] = time.time() - t0
                r["version"] = ver
                write_atomic(m.json, json.dumps(r, indent=1))
                print("%s level %d member %d: mu_s %.5f (%.0f s)" %
                      (m.case[0], m.level, m.j, r["mu_s"], r["run_wall_s"]), flush=True)
                done()
            else:
                why = err.strip().splitlines()[-1] if err.strip() else "exit %d" % p.returncode
                write_atomic(m.fail, why + "\n")
                print("%s level %d member %d failed: %s" % (m.case[0], m.level, m.j, why),
                      flush=True)
                # the others of a failed member 0 cannot be placed
                if m.j == 0:
                    pending = [q for q in pending if q.dir != m.dir]
        while len(running) < jobs and (max_runs <= 0 or started < max_runs):
            nxt = next((m for m in pending if m.ready()), None)
            if nxt is None:
                break
            pending.remove(nxt)
            os.makedirs(nxt.dir, exist_ok=True)
            ver = binary_version(cli)
            running.append((nxt, subprocess.Popen(nxt.command(cli), stdout=subprocess.PIPE,
                                                  stderr=subprocess.PIPE, text=True),
                            time.time(), ver))
            started += 1
        if not running:
            break
        time.sleep(1.0)


def collect(work, cases, levels):
    mcols = ["case", "family", "delta_over_omega_c", "t_over_R", "E_ratio", "mesh_level",
             "member", "elements_per_contact", "a0_mm", "a_max_mm", "mu_s", "mu_s_preload",
             "P_over_P_c", "A_over_A_c", "Q_still_rising", "wall_s", "version"]
    rcols = ["case", "family", "delta_over_omega_c", "t_over_R", "E_ratio", "mesh_level",
             "placements", "mu_s", "mu_s_err", "mu_s_min", "mu_s_max", "mu_s_single",
             "P_over_P_c", "wall_s", "version"]
    old, old_ramps = {}, {}
    if os.path.exists(MEMBERS_CSV):
        with open(MEMBERS_CSV) as f:
            old = {(r["case"], r["mesh_level"], r["member"]): r for r in csv.DictReader(f)}
    if os.path.exists(RAMPS_CSV):
        with open(RAMPS_CSV) as f:
            for r in csv.DictReader(f):
                old_ramps.setdefault((r["case"], r["mesh_level"], r["member"]), []).append(r)
    mrows, rrows, ramps = [], [], []
    for level in levels:
        for c in cases:
            got = []
            for j in range(MAX_MEMBERS):
                m = Member(work, c, level, j)
                key = (c[0], str(level), str(j))
                if os.path.exists(m.json):
                    r = load(m.json)
                    row = {"case": c[0], "family": c[1], "delta_over_omega_c": c[2],
                           "t_over_R": c[3], "E_ratio": c[4], "mesh_level": level, "member": j,
                           "elements_per_contact": "%.6f" % r["elements_per_contact"],
                           "a0_mm": "%.9g" % r["a_mm"], "a_max_mm": "%.9g" % r["a_max_mm"],
                           "mu_s": "%.6f" % r["mu_s"],
                           "mu_s_preload": "%.6f" % r["mu_s_preload"],
                           "P_over_P_c": "%.6f" % r["P_over_P_c"],
                           "A_over_A_c": "%.6f" % r["A_over_A_c"],
                           "Q_still_rising": int(bool(r.get("Q_still_rising"))),
                           "wall_s": "%.0f" % r.get("run_wall_s", r["wall_s"]),
                           "version": r["version"]}
                    same = key in old and all(str(row[k]) == old[key][k] for k in mcols
                                              if k not in ("wall_s", "version"))
                    if same:  # a stored member run again (for its ramp): its row stays
                        row = old[key]
                elif key in old:  # stored, its run not in this WORKDIR
                    row = old[key]
                else:
                    continue
                if os.path.exists(m.json) and os.path.exists(m.curve):
                    with open(m.curve) as f:
                        ramps += [dict({"case": c[0], "mesh_level": level, "member": j},
                                       **{k: p[k] for k in RAMP_COLS})
                                  for p in csv.DictReader(f)]
                else:
                    ramps += old_ramps.get(key, [])
                mrows.append(row)
                if len(got) == j:  # the members 0 .. j are all there
                    got.append(row)
            k = complete(len(got))
            if not k:
                continue
            got = got[:k]
            mu = [float(r["mu_s"]) for r in got]
            mean = sum(mu) / k
            se = math.sqrt(sum((x - mean) ** 2 for x in mu) / (k - 1) / k)
            rrows.append({"case": c[0], "family": c[1], "delta_over_omega_c": c[2],
                          "t_over_R": c[3], "E_ratio": c[4], "mesh_level": level,
                          "placements": k, "mu_s": "%.6f" % mean, "mu_s_err": "%.6f" % se,
                          "mu_s_min": "%.6f" % min(mu), "mu_s_max": "%.6f" % max(mu),
                          "mu_s_single": got[0]["mu_s"],
                          "P_over_P_c": "%.6f" % (sum(float(r["P_over_P_c"])
                                                      for r in got) / k),
                          "wall_s": "%.0f" % sum(float(r["wall_s"]) for r in got),
                          "version": got[0]["version"]})
    write_csv(MEMBERS_CSV, mcols, mrows)
    write_csv(REFS_CSV, rcols, rrows)
    if ramps:
        write_csv(RAMPS_CSV, ["case", "mesh_level", "member"] + RAMP_COLS, ramps)
    return mrows, rrows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cli")
    ap.add_argument("work")
    ap.add_argument("--levels", default="0,1")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="", help="case ids, comma-separated")
    ap.add_argument("--members", type=int, default=K,
                    help="members per (case, level): 4, 8, 16, ... (default %d)" % K)
    ap.add_argument("--max-runs", type=int, default=0, help="start at most M member runs")
    ap.add_argument("--retry-failed", action="store_true")
    ap.add_argument("--no-ramp-reruns", action="store_true",
                    help="a stored member without its ramp counts as done too")
    ap.add_argument("--collect", action="store_true",
                    help="run nothing: write the CSV files from WORKDIR's finished members")
    a = ap.parse_args()
    cases = held_set()
    if a.only:
        want = a.only.split(",")
        bad = [w for w in want if w not in [c[0] for c in cases]]
        if bad:
            sys.exit("--only: unknown case %s (cases: %s)" %
                     (", ".join(bad), ", ".join(c[0] for c in cases)))
        cases = [c for c in cases if c[0] in want]
    if a.members < 4 or a.members > MAX_MEMBERS or complete(a.members) != a.members:
        sys.exit("--members: %d is not a power of two from 4 to %d" % (a.members, MAX_MEMBERS))
    levels = [int(x) for x in a.levels.split(",")]
    stored = stored_members(not a.no_ramp_reruns)
    # level by level, the first 4 members of every case, then the next 4, 8, ...
    members = [Member(a.work, c, lv, j, stored) for lv in levels
               for lo, hi in [(0, 4)] + [(k, 2 * k) for k in (4, 8, 16, 32) if k < a.members]
               for c in cost_order(a.work, cases, lv, stored) for j in range(lo, hi)]
    if a.retry_failed:
        for m in members:
            if m.failed():
                os.remove(m.fail)
    if not a.collect:
        schedule(a.cli, members, a.jobs, a.max_runs,
                 lambda: collect(a.work, held_set(), [0, 1, 2]))
    _, rrows = collect(a.work, held_set(), [0, 1, 2])
    fails = [m for m in members if m.failed()]
    for m in fails:
        with open(m.fail) as f:
            print("failed: %s level %d member %d: %s" % (m.case[0], m.level, m.j,
                                                        f.read().strip()))
    print("%d (case, level) ensembles complete in %s" % (len(rrows), REFS_CSV))


if __name__ == "__main__":
    main()
