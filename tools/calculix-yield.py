#!/usr/bin/env python3
"""First yield of an elastic hemisphere pressed by a rigid flat, computed with
CalculiX (ccx) as independent evidence for the first-yield numbers of the
axisymmetric FE solver (docs/yield-discrepancies.md; data/calculix/README.md).

  calculix-yield.py run --contact slip|stick|touch --N 32 [options]   one case
  calculix-yield.py sweep [--out data/calculix/first-yield.csv]        the stored study

Model (docs/design.md §2.1): a hemisphere of radius R (coated: R + t, the
coating outside rho = R), fixed (u_x = u_y = 0) on its base plane through the
centre, u_x = 0 on the axis, axisymmetric (CAX8, CAX6 at the apex and the
rim), linear elastic, pressed by a flat whose nodes all have prescribed
displacements (so it is rigid).  Contact: node-to-surface penalty contact,
sphere surface the slave, linear pressure-overclosure (slope --penalty,
MPa/mm); face-to-face contact loses the contact next to the axis in ccx's
expanded axisymmetric model.  slip: frictionless.  stick: ccx's friction,
coefficient 1e4, stick slope = the normal penalty.  touch: stuck where it
touched (see write_deck): frictionless contact, one step per increment, a
node's radial displacement fixed from the step after it first touched, the
touch steps iterated over whole runs until they repeat.

Mesh (written here): polar around the apex.  Ring k is the circle of radius
s_k about the apex; on it the nodes are spread uniformly in the angle psi
(from the downward axis) between the axis (below the centre: the base plane)
and the sphere surface, N intervals.  The rings grow geometrically with a
ratio 1 + pi/(2N) (square elements) out to 3 a_max, then the ratio grows by
4 % per ring up to 1 + 4 pi/(2N); the centre is a ring point and the last
ring collapses to the rim point (R, 0).  The innermost ring s_1 = a_max/20
is joined to the apex by a fan of triangles.  Element size at depth d below
the apex on the axis: d pi/(2N).  Midside nodes lie on the same map, so
edges on the sphere are on the sphere.  Coated: an element is coating when
its centroid lies outside rho = R (the interface is stepped, not fitted).

Interference delta: the descent of the surface node of ring 1 plus its
initial gap (the flat's descent less the penalty overclosure).  Load: the
flat's total reaction times 180 (ccx prints its expanded 2-degree sector).
First yield: the peak von Mises stress over the integration points of the
elements within --box-r a_max of the axis and --box-d a_max of the surface,
per increment (coated: the coating's elements against its own Y); delta_y
where the power law through the two increments that bracket Y reaches it.
"""
import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

E_DEF, NU_DEF, R_DEF, EY_DEF = 200000.0, 0.32, 10.0, 1000.0
# The deck is written in micrometres and micronewtons (stress stays in MPa):
# ccx rejects the Jacobian of axisymmetric elements of 1e-4 mm next to the axis
# (an absolute threshold), and in micrometres they are 0.1.
LU = 1000.0          # deck lengths per mm
FU = 1.0e6           # deck forces per N
FLAT_X0 = 1e-3       # the flat starts this fraction of s_1 off the axis
SECTOR = 180.0       # ccx prints the reactions of its expanded 2-degree sector


def omega_c(E, nu, Y, R):
    """Kogut & Etsion (2002) critical interference (mm) and load (N)."""
    cv = 1.234 + 1.256 * nu
    w = (cv * math.pi * (1 - nu * nu) / 2 * (Y / E)) ** 2 * R
    P = math.pi ** 3 * Y / 6 * cv ** 3 * (R * (1 - nu * nu) * (Y / E)) ** 2
    return w, P


# ---------------------------------------------------------------- the mesh
def rings(R, N, amax, core=20.0, near=3.0, growth=1.04, maxaspect=4.0):
    """Ring radii about the apex, s_0 = 0 ... s_K = sqrt(2) R (the rim)."""
    q0 = 1 + math.pi / (2 * N)
    qmax = 1 + maxaspect * math.pi / (2 * N)
    s = [0.0, amax / core]
    q = q0
    smax = math.sqrt(2) * R
    while s[-1] * q < smax:
        if s[-1] > near * amax:
            q = min(q * growth, qmax)
        if s[-1] < R < s[-1] * q:        # the centre is a node: the axis turns into the base there
            if R / s[-1] > 1 + 0.3 * (q - 1):
                s.append(R)
            else:
                s[-1] = R
            continue
        s.append(s[-1] * q)
    # the last step must not be tiny: merge it into the previous one
    if smax / s[-1] < 1 + 0.3 * (q - 1):
        s.pop()
    s.append(smax)
    return s


