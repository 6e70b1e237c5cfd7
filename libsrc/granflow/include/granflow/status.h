/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — status codes and error messages.
 *
 * Every fallible call of libgranflow returns a gf_status.  GF_SUCCESS is 0;
 * any other value names the class of failure, gf_strerror() gives its fixed
 * text and gf_error_detail() the specific reason of the most recent failure
 * in the calling thread (which parameter, its value and the allowed range),
 * in the way errno and strerror work.
 */
#ifndef GRANFLOW_STATUS_H
#define GRANFLOW_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gf_status {
    GF_SUCCESS = 0,
    GF_EINVAL,      /* invalid argument: null pointer, bad size, bad option */
    GF_EDOM,        /* parameter outside its allowed range */
    GF_EPHYS,       /* physically impossible combination of parameters */
    GF_ENONFINITE,  /* NaN or infinite input */
    GF_ENOTFOUND,   /* unknown name (friction law, parameter key, model) */
    GF_ENOMEM,      /* allocation failed */
    GF_ENOCONV,     /* an iteration (root finder, ...) did not converge */
    GF_EGSL,        /* a GSL routine reported an error */
    GF_EIO          /* reading or writing a file failed */
} gf_status;

/* Fixed, human-readable text for a status code ("success", ...). */
const char *gf_strerror(gf_status status);

/* Detail of the last failure in this thread, e.g.
 * "bed friction angle delta = 35 deg exceeds internal friction angle
 *  phi = 30 deg: ... K_act and K_pass are complex
 *  (doc/theory/savage-hutter.md, section 3); require delta <= phi".
 * Empty string when no failure has been recorded. */
const char *gf_error_detail(void);

/* A whole token as a finite number: surrounding blanks allowed, nothing else
 * ("0.5inf", "1e", "2,5" are not numbers).  1 on success, 0 otherwise (*v is
 * then unspecified).  The one number parser of granflow's programs and
 * files (gfPathAnalysis's options, granflow1d's and the CSV readers'). */
int gf_parse_number(const char *t, double *v);

#ifdef __cplusplus
}
#endif

#endif
