/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Ensemble workers (gf_workers, granflow/workers.h) with fake worker
 * programs instead of the solver: sh scripts that read one member folder a
 * line and answer "member FOLDER: ok" or "member FOLDER: FAILED: why", or
 * die in a member.  The pool hands each folder (made canonical) to one
 * worker and reads its answer, reports a worker's death with its exit
 * status and log and starts it again, serves several threads at once with
 * one member per worker, writes the workers' lines to their logs, and
 * refuses what it must. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "../gf_test.h"
#include "../gf_tmpdir.h"

#include <pthread.h>
#include <sched.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "granflow/workers.h"

GF_TMPDIR_FIXTURES("gf_workers")

/* the fake workers */
#define WORKER_OK "while IFS= read -r f; do echo \"member $f: ok\"; done"
/* noise, an answer for another folder whose name starts with this one's,
 * then the answer: FAILED for a folder named *bad* */
#define WORKER_MIXED                                                                                        \
    "while IFS= read -r f; do echo \"reading $f\"; echo \"member ${f}x: ok\"; case \"$f\" in "              \
    "*bad*) echo \"member $f: FAILED: some reason\";; *) echo \"member $f: ok\";; esac; done"
/* dies in a folder named *die* (exit 3, a line on its standard error
 * first), or *kill* (SIGKILL) */
#define WORKER_DIES                                                                                         \
    "while IFS= read -r f; do case \"$f\" in *die*) echo \"worker dies in $f\" >&2; exit 3;; "              \
    "*kill*) kill -9 $$;; esac; echo \"member $f: ok\"; done"
/* answers every member, then ends with exit status 2 */
#define WORKER_ENDS_BADLY "while IFS= read -r f; do echo \"member $f: ok\"; done; exit 2"
/* writes FOLDER/started, waits for FOLDER/go, answers ok */
#define WORKER_WAITS                                                                                        \
    "while IFS= read -r f; do : > \"$f/started\"; while [ ! -e \"$f/go\" ]; do sleep 0.01; done; "          \
    "echo \"member $f: ok\"; done"

static void start(const char *script, size_t n, const char *log_name, gf_workers **p)
{
    char *argv[] = {"sh", "-c", (char *)script, NULL};
    char fmt[200];
    snprintf(fmt, sizeof fmt, "%s/%s_%%u", tmpdir, log_name);
    *p = NULL;
    assert_int_equal(gf_workers_start(n, argv, fmt, p), GF_SUCCESS);
    assert_non_null(*p);
    assert_int_equal(gf_workers_count(*p), n);
}

/* a folder tmpdir/name, made; its canonical path in real */
static void folder(const char *name, char *path, size_t size, char *real)
{
    snprintf(path, size, "%s", tmp(name));
    assert_int_equal(mkdir(path, 0755), 0);
    if (real) {
        char *r = realpath(path, NULL);
        assert_non_null(r);
        snprintf(real, 4096, "%s", r);
        free(r);
    }
}

/* the text of the logs tmpdir/log_name_0 .. _(n-1), one after the other */
static char *read_logs(const char *log_name, size_t n)
{
    size_t len = 0, cap = 1;
    char *text = calloc(1, 1);
    assert_non_null(text);
    for (size_t k = 0; k < n; ++k) {
        char path[256];
        snprintf(path, sizeof path, "%s/%s_%zu", tmpdir, log_name, k);
        FILE *f = fopen(path, "r");
        assert_non_null(f);
        char buf[4096];
        size_t r;
        while ((r = fread(buf, 1, sizeof buf, f)) > 0) {
            if (len + r + 1 > cap) {
                cap = 2 * (len + r + 1);
                text = realloc(text, cap);
                assert_non_null(text);
            }
            memcpy(text + len, buf, r);
            len += r;
            text[len] = '\0';
        }
        fclose(f);
    }
    return text;
}

/* the lines of text equal to line */
static size_t count_lines(const char *text, const char *line)
{
    size_t n = 0;
    const size_t len = strlen(line);
    for (const char *t = text; *t;) {
        const char *end = strchr(t, '\n');
        const size_t l = end ? (size_t)(end - t) : strlen(t);
        n += l == len && strncmp(t, line, len) == 0;
        t += l + (end != NULL);
    }
    return n;
}

