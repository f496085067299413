#!/usr/bin/env python3
"""The default single shear run against the stored converged references of
the held set (data/fe/references.csv, made by tools/references.py).

validate-references.py CLI OUT.csv OUT.md [--level 1]

For every held case with a stored reference at LEVEL (a node-placement
ensemble of 4 or more members one full refinement finer than the default
mesh): a fresh default run, `stiction asperity ARGS --shear --json` with no
numerical option, its mu_s and printed error estimate against the reference.  Check: the printed
error estimate covers the actual error (one standard error of the run and of
the reference in quadrature, times two: a 95 % band).  Targets: the single run
within 2 % of the reference; every held case has its reference.  Also the
default mesh's own placement mean against the finer one (how far the
mesh moves the ensemble), from the stored rows; and the WSP sphere's
references against the Wu-Shi-Polycarpou fit (5 %), a miss stated as a
finding with the independent evidence: up to omega_c the elastic sphere in
full slip over the half-space's grown contact, and at every interference the
growth-free value tau_c A0 / P0 of the axisymmetric normal step.
"""
import argparse
import json
import math
import subprocess
import sys
import time

from references import held_set, stored_refs
from vreport import Report
from wsp_case import ABOVE_1, elastic_mu, growth_free_mu, write_progress, wsp_mu

TARGET = 0.02
FIT_TOL = 0.05  # the band on mu_s against the WSP fit, as in validate-shear.py


