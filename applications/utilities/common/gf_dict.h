/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — OpenFOAM-style dictionaries for the C programs (gfCalibrate's
 * system/calibrationDict): the subset a case's dictionaries use.
 *
 *     key   value ... ;          // a value: words, numbers, "strings", ( lists )
 *     key { key value; ... }     // a sub-dictionary
 *     / * comments * /, // comments; a FoamFile { ... } header is skipped
 *
 * Directives (#include, #calc, $variables) are refused with the line, not
 * ignored.  Every entry remembers its line; the readers mark what they read
 * so that a program can refuse a key it does not know (gf_dict_unused),
 * never ignore it silently.
 */
#ifndef GF_DICT_H
#define GF_DICT_H

#include <stddef.h>

typedef struct gf_dict gf_dict;

typedef struct gf_dict_entry {
    char *key;
    int line;
    gf_dict *sub;    /* a sub-dictionary, or NULL */
    char **tok;      /* the value's tokens ("(" and ")" are tokens), quotes removed */
    size_t ntok;
    int used;
} gf_dict_entry;

struct gf_dict {
    const char *path; /* the file (for messages) */
    char *name;       /* the dictionary's key path ("" for the top) */
    gf_dict_entry *e;
    size_t n;
};

/* The dictionary in a file; NULL with a message naming the file and line in
 * err. */
gf_dict *gf_dict_read(const char *path, char *err, size_t errsize);
void gf_dict_free(gf_dict *d);

/* The entry named key (marked used), or NULL. */
gf_dict_entry *gf_dict_find(const gf_dict *d, const char *key);

/* The first entry of d or its sub-dictionaries that no reader marked used;
 * NULL when every one was. */
const gf_dict_entry *gf_dict_unused(const gf_dict *d, const gf_dict **in);

/* ---- typed readers that refuse a bad value and end the program ----------
 * A refusal prints "PROG: FILE:LINE: KEY: what is wrong (the allowed range)"
 * on stderr, KEY the full key path (scenarios/a/d0Star), and exits with
 * status 1; PROG is the program's name (program_invocation_short_name). */

/* Refuse entry e (NULL: a missing key, no line) of the dictionary file path. */
void gf_dict_refuse(const char *path, const gf_dict_entry *e, const char *key, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));

/* The full key path of key in d ("" at the top: key; else name/key). */
void gf_dict_key_path(const gf_dict *d, const char *key, char *out, size_t size);

/* A number key of d in [lo, hi]; def when absent (def NAN: required). */
double gf_dict_number(const gf_dict *d, const char *key, double def, double lo, double hi);

/* A whole number key of d in [lo, hi]; def when absent (def NAN: required). */
long gf_dict_whole(const gf_dict *d, const char *key, double def, double lo, double hi);

/* A one-word (or "quoted") key of d; def when absent (may be NULL).  maxlen
 * > 0: refused when longer. */
const char *gf_dict_word(const gf_dict *d, const char *key, const char *def, size_t maxlen);

/* A yes/no key of d (yes true on 1, no false off 0); def when absent. */
int gf_dict_bool(const gf_dict *d, const char *key, int def);

/* A list ( n1 n2 ... ) of at most max numbers in [lo, hi] of entry e (key
 * its full path, for the messages) into v; their count. */
size_t gf_dict_numbers(const gf_dict_entry *e, const char *path, const char *key, double *v, size_t max, double lo,
                       double hi);

/* A sub-dictionary key of d; NULL when absent and not required. */
const gf_dict *gf_dict_sub(const gf_dict *d, const char *key, int required);

#endif