static size_t count_answers(const char *text, const char *real, const char *answer)
{
    char line[4300];
    snprintf(line, sizeof line, "member %.4096s: %.190s", real, answer);
    return count_lines(text, line);
}

/* Two workers answer six members ok, the folders given in any form (a
 * trailing slash, a "..") made canonical; each answer in the logs once;
 * the pool ends cleanly */
static void members_are_answered_ok_and_logged(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_OK, 2, "log.ok", &p);
    char path[6][256], real[6][4096], given[6][300], sub[256];
    folder("sub", sub, sizeof sub, NULL);
    for (int i = 0; i < 6; ++i) {
        char name[16];
        snprintf(name, sizeof name, "ok%d", i);
        folder(name, path[i], sizeof path[i], real[i]);
        if (i == 3)
            snprintf(given[i], sizeof given[i], "%.256s/", path[i]);
        else if (i == 4)
            snprintf(given[i], sizeof given[i], "%.256s/../%.16s", sub, name);
        else
            snprintf(given[i], sizeof given[i], "%.256s", path[i]);
    }
    for (int i = 0; i < 6; ++i) {
        int ok = -1;
        char why[256] = "junk";
        assert_int_equal(gf_workers_run(p, given[i], &ok, why, sizeof why), GF_SUCCESS);
        assert_int_equal(ok, 1);
        assert_string_equal(why, "");
    }
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
    char *text = read_logs("log.ok", 2);
    for (int i = 0; i < 6; ++i)
        assert_int_equal(count_answers(text, real[i], "ok"), 1);
    assert_int_equal(count_lines(text, ""), 0);
    free(text);
    assert_int_equal(gf_workers_count(NULL), 0);
    assert_int_equal(gf_workers_stop(NULL), GF_SUCCESS);
}

/* A member the worker fails: ok 0 and the worker's reason, cut to the
 * buffer; the worker's other lines (and an answer for another folder whose
 * name starts with this one's) are not the answer but go to the log; the
 * next member is ok */
static void failed_member_gives_the_workers_reason(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_MIXED, 1, "log.mixed", &p);
    char bad[256], bad_real[4096], good[256], good_real[4096];
    folder("bad1", bad, sizeof bad, bad_real);
    folder("good1", good, sizeof good, good_real);
    int ok = -1;
    char why[256];
    assert_int_equal(gf_workers_run(p, bad, &ok, why, sizeof why), GF_SUCCESS);
    assert_int_equal(ok, 0);
    assert_string_equal(why, "some reason");
    assert_int_equal(gf_workers_run(p, good, &ok, why, sizeof why), GF_SUCCESS);
    assert_int_equal(ok, 1);
    assert_string_equal(why, "");
    char small[5];
    assert_int_equal(gf_workers_run(p, bad, &ok, small, sizeof small), GF_SUCCESS);
    assert_int_equal(ok, 0);
    assert_string_equal(small, "some");
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
    char *text = read_logs("log.mixed", 1);
    char line[4300];
    assert_int_equal(count_answers(text, bad_real, "FAILED: some reason"), 2);
    assert_int_equal(count_answers(text, good_real, "ok"), 1);
    snprintf(line, sizeof line, "reading %s", bad_real);
    assert_int_equal(count_lines(text, line), 2);
    snprintf(line, sizeof line, "member %sx: ok", good_real);
    assert_int_equal(count_lines(text, line), 1);
    free(text);
}

/* A worker that ends in a member (exit 3, or SIGKILL) fails that member
 * with "the worker process ended in this member (exit status 3; LOG)" (or
 * "signal 9") and is started again: the next member runs ok on it; its
 * standard error goes to the log; the restarted worker ends cleanly */
