#!/usr/bin/env python3
"""make reproduce, combined loading: thesis Figs. 4.8, 4.10, 4.16-4.21.

reproduce-shear.py CLI OUTDIR [--jobs N] [--mesh LEVEL] [--only fig4_8,fig4_10,...]
                   [--summary FILE]

make reproduce calls it once per figure (tools/reproduce.d/3*-shear-FIG.sh)
with the 3D mesh level STICTION_SHEAR_MESH, default 0 (coarse: the default
level 1 costs too much per run), two runs at a time (STICTION_JOBS), and
what it prints kept in OUTDIR/FIG.txt (--summary).  Each figure runs only
the FE runs it plots; a run that several figures plot is run once.

Every FE run is one `stiction asperity --shear` call whose JSON and Q-ux CSV
are kept in OUTDIR/runs[-meshL]/NAME/ (written to NAME.tmp and renamed when the run
has finished), so an interrupted reproduce resumes where it stopped and never
redoes a finished run.  A run that fails is recorded with its reason in
OUTDIR/runs[-meshL]/NAME.failed and left out of the figures (never plotted as a
number); the script then exits with status 1 after writing everything else.

Figures (gnuplot) and the CSV behind each, every one with its case, its
reference (the Wu-Shi-Polycarpou fit for the homogeneous sphere) and the
deviation from it written on it:
  fig4_8   homogeneous WSP sphere (E 74 GPa, nu 0.33, Y 325 MPa, R' 10.5 mm,
           slip normal step): Q/Pc versus ux/omega_c at omega/omega_c = 0.5, 3,
           12, 72, with the plateau of the Wu-Shi-Polycarpou fit (mu_s P/Pc).
  fig4_10  mu_s versus omega/omega_c (0.5 ... 72) against the WSP fit
           mu_s = 0.3 coth(0.57 (omega/omega_c)^0.41) (Wu et al. 2012; thesis
           eq. 4.1).
  fig4_16..18  coated grid of thesis Table 4.1 (R 10 mm, Esu 200 GPa,
           E/Y 1000, nu 0.32, stick normal step): Q/Pc_su versus ux/omega_c_su
           for delta/omega_c_su = 1, 10, 30, 60 and Eco/Esu = 1, 2, 4, one
           figure per t/R = 0.005, 0.025, 0.05; the table of Qmax and mu_s
           and the grid checks of that t/R printed.
  fig4_19, fig4_20  delta = omega_c_su, Eco/Esu = 2 (4.19) and 4 (4.20), the
           three t/R with the homogeneous sphere.
  fig4_21  mu_s versus P/Pc_su under load control (--load) for each t/R.
"""
import argparse
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys

import figure
import refdata
from figure import pct, pct_range
from wsp_case import WSP, wsp_mu
WSP_OMEGAS = (0.5, 1, 3, 6, 12, 24, 48, 72)
# thesis Fig. 4.8: plateaus of the Wu et al. (2012) curves, read off the plot
FIG48_THESIS = {r["omega_over_omega_c"]: r["Q_over_P_c"]
                for r in refdata.rows("thesis/fig4_8_plateaus.csv")}
FIG48_OMEGAS = tuple(sorted(FIG48_THESIS))
# the coated grid: thesis Table 4.1 (grid_args)
_T41 = refdata.thesis_table4_1()
GRID_TR, GRID_ER = _T41["t_over_R"], _T41["E_ratio"]
(GRID_R,), (GRID_E_SU,), (GRID_NU,), (GRID_E_OVER_Y,) = (_T41[k] for k in ("R", "E_su", "nu",
                                                                            "E_over_Y"))
GRID_DELTA = (1, 10, 30, 60)
LOADS = (2, 10, 30, 60, 100)
GRID_FIGS = ("fig4_16", "fig4_17", "fig4_18")  # one per t/R of GRID_TR


def total_wall(r):
    """Solver wall time of a run: normal step + ramp, s."""
    return r.get("wall_s", float("nan")) + r.get("shear_wall_s", 0.0)


