/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — ensemble workers: solver processes that load a case's meshes
 * once and run member folders on demand (faGranularFlowFoam -members -,
 * doc/theory/hazard-analysis.md section 4; doc/theory/calibration.md).
 *
 * A pool starts n copies of a program whose standard input takes one member
 * folder per line and whose standard output answers each with
 *     member FOLDER: ok
 *     member FOLDER: FAILED: <reason>
 * (the solver's memberRuns.H).  gf_workers_run hands a folder to an idle
 * worker and waits for its answer; it may be called from several threads
 * at once (one member per worker at a time), so that a driver that decides
 * its next runs from the last results (a simplex refinement per thread)
 * keeps every worker busy.  A worker that dies fails the member it was
 * running (with its exit status) and is started again for the next one.
 * Every line a worker prints goes to its log file.
 */
#ifndef GRANFLOW_WORKERS_H
#define GRANFLOW_WORKERS_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gf_workers gf_workers;

/** Start n workers (1 <= n <= 256), each `argv` (argv[0] looked up on PATH,
 *  NULL-terminated; the folder list is its standard input), its standard
 *  output and error appended to log_fmt with %u the worker's number 0..n-1
 *  (e.g. "DIR/log.worker_%u").  The processes start now (their set-up
 *  overlaps).  Refused: n outside the range, a NULL argument (GF_EINVAL); a
 *  log that cannot be opened, a program that cannot be started (GF_EIO). */
gf_status gf_workers_start(size_t n, char *const argv[], const char *log_fmt, gf_workers **out);

/** Run one member folder (made absolute and canonical here: it must exist)
 *  on the next idle worker; blocks until the worker answers.  *ok = 1 for
 *  "ok"; 0 for a failed member, its reason in why (the worker's message, or
 *  "the worker process ended in this member (exit status S; LOG)").
 *  Thread-safe.  Refused: a NULL argument (GF_EINVAL); a folder that does
 *  not exist (GF_EIO); a pool whose workers cannot be restarted (GF_EIO). */
gf_status gf_workers_run(gf_workers *p, const char *folder, int *ok, char *why, size_t whysize);

/** Workers in the pool. */
size_t gf_workers_count(const gf_workers *p);

/** End the workers (their input closed, then waited for) and free the pool;
 *  GF_EIO when a worker ended with an error status. */
gf_status gf_workers_stop(gf_workers *p);

#ifdef __cplusplus
}
#endif

#endif