class Mesh:
    """Nodes keyed by doubled (ring, ray) indices so midside nodes are integer."""

    def __init__(self, R, N, amax):
        self.R, self.N = R, N
        self.s = rings(R, N, amax)
        self.K = len(self.s) - 1

    def s_at(self, k2):
        k, r = divmod(k2, 2)
        return self.s[k] if r == 0 else 0.5 * (self.s[k] + self.s[k + 1])

    def xy(self, k2, j2):
        R = self.R
        s = self.s_at(k2)
        if s == 0.0:
            return 0.0, R
        lo = 0.0 if s <= R else math.acos(min(1.0, R / s))
        hi = math.acos(min(1.0, s / (2 * R)))
        psi = lo + (hi - lo) * j2 / (2 * self.N)
        return s * math.sin(psi), R - s * math.cos(psi)

    def elements(self):
        """(type, corner keys ccw, midside keys) in (x, y)."""
        N, K = self.N, self.K
        out = []
        # apex fan: apex, ring 1 ray j, ring 1 ray j+1 (psi grows towards the surface,
        # x grows with psi, so (apex, j+1, j) is counterclockwise)
        for j in range(N):
            c = [(0, 0), (2, 2 * j + 2), (2, 2 * j)]
            out.append(("CAX6", c, [(1, 2 * j + 2), (2, 2 * j + 1), (1, 2 * j)]))
        for k in range(1, K - 1):
            for j in range(N):
                a, b = 2 * k, 2 * k + 2
                c = [(a, 2 * j), (b, 2 * j), (b, 2 * j + 2), (a, 2 * j + 2)]
                mid = [(a + 1, 2 * j), (b, 2 * j + 1), (a + 1, 2 * j + 2), (a, 2 * j + 1)]
                out.append(("CAX8", c, mid))
        # the last ring is one point (the rim): triangles
        k = K - 1
        a, b = 2 * k, 2 * k + 2
        for j in range(N):
            c = [(a, 2 * j), (b, 0), (a, 2 * j + 2)]
            out.append(("CAX6", c, [(a + 1, 2 * j), (a + 1, 2 * j + 2), (a, 2 * j + 1)]))
        return out

    def canon(self, key):
        """Collapsed keys: every ray of ring 0 is the apex, of ring K the rim."""
        k2, j2 = key
        if k2 == 0 or k2 == 2 * self.K:
            return (k2, 0)
        return key


