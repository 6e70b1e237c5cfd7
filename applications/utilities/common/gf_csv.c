/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Strict number and CSV parsing shared by granflow's C programs (gf_csv.h). */
#include "gf_csv.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int gf_csv_read(const char *path, const char *const *cols, const int *nonneg, int ncols, double **out,
                size_t *rows, char *err, size_t errsize)
{
#define FAIL(...) do { snprintf(err, errsize, __VA_ARGS__); if (f) fclose(f); \
                       for (int c_ = 0; c_ < ncols; ++c_) { free(out[c_]); out[c_] = NULL; } return -1; } while (0)
    for (int c = 0; c < ncols; ++c)
        out[c] = NULL;
    FILE *f = fopen(path, "r");
    if (!f)
        FAIL("cannot open '%s': %s", path, strerror(errno));
    char line[4096], head[4096];
    size_t lineno = 0;
    do {
        if (!fgets(head, sizeof head, f))
            FAIL("'%s' has no header line", path);
        ++lineno;
    } while (head[0] == '#');
    int idx[8], nhead = 0;
    char *names[64];
    for (char *t = strtok(head, ",\r\n"); t; t = strtok(NULL, ",\r\n")) {
        while (isspace((unsigned char)*t))
            ++t;
        if (nhead == 64)
            FAIL("'%s' line %zu: more than 64 columns", path, lineno);
        names[nhead++] = t;
    }
    for (int c = 0; c < ncols; ++c) {
        idx[c] = -1;
        for (int k = 0; k < nhead; ++k)
            if (!strcmp(names[k], cols[c]))
                idx[c] = k;
        if (idx[c] < 0)
            FAIL("'%s' has no column '%s' in its header (line %zu)", path, cols[c], lineno);
    }
    size_t n = 0, cap = 256;
    for (int c = 0; c < ncols; ++c)
        if (!(out[c] = malloc(cap * sizeof **out)))
            FAIL("out of memory reading '%s'", path);
    while (fgets(line, sizeof line, f)) {
        ++lineno;
        if (!strchr(line, '\n') && !feof(f))
            FAIL("'%s' line %zu: longer than %zu characters", path, lineno, sizeof line - 2);
        if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
            continue;
        double v[64];
        int k = 0;
        /* split on every comma, so that an empty field is an error, not skipped */
        for (char *t = line, *c; ; t = c + 1) {
            c = strchr(t, ',');
            if (c)
                *c = 0;
            else
                t[strcspn(t, "\r\n")] = 0;
            if (k == 64 || k == nhead)
                FAIL("'%s' line %zu: more values than the %d columns of the header", path, lineno,
                    nhead);
            if (!gf_parse_number(t, &v[k]))
                FAIL("'%s' line %zu, column %d (%s): '%s' is not a finite number", path, lineno,
                    k + 1, names[k], t);
            ++k;
            if (!c)
                break;
        }
        if (k != nhead)
            FAIL("'%s' line %zu: %d values, the header has %d columns", path, lineno, k, nhead);
        for (int c = 0; c < ncols; ++c)
            if (nonneg[c] && v[idx[c]] < 0.0)
                FAIL("'%s' line %zu: %s = %g is negative (must be >= 0)", path, lineno, cols[c],
                    v[idx[c]]);
        if (n > 0 && !(v[idx[0]] > out[0][n - 1]))
            FAIL("'%s' line %zu: %s = %g does not increase (previous row %g); rows must be "
                "sorted by strictly increasing %s", path, lineno, cols[0], v[idx[0]], out[0][n - 1],
                cols[0]);
        if (n == cap) {
            cap *= 2;
            for (int c = 0; c < ncols; ++c)
                if (!(out[c] = realloc(out[c], cap * sizeof **out)))
                    FAIL("out of memory reading '%s'", path);
        }
        for (int c = 0; c < ncols; ++c)
            out[c][n] = v[idx[c]];
        ++n;
    }
    fclose(f);
    *rows = n;
    return 0;
#undef FAIL
}

