/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared helpers of the granflow cmocka tests.
 * cmocka 1.1.5 (Debian bookworm) compares assert_float_equal in single
 * precision; assert_close compares doubles to an absolute tolerance and
 * prints both values in full when it fails. */
#ifndef GF_TEST_H
#define GF_TEST_H

#include <fnmatch.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

static inline void gf_assert_close(double a, double b, double tol, const char *ea, const char *eb,
                                   const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) { /* also fails on NaN */
        print_error("%s = %.17g but %s = %.17g: |difference| = %.3g > tolerance %.3g\n", ea, a, eb,
                    b, fabs(a - b), tol);
        _fail(file, line);
    }
}
#define assert_close(a, b, tol) gf_assert_close((a), (b), (tol), #a, #b, __FILE__, __LINE__)

/* One machine-readable line per verified quantity, read by doc/make-verification:
 *   VERIFY|test|problem|reference|quantity|value|relation bound
 * (value and bound %.3g; relation <, <=, >, >= or = as the test asserts it).
 * gf_verify prints it for the calling test; the problem is a printf format. */
static inline void gf_verify_line(const char *test, const char *reference, const char *quantity, double value,
                                  const char *relation, double bound, const char *fmt, ...)
{
    char problem[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(problem, sizeof problem, fmt, ap);
    va_end(ap);
    printf("VERIFY|%s|%s|%s|%s|%.3g|%s %.3g\n", test, problem, reference, quantity, value, relation, bound);
}
#define gf_verify(reference, quantity, value, relation, bound, ...)                                         \
    gf_verify_line(__func__, (reference), (quantity), (value), (relation), (bound), __VA_ARGS__)

/* gf_run_tests: cmocka_run_group_tests_name, with the cases chosen by the
 * environment (the program's name is its source file's, test_*.c):
 *   GF_TEST_LIST=1       prints "program case" for every case, runs none
 *   GF_TEST_FILTER=a,b   runs the cases that one of the patterns matches
 *                        (a comma list of names or shell wildcards)
 *   GF_TEST_FILTER=-a,b  runs every case but those
 *   GF_TEST_RECORD=file  appends "program case" for each case it runs
 * A pattern that matches no case is an error (exit 2): a misspelt name would
 * otherwise leave a case unrun.  ./Alltest runs the cases of
 * tests/long-tests.txt optimised and the others under the sanitizers this
 * way, and checks with the lists and records that each case ran once. */
#define gf_run_tests(group, tests, setup, teardown)                                               \
    gf_run_tests_((group), (tests), sizeof(tests) / sizeof((tests)[0]), (setup), (teardown), \
                  __FILE__)

static inline int gf_run_tests_(const char *group, const struct CMUnitTest *tests, size_t n,
                                CMFixtureFunction setup, CMFixtureFunction teardown,
                                const char *file)
{
    const char *prog = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
    const int prog_len = (int)strcspn(prog, ".");
    if (getenv("GF_TEST_LIST")) {
        for (size_t i = 0; i < n; ++i)
            printf("%.*s %s\n", prog_len, prog, tests[i].name);
        return 0;
    }
    const char *filter = getenv("GF_TEST_FILTER");
    const int exclude = filter && filter[0] == '-';
    char *patterns = strdup(filter ? filter + exclude : "");
    const size_t max_patterns = (patterns ? strlen(patterns) : 0) / 2 + 1;
    char **pattern = malloc(max_patterns * sizeof *pattern);
    size_t *hits = calloc(max_patterns, sizeof *hits); /* the cases each pattern matches */
    struct CMUnitTest *run = malloc((n + 1) * sizeof *run);
    if (!patterns || !pattern || !hits || !run) {
        fprintf(stderr, "gf_run_tests: out of memory\n");
        exit(2);
    }
    size_t n_patterns = 0, n_run = 0;
    char *save = NULL;
    for (char *p = strtok_r(patterns, ",", &save); p; p = strtok_r(NULL, ",", &save))
        pattern[n_patterns++] = p;
    for (size_t i = 0; i < n; ++i) {
        int match = 0;
        for (size_t j = 0; j < n_patterns; ++j)
            if (fnmatch(pattern[j], tests[i].name, 0) == 0) {
                match = 1;
                ++hits[j];
            }
        if (n_patterns == 0 || match != exclude)
            run[n_run++] = tests[i];
    }
    int bad = 0;
    for (size_t j = 0; j < n_patterns; ++j)
        if (!hits[j]) {
            fprintf(stderr, "GF_TEST_FILTER: %s matches no test case of %.*s\n", pattern[j],
                    prog_len, prog);
            bad = 1;
        }
    const char *record = getenv("GF_TEST_RECORD");
    FILE *f = record && !bad ? fopen(record, "a") : NULL;
    if (record && !bad && !f) {
        fprintf(stderr, "GF_TEST_RECORD: cannot open %s\n", record);
        bad = 1;
    }
    for (size_t i = 0; f && i < n_run; ++i)
        fprintf(f, "%.*s %s\n", prog_len, prog, run[i].name);
    if (f && fclose(f)) {
        fprintf(stderr, "GF_TEST_RECORD: cannot write %s\n", record);
        bad = 1;
    }
    int rc = bad ? 2 : 0;
    if (!bad && n_run)
        rc = _cmocka_run_group_tests(group, run, n_run, setup, teardown);
    else if (!bad)
        printf("[==========] %.*s: no test case selected\n", prog_len, prog);
    free(run);
    free(hits);
    free(pattern);
    free(patterns);
    return rc;
}

#endif
