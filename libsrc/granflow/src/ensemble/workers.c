/* SPDX-License-Identifier: GPL-3.0-or-later */
/* granflow — ensemble workers on demand (granflow/workers.h). */
#define _GNU_SOURCE
#include "granflow/workers.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "internal.h"

typedef struct worker {
    pid_t pid;
    int in;      /* its standard input (a socket: a dead worker gives EPIPE, not SIGPIPE) */
    FILE *out;   /* its standard output */
    FILE *log;
    int busy;
    unsigned restarts;
} worker;

struct gf_workers {
    size_t n;
    char **argv;
    char **logs;
    worker *w;
    pthread_mutex_t lock;
    pthread_cond_t idle;
};

static void free_argv(char **a)
{
    if (!a) return;
    for (char **p = a; *p; ++p) free(*p);
    free(a);
}

static gf_status spawn(gf_workers *p, size_t k)
{
    worker *w = &p->w[k];
    int in[2], out[2], st[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, in) != 0) return gf_fail(GF_EIO, "worker %zu: socketpair: %s", k, strerror(errno));
    if (pipe2(out, O_CLOEXEC) != 0) {
        close(in[0]);
        close(in[1]);
        return gf_fail(GF_EIO, "worker %zu: pipe: %s", k, strerror(errno));
    }
    /* the exec's status: closed by a successful exec (O_CLOEXEC, nothing
     * read), the child's errno when the program cannot start */
    if (pipe2(st, O_CLOEXEC) != 0) {
        close(in[0]), close(in[1]), close(out[0]), close(out[1]);
        return gf_fail(GF_EIO, "worker %zu: pipe: %s", k, strerror(errno));
    }
    fflush(w->log);
    const pid_t pid = fork();
    if (pid < 0) {
        close(in[0]), close(in[1]), close(out[0]), close(out[1]), close(st[0]), close(st[1]);
        return gf_fail(GF_EIO, "worker %zu: fork: %s", k, strerror(errno));
    }
    if (pid == 0) {
        /* the worker: input from the pool, output to the pool, errors to its log */
        dup2(in[1], STDIN_FILENO);
        dup2(out[1], STDOUT_FILENO);
        dup2(fileno(w->log), STDERR_FILENO);
        shutdown(STDIN_FILENO, SHUT_WR);
        execvp(p->argv[0], p->argv);
        const int e = errno;
        fprintf(stderr, "cannot start %s: %s\n", p->argv[0], strerror(e));
        if (write(st[1], &e, sizeof e) < 0) { /* the parent sees no status: it reads the log */
        }
        _exit(127);
    }
    close(in[1]);
    close(out[1]);
    close(st[1]);
    int e = 0;
    ssize_t got;
    while ((got = read(st[0], &e, sizeof e)) < 0 && errno == EINTR) {
    }
    close(st[0]);
    if (got > 0) {
        close(in[0]);
        close(out[0]);
        waitpid(pid, NULL, 0);
        return gf_fail(GF_EIO, "worker %zu: cannot start %s: %s", k, p->argv[0], strerror(e));
    }
    w->pid = pid;
    w->in = in[0];
    w->out = fdopen(out[0], "r");
    if (!w->out) {
        close(out[0]);
        close(in[0]);
        return gf_fail(GF_EIO, "worker %zu: fdopen: %s", k, strerror(errno));
    }
    return GF_SUCCESS;
}

gf_status gf_workers_start(size_t n, char *const argv[], const char *log_fmt, gf_workers **out)
{
    if (!argv || !argv[0] || !log_fmt || !out) return gf_fail(GF_EINVAL, "gf_workers_start: a NULL argument");
    if (n < 1 || n > 256) return gf_fail(GF_EINVAL, "gf_workers_start: %zu workers (allowed 1..256)", n);
    *out = NULL;
    gf_workers *p = calloc(1, sizeof *p);
    if (!p) return gf_fail(GF_ENOMEM, "gf_workers_start: out of memory");
    size_t na = 0;
    while (argv[na]) ++na;
    p->argv = calloc(na + 1, sizeof *p->argv);
    p->logs = calloc(n + 1, sizeof *p->logs);
    p->w = calloc(n, sizeof *p->w);
    if (!p->argv || !p->logs || !p->w) goto nomem;
    for (size_t a = 0; a < na; ++a)
        if (!(p->argv[a] = strdup(argv[a]))) goto nomem;
    p->n = n;
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->idle, NULL);
    for (size_t k = 0; k < n; ++k) {
        const int len = snprintf(NULL, 0, log_fmt, (unsigned)k);
        p->logs[k] = malloc((size_t)len + 1);
        if (!p->logs[k]) goto nomem;
        snprintf(p->logs[k], (size_t)len + 1, log_fmt, (unsigned)k);
        p->w[k].in = -1;
        p->w[k].log = fopen(p->logs[k], "ae");
        if (!p->w[k].log) {
            const gf_status s = gf_fail(GF_EIO, "worker log %s: cannot write: %s", p->logs[k], strerror(errno));
            p->n = k;
            gf_workers_stop(p);
            return s;
        }
        setvbuf(p->w[k].log, NULL, _IOLBF, 0);
        const gf_status s = spawn(p, k);
        if (s != GF_SUCCESS) {
            p->n = k;
            fclose(p->w[k].log);
            gf_workers_stop(p);
            return s;
        }
    }
    *out = p;
    return GF_SUCCESS;