def grid_args(tr, er):
    return ["--R", "%g" % GRID_R, "--E-su", "%g" % GRID_E_SU, "--E-over-Y", "%g" % GRID_E_OVER_Y,
            "--nu", "%g" % GRID_NU,
            "--t-over-R", "%g" % tr, "--E-ratio", "%g" % er, "--contact", "stick"]


class Runner:
    def __init__(self, cli, out, mesh):
        # one cache per mesh: a finished run is only reused for the same mesh
        sub = "runs" if mesh is None else "runs-mesh%s" % mesh
        self.cli, self.dir, self.mesh = cli, os.path.join(out, sub), mesh
        os.makedirs(self.dir, exist_ok=True)

    def path(self, name):
        return os.path.join(self.dir, name)

    def done(self, name):
        return os.path.exists(os.path.join(self.path(name), "result.json"))

    def run(self, name, args):
        """One FE run; returns (name, ok, message).  Finished runs are kept."""
        if self.done(name):
            return name, True, "cached"
        final, tmp = self.path(name), self.path(name) + ".tmp"
        shutil.rmtree(tmp, ignore_errors=True)
        os.makedirs(tmp)
        cmd = [self.cli, "asperity", "--shear", "--model", "3d", "--json", "--out", tmp]
        if self.mesh is not None:
            cmd += ["--mesh", str(self.mesh)]
        env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"),
                   OPENBLAS_NUM_THREADS="1")
        r = subprocess.run(cmd + args, capture_output=True, text=True, env=env)
        failed = final + ".failed"
        if r.returncode != 0:
            shutil.rmtree(tmp, ignore_errors=True)
            with open(failed, "w") as f:
                f.write("%s\n%s\n" % (" ".join(cmd + args), r.stderr.strip()))
            return name, False, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "?"
        with open(os.path.join(tmp, "result.json"), "w") as f:
            f.write(r.stdout)
        if os.path.exists(failed):
            os.remove(failed)
        os.rename(tmp, final)
        return name, True, "ran"

    def result(self, name):
        if not self.done(name):
            return None
        with open(os.path.join(self.path(name), "result.json")) as f:
            j = json.load(f)
        return j[-1] if isinstance(j, list) else j

    def curve(self, name):
        fn = os.path.join(self.path(name), "shear.csv")
        if not self.done(name) or not os.path.exists(fn):
            return None
        return fn


def grid_name(tr, er, d):
    return "grid_t%g_E%g_d%g" % (tr, er, d)


def fig419_runs(er):
    """(t/R, Eco/Esu) of the curves of Fig. 4.19 (er = 2) or 4.20 (er = 4) at
    delta = omega_c_su: the homogeneous sphere (Eco/Esu = 1, middle t/R) and
    Eco/Esu = er at each t/R."""
    return [(GRID_TR[1], 1)] + [(tr, er) for tr in reversed(GRID_TR)]


def figure_jobs(fig):
    """{name: args} of the FE runs figure fig needs (runs shared between
    figures have one name, so each is computed once)."""
    jobs = {}
    if fig in ("fig4_8", "fig4_10"):
        for w in FIG48_OMEGAS if fig == "fig4_8" else WSP_OMEGAS:
            jobs["wsp_w%g" % w] = WSP + ["--delta", "%g" % w]
    elif fig in GRID_FIGS:
        tr = GRID_TR[GRID_FIGS.index(fig)]
        for er in GRID_ER:
            for d in GRID_DELTA:
                jobs[grid_name(tr, er, d)] = grid_args(tr, er) + ["--delta", "%g" % d]
    elif fig in ("fig4_19", "fig4_20"):
        for tr, er in fig419_runs(2 if fig == "fig4_19" else 4):
            jobs[grid_name(tr, er, 1)] = grid_args(tr, er) + ["--delta", "%g" % 1]
    elif fig == "fig4_21":
        for tr in GRID_TR:
            for er in GRID_ER:
                for x in LOADS:
                    jobs["load_t%g_E%g_P%g" % (tr, er, x)] = grid_args(tr, er) + ["--load", "%g" % x]
    return jobs


def jobs_for(figs):
    """(name, args) of every run the chosen figures need."""
    jobs = {}
    for fig in figs:
        jobs.update(figure_jobs(fig))
    return jobs


