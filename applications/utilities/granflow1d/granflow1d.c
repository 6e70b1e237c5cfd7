/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow1d — run a 1D Savage–Hutter case with libgranflow's RKDG or kinetic
 * solvers.
 *
 *   granflow1d CASE.ini [section.key=value ...]
 *
 *   granflow1d --keywords | --version
 *
 * Every key is read through its row of granflow1d_keys.h (default, range,
 * choices; --keywords prints them, doc/keywords.md); a key of no row is an
 * error.  The case file schema (every key optional unless stated; angles in
 * degrees):
 *
 *   [model]       epsilon (1), g (1), chi (1), rho (1: flow density, used by
 *                 mu_i's inertial number), earth_pressure (isotropic |
 *                 savageHutter), phi, delta (deg; savageHutter needs both),
 *                 friction (none | coulomb | mu_i | voellmy | chezy)
 *   [friction]    the law's coefficients (coulomb: mu, u0; mu_i: mu_s, mu_2,
 *                 I_0, d, rho_p, u0; voellmy: mu, xi, u0; chezy: C); coulomb
 *                 defaults to mu = tan(delta), u0 = 0
 *   [topography]  type (flat | chute | tabulated); flat: zeta; chute: zeta0,
 *                 zeta1 (0), x1 (17.5), x2 (21.5); tabulated: file (CSV x,zeta)
 *   [domain]      x_min (0), x_max (30), cells (256), bc_left, bc_right
 *                 (transmissive | wall | periodic)
 *   [initial]     shape: dam (x0, h_left, h_right, u_left, u_right) |
 *                 box (x1, x2, h_in, h_out) | semicircle (x0, radius) |
 *                 parabola (x0, K, l: max(K/10, K - l (x-x0)^2)) |
 *                 sinusoid (the kinetic paper's test 5) | file (CSV x,h,u) |
 *                 cap (x0, radius, depth: sqrt(r^2 - (x-x0)^2) - depth, >= 0)
 *   [solver]      method (rkdg | kinetic), degree (2), scheme (3),
 *                 kinetic_order (1 | 2: reconstruction and Heun; schemes 1, 3), cfl,
 *                 dt, limiter (moment | minmod | none; minmod is the rkdg
 *                 paper's eq. 13 with gamma), gamma (0.5), tvb_m (0 for
 *                 minmod, 1 for moment),
 *                 velocity_limiter (on | off), h_eps, h_semi,
 *                 moving_mesh (off | on: rkdg's front tracking, the cells span
 *                 the wet interval and its dry-front nodes move with the fronts;
 *                 the CSV then has a row per cell of that interval),
 *                 startup_levels (0; 1..5: the first phase on grids 2^L..2
 *                 times finer, for discontinuous initial data such as a dam
 *                 break on a dry bed), riemann_start (0; t_s > 0: a uniform dam on a
 *                 dry plane starts at t_s from its exact solution; output times
 *                 from t_s on); the other method's keys are checked and
 *                 named on stderr as ignored
 *   [output]      times (list), dir (.), name (case file stem), plot (no | yes),
 *                 exact (no | riemann: exact columns for a dam | dressler: Dressler's
 *                 solution for a dam on a dry bed with chezy friction), front_h (1e-3),
 *                 every (0: summary line every this much time)
 *
 * Output: NAME_t<time>.csv with columns x,h,u[,X,Z,Xs,Zs][,h_exact,u_exact]
 * (X,Z bed position, Xs,Zs free-surface point, rkdg appendix) and NAME.summary
 * (time, mass, max depth, front, tail, max speed, steps, CPU seconds, the
 * mass out through the ends and the balance's relative defect).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ini.h>

#include "gf_csv.h"
#include "granflow/granflow.h"
#include "granflow/sh1d.h"
#include "granflow/version.h"

#include "granflow1d_keys.h"

#define MAXE 256
#define MAXT 64

typedef struct entry {
    char section[32], key[32];
    char *value; /* any length (an output folder's path) */
    int used;
} entry;

typedef struct ini_data {
    entry e[MAXE];
    int n;
    const char *file;
} ini_data;

static const char *file_name = "";

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "granflow1d: %s: ", file_name);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    exit(2);
}

/* a copy of s (the program stops when memory is out) */
static char *dup_str(const char *s)
{
    char *c = strdup(s);
    if (!c)
        die("out of memory");
    return c;
}

/* a formatted path of any length, allocated (free it) */
static char *mkpath(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int r = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *buf = r < 0 ? NULL : malloc((size_t)r + 1);
    if (!buf)
        die("out of memory for an output path");
    va_start(ap, fmt);
    vsnprintf(buf, (size_t)r + 1, fmt, ap);
    va_end(ap);
    return buf;
}

static void put(ini_data *d, const char *sec, const char *key, const char *val)
{
    for (int i = 0; i < d->n; ++i)
        if (!strcmp(d->e[i].section, sec) && !strcmp(d->e[i].key, key)) {
            free(d->e[i].value);
            d->e[i].value = dup_str(val);
            return;
        }
    if (d->n == MAXE)
        die("too many entries");
    entry *e = &d->e[d->n++];
    if (strlen(sec) >= sizeof e->section || strlen(key) >= sizeof e->key)
        die("[%s] %s: a section or key name longer than %zu characters", sec, key, sizeof e->key - 1);
    snprintf(e->section, sizeof e->section, "%s", sec);
    snprintf(e->key, sizeof e->key, "%s", key);
    e->value = dup_str(val);
    e->used = 0;
}

