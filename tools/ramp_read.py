"""Readings of one shear ramp under candidate sliding-inception rules, shared
by ramp-readings.py (the references' kept ramps) and validate-smoothness.py
(a run's own shear.csv).  A ramp is a list of points (ux, Q, P, limit
fraction), ux increasing (docs/design.md section 4.4)."""
import csv


def load_shear_csv(path):
    """The ramp of one run's shear.csv (stiction asperity --shear --out DIR)."""
    with open(path) as f:
        return [tuple(float(r[c]) for c in ("ux_mm", "Q_N", "P_N", "limit_fraction"))
                for r in csv.DictReader(f)]


def first_crossing(pts, col, x):
    """(i, s): the first ramp point i whose column col reaches x and the
    fraction s of the way from point i - 1 where it crosses (linear); None if
    it never does."""
    for i in range(1, len(pts)):
        v0, v1 = pts[i - 1][col], pts[i][col]
        if v1 >= x:
            return i, (x - v0) / (v1 - v0) if v1 > v0 else 1.0
    return None


def between(pts, i, s, col):
    return pts[i - 1][col] + s * (pts[i][col] - pts[i - 1][col])


def at_fraction(pts, x):
    """Q_max up to the first crossing of the limit fraction through x, over P
    there; None if the ramp never reaches x."""
    c = first_crossing(pts, 3, x)
    if c is None:
        return None
    i, s = c
    return max(max(p[1] for p in pts[:i]), between(pts, i, s, 1)) / between(pts, i, s, 2)


def at_stiffness(pts, a):
    """Q/P where the secant stiffness first falls to a times the first's."""
    if len(pts) < 3 or pts[1][0] <= pts[0][0]:
        return None
    kt1 = (pts[1][1] - pts[0][1]) / (pts[1][0] - pts[0][0])
    for i in range(2, len(pts)):
        kt = (pts[i][1] - pts[i - 1][1]) / (pts[i][0] - pts[i - 1][0])
        if kt <= a * kt1:
            return pts[i][1] / pts[i][2]
    return None


def readings(pts, as_run, fractions, stiffness):
    """One ramp's mu_s under each rule: [as_run (the run's own), Q/P at the first
    crossing of each limit fraction, where the secant falls to each stiffness
    ratio]; None where the ramp does not reach a rule."""
    return [as_run] + [at_fraction(pts, x) for x in fractions] + \
        [at_stiffness(pts, a) for a in stiffness]


def at_ux(pts, u):
    """Q/P at ux = u, interpolated; None beyond the ramp."""
    c = first_crossing(pts, 0, u)
    if c is None:
        return None
    i, s = c
    return between(pts, i, s, 1) / between(pts, i, s, 2)