# the case lines of the figures' titles (the mesh level is added by main)
WSP_CASE = ("homogeneous sphere, R = 10.5 mm, E = 74 GPa, ν = 0.33, Y = 325 MPa; slip normal"
            " step, interface τ_{c} = Y/√3; FE 3D")
GRID_CASE = ("R = 10 mm, E_{su} = 200 GPa, E/Y = 1000 in both layers, ν = 0.32; stick normal"
             " step, interface τ_{c} = Y_{co}/√3; FE 3D")
MESH_NOTE = [""]  # ", mesh level L": the 3D mesh of every run
WSP_FIT = "Wu, Shi and Polycarpou (2012) fit μ_{s} = 0.3 coth(0.57 (ω/ω_{c})^{0.41})"
PLACEMENT = ("One 3D mesh: node placement alone moves a single run's μ_{s} by ±4 … 8 %"
             " (docs/design.md §4.5).")


def panel_plot(png, title, panels, xlabel, ylabel, notes, key="left top", setup=""):
    """panels: list of (subtitle, [(csv, xcol, ycol, label)], extra_plot_items);
    title: two lines (what, case); notes: lines under the plots."""
    n = len(panels)
    cols = 2 if n > 1 else 1
    rows = (n + cols - 1) // cols
    w, h = 620 * cols if n > 1 else 1000, 440 * rows + 80 + figure.LINE_PX * len(notes)
    note, bottom = figure.notes(notes, h)
    top = 1.0 - 80.0 / h
    s = ["set datafile separator ','", "set grid", note,
         "set multiplot layout %d,%d title \"%s\" margins 0.07,0.98,%g,%g spacing 0.07,%g"
         % (rows, cols, title, bottom, top, 95.0 / h),
         "set xlabel \"%s\"" % xlabel, "set ylabel \"%s\"" % ylabel,
         "set key %s Left reverse" % key, setup]
    for sub, lines, extra in panels:
        items = ["'%s' u %s:%s w l lw 2 t '%s'" % (c, x, y, lab) for c, x, y, lab in lines] + extra
        s.append("set title \"%s\"" % sub)
        s.append("plot " + ", ".join(items) if items else "plot 0 notitle")
        s.append("unset label")  # the notes belong to the first panel's screen only
    s.append("unset multiplot")
    figure.gnuplot(png, w, h, "\n".join(s) + "\n")


def wsp_plateau(r, w):
    """The plateau the WSP fit gives a run: mu_s(fit) at w = delta/omega_c
    times the run's P/Pc, as a gnuplot plot item."""
    return "%.6g w l dt 2 lw 2 lc rgb 'black' t 'WSP fit: μ_{s}(ω) P/P_{c}'" % (
        wsp_mu(w) * r["P_over_P_c"])