# ---------------------------------------------------------------- the deck
def write_deck(path, m, E, nu, dmax, amp, contact, penalty, box, amax, pair, Rin=None, Eco=None,
               touch=None, anchor="end"):
    """touch (contact "touch"): {node: step at whose end it was first in contact};
    one step per amplitude value, and a node's radial displacement is fixed
    (*BOUNDARY, FIXED: at its value at the end of the previous step) from the step
    after that on (anchor "end": where it was at the end of the step in which it
    touched, having slid frictionlessly for part of it) or from that step on
    (anchor "start": where it was just before the step, before it touched).  The
    two err by one step in opposite directions.  Frictionless contact carries
    the normal load."""
    """The ccx input deck; returns (apex node id, 2D node count, element count, centroids)."""
    ids, coords = {}, []

    def nid(key):
        key = m.canon(key)
        if key not in ids:
            ids[key] = len(ids) + 1
            coords.append(m.xy(*key))
        return ids[key]

    els = []
    for typ, cs, ms in m.elements():
        pts = [m.xy(*m.canon(k)) for k in cs]
        n = len(pts)
        if sum(pts[a][0] * pts[(a + 1) % n][1] - pts[(a + 1) % n][0] * pts[a][1] for a in range(n)) < 0:
            cs = cs[::-1]                       # counterclockwise in (x, y)
            ms = [ms[(n - 2 - i) % n] for i in range(n)]
        nodes = [nid(k) for k in cs] + [nid(k) for k in ms]
        pts = [coords[n - 1] for n in nodes[:len(cs)]]
        n = len(pts)
        area = sum(pts[a][0] * pts[(a + 1) % n][1] - pts[(a + 1) % n][0] * pts[a][1] for a in range(n))
        if area <= 0:
            raise RuntimeError("element %d is not counterclockwise (area %g)" % (len(els) + 1, area))
        cx = sum(p[0] for p in pts) / n
        cy = sum(p[1] for p in pts) / n
        els.append((len(els) + 1, typ, nodes, (cx, cy), cs))
    R = m.R
    nn = len(coords)
    # a coated sphere: an element is coating when its centroid lies outside rho = Rin
    layer = {e[0]: "COAT" if Rin and math.hypot(*e[3]) > Rin else "SUB" for e in els}
    apex = ids[(0, 0)]
    probe = ids[(2, 2 * m.N)]            # ring 1 on the sphere: in contact from the start
    tol = 1e-12 * R
    base = [k for k, (x, y) in enumerate(coords, 1) if abs(y) < tol]
    axis = [k for k, (x, y) in enumerate(coords, 1) if abs(x) < tol and y >= -tol]
    # the flat: a row of CAX4 elements over x in [0, xf], y in [R, R + H]
    # its nodes at the x of the sphere's surface corners (the master faces match
    # the slave faces one to one), the first one off the axis by FLAT_X0 of s_1
    xf, H = 3.0 * amax, 0.5 * amax
    fx = sorted(x for (k2, j2), (x, y) in zip(ids, coords)
                if j2 == 2 * m.N and k2 % 2 == 0 and 0 < x < xf)
    fx = [FLAT_X0 * m.s[1]] + fx + [xf]
    nf = len(fx) - 1
    fnodes = []
    with open(path, "w") as f:
        f.write("*HEADING\nhemisphere on a rigid flat, first yield (tools/calculix-yield.py)\n*NODE\n")
        for k, (x, y) in enumerate(coords, 1):
            f.write("%d,%.16g,%.16g\n" % (k, x * LU, y * LU))
        for q, x in enumerate(fx):
            f.write("%d,%.16g,%.16g\n%d,%.16g,%.16g\n" % (nn + 2 * q + 1, x * LU, R * LU,
                                                           nn + 2 * q + 2, x * LU, (R + H) * LU))
            fnodes += [nn + 2 * q + 1, nn + 2 * q + 2]
        for typ in ("CAX8", "CAX6"):
            for lay in ("SUB", "COAT"):
                sel = [e for e in els if e[1] == typ and layer[e[0]] == lay]
                if sel:
                    f.write("*ELEMENT,TYPE=%s,ELSET=%s\n" % (typ, lay))
                    for e in sel:
                        f.write("%d,%s\n" % (e[0], ",".join(map(str, e[2]))))
        ne = len(els)
        f.write("*ELEMENT,TYPE=CAX4,ELSET=FLAT\n")
        for q in range(nf):
            a, b = nn + 2 * q + 1, nn + 2 * q + 3
            f.write("%d,%d,%d,%d,%d\n" % (ne + q + 1, a, b, b + 1, a + 1))
        writeset(f, "NSET", "BASE", base)
        writeset(f, "NSET", "AXIS", axis)
        writeset(f, "NSET", "APEX", [probe])
        writeset(f, "NSET", "FLATN", fnodes)
        surfn = sorted(ids[k] for k in ids if (k[1] == 2 * m.N or k == (0, 0))
                       and m.xy(*k)[0] < 0.8 * xf)
        writeset(f, "NSET", "SURFN", surfn)
        eout = [e[0] for e in els if e[3][0] <= box[0] * amax and R - e[3][1] <= box[1] * amax]
        writeset(f, "ELSET", "EOUT", eout)
        # slave faces: element edges on the sphere (ray N) within x < xf
        f.write("*SURFACE,NAME=SPH,TYPE=ELEMENT\n")
        nslave = 0
        for e in els:
            cs = e[4]
            n = len(cs)
            for a in range(n):
                p, q = m.canon(cs[a]), m.canon(cs[(a + 1) % n])
                on = [k == (0, 0) or k[1] == 2 * m.N for k in (p, q)]
                if all(on) and p != q:
                    xa = max(m.xy(*p)[0], m.xy(*q)[0])
                    if xa < 0.8 * xf:
                        f.write("%d,S%d\n" % (e[0], a + 1))
                        nslave += 1
        f.write("*SURFACE,NAME=FLS,TYPE=ELEMENT\n")
        for q in range(nf):
            f.write("%d,S1\n" % (ne + q + 1))
        f.write("*MATERIAL,NAME=MSP\n*ELASTIC\n%.10g,%.10g\n" % (E, nu))
        f.write("*MATERIAL,NAME=MCO\n*ELASTIC\n%.10g,%.10g\n" % (Eco or E, nu))
        f.write("*MATERIAL,NAME=MFL\n*ELASTIC\n%.10g,0.\n" % (1000 * E))
        f.write("*SOLID SECTION,ELSET=SUB,MATERIAL=MSP\n")
        if "COAT" in layer.values():
            f.write("*SOLID SECTION,ELSET=COAT,MATERIAL=MCO\n")
        f.write("*SOLID SECTION,ELSET=FLAT,MATERIAL=MFL\n")
        f.write("*SURFACE INTERACTION,NAME=SI\n*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR\n"
                "%.6g\n" % (penalty / LU))
        if contact == "stick":
            f.write("*FRICTION\n1e4,%.6g\n" % (penalty / LU))
        f.write("*CONTACT PAIR,INTERACTION=SI,TYPE=%s\nSPH,FLS\n" % pair)
        f.write("*BOUNDARY\nBASE,1,2\nAXIS,1\nFLATN,1\n")
        prints = ("*NODE PRINT,NSET=APEX\nU\n*NODE PRINT,NSET=FLATN,TOTALS=ONLY\nRF\n"
                  "*NODE PRINT,NSET=SURFN\nU\n*EL PRINT,ELSET=EOUT\nS\n*END STEP\n")
        if contact == "touch":
            for k in range(1, len(amp)):
                f.write("*STEP,INC=1000\n*STATIC\n1.,1.\n*BOUNDARY\nFLATN,2,2,%.12g\n"
                        % (-dmax * amp[k] * LU))
                lag = 1 if anchor == "end" else 0
                new = sorted(nd for nd, s in touch.items() if s == k - lag and nd not in axis)
                if new:
                    f.write("*BOUNDARY,FIXED\n")
                    for nd in new:
                        f.write("%d,1,1\n" % nd)
                f.write(prints)
        else:
            f.write("*AMPLITUDE,NAME=RAMP\n")
            n = len(amp)
            for k, v in enumerate(amp):
                f.write("%.12g,%.12g\n" % (k / (n - 1), v))
            f.write("*STEP,INC=100000\n*STATIC,DIRECT\n%.12g,1.\n" % (1.0 / (n - 1)))
            f.write("*BOUNDARY,AMPLITUDE=RAMP\nFLATN,2,2,%.12g\n" % (-dmax * LU))
            f.write(prints)
    gap = R - coords[probe - 1][1]
    return gap, nn, ne, {e[0]: e[3] for e in els}, layer, {k: coords[k - 1] for k in surfn}