static int handler(void *user, const char *sec, const char *key, const char *val)
{
    put(user, sec, key, val);
    return 1;
}

static entry *find(ini_data *d, const char *sec, const char *key)
{
    for (int i = 0; i < d->n; ++i)
        if (!strcmp(d->e[i].section, sec) && !strcmp(d->e[i].key, key)) {
            d->e[i].used = 1;
            return &d->e[i];
        }
    return NULL;
}

/* ---- keys: every one through its row of gf1d_keys (granflow1d_keys.h) ---- */
static const gf1d_key *key_row(const char *sec, const char *key)
{
    for (size_t i = 0; i < sizeof gf1d_keys / sizeof *gf1d_keys; ++i)
        if (!strcmp(gf1d_keys[i].section, sec) && !strcmp(gf1d_keys[i].key, key))
            return &gf1d_keys[i];
    fprintf(stderr, "granflow1d: internal error: [%s] %s has no row in granflow1d_keys.h\n", sec, key);
    abort();
}

/* a string key: the value, else def (NULL: absent) */
static const char *get_str(ini_data *d, const char *sec, const char *key, const char *def)
{
    key_row(sec, key);
    entry *e = find(d, sec, key);
    return e ? e->value : def;
}

static double get_num_range(ini_data *d, const char *sec, const char *key, double def, double lo, double hi)
{
    entry *e = find(d, sec, key);
    if (!e)
        return def;
    double v;
    if (!gf_parse_number(e->value, &v))
        die("[%s] %s = '%s' is not a number", sec, key, e->value);
    if (v < lo || v > hi)
        die("[%s] %s = %g is outside the allowed range [%g, %g]", sec, key, v, lo, hi);
    return v;
}

/* a number key with its row's range and the default def (computed by the caller) */
static double get_num_or(ini_data *d, const char *sec, const char *key, double def)
{
    const gf1d_key *r = key_row(sec, key);
    return get_num_range(d, sec, key, def, r->lo, r->hi);
}

/* a number key with its row's default (NAN: "-" or "required") and range */
static double get_num(ini_data *d, const char *sec, const char *key)
{
    const gf1d_key *r = key_row(sec, key);
    double def;
    if (!gf_parse_number(r->deflt, &def))
        def = NAN;
    return get_num_range(d, sec, key, def, r->lo, r->hi);
}

/* an integer key: a number without fractional part, inside the row's range */
static long get_int(ini_data *d, const char *sec, const char *key)
{
    const gf1d_key *r = key_row(sec, key);
    entry *e = find(d, sec, key);
    double v;
    if (!e) {
        gf_parse_number(r->deflt, &v);
        return (long)v;
    }
    if (!gf_parse_number(e->value, &v) || v != floor(v))
        die("[%s] %s = '%s' is not an integer", sec, key, e->value);
    if (v < r->lo || v > r->hi)
        die("[%s] %s = %g is outside the allowed range [%ld, %ld]", sec, key, v, (long)r->lo, (long)r->hi);
    return (long)v;
}

/* a choice key: the index of the value among the row's "a | b | c" */
static int get_choice(ini_data *d, const char *sec, const char *key)
{
    const gf1d_key *r = key_row(sec, key);
    const char *v = get_str(d, sec, key, r->deflt);
    char list[256] = "";
    int i = 0;
    for (const char *c = r->allowed; *c; ++i) {
        const size_t n = strcspn(c, " |");
        if (strlen(v) == n && !strncmp(v, c, n))
            return i;
        if (i)
            strncat(list, ", ", sizeof list - strlen(list) - 1);
        strncat(list, c, n < sizeof list - strlen(list) - 1 ? n : sizeof list - strlen(list) - 1);
        c += n;
        c += strspn(c, " |");
    }
    die("[%s] %s = '%s' is not one of: %s", sec, key, v, list);
    return -1;
}

/* a key of no row: the error names the file, section and key and lists the
 * valid keys of the section (or the sections) */
static void unknown_key(const char *sec, const char *key)
{
    char list[2048] = "";
    const size_t n = sizeof gf1d_keys / sizeof *gf1d_keys;
    for (size_t i = 0; i < n; ++i)
        if (!strcmp(gf1d_keys[i].section, sec)) {
            strncat(list, *list ? ", " : "", sizeof list - strlen(list) - 1);
            strncat(list, gf1d_keys[i].key, sizeof list - strlen(list) - 1);
        }
    if (*list)
        die("unknown key [%s] %s; valid keys of [%s]: %s", sec, key, sec, list);
    for (size_t i = 0; i < n; ++i)
        if (!i || strcmp(gf1d_keys[i].section, gf1d_keys[i - 1].section)) {
            strncat(list, *list ? ", " : "", sizeof list - strlen(list) - 1);
            strncat(list, gf1d_keys[i].section, sizeof list - strlen(list) - 1);
        }
    die("unknown section [%s] (key %s); valid sections: %s, friction", sec, key, list);
}

/* the allowed values of a row as text: the choices, the names the library
 * knows, or the range */
