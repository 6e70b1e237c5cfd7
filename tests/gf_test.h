/* Shared helpers of the granflow cmocka tests.
 * cmocka 1.1.5 (Debian bookworm) compares assert_float_equal in single
 * precision; assert_close compares doubles to an absolute tolerance and
 * prints both values in full when it fails. */
#ifndef GF_TEST_H
#define GF_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
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

#endif