static void worker_that_dies_fails_the_member_and_is_restarted(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_DIES, 1, "log.dies", &p);
    char names[5][16] = {"m0", "die0", "m1", "kill0", "m2"};
    char path[5][256], real[5][4096];
    for (int i = 0; i < 5; ++i)
        folder(names[i], path[i], sizeof path[i], real[i]);
    char log[256], want[512], why[512];
    snprintf(log, sizeof log, "%s/log.dies_0", tmpdir);
    for (int i = 0; i < 5; ++i) {
        int ok = -1;
        assert_int_equal(gf_workers_run(p, path[i], &ok, why, sizeof why), GF_SUCCESS);
        if (i == 1 || i == 3) {
            snprintf(want, sizeof want, "the worker process ended in this member (%s; %s)",
                     i == 1 ? "exit status 3" : "signal 9", log);
            assert_int_equal(ok, 0);
            assert_string_equal(why, want);
        } else {
            assert_int_equal(ok, 1);
            assert_string_equal(why, "");
        }
    }
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
    char *text = read_logs("log.dies", 1);
    for (int i = 0; i < 5; i += 2)
        assert_int_equal(count_answers(text, real[i], "ok"), 1);
    char line[4300];
    snprintf(line, sizeof line, "worker dies in %s", real[1]);
    assert_int_equal(count_lines(text, line), 1);
    assert_int_equal(count_answers(text, real[1], "ok"), 0);
    assert_int_equal(count_answers(text, real[3], "ok"), 0);
    free(text);
}

/* several threads, one pool */
enum { POOL = 3, CALLERS = 6, PER_CALLER = 10 };
typedef struct caller {
    gf_workers *p;
    int id;
    char path[PER_CALLER][256];
    gf_status st[PER_CALLER];
    int ok[PER_CALLER];
    char why[PER_CALLER][512];
} caller;

static int is_die(int id, int i) { return (id * PER_CALLER + i) % 7 == 4; }

static void *caller_thread(void *arg)
{
    caller *c = arg;
    for (int i = 0; i < PER_CALLER; ++i)
        c->st[i] = gf_workers_run(c->p, c->path[i], &c->ok[i], c->why[i], sizeof c->why[i]);
    return NULL;
}

/* Six threads run ten members each on a pool of three workers at once,
 * every seventh member one the worker dies in: each member is answered ok
 * exactly once (one answer line in the logs) or failed with the worker's
 * death and one of the logs; the workers are restarted in between */
static void concurrent_runs_answer_each_member_once(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_DIES, POOL, "log.conc", &p);
    static caller c[CALLERS];
    static char real[CALLERS][PER_CALLER][4096];
    for (int t = 0; t < CALLERS; ++t) {
        c[t].p = p;
        c[t].id = t;
        for (int i = 0; i < PER_CALLER; ++i) {
            char name[32];
            snprintf(name, sizeof name, "%s%d_%d", is_die(t, i) ? "die" : "c", t, i);
            folder(name, c[t].path[i], sizeof c[t].path[i], real[t][i]);
        }
    }
    pthread_t th[CALLERS];
    for (int t = 0; t < CALLERS; ++t)
        assert_int_equal(pthread_create(&th[t], NULL, caller_thread, &c[t]), 0);
    for (int t = 0; t < CALLERS; ++t)
        assert_int_equal(pthread_join(th[t], NULL), 0);
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
    char *text = read_logs("log.conc", POOL);
    int n_ok = 0, n_died = 0;
    for (int t = 0; t < CALLERS; ++t)
        for (int i = 0; i < PER_CALLER; ++i) {
            assert_int_equal(c[t].st[i], GF_SUCCESS);
            if (is_die(t, i)) {
                ++n_died;
                assert_int_equal(c[t].ok[i], 0);
                const char *prefix = "the worker process ended in this member (exit status 3; ";
                assert_int_equal(strncmp(c[t].why[i], prefix, strlen(prefix)), 0);
                int logs = 0;
                for (int k = 0; k < POOL; ++k) {
                    char tail[300];
                    snprintf(tail, sizeof tail, "%s/log.conc_%d)", tmpdir, k);
                    logs += strcmp(c[t].why[i] + strlen(prefix), tail) == 0;
                }
                assert_int_equal(logs, 1);
                assert_int_equal(count_answers(text, real[t][i], "ok"), 0);
            } else {
                ++n_ok;
                assert_int_equal(c[t].ok[i], 1);
                assert_string_equal(c[t].why[i], "");
                assert_int_equal(count_answers(text, real[t][i], "ok"), 1);
            }
        }
    assert_int_equal(n_ok + n_died, CALLERS * PER_CALLER);
    assert_true(n_died >= 8);
    free(text);
}

