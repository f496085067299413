"""The homogeneous Wu-Shi-Polycarpou sphere of the thesis's combined-loading
check, shared by validate-shear.py, bench-shear.py and
reproduce-shear.py: E = 74 GPa, nu = 0.33, Y = 325 MPa, R' = 10.5 mm, slip
normal step (thesis section 4.1.3), as `stiction asperity` arguments, the
WSP fit (the same formula as stc_wsp_mu in asperity/formulas.c) and the
independent evidence it is held to (the elastic half-space, the growth-free
value); and the atomic CSV writers of the validate scripts."""
import csv
import json
import math
import os
import subprocess

# the sphere alone (radius, modulus, Poisson's ratio), and the whole case
WSP_SPHERE = ["--R", "10.5", "--E-su", "74000", "--nu", "0.33"]
WSP = WSP_SPHERE + ["--t-over-R", "0", "--Y-su", "325", "--contact", "slip"]


def wsp_mu(w):
    """Wu, Shi & Polycarpou (2012) fit, thesis eq. 4.1: mu_s at omega/omega_c = w."""
    return 0.3 / math.tanh(0.57 * w ** 0.41)


def elastic_mu(cli, omega):
    """(mu_s, area growth) of the elastic WSP sphere at omega: full slip at
    tau_c = Y/sqrt(3) over the grown contact of the elastic half-space
    (`stiction halfspace`); None when the run fails."""
    p = subprocess.run([cli, "halfspace", "--json", "--delta", "%g" % omega, "--cells", "256"]
                       + WSP_SPHERE + ["--Y-su", "325"], capture_output=True, text=True)
    if p.returncode != 0:
        return None
    j = json.loads(p.stdout)
    return j["mu_s"], j["area_growth"]


def growth_free_mu(cli, omega):
    """tau_c A0 / P0 of the WSP sphere at omega from the axisymmetric normal step
    (default mesh; the smoothed load and area where the run gives them): what
    full slip over the preload's contact at the preload would give, without
    junction growth or load relaxation.  None when the run fails."""
    p = subprocess.run([cli, "asperity", "--delta", "%g" % omega, "--json"] + WSP,
                       capture_output=True, text=True)
    if p.returncode != 0:
        return None
    j = json.loads(p.stdout)
    A = j.get("A_smooth_mm2") or j["A_mm2"]
    P = j.get("P_smooth_N") or j["P_N"]
    return 325.0 / math.sqrt(3.0) * A / P


# What decides the comparisons with the fit above 1 omega_c, measured once
# (docs/design.md sections 4.2, 4.5): the readings' means and one full refinement
ABOVE_1 = ("Above 1 omega_c no closed form bounds mu_s. At 3 omega_c the junction readings' "
           "period means over eight placements are 0.3931 (axis lines, the default) and 0.4104 "
           "(node rows, --foot-rows 0.6), -6.5 and -2.4 % from the fit; one full refinement "
           "finer the four-placement means are 0.4008 (axis lines, -4.7 %) and 0.4177 (rows, "
           "-0.7 %). The readings' gap (4 %) does not close with the mesh: where the FE and "
           "the fit differ by more than it, neither is shown off.")


def write_csv(path, cols, rows):
    """rows (dicts) under the header cols into path, via path.tmp and a rename,
    so a reader never sees half a table."""
    with open(path + ".tmp", "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=cols)
        wr.writeheader()
        wr.writerows(rows)
    os.replace(path + ".tmp", path)


def write_progress(path, cols, rows, done=False):
    """The rows so far into path.part while a validate script runs; with
    done, the whole table into path and the progress copy removed."""
    if not done:
        write_csv(path + ".part", cols, rows)
        return
    write_csv(path, cols, rows)
    if os.path.exists(path + ".part"):
        os.remove(path + ".part")