def writeset(f, kind, name, items):
    f.write("*%s,%s=%s\n" % (kind, kind, name))
    for a in range(0, len(items), 12):
        f.write(",".join(map(str, items[a:a + 12])) + "\n")


# ---------------------------------------------------------------- results
def parse_dat(path, layer):
    """Per increment (time): the probe's u_y, the flat's total reaction, the
    surface nodes' u_y, peak von Mises per layer with element and point."""
    inc = {}
    mode, t = None, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            if s.startswith("displacements"):
                mode, t = ("us" if "SURFN" in s else "u"), float(s.split()[-1])
                continue
            if s.startswith("total force"):
                mode, t = "rf", float(s.split()[-1])
                continue
            if s.startswith("stresses"):
                mode, t = "s", float(s.split()[-1])
                continue
            if s[0].isalpha():
                mode = None
                continue
            r = inc.setdefault(t, {"peak": (0.0, 0, 0), "peaks": {}, "surf": {}})
            v = s.split()
            if mode == "u":
                r["uy"] = float(v[2]) / LU
            elif mode == "us":
                r["surf"][int(v[0])] = float(v[2]) / LU
            elif mode == "rf":
                r["P"] = -float(v[1]) * SECTOR / FU
            elif mode == "s":
                sx, sy, sz, txy, txz, tyz = map(float, v[2:8])
                vm = math.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                               + 3 * (txy ** 2 + txz ** 2 + tyz ** 2))
                e, lay = int(v[0]), layer[int(v[0])]
                if vm > r["peak"][0]:
                    r["peak"] = (vm, e, int(v[1]))
                if vm > r["peaks"].get(lay, (0.0,))[0]:
                    r["peaks"][lay] = (vm, e, int(v[1]))
    return [dict(time=k, **v) for k, v in sorted(inc.items()) if "uy" in v and "P" in v]


