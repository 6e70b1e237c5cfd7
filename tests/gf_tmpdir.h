/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A temporary folder for a test program's files (the terrain, path-analysis
 * and ensemble tests write rasters and vectors through GDAL): GF_TMPDIR_FIXTURES(prefix)
 * defines tmpdir, tmp(name) (its path, four kept at a time), and the group
 * set-up and tear-down that make and remove /tmp/<prefix>_XXXXXX. */
#ifndef GF_TMPDIR_H
#define GF_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>

#define GF_TMPDIR_FIXTURES(prefix)                                          \
    static char tmpdir[64];                                                 \
    static const char *tmp(const char *name)                                \
    {                                                                       \
        static char path[8][160];                                           \
        static int k = 0;                                                   \
        k = (k + 1) % 8;                                                    \
        snprintf(path[k], sizeof path[k], "%s/%s", tmpdir, name);           \
        return path[k];                                                     \
    }                                                                       \
    static int setup(void **state)                                          \
    {                                                                       \
        (void)state;                                                        \
        snprintf(tmpdir, sizeof tmpdir, "/tmp/" prefix "_XXXXXX");          \
        return mkdtemp(tmpdir) ? 0 : -1;                                    \
    }                                                                       \
    static int teardown(void **state)                                       \
    {                                                                       \
        (void)state;                                                        \
        char cmd[128];                                                      \
        snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);                     \
        return system(cmd);                                                 \
    }

#endif
