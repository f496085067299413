/* Randomised inputs for every reader of user files: INI configurations
 * (stc_ini_load + stc_params_set), text height grids (srf_map_import_text),
 * HDF5 surface files (srf_map_read, srf_map_import_h5), and the CLI
 * (`formulas`, `surface stats|synth|predict`, `asperity`'s normal step)
 * on random configurations, argument lists and grids.
 *
 * Each case is generated from a fixed seed, so a failure repeats; the case
 * number is in the message.  Where the generator knows the answer (a grid
 * with one bad token at a known line, a clean grid whose heights it wrote)
 * the reader's status, message and numbers are checked against it;
 * everywhere else the properties every reader owes the user are: a known
 * status; a failure carries a message (naming the line for a malformed
 * file, the key and value for a bad parameter) and returns no object; a
 * success returns only finite numbers in range.  Nothing may crash (run
 * `make SANITIZE=1 check` for memory errors).
 *
 * STICTION_FUZZ_CASES=N scales every loop (default 1: about 5 s; 100 runs
 * a hundred times as many cases).  The CLI part needs the binary
 * ($STICTION_CLI or ../bin/stiction beside this program, as test_cli). */
#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include <hdf5.h>

#include "cli_util.h"
#include "stiction/formulas.h"
#include "stiction/params.h"
#include "stiction/surface.h"
#include "tmp_util.h"

static char dir[256];  /* scratch directory */
static long scale = 1; /* STICTION_FUZZ_CASES */

/* ------------------------------------------------------------ helpers */

/* xorshift64*: a fixed sequence per seed, independent of the C library. */
static uint64_t rng;
static void seed(uint64_t s) { rng = s * 0x9E3779B97F4A7C15ull + 1; }
static uint64_t rnd(void)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return rng * 0x2545F4914F6CDD1Dull;
}
static int pick(int n) { return (int)(rnd() % (uint64_t)n); }
static double unif(double a, double b) /* uniform in [a, b): 53 random bits */
{
    return a + (b - a) * (double)(rnd() >> 11) / 9007199254740992.0;
}
static const char *one_of(const char *const *list, int n) { return list[pick(n)]; }
#define ONE_OF(list) one_of(list, (int)(sizeof list / sizeof *list))

static const char *path_in(const char *name) { return cli_path(dir, name); }

