/* Helper of the tests that compare against the reference data in data/
 * (data/README.md): read named numeric columns of a CSV file.  The Makefile
 * passes the source tree's data directory as STC_DATA_DIR.  Header-only. */
#ifndef STICTION_TESTS_DATA_UTIL_H
#define STICTION_TESTS_DATA_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef STC_DATA_DIR
#define STC_DATA_DIR "data"
#endif

enum { DATA_MAX_COLS = 16, DATA_LINE = 1024 };

/* Split line (modified in place) at commas into at most DATA_MAX_COLS
 * fields; a trailing newline is dropped.  Returns the field count. */
static int data_split(char *line, char *field[DATA_MAX_COLS])
{
    int n = 0;
    line[strcspn(line, "\r\n")] = '\0';
    for (char *s = line; n < DATA_MAX_COLS; n++) {
        field[n] = s;
        char *c = strchr(s, ',');
        if (!c) return n + 1;
        *c = '\0';
        s = c + 1;
    }
    return n;
}

/* Read the columns named in cols[0 .. ncol-1] of STC_DATA_DIR/file into
 * out[j][0 .. max-1] (out borrowed, filled row by row).  Every named column
 * must exist and every value must parse completely as a number.  Returns
 * the row count, or -1 (message on stderr) if the file cannot be read, a
 * column is missing, a value is not a number or there are more than max
 * rows. */
static int data_read_columns(const char *file, int ncol, const char *const cols[],
                             double *out[], int max)
{
    char path[512], line[DATA_LINE], *field[DATA_MAX_COLS];
    int idx[DATA_MAX_COLS], rows = 0;
    snprintf(path, sizeof path, "%s/%s", STC_DATA_DIR, file);
    FILE *f = fopen(path, "r");
    if (!f || ncol > DATA_MAX_COLS || !fgets(line, sizeof line, f)) {
        fprintf(stderr, "data_read_columns: cannot read %s\n", path);
        if (f) fclose(f);
        return -1;
    }
    int nf = data_split(line, field);
    for (int j = 0; j < ncol; j++) {
        idx[j] = -1;
        for (int i = 0; i < nf; i++)
            if (strcmp(field[i], cols[j]) == 0) idx[j] = i;
        if (idx[j] < 0) {
            fprintf(stderr, "data_read_columns: %s has no column %s\n", path, cols[j]);
            fclose(f);
            return -1;
        }
    }
    while (fgets(line, sizeof line, f)) {
        if (line[strspn(line, " \t\r\n")] == '\0') continue;
        nf = data_split(line, field);
        if (rows == max) goto bad;
        for (int j = 0; j < ncol; j++) {
            char *end;
            if (idx[j] >= nf) goto bad;
            out[j][rows] = strtod(field[idx[j]], &end);
            if (end == field[idx[j]] || *end != '\0') goto bad;
        }
        rows++;
    }
    fclose(f);
    return rows;
bad:
    fprintf(stderr, "data_read_columns: %s row %d: bad value or too many rows\n", path, rows + 1);
    fclose(f);
    return -1;
}

#endif
