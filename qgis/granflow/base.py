# SPDX-License-Identifier: GPL-3.0-or-later
"""What the algorithms share: the case parameters (DEM, release, optional
entrainment, resistance, dam, path, split point; friction, density, cell
size, stop criterion, end time), their checks, and the gfRunCase run with
its progress and Cancel."""
import os
import re
import shutil

from qgis.core import (QgsProcessing, QgsProcessingAlgorithm, QgsProcessingException,
                       QgsProcessingParameterBoolean, QgsProcessingParameterDefinition,
                       QgsProcessingParameterEnum, QgsProcessingParameterFeatureSource,
                       QgsProcessingParameterField, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterString)

from .inputs import MARKER, CaseInputs, InputError, check_folder
from .runner import Cancelled, failure, run_tool

FRICTIONS = ['samosATAuto', 'samosAT', 'samosATMedium', 'samosATSmall']
# the report maps (gfReportMaps, run by gfRunCase) in OUTPUT/run/postProcessing/hazardMaps/report
REPORT_MAPS = [('REPORT_HPEAK', 'hPeak', 'Report map: peak flow thickness (PDF; PNG beside it)'),
               ('REPORT_SPEED_PEAK', 'speedPeak', 'Report map: peak flow speed (PDF; PNG beside it)'),
               ('REPORT_PRESSURE_PEAK', 'pressurePeak', 'Report map: peak pressure (PDF; PNG beside it)'),
               ('REPORT_PRESSURE_ZONES', 'pressureZones', 'Report map: pressure zones (PDF; PNG beside it)')]
DEFAULT_END_TIME = 400.0   # [s] the cap (AvaFrame's default; etc/caseTemplate's endTime)


def num(v):
    """A number as the command line takes it (200, 0.01, 1e-05)."""
    return '%.15g' % v


