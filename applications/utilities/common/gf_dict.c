/* SPDX-License-Identifier: GPL-3.0-or-later */
/* granflow — OpenFOAM-style dictionaries for the C programs (gf_dict.h). */
#define _GNU_SOURCE /* program_invocation_short_name */
#include "gf_dict.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/status.h" /* gf_parse_number */

typedef struct lexer {
    const char *s;
    size_t i, n;
    int line;
    const char *path;
    char *err;
    size_t errsize;
} lexer;

static char *dup_range(const char *s, size_t n)
{
    char *r = malloc(n + 1);
    if (r) {
        memcpy(r, s, n);
        r[n] = '\0';
    }
    return r;
}

/* The next token into *tok (malloc'ed); 0 at the end, -1 on an error */
static int next_token(lexer *L, char **tok, int *line)
{
    for (;;) {
        while (L->i < L->n && isspace((unsigned char)L->s[L->i])) {
            if (L->s[L->i] == '\n') ++L->line;
            ++L->i;
        }
        if (L->i + 1 < L->n && L->s[L->i] == '/' && L->s[L->i + 1] == '/') {
            while (L->i < L->n && L->s[L->i] != '\n') ++L->i;
            continue;
        }
        if (L->i + 1 < L->n && L->s[L->i] == '/' && L->s[L->i + 1] == '*') {
            const int start = L->line;
            L->i += 2;
            while (L->i + 1 < L->n && !(L->s[L->i] == '*' && L->s[L->i + 1] == '/')) {
                if (L->s[L->i] == '\n') ++L->line;
                ++L->i;
            }
            if (L->i + 1 >= L->n) {
                snprintf(L->err, L->errsize, "%s:%d: a comment /* that is never closed", L->path, start);
                return -1;
            }
            L->i += 2;
            continue;
        }
        break;
    }
    if (L->i >= L->n) return 0;
    *line = L->line;
    const char c = L->s[L->i];
    if (strchr("{};()", c)) {
        *tok = dup_range(&L->s[L->i], 1);
        ++L->i;
        return *tok ? 1 : -1;
    }
    if (c == '"') {
        const size_t b = ++L->i;
        while (L->i < L->n && L->s[L->i] != '"' && L->s[L->i] != '\n') ++L->i;
        if (L->i >= L->n || L->s[L->i] != '"') {
            snprintf(L->err, L->errsize, "%s:%d: a string \" that is not closed on its line", L->path, *line);
            return -1;
        }
        *tok = dup_range(&L->s[b], L->i - b);
        ++L->i;
        return *tok ? 1 : -1;
    }
    if (c == '#' || c == '$') {
        snprintf(L->err, L->errsize,
                 "%s:%d: '%c' directives and variables are not read by this program; write the value",
                 L->path, *line, c);
        return -1;
    }
    const size_t b = L->i;
    while (L->i < L->n && !isspace((unsigned char)L->s[L->i]) && !strchr("{};()\"", L->s[L->i])) {
        if (L->s[L->i] == '/' && L->i + 1 < L->n && (L->s[L->i + 1] == '/' || L->s[L->i + 1] == '*')) break;
        ++L->i;
    }
    *tok = dup_range(&L->s[b], L->i - b);
    return *tok ? 1 : -1;
}

static void free_entries(gf_dict *d)
{
    for (size_t k = 0; k < d->n; ++k) {
        free(d->e[k].key);
        for (size_t t = 0; t < d->e[k].ntok; ++t) free(d->e[k].tok[t]);
        free(d->e[k].tok);
        if (d->e[k].sub) gf_dict_free(d->e[k].sub);
    }
    free(d->e);
}

void gf_dict_free(gf_dict *d)
{
    if (!d) return;
    free_entries(d);
    free(d->name);
    free(d);
}

static gf_dict *new_dict(const char *path, const char *parent, const char *key)
{
    gf_dict *d = calloc(1, sizeof *d);
    if (!d) return NULL;
    d->path = path;
    const size_t n = strlen(parent) + strlen(key) + 2;
    d->name = malloc(n);
    if (!d->name) {
        free(d);
        return NULL;
    }
    snprintf(d->name, n, "%s%s%s", parent, *parent ? "/" : "", key);
    return d;
}