static void allowed_text(const gf1d_key *r, char *buf, size_t size)
{
    if (r->allowed) {
        size_t k = 0; /* "a | b" -> "a, b" */
        for (const char *c = r->allowed; *c && k + 2 < size; ++c)
            if (!strncmp(c, " | ", 3)) {
                buf[k++] = ',';
                buf[k++] = ' ';
                c += 2;
            } else
                buf[k++] = *c;
        buf[k] = 0;
        return;
    }
    if (!strcmp(r->type, "name")) {
        snprintf(buf, size, "%s",
                 !strcmp(r->key, "method") ? gf_sh1d_type_names()
                 : !strcmp(r->key, "limiter") ? gf_limiter_names() : gf_friction_names());
        return;
    }
    if (strcmp(r->type, "number") && strcmp(r->type, "integer"))
        *buf = 0;
    else if (r->lo <= -1e300 && r->hi >= 1e300)
        snprintf(buf, size, "any");
    else if (r->hi >= 1e300)
        snprintf(buf, size, r->lo == 1e-300 ? "> 0" : ">= %g", r->lo);
    else
        snprintf(buf, size, "[%g, %g]", r->lo, r->hi);
}

/* --keywords: the rows as Markdown, a table per section (doc/keywords.md) */
static void print_keywords(void)
{
    const size_t n = sizeof gf1d_keys / sizeof *gf1d_keys;
    char allowed[512];
    for (size_t i = 0; i < n; ++i) {
        const gf1d_key *r = &gf1d_keys[i];
        if (!i || strcmp(r->section, gf1d_keys[i - 1].section))
            printf("%s### `[%s]`\n\n| key | type | default | allowed | unit | applies to | description |\n"
                   "|---|---|---|---|---|---|---|\n", i ? "\n" : "", r->section);
        allowed_text(r, allowed, sizeof allowed);
        printf("| `%s` | %s | %s | %s | %s | %s | %s |\n", r->key, r->type, r->deflt, allowed, r->unit,
               r->applies, r->description);
    }
    printf("\n### `[friction]`\n\nThe coefficients of the law of [model] friction (libgranflow's table of laws,"
           " granflow/friction.h); coulomb: mu defaults to tan(delta) when [model] delta is given.\n\n"
           "| key | type | default | allowed | unit | applies to | description |\n|---|---|---|---|---|---|---|\n");
    for (const gf_friction_type *const *t = gf_friction_types(); *t; ++t)
        for (size_t k = 0; k < (*t)->n_params; ++k) {
            const gf_friction_param *p = &(*t)->params[k];
            printf("| `%s` | number | %g | [%g, %g] | %s | %s | %s |\n", p->name, p->default_value, p->min,
                   p->max, p->unit, (*t)->name, p->description);
        }
}

static void lib_check(gf_status st, const char *what)
{
    if (st)
        die("%s: %s (%s)", what, gf_error_detail(), gf_strerror(st));
}

/* ---- initial data -------------------------------------------------------- */
typedef struct init_data {
    int shape;
    double x0, x1, x2, hl, hr, ul, ur, hin, hout, r, K, l, depth;
    size_t nf;
    double *fx, *fh, *fu;
} init_data;

enum { DAM, BOX, SEMICIRCLE, PARABOLA, SINUSOID, FILE_SHAPE, CAP };

static void initial(double x, void *ctx, double *h, double *u)
{
    const init_data *p = ctx;
    *u = 0.0;
    switch (p->shape) {
    case DAM:
        *h = x <= p->x0 ? p->hl : p->hr;
        *u = x <= p->x0 ? p->ul : p->ur;
        break;
    case BOX:
        *h = (x > p->x1 && x <= p->x2) ? p->hin : p->hout;
        break;
    case SEMICIRCLE: {
        const double d = x - p->x0;
        *h = d * d < p->r * p->r ? sqrt(p->r * p->r - d * d) : 0.0;
        break;
    }
    case CAP: { /* cross-section of a sphere or cylinder whose centre lies depth below the bed */
        const double d = x - p->x0, s2 = p->r * p->r - d * d;
        *h = s2 > 0.0 ? fmax(0.0, sqrt(s2) - p->depth) : 0.0;
        break;
    }
    case PARABOLA:
        *h = fmax(p->K / 10.0, p->K - p->l * (x - p->x0) * (x - p->x0));
        break;
    case SINUSOID: /* kinetic paper, section 4, fifth test */
        *h = (x > 0.6 && x < 1.6)
                 ? fmax(0.9 * sin(GF_PI * (x - 0.6)) -
                            0.3 * sin(2 * GF_PI * (x - 0.6)), 0.1)
                 : 0.1;
        break;
    default: { /* linear interpolation in the table, constant outside */
        size_t i = 0;
        if (x <= p->fx[0]) {
            *h = p->fh[0];
            *u = p->fu[0];
            return;
        }
        if (x >= p->fx[p->nf - 1]) {
            *h = p->fh[p->nf - 1];
            *u = p->fu[p->nf - 1];
            return;
        }
        while (p->fx[i + 1] < x)
            ++i;
        const double w = (x - p->fx[i]) / (p->fx[i + 1] - p->fx[i]);
        *h = (1 - w) * p->fh[i] + w * p->fh[i + 1];
        *u = (1 - w) * p->fu[i] + w * p->fu[i + 1];
    }
    }
}

