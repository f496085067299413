"""The homogeneous Wu-Shi-Polycarpou sphere of the thesis's combined-loading
check, shared by validate-shear.py, bench-shear.py and
reproduce-shear.py: E = 74 GPa, nu = 0.33, Y = 325 MPa, R' = 10.5 mm, slip
normal step (thesis section 4.1.3), as `stiction asperity` arguments, and the
WSP fit (the same formula as stc_wsp_mu in asperity/formulas.c); and the
atomic CSV writers of the validate scripts."""
import csv
import math
import os

# the sphere alone (radius, modulus, Poisson's ratio), and the whole case
WSP_SPHERE = ["--R", "10.5", "--E-su", "74000", "--nu", "0.33"]
WSP = WSP_SPHERE + ["--t-over-R", "0", "--Y-su", "325", "--contact", "slip"]


def wsp_mu(w):
    """Wu, Shi & Polycarpou (2012) fit, thesis eq. 4.1: mu_s at omega/omega_c = w."""
    return 0.3 / math.tanh(0.57 * w ** 0.41)


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