static void pause_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void *run_one(void *arg)
{
    caller *c = arg;
    c->st[0] = gf_workers_run(c->p, c->path[0], &c->ok[0], c->why[0], sizeof c->why[0]);
    return NULL;
}

static int exists_in(const char *dir, const char *name)
{
    char f[300];
    snprintf(f, sizeof f, "%s/%s", dir, name);
    return access(f, F_OK) == 0;
}

static void touch_in(const char *dir, const char *name)
{
    char f[300];
    snprintf(f, sizeof f, "%s/%s", dir, name);
    FILE *o = fopen(f, "w");
    assert_non_null(o);
    fclose(o);
}

/* Three workers hold three members at once (each worker has written its
 * member's "started" and waits for "go"), while a fourth caller waits for
 * an idle worker: its member has not started; released, all four are ok */
static void workers_run_members_at_once_one_each(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_WAITS, POOL, "log.wait", &p);
    static caller c[POOL + 1];
    pthread_t th[POOL + 1];
    for (int t = 0; t <= POOL; ++t) {
        char name[16];
        snprintf(name, sizeof name, "w%d", t);
        c[t].p = p;
        folder(name, c[t].path[0], sizeof c[t].path[0], NULL);
    }
    for (int t = 0; t < POOL; ++t)
        assert_int_equal(pthread_create(&th[t], NULL, run_one, &c[t]), 0);
    int started = 0; /* a bounded wait for the three (no time asserted) */
    for (long spin = 0; spin < 3000 && started < POOL; ++spin) {
        started = 0;
        for (int t = 0; t < POOL; ++t)
            started += exists_in(c[t].path[0], "started");
        if (started < POOL)
            pause_ms(10);
    }
    assert_int_equal(started, POOL);
    assert_int_equal(pthread_create(&th[POOL], NULL, run_one, &c[POOL]), 0);
    for (int k = 0; k < 20; ++k)
        sched_yield();
    pause_ms(50);
    assert_false(exists_in(c[POOL].path[0], "started")); /* every worker busy */
    for (int t = 0; t <= POOL; ++t)
        touch_in(c[t].path[0], "go");
    for (int t = 0; t <= POOL; ++t) {
        assert_int_equal(pthread_join(th[t], NULL), 0);
        assert_int_equal(c[t].st[0], GF_SUCCESS);
        assert_int_equal(c[t].ok[0], 1);
    }
    assert_true(exists_in(c[POOL].path[0], "started"));
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
}

/* A folder that does not exist: GF_EIO naming it, and the pool still runs
 * the next one; a folder with a line break in its name, NULL arguments and
 * an empty reason buffer refused (GF_EINVAL) */
static void missing_folder_and_bad_arguments_are_refused(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_OK, 1, "log.missing", &p);
    char good[256], nope[256], nl[256];
    folder("there", good, sizeof good, NULL);
    snprintf(nope, sizeof nope, "%s/not-there", tmpdir);
    int ok = -1;
    char why[256];
    assert_int_equal(gf_workers_run(p, nope, &ok, why, sizeof why), GF_EIO);
    assert_int_equal(ok, 0);
    assert_non_null(strstr(gf_error_detail(), "not-there"));
    folder("line\nbreak", nl, sizeof nl, NULL);
    assert_int_equal(gf_workers_run(p, nl, &ok, why, sizeof why), GF_EINVAL);
    assert_int_equal(gf_workers_run(NULL, good, &ok, why, sizeof why), GF_EINVAL);
    assert_int_equal(gf_workers_run(p, NULL, &ok, why, sizeof why), GF_EINVAL);
    assert_int_equal(gf_workers_run(p, good, NULL, why, sizeof why), GF_EINVAL);
    assert_int_equal(gf_workers_run(p, good, &ok, NULL, sizeof why), GF_EINVAL);
    assert_int_equal(gf_workers_run(p, good, &ok, why, 0), GF_EINVAL);
    assert_int_equal(gf_workers_run(p, good, &ok, why, sizeof why), GF_SUCCESS);
    assert_int_equal(ok, 1);
    assert_int_equal(gf_workers_stop(p), GF_SUCCESS);
}