/* read_csv: the shared strict parser (../common/gf_csv.h), dying with its message */
static size_t read_csv(const char *path, const char *const *cols, const int *nonneg, int ncols,
                       double **out)
{
    char err[1024];
    size_t n;
    if (gf_csv_read(path, cols, nonneg, ncols, out, &n, err, sizeof err))
        die("%s", err);
    return n;
}

/* ---- main ------------------------------------------------------------------ */
/* ---- the case: everything read from the case file ------------------------ */
typedef struct gf1d_case {
    const char *file;
    gf_sh1d_config c;
    const gf_sh1d_type *method;
    gf_topography *topo;
    int tt;            /* topography type: 0 flat, 1 chute, 2 tabulated */
    const char *law;
    init_data ini;
    double times[MAXT];
    int nt;
    const char *dir, *name;
    char stem[256];
    int plot, exact;   /* exact: 0 no, 1 riemann, 2 dressler */
    double front_h, every;
} gf1d_case;

/* A name the library looks up (solver method, limiter): the value or die
 * listing the valid names. */
static const char *get_name(ini_data *d, const char *sec, const char *key, const char *def, int valid,
                            const char *names)
{
    const char *v = get_str(d, sec, key, def);
    if (!valid)
        die("[%s] %s = '%s' is not one of: %s", sec, key, v, names);
    return v;
}

/* Parse the case file and the command-line overrides into cs; dies naming
 * the file, section, key and allowed range on any bad entry. */