nomem:
    free_argv(p->argv);
    free_argv(p->logs);
    free(p->w);
    free(p);
    return gf_fail(GF_ENOMEM, "gf_workers_start: out of memory");
}

size_t gf_workers_count(const gf_workers *p) { return p ? p->n : 0; }

/* the worker's exit, waited for: its description in buf */
static void reap(worker *w, char *buf, size_t size)
{
    int st = 0;
    if (w->out) fclose(w->out);
    w->out = NULL;
    if (w->in >= 0) close(w->in);
    w->in = -1;
    if (w->pid > 0 && waitpid(w->pid, &st, 0) == w->pid) {
        if (WIFSIGNALED(st))
            snprintf(buf, size, "signal %d", WTERMSIG(st));
        else
            snprintf(buf, size, "exit status %d", WEXITSTATUS(st));
    } else {
        snprintf(buf, size, "not waited for");
    }
    w->pid = 0;
}

gf_status gf_workers_run(gf_workers *p, const char *folder, int *ok, char *why, size_t whysize)
{
    if (!p || !folder || !ok || !why || whysize == 0) return gf_fail(GF_EINVAL, "gf_workers_run: a NULL argument");
    *ok = 0;
    why[0] = '\0';
    char *abs = realpath(folder, NULL);
    if (!abs) return gf_fail(GF_EIO, "member folder %s: %s", folder, strerror(errno));
    if (strchr(abs, '\n')) {
        free(abs);
        return gf_fail(GF_EINVAL, "member folder %s: a line break in its name", folder);
    }
    pthread_mutex_lock(&p->lock);
    size_t k;
    for (;;) {
        for (k = 0; k < p->n && p->w[k].busy; ++k) {
        }
        if (k < p->n) break;
        pthread_cond_wait(&p->idle, &p->lock);
    }
    worker *w = &p->w[k];
    w->busy = 1;
    pthread_mutex_unlock(&p->lock);

    gf_status status = GF_SUCCESS;
    if (w->pid == 0) { /* died with the last member: a new process */
        status = spawn(p, k);
        ++w->restarts;
    }
    if (status == GF_SUCCESS) {
        const size_t len = strlen(abs);
        char *line = malloc(len + 2);
        int sent = 0;
        if (line) {
            memcpy(line, abs, len);
            line[len] = '\n';
            line[len + 1] = '\0';
            size_t done = 0;
            while (done < len + 1) {
                const ssize_t r = send(w->in, line + done, len + 1 - done, MSG_NOSIGNAL);
                if (r < 0 && errno == EINTR) continue;
                if (r <= 0) break;
                done += (size_t)r;
            }
            sent = done == len + 1;
            free(line);
        }
        /* its answer: "member ABS: ok" or "member ABS: FAILED: why" */
        char *buf = NULL;
        size_t cap = 0;
        int answered = 0;
        while (sent && getline(&buf, &cap, w->out) >= 0) {
            fputs(buf, w->log);
            if (strncmp(buf, "member ", 7) == 0 && strncmp(buf + 7, abs, len) == 0 && buf[7 + len] == ':') {
                const char *rest = buf + 7 + len + 1;
                if (strncmp(rest, " ok", 3) == 0) {
                    *ok = 1;
                    answered = 1;
                    break;
                }
                if (strncmp(rest, " FAILED: ", 9) == 0) {
                    snprintf(why, whysize, "%s", rest + 9);
                    const size_t wl = strlen(why);
                    if (wl && why[wl - 1] == '\n') why[wl - 1] = '\0';
                    answered = 1;
                    break;
                }
            }
        }
        free(buf);
        if (!answered) {
            char st[64];
            reap(w, st, sizeof st);
            snprintf(why, whysize, "the worker process ended in this member (%s; %s)", st, p->logs[k]);
        }
    }
    pthread_mutex_lock(&p->lock);
    w->busy = 0;
    pthread_cond_signal(&p->idle);
    pthread_mutex_unlock(&p->lock);
    free(abs);
    return status;
}

gf_status gf_workers_stop(gf_workers *p)
{
    if (!p) return GF_SUCCESS;
    gf_status status = GF_SUCCESS;
    for (size_t k = 0; k < p->n; ++k) {
        worker *w = &p->w[k];
        if (w->in >= 0) shutdown(w->in, SHUT_WR);
        if (w->out) { /* the rest of its output (the end of its run) to its log */
            char *buf = NULL;
            size_t cap = 0;
            while (getline(&buf, &cap, w->out) >= 0) fputs(buf, w->log);
            free(buf);
        }
        if (w->pid > 0) {
            char st[64];
            reap(w, st, sizeof st);
            if (strcmp(st, "exit status 0") != 0 && status == GF_SUCCESS)
                status = gf_fail(GF_EIO, "worker %zu ended with %s (%s)", k, st, p->logs[k]);
        }
        if (w->log) fclose(w->log);
    }
    if (p->n) {
        pthread_mutex_destroy(&p->lock);
        pthread_cond_destroy(&p->idle);
    }
    free_argv(p->argv);
    free_argv(p->logs);
    free(p->w);
    free(p);
    return status;
}
