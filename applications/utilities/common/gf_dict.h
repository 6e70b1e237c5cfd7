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

#endif