static void read_case(int argc, char **argv, gf1d_case *cs)
{
    static ini_data d;
    cs->file = file_name = argv[1];
    {
        /* inih reads a line into INI_MAX_LINE bytes (newline and NUL
           included) and would cut a longer one into a syntax error: refuse it
           by name (a long output folder goes on the command line) */
        FILE *f = fopen(argv[1], "r");
        char *line = NULL;
        size_t cap = 0;
        ssize_t len;
        for (int no = 1; f && (len = getline(&line, &cap, f)) >= 0; ++no) {
            len -= len > 0 && line[len - 1] == '\n';
            if (len > INI_MAX_LINE - 2)
                die("line %d has %zd bytes, more than the case-file reader's %d; give a long value on "
                    "the command line instead (an output folder: granflow1d %s output.dir=FOLDER)",
                    no, len, INI_MAX_LINE - 2, argv[1]);
        }
        free(line);
        if (f)
            fclose(f);
    }
    const int ir = ini_parse(argv[1], handler, &d);
    if (ir < 0)
        die("cannot read the case file");
    if (ir > 0)
        die("syntax error on line %d", ir);
    for (int a = 2; a < argc; ++a) {
        char sec[32], key[32];
        const char *dot = strchr(argv[a], '.'), *eq = strchr(argv[a], '=');
        if (!dot || !eq || dot > eq || dot - argv[a] >= 32 || eq - dot - 1 >= 32)
            die("override '%s' is not section.key=value", argv[a]);
        snprintf(sec, sizeof sec, "%.*s", (int)(dot - argv[a]), argv[a]);
        snprintf(key, sizeof key, "%.*s", (int)(eq - dot - 1), dot + 1);
        put(&d, sec, key, eq + 1);
    }
    gf_sh1d_config c;
    gf_sh1d_config_init(&c);

    /* model */
    c.epsilon = get_num(&d, "model", "epsilon");
    c.g = get_num(&d, "model", "g");
    c.chi = get_num(&d, "model", "chi");
    c.rho = get_num(&d, "model", "rho");
    const int ep = get_choice(&d, "model", "earth_pressure");
    const double phi = get_num(&d, "model", "phi");
    const double delta = get_num(&d, "model", "delta");
    if (ep == 1 && (isnan(phi) || isnan(delta)))
        die("[model] earth_pressure = savageHutter needs phi and delta");
    {
        gf_status st = gf_earth_pressure_init(&c.earth_pressure, (gf_earth_pressure_model)ep,
                                              phi * GF_DEG, delta * GF_DEG);
        if (st)
            die("[model] phi = %g, delta = %g: %s", phi, delta, gf_error_detail());
    }
    const char *law = get_str(&d, "model", "friction", key_row("model", "friction")->deflt);
    if (gf_friction_init(&c.friction, law))
        die("[model] friction: %s", gf_error_detail());
    if (!strcmp(law, "coulomb")) {
        if (isnan(delta) && !find(&d, "friction", "mu"))
            die("[model] friction = coulomb needs [model] delta or [friction] mu");
        if (!isnan(delta))
            lib_check(gf_friction_set(&c.friction, "mu", tan(delta * GF_DEG)), "[model] delta");
    }
    for (int i = 0; i < d.n; ++i)
        if (!strcmp(d.e[i].section, "friction")) {
            const double v = get_num_range(&d, "friction", d.e[i].key, 0, -1e300, 1e300); /* the law checks */
            if (gf_friction_set(&c.friction, d.e[i].key, v))
                die("[friction] %s: %s", d.e[i].key, gf_error_detail());
        }
    if (gf_friction_check(&c.friction))
        die("[friction]: %s", gf_error_detail());

    /* topography */
    const int tt = get_choice(&d, "topography", "type");
    gf_topography *topo = NULL;
    if (tt == 0) {
        c.zeta = get_num(&d, "topography", "zeta") * GF_DEG;
    } else if (tt == 1) {
        const double z0 = get_num(&d, "topography", "zeta0");
        if (isnan(z0))
            die("[topography] type = chute needs zeta0");
        lib_check(gf_topography_chute_alloc(z0 * GF_DEG,
                                            get_num(&d, "topography", "zeta1") * GF_DEG,
                                            get_num(&d, "topography", "x1"),
                                            get_num(&d, "topography", "x2"), &topo),
                  "[topography]");
    } else {
        const char *path = get_str(&d, "topography", "file", NULL);
        if (!path)
            die("[topography] type = tabulated needs file");
        static const char *const cols[] = {"x", "zeta"};
        static const int nonneg[] = {0, 0};
        double *col[2];
        const size_t n = read_csv(path, cols, nonneg, 2, col);
        for (size_t i = 0; i < n; ++i)
            col[1][i] *= GF_DEG;
        lib_check(gf_topography_tabulated_alloc(col[0], col[1], n, &topo), "[topography] file");
        free(col[0]);
        free(col[1]);
    }
    c.topo = topo;

    /* domain */
    c.x_min = get_num(&d, "domain", "x_min");
    c.x_max = get_num(&d, "domain", "x_max");
    c.n_cells = (size_t)get_int(&d, "domain", "cells");
    c.bc_left = (gf_bc)get_choice(&d, "domain", "bc_left");
    c.bc_right = (gf_bc)get_choice(&d, "domain", "bc_right");

    /* initial */
    init_data ini = {0};
    ini.shape = get_choice(&d, "initial", "shape");
    ini.x0 = get_num_or(&d, "initial", "x0", 0.5 * (c.x_min + c.x_max));
    ini.hl = get_num(&d, "initial", "h_left");
    ini.hr = get_num(&d, "initial", "h_right");
    ini.ul = get_num(&d, "initial", "u_left");
    ini.ur = get_num(&d, "initial", "u_right");
    ini.x1 = get_num_or(&d, "initial", "x1", c.x_min);
    ini.x2 = get_num_or(&d, "initial", "x2", c.x_max);
    ini.hin = get_num(&d, "initial", "h_in");
    ini.hout = get_num(&d, "initial", "h_out");
    ini.r = get_num(&d, "initial", "radius");
    ini.K = get_num(&d, "initial", "K");
    ini.l = get_num(&d, "initial", "l");
    ini.depth = get_num(&d, "initial", "depth");
    if (ini.shape == FILE_SHAPE) {
        const char *path = get_str(&d, "initial", "file", NULL);
        if (!path)
            die("[initial] shape = file needs file");
        static const char *const cols[] = {"x", "h", "u"};
        static const int nonneg[] = {0, 1, 0};
        double *col[3];
        ini.nf = read_csv(path, cols, nonneg, 3, col);
        if (ini.nf < 2)
            die("[initial] file '%s' needs at least 2 rows", path);
        ini.fx = col[0];
        ini.fh = col[1];
        ini.fu = col[2];
    }

    /* solver */
    const char *mname = get_str(&d, "solver", "method", key_row("solver", "method")->deflt);
    cs->method = gf_sh1d_type_lookup(mname);
    get_name(&d, "solver", "method", mname, cs->method != NULL, gf_sh1d_type_names());
    c.degree = (int)get_int(&d, "solver", "degree");
    c.scheme = (int)get_int(&d, "solver", "scheme");
    /* the other method's keys: read and range-checked like the rest (a
     * case file can switch methods on the command line), and named on
     * stderr as not acting */
    {
        static const char *const dg_keys[] = {"degree", "limiter", "gamma", "tvb_m", "velocity_limiter",
                                               "moving_mesh"};
        static const char *const kin_keys[] = {"scheme", "kinetic_order"};
        const int kinetic = cs->method == gf_sh1d_kinetic;
        const char *const *keys = kinetic ? dg_keys : kin_keys;
        const size_t nk = kinetic ? sizeof dg_keys / sizeof *dg_keys : sizeof kin_keys / sizeof *kin_keys;
        for (size_t i = 0; i < nk; ++i)
            if (find(&d, "solver", keys[i]))
                fprintf(stderr, "granflow1d: %s: note: [solver] %s applies to method = %s, not %s; ignored\n",
                        file_name, keys[i], kinetic ? "rkdg" : "kinetic", kinetic ? "kinetic" : "rkdg");
    }
    c.kinetic_order = (int)get_int(&d, "solver", "kinetic_order");
    c.cfl = get_num(&d, "solver", "cfl");
    c.dt_fixed = get_num(&d, "solver", "dt");
    const char *lname = get_str(&d, "solver", "limiter", key_row("solver", "limiter")->deflt);
    const int lim = gf_limiter_lookup(lname);
    get_name(&d, "solver", "limiter", lname, lim >= 0, gf_limiter_names());
    c.limiter = (gf_limiter)lim;
    c.velocity_limiter = get_choice(&d, "solver", "velocity_limiter");
    c.gamma = get_num(&d, "solver", "gamma");
    /* the paper's minmod is strict (M = 0); the moment limiter spares smooth extrema */
    c.tvb_m = get_num_or(&d, "solver", "tvb_m", c.limiter == GF_LIMITER_MINMOD ? 0.0 : 1.0);
    c.h_eps = get_num(&d, "solver", "h_eps");
    c.h_semi = get_num(&d, "solver", "h_semi");
    c.startup_levels = (int)get_int(&d, "solver", "startup_levels");
    c.moving_mesh = get_choice(&d, "solver", "moving_mesh");
    c.riemann_start = get_num(&d, "solver", "riemann_start");
    if (cs->method == gf_sh1d_kinetic)
        c.moving_mesh = 0; /* named above as not acting */

    /* output */
    double *times = cs->times;
    int nt = 0;
    {
        char buf[512];
        snprintf(buf, sizeof buf, "%s", get_str(&d, "output", "times", ""));
        for (char *t = strtok(buf, " ,\t"); t; t = strtok(NULL, " ,\t")) {
            if (nt == MAXT)
                die("[output] times: more than %d times", MAXT);
            if (!gf_parse_number(t, &times[nt]) || !(times[nt] >= 0) ||
                (nt && times[nt] <= times[nt - 1]))
                die("[output] times: '%s' is not a time after the previous one", t);
            ++nt;
        }
        if (!nt)
            die("[output] times: give at least one output time");
    }
    cs->nt = nt;
    cs->dir = get_str(&d, "output", "dir", ".");
    char *stem = cs->stem;
    {
        const char *b = strrchr(argv[1], '/');
        snprintf(stem, sizeof cs->stem, "%s", b ? b + 1 : argv[1]);
        char *dotp = strrchr(stem, '.');
        if (dotp)
            *dotp = 0;
    }
    cs->name = get_str(&d, "output", "name", stem);
    cs->plot = get_choice(&d, "output", "plot");
    cs->exact = get_choice(&d, "output", "exact");
    cs->front_h = get_num(&d, "output", "front_h");
    cs->every = get_num(&d, "output", "every");

    for (int i = 0; i < d.n; ++i)
        if (!d.e[i].used)
            unknown_key(d.e[i].section, d.e[i].key);
    cs->c = c;
    cs->topo = topo;
    cs->tt = tt;
    cs->law = law;
    cs->ini = ini;
}