static void write_bytes(const char *path, const char *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* A failure's message must be there, and say the text `what` if given. */
static void assert_message(stc_status st, const char *what, long c)
{
    const char *m = stc_errmsg();
    if (st <= STC_OK || st >= STC_NSTATUS)
        fail_msg("case %ld: status %d is not a known one", c, st);
    if (!m || !*m) fail_msg("case %ld: %s without a message", c, stc_strerror(st));
    if (what && !strstr(m, what)) fail_msg("case %ld: message '%s' does not say '%s'", c, m, what);
}

/* A map a reader returned: a usable grid of finite heights. */
static void assert_map_sane(const srf_map *m, long c)
{
    if (!m || m->nx < 3 || m->ny < 3 || !(m->lx > 0) || !(m->ly > 0) || !isfinite(m->lx) ||
        !isfinite(m->ly))
        fail_msg("case %ld: a map of %d x %d, %g x %g mm accepted", c, m ? m->nx : 0,
                 m ? m->ny : 0, m ? m->lx : 0, m ? m->ly : 0);
    for (size_t k = 0; k < (size_t)m->nx * m->ny; k++)
        if (!isfinite(m->z[k])) fail_msg("case %ld: height %zu is %g", c, k, m->z[k]);
}

/* ------------------------------------------------------------ INI files */

static stc_status ini_set(void *user, const char *section, const char *key, const char *value)
{
    (void)section;
    return stc_params_set(user, key, value);
}

static void test_ini(void **state)
{
    (void)state;
    static const char *const keys[] = {"R", "t-over-R", "t_over_R", "--E-su", "E-ratio",
                                       "E_over_Y", "Y-su", "Y-co", "nu", "nu-co", "bogus", "",
                                       "R R", "nu\x01"};
    static const char *const vals[] = {"1", "0", "-1", "0.3", "0.025", "2", "1000", "1e308",
                                       "1e-308", "1e400", "nan", "inf", "-inf", "", " ", "0x10",
                                       "1,5", "abc", "0.5", "0.4999", "10 mm", "'3'", "3;c",
                                       "3 # c", "1e-3", "-0", "200000", "70000"};
    static const char *const junk[] = {"[", "[]", "[asperity]", "=", "==", "key", "; comment",
                                       "# comment", "=3", "\x01\x02", "  indented = 1", "[x"};
    long n = 1500 * scale, count[STC_NSTATUS] = {0}, valid = 0;
    const char *path = path_in("fuzz.ini");
    char text[4096];
    for (long c = 0; c < n; c++) {
        seed(1000 + (uint64_t)c);
        size_t len = 0;
        for (int l = pick(7); l > 0; l--) {
            const char *line;
            char kv[600];
            if (pick(6) == 0) {
                line = ONE_OF(junk);
            } else if (pick(40) == 0) { /* a line longer than any buffer */
                memset(kv, 'A', 500);
                kv[500] = '\0';
                line = kv;
            } else {
                snprintf(kv, sizeof kv, "%s%s=%s%s", ONE_OF(keys), pick(3) ? "" : " ",
                         pick(3) ? "" : " ", ONE_OF(vals));
                line = kv;
            }
            len += (size_t)snprintf(text + len, sizeof text - len, "%s%s", line,
                                    pick(5) ? "\n" : "\r\n");
            if (len >= sizeof text - 600) break;
        }
        write_bytes(path, text, len);
        stc_params p;
        stc_params_default(&p);
        stc_error_clear();
        stc_status st = stc_ini_load(path, ini_set, &p);
        if (st == STC_OK) st = stc_params_validate(&p);
        count[st >= 0 && st < STC_NSTATUS ? st : 0]++;
        if (st == STC_EUNSUPPORTED) continue; /* an unknown key: the caller's to name */
        if (st != STC_OK) {
            assert_message(st, st == STC_EFORMAT ? "line" : NULL, c);
            /* a bad value says what is valid ("must be ...", "valid: ...") */
            if (st == STC_EINVAL && !strstr(stc_errmsg(), "must") && !strstr(stc_errmsg(), "valid"))
                fail_msg("case %ld: '%s' does not say what is valid", c, stc_errmsg());
            continue;
        }
        /* accepted: both layers and the closed forms must be usable */
        stc_material su, co;
        stc_critical cr;
        stc_params_materials(&p, &su, &co);
        if (!(p.R > 0 && isfinite(p.R) && p.t_over_R >= 0 && isfinite(p.t_over_R)))
            fail_msg("case %ld: R = %g, t/R = %g accepted", c, p.R, p.t_over_R);
        const stc_material *ms[] = {&su, &co};
        for (int i = 0; i < 2; i++)
            if (!(ms[i]->E > 0 && isfinite(ms[i]->E) && ms[i]->Y > 0 && isfinite(ms[i]->Y) &&
                  ms[i]->nu > -1 && ms[i]->nu < 0.5))
                fail_msg("case %ld: layer %d E %g Y %g nu %g accepted", c, i, ms[i]->E, ms[i]->Y,
                         ms[i]->nu);
        stc_status s2 = stc_critical_eval(&su, p.R, &cr);
        if (s2 == STC_OK && !(isfinite(cr.omega_c) && isfinite(cr.P_c) && cr.omega_c > 0))
            fail_msg("case %ld: omega_c %g, P_c %g from accepted parameters", c, cr.omega_c,
                     cr.P_c);
        if (s2 != STC_OK) assert_message(s2, NULL, c);
        valid++;
    }
    printf("# INI: %ld files: %ld accepted, %ld bad values, %ld malformed, %ld unknown keys, "
           "%ld other\n", n, valid, count[STC_EINVAL], count[STC_EFORMAT],
           count[STC_EUNSUPPORTED], n - valid - count[STC_EINVAL] - count[STC_EFORMAT] -
           count[STC_EUNSUPPORTED]);
    /* the generator must reach every outcome, or it tests less than it says */
    assert_true(valid > 0 && count[STC_EINVAL] > 0 && count[STC_EFORMAT] > 0 &&
                count[STC_EUNSUPPORTED] > 0);
}

/* ------------------------------------------------------------ text grids */

/* One valid number as text (value into *v). */
static void good_token(char *tok, size_t n, double *v)
{
    double x = unif(-1000, 1000);
    switch (pick(8)) {
    case 0: snprintf(tok, n, "%g", x); break;
    case 1: snprintf(tok, n, "%.17g", x); break;
    case 2: snprintf(tok, n, "%e", x); break;
    case 3: snprintf(tok, n, "%+f", x); break;
    case 4: snprintf(tok, n, "%d", (int)x); break;
    case 5: snprintf(tok, n, "%.3E", x); break;
    case 6: snprintf(tok, n, "%s", pick(2) ? "-0" : ".5"); break;
    default: snprintf(tok, n, "%s", pick(2) ? "5." : "0x1p3"); break;
    }
    *v = strtod(tok, NULL);
}

static void test_text_grids(void **state)
{
    (void)state;
    static const char *const bad[] = {"abc", "1.2.3", "nan", "inf", "-inf", "1e400", "--1",
                                      "1e", "+-3", "\x01", "1e-400", "3mm", "\xff\xfe", "NaN"};
    static const char *const seps[] = {" ", "\t", ",", ";", "  ", " , "};
    enum { MAXN = 9 };
    long n = 3000 * scale, ok = 0, refused = 0;
    const char *path = path_in("fuzz.txt");
    static char text[1 << 15];
    for (long c = 0; c < n; c++) {
        seed(50000 + (uint64_t)c);
        int nx = pick(MAXN), ny = pick(MAXN), rows = 0;
        /* at most one defect, at a known data row: a bad token, a short or
         * long row, or a NUL byte */
        int defect = pick(3) ? 0 : 1 + pick(3), drow = ny ? pick(ny) : 0;
        int dcol = nx ? pick(nx) : 0, dline = 0, line = 0;
        double z[MAXN][MAXN], dx = 0.01, dy = 0.02, zs = pick(2) ? 1.0 : 1e-3;
        int bad_pixel = pick(25) == 0;
        if (bad_pixel) dx = pick(2) ? 0.0 : NAN;
        size_t len = 0;
        for (int j = 0; j < ny; j++) {
            while (pick(5) == 0) { /* comments and blank lines between rows */
                len += (size_t)snprintf(text + len, 64, "%s\n", pick(2) ? "# note" : "   ");
                line++;
            }
            line++;
            int cols = nx;
            if (j == drow) dline = line;
            if (defect == 2 && j == drow) cols = nx + (pick(2) || nx == 1 ? 1 : -1);
            for (int i = 0; i < cols; i++) {
                char tok[64];
                double v;
                good_token(tok, sizeof tok, &v);
                if (i < MAXN) z[j][i] = v;
                if (defect == 1 && j == drow && i == dcol)
                    snprintf(tok, sizeof tok, "%s", ONE_OF(bad));
                len += (size_t)snprintf(text + len, 128, "%s%s", i ? ONE_OF(seps) : "", tok);
            }
            if (defect == 3 && j == drow && nx > 0) text[len++] = '\0';
            if (pick(6) == 0) len += (size_t)snprintf(text + len, 64, " # trailing");
            len += (size_t)snprintf(text + len, 8, "%s", pick(4) ? "\n" : "\r\n");
            rows += cols > 0;
        }
        /* rows of nothing have no defect to find; a row of another length
         * needs a second row to differ from */
        if (nx == 0 || ny == 0 || (defect == 2 && ny < 2)) defect = 0;
        write_bytes(path, text, len);
        srf_map *m = (srf_map *)&m; /* must be cleared on failure */
        stc_error_clear();
        stc_status st = srf_map_import_text(path, dx, dy, zs, &m);
        char want[64];
        if (bad_pixel) {
            if (st != STC_EINVAL) fail_msg("case %ld: dx = %g accepted", c, dx);
            assert_message(st, "dx", c);
        } else if (defect) {
            snprintf(want, sizeof want, "line %d", dline);
            if (st != STC_EFORMAT) fail_msg("case %ld: defect %d at line %d: %s", c, defect, dline,
                                            stc_strerror(st));
            assert_message(st, want, c);
        } else if (nx < 3 || rows < 3) {
            if (st != STC_EFORMAT) fail_msg("case %ld: %d rows of %d accepted", c, rows, nx);
            assert_message(st, "3 x 3", c);
        } else {
            if (st != STC_OK) fail_msg("case %ld: clean %d x %d grid refused: %s", c, nx, ny,
                                       stc_errmsg());
            assert_map_sane(m, c);
            assert_int_equal(m->nx, nx);
            assert_int_equal(m->ny, ny);
            /* heights as written, once the removed plane is added back */
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++) {
                    double back = m->z[j * nx + i] + m->tilt_x * i * dx + m->tilt_y * j * dy +
                                  m->offset;
                    if (fabs(back - zs * z[j][i]) > 1e-11 * zs * 1000)
                        fail_msg("case %ld: height (%d, %d) %.17g read back as %.17g", c, j, i,
                                 zs * z[j][i], back);
                }
            srf_map_destroy(&m);
            ok++;
            continue;
        }
        if (m != NULL) fail_msg("case %ld: a failed import returned a map", c);
        refused++;
    }
    printf("# text grids: %ld files: %ld read back exactly, %ld refused as expected\n", n, ok,
           refused);
    assert_true(ok > 0 && refused > 0);
}

