/* Minimal streaming JSON writer for the CLI. */
#include <math.h>
#include "cli.h"

void cj_init(cli_json *j, FILE *f)
{
    j->f = f;
    j->depth = 0;
    j->count[0] = 0;
}

static void put_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c == '\n') fputs("\\n", f);
        else if (c < 0x20) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

static void member(cli_json *j, const char *key)
{
    if (j->count[j->depth]++ > 0) fputc(',', j->f);
    if (j->depth > 0) fprintf(j->f, "\n%*s", 2 * j->depth, "");
    if (key) {
        put_string(j->f, key);
        fputs(": ", j->f);
    }
}

static void open_(cli_json *j, const char *key, char c)
{
    member(j, key);
    fputc(c, j->f);
    if (j->depth < 31) j->count[++j->depth] = 0;
}

static void close_(cli_json *j, char c)
{
    int had = j->count[j->depth];
    if (j->depth > 0) j->depth--;
    if (had) fprintf(j->f, "\n%*s", 2 * j->depth, "");
    fputc(c, j->f);
}

void cj_obj(cli_json *j, const char *key) { open_(j, key, '{'); }
void cj_end_obj(cli_json *j) { close_(j, '}'); }
void cj_arr(cli_json *j, const char *key) { open_(j, key, '['); }
void cj_end_arr(cli_json *j) { close_(j, ']'); }

void cj_num(cli_json *j, const char *key, double v)
{
    member(j, key);
    if (isfinite(v)) fprintf(j->f, "%.10g", v);
    else fputs("null", j->f);
}

void cj_int(cli_json *j, const char *key, long v)
{
    member(j, key);
    fprintf(j->f, "%ld", v);
}

void cj_str(cli_json *j, const char *key, const char *v)
{
    member(j, key);
    if (v) put_string(j->f, v);
    else fputs("null", j->f);
}

void cj_bool(cli_json *j, const char *key, int v)
{
    member(j, key);
    fputs(v ? "true" : "false", j->f);
}

void cj_null(cli_json *j, const char *key)
{
    member(j, key);
    fputs("null", j->f);
}

void cj_params(cli_json *j, const stc_params *p)
{
    stc_material su, co;
    stc_params_materials(p, &su, &co);
    cj_num(j, "R_mm", p->R);
    cj_num(j, "t_over_R", p->t_over_R);
    cj_num(j, "t_mm", stc_params_t(p));
    cj_num(j, "E_su_MPa", su.E);
    cj_num(j, "E_co_MPa", co.E);
    cj_num(j, "E_ratio", p->E_ratio);
    cj_num(j, "Y_su_MPa", su.Y);
    cj_num(j, "Y_co_MPa", co.Y);
    cj_num(j, "nu_su", su.nu);
    cj_num(j, "nu_co", co.nu);
}

void cj_done(cli_json *j) { fputc('\n', j->f); }