/* The exact solution asked for by [output] exact, checked before the run. */
static void setup_exact(const gf1d_case *cs, gf_riemann *rp, gf_dressler *dp)
{
    double chezy = 0.0;
    if (cs->exact == 2) {
        if (cs->ini.shape != DAM || cs->tt != 0 || cs->c.zeta != 0.0 || strcmp(cs->law, "chezy") || cs->ini.hr != 0.0 ||
            cs->ini.ul != 0.0 || cs->c.earth_pressure.k_act != 1.0 || cs->c.earth_pressure.k_pass != 1.0 ||
            cs->c.epsilon != cs->c.g)
            die("[output] exact = dressler needs shape = dam with h_right = 0 and u_left = 0 on "
                "flat ground, friction = chezy, isotropic earth pressure and epsilon = g");
        lib_check(gf_friction_get(&cs->c.friction, "C", &chezy), "[friction] C");
        lib_check(gf_dressler_init(dp, cs->c.g, cs->ini.hl, chezy, cs->ini.x0), "exact solution");
        for (int k = 0; k < cs->nt; ++k) /* fail before the run, not after */
            if (cs->times[k] > 0.0 && gf_dressler_at(dp, cs->times[k]))
                die("[output] exact = dressler at t = %g: %s", cs->times[k], gf_error_detail());
    } else if (cs->exact) {
        if (cs->ini.shape != DAM || cs->tt != 0 || cs->c.zeta != 0.0 || strcmp(cs->law, "none"))
            die("[output] exact = riemann needs shape = dam on flat ground without friction");
        const double beta = cs->c.epsilon * cs->c.earth_pressure.k_act; /* K constant: isotropic or phi = delta */
        if (cs->c.earth_pressure.k_act != cs->c.earth_pressure.k_pass)
            die("[output] exact = riemann needs K_act = K_pass (isotropic, or phi = delta)");
        lib_check(gf_riemann_solve(rp, beta, cs->ini.hl, cs->ini.ul, cs->ini.hr, cs->ini.ur, cs->ini.x0), "exact solution");
    }

}

/* NAME_t<time>.csv of output time k: x,h,u[,X,Z,Xs,Zs][,h_exact,u_exact]. */
static void write_profile(const gf1d_case *cs, const gf_sh1d *s, int k, const double *h, const double *u,
                          const gf_riemann *rp, gf_dressler *dp)
{
    const size_t n = gf_sh1d_n_cells(s);
    const char *dir = cs->dir, *name = cs->name;
    const double *times = cs->times;
    const int exact = cs->exact;
    gf_topography *topo = cs->topo;
    char *path = mkpath("%s/%s_t%g.csv", dir, name, times[k]);
        FILE *f = fopen(path, "w");
        if (!f)
            die("cannot write '%s': %s", path, strerror(errno));
        if (exact == 2 && times[k] > 0.0 && gf_dressler_at(dp, times[k]))
            die("[output] exact = dressler at t = %g: %s", times[k], gf_error_detail());
        fprintf(f, "x,h,u%s%s\n", topo ? ",X,Z,Xs,Zs" : "", exact ? ",h_exact,u_exact" : "");
        for (size_t i = 0; i < n; ++i) {
            const double x = gf_sh1d_cell_centre(s, i);
            fprintf(f, "%.10g,%.12g,%.12g", x, h[i], u[i]);
            if (topo) {
                double X, Z, z, kap;
                gf_topography_position(topo, x, &X, &Z);
                gf_topography_eval(topo, x, &z, &kap);
                fprintf(f, ",%.10g,%.10g,%.10g,%.10g", X, Z, X + h[i] * sin(z), Z + h[i] * cos(z));
            }
            if (exact) {
                double he, ue;
                if (exact == 2 && times[k] > 0.0)
                    gf_dressler_sample(dp, x, times[k], &he, &ue); /* checked above */
                else if (exact == 2)
                    gf_dressler_outer(dp, x, 0.0, &he, &ue); /* the initial dam */
                else
                    gf_riemann_sample(rp, x, times[k], &he, &ue);
                fprintf(f, ",%.12g,%.12g", he, ue);
            }
            fprintf(f, "\n");
        }
        if (fclose(f) != 0)
            die("cannot write '%s': %s", path, strerror(errno));
        free(path);
}