def fig48(rn, out, fig="fig4_8"):
    panels, rows, drops = [], [], []
    for w in FIG48_OMEGAS:
        name = "wsp_w%g" % w
        r, c = rn.result(name), rn.curve(name)
        lines = [(c, "2", "4", "FE")] if c else []
        extra, sub = [], "ω = %g ω_{c}: run failed" % w
        if r:
            plateau = wsp_mu(w) * r["P_over_P_c"]
            extra = [wsp_plateau(r, w),
                     "%g w l dt 3 lw 2 lc rgb 'gray50' t 'thesis Fig. 4.8 plateau (read off)'"
                     % FIG48_THESIS[w]]
            rows.append((w, r["Q_max_over_P_c"], plateau, FIG48_THESIS[w]))
            drops.append(r["P_at_slide_N"] / r["P_preload_N"] - 1)
            sub = "ω = %g ω_{c}: Q_{max}/P_{c} FE %.3g, WSP fit %.3g (%s), thesis ≈ %g" % (
                w, r["Q_max_over_P_c"], plateau, pct(r["Q_max_over_P_c"] / plateau - 1),
                FIG48_THESIS[w])
        panels.append((sub, lines, extra))
    devs = [q / fit - 1 for _, q, fit, _ in rows]
    panel_plot(os.path.join(out, "fig4_8.png"),
               "Fig. 4.8: tangential force versus tangential displacement up to sliding"
               " inception\\n%s%s" % (WSP_CASE, MESH_NOTE[0]), panels,
               "u_{x}/ω_{c}  (tangential displacement, normalised)",
               "Q/P_{c}  (tangential force, normalised)",
               ["FE Q_{max} vs the plateau of the %s times the preload P: %s."
                % (WSP_FIT, pct_range(devs)),
                "Why: P falls during the ramp (by up to %.0f %% at inception), while μ_{s} ="
                " Q_{max}/P at inception follows the fit (Fig. 4.10)." % (-100 * min(drops + [0])),
                "The thesis's plateaus (read off its plot, ±10 %) are higher at large ω: whether"
                " the references' finite-strain model owes its extra μ_{s} to",
                "junction growth, pile-up or its contact-area measure is open (docs/design.md"
                " §4.8).", PLACEMENT], key="right bottom")
    with open(os.path.join(out, "fig4_8.csv"), "w") as f:
        f.write("omega_over_omega_c,Qmax_over_Pc_FE,Qmax_over_Pc_WSP_fit,plateau_thesis_fig\n")
        for row in rows:
            f.write("%g,%.6g,%.6g,%g\n" % row)
    print("Fig. 4.8: plateau Qmax/Pc (FE, WSP fit mu_s P/Pc, thesis figure approx.)")
    for w, q, fit, th in rows:
        print("  omega/omega_c = %4g: FE %8.4f  fit %8.4f (%+.1f %%)  thesis ~%g"
              % (w, q, fit, 100 * (q / fit - 1), th))


def fig410(rn, out, fig="fig4_10"):
    fn = os.path.join(out, "fig4_10.csv")
    rows = []
    for w in WSP_OMEGAS:
        r = rn.result("wsp_w%g" % w)
        if r:
            rows.append((w, r["mu_s"], wsp_mu(w), total_wall(r)))
    with open(fn, "w") as f:
        f.write("omega_over_omega_c,mu_s_FE,mu_s_WSP,rel_err,wall_s\n")
        for w, m, fit, t in rows:
            f.write("%g,%.6g,%.6g,%.5f,%.3g\n" % (w, m, fit, m / fit - 1, t))
    devs = [m / fit - 1 for _, m, fit, _ in rows]
    panel_plot(os.path.join(out, "fig4_10.png"),
               "Fig. 4.10: static friction coefficient versus preload, displacement control"
               "\\n%s%s" % (WSP_CASE, MESH_NOTE[0]),
               [("μ_{s} = Q_{max}/P at sliding inception (whole contact at τ_{c}, Q flat)",
                 [], ["'%s' u 1:2 w lp pt 7 ps 1.2 lw 2 t 'FE (stiction)'" % fn,
                      "[0.4:80] 0.3/tanh(0.57*x**0.41) w l dt 2 lw 2 lc rgb 'black' t"
                      " 'Wu et al. (2012) fit'"])],
               "ω/ω_{c}  (normal interference, normalised; log scale)",
               "static friction coefficient μ_{s}",
               ["FE vs the %s: %s." % (WSP_FIT, pct_range(devs)),
                PLACEMENT, "Means over four node placements: −6.4 … +3.8 % of the fit"
                " (docs/design.md §4.8)."],
               key="right top", setup="set logscale x\nset xrange [0.4:80]")
    print("Fig. 4.10: mu_s, FE vs WSP fit")
    for w, m, fit, t in rows:
        print("  omega/omega_c = %4g: FE %.4f  fit %.4f  (%+.2f %%)  %.1f s"
              % (w, m, fit, 100 * (m / fit - 1), t))


def e1_vs_wsp(rn, tr, deltas):
    """Eco/Esu = 1 (the homogeneous sphere) at t/R tr against the WSP fit at
    each delta that ran: (Qmax/Pc over the fit's plateau with the preload,
    mu_s over the fit's) - 1."""
    rs = [(d, r) for d in deltas for r in [rn.result(grid_name(tr, 1, d))] if r]
    return ([r["Q_max_over_P_c"] / (wsp_mu(d) * r["P_over_P_c"]) - 1 for d, r in rs],
            [r["mu_s"] / wsp_mu(d) - 1 for d, r in rs])