/* entries until '}' (closing = 1) or the end (closing = 0) */
static int parse_entries(lexer *L, gf_dict *d, int closing)
{
    size_t cap = 0;
    for (;;) {
        char *key = NULL;
        int line = 0;
        const int r = next_token(L, &key, &line);
        if (r < 0) return -1;
        if (r == 0) {
            if (closing) {
                snprintf(L->err, L->errsize, "%s: dictionary %s is not closed by '}' before the end of the file",
                         L->path, d->name);
                return -1;
            }
            return 0;
        }
        if (strcmp(key, "}") == 0) {
            free(key);
            if (closing) return 0;
            snprintf(L->err, L->errsize, "%s:%d: a '}' without its '{'", L->path, line);
            return -1;
        }
        if (strchr("{;()", key[0])) {
            snprintf(L->err, L->errsize, "%s:%d: '%s' where a keyword was expected", L->path, line, key);
            free(key);
            return -1;
        }
        for (size_t k = 0; k < d->n; ++k)
            if (strcmp(d->e[k].key, key) == 0) {
                snprintf(L->err, L->errsize, "%s:%d: %s%s%s is given twice (line %d and %d)", L->path, line,
                         d->name, *d->name ? "/" : "", key, d->e[k].line, line);
                free(key);
                return -1;
            }
        if (d->n == cap) {
            cap = cap ? 2 * cap : 8;
            gf_dict_entry *e = realloc(d->e, cap * sizeof *e);
            if (!e) {
                free(key);
                snprintf(L->err, L->errsize, "%s: out of memory", L->path);
                return -1;
            }
            d->e = e;
        }
        gf_dict_entry *e = &d->e[d->n++];
        memset(e, 0, sizeof *e);
        e->key = key;
        e->line = line;
        /* a sub-dictionary or a value up to ';' */
        char *t = NULL;
        int tl = 0;
        size_t tcap = 0;
        int depth = 0;
        for (;;) {
            const int q = next_token(L, &t, &tl);
            if (q < 0) return -1;
            if (q == 0) {
                snprintf(L->err, L->errsize, "%s:%d: %s: no ';' before the end of the file", L->path, line, key);
                return -1;
            }
            if (strcmp(t, "{") == 0 && e->ntok == 0) {
                free(t);
                e->sub = new_dict(L->path, d->name, key);
                if (!e->sub) return -1;
                if (parse_entries(L, e->sub, 1) != 0) return -1;
                break;
            }
            if (strcmp(t, ";") == 0 && depth == 0) {
                free(t);
                if (e->ntok == 0) {
                    snprintf(L->err, L->errsize, "%s:%d: %s has no value", L->path, line, key);
                    return -1;
                }
                break;
            }
            if (strcmp(t, "{") == 0 || strcmp(t, "}") == 0 || strcmp(t, ";") == 0) {
                snprintf(L->err, L->errsize, "%s:%d: %s: '%s' in a value (a ';' missing before it?)", L->path,
                         tl, key, t);
                free(t);
                return -1;
            }
            if (strcmp(t, "(") == 0) ++depth;
            if (strcmp(t, ")") == 0 && --depth < 0) {
                snprintf(L->err, L->errsize, "%s:%d: %s: a ')' without its '('", L->path, tl, key);
                free(t);
                return -1;
            }
            if (e->ntok == tcap) {
                tcap = tcap ? 2 * tcap : 4;
                char **nt = realloc(e->tok, tcap * sizeof *nt);
                if (!nt) {
                    free(t);
                    return -1;
                }
                e->tok = nt;
            }
            e->tok[e->ntok++] = t;
        }
        if (strcmp(key, "FoamFile") == 0) e->used = 1; /* the header */
    }
}

gf_dict *gf_dict_read(const char *path, char *err, size_t errsize)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errsize, "%s: cannot read the file", path);
        return NULL;
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 4096 > cap) {
            cap = cap ? 2 * cap : 65536;
            char *b = realloc(buf, cap);
            if (!b) {
                free(buf);
                fclose(f);
                snprintf(err, errsize, "%s: out of memory", path);
                return NULL;
            }
            buf = b;
        }
        const size_t r = fread(buf + n, 1, cap - n, f);
        n += r;
        if (r == 0) break;
    }
    fclose(f);
    lexer L = {buf, 0, n, 1, path, err, errsize};
    gf_dict *d = new_dict(path, "", "");
    if (!d || parse_entries(&L, d, 0) != 0) {
        if (!d) snprintf(err, errsize, "%s: out of memory", path);
        gf_dict_free(d);
        free(buf);
        return NULL;
    }
    free(buf);
    return d;
}

gf_dict_entry *gf_dict_find(const gf_dict *d, const char *key)
{
    if (!d) return NULL;
    for (size_t k = 0; k < d->n; ++k)
        if (strcmp(d->e[k].key, key) == 0) {
            d->e[k].used = 1;
            return &d->e[k];
        }
    return NULL;
}

const gf_dict_entry *gf_dict_unused(const gf_dict *d, const gf_dict **in)
{
    for (size_t k = 0; k < d->n; ++k) {
        if (!d->e[k].used) {
            if (in) *in = d;
            return &d->e[k];
        }
        if (d->e[k].sub && strcmp(d->e[k].key, "FoamFile") != 0) {
            const gf_dict_entry *u = gf_dict_unused(d->e[k].sub, in);
            if (u) return u;
        }
    }
    return NULL;
}