/* Run to every output time: a summary line (stdout and NAME.summary) and
 * a profile per time. */
static void run_case(const gf1d_case *cs, gf_sh1d *s, const gf_riemann *rp, gf_dressler *dp)
{
    const char *dir = cs->dir, *name = cs->name;
    const double *times = cs->times, front_h = cs->front_h, every = cs->every;
    const int nt = cs->nt;
    char *path = mkpath("%s/%s.summary", dir, name);
    FILE *sum = fopen(path, "w");
    if (!sum)
        die("cannot write '%s': %s", path, strerror(errno));
    const double m0 = gf_sh1d_mass(s);
    const size_t n = gf_sh1d_n_cells(s);
    double *h = malloc(n * sizeof *h), *u = malloc(n * sizeof *u);
    fprintf(sum, "# granflow1d %s: %s, %zu cells\n", cs->file, gf_sh1d_type_name(cs->method), n);
    fprintf(sum, "time,mass,mass_rel_change,max_h,front,tail,max_speed,steps,cpu_s,outflow,balance_rel\n");
    printf("%-10s %-12s %-10s %-10s %-10s %-10s %-8s %s\n", "time", "mass", "max_h", "front", "tail",
           "max|u|", "steps", "cpu_s");
    const clock_t c0 = clock();
    double next_report = every > 0 ? every : HUGE_VAL;
    for (int k = 0; k < nt; ++k) {
        while (gf_sh1d_time(s) < times[k] - 1e-12) {
            const double target = fmin(times[k], next_report);
            if (gf_sh1d_advance_to(s, target)) {
                fclose(sum);
                die("run failed: %s", gf_error_detail());
            }
            if (gf_sh1d_time(s) >= next_report - 1e-12) {
                printf("  t = %g, max|u| = %.3g, steps %zu\n", gf_sh1d_time(s), gf_sh1d_max_speed(s),
                       gf_sh1d_steps(s));
                next_report += every;
            }
        }
        gf_sh1d_means(s, h, u);
        double hmax = 0, front = NAN, tail = NAN;
        for (size_t i = 0; i < n; ++i) {
            hmax = fmax(hmax, h[i]);
            if (h[i] >= front_h) {
                const double x = gf_sh1d_cell_centre(s, i);
                front = isnan(front) ? x : fmax(front, x);
                tail = isnan(tail) ? x : fmin(tail, x);
            }
        }
        const double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC, mass = gf_sh1d_mass(s);
        /* the mass balance: what is in the domain plus what has left through its
         * ends is the initial mass (balance_rel: the relative defect) */
        const double out = gf_sh1d_outflow(s);
        fprintf(sum, "%g,%.15g,%.3e,%.10g,%.10g,%.10g,%.10g,%zu,%.4f,%.15g,%.3e\n", times[k], mass,
                (mass - m0) / m0, hmax, front, tail, gf_sh1d_max_speed(s), gf_sh1d_steps(s), cpu, out,
                (mass + out - m0) / m0);
        printf("%-10g %-12.8g %-10.5g %-10.5g %-10.5g %-10.3g %-8zu %.3f\n", times[k], mass, hmax,
               front, tail, gf_sh1d_max_speed(s), gf_sh1d_steps(s), cpu);

        write_profile(cs, s, k, h, u, rp, dp);
    }
    if (fclose(sum) != 0)
        die("cannot write '%s': %s", path, strerror(errno));
    free(path);
    if (gf_sh1d_startup_steps(s) > 0)
        printf("start-up refinement (startup_levels = %d): %zu steps on the finer grids up to t = %g "
               "(counted as 1 step above)\n",
               gf_sh1d_get_config(s)->startup_levels, gf_sh1d_startup_steps(s), gf_sh1d_startup_time(s));

    free(h);
    free(u);
}

/* s as a gnuplot string in single quotes (a quote in it doubled) */
static void gp_string(FILE *g, const char *s)
{
    fputc('\'', g);
    for (; *s; ++s) {
        if (*s == '\'')
            fputc('\'', g);
        fputc(*s, g);
    }
    fputc('\'', g);
}

/* NAME.gp and NAME.png: h and u at every output time (and the bed).  The
 * script names its files relative to the output folder, and gnuplot runs
 * there (no shell, no path in a command line): an output folder of any
 * length and name. */
