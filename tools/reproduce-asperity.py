#!/usr/bin/env python3
"""make reproduce, asperity part: thesis Fig. 4.3 and Figs. 4.4-4.5.

reproduce-asperity.py CLI OUTDIR

Fig. 4.3: R = 10 mm, Esu = 200 GPa, Eco/Esu = 4, t/R = 0.001 ... 0.009,
omega <= 0.0002 mm, elastic (yield strengths just below E), slip: P-omega
curves with the uncoated sphere.  Figs. 4.4-4.5: t/R = 0.05, Eco/Esu =
2 ... 10, stick, E/Y = 1000: L/Lc2 and A/Ac2 versus delta/delta_c2 up to 1
against the Ronen et al. (2017) relations L/Lc2 = (d/dc2)^1.25, A/Ac2 =
d/dc2, normalised by the fits' dc2, Lc2, Ac2.  Writes CSV
data, PNG figures (gnuplot, 'png' terminal) and a deviations table.
"""
import json
import math
import os
import subprocess
import sys


def run(cli, args):
    r = subprocess.run([cli, "asperity", "--json"] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("stiction asperity %s: %s" % (" ".join(args), r.stderr.strip()))
    j = json.loads(r.stdout)
    return j if isinstance(j, list) else [j]


def smooth(p):
    """P_smooth (the load without the node-entry sawtooth), or P where the
    solver had too few increments for it."""
    return p["P_smooth_N"] if p["P_smooth_N"] is not None else p["P_N"]


def gnuplot(script):
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def fig43(cli, out):
    rows = []
    cases = [("uncoated", ["--t-over-R", "0", "--Y-co", "199000"])] + [
        ("t/R=%g" % t, ["--t-over-R", str(t), "--E-ratio", "4", "--Y-co", "799000"])
        for t in (0.001, 0.003, 0.005, 0.007, 0.009)]
    plots = []
    for name, a in cases:
        pts = run(cli, a + ["--Y-su", "199000", "--contact", "slip",
                            "--delta-mm", "0.00002:0.0002:10"])
        fn = os.path.join(out, "fig4_3_%s.csv" % name.replace("/", "").replace("=", "_"))
        with open(fn, "w") as f:
            f.write("omega_mm,P_N\n")
            for p in pts:
                f.write("%.9g,%.9g\n" % (p["delta_mm"], p["P_N"]))
        rows.append((name, pts[-1]["P_N"]))
        plots.append("'%s' u 1:2 every ::1 w lp t '%s'" % (fn, name))
    gnuplot("set terminal png size 900,650\nset output '%s'\nset datafile separator ','\n"
            "set xlabel 'omega (mm)'\nset ylabel 'P (N)'\nset key left top\n"
            "set title 'Fig. 4.3: coated sphere, Eco/Esu = 4, elastic, slip'\nplot %s\n"
            % (os.path.join(out, "fig4_3.png"), ", ".join(plots)))
    base = rows[0][1]
    print("Fig. 4.3: P at omega = 0.0002 mm (stiffening over the uncoated sphere)")
    for name, P in rows:
        print("  %-10s P = %8.4f N  (%+.1f %%)" % (name, P, 100 * (P / base - 1)))


def fig44(cli, out):
    nu, EY, R = 0.32, 1000.0, 10.0
    Cv = 1.234 + 1.256 * nu
    wc = (Cv * math.pi * (1 - nu * nu) / 2 / EY) ** 2 * R
    Pc_su = math.pi ** 3 * 200.0 / 6 * Cv ** 3 * (R * (1 - nu * nu) / EY) ** 2
    Ac = math.pi * wc * R
    tR = 0.05
    pl, pa = [], []
    print("Figs. 4.4-4.5: t/R = 0.05, stick; deviation of FE from Ronen at delta = delta_c2")
    for er in (2, 4, 6, 8, 10):
        dc2 = tR ** 1.17 * (er - 1) ** -0.09 * EY ** 1.93 * EY ** -0.89 * wc
        Lc2 = tR ** 1.8 * (er - 1) ** -0.27 * EY ** 2.3 * EY ** -0.78 * (er * Pc_su)
        Ac2 = tR ** 1.6 * (er - 1) ** -0.2 * EY ** 2 * EY ** -0.7 * Ac
        pts = run(cli, ["--t-over-R", str(tR), "--E-ratio", str(er), "--contact", "stick",
                        "--delta-mm", "%.9g:%.9g:8" % (dc2 / 8, dc2)])
        fn = os.path.join(out, "fig4_4_E%d.csv" % er)
        with open(fn, "w") as f:
            # L_smooth: P_smooth, the load without the node-entry sawtooth
            f.write("d_over_dc2,L_over_Lc2,A_over_Ac2,L_smooth_over_Lc2\n")
            for p in pts:
                f.write("%.6g,%.6g,%.6g,%.6g\n" % (p["delta_mm"] / dc2, p["P_N"] / Lc2,
                                                  p["A_mm2"] / Ac2, smooth(p) / Lc2))
        last = pts[-1]
        Ps = smooth(last)
        print("  Eco/Esu = %2d: L/Lc2 = %.3f (smoothed %.3f; Ronen 1), A/Ac2 = %.3f (Ronen 1), "
              "FE dc2/fit = %s"
              % (er, last["P_N"] / Lc2, Ps / Lc2, last["A_mm2"] / Ac2,
                 "%.3f" % (last["delta_c2_over_omega_c_su"] * wc / dc2)
                 if last["delta_c2_over_omega_c_su"] else "not reached"))
        pl.append("'%s' u 1:4 w lp t 'FE Eco/Esu=%d'" % (fn, er))
        pa.append("'%s' u 1:3 w lp t 'FE Eco/Esu=%d'" % (fn, er))
    for name, col, ronen, curves in (("fig4_4", "L/Lc2", "x**1.25", pl),
                                     ("fig4_5", "A/Ac2", "x", pa)):
        gnuplot("set terminal png size 900,650\nset output '%s'\nset datafile separator ','\n"
                "set xlabel 'delta/delta_c2'\nset ylabel '%s'\nset key left top\n"
                "set xrange [0:1]\nplot %s, %s w l lw 2 t 'Ronen et al. 2017'\n"
                % (os.path.join(out, name + ".png"), col, ", ".join(curves), ronen))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    os.makedirs(sys.argv[2], exist_ok=True)
    fig43(sys.argv[1], sys.argv[2])
    fig44(sys.argv[1], sys.argv[2])
