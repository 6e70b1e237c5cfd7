#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Cancel in the granflow plugin's Avalanche simulation, headless.

    cancel.py DEM RELEASE CELLSIZE OUTPUT

Runs granflow:simulation in a standalone QGIS (QT_QPA_PLATFORM=offscreen),
the plugin loaded from $GRANFLOW_DIR/qgis as QGIS loads it, on the DEM and
release files at CELLSIZE with a stop fraction that keeps the solver
running; the feedback's Cancel is pressed when the first
progress line of the solver arrives (as a user pressing Cancel in the
dialog).  Checks: the algorithm ends with the "Cancelled" error, the solver
had not ended (no "End condition" in the log), OUTPUT is gone, and no
process is left in it (no process's working folder lies in OUTPUT).
Prints one line with the times; exit status 1 on a failed check."""
import os
import sys
import time

from qgis.core import QgsApplication, QgsProcessingException, QgsProcessingFeedback


def main():
    dem, release, cell, out = sys.argv[1], sys.argv[2], float(sys.argv[3]), os.path.abspath(sys.argv[4])
    app = QgsApplication([], False)
    app.initQgis()
    sys.path.append('/usr/share/qgis/python/plugins')
    sys.path.insert(0, os.path.join(os.environ['GRANFLOW_DIR'], 'qgis'))
    from processing.core.Processing import Processing
    Processing.initialize()
    import processing
    from granflow.plugin import GranflowPlugin
    plugin = GranflowPlugin()
    plugin.initProcessing()

    feedback = QgsProcessingFeedback()
    log, marks = [], {}
    feedback.pushConsoleInfo = lambda text: log.append(text)
    feedback.pushInfo = lambda text: log.append(text)

    def on_progress(p):
        if p > 5 and 'cancel' not in marks:
            marks['cancel'] = time.monotonic()
            feedback.cancel()
    feedback.progressChanged.connect(on_progress)
    params = {'DEM': dem, 'RELEASE': release, 'CELL_SIZE': cell, 'STOP_FRACTION': 1e-7, 'END_TIME': 3000,
              'OUTPUT': out}
    start = time.monotonic()
    error = ''
    try:
        processing.run('granflow:simulation', params, feedback=feedback)
    except QgsProcessingException as e:
        error = str(e)
    end = time.monotonic()
    fails = []
    if 'cancel' not in marks:
        fails.append('Cancel was never pressed (no solver progress)')
    if not error.startswith('Cancelled'):
        fails.append('the algorithm did not end cancelled: {}'.format(error or 'it succeeded'))
    if not any('granflow: t = ' in l for l in log):
        fails.append('no solver progress line before the cancel')
    if any(l.startswith('End condition') for l in log):
        fails.append('the solver had ended before the cancel (End condition in the log)')
    if os.path.exists(out):
        fails.append('{} is left: {}'.format(out, os.listdir(out)))
    left = []
    for pid in os.listdir('/proc'):
        try:
            cwd = os.readlink('/proc/{}/cwd'.format(pid))
        except OSError:
            continue
        if cwd.startswith(out):
            left.append('{} ({})'.format(pid, cwd))
    if left:
        fails.append('processes left in the folder: {}'.format(', '.join(left)))
    plugin.unload()
    app.exitQgis()
    if fails:
        for f in fails:
            print('FAILED: cancel: ' + f)
        return 1
    ended = next((l.split('(')[-1].rstrip(')') for l in log if 'process group' in l and 'ended' in l), '?')
    print('cancelled {:.1f} s after the start, at the solver\'s first progress line; the processes ended on {}, '
          'all stopped and removed in {:.1f} s; no folder and no process left ({})'
          .format(marks['cancel'] - start, ended, end - marks['cancel'], error))
    return 0


if __name__ == '__main__':
    sys.exit(main())