def first_yield(rows, Y, lay="SUB"):
    """delta (mm) where the peak von Mises reaches Y (power law between the
    bracketing increments), the load there (same), the element, the ratio of
    the bracketing deltas."""
    prev = None
    for r in rows:
        d, s, P = -r["uy"], r["peaks"].get(lay, (0.0,))[0], r["P"]
        if s >= Y:
            if prev is None or prev[1] <= 0 or prev[2] <= 0:
                return None
            d0, s0, P0 = prev
            n = math.log(s / s0) / math.log(d / d0)
            dy = d0 * (Y / s0) ** (1 / n)
            Py = P0 * (dy / d0) ** (math.log(P / P0) / math.log(d / d0))
            return dy, Py, r["peaks"][lay][1], d / d0
        prev = (d, s, P)
    return None


def ramp(lo, knee, hi, q_lo, q_hi):
    """Amplitude values (fractions of hi): geometric with ratio q_lo from lo
    up to knee, then q_hi up to hi."""
    v = [lo]
    while v[-1] * q_lo < knee:
        v.append(v[-1] * q_lo)
    while v[-1] * q_hi < hi * (1 - 1e-9):
        v.append(v[-1] * q_hi)
    v.append(hi)
    return [0.0] + [x / hi for x in v]


def ccx_run(a, m, E, nu, dmax, amp, amax, Rin, Eco, touch):
    """Write the deck, run ccx on one thread, read its .dat."""
    tmp = tempfile.mkdtemp(prefix="ccxyield.")
    try:
        deck = os.path.join(tmp, "sphere.inp")
        gap, nn, ne, ecent, layer, surf = write_deck(
            deck, m, E, nu, dmax, amp, a.contact, a.penalty, (a.box_r, a.box_d), amax,
            PAIRS[a.pair], Rin, Eco, touch, a.anchor)
        if a.keep:
            shutil.copy(deck, a.keep + ".inp")
        env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1",
                   CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")
        t0 = time.time()
        p = subprocess.run(["ccx", "-i", "sphere"], cwd=tmp, capture_output=True, text=True, env=env)
        wall = time.time() - t0
        if a.keep:
            with open(a.keep + ".log", "w") as g:
                g.write(p.stdout + p.stderr)
            if os.path.exists(os.path.join(tmp, "sphere.dat")):
                shutil.copy(os.path.join(tmp, "sphere.dat"), a.keep + ".dat")
        if p.returncode != 0 or not os.path.exists(os.path.join(tmp, "sphere.dat")):
            sys.stderr.write(p.stdout[-3000:] + p.stderr[-2000:])
            raise RuntimeError("ccx failed")
        rows = parse_dat(os.path.join(tmp, "sphere.dat"), layer)
        for r in rows:                   # delta = the probe's descent + its initial gap
            r["uy"] -= gap
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return rows, wall, gap, nn, ne, ecent, layer, surf


