/* Friction tables in HDF5 (include/stiction/table.h; the format is
 * docs/table-format.md).  Written atomically: a temporary file beside the
 * target, flushed to disk, renamed over it. */
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <hdf5.h>

#include "stc_check.h"
#include "stc_h5.h"
#include "table_impl.h"

#ifndef STC_VERSION
#define STC_VERSION "unknown"
#endif

static const char *const axis_name[3] = {"delta_over_omega_c", "t_over_R", "E_ratio"};

/* The per-point datasets: name, offset of the double (or int) in tbl_point. */
typedef struct {
    const char *name;
    size_t off;
    int is_int;
    const char *doc; /* the dataset's "description" attribute */
    int since;       /* the format version that added it (older files: an integer
                        0, a number NaN: not known) */
} field;

#define D(n, m, doc) {n, offsetof(tbl_point, m), 0, doc, 1}
#define I(n, m, doc) {n, offsetof(tbl_point, m), 1, doc, 1}
static const field fields[] = {
    I("state", state, "0 pending, 1 done, 2 failed"),
    D("P_over_P_c", P_Pc, "preload P / Pc_su (end of the normal step, mean of the members)"),
    D("A_over_A_c", A_Ac, "preload contact area A / Ac_su"),
    D("P_slide_over_P_c", P_slide_Pc, "normal load at sliding inception / Pc_su"),
    D("Q_max_over_P_c", Q_max_Pc, "tangential load at sliding inception / Pc_su"),
    D("mu_s", mu_s, "static friction coefficient Q_max / P at inception (mean of the members)"),
    D("mu_s_err", mu_s_err, "error estimate of mu_s, one standard error (absolute)"),
    D("mu_s_preload", mu_s_preload, "Q_max / preload"),
    D("mu_s_min", mu_s_min, "smallest member mu_s"),
    D("mu_s_max", mu_s_max, "largest member mu_s"),
    D("ux_slide_over_omega_c", ux_slide_wc, "flat displacement at inception / omega_c_su"),
    {"mu_s_ux_slope", offsetof(tbl_point, mu_s_ux_slope), 0, "d ln mu_s / d ln ux at "
     "inception, mean of the members: how much mu_s depends on where inception is declared "
     "(NaN: not known)", 7},
    I("members", members, "node-placement members that reached inception"),
    I("newton_iterations", newton_iterations, "Newton iterations, both steps, all members"),
    I("factorizations", factorizations, "Cholesky factorizations, both steps, all members"),
    D("wall_s", wall_s, "wall time of the point, s"),
    D("cpu_s", cpu_s, "CPU time of the point, s"),
    {"copied", offsetof(tbl_point, copied), 1, "1: the answer of the point at the first t/R "
     "with the same delta and E_ratio (one material: E_ratio 1, the same E/Y and nu in both "
     "layers), copied; 0: computed as itself", 4},
};
#undef D
#undef I
enum { NFIELD = sizeof fields / sizeof *fields };

/* ---- write -------------------------------------------------------------------- */

static int write_family(hid_t g, const tbl_table *t)
{
    const tbl_family *f = &t->fam;
    const tbl_numerics *n = &t->num;
    return stc_h5_put_d(g, "E_over_Y_su", f->E_over_Y_su) |
           stc_h5_put_d(g, "E_over_Y_co", f->E_over_Y_co) | stc_h5_put_d(g, "nu_su", f->nu_su) |
           stc_h5_put_d(g, "nu_co", f->nu_co) |
           stc_h5_put_s(g, "contact", f->contact == ASP_CONTACT_STICK ? "stick" : "slip") |
           stc_h5_put_d(g, "tau_c_over_Y_co", f->tau_c_over_Y_co) |
           stc_h5_put_s(g, "criterion", f->criterion == ASP_SHEAR_CRIT_SHEAR ? "shear"
                                                                             : "stiffness") |
           stc_h5_put_d(g, "alpha", f->alpha) | stc_h5_put_i(g, "mesh_level", n->mesh_level) |
           stc_h5_put_i(g, "placements", n->placements) |
           stc_h5_put_i(g, "placements_max", n->placements_max) |
           stc_h5_put_d(g, "refine_err", n->refine_err) |
           stc_h5_put_d(g, "elements_per_contact", n->elements_per_contact) |
           stc_h5_put_d(g, "err_floor", n->err_floor) |
           stc_h5_put_d(g, "err_single", n->err_single) |
           stc_h5_put_d(g, "foot_rows", n->foot_rows) |
           stc_h5_put_i(g, "normal_level", n->normal_level);
}