class GranflowAlgorithm(QgsProcessingAlgorithm):
    """The provider's algorithms: their group, help and helpers."""

    def group(self):
        return ''

    def groupId(self):
        return ''

    HELP = ''

    def shortHelpString(self):
        # one line per paragraph: the dialog's help panel breaks lines where the text does
        return ' '.join(self.HELP.split())

    def createInstance(self):
        return type(self)()

    def helpUrl(self):
        return 'file://' + os.path.normpath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir,
                                                         'doc', 'guide', 'qgis.md'))

    def has_value(self, parameters, name):
        v = parameters.get(name)
        return v is not None and v != '' and not (hasattr(v, 'isNull') and v.isNull())

    def parameter_names(self):
        return [p.name() for p in self.parameterDefinitions()]

    def advanced(self, param):
        param.setFlags(param.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
        self.addParameter(param)

    def add_enum(self, name, description, options, default, advanced=False):
        """A choice among names: the dialog's list; in qgis_process and
        processing.run the name (or its number, from 0); the description
        lists the names."""
        p = QgsProcessingParameterEnum(name, '{}: {}'.format(description, ', '.join(options)), options, False,
                                       default, False)
        p.setUsesStaticStrings(True)
        p.setHelp('one of {} (the name, or its number 0 to {})'.format(', '.join(options), len(options) - 1))
        if advanced:
            self.advanced(p)
        else:
            self.addParameter(p)

    def enum_string(self, parameters, name):
        """An enum parameter's name: given as a name or its number (0, 1,
        ...); the default when not given.  InputError for anything else,
        with the valid names."""
        p = self.parameterDefinition(name)
        options = p.options()
        v = parameters.get(name)
        if isinstance(v, (list, tuple)) and len(v) == 1:
            v = v[0]
        if v is None or v == '' or (hasattr(v, 'isNull') and v.isNull()):
            return p.defaultValue()
        if isinstance(v, str) and v.strip() in options:
            return v.strip()
        text = str(v).strip()
        if not isinstance(v, bool) and re.fullmatch(r'[0-9]+(\.0*)?', text) \
                and int(float(text)) < len(options):
            return options[int(float(text))]
        raise InputError('{} \'{}\': allowed {} (the name, or its number 0 to {})'
                         .format(name, text, ', '.join(options), len(options) - 1))

    def processAlgorithm(self, parameters, context, feedback):
        # a refusal is a QgsProcessingException itself: Processing prints its
        # message (a subclass raised in Python comes out as a traceback)
        try:
            return self.process(parameters, context, feedback)
        except InputError as e:
            raise QgsProcessingException(str(e))

    # ---- the case parameters ------------------------------------------------
    def add_case_parameters(self, ranks=True):
        P = QgsProcessingParameterFeatureSource
        self.addParameter(QgsProcessingParameterRasterLayer('DEM', 'DEM (elevation raster, projected CRS in metres)'))
        self.addParameter(P('RELEASE', 'Release areas', [QgsProcessing.TypeVectorPolygon]))
        self.addParameter(QgsProcessingParameterField(
            'THICKNESS_FIELD', 'Release thickness field [m] (default: the field \'thickness\')', None, 'RELEASE',
            QgsProcessingParameterField.Numeric, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'THICKNESS', 'Release thickness [m] for every polygon (instead of a field)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(P('ENTRAINMENT', 'Entrainment areas (simType ent)', [QgsProcessing.TypeVectorPolygon],
                            optional=True))
        self.advanced(QgsProcessingParameterField(
            'ENT_THICKNESS_FIELD', 'Entrainment thickness field [m] (default: the field \'thickness\')', None,
            'ENTRAINMENT', QgsProcessingParameterField.Numeric, optional=True))
        self.advanced(QgsProcessingParameterNumber(
            'ENT_THICKNESS', 'Entrainment thickness [m] for every polygon (instead of a field)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(P('RESISTANCE', 'Resistance areas, forests (simType res)',
                            [QgsProcessing.TypeVectorPolygon], optional=True))
        self.addParameter(P('DAM', 'Dam crown line (burnt into the DEM)', [QgsProcessing.TypeVectorLine],
                            optional=True))
        self.addParameter(P('PATH', 'Avalanche path (line from the release down: the path analysis)',
                            [QgsProcessing.TypeVectorLine], optional=True))
        self.addParameter(P('SPLIT_POINT', 'Split point (the runout area starts at the beta point below it)',
                            [QgsProcessing.TypeVectorPoint], optional=True))
        self.add_enum('FRICTION', 'Friction (samosAT set)', FRICTIONS, 'samosATAuto')
        self.addParameter(QgsProcessingParameterNumber('RHO', 'Density [kg/m3]', QgsProcessingParameterNumber.Double,
                                                       200.0, False, 1e-6))
        self.addParameter(QgsProcessingParameterNumber(
            'CELL_SIZE', 'Mesh cell size [m] (a multiple of the DEM\'s; empty: the DEM\'s)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(QgsProcessingParameterNumber(
            'STOP_FRACTION', 'Stop when the kinetic energy falls below this fraction of its peak',
            QgsProcessingParameterNumber.Double, 0.01, False, 1e-12, 0.999999))
        self.addParameter(QgsProcessingParameterNumber(
            'END_TIME', 'End time (the cap; the stop criterion ends the run before) [s]',
            QgsProcessingParameterNumber.Double, DEFAULT_END_TIME, False, 1e-6))
        self.advanced(QgsProcessingParameterNumber(
            'THRESHOLD', 'Affected area: peak thickness at least [m]', QgsProcessingParameterNumber.Double,
            0.1, False, 1e-9))
        if ranks:
            self.advanced(QgsProcessingParameterNumber('NP', 'Solver processes (MPI ranks)',
                                                       QgsProcessingParameterNumber.Integer, 1, False, 1))
        self.addParameter(QgsProcessingParameterBoolean(
            'REPORT_MAPS', 'Draw the report maps (PDF and PNG: peak thickness, speed, pressure, pressure zones; '
            'gfReportMaps, a few seconds)', True))
        self.advanced(QgsProcessingParameterString(
            'ZONES', 'Report maps: pressure zone limits [kPa], increasing', '1 10 30'))

    def zones(self, parameters, context):
        """ZONES as gfReportMaps -zones takes it ("1 10 30"); InputError
        unless increasing positive numbers."""
        text = self.parameterAsString(parameters, 'ZONES', context) if 'ZONES' in self.parameter_names() else ''
        if not text or not text.strip():
            return '1 10 30'
        bad = InputError('ZONES \'{}\': increasing positive pressure limits in kPa, e.g. 1 10 30'.format(text))
        try:
            v = [float(x) for x in re.split(r'[,;\s]+', text.strip()) if x]
        except ValueError:
            raise bad
        if not v or any(x <= 0 or x != x or x == float('inf') for x in v) \
                or any(b <= a for a, b in zip(v, v[1:])):
            raise bad
        return ' '.join(num(x) for x in v)

    def report_maps(self, parameters, context):
        return 'REPORT_MAPS' in self.parameter_names() and self.parameterAsBoolean(parameters, 'REPORT_MAPS', context)

    def case_inputs(self, parameters, context):
        return CaseInputs(self, parameters, context)

    def checkParameterValues(self, parameters, context):
        # the enum parameters first: a name or a number, else the valid names
        # (QGIS's own check knows only the one or the other)
        params = dict(parameters)
        try:
            for p in self.parameterDefinitions():
                if isinstance(p, QgsProcessingParameterEnum) and p.name() in params:
                    params[p.name()] = self.enum_string(params, p.name())
        except InputError as e:
            return False, str(e)
        ok, msg = super().checkParameterValues(params, context)
        if not ok:
            return ok, msg
        try:
            self.check(params, context)
        except InputError as e:
            return False, str(e)
        return True, ''

    def check(self, parameters, context):
        """Refuses bad input (InputError, the command-line tools' words)."""
        if 'DEM' in self.parameter_names() and 'RELEASE' in self.parameter_names():
            self.case_inputs(parameters, context).check()
            self.zones(parameters, context)
            out = self.parameterAsString(parameters, 'OUTPUT', context) if self.has_value(parameters, 'OUTPUT') else ''
            if out and out != 'TEMPORARY_OUTPUT':   # (a temporary folder is made new)
                check_folder(os.path.abspath(out))

    def check_batch(self, parameters, context, case):
        """The checks of an algorithm that runs a batch of members on a case
        (calibration, regional map): its OUTPUT folder (self.output_folder),
        NP workers in [1, 256], the DICT file when given; the DICT path or
        None."""
        if self.has_value(parameters, 'OUTPUT') and self.parameterAsString(parameters, 'OUTPUT', context) \
                != 'TEMPORARY_OUTPUT':
            self.output_folder(parameters, context, case)
        n = self.parameterAsInt(parameters, 'NP', context)
        if not 1 <= n <= 256 or self.parameterAsDouble(parameters, 'NP', context) != n:
            raise InputError('NP {}: workers, a whole number in [1, 256]'.format(parameters.get('NP')))
        if not self.has_value(parameters, 'DICT'):
            return None
        d = self.parameterAsFile(parameters, 'DICT', context)
        if not os.path.isfile(d):
            raise InputError('DICT {}: no such file'.format(d))
        return d

    def case_options(self, parameters, context, inputs):
        """gfRunCase's options for the parameters."""
        opts = ['-friction', self.enum_string(parameters, 'FRICTION'),
                '-rho', num(self.parameterAsDouble(parameters, 'RHO', context))]
        if self.has_value(parameters, 'CELL_SIZE') and self.parameterAsDouble(parameters, 'CELL_SIZE', context) > 0:
            opts += ['-cellSize', num(self.parameterAsDouble(parameters, 'CELL_SIZE', context))]
        opts += ['-stopFraction', num(self.parameterAsDouble(parameters, 'STOP_FRACTION', context)),
                 '-endTime', num(self.parameterAsDouble(parameters, 'END_TIME', context)),
                 '-threshold', num(self.parameterAsDouble(parameters, 'THRESHOLD', context))]
        if inputs.sim_type() != 'null':
            opts += ['-simType', inputs.sim_type()]
        if inputs.dam is not None:
            opts += ['-dam']
        if 'NP' in self.parameter_names():
            n = self.parameterAsInt(parameters, 'NP', context)
            if n > 1:
                opts += ['-np', str(n)]
        if self.report_maps(parameters, context):
            opts += ['-zones', self.zones(parameters, context)]
        else:
            opts += ['-reportMaps', 'no']
        return opts

    # ---- the gfRunCase run ---------------------------------------------------
    def run_case(self, parameters, context, feedback, lo=0.0, hi=100.0):
        """Writes the inputs into the output folder, runs gfRunCase on it;
        returns (folder, run folder, output lines, exit status).  Cancel
        stops the run and removes what it wrote (the run folder, the inputs,
        the folder when the algorithm made it).  A gfRunCase that fails
        before the hazard maps are written ends the algorithm; one that
        fails after them (a drawing, the path analysis) leaves the run's
        results, and its status and message are reported as an error that
        does not end the algorithm."""
        inputs = self.case_inputs(parameters, context)
        inputs.check()
        folder = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        check_folder(folder)
        made = not os.path.exists(folder)
        os.makedirs(folder, exist_ok=True)
        inputs.write(folder, context, feedback)
        run = os.path.join(folder, 'run')
        end = self.parameterAsDouble(parameters, 'END_TIME', context)
        draw = self.report_maps(parameters, context)
        report = os.path.join(run, 'postProcessing', 'hazardMaps', 'report')
        # the run's fractions: meshing, the solver (its progress lines against
        # the end time), the hazard maps, the path analysis, the report maps
        # (their PNG files as they appear)
        solver_end, maps_at = (0.80, 0.85) if draw else (0.95, 0.98)
        steps = {'gfTerrainMesh:': 0.02, 'makeFaMesh:': 0.03, 'gfSetRelease:': 0.05,
                 'wrote postProcessing/hazardMaps': solver_end + 0.02, 'path analysis (': solver_end + 0.04,
                 'results in ': 0.99}
        state = {'drawing': False, 'pending': False}

        def scaled(f):
            return lo + (hi - lo) * f

        def drawing_starts():
            state['drawing'] = True
            text = ('drawing the report maps (gfReportMaps: peak thickness, speed, pressure and the pressure zones '
                    '{} kPa, PDF and PNG; parameter REPORT_MAPS off leaves them out) ...'
                    .format(self.zones(parameters, context)))
            feedback.pushInfo(text)
            feedback.setProgressText('drawing the report maps ...')

        def progress(line):
            m = re.match(r'\s*granflow: t = ([-+0-9.eE]+) s', line)
            if m:
                return scaled(0.05 + (solver_end - 0.05) * min(1.0, float(m.group(1)) / end))
            if line.startswith('results in '):
                state['drawing'] = state['pending'] = False
            elif draw and not state['drawing'] and not os.path.isdir(report) \
                    and (line.startswith('path analysis (') or line.startswith('no Inputs/LINES/')):
                # the last step before the maps (gfRunCase draws them
                # silently): they start when the output pauses after it
                state['pending'] = True
            f = next((v for k, v in steps.items() if line.startswith(k)), None)
            return None if f is None else scaled(f)

        def idle():
            if state['pending']:
                state['pending'] = False
                drawing_starts()
                return scaled(maps_at)
            if not state['drawing'] or not os.path.isdir(report):
                return None
            n = len([f for f in os.listdir(report) if f.endswith('.png')])
            return scaled(maps_at + (0.99 - maps_at) * min(n, len(REPORT_MAPS)) / len(REPORT_MAPS))
        args = ['gfRunCase'] + self.case_options(parameters, context, inputs) + [folder]
        try:
            rc, lines = run_tool(args, feedback, progress, idle=idle)
        except Cancelled:
            remove_outputs(folder, made, ['run'], feedback)
            raise QgsProcessingException('Cancelled: the run was stopped and {} removed'
                                         .format(folder if made else run))
        if rc != 0:
            maps = os.path.join(run, 'postProcessing', 'hazardMaps')
            if not all(os.path.isfile(os.path.join(maps, f)) for f in ('summary.dat', 'hPeak.tif',
                                                                       'speedPeak.tif', 'pressurePeak.tif')):
                raise QgsProcessingException('gfRunCase failed: {} (logs in {})'.format(failure('gfRunCase', lines),
                                                                                       run))
            feedback.reportError('gfRunCase ended with exit status {} after the run: {} (logs in {}); the run\'s '
                                 'hazard maps are complete and loaded'.format(rc, failure('gfRunCase', lines), run),
                                 False)
        return folder, run, lines, rc


def end_condition(run):
    """How the run ended, from the solver's log (run/log.faGranularFlowFoam;
    the lines of stopReport.H): a dict with 'status' (stopped: the stop
    criterion ended it; cap: endTime did with the criterion on, the flow had
    not stopped; endTime: no stop criterion, the run went to endTime as
    asked; unknown), 'time' [s], 'moving_percent' (the volume faster than
    stopReportSpeed at the end, % of the volume; None when not reported),
    'line' (the end condition) and 'warnings' (the solver's warnings at the
    end)."""
    out = {'status': 'unknown', 'time': None, 'moving_percent': None, 'speed': None, 'line': '', 'warnings': []}
    try:
        with open(os.path.join(run, 'log.faGranularFlowFoam'), errors='replace') as f:
            log = f.read().splitlines()
    except OSError:
        return out
    for line in log:
        if line.startswith('End condition: '):
            out['line'] = line
            if line.startswith('End condition: stopCriterion'):
                out['status'] = 'stopped'
            elif re.match(r'End condition: endTime .* reached \(stopCriterion none', line):
                out['status'] = 'endTime'
            elif line.startswith('End condition: endTime '):
                out['status'] = 'cap'
        m = re.match(r'moving faces at the end \(t = ([-+0-9.eE]+) s\): \S+ faces faster than ([-+0-9.eE]+) m/s'
                     r'.* m3 \(([-+0-9.eE]+) % of ', line)
        if m:
            out['time'], out['speed'], out['moving_percent'] = float(m.group(1)), float(m.group(2)), float(m.group(3))
        if line.startswith('Warning: the run '):
            out['warnings'].append(line)
    return out


def report_end(end, feedback, what='the run'):
    """The end condition in the log; the cap as an error that does not end
    the algorithm (the results are there, but the flow had not stopped)."""
    if end['status'] == 'cap':
        moving = '' if end['moving_percent'] is None else \
            ' ({:.3g} % of the volume still faster than {:g} m/s)'.format(end['moving_percent'], end['speed'])
        feedback.reportError('WARNING: {} ended at the endTime cap: the flow had not stopped{}; the hazard maps '
                             'hold the state at the cap, not the deposit: raise END_TIME and run again'
                             .format(what, moving), False)
    for w in end['warnings']:
        if end['status'] != 'cap' or 'endTime cap' not in w:
            feedback.pushWarning(w) if hasattr(feedback, 'pushWarning') else feedback.pushInfo(w)


def remove_outputs(folder, made, names, feedback):
    """After a cancelled run: the named folders in folder, the inputs the
    plugin wrote, and the folder itself when the algorithm made it."""
    if made:
        shutil.rmtree(folder, ignore_errors=True)
        feedback.pushInfo('removed {}'.format(folder))
        return
    for n in names + ['Inputs']:
        p = os.path.join(folder, n)
        if n == 'Inputs' and not os.path.exists(os.path.join(p, MARKER)):
            continue
        if os.path.isdir(p):
            shutil.rmtree(p, ignore_errors=True)
            feedback.pushInfo('removed {}'.format(p))