static void write_plot(const gf1d_case *cs)
{
    const char *dir = cs->dir, *name = cs->name;
    const double *times = cs->times;
    const int nt = cs->nt, exact = cs->exact;
    const gf_topography *topo = cs->topo;
    char *path = mkpath("%s/%s.gp", dir, name), *gp = mkpath("%s.gp", name);
        FILE *g = fopen(path, "w");
        if (!g)
            die("cannot write '%s': %s", path, strerror(errno));
        fprintf(g, "set datafile separator ','\nset terminal pngcairo size 900,%d font ',10'\n",
                topo ? 900 : 600);
        char *png = mkpath("%s.png", name);
        fprintf(g, "set output ");
        gp_string(g, png);
        fprintf(g, "\nset multiplot layout %d,1 title ", topo ? 3 : 2);
        gp_string(g, name);
        fprintf(g, "\nset key outside right\nset grid\nset xlabel 'x'\n");
        for (int panel = 0; panel < 2; ++panel) {
            fprintf(g, "set ylabel '%s'\nplot ", panel ? "u" : "h");
            for (int k = 0; k < nt; ++k) {
                char *csv = mkpath("%s_t%g.csv", name, times[k]);
                fprintf(g, "%s", k ? ", " : "");
                gp_string(g, csv);
                fprintf(g, " skip 1 using 1:%d with lines lw 2 title 't = %g'", panel ? 3 : 2, times[k]);
                if (exact) {
                    fprintf(g, ", ");
                    gp_string(g, csv);
                    fprintf(g, " skip 1 using 1:%d with lines dt 2 lc rgb 'black' title 'exact t = %g'",
                            panel ? (topo ? 9 : 5) : (topo ? 8 : 4), times[k]);
                }
                free(csv);
            }
            fprintf(g, "\n");
        }
        if (topo) {
            char *csv = mkpath("%s_t%g.csv", name, times[nt - 1]);
            fprintf(g, "set ylabel 'Z (vertical)'\nset xlabel 'X (horizontal)'\nset size ratio -1\nplot ");
            gp_string(g, csv);
            fprintf(g, " skip 1 using 4:5 with lines lc rgb 'black' lw 2 title 'bed', "
                       "'' skip 1 using 6:7 with lines lw 2 title 'surface t = %g'\n",
                    times[nt - 1]);
            free(csv);
        }
        fprintf(g, "unset multiplot\n");
        if (fclose(g) != 0)
            die("cannot write '%s': %s", path, strerror(errno));
        /* gnuplot NAME.gp in the output folder */
        fflush(NULL);
        const pid_t pid = fork();
        if (pid == 0) {
            if (chdir(dir) != 0) {
                fprintf(stderr, "granflow1d: cannot enter the output folder '%s' for gnuplot: %s\n", dir,
                        strerror(errno));
                _exit(126);
            }
            execlp("gnuplot", "gnuplot", gp, (char *)NULL);
            fprintf(stderr, "granflow1d: cannot run gnuplot: %s\n", strerror(errno));
            _exit(127);
        }
        int ws = 0;
        if (pid < 0)
            fprintf(stderr, "granflow1d: cannot start gnuplot: %s\n", strerror(errno));
        else
            while (waitpid(pid, &ws, 0) < 0 && errno == EINTR) {
            }
        if (pid < 0 || !WIFEXITED(ws) || WEXITSTATUS(ws) != 0)
            fprintf(stderr, "granflow1d: warning: gnuplot failed on %s (no %s/%s.png)\n", path, dir, name);
        free(png);
        free(gp);
        free(path);
}

int main(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
        fprintf(stderr, "usage: granflow1d CASE.ini [section.key=value ...]\n"
                        "       granflow1d --keywords   (the keys of the case file, Markdown)\n"
                        "       granflow1d --version\n"
                        "Runs a 1D Savage-Hutter case; the keys are in doc/keywords.md.\n");
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-version")) {
        printf("granflow %s (granflow1d)\n", gf_version());
        return 0;
    }
    if (!strcmp(argv[1], "--keywords") || !strcmp(argv[1], "-keywords")) {
        print_keywords();
        return 0;
    }
    static gf1d_case cs;
    read_case(argc, argv, &cs);
    gf_riemann rp;
    gf_dressler dp;
    setup_exact(&cs, &rp, &dp);
    gf_sh1d *s;
    if (gf_sh1d_alloc(cs.method, &cs.c, &s))
        die("[solver]/[domain]: %s", gf_error_detail());
    if (gf_sh1d_set_initial(s, initial, &cs.ini))
        die("[initial]: %s", gf_error_detail());
    if (cs.c.riemann_start > 0.0) {
        /* the solver starts at t_s from the dams' exact solution */
        const double ts = gf_sh1d_time(s);
        if (cs.times[0] < ts)
            die("[output] times: %g is before t_s = %g, where riemann_start starts the solver from the "
                "dam's exact solution; give times >= %g", cs.times[0], ts, ts);
        printf("Riemann start: the dams' exact solution up to t_s = %.6g\n", ts);
    }
    run_case(&cs, s, &rp, &dp);
    if (cs.plot)
        write_plot(&cs);
    free(cs.ini.fx);
    free(cs.ini.fh);
    free(cs.ini.fu);
    gf_sh1d_free(s);
    gf_topography_free(cs.topo);
    return 0;
}