static int write_root(hid_t f, const tbl_table *t)
{
    int done, failed, pending;
    tbl_count(t, &done, &failed, &pending);
    char when[32];
    time_t now = time(NULL);
    struct tm tm;
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&now, &tm));
    asp_blas_kernels k;
    asp_blas_kernels_get(&k);
    return stc_h5_put_s(f, "format", TBL_FORMAT_NAME) |
           stc_h5_put_i(f, "format_version", TBL_FORMAT_VERSION) |
           stc_h5_put_s(f, "stiction_version", STC_VERSION) | stc_h5_put_s(f, "created", when) |
           stc_h5_put_s(f, "blas", k.summary) |
           stc_h5_put_s(f, "command", t->command) | stc_h5_put_s(f, "history", t->history) |
           stc_h5_put_d(f, "build_wall_s", t->build_wall_s) |
           stc_h5_put_s(f, "units", "responses normalised by omega_c, P_c, A_c of the "
                                    "substrate (Kogut & Etsion 2002)") |
           stc_h5_put_s(f, "layout", "points/* are [n_E_ratio][n_t_over_R][n_delta]; "
                                     "normal/* are [n_E_ratio][n_t_over_R] (per curve) or "
                                     "[n_E_ratio][n_t_over_R][n_delta] on normal/axes") |
           stc_h5_put_d(f, "R_mm", TBL_REF_R_MM) | stc_h5_put_d(f, "E_su_MPa", TBL_REF_E_SU_MPA) |
           stc_h5_put_i(f, "points_done", done) | stc_h5_put_i(f, "points_failed", failed) |
           stc_h5_put_i(f, "points_pending", pending) | write_family(f, t);
}