/*---------------------------------------------------------- typed readers --*/

void gf_dict_refuse(const char *path, const gf_dict_entry *e, const char *key, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: %s", program_invocation_short_name, path);
    if (e) fprintf(stderr, ":%d", e->line);
    fprintf(stderr, ": %s: ", key);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    exit(1);
}

void gf_dict_key_path(const gf_dict *d, const char *key, char *out, size_t size)
{
    snprintf(out, size, "%s%s%s", d->name, *d->name ? "/" : "", key);
}

double gf_dict_number(const gf_dict *d, const char *key, double def, double lo, double hi)
{
    char full[256];
    gf_dict_key_path(d, key, full, sizeof full);
    const gf_dict_entry *e = gf_dict_find(d, key);
    if (!e) {
        if (isnan(def)) gf_dict_refuse(d->path, NULL, full, "required (a number in [%g, %g])", lo, hi);
        return def;
    }
    double v;
    if (e->sub || e->ntok != 1 || !gf_parse_number(e->tok[0], &v))
        gf_dict_refuse(d->path, e, full, "expected one number in [%g, %g]", lo, hi);
    if (!(v >= lo && v <= hi)) gf_dict_refuse(d->path, e, full, "%g is outside the allowed range [%g, %g]", v, lo, hi);
    return v;
}

long gf_dict_whole(const gf_dict *d, const char *key, double def, double lo, double hi)
{
    const double v = gf_dict_number(d, key, def, lo, hi);
    if (v != floor(v)) {
        char full[256];
        gf_dict_key_path(d, key, full, sizeof full);
        gf_dict_refuse(d->path, gf_dict_find(d, key), full, "%g is not a whole number in [%g, %g]", v, lo, hi);
    }
    return (long)v;
}

const char *gf_dict_word(const gf_dict *d, const char *key, const char *def, size_t maxlen)
{
    char full[256];
    gf_dict_key_path(d, key, full, sizeof full);
    const gf_dict_entry *e = gf_dict_find(d, key);
    if (!e) return def;
    if (e->sub || e->ntok != 1 || !*e->tok[0]) gf_dict_refuse(d->path, e, full, "expected one word or \"file name\"");
    if (maxlen && strlen(e->tok[0]) > maxlen) gf_dict_refuse(d->path, e, full, "longer than %zu characters", maxlen);
    return e->tok[0];
}

int gf_dict_bool(const gf_dict *d, const char *key, int def)
{
    char full[256];
    gf_dict_key_path(d, key, full, sizeof full);
    const gf_dict_entry *e = gf_dict_find(d, key);
    if (!e) return def;
    static const char *yes[] = {"yes", "true", "on", "1"}, *no[] = {"no", "false", "off", "0"};
    if (!e->sub && e->ntok == 1)
        for (size_t k = 0; k < 4; ++k) {
            if (strcmp(e->tok[0], yes[k]) == 0) return 1;
            if (strcmp(e->tok[0], no[k]) == 0) return 0;
        }
    gf_dict_refuse(d->path, e, full, "expected yes or no");
}

size_t gf_dict_numbers(const gf_dict_entry *e, const char *path, const char *key, double *v, size_t max, double lo,
                       double hi)
{
    if (e->sub || e->ntok < 3 || strcmp(e->tok[0], "(") || strcmp(e->tok[e->ntok - 1], ")"))
        gf_dict_refuse(path, e, key, "expected a list ( n1 n2 ... ) of numbers in [%g, %g]", lo, hi);
    const size_t n = e->ntok - 2;
    if (n > max) gf_dict_refuse(path, e, key, "%zu values: at most %zu allowed", n, max);
    for (size_t k = 0; k < n; ++k) {
        if (!gf_parse_number(e->tok[k + 1], &v[k])) gf_dict_refuse(path, e, key, "'%s' is not a number", e->tok[k + 1]);
        if (!(v[k] >= lo && v[k] <= hi))
            gf_dict_refuse(path, e, key, "%g is outside the allowed range [%g, %g]", v[k], lo, hi);
    }
    return n;
}

const gf_dict *gf_dict_sub(const gf_dict *d, const char *key, int required)
{
    char full[256];
    gf_dict_key_path(d, key, full, sizeof full);
    const gf_dict_entry *e = gf_dict_find(d, key);
    if (!e) {
        if (required) gf_dict_refuse(d->path, NULL, full, "required: a dictionary { ... }");
        return NULL;
    }
    if (!e->sub) gf_dict_refuse(d->path, e, full, "expected a dictionary { ... }");
    return e->sub;
}