def run(a):
    """One ccx run; a dict of the CSV fields (and _checks, _rows for printing).
    Coated: the sphere's outer radius is R + t, omega_c and P_c those of the
    substrate with R (as the FE solver's tables), the coating Y = E_co/(E/Y)."""
    E, nu, R, Y = a.E, a.nu, a.R, a.E / a.E_over_Y
    t = a.t_over_R * R
    Eco = E * a.E_ratio
    wc, Pc = omega_c(E, nu, Y, R)
    Ro = R + t
    dmax = a.delta_max * wc
    amax = math.sqrt(Ro * dmax)
    m = Mesh(Ro, a.N, amax)
    amp = ramp(a.delta_min, a.knee, a.delta_max, a.ratio_lo, a.ratio_hi)
    touch, passes, wall, changed = {}, 0, 0.0, ""
    while True:
        rows, wall1, gap, nn, ne, ecent, layer, surf = ccx_run(
            a, m, E, nu, dmax, amp, amax, R if t > 0 else None, Eco, touch)
        wall += wall1
        passes += 1
        if a.contact != "touch":
            break
        # first step at whose end each surface node is in contact (zero or
        # positive overclosure), from this pass; repeat until it does not change
        new = {}
        for r in rows:
            k = round(r["time"])
            if abs(r["time"] - k) > 1e-6:
                continue
            front = Ro - dmax * amp[k]
            for nd, uy in r["surf"].items():
                if nd not in new and surf[nd][1] + uy >= front:
                    new[nd] = k
        if new == touch or passes >= a.passes:
            changed = sum(1 for nd in set(new) | set(touch) if new.get(nd) != touch.get(nd))
            break
        touch = new
    # Hertz with the outer layer's modulus (homogeneous: the sphere's)
    Es = (Eco if t > 0 else E) / (1 - nu * nu)
    out = {"case": case_name(a),
           "contact": a.contact, "nu": nu, "N": a.N,
           "h_yield_over_a": round(0.5 * math.pi / (2 * a.N), 4),
           "nodes_2d": nn, "elements": ne, "increments": len(rows), "wall_s": round(wall, 1),
           "passes": passes, "touch_changed": changed}
    checks = []
    for r in rows:
        d = -r["uy"]
        if d > 0:
            checks.append((d / wc, r["P"] / (4.0 / 3.0 * Es * math.sqrt(Ro) * d ** 1.5)))
    # homogeneous: the sphere; coated: the coating (first yield delta_c1)
    lay, Yl = ("COAT", Eco / a.E_over_Y) if t > 0 else ("SUB", Y)
    fy = first_yield(rows, Yl, lay)
    if fy is None:
        out.update(delta_y_over_omega_c="", P_y_over_P_c="", yield_r_over_a="", yield_depth_over_a="")
    else:
        dy, Py, e, ratio = fy
        x, y = ecent[e]
        ay = math.sqrt(Ro * dy)
        out.update(delta_y_over_omega_c=round(dy / wc, 5), P_y_over_P_c=round(Py / Pc, 5),
                   yield_r_over_a=round(x / ay, 3), yield_depth_over_a=round((Ro - y) / ay, 3))
    # Hertz check: P / (4/3 E* R^1/2 delta^3/2) at the increment nearest 1 omega_c
    if checks:
        c = min(checks, key=lambda c: abs(c[0] - 1.0))
        out["P_over_Hertz"] = round(c[1], 5)
        out["P_over_Hertz_at"] = round(c[0], 3)
    out["_checks"] = checks
    out["_rows"] = rows
    out["_Y"] = Yl
    return out


def case_name(a):
    return "homogeneous" if a.t_over_R == 0 else "coated t/R %g Eco/Esu %g" % (a.t_over_R, a.E_ratio)


def ramp_text(a):
    """first step, ratio up to the knee, knee, ratio beyond (omega_c)"""
    return "%g,%g,%g,%g" % (a.delta_min, a.ratio_lo, a.knee, a.ratio_hi)


PAIRS = {"n2s": "NODE TO SURFACE", "s2s": "SURFACE TO SURFACE"}

FIELDS = ["case", "contact", "nu", "N", "h_yield_over_a", "nodes_2d", "elements", "increments",
          "delta_y_over_omega_c", "P_y_over_P_c", "yield_r_over_a", "yield_depth_over_a",
          "P_over_Hertz", "P_over_Hertz_at", "ramp", "anchor", "passes", "touch_changed", "wall_s"]


