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

import figure
from figure import pct_range
from wsp_case import wsp_mu

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
    info = json.loads(run([cli, "table", "info", table, "--json"]))
    fam = info["family"]
    # Eco/Esu = 1 is the homogeneous sphere: against the WSP fit at the same delta
    devs = []
    with open(curves) as f:
        for r in csv.DictReader(l for l in f if l.strip()):
            if r["t_over_R"] != "t_over_R" and float(r["E_ratio"]) == 1.0:
                devs.append(float(r["mu_s"]) / wsp_mu(float(r["delta_over_omega_c"])) - 1)
    note, bottom = figure.notes([
        "Lines: the table's surrogate along δ, band ± 1 standard error; points: the table's"
        " FE points with their error bars; P is the normal load at sliding inception.",
        "Dashed: the homogeneous sphere's Wu, Shi and Polycarpou (2012) fit μ_{s}(δ/ω_{c}) at"
        " the δ of E_{co}/E_{su} = 1 (that sphere): the table vs it %s." % pct_range(devs),
        "No published fit gives the coated sphere's μ_{s}. Table: %d points, surrogate"
        " leave-one-out error %.1f %% rms (stiction table info)."
        % (info["points"], 100 * info["loo_rms_rel"])], 620)
    gp = """set datafile separator ","
set multiplot layout 1,3 margins 0.05,0.99,%(bottom)g,0.84 spacing 0.05,0 title "Fig. 4.21: static friction coefficient of a coated sphere versus normal load, from the FE friction table %(table)s\\n%(case)s"
set xrange [0:100]
set yrange [0:1.5]
set grid
set xlabel "P/P_{c,su}  (normal load at sliding inception, normalised)"
set ylabel "static friction coefficient μ_{s} = Q_{max}/P"
set key top right Left reverse
colors = "#0050a0 #c04000 #208020"
wsp(w) = 0.3 / tanh(0.57 * w**0.41)
%(note)s""" % {"table": os.path.basename(table), "note": note, "bottom": bottom,
               "case": "E/Y = %g (substrate), %g (coating), ν = %g; %s normal step, interface"
                       " τ_{c} = %.3g Y_{co}, %s criterion of sliding inception; R and E_{su}:"
                       " any (normalised)" % (fam["E_over_Y_su"], fam["E_over_Y_co"],
                                              fam["nu_su"], fam["contact"],
                                              fam["tau_c_over_Y_co"], fam["criterion"])}
    for i, t in enumerate(TR):
        gp += 'set title "(%s) t/R = %g"\n' % ("abc"[i], t)
        parts = []
        for j, e in enumerate(ER):
            blk = 3 * i + j
            c = 'lc rgb word(colors, %d)' % (j + 1)
            parts.append('"%s" index %d using 4:($5-$6):($5+$6) with filledcurves fs '
                         'transparent solid 0.2 %s notitle' % (curves, blk, c))
            parts.append('"%s" index %d using 4:5 with lines lw 2 %s title "E_{co}/E_{su} = %g"'
                         % (curves, blk, c, e))
            parts.append('"%s" index %d using 4:5:6 with yerrorbars pt 7 ps 0.8 %s notitle'
                         % (pts, blk, c))
            if e == 1.0:
                parts.append('"%s" index %d using 4:(wsp($3)) with lines dt 2 lw 2 lc rgb '
                             '"black" title "WSP fit, E_{co}/E_{su} = 1"' % (curves, blk))
        gp += "plot " + ", \\\n     ".join(parts) + "\n"
        gp += "unset label\n"
    gp += "unset multiplot\n"
    figure.gnuplot(png, 1500, 620, gp)
    print("wrote %s (curves %s, points %s); Eco/Esu = 1 vs the WSP fit at its delta: %s"
          % (png, curves, pts, pct_range(devs)))


if __name__ == "__main__":
    main()