def grid_notes(devs):
    plateau, mu = devs
    return ["Dashed: the plateau of the homogeneous sphere's %s, with the FE's preload P" % WSP_FIT,
            "(made for a slip normal step; E_{co}/E_{su} = 1 is that sphere). FE vs it: Q_{max}"
            " %s, μ_{s} = Q_{max}/P at inception %s (P falls during the ramp)."
            % (pct_range(plateau), pct_range(mu)),
            "No published fit gives the coated sphere's Q. " + PLACEMENT]


def fig_grid(rn, out, fig):
    """Fig. 4.16, 4.17 or 4.18: the grid at one t/R, a panel per delta."""
    tr = GRID_TR[GRID_FIGS.index(fig)]
    panels = []
    for d in GRID_DELTA:
        lines, mus = [], []
        for er in GRID_ER:
            c, r = rn.curve(grid_name(tr, er, d)), rn.result(grid_name(tr, er, d))
            if c:
                lines.append((c, "2", "4", "E_{co}/E_{su} = %g" % er))
            mus.append("%.3g" % r["mu_s"] if r else "failed")
        r1 = rn.result(grid_name(tr, 1, d))
        panels.append(("δ = %g ω_{c,su}: μ_{s} = %s (E_{co}/E_{su} = %s)"
                       % (d, " / ".join(mus), " / ".join("%g" % e for e in GRID_ER)), lines,
                       [wsp_plateau(r1, d)] if r1 else []))
    panel_plot(os.path.join(out, fig + ".png"),
               "Fig. %s: tangential force versus tangential displacement of a coated sphere,"
               " t/R = %g\\n%s%s" % (figure.number(fig), tr, GRID_CASE, MESH_NOTE[0]), panels,
               "u_{x}/ω_{c,su}  (tangential displacement, normalised)",
               "Q/P_{c,su}  (tangential force, normalised)",
               grid_notes(e1_vs_wsp(rn, tr, GRID_DELTA)), key="right bottom")
    fn = os.path.join(out, fig + ".csv")
    with open(fn, "w") as f:
        f.write("t_over_R,E_ratio,delta_over_omega_c_su,P_over_Pc_su,Qmax_over_Pc_su,mu_s,"
                "ux_at_slide_over_omega_c_su,KT_after_over_KT1,wall_s\n")
        print("Fig. %s: Qmax/Pc_su (mu_s) per Eco/Esu, delta/omega_c_su = %s; * = Q still"
              " rising past inception (KT/KT1 after it > 0.05): mu_s there depends on where"
              " inception is declared (docs/design.md §4.4)"
              % (figure.number(fig), ", ".join("%g" % d for d in GRID_DELTA)))
        for er in GRID_ER:
            line = []
            for d in GRID_DELTA:
                r = rn.result(grid_name(tr, er, d))
                if not r:
                    line.append("   (failed)      ")
                    continue
                kt = r.get("KT_over_KT1_after_slide")
                f.write("%g,%g,%g,%.6g,%.6g,%.6g,%.6g,%s,%.3g\n" % (
                    tr, er, d, r["P_over_P_c"], r["Q_max_over_P_c"], r["mu_s"],
                    r["ux_at_slide_over_omega_c"], "%.4g" % kt if kt is not None else "",
                    total_wall(r)))
                line.append("%8.3f (%.3f)%s" % (r["Q_max_over_P_c"], r["mu_s"],
                                                "*" if kt is not None and kt > 0.05 else " "))
            print("  t/R %-5g Eco/Esu %g: %s" % (tr, er, "  ".join(line)))
    grid_checks(rn, tr)


