#!/usr/bin/env python3
"""The thesis's Fig. 4.21 (mu_s versus P/Pc_su for t/R = 0.005, 0.025, 0.05
and Eco/Esu = 1, 2, 4) from an FE friction table: the table's surrogate along
delta (line, with its one-standard-error band) and the table's own points
(with their error bars), P the normal load at sliding inception.

Usage: fig4_21_table.py CLI TABLE OUTDIR
Writes OUTDIR/fig4_21_curves.csv, fig4_21_points.csv and fig4_21.png."""
import csv
import io
import json
import os
import subprocess
import sys

TR = (0.005, 0.025, 0.05)
ER = (1.0, 2.0, 4.0)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr))
    return p.stdout


def main():
    cli, table, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    axes = json.loads(run([cli, "table", "info", table, "--json"]))["axes"]
    w = axes["delta_over_omega_c"]
    n = 60
    grid = [w[0] * (w[-1] / w[0]) ** (i / (n - 1)) for i in range(n)]
    curves = os.path.join(out, "fig4_21_curves.csv")
    with open(curves, "w") as f:
        f.write("t_over_R,E_ratio,delta_over_omega_c,P_slide_over_P_c,mu_s,mu_s_err\n")
        for t in TR:
            for e in ER:
                q = json.loads(run([cli, "table", "query", table, "--delta",
                                    ",".join("%.6g" % x for x in grid), "--t-over-R", repr(t),
                                    "--E-ratio", repr(e), "--json"]))
                for r in q:
                    f.write("%g,%g,%.6g,%.6g,%.6g,%.6g\n" % (t, e, r["delta_over_omega_c"],
                                                            r["P_slide_over_P_c"], r["mu_s"],
                                                            r["mu_s_err"]))
                f.write("\n\n")
    pts = os.path.join(out, "fig4_21_points.csv")
    rows = list(csv.DictReader(io.StringIO(run([cli, "table", "info", table, "--points"]))))
    with open(pts, "w") as f:
        f.write("t_over_R,E_ratio,delta_over_omega_c,P_slide_over_P_c,mu_s,mu_s_err\n")
        for t in TR:
            for e in ER:
                for r in rows:
                    if (r["state"] == "done" and abs(float(r["t_over_R"]) - t) < 1e-9 and
                            abs(float(r["E_ratio"]) - e) < 1e-9):
                        f.write("%s,%s,%s,%s,%s,%s\n" % (t, e, r["delta_over_omega_c"],
                                                         r["P_slide_over_P_c"], r["mu_s"],
                                                         r["mu_s_err"]))
                f.write("\n\n")
    png = os.path.join(out, "fig4_21.png")
    gp = """set terminal png size 1500,520 font ",11" noenhanced
set output "%(png)s.tmp"
set datafile separator ","
set multiplot layout 1,3 title "Static friction of a coated asperity under load (thesis Fig. 4.21) from the FE friction table %(table)s: lines = table surrogate +- 1 standard error, points = table points"
set xrange [0:100]
set yrange [0:1.5]
set grid
set xlabel "P/Pc_su (P at sliding inception)"
set ylabel "static friction coefficient mu_s"
set key top right
colors = "#0050a0 #c04000 #208020"
""" % {"png": png, "table": os.path.basename(table)}
    for i, t in enumerate(TR):
        gp += 'set title "(%s) t/R = %g"\n' % ("abc"[i], t)
        parts = []
        for j, e in enumerate(ER):
            blk = 3 * i + j
            c = 'lc rgb word(colors, %d)' % (j + 1)
            parts.append('"%s" index %d using 4:($5-$6):($5+$6) with filledcurves fs '
                         'transparent solid 0.2 %s notitle' % (curves, blk, c))
            parts.append('"%s" index %d using 4:5 with lines lw 2 %s title "Eco/Esu = %g"'
                         % (curves, blk, c, e))
            parts.append('"%s" index %d using 4:5:6 with yerrorbars pt 7 ps 0.8 %s notitle'
                         % (pts, blk, c))
        gp += "plot " + ", \\\n     ".join(parts) + "\n"
    gp += "unset multiplot\n"
    p = subprocess.run(["gnuplot"], input=gp, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("gnuplot failed: %s" % p.stderr)
    os.replace(png + ".tmp", png)
    print("wrote %s (curves %s, points %s)" % (png, curves, pts))


if __name__ == "__main__":
    main()