/* Random bytes flipped, inserted or deleted in a valid grid: any status, but
 * a success must be a sane map and a failure must say why. */
static void test_text_mutations(void **state)
{
    (void)state;
    static const char base[] = "# heights, um\n1 2 3 4\n5 6 7 8\n9 10 11 12.5\n-1 -2 -3 -4e0\n";
    long n = 3000 * scale, ok = 0;
    const char *path = path_in("mut.txt");
    char text[256];
    for (long c = 0; c < n; c++) {
        seed(90000 + (uint64_t)c);
        size_t len = sizeof base - 1;
        memcpy(text, base, len);
        for (int k = 1 + pick(4); k > 0; k--) {
            size_t at = (size_t)pick((int)len);
            int op = pick(3);
            if (op == 0) {
                text[at] = (char)pick(256);
            } else if (op == 1 && len < sizeof text - 1) {
                memmove(text + at + 1, text + at, len - at);
                text[at] = (char)pick(256);
                len++;
            } else if (len > 1) {
                memmove(text + at, text + at + 1, len - at - 1);
                len--;
            }
        }
        write_bytes(path, text, len);
        srf_map *m = NULL;
        stc_error_clear();
        stc_status st = srf_map_import_text(path, 0.001, 0.001, 1e-3, &m);
        if (st == STC_OK) {
            assert_map_sane(m, c);
            srf_map_destroy(&m);
            ok++;
        } else {
            assert_message(st, st == STC_EFORMAT ? path : NULL, c);
            assert_null(m);
        }
    }
    printf("# mutated grids: %ld files, %ld still valid grids\n", n, ok);
}