def add_args(ap):
    ap.add_argument("--contact", default="slip", choices=["slip", "stick", "touch"],
                    help="slip: frictionless; stick: ccx friction, mu 1e4; touch: frictionless, "
                    "a node's radial displacement fixed from the step after it touched")
    ap.add_argument("--passes", type=int, default=4, help="touch: at most this many runs")
    ap.add_argument("--anchor", default="end", choices=["end", "start"],
                    help="touch: a node is fixed where it was at the end of the step in which "
                    "it touched, or at its start")
    ap.add_argument("--N", type=int, default=32, help="angular intervals about the apex")
    ap.add_argument("--E", type=float, default=E_DEF)
    ap.add_argument("--nu", type=float, default=NU_DEF)
    ap.add_argument("--R", type=float, default=R_DEF)
    ap.add_argument("--E-over-Y", type=float, default=EY_DEF)
    ap.add_argument("--t-over-R", type=float, default=0.0, help="coating thickness / R")
    ap.add_argument("--E-ratio", type=float, default=1.0, help="E_coating / E_substrate")
    ap.add_argument("--delta-max", type=float, default=1.15, help="in omega_c")
    ap.add_argument("--delta-min", type=float, default=0.02, help="first increment, omega_c")
    ap.add_argument("--knee", type=float, default=0.7, help="omega_c where the ramp turns fine")
    ap.add_argument("--ratio-lo", type=float, default=1.1)
    ap.add_argument("--ratio-hi", type=float, default=1.025)
    ap.add_argument("--pair", default="n2s", choices=sorted(PAIRS),
                    help="contact pair type (face-to-face fails at the axis)")
    ap.add_argument("--penalty", type=float, default=1e10, help="MPa/mm, normal and stick")
    ap.add_argument("--box-r", type=float, default=0.5, help="yield box radius, a_max")
    ap.add_argument("--box-d", type=float, default=1.0, help="yield box depth, a_max")
    ap.add_argument("--keep", default=None, help="keep the deck, log and .dat as KEEP.*")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cmd", choices=["run", "sweep"])
    ap.add_argument("--out", default=None)
    add_args(ap)
    a = ap.parse_args()
    if a.cmd == "run":
        out = run(a)
        Yl = out.pop("_Y")
        for (d, c), r in zip(out.pop("_checks"), out.pop("_rows")):
            pk = sorted(r["peaks"].items())
            print("delta/omega_c %.4f  P/Hertz %.5f  peak VM/Y %s" % (d, c, "  ".join(
                "%s %.4f (element %d point %d)" % (k, v[0] / Yl, v[1], v[2]) for k, v in pk)))
        for k, v in out.items():
            print("%s = %s" % (k, v))
        if a.out:
            append_csv(a.out, out)
        return 0
    out_path = a.out or "data/calculix/first-yield.csv"
    done = set()
    if os.path.exists(out_path):      # runs already stored are kept (delete the file to redo)
        with open(out_path) as f:
            done = {(r["case"], r["contact"], float(r["nu"]), int(r["N"]), r["ramp"],
                     r.get("anchor", "")) for r in csv.DictReader(f)}
    for args in SWEEP:
        b = ap.parse_args(["run"] + args.split())
        key = (case_name(b), b.contact, b.nu, b.N, ramp_text(b),
               b.anchor if b.contact == "touch" else "")
        if key in done:
            continue
        out = run(b)
        out.pop("_checks"), out.pop("_rows"), out.pop("_Y")
        out["ramp"] = ramp_text(b)
        out["anchor"] = b.anchor if b.contact == "touch" else ""
        append_csv(out_path, out)
        print(", ".join("%s=%s" % kv for kv in out.items()), flush=True)
    return 0


# The stored study, in the order it was run.  slip needs few increments
# (frictionless contact has no history); stick and touch take 15 % steps up
# to 0.85 omega_c, then 2.5 %; coated runs go to 2 omega_c_su, and their yield
# box reaches below the interface (t = 1.58 a_max).
SLIP = "--contact slip --delta-min 0.3 --ratio-lo 1.4 --knee 0.85 --ratio-hi 1.025"
STICK = "--contact stick --delta-min 0.05 --ratio-lo 1.15 --knee 0.85 --ratio-hi 1.025"
TOUCH = STICK.replace("stick", "touch")
START = TOUCH + " --anchor start"
FINE = lambda s: s.replace("1.15", "1.07").replace("1.025", "1.0125")
COATED = " --t-over-R 0.005 --E-ratio 2 --delta-max 2.0 --knee 1.1 --box-d 1.8"
SWEEP = [SLIP + " --N 16", SLIP + " --N 32",
         STICK + " --N 16", STICK + " --N 32", FINE(STICK) + " --N 16",
         SLIP + " --N 64",
         TOUCH + " --N 16", TOUCH + " --N 32", TOUCH + COATED + " --N 16",
         FINE(TOUCH) + " --N 16", TOUCH + " --nu 0.25 --N 16",
         START + " --N 16", FINE(START) + " --N 16", START + COATED + " --N 16",
         START + " --nu 0.25 --N 16",
         FINE(TOUCH + COATED) + " --N 16", FINE(START + COATED) + " --N 16",
         FINE(TOUCH) + " --nu 0.25 --N 16", FINE(START) + " --nu 0.25 --N 16",
         TOUCH + COATED + " --N 32", START + COATED + " --N 32", STICK + " --N 64"]


def append_csv(path, out):
    new = not os.path.exists(path)
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        if new:
            w.writeheader()
        w.writerow(out)


if __name__ == "__main__":
    sys.exit(main())
