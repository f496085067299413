#!/usr/bin/env python3
"""make reproduce, combined loading: thesis Figs. 4.8, 4.10, 4.16-4.21.

reproduce-shear.py CLI OUTDIR [--jobs N] [--mesh LEVEL] [--only fig4_8,fig4_10,...]

Every FE run is one `stiction asperity --shear` call whose JSON and Q-ux CSV
are kept in OUTDIR/runs[-meshL]/NAME/ (written to NAME.tmp and renamed when the run
has finished), so an interrupted reproduce resumes where it stopped and never
redoes a finished run.  A run that fails is recorded with its reason in
OUTDIR/runs[-meshL]/NAME.failed and left out of the figures (never plotted as a
number); the script then exits with status 1 after writing everything else.

Figures (gnuplot 'png' terminal) and the CSV behind each:
  fig4_8   homogeneous WSP sphere (E 74 GPa, nu 0.33, Y 325 MPa, R' 10.5 mm,
           slip normal step): Q/Pc versus ux/omega_c at omega/omega_c = 0.5, 3,
           12, 72, with the plateau of the Wu-Shi-Polycarpou fit (mu_s P/Pc).
  fig4_10  mu_s versus omega/omega_c (0.5 ... 72) against the WSP fit
           mu_s = 0.3 coth(0.57 (omega/omega_c)^0.41) (Wu et al. 2012; thesis
           eq. 4.1).
  fig4_16..18  coated grid of thesis Table 4.1 (R 10 mm, Esu 200 GPa,
           E/Y 1000, nu 0.32, stick normal step): Q/Pc_su versus ux/omega_c_su
           for delta/omega_c_su = 1, 10, 30, 60 and Eco/Esu = 1, 2, 4, one
           figure per t/R = 0.005, 0.025, 0.05.
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

import refdata
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
MESH_NOTE = [""]  # appended to every figure title: the 3D mesh level used


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


def jobs_for(figs):
    """(name, args) of every run the chosen figures need."""
    jobs = {}
    if {"fig4_8", "fig4_10"} & figs:
        for w in WSP_OMEGAS if "fig4_10" in figs else FIG48_OMEGAS:
            jobs["wsp_w%g" % w] = WSP + ["--delta", "%g" % w]
    if {"fig4_16", "fig4_17", "fig4_18", "fig4_19", "fig4_20"} & figs:
        for tr in GRID_TR:
            for er in GRID_ER:
                for d in GRID_DELTA:
                    jobs["grid_t%g_E%g_d%g" % (tr, er, d)] = grid_args(tr, er) + ["--delta", "%g" % d]
    if "fig4_21" in figs:
        for tr in GRID_TR:
            for er in GRID_ER:
                for x in LOADS:
                    jobs["load_t%g_E%g_P%g" % (tr, er, x)] = grid_args(tr, er) + ["--load", "%g" % x]
    return jobs


def gnuplot(script):
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def panel_plot(png, title, panels, xlabel, ylabel, key="left top"):
    """panels: list of (subtitle, [(csv, xcol, ycol, label)], extra_plot_items)."""
    n = len(panels)
    cols = 2 if n > 1 else 1
    rows = (n + cols - 1) // cols
    s = ["set terminal png noenhanced size %d,%d" % (560 * cols, 430 * rows),
         "set output '%s'" % png, "set datafile separator ','",
         "set multiplot layout %d,%d title '%s%s'" % (rows, cols, title, MESH_NOTE[0]),
         "set xlabel '%s'" % xlabel, "set ylabel '%s'" % ylabel, "set key %s" % key]
    for sub, lines, extra in panels:
        items = ["'%s' u %s:%s w l lw 2 t '%s'" % (c, x, y, lab) for c, x, y, lab in lines] + extra
        s.append("set title '%s'" % sub)
        s.append("plot " + ", ".join(items) if items else "plot 0 notitle")
    s.append("unset multiplot")
    gnuplot("\n".join(s) + "\n")


def fig48(rn, out):
    panels, rows = [], []
    for w in FIG48_OMEGAS:
        name = "wsp_w%g" % w
        r, c = rn.result(name), rn.curve(name)
        lines = [(c, "2", "4", "FE")] if c else []
        extra = []
        if r:
            plateau = wsp_mu(w) * r["P_over_P_c"]
            extra = ["%.6g w l dt 2 t 'WSP fit plateau mu_s(fit) P/Pc'" % plateau]
            rows.append((w, r["Q_max_over_P_c"], plateau, FIG48_THESIS[w]))
        panels.append(("omega = %g omega_c" % w, lines, extra))
    panel_plot(os.path.join(out, "fig4_8.png"),
               "Fig. 4.8: homogeneous sphere (WSP), Q/Pc versus ux/omega_c", panels,
               "ux/omega_c", "Q/Pc")
    with open(os.path.join(out, "fig4_8.csv"), "w") as f:
        f.write("omega_over_omega_c,Qmax_over_Pc_FE,Qmax_over_Pc_WSP_fit,plateau_thesis_fig\n")
        for row in rows:
            f.write("%g,%.6g,%.6g,%g\n" % row)
    print("Fig. 4.8: plateau Qmax/Pc (FE, WSP fit mu_s P/Pc, thesis figure approx.)")
    for w, q, fit, th in rows:
        print("  omega/omega_c = %4g: FE %8.4f  fit %8.4f (%+.1f %%)  thesis ~%g"
              % (w, q, fit, 100 * (q / fit - 1), th))


def fig410(rn, out):
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
    panel_plot(os.path.join(out, "fig4_10.png"),
               "Fig. 4.10: static friction coefficient, homogeneous sphere",
               [("displacement control, shear criterion",
                 [], ["'%s' u 1:2 w lp pt 7 t 'FE (stiction)'" % fn,
                      "[0.3:75] 0.3/tanh(0.57*x**0.41) w l t 'Wu et al. (2012) fit'"])],
               "omega/omega_c", "mu_s", key="right top")
    print("Fig. 4.10: mu_s, FE vs WSP fit")
    for w, m, fit, t in rows:
        print("  omega/omega_c = %4g: FE %.4f  fit %.4f  (%+.2f %%)  %.1f s"
              % (w, m, fit, 100 * (m / fit - 1), t))


def fig416(rn, out):
    for k, tr in enumerate(GRID_TR):
        panels = []
        for d in GRID_DELTA:
            lines = []
            for er in GRID_ER:
                c = rn.curve("grid_t%g_E%g_d%g" % (tr, er, d))
                if c:
                    lines.append((c, "2", "4", "Eco/Esu = %g" % er))
            panels.append(("delta = %g omega_c_su" % d, lines, []))
        panel_plot(os.path.join(out, "fig4_%d.png" % (16 + k)),
                   "Fig. 4.%d: Q/Pc_su versus ux/omega_c_su, t/R = %g" % (16 + k, tr), panels,
                   "ux/omega_c_su", "Q/Pc_su")
    for fig, er in ((19, 2), (20, 4)):
        lines = []
        c = rn.curve("grid_t%g_E1_d1" % GRID_TR[1])
        if c:
            lines.append((c, "2", "4", "Eco/Esu = 1 (t/R = %g)" % GRID_TR[1]))
        for tr in reversed(GRID_TR):
            c = rn.curve("grid_t%g_E%g_d1" % (tr, er))
            if c:
                lines.append((c, "2", "4", "Eco/Esu = %g, t/R = %g" % (er, tr)))
        panel_plot(os.path.join(out, "fig4_%d.png" % fig),
                   "Fig. 4.%d: delta = omega_c_su, Eco/Esu = %g" % (fig, er),
                   [("", lines, [])], "ux/omega_c_su", "Q/Pc_su")
    fn = os.path.join(out, "fig4_16_20.csv")
    with open(fn, "w") as f:
        f.write("t_over_R,E_ratio,delta_over_omega_c_su,P_over_Pc_su,Qmax_over_Pc_su,mu_s,"
                "ux_at_slide_over_omega_c_su,KT_after_over_KT1,wall_s\n")
        print("Figs. 4.16-4.20: Qmax/Pc_su (mu_s) per t/R, Eco/Esu, delta/omega_c_su; "
              "* = Q still rising past inception (KT/KT1 after it > 0.05): mu_s there "
              "depends on where inception is declared (docs/design.md §4.4)")
        for tr in GRID_TR:
            for er in GRID_ER:
                line = []
                for d in GRID_DELTA:
                    r = rn.result("grid_t%g_E%g_d%g" % (tr, er, d))
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
    grid_checks(rn)


def initial_slope(csv):
    """d(Q/Pc)/d(ux/omega_c) over the first ramp increment of a shear.csv."""
    with open(csv) as f:
        rows = [l.split(",") for l in f.read().split("\n")[1:] if l.strip()]
    for r in rows:
        if float(r[1]) > 0.0:
            return float(r[3]) / float(r[1])
    return math.nan


def grid_checks(rn):
    """What the thesis reports for the grid, measured on our runs: the same
    initial tangent for every Eco/Esu, a higher Qmax for a stiffer coating,
    and mu_s ordered by Eco/Esu with a spread growing with t/R."""
    print("Grid checks (ratios to Eco/Esu = 1 at the same t/R and delta):")
    for tr in GRID_TR:
        for d in GRID_DELTA:
            base = rn.result("grid_t%g_E1_d%g" % (tr, d))
            cb = rn.curve("grid_t%g_E1_d%g" % (tr, d))
            if not base or not cb:
                continue
            k1, parts = initial_slope(cb), []
            for er in GRID_ER[1:]:
                r, c = rn.result("grid_t%g_E%g_d%g" % (tr, er, d)), \
                    rn.curve("grid_t%g_E%g_d%g" % (tr, er, d))
                if not r or not c:
                    parts.append("Eco/Esu %g failed" % er)
                    continue
                parts.append("Eco/Esu %g: slope %.3f Qmax %.3f mu_s %.3f" % (
                    er, initial_slope(c) / k1, r["Q_max_over_P_c"] / base["Q_max_over_P_c"],
                    r["mu_s"] / base["mu_s"]))
            print("  t/R %-5g delta %2g: %s" % (tr, d, "; ".join(parts)))
    print("Initial slope against Cattaneo-Mindlin K = 8 G a / (2 - nu) (Johnson 1985 7.2),"
          " with G of the coating / of the substrate:")
    for tr in GRID_TR:
        for d in GRID_DELTA:
            parts = []
            for er in GRID_ER:
                r, c = rn.result("grid_t%g_E%g_d%g" % (tr, er, d)), \
                    rn.curve("grid_t%g_E%g_d%g" % (tr, er, d))
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


def fig421(rn, out):
    fn = os.path.join(out, "fig4_21.csv")
    panels = []
    with open(fn, "w") as f:
        f.write("t_over_R,E_ratio,P_over_Pc_su_target,P_over_Pc_su,mu_s,mu_s_preload,wall_s\n")
        for tr in GRID_TR:
            items = []
            for er in GRID_ER:
                sub = os.path.join(out, "fig4_21_t%g_E%g.csv" % (tr, er))
                with open(sub, "w") as g:
                    g.write("P_over_Pc_su,mu_s\n")
                    for x in LOADS:
                        r = rn.result("load_t%g_E%g_P%g" % (tr, er, x))
                        if r:
                            g.write("%.6g,%.6g\n" % (r["P_over_P_c"], r["mu_s"]))
                            f.write("%g,%g,%g,%.6g,%.6g,%.6g,%.3g\n" % (
                                tr, er, x, r["P_over_P_c"], r["mu_s"], r["mu_s_preload"],
                                total_wall(r)))
                items.append("'%s' u 1:2 every ::0 w lp pt 7 t 'Eco/Esu = %g'" % (sub, er))
            panels.append(("t/R = %g" % tr, [], items))
    panel_plot(os.path.join(out, "fig4_21.png"),
               "Fig. 4.21: mu_s versus P/Pc_su, load control", panels, "P/Pc_su", "mu_s",
               key="right top")
    print("Fig. 4.21: mu_s under load control: see fig4_21.csv")


FIGS = {"fig4_8": fig48, "fig4_10": fig410, "fig4_16": fig416, "fig4_21": fig421}
ALIASES = {"fig4_17": "fig4_16", "fig4_18": "fig4_16", "fig4_19": "fig4_16",
           "fig4_20": "fig4_16"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("STICTION_JOBS", "2")))
    ap.add_argument("--mesh", default=None, help="--mesh passed to every run")
    ap.add_argument("--only", default="fig4_8,fig4_10,fig4_16,fig4_21")
    a = ap.parse_args()
    figs = set()
    for f in a.only.split(","):
        f = f.strip()
        if f not in FIGS and f not in ALIASES:
            sys.exit("reproduce-shear: --only %s: not one of %s" % (f, ", ".join(sorted(FIGS))))
        figs.add(ALIASES.get(f, f))
    os.makedirs(a.out, exist_ok=True)
    rn = Runner(a.cli, a.out, a.mesh)
    MESH_NOTE[0] = " (3D mesh %s)" % (a.mesh if a.mesh is not None else "default")
    jobs = jobs_for(figs)
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = [ex.submit(rn.run, n, args) for n, args in sorted(jobs.items())]
        for fu in concurrent.futures.as_completed(futs):
            name, ok, msg = fu.result()
            print("  run %-28s %s" % (name, msg if ok else "FAILED: " + msg), file=sys.stderr)
            if not ok:
                failed.append((name, msg))
    for f in ("fig4_8", "fig4_10", "fig4_16", "fig4_21"):
        if f in figs:
            FIGS[f](rn, a.out)
    if failed:
        print("%d run(s) failed (reasons in %s/*.failed):" % (len(failed), rn.dir))
        for name, msg in failed:
            print("  %s: %s" % (name, msg))
        sys.exit(1)


if __name__ == "__main__":
    main()
