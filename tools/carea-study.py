#!/usr/bin/env python3
"""Contact-radius estimator study (asperity/asp_contact.c: contact_radius).

Runs `stiction asperity` built with -DASP_CAREA_DUMP (the study hook in
asp_contact.c appends the converged surface-node forces, displacements and
contact states of every increment to $ASP_CAREA_DUMP, one JSON line each),
then evaluates on the final state of each run
  old: Hertz edge p = sqrt(a² - r²) fitted to F_L / F_L-1 (the estimator
       before this study),
  new: p ∝ sqrt(1 - (r/a)^2n) fitted to F_L / F_L-1 and F_L-1 / F_L-2,
       and not below the same fit without node L (the one in asp_contact.c
       now; checked against the a_mm of the runs made by this invocation),
and prints a - a_ref per case and mesh level.  The reference of a case is
the mean of the new estimator over its fine runs (level 3, and where run
level 4 and --elements-per-contact 40..56), because a single fine level
still carries the node-entry sawtooth (the spread is printed).

Cases: the homogeneous WSP sphere (wsp_case.py) under slip at
delta/omega_c in {0.5 .. 72}, the default coated sphere (t/R = 0.025,
Eco/Esu = 2) under stick at {1, 10, 30, 60}, and a few 3D level-0 runs.
One solver process at a time, --threads 1.  Runs are cached in --dir.

  python3 tools/carea-study.py [--dir D] [--levels 0,1,2,3] [--fine] [--3d] [--paths]
    --fine: add level 4 at 6 omega_c and --elements-per-contact 40..56
            at 6 and 24 omega_c (about 15 min)
    --3d:   add 3D level-0 runs (10-30 s each) and one level-1 run (~8 min)
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wsp_case import WSP  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COAT = ["--t-over-R", "0.025", "--E-ratio", "2", "--contact", "stick"]
WSP_D = [0.5, 1, 3, 6, 12, 24, 48, 72]
COAT_D = [1, 10, 30, 60]
NS = 64  # Simpson intervals per half hat, as in asp_contact.c


# ---- the two estimators (ports of asp_contact.c) -------------------------
def shape(x, n):
    if n == 1.0:
        return 1.0
    if x >= 1.0 - 1e-9:
        return math.sqrt(n)
    return math.sqrt((1.0 - x ** (2.0 * n)) / (1.0 - x * x))


def hat(r, k, a, n, axi):
    F = 0.0
    for side in (0, 1):
        lo = (r[k - 1] if k > 0 else r[k]) if side == 0 else r[k]
        hi = r[k] if side == 0 else (r[k + 1] if k + 1 < len(r) else r[k])
        if hi <= lo or lo >= a:
            continue
        p0, p1 = math.asin(min(lo / a, 1.0)), math.asin(min(hi / a, 1.0))
        h, s = (p1 - p0) / NS, 0.0
        for i in range(NS + 1):
            ph = p0 + i * h
            rr, c = a * math.sin(ph), a * math.cos(ph)
            N = (rr - lo) / (hi - lo) if side == 0 else (hi - rr) / (hi - lo)
            w = 1 if i in (0, NS) else (4 if i % 2 else 2)
            s += w * c * shape(rr / a, n) * N * (rr if axi else 1.0) * c
        F += s * h / 3.0
    return F


def illinois(fn, x0, f0, x1, f1, tol):
    x, side = x1, 0
    for _ in range(60):
        if abs(x1 - x0) <= tol:
            break
        x = (x0 * f1 - x1 * f0) / (f1 - f0)
        fx = fn(x)
        if fx == 0.0:
            return x
        if (fx > 0) == (f1 > 0):
            x1, f1 = x, fx
            if side == 1:
                f0 *= 0.5
            side = 1
        else:
            x0, f0 = x, fx
            if side == -1:
                f1 *= 0.5
            side = -1
    return x


def edge_radius(r, F, L, n, axi):
    lo, hi = r[L - 1] + 1e-6 * (r[L] - r[L - 1]), r[L + 1]
    fn = lambda a: hat(r, L, a, n, axi) / hat(r, L - 1, a, n, axi) - F[L] / F[L - 1]
    flo, fhi = fn(lo), fn(hi)
    if not flo < 0:
        return lo
    if not fhi > 0:
        return hi
    return illinois(fn, lo, flo, hi, fhi, 1e-9 * (hi - lo))


def trivial(r, L):
    if L < 0:
        return 0.0
    if L + 1 >= len(r):
        return r[-1]
    if L == 0:
        return 0.5 * r[1]
    return None


def est_old(r, F, L, axi):
    t = trivial(r, L)
    return t if t is not None else edge_radius(r, F, L, 1.0, axi)


def est_new(r, F, L, axi):
    """the fit with node L last, bounded below by the fit without node L"""
    a = edge_fit(r, F, L, axi)
    if L >= 1 and L + 1 < len(r):
        a = max(a, edge_fit(r, F, L - 1, axi))
    return a


def edge_fit(r, F, L, axi, nmin=0.5, nmax=64.0):
    t = trivial(r, L)
    if t is not None:
        return t
    if L == 1 or not F[L - 2] > 0:
        return edge_radius(r, F, L, 1.0, axi)

    def inner(t):
        n = math.exp(t)
        a = edge_radius(r, F, L, n, axi)
        return hat(r, L - 1, a, n, axi) / hat(r, L - 2, a, n, axi) - F[L - 1] / F[L - 2]

    t0, t1 = math.log(nmin), math.log(nmax)
    f0, f1 = inner(t0), inner(t1)
    if (f0 > 0) == (f1 > 0):
        return edge_radius(r, F, L, nmin if abs(f0) < abs(f1) else nmax, axi)
    return edge_radius(r, F, L, math.exp(illinois(inner, t0, f0, t1, f1, 1e-6)), axi)


def surface_line(rec):
    """Nodes on the radius line (axisym: all; 3D: y = 0, x >= 0), by r."""
    d, out = rec["dim"], []
    for nd in rec["nodes"]:
        x, fz, cs = nd[:d], nd[2 * d], nd[2 * d + 1]
        if d == 3 and not (x[1] == 0.0 and x[0] >= 0.0):
            continue
        out.append((x[0], -fz, cs))
    out.sort()
    r, F = [o[0] for o in out], [o[1] for o in out]
    L = max([i for i, o in enumerate(out) if o[2] != 0], default=-1)
    return r, F, L, d == 2


# ---- runs -----------------------------------------------------------------
def build(bdir):
    subprocess.run(["make", "-C", ROOT, "O=" + bdir, "OPTFLAGS=-O2 -DASP_CAREA_DUMP", "-j2",
                    bdir + "/bin/stiction"], check=True, stdout=subprocess.DEVNULL)
    return bdir + "/bin/stiction"


def run(exe, d, tag, args):
    js, dump = os.path.join(d, tag + ".json"), os.path.join(d, tag + ".jsonl")
    fresh = not os.path.exists(js)
    if fresh:
        if os.path.exists(dump):
            os.remove(dump)
        t = time.time()
        p = subprocess.run([exe, "asperity"] + args + ["--json", "--threads", "1"],
                           env=dict(os.environ, ASP_CAREA_DUMP=dump), capture_output=True,
                           text=True)
        if p.returncode:
            print("# %s failed: %s" % (tag, p.stderr.strip()[-200:]), file=sys.stderr)
            return None
        res = json.loads(p.stdout)
        res["time_s"] = time.time() - t
        with open(js, "w") as f:
            json.dump(res, f)
    with open(js) as f:
        res = json.load(f)
    with open(dump) as f:
        last = f.readlines()[-1]
    r, F, L, axi = surface_line(json.loads(last))
    return {"old": est_old(r, F, L, axi), "new": est_new(r, F, L, axi), "run": res["a_mm"],
            "t": res["time_s"], "fresh": fresh}


def path(d, tag, est, stride=1):
    """(delta, a) over the increments of a cached run (contacts of >= 4 nodes)."""
    with open(os.path.join(d, tag + ".jsonl")) as f:
        lines = f.readlines()
    out = []
    for ln in lines[::stride] + lines[-1:]:
        rec = json.loads(ln)
        r, F, L, axi = surface_line(rec)
        if L >= 3:
            out.append((rec["delta"], est(r, F, L, axi)))
    return sorted(set(out))


def interp(p, x):
    for (x0, y0), (x1, y1) in zip(p, p[1:]):
        if x0 <= x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0) if x1 > x0 else y0
    return None


def path_stats(d, name, dl, levels):
    """Every increment of the level-0/1 run in [delta/2, delta] against the
    level-3 run's increments (new estimator, linear in delta): the sawtooth
    phases a single delta samples at random."""
    ref = path(d, "%s_d%g_L3" % (name, dl), est_new, 2)
    dmax = ref[-1][0]
    row = "%-6s %6g |" % (name, dl)
    for lev in levels:
        for est in (est_old, est_new):
            e = [a / interp(ref, x) - 1 for x, a in path(d, "%s_d%g_L%d" % (name, dl, lev), est)
                 if x >= 0.5 * dmax and interp(ref, x)]
            if not e:
                continue
            m, rms = sum(e) / len(e), math.sqrt(sum(x * x for x in e) / len(e))
            row += " %+5.2f %4.2f %+5.2f |" % (100 * m, 100 * rms, 100 * max(e, key=abs))
        row += " n=%d |" % len(e)
    print(row, flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", default="/tmp/carea-study")
    ap.add_argument("--build", default="/tmp/b-carea-study")
    ap.add_argument("--levels", default="0,1,2,3")
    ap.add_argument("--fine", action="store_true")
    ap.add_argument("--3d", dest="three", action="store_true")
    ap.add_argument("--paths", action="store_true",
                    help="also the statistics over all increments of levels 0, 1 (slow: pure Python)")
    o = ap.parse_args()
    os.makedirs(o.dir, exist_ok=True)
    exe = build(o.build)
    levels = sorted(set([int(x) for x in o.levels.split(",")] + [3]))  # 3: the reference
    cases = [("wsp", dl, WSP) for dl in WSP_D] + [("coat", dl, COAT) for dl in COAT_D]
    worst, checked, refs = 0.0, 0, {}

    def check(e):  # runs made now use the new estimator in C
        nonlocal worst, checked
        if e["fresh"]:
            worst, checked = max(worst, abs(e["new"] / e["run"] - 1)), checked + 1
    print("case     d/wc  a_ref mm  spread%% (runs) | levels %s: old%%, new%% (a/a_ref - 1) | time s"
          % ",".join(map(str, levels)))
    for name, dl, base in cases:
        a = {}
        for lev in levels:
            a[lev] = run(exe, o.dir, "%s_d%g_L%d" % (name, dl, lev),
                         base + ["--delta", str(dl), "--mesh", str(lev)])
        fine = [a[3]] if 3 in a and a[3] else []
        if o.fine and (name, dl) in (("wsp", 6), ("wsp", 24)):
            for n in (40, 44, 52, 56):
                fine.append(run(exe, o.dir, "%s_d%g_n%d" % (name, dl, n),
                                base + ["--delta", str(dl), "--elements-per-contact", str(n)]))
            if dl == 6:
                fine.append(run(exe, o.dir, "%s_d%g_L4" % (name, dl),
                                base + ["--delta", str(dl), "--mesh", "4"]))
        fine = [f for f in fine if f]
        if not fine:
            continue
        ref = sum(f["new"] for f in fine) / len(fine)
        refs[name, dl] = ref
        spread = 100 * (max(f["new"] for f in fine) - min(f["new"] for f in fine)) / ref
        row = "%-6s %6g  %.5f  %5.2f (%d) |" % (name, dl, ref, spread, len(fine))
        for lev in levels:
            e = a.get(lev)
            if not e:
                row += "   failed    |"
                continue
            check(e)
            row += " %+6.2f %+6.2f |" % (100 * (e["old"] / ref - 1), 100 * (e["new"] / ref - 1))
        row += " " + " ".join("%.0f" % a[lev]["t"] for lev in levels if a.get(lev))
        print(row, flush=True)
    if o.three:
        print("3D (y = 0 line) against the axisymmetric reference above")
        for name, dl, lev in (("wsp", 1, 0), ("wsp", 6, 0), ("wsp", 24, 0), ("coat", 30, 0),
                              ("wsp", 6, 1)):
            e = run(exe, o.dir, "%s3d_d%g_L%d" % (name, dl, lev),
                    (WSP if name == "wsp" else COAT)
                    + ["--delta", str(dl), "--mesh", str(lev), "--model", "3d"])
            if e and (name, dl) in refs:
                check(e)
                print("%-6s %6g level %d: old %+6.2f %%  new %+6.2f %%  %.0f s"
                      % (name, dl, lev, 100 * (e["old"] / refs[name, dl] - 1),
                         100 * (e["new"] / refs[name, dl] - 1), e["t"]))
    if o.paths:
        print("over the increments in [delta/2, delta], vs level 3: per level old then new: "
              "mean%, rms%, worst%")
        for name, dl in (("wsp", 6), ("wsp", 12), ("wsp", 24), ("wsp", 48), ("coat", 10)):
            path_stats(o.dir, name, dl, [lv for lv in (0, 1) if lv in levels])
    print("# new estimator, python port vs C (a_mm of the %d runs made now): "
          "largest relative difference %.2g" % (checked, worst))


if __name__ == "__main__":
    main()