/* ------------------------------------------------------------ HDF5 files */

static void h5_attr_d(hid_t d, const char *name, double v, int n)
{
    if (H5Aexists(d, name) > 0) H5Adelete(d, name);
    hsize_t dim = (hsize_t)n;
    hid_t sp = H5Screate_simple(1, &dim, NULL);
    hid_t a = H5Acreate2(d, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
    double buf[4] = {v, v, v, v};
    H5Awrite(a, H5T_NATIVE_DOUBLE, buf);
    H5Aclose(a);
    H5Sclose(sp);
}

static void h5_attr_s(hid_t d, const char *name, const char *v)
{
    if (H5Aexists(d, name) > 0) H5Adelete(d, name);
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen(v) + 1);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(d, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, v);
    H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
}

/* Replace /height by a dataset of the given rank, dims and type, filled
 * with `fill` (and a NaN at element `nan_at` if >= 0). */
static void h5_height(hid_t f, int rank, const hsize_t *dims, hid_t type, double fill, long nan_at)
{
    if (H5Lexists(f, "height", H5P_DEFAULT) > 0) H5Ldelete(f, "height", H5P_DEFAULT);
    hsize_t total = 1;
    for (int r = 0; r < rank; r++) total *= dims[r];
    double *v = malloc((size_t)(total ? total : 1) * sizeof *v);
    assert_non_null(v);
    for (hsize_t k = 0; k < total; k++) v[k] = fill + (double)(k % 7);
    if (nan_at >= 0 && (hsize_t)nan_at < total) v[nan_at] = NAN;
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t d = H5Dcreate2(f, "height", type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(d);
    H5Sclose(sp);
    free(v);
}

static void test_hdf5_files(void **state)
{
    (void)state;
    long n = 400 * scale, ok = 0, refused = 0, stats_refused = 0;
    const char *path = path_in("fuzz.h5");
    static const char *const dattrs[] = {"lx_mm", "ly_mm", "rms_mm", "hurst", "z_scale",
                                         "corr_length_x_mm", "detrend_offset_mm"};
    static const char *const sattrs[] = {"origin", "spectrum", "amplitude", "johnson_family",
                                         "source"};
    static const double dvals[] = {0.0, -1.0, NAN, INFINITY, 1e308, 1e-308, 1.0, 0.5};
    for (long c = 0; c < n; c++) {
        seed(120000 + (uint64_t)c);
        srf_map *m;
        assert_int_equal(srf_map_create(4 + pick(4), 4 + pick(4), 1.0, 1.0, &m), STC_OK);
        for (size_t k = 0; k < (size_t)m->nx * m->ny; k++) m->z[k] = unif(-1e-3, 1e-3);
        assert_int_equal(srf_map_write_h5(m, path), STC_OK);
        srf_map_destroy(&m);
        hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
        assert_true(f >= 0);
        hid_t d = H5Dopen2(f, "height", H5P_DEFAULT);
        assert_true(d >= 0);
        for (int k = 1 + pick(3); k > 0; k--) {
            switch (pick(6)) {
            case 0: h5_attr_d(d, ONE_OF(dattrs), dvals[pick(8)], pick(6) ? 1 : 2); break;
            case 1: /* a string where a number or another string belongs */
                h5_attr_s(d, pick(2) ? ONE_OF(sattrs) : ONE_OF(dattrs), pick(2) ? "" : "\x01 junk");
                break;
            case 2: if (H5Aexists(d, "lx_mm") > 0) H5Adelete(d, "lx_mm"); break;
            case 3: {
                long big = 0x7fffffffL;
                hid_t sp = H5Screate(H5S_SCALAR);
                const char *nm = pick(2) ? "periodic" : "seed";
                if (H5Aexists(d, nm) > 0) H5Adelete(d, nm);
                hid_t a = H5Acreate2(d, nm, H5T_NATIVE_LONG, sp, H5P_DEFAULT, H5P_DEFAULT);
                H5Awrite(a, H5T_NATIVE_LONG, &big);
                H5Aclose(a);
                H5Sclose(sp);
                break;
            }
            default: {
                /* the heights themselves: rank, size, type, a NaN */
                int rank = pick(4) ? 2 : 1 + 2 * pick(2);
                hsize_t dims[3] = {(hsize_t)pick(6), (hsize_t)pick(6), 2};
                hid_t types[] = {H5T_NATIVE_DOUBLE, H5T_NATIVE_FLOAT, H5T_NATIVE_INT,
                                 H5T_NATIVE_CHAR};
                H5Dclose(d);
                h5_height(f, rank, dims, types[pick(4)], pick(5) ? 1.0 : 1e300,
                          pick(3) ? -1 : pick(20));
                d = H5Dopen2(f, "height", H5P_DEFAULT);
                h5_attr_d(d, "lx_mm", 1.0, 1);
                h5_attr_d(d, "ly_mm", 1.0, 1);
                break;
            }
            }
        }
        H5Dclose(d);
        H5Fclose(f);
        for (int reader = 0; reader < 2; reader++) {
            m = (srf_map *)&m;
            stc_error_clear();
            stc_status st = reader ? srf_map_import_h5(path, "height", 0.1, 0.1, 1.0, &m)
                                   : srf_map_read(path, &m);
            if (st == STC_OK) {
                assert_map_sane(m, c);
                /* what `surface stats` does next: numbers, or a reason */
                srf_summits *su = NULL;
                srf_stats sts;
                st = srf_summits_find(m, SRF_RULE_8, &su);
                if (st == STC_OK) st = srf_stats_compute(m, su, &sts);
                if (st == STC_OK && !(isfinite(sts.sigma) && isfinite(sts.m0) &&
                                      isfinite(sts.m2) && isfinite(sts.m4)))
                    fail_msg("case %ld: statistics sigma %g, m2 %g, m4 %g returned as a result",
                             c, sts.sigma, sts.m2, sts.m4);
                if (st != STC_OK) assert_message(st, NULL, c);
                stats_refused += st != STC_OK;
                srf_summits_destroy(&su);
                srf_map_destroy(&m);
                ok++;
            } else {
                assert_message(st, NULL, c);
                if (m != NULL) fail_msg("case %ld: a failed read returned a map", c);
                refused++;
            }
        }
    }
    printf("# HDF5: %ld files, two readers: %ld maps read (statistics refused for %ld), %ld "
           "refused with a message\n", n, ok, stats_refused, refused);
    assert_true(ok > 0 && refused > 0);
}

/* ------------------------------------------------------------ the CLI */

static char cli[PATH_MAX];

/* Run the CLI with `args` in the scratch directory; stdout and stderr into
 * out and err.  Returns the exit status (128 + signal if killed). */
static int run_cli(const char *args, char *out, char *err, size_t n)
{
    char cmd[PATH_MAX + 4096];
    snprintf(cmd, sizeof cmd, "cd '%s' && timeout 20 '%s' %s >o.txt 2>e.txt", dir, cli, args);
    int st = system(cmd);
    int rc = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    const char *names[] = {"o.txt", "e.txt"};
    char *bufs[] = {out, err};
    for (int k = 0; k < 2; k++) {
        FILE *f = fopen(path_in(names[k]), "rb");
        assert_non_null(f);
        size_t got = fread(bufs[k], 1, n - 1, f);
        bufs[k][got] = '\0';
        fclose(f);
    }
    return rc;
}

/* The first word of `out` that reads nan or inf (any case, signed) and is
 * not itself one of the words of `args` (a file the user named "nan" is
 * echoed back, not computed), or NULL. */
static const char *non_number(const char *out, const char *args)
{
    static char word[64];
    for (const char *p = out; *p;) {
        size_t n = strcspn(p, " \t\n,;:()[]{}\"=");
        if (n > 0 && n < sizeof word) {
            memcpy(word, p, n);
            word[n] = '\0';
            const char *w = word + (word[0] == '-' || word[0] == '+');
            if (!strcasecmp(w, "nan") || !strcasecmp(w, "inf") || !strcasecmp(w, "infinity")) {
                char padded[80], pargs[1100];
                snprintf(padded, sizeof padded, " %s ", word);
                snprintf(pargs, sizeof pargs, " %s ", args);
                if (!strstr(pargs, padded)) return word;
            }
        }
        p += n ? n : 1;
    }
    return NULL;
}

/* Remove a file, or a directory with the files in it (an --out DIR). */
static void remove_tree(const char *path)
{
    if (unlink(path) == 0) return;
    DIR *d = opendir(path);
    struct dirent *e;
    char sub[PATH_MAX + 256];
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
            unlink(sub);
        }
    if (d) closedir(d);
    rmdir(path);
}