static int write_array(hid_t g, const char *name, int rank, const hsize_t *dims, hid_t ftype,
                       hid_t mtype, const void *v, const char *doc)
{
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t d = H5Dcreate2(g, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int e = d < 0 || H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0;
    if (!e && doc) e = stc_h5_put_s(d, "description", doc) != 0;
    if (d >= 0) H5Dclose(d);
    H5Sclose(sp);
    return e ? -1 : 0;
}

static int write_strings(hid_t g, const char *name, int rank, const hsize_t *dims,
                         const char *v, const char *doc);

static int write_points(hid_t f, const tbl_table *t)
{
    int np = tbl_points(t), e = 0;
    hsize_t dims[3] = {(hsize_t)t->n[2], (hsize_t)t->n[1], (hsize_t)t->n[0]};
    hid_t g = H5Gcreate2(f, "points", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return -1;
    double *dv = malloc((size_t)np * sizeof *dv);
    int *iv = malloc((size_t)np * sizeof *iv);
    char *rs = malloc((size_t)np * TBL_REASON_MAX);
    e = !dv || !iv || !rs;
    for (int k = 0; !e && k < NFIELD; k++) {
        for (int i = 0; i < np; i++) {
            const char *p = (const char *)&t->pt[i] + fields[k].off;
            /* numbers of a point that is not done are not an answer */
            int keep = t->pt[i].state == TBL_DONE || fields[k].is_int ||
                       !strcmp(fields[k].name, "wall_s") || !strcmp(fields[k].name, "cpu_s");
            if (fields[k].is_int) iv[i] = *(const int *)p;
            else dv[i] = keep ? *(const double *)p : NAN;
        }
        e = fields[k].is_int
                ? write_array(g, fields[k].name, 3, dims, H5T_STD_I32LE, H5T_NATIVE_INT, iv,
                              fields[k].doc)
                : write_array(g, fields[k].name, 3, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dv,
                              fields[k].doc);
    }
    if (!e) {
        for (int i = 0; i < np; i++) {
            memset(rs + (size_t)i * TBL_REASON_MAX, 0, TBL_REASON_MAX);
            snprintf(rs + (size_t)i * TBL_REASON_MAX, TBL_REASON_MAX, "%s", t->pt[i].reason);
        }
        e = write_strings(g, "reason", 3, dims, rs, "why a point failed, or the criterion's "
                          "reason at inception");
    }
    free(dv);
    free(iv);
    free(rs);
    H5Gclose(g);
    return e ? -1 : 0;
}

/* /members: each done point's placement members (tbl_members), per point
 * [m_E][m_t][m_w] and per member [m_E][m_t][m_w][ASP_PLACEMENTS_MAX]; the
 * places past a point's count hold NaN (0 for integers). */
typedef struct {
    const char *name;
    size_t off;  /* in tbl_members (per point) or tbl_member (per member) */
    int is_int, per_member;
    const char *doc;
    int since;   /* the format version that added it (older files: as in fields) */
} mfield;

#define MP(n, m, i, doc) {n, offsetof(tbl_members, m), i, 0, doc, 6}
#define MM(n, m, i, doc) {n, offsetof(tbl_member, m), i, 1, doc, 6}
static const mfield mfields[] = {
    MP("count", k, 1, "members stored: the point's, or 0 (not done, a copy)"),
    MP("edge_refine", edge_refine, 1, "the members' edge band levels (0: none)"),
    MP("period", period, 0, "shift of elements per contact that moves the surface nodes at "
       "the contact edge by one spacing"),
    MP("delta_mm", delta, 0, "the members' interference, mm (reference sphere)"),
    MP("delta_mesh_mm", delta_mesh, 0, "the interference their meshes are sized for, mm"),
    MP("edge_a0_mm", edge_a0, 0, "the edge band's contact radius, mm (0: none)"),
    MM("elements_per_contact", elements_per_contact, 0, "the member's mesh"),
    MM("P_N", P, 0, "preload, N (reference sphere: R 10 mm, Esu 200 GPa)"),
    MM("A_mm2", A, 0, "preload contact area, mm^2"),
    MM("P_slide_N", P_slide, 0, "normal load at inception, N"),
    MM("Q_max_N", Q_max, 0, "tangential load at inception, N"),
    MM("ux_slide_mm", ux_slide, 0, "flat displacement at inception, mm"),
    MM("mu_s", mu_s, 0, "the member's mu_s"),
    MM("mu_s_preload", mu_s_preload, 0, "Q_max / preload"),
    MM("mu_s_err", mu_s_err, 0, "the error its run printed (absolute)"),
    MM("cpu_s", cpu_s, 0, "CPU time of the member, s"),
    MM("newton_iterations", newton_iterations, 1, "Newton iterations, both steps"),
    MM("factorizations", factorizations, 1, "Cholesky factorizations, both steps"),
    {"mu_s_ux_slope", offsetof(tbl_member, mu_s_ux_slope), 0, 1, "d ln(Q/P) / d ln ux at "
     "inception (asp_shear_result.mu_s_ux_slope)", 7},
};
#undef MP
#undef MM
enum { NMFIELD = sizeof mfields / sizeof *mfields };

/* The place of field k of point i's member j (j ignored per point). */
static void *mfield_at(tbl_point *p, int k, int j)
{
    return mfields[k].per_member ? (char *)&p->ens.m[j] + mfields[k].off
                                 : (char *)&p->ens + mfields[k].off;
}

static int write_members(hid_t f, const tbl_table *t)
{
    int np = tbl_points(t), nm = ASP_PLACEMENTS_MAX, e = 0;
    hsize_t dims[4] = {(hsize_t)t->n[2], (hsize_t)t->n[1], (hsize_t)t->n[0], (hsize_t)nm};
    hid_t g = H5Gcreate2(f, "members", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return -1;
    double *dv = malloc((size_t)np * nm * sizeof *dv);
    int *iv = malloc((size_t)np * nm * sizeof *iv);
    e = !dv || !iv;
    for (int k = 0; !e && k < NMFIELD; k++) {
        int per = mfields[k].per_member ? nm : 1;
        for (int i = 0; i < np; i++)
            for (int j = 0; j < per; j++) {
                const void *v = mfield_at(&t->pt[i], k, j);
                int here = !mfields[k].per_member || j < t->pt[i].ens.k;
                size_t at = (size_t)i * per + j;
                if (mfields[k].is_int) iv[at] = here ? *(const int *)v : 0;
                else dv[at] = here && t->pt[i].ens.k > 0 ? *(const double *)v : NAN;
            }
        int rank = mfields[k].per_member ? 4 : 3;
        e = mfields[k].is_int
                ? write_array(g, mfields[k].name, rank, dims, H5T_STD_I32LE, H5T_NATIVE_INT, iv,
                              mfields[k].doc)
                : write_array(g, mfields[k].name, rank, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                              dv, mfields[k].doc);
    }
    free(dv);
    free(iv);
    H5Gclose(g);
    return e ? -1 : 0;
}

static int write_axes(hid_t f, const tbl_table *t)
{
    hid_t g = H5Gcreate2(f, "axes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return -1;
    static const char *const doc[3] = {"interference delta / omega_c of the substrate",
                                       "coating thickness / substrate radius",
                                       "coating / substrate Young's modulus"};
    int e = 0;
    for (int k = 0; k < 3 && !e; k++) {
        hsize_t n = (hsize_t)t->n[k];
        e = write_array(g, axis_name[k], 1, &n, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, t->ax[k],
                        doc[k]);
    }
    H5Gclose(g);
    return e;
}

static int write_fit(hid_t f, const tbl_table *t)
{
    if (!t->gp) return 0;
    const tbl_fit_info *fi = &t->fit;
    hid_t g = H5Gcreate2(f, "fit", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return -1;
    int e = stc_h5_put_s(g, "model", "Gaussian process on ln mu_s - ln mu_WSP(w): a term in "
                                     "ln w plus ln E_ratio times a term in (ln w, x2 = ln t/R - "
                                     "ln w / 2, ln E_ratio) whose length scales are times "
                                     "exp(gamma (x2 - middle of its range)); refitted when "
                                     "read unless data_hash matches the points") |
            stc_h5_put_u(g, "data_hash", (unsigned long)t->fit_hash) |
            (t->fit_npar > 0 ? stc_h5_put_dv(g, "hyperparameters", t->fit_npar, t->fit_par)
                             : 0) |
            stc_h5_put_i(g, "n", fi->n) | stc_h5_put_d(g, "ell_ln_w", fi->ell[0]) |
            stc_h5_put_d(g, "ell_ln_t_over_a", fi->ell[1]) |
            stc_h5_put_d(g, "ell_ln_E_ratio", fi->ell[2]) |
            stc_h5_put_d(g, "gamma", fi->gamma) |
            stc_h5_put_d(g, "ell_base_ln_w", fi->ell_base) |
            stc_h5_put_d(g, "noise_scale", fi->noise_scale) |
            stc_h5_put_d(g, "loo_rms_rel", fi->loo_rms) |
            stc_h5_put_d(g, "loo_max_rel", fi->loo_max) |
            stc_h5_put_d(g, "loo_cover2", fi->loo_cover2);
    H5Gclose(g);
    return e;
}

/* The per-curve datasets of the normal grid: name, offset in tbl_curve. */
static const field curve_fields[] = {
    {"state", offsetof(tbl_curve, state), 1, "0 pending, 1 done, 2 failed", 2},
    {"increments", offsetof(tbl_curve, increments), 1, "load increments of the curve", 2},
    {"newton_iterations", offsetof(tbl_curve, newton_iterations), 1, "Newton iterations", 2},
    {"wall_s", offsetof(tbl_curve, wall_s), 0, "wall time of the curve, s", 2},
    {"cpu_s", offsetof(tbl_curve, cpu_s), 0, "CPU time of the curve, s", 2},
    {"copied", offsetof(tbl_curve, copied), 1, "1: the run of the curve at the first t/R of its "
     "E_ratio (one material), copied; 0: computed as itself", 5},
};
enum { NCURVE_FIELD = sizeof curve_fields / sizeof *curve_fields };

static int write_strings(hid_t g, const char *name, int rank, const hsize_t *dims,
                         const char *v, const char *doc)
{
    hid_t st = H5Tcopy(H5T_C_S1);
    H5Tset_size(st, TBL_REASON_MAX);
    H5Tset_strpad(st, H5T_STR_NULLTERM);
    int e = write_array(g, name, rank, dims, st, st, v, doc);
    H5Tclose(st);
    return e;
}

static int write_normal(hid_t f, const tbl_table *t)
{
    const tbl_normal *g = &t->nrm;
    if (g->level < 0) return 0;
    int nc = tbl_curves(t), e = 0;
    hsize_t dc[2] = {(hsize_t)g->n[2], (hsize_t)g->n[1]};
    hsize_t dv[3] = {(hsize_t)g->n[2], (hsize_t)g->n[1], (hsize_t)g->n[0]};
    hid_t gr = H5Gcreate2(f, "normal", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (gr < 0) return -1;
    hid_t ga = H5Gcreate2(gr, "axes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    e = ga < 0 || stc_h5_put_i(gr, "level", g->level) != 0 ||
        stc_h5_put_s(gr, "description", "the preload's P and A from axisymmetric load curves "
                     "(one per t/R, E_ratio node, through every delta node) at this "
                     "axisymmetric mesh level") != 0;
    for (int k = 0; !e && k < 3; k++) {
        hsize_t n = (hsize_t)g->n[k];
        e = write_array(ga, axis_name[k], 1, &n, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, g->ax[k],
                        NULL);
    }
    if (ga >= 0) H5Gclose(ga);
    double *d = malloc((size_t)nc * sizeof *d);
    int *iv = malloc((size_t)nc * sizeof *iv);
    char *rs = calloc((size_t)nc, TBL_REASON_MAX);
    e = e || !d || !iv || !rs;
    for (int k = 0; !e && k < NCURVE_FIELD; k++) {
        for (int c = 0; c < nc; c++) {
            const char *p = (const char *)&g->c[c] + curve_fields[k].off;
            if (curve_fields[k].is_int) iv[c] = *(const int *)p;
            else d[c] = *(const double *)p;
        }
        e = curve_fields[k].is_int
                ? write_array(gr, curve_fields[k].name, 2, dc, H5T_STD_I32LE, H5T_NATIVE_INT, iv,
                              curve_fields[k].doc)
                : write_array(gr, curve_fields[k].name, 2, dc, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                              d, curve_fields[k].doc);
    }
    for (int c = 0; !e && c < nc; c++)
        snprintf(rs + (size_t)c * TBL_REASON_MAX, TBL_REASON_MAX, "%s", g->c[c].reason);
    if (!e) e = write_strings(gr, "reason", 2, dc, rs, "why a curve failed");
    if (!e) e = write_array(gr, "P_over_P_c", 3, dv, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, g->P,
                            "preload P / Pc_su, the node-entry sawtooth removed (NaN unless "
                            "the curve is done)");
    if (!e) e = write_array(gr, "A_over_A_c", 3, dv, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, g->A,
                            "preload contact area / Ac_su (NaN unless the curve is done)");
    free(d);
    free(iv);
    free(rs);
    H5Gclose(gr);
    return e ? -1 : 0;
}

/* Temporary name beside path (same file system, so rename is atomic). */
static stc_status tmp_beside(const char *path, char *buf, size_t n)
{
    int k = snprintf(buf, n, "%s.tmp", path); /* one writer per path */
    STC_CHECK(k > 0 && (size_t)k < n, STC_EINVAL, "%s: path too long", path);
    return STC_OK;
}

/* Flush a closed file and its directory entry to disk. */
static int sync_path(const char *path)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0) return -1;
    int r = fsync(fd);
    close(fd);
    return r;
}

static void sync_dir_of(const char *path)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    int fd = open(dirname(buf), O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
        fsync(fd); /* best effort: some file systems refuse it */
        close(fd);
    }
}

stc_status tbl_write(const tbl_table *t, const char *path)
{
    STC_CHECK(t && path && *path, STC_EINVAL, "tbl_write: table and path required");
    char tmp[4200];
    STC_CALL(tmp_beside(path, tmp, sizeof tmp));
    stc_status st = STC_OK;
    hid_t f = -1;
    H5E_BEGIN_TRY { f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(f >= 0, STC_EIO, "%s: cannot create the table file (%s)", tmp, strerror(errno));
    int e;
    H5E_BEGIN_TRY {
        e = write_root(f, t) | write_axes(f, t) | write_points(f, t) | write_members(f, t) |
            write_fit(f, t) | write_normal(f, t);
    } H5E_END_TRY;
    herr_t c;
    H5E_BEGIN_TRY { c = H5Fclose(f); } H5E_END_TRY;
    STC_CHECK_GOTO(e == 0 && c >= 0, st, fail, STC_EIO, "%s: cannot write the table (disk "
                   "full?)", tmp);
    STC_CHECK_GOTO(sync_path(tmp) == 0, st, fail, STC_EIO, "%s: cannot sync: %s", tmp,
                   strerror(errno));
    STC_CHECK_GOTO(rename(tmp, path) == 0, st, fail, STC_EIO, "%s: cannot rename from %s: %s",
                   path, tmp, strerror(errno));
    sync_dir_of(path);
    return STC_OK;
fail:
    remove(tmp);
    return st;
}

/* ---- read ---------------------------------------------------------------------- */

static stc_status read_array(hid_t g, const char *path, const char *name, hid_t mtype,
                             const hsize_t *want, int rank, void *out)
{
    hid_t d = -1, sp = -1;
    stc_status st = STC_OK;
    H5E_BEGIN_TRY { d = H5Dopen2(g, name, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(d >= 0, STC_EFORMAT, "%s: not a friction table: dataset '%s' missing", path, name);
    sp = H5Dget_space(d);
    hsize_t dims[4] = {0, 0, 0, 0};
    if (rank > 4) rank = -1; /* no dataset of this format has more */
    int r = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
    if (r == rank) H5Sget_simple_extent_dims(sp, dims, NULL);
    int ok = r == rank;
    for (int k = 0; ok && k < rank; k++) ok = dims[k] == want[k];
    STC_CHECK_GOTO(ok, st, done, STC_EFORMAT, "%s: dataset '%s' has the wrong shape (rank %d)",
                   path, name, r);
    herr_t rr;
    H5E_BEGIN_TRY { rr = H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out); } H5E_END_TRY;
    STC_CHECK_GOTO(rr >= 0, st, done, STC_EFORMAT, "%s: cannot read dataset '%s'", path, name);
done:
    if (sp >= 0) H5Sclose(sp);
    H5Dclose(d);
    return st;
}

static stc_status read_family(hid_t f, const char *path, int version, tbl_family *fam,
                              tbl_numerics *num)
{
    /* version 1 has no normal grid: P and A come from the points */
    num->normal_level = -1;
    if (version >= 2 && stc_h5_get_i(f, "normal_level", &num->normal_level) != 0)
        return STC_FAIL(STC_EFORMAT, "%s: friction table without its normal_level attribute",
                        path);
    /* versions 1-2: the axis-line reading */
    num->foot_rows = 0.0;
    if (version >= 3 && stc_h5_get_d(f, "foot_rows", &num->foot_rows) != 0)
        return STC_FAIL(STC_EFORMAT, "%s: friction table without its foot_rows attribute", path);
    char contact[16] = "", crit[16] = "";
    int bad = stc_h5_get_d(f, "E_over_Y_su", &fam->E_over_Y_su) |
              stc_h5_get_d(f, "E_over_Y_co", &fam->E_over_Y_co) |
              stc_h5_get_d(f, "nu_su", &fam->nu_su) | stc_h5_get_d(f, "nu_co", &fam->nu_co) |
              stc_h5_get_s(f, "contact", contact, sizeof contact) |
              stc_h5_get_d(f, "tau_c_over_Y_co", &fam->tau_c_over_Y_co) |
              stc_h5_get_s(f, "criterion", crit, sizeof crit) |
              stc_h5_get_d(f, "alpha", &fam->alpha) |
              stc_h5_get_i(f, "mesh_level", &num->mesh_level) |
              stc_h5_get_i(f, "placements", &num->placements) |
              stc_h5_get_d(f, "elements_per_contact", &num->elements_per_contact) |
              stc_h5_get_d(f, "err_floor", &num->err_floor) |
              stc_h5_get_d(f, "err_single", &num->err_single);
    STC_CHECK(!bad, STC_EFORMAT, "%s: friction table without its family or numerics "
              "attributes", path);
    /* refinement: absent from tables written before it (none) */
    num->placements_max = 0, num->refine_err = ASP_REFINE_ERR;
    if (H5Aexists(f, "placements_max") > 0 &&
        (stc_h5_get_i(f, "placements_max", &num->placements_max) |
         stc_h5_get_d(f, "refine_err", &num->refine_err)))
        return STC_FAIL(STC_EFORMAT, "%s: friction table with placements_max but no refine_err",
                        path);
    STC_CHECK(!strcmp(contact, "stick") || !strcmp(contact, "slip"), STC_EFORMAT,
              "%s: contact = '%s': must be stick or slip", path, contact);
    STC_CHECK(!strcmp(crit, "shear") || !strcmp(crit, "stiffness"), STC_EFORMAT,
              "%s: criterion = '%s': must be shear or stiffness", path, crit);
    fam->contact = !strcmp(contact, "stick") ? ASP_CONTACT_STICK : ASP_CONTACT_SLIP;
    fam->criterion = !strcmp(crit, "shear") ? ASP_SHEAR_CRIT_SHEAR : ASP_SHEAR_CRIT_STIFFNESS;
    stc_status s = tbl_family_validate(fam);
    if (s == STC_OK) s = tbl_numerics_validate(num);
    STC_CHECK(s == STC_OK, STC_EFORMAT, "%s: %s", path, stc_errmsg());
    return STC_OK;
}

/* The three axes in group g (named gname in messages); new arrays in ax. */
static stc_status read_axes_in(hid_t g, const char *path, const char *gname, double *ax[3],
                               int n[3])
{
    stc_status st = STC_OK;
    for (int k = 0; k < 3 && st == STC_OK; k++) {
        hid_t d = -1;
        H5E_BEGIN_TRY { d = H5Dopen2(g, axis_name[k], H5P_DEFAULT); } H5E_END_TRY;
        STC_CHECK(d >= 0, STC_EFORMAT, "%s: axis '%s/%s' missing", path, gname, axis_name[k]);
        hid_t sp = H5Dget_space(d);
        hssize_t np = H5Sget_simple_extent_npoints(sp);
        H5Sclose(sp);
        H5Dclose(d);
        STC_CHECK(np >= 1 && np <= 10000, STC_EFORMAT, "%s: axis '%s/%s' has %lld values: "
                  "must be 1 to 10000", path, gname, axis_name[k], (long long)np);
        n[k] = (int)np;
        ax[k] = malloc((size_t)np * sizeof(double));
        STC_CHECK(ax[k], STC_ENOMEM, "tbl_read: out of memory");
        hsize_t want = (hsize_t)np;
        st = read_array(g, path, axis_name[k], H5T_NATIVE_DOUBLE, &want, 1, ax[k]);
    }
    return st;
}

static stc_status read_axes(hid_t f, const char *path, double *ax[3], int n[3])
{
    hid_t g = -1;
    H5E_BEGIN_TRY { g = H5Gopen2(f, "axes", H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(g >= 0, STC_EFORMAT, "%s: not a friction table: group 'axes' missing", path);
    stc_status st = read_axes_in(g, path, "axes", ax, n);
    H5Gclose(g);
    return st;
}

static stc_status read_points(hid_t f, const char *path, int version, tbl_table *t)
{
    int np = tbl_points(t);
    hsize_t dims[3] = {(hsize_t)t->n[2], (hsize_t)t->n[1], (hsize_t)t->n[0]};
    hid_t g = -1;
    H5E_BEGIN_TRY { g = H5Gopen2(f, "points", H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(g >= 0, STC_EFORMAT, "%s: not a friction table: group 'points' missing", path);
    stc_status st = STC_OK;
    double *dv = malloc((size_t)np * sizeof *dv);
    int *iv = malloc((size_t)np * sizeof *iv);
    char *rs = malloc((size_t)np * TBL_REASON_MAX);
    STC_CHECK_GOTO(dv && iv && rs, st, done, STC_ENOMEM, "tbl_read: out of memory");
    for (int k = 0; k < NFIELD; k++) {
        int isi = fields[k].is_int;
        if (fields[k].since > version) { /* not in the file: integers 0 (tbl_create) */
            for (int i = 0; !isi && i < np; i++)
                *(double *)((char *)&t->pt[i] + fields[k].off) = NAN;
            continue;
        }
        STC_CALL_GOTO(read_array(g, path, fields[k].name, isi ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                                 dims, 3, isi ? (void *)iv : (void *)dv), st, done);
        for (int i = 0; i < np; i++) {
            char *p = (char *)&t->pt[i] + fields[k].off;
            if (isi) *(int *)p = iv[i];
            else *(double *)p = dv[i];
        }
    }
    hid_t stype = H5Tcopy(H5T_C_S1);
    H5Tset_size(stype, TBL_REASON_MAX);
    H5Tset_strpad(stype, H5T_STR_NULLTERM);
    st = read_array(g, path, "reason", stype, dims, 3, rs);
    H5Tclose(stype);
    for (int i = 0; st == STC_OK && i < np; i++) {
        tbl_point *p = &t->pt[i];
        memcpy(p->reason, rs + (size_t)i * TBL_REASON_MAX, TBL_REASON_MAX);
        p->reason[TBL_REASON_MAX - 1] = '\0';
        STC_CHECK_GOTO(p->state >= TBL_PENDING && p->state <= TBL_FAILED, st, done, STC_EFORMAT,
                       "%s: point %d: state %d is not 0, 1 or 2", path, i, p->state);
        STC_CHECK_GOTO(p->copied == 0 || (p->copied == 1 && tbl_point_source(t, i) != i), st,
                       done, STC_EFORMAT, "%s: point %d: copied = %d, but it is its own source",
                       path, i, p->copied);
        STC_CHECK_GOTO(p->state != TBL_DONE ||
                           (isfinite(p->P_Pc) && p->P_Pc > 0 && isfinite(p->A_Ac) &&
                            p->A_Ac > 0 && isfinite(p->mu_s) && p->mu_s > 0 &&
                            isfinite(p->mu_s_err) && p->mu_s_err > 0 &&
                            isfinite(p->P_slide_Pc) && p->P_slide_Pc > 0),
                       st, done, STC_EFORMAT, "%s: point %d is marked done but its P, A, mu_s "
                       "or error is not a positive number", path, i);
    }
done:
    free(dv);
    free(iv);
    free(rs);
    H5Gclose(g);
    return st;
}

/* /members (format 6): the done points' members; a count that does not fit
 * the point (not done, or not its members) is a broken file. */
static stc_status read_members(hid_t f, const char *path, int version, tbl_table *t)
{
    int np = tbl_points(t), nm = ASP_PLACEMENTS_MAX;
    hsize_t dims[4] = {(hsize_t)t->n[2], (hsize_t)t->n[1], (hsize_t)t->n[0], (hsize_t)nm};
    hid_t g = -1;
    H5E_BEGIN_TRY { g = H5Gopen2(f, "members", H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(g >= 0, STC_EFORMAT, "%s: not a friction table of format %d: group 'members' "
              "missing", path, version);
    stc_status st = STC_OK;
    double *dv = malloc((size_t)np * nm * sizeof *dv);
    int *iv = malloc((size_t)np * nm * sizeof *iv);
    STC_CHECK_GOTO(dv && iv, st, done, STC_ENOMEM, "tbl_read: out of memory");
    for (int k = 0; k < NMFIELD; k++) {
        int isi = mfields[k].is_int, per = mfields[k].per_member ? nm : 1;
        if (mfields[k].since > version) { /* not in the file: integers 0, numbers NaN */
            for (int i = 0; !isi && i < np; i++)
                for (int j = 0; j < t->pt[i].ens.k; j++)
                    *(double *)mfield_at(&t->pt[i], k, j) = NAN;
            continue;
        }
        STC_CALL_GOTO(read_array(g, path, mfields[k].name, isi ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                                 dims, mfields[k].per_member ? 4 : 3,
                                 isi ? (void *)iv : (void *)dv), st, done);
        for (int i = 0; i < np; i++)
            for (int j = 0; j < per; j++) {
                void *v = mfield_at(&t->pt[i], k, j);
                size_t at = (size_t)i * per + j;
                if (isi) *(int *)v = iv[at];
                else *(double *)v = dv[at];
            }
        if (k == 0) /* the counts first: the rest is read within them */
            for (int i = 0; i < np; i++) {
                const tbl_point *p = &t->pt[i];
                STC_CHECK_GOTO(p->ens.k == 0 || (p->state == TBL_DONE && !p->copied &&
                                                 p->ens.k == p->members && p->ens.k <= nm),
                               st, done, STC_EFORMAT, "%s: point %d: %d members stored, but "
                               "it is %s with %d members", path, i, p->ens.k,
                               tbl_state_name(p->state), p->members);
            }
    }
done:
    free(dv);
    free(iv);
    H5Gclose(g);
    return st;
}

/* The normal grid: its own axes (adopted as they are), curves and values. */
static stc_status read_normal(hid_t f, const char *path, int version, tbl_table *t)
{
    hid_t gr = -1, ga = -1;
    H5E_BEGIN_TRY { gr = H5Gopen2(f, "normal", H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(gr >= 0, STC_EFORMAT, "%s: friction table with a normal level but no group "
              "'normal'", path);
    stc_status st = STC_OK;
    double *ax[3] = {NULL, NULL, NULL}, *d = NULL, *P = NULL, *A = NULL;
    int n[3] = {0, 0, 0}, *iv = NULL;
    char *rs = NULL;
    int level = -2;
    stc_h5_get_i(gr, "level", &level);
    STC_CHECK_GOTO(level == t->num.normal_level, st, done, STC_EFORMAT, "%s: normal grid level "
                   "%d differs from the table's normal_level %d", path, level,
                   t->num.normal_level);
    H5E_BEGIN_TRY { ga = H5Gopen2(gr, "axes", H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK_GOTO(ga >= 0, st, done, STC_EFORMAT, "%s: group 'normal/axes' missing", path);
    STC_CALL_GOTO(read_axes_in(ga, path, "normal/axes", ax, n), st, done);
    STC_CALL_GOTO(tbl_normal_init_axes(t, ax, n), st, done);
    int nc = tbl_curves(t);
    size_t nv = (size_t)nc * n[0];
    hsize_t dc[2] = {(hsize_t)n[2], (hsize_t)n[1]};
    hsize_t dv[3] = {(hsize_t)n[2], (hsize_t)n[1], (hsize_t)n[0]};
    d = malloc((size_t)nc * sizeof *d);
    iv = malloc((size_t)nc * sizeof *iv);
    rs = malloc((size_t)nc * TBL_REASON_MAX);
    P = malloc(nv * sizeof *P);
    A = malloc(nv * sizeof *A);
    STC_CHECK_GOTO(d && iv && rs && P && A, st, done, STC_ENOMEM, "tbl_read: out of memory");
    tbl_curve *cv = calloc((size_t)nc, sizeof *cv);
    STC_CHECK_GOTO(cv, st, done, STC_ENOMEM, "tbl_read: out of memory");
    for (int k = 0; k < NCURVE_FIELD && st == STC_OK; k++) {
        int isi = curve_fields[k].is_int;
        if (curve_fields[k].since > version) continue; /* not in the file: 0 (calloc) */
        st = read_array(gr, path, curve_fields[k].name, isi ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                        dc, 2, isi ? (void *)iv : (void *)d);
        for (int c = 0; st == STC_OK && c < nc; c++) {
            char *p = (char *)&cv[c] + curve_fields[k].off;
            if (isi) *(int *)p = iv[c];
            else *(double *)p = d[c];
        }
    }
    hid_t stype = H5Tcopy(H5T_C_S1);
    H5Tset_size(stype, TBL_REASON_MAX);
    H5Tset_strpad(stype, H5T_STR_NULLTERM);
    if (st == STC_OK) st = read_array(gr, path, "reason", stype, dc, 2, rs);
    H5Tclose(stype);
    if (st == STC_OK) st = read_array(gr, path, "P_over_P_c", H5T_NATIVE_DOUBLE, dv, 3, P);
    if (st == STC_OK) st = read_array(gr, path, "A_over_A_c", H5T_NATIVE_DOUBLE, dv, 3, A);
    for (int c = 0; st == STC_OK && c < nc; c++) {
        memcpy(cv[c].reason, rs + (size_t)c * TBL_REASON_MAX, TBL_REASON_MAX);
        cv[c].reason[TBL_REASON_MAX - 1] = '\0';
        if (tbl_curve_set(t, c, &cv[c], P + (size_t)c * n[0], A + (size_t)c * n[0]) != STC_OK)
            st = STC_FAIL(STC_EFORMAT, "%s: normal grid: %s", path, stc_errmsg());
    }
    free(cv);
done:
    for (int k = 0; k < 3; k++) free(ax[k]);
    free(d), free(iv), free(rs), free(P), free(A);
    if (ga >= 0) H5Gclose(ga);
    H5Gclose(gr);
    return st;
}

/* The stored fit's hyperparameters and data hash, for tbl_fit to reuse
 * (absent or unreadable: none; tbl_fit then searches). */
static void read_fit(hid_t f, tbl_table *t)
{
    t->fit_npar = -1;
    H5E_BEGIN_TRY {
        hid_t g = H5Gopen2(f, "fit", H5P_DEFAULT);
        if (g >= 0) {
            unsigned long hash;
            int np = 0;
            if (stc_h5_get_u(g, "data_hash", &hash) == 0) {
                if (!stc_h5_attr_exists(g, "hyperparameters") ||
                    stc_h5_get_dv(g, "hyperparameters", TBL_GP_MAXPAR, t->fit_par, &np) == 0) {
                    t->fit_hash = hash;
                    t->fit_npar = np;
                }
            }
            H5Gclose(g);
        }
    } H5E_END_TRY;
}

stc_status tbl_read(const char *path, tbl_table **out)
{
    STC_CHECK(out, STC_EINVAL, "tbl_read: out must not be NULL");
    *out = NULL;
    STC_CHECK(path && *path, STC_EINVAL, "tbl_read: path required");
    struct stat sb;
    STC_CHECK(stat(path, &sb) == 0, STC_EIO, "%s: cannot open: %s", path, strerror(errno));
    STC_CHECK(!S_ISDIR(sb.st_mode), STC_EIO, "%s: is a directory (expected a friction table "
              "file from `stiction table build`)", path);
    hid_t f = -1;
    H5E_BEGIN_TRY { f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(f >= 0, STC_EFORMAT, "%s: %s", path,
              access(path, R_OK) == 0 ? "not an HDF5 file (expected a friction table from "
                                        "`stiction table build`)"
                                      : "cannot read");
    stc_status st = STC_OK;
    double *ax[3] = {NULL, NULL, NULL};
    int n[3] = {0, 0, 0}, ver = 0;
    char fmt[64] = "";
    H5E_BEGIN_TRY {
        stc_h5_get_s(f, "format", fmt, sizeof fmt);
        stc_h5_get_i(f, "format_version", &ver);
    } H5E_END_TRY;
    STC_CHECK_GOTO(!strcmp(fmt, TBL_FORMAT_NAME), st, done, STC_EFORMAT,
                   "%s: not a friction table (format attribute '%s', expected '%s')", path, fmt,
                   TBL_FORMAT_NAME);
    STC_CHECK_GOTO(ver >= 1 && ver <= TBL_FORMAT_VERSION, st, done, STC_EFORMAT,
                   "%s: table format version %d: this stiction reads versions 1 to %d", path,
                   ver, TBL_FORMAT_VERSION);
    tbl_family fam;
    tbl_numerics num;
    H5E_BEGIN_TRY { st = read_family(f, path, ver, &fam, &num); } H5E_END_TRY;
    if (st) goto done;
    H5E_BEGIN_TRY { st = read_axes(f, path, ax, n); } H5E_END_TRY;
    if (st) goto done;
    STC_CALL_GOTO(tbl_create(&fam, &num, ax[0], n[0], ax[1], n[1], ax[2], n[2], out), st, done);
    H5E_BEGIN_TRY { st = read_points(f, path, ver, *out); } H5E_END_TRY;
    if (st) goto done;
    if (ver >= 6) { /* before: no members kept (every ens.k 0, tbl_create) */
        H5E_BEGIN_TRY { st = read_members(f, path, ver, *out); } H5E_END_TRY;
        if (st) goto done;
    }
    if (num.normal_level >= 0) {
        H5E_BEGIN_TRY { st = read_normal(f, path, ver, *out); } H5E_END_TRY;
        if (st) goto done;
    }
    char cmd[512] = "", hist[sizeof(*out)->history] = "";
    double wall = NAN;
    H5E_BEGIN_TRY {
        stc_h5_get_s(f, "command", cmd, sizeof cmd);
        stc_h5_get_d(f, "build_wall_s", &wall);
        stc_h5_get_s(f, "history", hist, sizeof hist); /* absent before it was kept */
    } H5E_END_TRY;
    tbl_set_provenance(*out, cmd, wall);
    tbl_history_carry(*out, hist, NULL);
    read_fit(f, *out);
    int done_pts;
    tbl_count(*out, &done_pts, NULL, NULL);
    if (done_pts >= 3) st = tbl_fit(*out);
done:
    if (st != STC_OK && st != STC_EFORMAT && st != STC_ENOMEM && *out == NULL) st = STC_EFORMAT;
    if (st != STC_OK) tbl_destroy(out);
    for (int k = 0; k < 3; k++) free(ax[k]);
    H5Fclose(f);
    return st;
}