def fig419(rn, out, fig):
    """Fig. 4.19 (Eco/Esu = 2) or 4.20 (4): delta = omega_c_su, the three t/R
    with the homogeneous sphere."""
    er = 2 if fig == "fig4_19" else 4
    lines, mus = [], []
    for tr, e in fig419_runs(er):
        c, r = rn.curve(grid_name(tr, e, 1)), rn.result(grid_name(tr, e, 1))
        lab = ("E_{co}/E_{su} = 1 (homogeneous)" if e == 1 else
               "E_{co}/E_{su} = %g, t/R = %g" % (e, tr))
        if c:
            lines.append((c, "2", "4", lab))
        mus.append("%s %s" % ("homogeneous" if e == 1 else "t/R %g" % tr,
                              "%.3f" % r["mu_s"] if r else "failed"))
    r1 = rn.result(grid_name(GRID_TR[1], 1, 1))
    panel_plot(os.path.join(out, fig + ".png"),
               "Fig. %s: tangential force versus tangential displacement, δ = ω_{c,su},"
               " E_{co}/E_{su} = %g\\n%s%s" % (figure.number(fig), er, GRID_CASE, MESH_NOTE[0]),
               [("μ_{s}: %s" % ", ".join(mus), lines, [wsp_plateau(r1, 1)] if r1 else [])],
               "u_{x}/ω_{c,su}  (tangential displacement, normalised)",
               "Q/P_{c,su}  (tangential force, normalised)",
               grid_notes(e1_vs_wsp(rn, GRID_TR[1], (1,))), key="right bottom")
    print("Fig. %s: delta = omega_c_su, Eco/Esu = %g: mu_s %s" % (figure.number(fig), er, "; ".join(mus)))


def initial_slope(csv):
    """d(Q/Pc)/d(ux/omega_c) over the first ramp increment of a shear.csv."""
    with open(csv) as f:
        rows = [l.split(",") for l in f.read().split("\n")[1:] if l.strip()]
    for r in rows:
        if float(r[1]) > 0.0:
            return float(r[3]) / float(r[1])
    return math.nan


def grid_checks(rn, tr):
    """What the thesis reports for the grid, measured on our runs at t/R tr:
    the same initial tangent for every Eco/Esu, a higher Qmax for a stiffer
    coating, and mu_s ordered by Eco/Esu with a spread growing with t/R."""
    print("Grid checks (ratios to Eco/Esu = 1 at the same t/R and delta):")
    for d in GRID_DELTA:
        base = rn.result(grid_name(tr, 1, d))
        cb = rn.curve(grid_name(tr, 1, d))
        if not base or not cb:
            continue
        k1, parts = initial_slope(cb), []
        for er in GRID_ER[1:]:
            r, c = rn.result(grid_name(tr, er, d)), rn.curve(grid_name(tr, er, d))
            if not r or not c:
                parts.append("Eco/Esu %g failed" % er)
                continue
            parts.append("Eco/Esu %g: slope %.3f Qmax %.3f mu_s %.3f" % (
                er, initial_slope(c) / k1, r["Q_max_over_P_c"] / base["Q_max_over_P_c"],
                r["mu_s"] / base["mu_s"]))
        print("  t/R %-5g delta %2g: %s" % (tr, d, "; ".join(parts)))
    print("Initial slope against Cattaneo-Mindlin K = 8 G a / (2 - nu) (Johnson 1985 7.2),"
          " with G of the coating / of the substrate:")
    for d in GRID_DELTA:
        parts = []
        for er in GRID_ER:
            r, c = rn.result(grid_name(tr, er, d)), rn.curve(grid_name(tr, er, d))
            if not r or not c:
                continue
            Pc = r["P_N"] / r["P_over_P_c"]
            wc = r["delta_mm"] / r["delta_over_omega_c_su"]
            k = initial_slope(c) * Pc / wc  # N/mm
            G_su = GRID_E_SU / (2.0 * (1.0 + GRID_NU))
            km = 8.0 * r["a_mm"] / (2.0 - GRID_NU)
            parts.append("Eco/Esu %g: %.2f / %.2f (t/a %.2g)" % (
                er, k / (km * er * G_su), k / (km * G_su), tr * GRID_R / r["a_mm"]))
        if parts:
            print("  t/R %-5g delta %2g: %s" % (tr, d, "; ".join(parts)))