/* Remove every out* entry of the scratch directory (keep = 0), or return
 * the name of the first one (keep = 1; NULL if none). */
static const char *outputs(int keep)
{
    static char name[256];
    const char *found = NULL;
    DIR *d = opendir(dir);
    assert_non_null(d);
    struct dirent *e;
    while ((e = readdir(d)))
        if (strncmp(e->d_name, "out", 3) == 0) {
            if (!keep) {
                remove_tree(path_in(e->d_name));
            } else if (!found) {
                snprintf(name, sizeof name, "%s", e->d_name);
                found = name;
            }
        }
    closedir(d);
    return found;
}

static void test_cli(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0 || access(cli, X_OK) != 0) {
        printf("# no CLI binary at %s: skipped\n", cli);
        skip();
    }
    static const char *const opts[] = {"--R", "--t-over-R", "--nu", "--E-ratio", "--E-su",
                                       "--E-over-Y", "--Y-su", "--delta", "--csv", "--json",
                                       "--sweep-t-over-R", "--sweep-E-ratio", "--output",
                                       "--config", "--bogus", "-", "--"};
    static const char *const vals[] = {"1", "0", "-1", "0.3", "0.025", "2", "1e308", "nan",
                                       "inf", "''", "1:2:3", "3:1:2", "0.002:0.05:0",
                                       "0.005,0.025", "1,,2", "x", "out.csv", "cfg.ini",
                                       "/nonexistent/out.csv", "1e-300"};
    static const char *const keys[] = {"R", "t-over-R", "nu", "E-ratio", "delta", "bogus", "json"};
    static const char *const sopts[] = {"--rule", "--pixel-size", "--dataset", "--z-scale",
                                        "--json", "--in", "--bogus"};
    static const char *const svals[] = {"8", "4", "3", "0.001", "0.001,0.002", "0", "-1", "1e-300",
                                        "1e300", "nan", "grid.txt", "height", "x", "1,2,3"};
    static const char *const gopts[] = {"--size", "--length", "--rms", "--spectrum",
                                        "--corr-length", "--hurst", "--cutoff-wavelength",
                                        "--skewness", "--kurtosis", "--amplitude", "--seed",
                                        "--no-png", "--json", "--png", "--threads"};
    static const char *const gvals[] = {"16", "33", "8,16", "0", "-1", "2", "1e9", "0.5",
                                        "0.01", "1e-300", "nan", "self-affine", "exponential",
                                        "rayleigh", "exact", "3", "4.5", "-0.5", "x", "out.png",
                                        "/nonexistent/out.png", "1,"};
    static const char *const popts[] = {"--model", "--layer", "--mode", "--density",
                                        "--pressures", "--separations", "--t-mm", "--rule",
                                        "--sampled", "--csv", "--png", "--out", "--json",
                                        "--surface", "--E-ratio", "--Y-co", "--config"};
    static const char *const pvals[] = {"hertz", "wsp", "coating", "substrate", "statistical",
                                        "deterministic", "gaussian", "kde", "1,10,100", "0.5",
                                        "-1", "0", "1e9", "nan", "3,2,1", "1:100:5", "out.csv",
                                        "out.png", "outdir", "srf.h5", "1.5e-3", "4", "7000"};
    /* normal-step options only: a shear run takes tens of seconds */
    static const char *const aopts[] = {"--delta", "--delta-mm", "--contact", "--surface-layers",
                                        "--elements-per-contact", "--newton-reuse", "--krylov",
                                        "--krylov-max", "--steps-per-node", "--return-map",
                                        "--no-separation", "--threads", "--json", "--out",
                                        "--t-over-R", "--E-ratio", "--nu", "--grade-3d"};
    static const char *const avals[] = {"1", "0.5", "1:3:2", "2,1", "0", "-1", "nan", "1e9",
                                        "slip", "stick", "x", "3", "0.025", "2", "outdir",
                                        "/nonexistent/outdir", "exact", "radial", "1000",
                                        "0.0001", "auto", "off"};
    long n = 150 * scale, ok = 0, ok_surface = 0, ok_synth = 0, ok_asperity = 0, ok_predict = 0;
    static char out[1 << 16], err[1 << 16];
    /* a small map for `surface predict --surface` (not an out* file) */
    if (run_cli("surface synth --size 64 --out srf.h5 --no-png", out, err, sizeof out) != 0)
        fail_msg("cannot make the predict test's map: %s", err);
    for (long c = 0; c < n; c++) {
        seed(200000 + (uint64_t)c);
        char cfg[512] = "", args[1024] = "formulas";
        size_t cl = 0, al = strlen(args);
        int family = pick(5), surface = family == 1;
        if (family == 4) { /* `surface predict`, statistical or on a small map */
            al = (size_t)snprintf(args, sizeof args, "surface predict %s%s", pick(2)
                                  ? "--summit-density 2303 --summit-radius 0.07 --sigma-s 4e-4"
                                  : "--surface srf.h5", pick(3) ? " --pressures 1,10" : "");
            for (int k = pick(5); k > 0; k--) {
                al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(popts));
                if (pick(5))
                    al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(pvals));
            }
        }
        if (family == 3) { /* `asperity`, normal step on the coarsest mesh */
            al = (size_t)snprintf(args, sizeof args, "asperity --mesh 0%s",
                                  pick(3) ? " --delta 1" : "");
            for (int k = pick(5); k > 0; k--) {
                al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(aopts));
                if (pick(5))
                    al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(avals));
            }
        }
        if (family == 2) { /* `surface synth` of a small map */
            al = (size_t)snprintf(args, sizeof args, "surface synth --out out.h5 --size %s",
                                  pick(3) ? "24" : ONE_OF(gvals));
            for (int k = pick(5); k > 0; k--) {
                al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(gopts));
                if (pick(5))
                    al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(gvals));
            }
        }
        if (surface) { /* `surface stats` on a small random grid */
            char grid[512];
            size_t gl = 0;
            int nx = 2 + pick(4), ny = 2 + pick(4);
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++)
                    gl += (size_t)snprintf(grid + gl, sizeof grid - gl, "%.6g%s",
                                           pick(30) ? unif(-1, 1) * pow(10, pick(9) - 4)
                                                    : (double)pick(2),
                                           i + 1 < nx ? " " : "\n");
            write_bytes(path_in("grid.txt"), grid, gl);
            al = (size_t)snprintf(args, sizeof args, "surface stats%s%s",
                                  pick(4) ? " grid.txt" : "", pick(3) ? " --pixel-size 0.01" : "");
            for (int k = pick(4); k > 0; k--) {
                al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(sopts));
                if (pick(4))
                    al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(svals));
            }
        }
        for (int l = pick(4); l > 0; l--)
            cl += (size_t)snprintf(cfg + cl, sizeof cfg - cl, "%s=%s\n", ONE_OF(keys),
                                   ONE_OF(vals));
        write_bytes(path_in("cfg.ini"), cfg, cl);
        for (int k = family ? 0 : pick(6); k > 0; k--) {
            al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(opts));
            if (pick(4)) al += (size_t)snprintf(args + al, sizeof args - al, " %s", ONE_OF(vals));
        }
        outputs(0);
        int rc = run_cli(args, out, err, sizeof out);
        /* a sanitizer build exits 1 on a memory error: read what it says */
        if ((rc != 0 && rc != 1 && rc != 2) || strstr(err, "Sanitizer") ||
            strstr(err, "runtime error:"))
            fail_msg("case %ld: 'stiction %s' exited %d: %.300s", c, args, rc, err);
        if (rc != 0) {
            if (!*ws(err)) fail_msg("case %ld: 'stiction %s' failed silently", c, args);
            if (*ws(out))
                fail_msg("case %ld: 'stiction %s' failed but printed '%.200s'", c, args, out);
            const char *left = outputs(1);
            if (left) fail_msg("case %ld: 'stiction %s' failed but left %s", c, args, left);
            continue;
        }
        if (family == 2) { /* what synth wrote, the library reads back */
            srf_map *m = NULL;
            if (srf_map_read(path_in("out.h5"), &m) != STC_OK)
                fail_msg("case %ld: 'stiction %s' wrote an unreadable out.h5: %s", c, args,
                         stc_errmsg());
            assert_map_sane(m, c);
            srf_map_destroy(&m);
            ok_synth++;
        }
        const char *bad = non_number(out, args);
        if (bad) fail_msg("case %ld: 'stiction %s' printed '%s': %.300s", c, args, bad, out);
        if (strstr(args, "--json") && !strstr(args, "--csv") && *ws(out) &&
            !strstr(args, "--output"))
            assert_json(out);
        ok++;
        ok_surface += surface;
        ok_asperity += family == 3;
        ok_predict += family == 4;
    }
    printf("# CLI: %ld runs of 'stiction formulas', 'surface stats|synth|predict' and "
           "'asperity' with random options, configs and grids: %ld succeeded (%ld stats, %ld "
           "synth, %ld predict, %ld asperity), the rest refused with a message\n", n, ok,
           ok_surface, ok_synth, ok_predict, ok_asperity);
    assert_true(ok_surface > 0 && ok_synth > 0 && ok_asperity > 0 && ok_predict > 0 &&
                ok > ok_surface + ok_synth + ok_asperity + ok_predict && ok < n);
}

/* ------------------------------------------------------------ driver */

static int setup(void **state)
{
    (void)state;
    const char *e = getenv("STICTION_FUZZ_CASES");
    if (e && *e) scale = strtol(e, NULL, 10) > 0 ? strtol(e, NULL, 10) : 1;
    snprintf(dir, sizeof dir, "%s/stiction-fuzz-XXXXXX", test_tmpdir());
    if (!mkdtemp(dir)) return -1;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* the test's own HDF5 calls may fail quietly */
    (void)cli_capture;                     /* cli_util.h helper this program does not need */
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.') remove_tree(path_in(e->d_name));
    if (d) closedir(d);
    rmdir(dir);
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ini),
        cmocka_unit_test(test_text_grids),
        cmocka_unit_test(test_text_mutations),
        cmocka_unit_test(test_hdf5_files),
        cmocka_unit_test(test_cli),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
