# SPDX-License-Identifier: GPL-3.0-or-later
"""granflow's command-line tools run from Processing.

Every algorithm of the provider runs the command a user types in a shell
(gfRunCase, gfPathAnalysis, gfRunEnsemble), in the environment of granflow's
etc/bashrc, as a subprocess in its own process group: its output goes to the
algorithm's log line by line, a parser turns lines into progress, and Cancel
stops the whole group (the tool, the solver, mpirun, tail, ...) and waits
until no process of it is left before the caller removes what it wrote.

granflow's folder (GRANFLOW_DIR) is, in this order: the Processing setting
"granflow folder" (Settings > Options > Processing > Providers > granflow),
the environment variable GRANFLOW_DIR, or the repository the plugin lies in
(qgis/granflow inside granflow's checkout, found through QGIS_PLUGINPATH).
"""
import os
import queue
import shlex
import signal
import subprocess
import threading
import time

from qgis.core import QgsProcessingException

SETTING_DIR = 'GRANFLOW_DIR'
PLUGIN_DIR = os.path.dirname(os.path.abspath(__file__))

# the environment of etc/bashrc, then the tool; a tool that is not built is
# named (exit 127) instead of bash's "command not found"
WRAPPER = r'''
. "$1/etc/bashrc" > /dev/null 2>&1
shift
command -v "$1" > /dev/null 2>&1 || {
    echo "granflow: $1 not found: build granflow first ($GRANFLOW_DIR/Allwmake)" >&2; exit 127; }
exec "$@"
'''


class Cancelled(Exception):
    """The user pressed Cancel; the tool's processes are gone."""


def granflow_dir():
    """granflow's folder: the Processing setting, GRANFLOW_DIR, or the
    repository the plugin lies in; refused when it has no etc/bashrc."""
    given = []
    try:
        from processing.core.ProcessingConfig import ProcessingConfig
        value = ProcessingConfig.getSetting(SETTING_DIR)
        if value:
            given.append(('the Processing setting "granflow folder"', value))
    except ImportError:
        pass
    if os.environ.get('GRANFLOW_DIR'):
        given.append(('the environment variable GRANFLOW_DIR', os.environ['GRANFLOW_DIR']))
    if given:
        what, path = given[0]
        if not os.path.isfile(os.path.join(path, 'etc', 'bashrc')):
            raise QgsProcessingException(
                '{} is {}: no etc/bashrc there (granflow\'s checkout is needed)'.format(what, path))
        return os.path.abspath(path)
    path = os.path.normpath(os.path.join(PLUGIN_DIR, os.pardir, os.pardir))
    if not os.path.isfile(os.path.join(path, 'etc', 'bashrc')):
        raise QgsProcessingException(
            'granflow not found: set Settings > Options > Processing > Providers > granflow > '
            '"granflow folder", or the environment variable GRANFLOW_DIR, to granflow\'s checkout')
    return path


def command_line(args):
    """The command as a user would type it in a shell."""
    return ' '.join(shlex.quote(str(a)) for a in args)


def _group_alive(pgid):
    """Whether a process of the group is left (zombies do not count: a
    container's init may never reap them)."""
    for pid in os.listdir('/proc'):
        if not pid.isdigit():
            continue
        try:
            with open('/proc/{}/stat'.format(pid)) as f:
                stat = f.read()
        except OSError:
            continue
        fields = stat[stat.rfind(')') + 2:].split()
        if len(fields) > 2 and fields[0] != 'Z' and int(fields[2]) == pgid:
            return True
    return False


def stop_group(proc, grace=30.0):
    """SIGTERM to the process group of proc (the solver writes its time and
    stops: stopAtWriteNowSignal 15), SIGKILL after grace seconds; returns
    when no process of the group is left."""
    pgid = proc.pid
    start = time.monotonic()
    for sig, wait in ((signal.SIGTERM, grace), (signal.SIGKILL, 10.0)):
        try:
            os.killpg(pgid, sig)
        except ProcessLookupError:
            pass
        end = time.monotonic() + wait
        while time.monotonic() < end:
            proc.poll()
            if not _group_alive(pgid):
                proc.wait()
                return '{} after {:.1f} s'.format(signal.Signals(sig).name, time.monotonic() - start)
            time.sleep(0.1)
    proc.wait()
    return 'not all gone after SIGKILL'



def run_tool(args, feedback, progress=None, cwd=None, env=None, idle=None):
    """Runs a granflow tool (args: the command and its options) in the
    environment of etc/bashrc, in its own process group; every output line
    goes to the log and to progress(line) (a percentage or None), and while
    no line comes idle() (a percentage or None) is asked every 0.2 s (the
    progress of a step that prints nothing).  Returns (exit status, output
    lines); raises Cancelled after stopping the group when the user
    cancels."""
    gdir = granflow_dir()
    feedback.pushCommandInfo(command_line(args))
    full_env = dict(os.environ)
    full_env.update(env or {})
    proc = subprocess.Popen(['bash', '-c', WRAPPER, 'granflow', gdir] + [str(a) for a in args],
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            cwd=cwd, env=full_env, start_new_session=True,
                            universal_newlines=True, errors='replace', bufsize=1)
    lines = queue.Queue()

    def read():
        with proc.stdout:
            for line in proc.stdout:
                lines.put(line)
        lines.put(None)
    threading.Thread(target=read, daemon=True).start()
    out = []
    try:
        while True:
            if feedback.isCanceled():
                feedback.pushInfo('Cancelled: stopping {} (process group {})'.format(args[0], proc.pid))
                how = stop_group(proc)
                feedback.pushInfo('Cancelled: process group {} ended ({})'.format(proc.pid, how))
                raise Cancelled()
            try:
                line = lines.get(timeout=0.2)
            except queue.Empty:
                p = idle() if idle else None
                if p is not None:
                    feedback.setProgress(max(0.0, min(100.0, p)))
                continue
            if line is None:
                break
            line = line.rstrip('\n')
            out.append(line)
            feedback.pushConsoleInfo(line)
            if progress:
                p = progress(line)
                if p is not None:
                    feedback.setProgress(max(0.0, min(100.0, p)))
    except Cancelled:
        raise
    except BaseException:
        stop_group(proc)
        raise
    return proc.wait(), out


def failure(tool, lines):
    """The reason a tool failed, from its output: its own refusal
    ("gfRunCase: ..."), an OpenFOAM FATAL ERROR's text, or the last lines."""
    own = [l for l in lines if l.startswith(tool + ': ') or l.startswith('granflow: ') and 'not found' in l]
    fatal = []
    for i, l in enumerate(lines):
        if 'FOAM FATAL' in l:
            for m in lines[i + 1:]:
                if not m.strip():
                    if fatal:
                        break
                    continue
                if m.strip().startswith('From ') or m.strip().startswith('in file'):
                    continue
                fatal.append(m.strip())
            break
    if own and not fatal:
        # the tool's last message, with its indented lines (the cause, the
        # command that redoes a step)
        i = len(lines) - 1 - lines[::-1].index(own[-1])
        more = []
        for l in lines[i + 1:i + 9]:
            if not l.startswith(' '):
                break
            more.append(l.strip())
        return ' '.join([own[-1]] + more)
    if fatal:
        return ' '.join(fatal)
    return '\n'.join(lines[-12:])
