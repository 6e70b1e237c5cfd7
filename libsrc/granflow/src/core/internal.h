/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal helpers of libgranflow: not installed, not part of the API. */
#ifndef GRANFLOW_INTERNAL_H
#define GRANFLOW_INTERNAL_H

/* The longest error detail gf_fail keeps (gf_error_detail): room for a few
 * file names of any length a message names (case paths of several hundred
 * characters, PATH_MAX each at most). */
#define GF_DETAIL_MAX 16384

#include "granflow/constants.h"
#include "granflow/status.h"

/* Record a formatted detail message for gf_error_detail() and return status. */
gf_status gf_fail(gf_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* GF_SUCCESS when lo <= value <= hi and finite, otherwise a message naming
 * the parameter, its value and the range.  */
gf_status gf_check_range(const char *name, double value, double lo, double hi);

#endif
