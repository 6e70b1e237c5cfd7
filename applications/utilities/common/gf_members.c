/* SPDX-License-Identifier: GPL-3.0-or-later */
/* granflow — member folders of a terrain case (gf_members.h). */
#define _GNU_SOURCE
#include "gf_members.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "gf_dict.h"
#include "granflow/status.h"

int gf_run(char *const argv[], const char *log)
{
    fflush(stdout);
    fflush(stderr);
    const pid_t pid = fork();
    if (pid < 0) return 127;
    if (pid == 0) {
        if (log) {
            const int fd = open(log, O_WRONLY | O_CREAT | O_APPEND, 0644);
            if (fd >= 0) {
                dup2(fd, 1);
                dup2(fd, 2);
            }
        }
        execvp(argv[0], argv);
        fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    int st = 0;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

int gf_exists(const char *path)
{
    struct stat s;
    return stat(path, &s) == 0;
}

char *gf_path(const char *a, const char *b)
{
    char *r = NULL;
    if (asprintf(&r, "%s/%s", a, b) < 0) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return r;
}

int gf_path_foam_safe(const char *path)
{
    return strpbrk(path, " \t\n\"'") == NULL;
}

int gf_append(const char *file, const char *text)
{
    FILE *f = fopen(file, "a");
    if (!f) return -1;
    const int r = fputs(text, f) < 0;
    return fclose(f) != 0 || r ? -1 : 0;
}

void gf_override_text(const char *entry, double v, char *out, size_t size)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", entry);
    char *parts[32], *save = NULL;
    size_t depth = 0, len = 0;
    for (char *t = strtok_r(buf, "/", &save); t && depth < 32; t = strtok_r(NULL, "/", &save)) parts[depth++] = t;
    if (depth == 0) {
        snprintf(out, size, "\n");
        return;
    }
    len += (size_t)snprintf(out + len, size - len, "\n// gfCalibrate\n");
    for (size_t i = 0; i + 1 < depth && len < size; ++i) len += (size_t)snprintf(out + len, size - len, "%s { ", parts[i]);
    if (len < size) len += (size_t)snprintf(out + len, size - len, "%s %.17g;", parts[depth - 1], v);
    for (size_t i = 0; i + 1 < depth && len < size; ++i) len += (size_t)snprintf(out + len, size - len, " }");
    if (len < size) snprintf(out + len, size - len, "\n");
}

void gf_remove_times(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d))) {
        double t;
        if (strcmp(de->d_name, "0") == 0 || !gf_parse_number(de->d_name, &t)) continue;
        char *f = gf_path(dir, de->d_name);
        char *rm[] = {"rm", "-rf", f, NULL};
        gf_run(rm, NULL);
        free(f);
    }
    closedir(d);
}

/* target linked at link (absolute); 0 or -1 */
static int link_abs(const char *target, const char *link)
{
    char *abs = realpath(target, NULL);
    const int r = abs && symlink(abs, link) == 0 ? 0 : -1;
    free(abs);
    return r;
}

int gf_member_template(const char *casedir, const char *dir, gf_case_controls *ctl, char *err, size_t errsize)
{
    memset(ctl, 0, sizeof *ctl);
    char *sys = gf_path(casedir, "system"), *zero = gf_path(casedir, "0"), *inp = gf_path(casedir, "Inputs");
    char *cons = gf_path(casedir, "constant"), *dcons = gf_path(dir, "constant");
    int r = -1;
    DIR *d = NULL;
    if (mkdir(dir, 0755) || mkdir(dcons, 0755)) {
        snprintf(err, errsize, "%s: cannot make the folder: %s", dir, strerror(errno));
        goto out;
    }
    char *cp[] = {"cp", "-r", sys, zero, (char *)dir, NULL};
    if (gf_run(cp, NULL)) {
        snprintf(err, errsize, "cannot copy %s and %s to %s", sys, zero, dir);
        goto out;
    }
    if (gf_exists(inp)) {
        char *l = gf_path(dir, "Inputs");
        const int bad = link_abs(inp, l);
        free(l);
        if (bad) {
            snprintf(err, errsize, "cannot link %s", inp);
            goto out;
        }
    }
    if (!(d = opendir(cons))) {
        snprintf(err, errsize, "%s: cannot read the folder", cons);
        goto out;
    }
    int meshes = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.') continue;
        char *f = gf_path(cons, de->d_name), *l = gf_path(dcons, de->d_name);
        int bad;
        if (strcmp(de->d_name, "polyMesh") == 0 || strcmp(de->d_name, "faMesh") == 0) {
            bad = link_abs(f, l);
            ++meshes;
        } else {
            char *c2[] = {"cp", "-r", f, l, NULL};
            bad = gf_run(c2, NULL);
        }
        free(l);
        if (bad) {
            snprintf(err, errsize, "cannot link or copy %s", f);
            free(f);
            goto out;
        }
        free(f);
    }
    if (meshes != 2) {
        snprintf(err, errsize, "%s: no polyMesh and faMesh: the case is not meshed (gfTerrainMesh)", cons);
        goto out;
    }
    char *cd = gf_path(dir, "system/controlDict");
    gf_dict *D = gf_dict_read(cd, err, errsize);
    free(cd);
    if (!D) goto out;
    const gf_dict_entry *e = gf_dict_find(D, "endTime");
    if (!e || e->sub || e->ntok != 1) {
        snprintf(err, errsize, "%s/system/controlDict: no endTime", casedir);
        gf_dict_free(D);
        goto out;
    }
    snprintf(ctl->end_time, sizeof ctl->end_time, "%s", e->tok[0]);
    const gf_dict_entry *sf = gf_dict_find(D, "setFields");
    for (size_t t = 0; sf && t < sf->ntok; ++t) ctl->sets_release |= strcmp(sf->tok[t], "releaseDict") == 0;
    ctl->has_path_analysis = gf_dict_find(D, "pathAnalysis") != NULL;
    gf_dict_free(D);
    r = 0;
out:
    if (d) closedir(d);
    free(sys), free(zero), free(inp), free(cons), free(dcons);
    return r;
}

int gf_member_copy(const char *templ, const char *m, char *err, size_t errsize)
{
    char *rm[] = {"rm", "-rf", (char *)m, NULL}, *cp[] = {"cp", "-a", (char *)templ, (char *)m, NULL};
    if (gf_run(rm, NULL) || gf_run(cp, NULL)) {
        snprintf(err, errsize, "cannot make the member folder %s from %s", m, templ);
        return -1;
    }
    return 0;
}
