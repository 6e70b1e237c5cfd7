/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — member folders of a terrain case for the C drivers that run
 * many variants of one case in the ensemble workers (gfCalibrate; the
 * regional runs): the case's template (its system/ and 0/ copied, its
 * meshes and Inputs linked), a member made from it with its own entries,
 * its time folders removed after the run, and the small process and file
 * helpers they share.  Not part of libgranflow's API (programs only).
 */
#ifndef GF_MEMBERS_H
#define GF_MEMBERS_H

#include <stddef.h>

/* Run a program (argv[0] on PATH, no shell), its standard output and error
 * appended to log (NULL: inherited); its exit status (128 + signal when
 * killed, 127 when it cannot start). */
int gf_run(char *const argv[], const char *log);

/* 1 when the path exists. */
int gf_exists(const char *path);

/* "a/b", malloc'ed (the program stops with a message when out of memory). */
char *gf_path(const char *a, const char *b);

/* 1 when an OpenFOAM case can lie in path: no blank and no quote
 * (OpenFOAM v1912 drops them from file names, fileName::stripInvalid). */
int gf_path_foam_safe(const char *path);

/* Append text to a file; 0, or -1 when it cannot be written. */
int gf_append(const char *file, const char *text);

/* An entry "a/b/c" set to v as text to append to a dictionary:
 * "a { b { c v; } }" (OpenFOAM merges a repeated sub-dictionary and takes a
 * repeated keyword's last value). */
void gf_override_text(const char *entry, double v, char *out, size_t size);

/* The time folders of a run removed, but 0/ (the logs, rasters and tables
 * stay). */
void gf_remove_times(const char *dir);

/* What a template's system/controlDict says. */
typedef struct gf_case_controls {
    char end_time[64];     /* endTime as written */
    int sets_release;      /* setFields lists releaseDict */
    int has_path_analysis; /* a pathAnalysis dictionary */
} gf_case_controls;

/* Make the folder dir (which must not exist) a template of the terrain case
 * casedir: system/ and 0/ copied, constant/polyMesh and constant/faMesh
 * linked (absolute links: the meshes are read, never written), the other
 * constant/ entries copied, Inputs/ linked when the case has it; ctl filled
 * from its controlDict.  0, or -1 with the reason in err. */
int gf_member_template(const char *casedir, const char *dir, gf_case_controls *ctl, char *err, size_t errsize);

/* A member folder m (replaced when it exists) as a copy of the template
 * templ; 0, or -1 with the reason in err. */
int gf_member_copy(const char *templ, const char *m, char *err, size_t errsize);

#endif