def against_fit(rep, cli, refs, cases, level):
    """The WSP sphere's converged references against the WSP fit: within 5 %,
    or a finding with the evidence."""
    for c in cases:
        ref = refs.get((c[0], level))
        if c[1] != "wsp" or ref is None:
            continue
        w = float(c[2])
        fit, mu, se = wsp_mu(w), float(ref["mu_s"]), float(ref["mu_s_err"])
        l0 = refs.get((c[0], 0))
        d = mu / fit - 1
        gf = growth_free_mu(cli, w)
        ev = ["The reference is %.4f +- %.4f (%s placements, mesh level %d)%s." % (
            mu, se, ref["placements"], level,
            "; the default mesh's %s placements read %.4f (%+.1f %%)" % (
                l0["placements"], float(l0["mu_s"]), 100 * (float(l0["mu_s"]) / mu - 1))
            if l0 else "")]
        if gf is not None:
            ev.append("Without junction growth or load relaxation (tau_c A0 / P0, axisymmetric "
                      "normal step) mu_s would be %.4f: growth and relaxation add %+.1f %%, the "
                      "fit asks for %+.1f %%." % (gf, 100 * (mu / gf - 1), 100 * (fit / gf - 1)))
        el = elastic_mu(cli, w) if w <= 1.0 else None
        if el is not None:
            ev.append("Up to omega_c the sphere is elastic under the normal load and mu_s = "
                      "tau_c A / P at full slip: with the elastic half-space's junction growth "
                      "(%+.2f %%) that is %.4f; the reference is %+.2f %% from it, the fit "
                      "%+.2f %%." % (100 * el[1], el[0], 100 * (mu / el[0] - 1),
                                     100 * (fit / el[0] - 1)))
        elif w > 1.0:
            ev.append(ABOVE_1)
        rep.compare("%s: converged reference" % c[0], "WSP 2012: %.4f" % fit, "5 %",
                    "%.4f (%+.2f %%)" % (mu, 100 * d), abs(d) <= FIT_TOL, ("", " ".join(ev)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("report")
    ap.add_argument("--level", type=int, default=1)
    a = ap.parse_args()
    refs = stored_refs()
    cases = held_set()
    rep = Report("One shear run against the converged references",
                 "tools/validate-references.py (`stiction asperity --shear --json` runs)")
    rep.out("Held set: the Wu-Shi-Polycarpou sphere (slip normal step) at 8 interferences and "
            "the coated thesis family (stick normal step) at t/R 0.005 and 0.05, Eco/Esu 2 and "
            "4, delta/omega_c_su 1 and 30.  Reference: K evenly spaced node placements on 3D mesh "
            "level %d (the default is level 0; each level doubles the elements across the "
            "contact), their mean and its standard error "
            "(data/fe/references.csv, tools/references.py; the members are in "
            "data/fe/reference-members.csv).  'single' is a fresh default run (no numerical "
            "option) with its printed error estimate; 'L0 mean' the default mesh's own "
            "placement mean (its K in brackets); 'slope' the single run's d ln mu_s / d ln ux at "
            "inception (mu_s_ux_slope: how much its mu_s depends on where inception is "
            "declared)." % a.level)
    rep.out("")
    cols = ["case", "delta_over_omega_c", "t_over_R", "E_ratio", "mu_s_ref", "mu_s_ref_err",
            "placements", "mu_s_single", "mu_s_single_err", "single_error_pct", "covered",
            "mu_s_ux_slope", "wall_s", "mu_s_L0", "placements_L0", "L0_vs_ref_pct"]
    rows, why = [], {}
    rep.out("| case | reference | K | single run ± printed error | error | covered | slope | "
            "wall s | L0 mean (K) | L0 mean vs ref |")
    rep.out("|---|---|---|---|---|---|---|---|---|---|")
    for c in cases:
        ref = refs.get((c[0], a.level))
        if ref is None:
            continue
        t0 = time.time()
        p = subprocess.run([a.cli, "asperity"] + c[5] + ["--shear", "--json"],
                           capture_output=True, text=True)
        wall = time.time() - t0
        j = json.loads(p.stdout) if p.returncode == 0 else {}
        mu_r, se_r = float(ref["mu_s"]), float(ref["mu_s_err"])
        l0 = refs.get((c[0], 0))
        r = {"case": c[0], "delta_over_omega_c": c[2], "t_over_R": c[3], "E_ratio": c[4],
             "mu_s_ref": ref["mu_s"], "mu_s_ref_err": ref["mu_s_err"],
             "placements": ref["placements"], "wall_s": "%.1f" % wall,
             "mu_s_L0": l0["mu_s"] if l0 else "", "placements_L0": l0["placements"] if l0 else "",
             "L0_vs_ref_pct": "%+.2f" % (100 * (float(l0["mu_s"]) / mu_r - 1)) if l0 else ""}
        if j.get("converged"):
            mu, se = j["mu_s"], j["mu_s_err"]
            err = mu / mu_r - 1
            band = 2 * math.hypot(se, se_r)
            slope = j.get("mu_s_ux_slope")
            r.update(mu_s_single="%.5f" % mu, mu_s_single_err="%.5f" % se,
                     single_error_pct="%+.2f" % (100 * err),
                     covered=int(abs(mu - mu_r) <= band),
                     mu_s_ux_slope="%.3f" % slope if slope is not None else "")
        rows.append(r)
        write_progress(a.out, cols, rows)
        rep.out("| %s | %.4f ± %.4f | %s | %s ± %s | %s %% | %s | %s | %s | %s | %s %% |"
                % (c[0], mu_r, se_r, r["placements"], r.get("mu_s_single", "failed"),
                   r.get("mu_s_single_err", "-"), r.get("single_error_pct", "-"),
                   "yes" if r.get("covered") else "no", r.get("mu_s_ux_slope") or "-",
                   r["wall_s"],
                   "%s (%s)" % (r["mu_s_L0"], r["placements_L0"]) if l0 else "-",
                   r["L0_vs_ref_pct"] or "-"))
        why[c[0]] = j.get("reason") or (p.stderr.strip().splitlines() or ["failed"])[-1]
    write_progress(a.out, cols, rows, done=True)
    rep.out("")
    for r in rows:
        rep.check("%s: the single run converges" % r["case"], "solver outcome", "converged",
                  "yes" if "mu_s_single" in r else "no: %s" % why[r["case"]],
                  "mu_s_single" in r)
    ok = [r for r in rows if "mu_s_single" in r]
    if ok:
        worst = max(ok, key=lambda r: abs(float(r["single_error_pct"])))
        cov = sum(r["covered"] for r in ok)
        rep.check("single runs: printed error covers the actual error",
                  "converged references (data/fe/references.csv)",
                  "|error| <= 2 sigma (run and reference in quadrature), every case",
                  "%d of %d" % (cov, len(ok)), cov == len(ok))
        within = sum(abs(float(r["single_error_pct"])) <= 100 * TARGET for r in ok)
        rep.target("single run within 2 % of the converged reference", "every case",
                   "%d of %d; worst %s %s %%" % (within, len(ok), worst["case"],
                                                 worst["single_error_pct"]),
                   within == len(ok))
    rep.target("converged references stored", "%d held cases" % len(cases),
               "%d of %d" % (len(rows), len(cases)), len(rows) == len(cases))
    against_fit(rep, a.cli, refs, cases, a.level)
    return rep.write(a.report)


if __name__ == "__main__":
    sys.exit(main())
