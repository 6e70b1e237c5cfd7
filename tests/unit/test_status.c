/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The number parser of granflow's programs and files (gf_parse_number,
 * granflow/status.h): a whole token as a finite number, nothing else. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include "../gf_test.h"

#include "granflow/status.h"

static void whole_tokens_are_numbers(void **state)
{
    (void)state;
    double v = 0;
    assert_int_equal(gf_parse_number("0.5", &v), 1);
    assert_true(v == 0.5);
    assert_int_equal(gf_parse_number("  -2.5e3\t\n", &v), 1);
    assert_true(v == -2500);
    assert_int_equal(gf_parse_number("1e-300", &v), 1);
    assert_true(v == 1e-300);
}

static void anything_else_is_refused(void **state)
{
    (void)state;
    const char *bad[] = {"", "   ", "0.5inf", "1e", "2,5", "abc", "1 2", "nan", "inf", "-inf", "1e999", "0x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        double v = 0;
        if (gf_parse_number(bad[i], &v) != 0)
            fail_msg("'%s' was read as the number %g", bad[i], v);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(whole_tokens_are_numbers),
        cmocka_unit_test(anything_else_is_refused),
    };
    return gf_run_tests("status", tests, NULL, NULL);
}