def fig421(rn, out, fig="fig4_21"):
    fn = os.path.join(out, "fig4_21.csv")
    panels, devs = [], []
    with open(fn, "w") as f:
        f.write("t_over_R,E_ratio,P_over_Pc_su_target,P_over_Pc_su,mu_s,mu_s_preload,wall_s\n")
        for tr in GRID_TR:
            items = []
            for er in GRID_ER:
                sub = os.path.join(out, "fig4_21_t%g_E%g.csv" % (tr, er))
                with open(sub, "w") as g:
                    g.write("P_over_Pc_su,mu_s,mu_s_WSP_fit_at_delta\n")
                    for x in LOADS:
                        r = rn.result("load_t%g_E%g_P%g" % (tr, er, x))
                        if r:
                            fit = wsp_mu(r["delta_over_omega_c_su"])
                            g.write("%.6g,%.6g,%.6g\n" % (r["P_over_P_c"], r["mu_s"], fit))
                            f.write("%g,%g,%g,%.6g,%.6g,%.6g,%.3g\n" % (
                                tr, er, x, r["P_over_P_c"], r["mu_s"], r["mu_s_preload"],
                                total_wall(r)))
                            if er == 1:
                                devs.append(r["mu_s"] / fit - 1)
                items.append("'%s' u 1:2 w lp pt 7 lw 2 t 'E_{co}/E_{su} = %g'" % (sub, er))
                if er == 1:
                    items.append("'%s' u 1:3 w l dt 2 lw 2 lc rgb 'black' t 'WSP fit at the"
                                 " δ of E_{co}/E_{su} = 1'" % sub)
            panels.append(("t/R = %g" % tr, [], items))
    panel_plot(os.path.join(out, "fig4_21.png"),
               "Fig. 4.21: static friction coefficient versus normal load, load control"
               "\\n%s%s" % (GRID_CASE, MESH_NOTE[0]), panels,
               "P/P_{c,su}  (normal load, normalised)", "static friction coefficient μ_{s}",
               ["Dashed: the homogeneous sphere's %s at the interference δ/ω_{c,su} of each"
                " E_{co}/E_{su} = 1 run:" % WSP_FIT,
                "FE vs it %s. No published fit gives the coated sphere's μ_{s}."
                % pct_range(devs), PLACEMENT],
               key="right top")
    print("Fig. 4.21: mu_s under load control: see fig4_21.csv; Eco/Esu = 1 vs the WSP fit at"
          " its delta: %s" % pct_range(devs))


FIGS = {"fig4_8": fig48, "fig4_10": fig410, "fig4_21": fig421}
FIGS.update({f: fig_grid for f in GRID_FIGS})
FIGS.update({f: fig419 for f in ("fig4_19", "fig4_20")})
ORDER = ("fig4_8", "fig4_10") + GRID_FIGS + ("fig4_19", "fig4_20", "fig4_21")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("STICTION_JOBS", "2")))
    ap.add_argument("--mesh", default=None, help="--mesh passed to every run")
    ap.add_argument("--only", default=",".join(ORDER))
    ap.add_argument("--summary", help="write what is printed to this file too")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.summary:
        figure.tee_stdout(a.summary)
    figs = set()
    for f in a.only.split(","):
        f = f.strip()
        if f not in FIGS:
            sys.exit("reproduce-shear: --only %s: not one of %s" % (f, ", ".join(ORDER)))
        figs.add(f)
    rn = Runner(a.cli, a.out, a.mesh)
    MESH_NOTE[0] = ", mesh level %s" % (a.mesh if a.mesh is not None else "default")
    jobs = jobs_for(figs)
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = [ex.submit(rn.run, n, args) for n, args in sorted(jobs.items())]
        for fu in concurrent.futures.as_completed(futs):
            name, ok, msg = fu.result()
            print("  run %-28s %s" % (name, msg if ok else "FAILED: " + msg), file=sys.stderr)
            if not ok:
                failed.append((name, msg))
    for f in ORDER:
        if f in figs:
            FIGS[f](rn, a.out, f)
    if failed:
        print("%d run(s) failed (reasons in %s/*.failed):" % (len(failed), rn.dir))
        for name, msg in failed:
            print("  %s: %s" % (name, msg))
        sys.exit(1)


if __name__ == "__main__":
    main()
