/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — strict number and CSV parsing for the C programs (granflow1d,
 * granflowExact): one parser, so that every input file is validated alike.
 */
#ifndef GF_CSV_H
#define GF_CSV_H

#include <stddef.h>

#include "granflow/status.h" /* gf_parse_number: the numbers in the tables */

/* A CSV table with a header naming the columns ('#' lines skipped): every
 * row has one finite number per header column, the first requested column
 * is strictly increasing, and the columns with nonneg[c] = 1 are >= 0.
 * out[c] receives a malloc'ed array of the requested column c, *rows their
 * length.  0 on success; -1 with a message naming the file, line and column
 * in err (nothing allocated). */
int gf_csv_read(const char *path, const char *const *cols, const int *nonneg, int ncols, double **out,
                size_t *rows, char *err, size_t errsize);

#endif
