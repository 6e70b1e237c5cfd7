/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static _Thread_local char gf_detail[GF_DETAIL_MAX];

const char *gf_strerror(gf_status status)
{
    switch (status) {
    case GF_SUCCESS: return "success";
    case GF_EINVAL: return "invalid argument";
    case GF_EDOM: return "parameter outside its allowed range";
    case GF_EPHYS: return "physically impossible parameters";
    case GF_ENONFINITE: return "NaN or infinite input";
    case GF_ENOTFOUND: return "unknown name";
    case GF_ENOMEM: return "out of memory";
    case GF_ENOCONV: return "iteration did not converge";
    case GF_EGSL: return "GSL routine failed";
    case GF_EIO: return "file input/output failed";
    }
    return "unknown status code";
}

const char *gf_error_detail(void) { return gf_detail; }

gf_status gf_fail(gf_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(gf_detail, sizeof gf_detail, fmt, ap);
    va_end(ap);
    return status;
}

gf_status gf_check_range(const char *name, double value, double lo, double hi)
{
    if (!isfinite(value))
        return gf_fail(GF_ENONFINITE, "%s = %g is not a finite number", name, value);
    if (value < lo || value > hi)
        return gf_fail(GF_EDOM, "%s = %g is outside the allowed range [%g, %g]",
                       name, value, lo, hi);
    return GF_SUCCESS;
}

int gf_parse_number(const char *t, double *v)
{
    char *end;
    while (isspace((unsigned char)*t))
        ++t;
    errno = 0;
    *v = strtod(t, &end);
    if (end == t)
        return 0;
    while (*end && isspace((unsigned char)*end))
        ++end;
    return !*end && !errno && isfinite(*v);
}