/* gf_workers_start refuses 0 or more than 256 workers and NULL arguments
 * (GF_EINVAL) and a log it cannot open (GF_EIO), leaving no pool */
static void start_refuses_bad_pools(void **state)
{
    (void)state;
    char *argv[] = {"sh", "-c", WORKER_OK, NULL}, *none[] = {NULL};
    char fmt[256], nodir[256];
    snprintf(fmt, sizeof fmt, "%s/log.refused_%%u", tmpdir);
    snprintf(nodir, sizeof nodir, "%s/no-such-dir/log_%%u", tmpdir);
    static int dummy;
    gf_workers *p = (gf_workers *)(void *)&dummy;
    assert_int_equal(gf_workers_start(0, argv, fmt, &p), GF_EINVAL);
    assert_int_equal(gf_workers_start(257, argv, fmt, &p), GF_EINVAL);
    assert_int_equal(gf_workers_start(1, NULL, fmt, &p), GF_EINVAL);
    assert_int_equal(gf_workers_start(1, none, fmt, &p), GF_EINVAL);
    assert_int_equal(gf_workers_start(1, argv, NULL, &p), GF_EINVAL);
    assert_int_equal(gf_workers_start(1, argv, fmt, NULL), GF_EINVAL);
    assert_int_equal(gf_workers_start(2, argv, nodir, &p), GF_EIO);
    assert_null(p);
    assert_non_null(strstr(gf_error_detail(), "no-such-dir"));
}

/* A program that cannot be started is refused by gf_workers_start
 * (GF_EIO, the program and the reason named; workers.h): the child's exec
 * failure comes back through a close-on-exec status pipe, so no pool is
 * made and no member is handed to a worker that will never answer; the
 * worker's log names it too */
static void program_that_cannot_start_is_refused(void **state)
{
    (void)state;
    char *argv[] = {"/nonexistent/gf-no-such-worker", NULL};
    char fmt[256];
    snprintf(fmt, sizeof fmt, "%s/log.nostart_%%u", tmpdir);
    gf_workers *p = (gf_workers *)1;
    assert_int_equal(gf_workers_start(1, argv, fmt, &p), GF_EIO);
    assert_null(p);
    assert_non_null(strstr(gf_error_detail(), "cannot start /nonexistent/gf-no-such-worker"));
    assert_non_null(strstr(gf_error_detail(), "No such file or directory"));
    char *text = read_logs("log.nostart", 1);
    assert_non_null(strstr(text, "cannot start /nonexistent/gf-no-such-worker"));
    free(text);
}

/* gf_workers_stop: GF_EIO naming the status when a worker ends with a
 * non-zero exit status (after answering its members ok) */
static void stop_reports_a_worker_that_exits_nonzero(void **state)
{
    (void)state;
    gf_workers *p;
    start(WORKER_ENDS_BADLY, 2, "log.ends", &p);
    char m[256];
    folder("ends0", m, sizeof m, NULL);
    int ok = -1;
    char why[256];
    assert_int_equal(gf_workers_run(p, m, &ok, why, sizeof why), GF_SUCCESS);
    assert_int_equal(ok, 1);
    assert_int_equal(gf_workers_stop(p), GF_EIO);
    assert_non_null(strstr(gf_error_detail(), "exit status 2"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(members_are_answered_ok_and_logged),
        cmocka_unit_test(failed_member_gives_the_workers_reason),
        cmocka_unit_test(worker_that_dies_fails_the_member_and_is_restarted),
        cmocka_unit_test(concurrent_runs_answer_each_member_once),
        cmocka_unit_test(workers_run_members_at_once_one_each),
        cmocka_unit_test(missing_folder_and_bad_arguments_are_refused),
        cmocka_unit_test(start_refuses_bad_pools),
        cmocka_unit_test(program_that_cannot_start_is_refused),
        cmocka_unit_test(stop_reports_a_worker_that_exits_nonzero),
    };
    return gf_run_tests("workers", tests, setup, teardown);
}
