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

#endif
