# SPDX-License-Identifier: GPL-3.0-or-later
"""Back-calculate an event: gfCalibrate on a meshed terrain case, as the
command line runs it.  The parameters become a dictionary in the format of
system/calibrationDict (or a dictionary file is taken as it is), and
gfCalibrate -np N -dict FILE -out DIR CASE runs; its outputs (summary.txt,
parameters.csv, evaluations.csv, bestOutline.tif, the best run's peak
pressure, loss_*.png) are loaded.  Exit status 3 (no evaluation reproduces
the observation) is a result: a warning with the summary's verdict, the
outputs loaded."""
import math
import os
import re
import shutil
import tempfile

from qgis.core import (QgsPalettedRasterRenderer, QgsProcessing, QgsProcessingException,
                       QgsProcessingLayerPostProcessorInterface, QgsProcessingOutputFile,
                       QgsProcessingOutputFolder, QgsProcessingOutputNumber, QgsProcessingOutputRasterLayer,
                       QgsProcessingOutputString, QgsProcessingParameterFeatureSource, QgsProcessingParameterFile,
                       QgsProcessingParameterFolderDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterRange, QgsProcessingParameterRasterLayer,
                       QgsProcessingParameterString, QgsProcessingUtils, QgsRasterLayer)
from qgis.PyQt.QtGui import QColor

from . import styles
from .base import GranflowAlgorithm, num
from .inputs import InputError, check_folder
from .path_analysis import raster_file
from .runner import Cancelled, failure, run_tool

_HELP = '''<p>Back-calculates an observed event with granflow's <code>gfCalibrate</code>
(doc/guide/back-calculation.md): the friction coefficient (any entry of the case's dictionaries) and
optionally a factor on the release thickness whose runs reproduce an observed outline, runout and
deposit, with the ranges the observation constrains and the ridges it leaves.</p>
<p><b>Case folder</b>: a terrain case that has been meshed and released, e.g. a tutorial's run
folder (<code>tutorials/avaKot/run-coarse</code> after <code>./Allrun -coarse</code>).</p>
<p><b>Calibration dictionary</b> (DICT): a file in the format of <code>system/calibrationDict</code>,
taken as it is (its parameters, observations, design, refinement, exploration, acceptance); only the
workers (NP) and the output folder are then the algorithm's. Without it the algorithm writes the
dictionary from its parameters: the friction entry (FRICTION_ENTRY of FRICTION_FILE, default
<code>samosATCoeffs/mu</code> of <code>constant/granularProperties</code>; the parameter is named after
the entry's last word) in FRICTION_RANGE, the release factor in RELEASE_RANGE (optional), the
observations (an outline polygon layer, a runout point or a runout distance along the case's path,
a deposit raster on the DEM's grid; each in the DEM's CRS) and the design sizes; a size left empty
is gfCalibrate's default (sobol 8 d + 8, morrisTrajectories 4, refinement starts 2 of 10 d + 5
evaluations, exploration 3 rounds of 8 d points).</p>
<p>The command that ran is in the log (rerun it in a shell to get the same files); its progress
lines are the log's, the progress bar counts the evaluations against the most it announces. Writes
into the output folder evaluations.csv, parameters.csv, summary.txt, best/ (the best run's case),
bestOutline.tif (1 both affected, 2 simulated only, 3 observed only), loss_A_B.png and
evals/ (every run, kept: run the algorithm again with the same parameters into the same folder to
resume a cancelled calibration).</p>
<p>Exit status 3 of gfCalibrate, <b>unreachable</b> (no evaluation reproduces the observation), is a
result, not an error: the algorithm warns with the summary's verdict and loads the outputs
(VERDICT UNREACHABLE).</p>'''

# the algorithm's parameters that write an entry of the dictionary: (key,
# dictionary section, dictionary key, what, lo, hi, whole); None: no bound
NUMBERS = [('SOBOL', 'design', 'sobol', 'Sobol design points (empty: 8 d + 8)', 1, 1e5, True),
           ('MORRIS', 'design', 'morrisTrajectories', 'Morris trajectories, 0 or >= 2 (empty: 4)', 0, 1e4, True),
           ('REFINE_STARTS', 'refinement', 'starts', 'Simplex refinements from the best points (empty: 2)',
            0, 100, True),
           ('REFINE_EVALUATIONS', 'refinement', 'evaluations',
            'Evaluations of each refinement, >= d + 1 (empty: 10 d + 5)', None, 1e5, True),
           ('EXPLORE_POINTS', 'exploration', 'points', 'Exploration: points per round (empty: 8 d)', 0, 1e5, True),
           ('EXPLORE_ROUNDS', 'exploration', 'rounds', 'Exploration: rounds at most (empty: 3)', 1, 100, True),
           ('THRESHOLD', 'scores', 'threshold', 'Affected where the peak pressure exceeds [kPa] (empty: 1)',
            0, 1e6, False),
           ('RUNOUT_TOLERANCE', 'acceptance', 'runoutTolerance',
            'Accepted: |runout error| at most [m] (empty: the runout scale, 20 m)', 0, 1e6, False),
           ('MIN_JACCARD', 'acceptance', 'minJaccard', 'Accepted: outline Jaccard index at least (empty: 0.8)',
            0, 1, False)]
SECTIONS = ['design', 'refinement', 'exploration', 'scores', 'acceptance']
# the observation parameters (a dictionary file names its own)
OBSERVATIONS = [('OUTLINE', 'outline'), ('RUNOUT_POINT', 'runoutPoint'), ('RUNOUT', 'runout'),
                ('DEPOSIT', 'deposit')]
ENTRY = re.compile(r'[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*')
PLAN = re.compile(r'gfCalibrate: \d+ parameters?, .* = (\d+) evaluations at most')
EVAL = re.compile(r'eval +\d+ ')
# bestOutline.tif's classes
OUTLINE_CLASSES = [(1, '#2b8a3e', 'both affected'), (2, '#d9480f', 'simulated only'),
                   (3, '#1c7ed6', 'observed only')]


class OutlineClasses(QgsProcessingLayerPostProcessorInterface):
    """bestOutline.tif: its three classes in their colours."""

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsRasterLayer):
            classes = [QgsPalettedRasterRenderer.Class(v, QColor(c), label) for v, c, label in OUTLINE_CLASSES]
            layer.setRenderer(QgsPalettedRasterRenderer(layer.dataProvider(), 1, classes))
            layer.emitStyleChanged()
            layer.triggerRepaint()


def openfoam_path(what, path):
    """A folder the members run in: OpenFOAM takes no space, tab or quote
    in a case's path (gfRunCase's rule)."""
    bad = [c for c in (' ', '\t', '\n', '"', "'") if c in path]
    if bad:
        raise InputError('{} {}: a path OpenFOAM cannot take (it holds {}): the runs are OpenFOAM cases; '
                         'choose a folder without spaces, tabs or quotes'
                         .format(what, path, ' and '.join(repr(c) for c in bad)))


def dict_string(what, path):
    """A path as a quoted dictionary string (the dictionary has no escapes)."""
    if '"' in path or '\n' in path:
        raise InputError('{} {}: a file name with a double quote or a line break cannot be written into the '
                         'dictionary; rename it'.format(what, path))
    return '"{}"'.format(path)


class Calibration(GranflowAlgorithm):

    def name(self):
        return 'calibration'

    def displayName(self):
        return 'Back-calculate an event (gfCalibrate)'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            'CASE', 'Case folder (a meshed terrain case, e.g. tutorials/avaKot/run-coarse)',
            QgsProcessingParameterFile.Folder))
        self.addParameter(QgsProcessingParameterFile(
            'DICT', 'Calibration dictionary (system/calibrationDict format; given: it replaces the parameters '
            'below but the workers and the output folder)', QgsProcessingParameterFile.File, '', None, True,
            'All files (*)'))   # (QGIS's default filter *.* refuses a name without a dot: calibrationDict)
        self.addParameter(QgsProcessingParameterString(
            'FRICTION_ENTRY', 'Friction parameter: the entry calibrated (a/b/c)', 'samosATCoeffs/mu'))
        self.advanced(QgsProcessingParameterString(
            'FRICTION_FILE', 'Friction parameter: the dictionary of the case that holds it',
            'constant/granularProperties'))
        self.addParameter(QgsProcessingParameterRange(
            'FRICTION_RANGE', 'Friction parameter: its range (lo < hi; without DICT required)',
            QgsProcessingParameterNumber.Double, '0.1,0.35', True))
        self.addParameter(QgsProcessingParameterRange(
            'RELEASE_RANGE', 'Release thickness factor: its range (empty: not calibrated)',
            QgsProcessingParameterNumber.Double, None, True))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'OUTLINE', 'Observed outline (polygons, the DEM\'s CRS)', [QgsProcessing.TypeVectorPolygon],
            optional=True))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'RUNOUT_POINT', 'Observed runout point (the DEM\'s CRS; measured along the case\'s path)',
            [QgsProcessing.TypeVectorPoint], optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'RUNOUT', 'Observed runout along the case\'s path [m] (instead of a point)',
            QgsProcessingParameterNumber.Double, None, True))
        self.addParameter(QgsProcessingParameterRasterLayer(
            'DEPOSIT', 'Observed deposit thickness [m] (a raster on the DEM\'s grid)', optional=True))
        for key, section, _, what, _, _, whole in NUMBERS:
            p = QgsProcessingParameterNumber(
                key, what, QgsProcessingParameterNumber.Integer if whole else QgsProcessingParameterNumber.Double,
                None, True)
            if section in ('design', 'refinement'):
                self.addParameter(p)
            else:
                self.advanced(p)
        self.addParameter(QgsProcessingParameterNumber(
            'NP', 'Workers (runs at once)', QgsProcessingParameterNumber.Integer, os.cpu_count() or 1))
        self.addParameter(QgsProcessingParameterFolderDestination(
            'OUTPUT', 'Output folder (the calibration\'s results; the same folder again resumes it)'))
        self.addOutput(QgsProcessingOutputString('VERDICT', 'Verdict: REACHABLE or UNREACHABLE'))
        self.addOutput(QgsProcessingOutputString('VERDICT_LINE', 'The summary\'s verdict line'))
        self.addOutput(QgsProcessingOutputString('BEST', 'Best parameter set (name value, ...)'))
        self.addOutput(QgsProcessingOutputNumber('EVALUATIONS_RUN', 'Evaluations'))
        self.addOutput(QgsProcessingOutputFile('SUMMARY', 'Summary (summary.txt)'))
        self.addOutput(QgsProcessingOutputFile('PARAMETERS', 'Parameters: best, reproducing range, design range '
                                                             '(parameters.csv)'))
        self.addOutput(QgsProcessingOutputFile('EVALUATIONS', 'Every evaluation (evaluations.csv)'))
        self.addOutput(QgsProcessingOutputRasterLayer(
            'BEST_OUTLINE', 'Best run against the observation (1 both, 2 simulated only, 3 observed only)'))
        self.addOutput(QgsProcessingOutputRasterLayer('BEST_PRESSURE_PEAK', 'Best run: peak pressure [kPa]'))
        self.addOutput(QgsProcessingOutputFolder('BEST_FOLDER', 'Best run\'s case (best/)'))
        self.addOutput(QgsProcessingOutputFile('LOSS_PICTURE', 'Loss over the first two parameters (PNG)'))
        self.addOutput(QgsProcessingOutputString('LOSS_PICTURES', 'Every loss picture loss_A_B.png (paths, ; '
                                                                  'between)'))

    # ---- the parameters ------------------------------------------------------
    def range_of(self, parameters, key, context, what, lo=None, hi=None):
        """A range parameter as (lo, hi); None when not given; InputError
        naming the key unless lo < hi, both finite (and within [lo, hi])."""
        if not self.range_given(parameters, key):
            return None
        v = parameters.get(key)
        if v is None:
            v = self.parameterDefinition(key).defaultValue()
        text = ','.join(str(x) for x in v) if isinstance(v, (list, tuple)) else str(v)
        r = self.parameterAsRange(parameters, key, context)
        allowed = 'lo < hi, both finite' + ('' if lo is None else ', within [{:g}, {:g}]'.format(lo, hi))
        if len(r) != 2 or not all(isinstance(x, float) and math.isfinite(x) for x in r) or not r[0] < r[1] \
                or (lo is not None and not (r[0] >= lo and r[1] <= hi)):
            raise InputError('{} \'{}\': {}: expected lo,hi with {}'.format(key, text, what, allowed))
        return r[0], r[1]

    def range_given(self, parameters, key):
        """A range parameter is given: not empty, not 'None,None' or
        'nan,nan' (an optional range the dialog leaves unset)."""
        v = parameters.get(key)
        if v is None:   # not given: its default (parameterAsRange's too)
            v = self.parameterDefinition(key).defaultValue()
        if v is None or v == '' or (hasattr(v, 'isNull') and v.isNull()):
            return False
        parts = [str(x).strip() for x in v] if isinstance(v, (list, tuple)) else str(v).split(',')
        return not all(p.lower() in ('', 'none', 'nan', 'null') for p in parts)

    def friction_name(self, parameters, context):
        entry = (self.parameterAsString(parameters, 'FRICTION_ENTRY', context) or '').strip()
        if not ENTRY.fullmatch(entry):
            raise InputError('FRICTION_ENTRY \'{}\': an entry of the dictionary as a/b/c (words of letters, digits '
                             'and _), e.g. samosATCoeffs/mu'.format(entry))
        name = entry.split('/')[-1]
        if name == 'release':
            raise InputError('FRICTION_ENTRY \'{}\': its last word names the parameter, and \'release\' is the '
                             'release factor\'s name'.format(entry))
        return entry, name

    def numbers(self, parameters, context, d):
        """The dictionary's entries from NUMBERS: {section: [(key, text)]};
        InputError naming the parameter, its dictionary key and the allowed
        range."""
        out = {}
        for key, section, dkey, _, lo, hi, whole in NUMBERS:
            if not self.has_value(parameters, key):
                continue
            raw = parameters.get(key)
            try:
                v = float(raw)
            except (TypeError, ValueError):
                v = self.parameterAsDouble(parameters, key, context)
            lo_ = d + 1 if lo is None else lo
            where = '{}/{}'.format(section, dkey)
            if not (math.isfinite(v) and lo_ <= v <= hi):
                raise InputError('{} {}: {} is outside the allowed range [{:g}, {:g}]'.format(key, where, num(v), lo_,
                                                                                             hi))
            if whole and v != math.floor(v):
                raise InputError('{} {}: {} is not a whole number (allowed: [{:g}, {:g}])'.format(key, where, num(v),
                                                                                                lo_, hi))
            if key == 'MORRIS' and v == 1:
                raise InputError('MORRIS design/morrisTrajectories: 1: allowed 0 or >= 2 (up to 10000)')
            out.setdefault(section, []).append((dkey, str(int(v)) if whole else num(v)))
        return out

    def case_folder(self, parameters, context):
        case = self.parameterAsFile(parameters, 'CASE', context)
        if not case:
            raise InputError('CASE: the case folder is required (a meshed terrain case, e.g. '
                             'tutorials/avaKot/run-coarse)')
        case = os.path.abspath(case)
        if not os.path.isdir(case):
            raise InputError('CASE {}: no such folder'.format(case))
        if not os.path.isfile(os.path.join(case, 'system', 'controlDict')):
            raise InputError('CASE {}: no system/controlDict: not an OpenFOAM case (a tutorial\'s run folder, e.g. '
                             'tutorials/avaKot/run-coarse after its ./Allrun -coarse)'.format(case))
        if not os.path.isfile(os.path.join(case, 'system', 'terrainDict')):
            raise InputError('CASE {}: no system/terrainDict: not a terrain case (gfTerrainMesh, gfRunCase)'
                             .format(case))
        if not os.path.isdir(os.path.join(case, 'constant', 'polyMesh')):
            raise InputError('CASE {}: no constant/polyMesh: the case is not meshed (its tutorial\'s ./Allrun, or '
                             'gfRunCase: the run folder they write)'.format(case))
        openfoam_path('CASE', case)
        return case

    def output_folder(self, parameters, context, case):
        out = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        check_folder(out)
        openfoam_path('OUTPUT', out)
        if os.path.realpath(out) == os.path.realpath(case):
            raise InputError('OUTPUT {}: the case folder itself; choose another folder (gfCalibrate\'s default: '
                             'CASE-calibration)'.format(out))
        return out

    def check(self, parameters, context):
        case = self.case_folder(parameters, context)
        d = self.check_batch(parameters, context, case)
        if d:
            given = [k for k, _ in OBSERVATIONS if self.has_value(parameters, k)] + \
                [k for k in ('RELEASE_RANGE',) if self.range_given(parameters, k)] + \
                [k for k, *_ in NUMBERS if self.has_value(parameters, k)]
            if given:
                raise InputError('DICT {} is given, and {} too: the dictionary names its parameters, observations '
                                 'and design; give the dictionary or these, not both'.format(d, ', '.join(given)))
            return
        _, name = self.friction_name(parameters, context)
        f = (self.parameterAsString(parameters, 'FRICTION_FILE', context) or '').strip()
        if not f or f.startswith('/') or '..' in f:
            raise InputError('FRICTION_FILE \'{}\': a dictionary of the case as a path inside it, e.g. '
                             'constant/granularProperties'.format(f))
        if not os.path.isfile(os.path.join(case, f)):
            raise InputError('FRICTION_FILE {}: the case {} has no such file'.format(f, case))
        dict_string('FRICTION_FILE', f)
        if self.range_of(parameters, 'FRICTION_RANGE', context, 'the range of {} (parameters/{}/range)'
                         .format(name, name)) is None:
            raise InputError('FRICTION_RANGE: required (lo,hi with lo < hi), e.g. 0.1,0.35')
        release = self.range_of(parameters, 'RELEASE_RANGE', context,
                                'the range of the release factor (parameters/release/range)', 0, 100)
        d = 1 + (release is not None)
        if not any(self.has_value(parameters, k) for k, _ in OBSERVATIONS):
            raise InputError('observations: none given: OUTLINE, RUNOUT_POINT or RUNOUT, DEPOSIT')
        if self.has_value(parameters, 'RUNOUT_POINT') and self.has_value(parameters, 'RUNOUT'):
            raise InputError('RUNOUT_POINT and RUNOUT: give the runout point or the runout distance, not both')
        if self.has_value(parameters, 'RUNOUT'):
            v = self.parameterAsDouble(parameters, 'RUNOUT', context)
            if not 0 <= v <= 1e6:
                raise InputError('RUNOUT {}: observations/runout: outside the allowed range [0, 1e+06] m'
                                 .format(num(v)))
        if self.has_value(parameters, 'DEPOSIT'):
            raster_file(self.parameterAsRasterLayer(parameters, 'DEPOSIT', context), 'DEPOSIT')
        self.numbers(parameters, context, d)

    # ---- the dictionary -----------------------------------------------------------
    def vector_file(self, parameters, key, context, feedback):
        """A vector parameter as a file gfCalibrate reads: the layer's own
        shapefile, else the features written to a temporary one."""
        path = self.parameterAsCompatibleSourceLayerPath(parameters, key, context, ['shp'], 'shp', feedback)
        if not path:
            raise InputError('{}: not a vector layer'.format(key))
        return os.path.abspath(path.split('|')[0])

    def dictionary(self, parameters, context, feedback):
        """The calibrationDict text of the parameters, and [(gfCalibrate's
        words, the algorithm's parameter)] for its messages (explain)."""
        entry, name = self.friction_name(parameters, context)
        ffile = self.parameterAsString(parameters, 'FRICTION_FILE', context).strip()
        lo, hi = self.range_of(parameters, 'FRICTION_RANGE', context, 'the range of {}'.format(name))
        release = self.range_of(parameters, 'RELEASE_RANGE', context, 'the range of the release factor', 0, 100)
        # gfCalibrate's words -> the parameter, the most specific first
        keys = [(entry, 'FRICTION_ENTRY')]
        lines = ['FoamFile { version 2.0; format ascii; class dictionary; object calibrationDict; }',
                 '// written by the granflow QGIS plugin (Back-calculate an event)',
                 'parameters', '{',
                 '    {} {{ file {}; entry {}; range ({} {}); }}'.format(name, dict_string('FRICTION_FILE', ffile),
                                                                       dict_string('FRICTION_ENTRY', entry),
                                                                       num(lo), num(hi))]
        if release is not None:
            lines.append('    release {{ release factor; range ({} {}); }}'.format(num(release[0]), num(release[1])))
        lines.append('}')
        obs = []
        for key, dkey in OBSERVATIONS:
            if not self.has_value(parameters, key):
                continue
            if key == 'RUNOUT':
                obs.append('runout {};'.format(num(self.parameterAsDouble(parameters, key, context))))
            else:
                if key == 'DEPOSIT':
                    path = os.path.abspath(raster_file(self.parameterAsRasterLayer(parameters, key, context), key))
                else:
                    path = self.vector_file(parameters, key, context, feedback)
                obs.append('{} {};'.format(dkey, dict_string(key, path)))
            keys += [('observations/' + dkey, key), ('observation ' + dkey, key)]
        lines.append('observations {{ {} }}'.format(' '.join(obs)))
        sections = self.numbers(parameters, context, 1 + (release is not None))
        for section in SECTIONS:
            if section in sections:
                entries = ' '.join('{} {};'.format(k, v) for k, v in sections[section])
                lines.append('{} {{ {} }}'.format(section, entries))
        keys += [('{}/{}'.format(section, dkey), key) for key, section, dkey, *_ in NUMBERS]
        if release is not None:
            keys.append(('release', 'RELEASE_RANGE'))
        keys += [(name, 'FRICTION_RANGE'), (ffile, 'FRICTION_FILE')]
        return '\n'.join(lines) + '\n', keys

    # ---- the run -------------------------------------------------------------------
    def process(self, parameters, context, feedback):
        self.check(parameters, context)
        case = self.case_folder(parameters, context)
        folder = self.output_folder(parameters, context, case)
        made = not os.path.exists(folder)
        had_dict = os.path.exists(os.path.join(folder, 'calibrationDict'))
        keys = []
        if self.has_value(parameters, 'DICT'):
            dict_path = os.path.abspath(self.parameterAsFile(parameters, 'DICT', context))
        else:
            text, keys = self.dictionary(parameters, context, feedback)
            dict_path = os.path.join(tempfile.mkdtemp(prefix='calibration', dir=QgsProcessingUtils.tempFolder()),
                                     'calibrationDict')
            with open(dict_path, 'w', encoding='utf-8') as f:
                f.write(text)
            feedback.pushInfo('the calibration dictionary (from the parameters), {}:'.format(dict_path))
            for line in text.splitlines()[2:]:
                feedback.pushInfo('    ' + line)
        np_ = self.parameterAsInt(parameters, 'NP', context)
        state = {'total': None, 'done': 0}

        def progress(line):
            m = PLAN.match(line)
            if m:
                state['total'] = int(m.group(1))
                return 2.0
            if EVAL.match(line) and state['total']:
                state['done'] += 1
                return 2.0 + 95.0 * min(1.0, state['done'] / state['total'])
            return None
        args = ['gfCalibrate', '-np', str(np_), '-dict', dict_path, '-out', folder, case]
        try:
            rc, lines = run_tool(args, feedback, progress)
        except Cancelled:
            n = len(results(folder))
            raise QgsProcessingException(
                'Cancelled: the calibration was stopped; its {} finished evaluation(s) are kept in {}: run the '
                'algorithm again with the same parameters and output folder to resume'.format(n, folder))
        if rc not in (0, 3):
            why = explain(failure('gfCalibrate', lines), dict_path, keys)
            if not results(folder):
                # nothing evaluated: what gfCalibrate wrote goes, so that the
                # corrected calibration is not refused as another one
                if made:
                    shutil.rmtree(folder, ignore_errors=True)
                elif not had_dict:
                    for n in ('calibrationDict', 'template', 'evals'):
                        p = os.path.join(folder, n)
                        shutil.rmtree(p, ignore_errors=True) if os.path.isdir(p) else \
                            (os.remove(p) if os.path.exists(p) else None)
            raise QgsProcessingException('gfCalibrate failed (exit status {}): {}'.format(rc, why))
        return self.outputs(folder, rc, feedback, context)

    def outputs(self, folder, rc, feedback, context):
        out = {'OUTPUT': folder, 'SUMMARY': os.path.join(folder, 'summary.txt'),
               'PARAMETERS': os.path.join(folder, 'parameters.csv'),
               'EVALUATIONS': os.path.join(folder, 'evaluations.csv'),
               'BEST_OUTLINE': os.path.join(folder, 'bestOutline.tif'),
               'BEST_FOLDER': os.path.join(folder, 'best'),
               'BEST_PRESSURE_PEAK': os.path.join(folder, 'best', 'postProcessing', 'hazardMaps', 'pressurePeak.tif')}
        missing = [k for k, v in out.items() if not os.path.exists(v)]
        for k in missing:
            feedback.reportError('gfCalibrate wrote no {} ({})'.format(out[k], k), False)
            del out[k]
        summary = []
        if 'SUMMARY' in out:
            with open(out['SUMMARY'], encoding='utf-8', errors='replace') as f:
                summary = f.read().splitlines()
        verdict = next((l for l in summary if l.startswith('verdict: ')), '')
        out['VERDICT_LINE'] = verdict
        out['VERDICT'] = 'UNREACHABLE' if rc == 3 else 'REACHABLE'
        m = next((re.match(r'evaluations: (\d+) ', l) for l in summary if l.startswith('evaluations: ')), None)
        if m:
            out['EVALUATIONS_RUN'] = int(m.group(1))
        if 'PARAMETERS' in out:
            with open(out['PARAMETERS'], encoding='utf-8', errors='replace') as f:
                rows = [l.rstrip('\n').split(',') for l in f if l.strip()]
            out['BEST'] = ', '.join('{} {}'.format(r[0], r[1]) for r in rows[1:] if len(r) > 1)
        pictures = sorted(os.path.join(folder, f) for f in os.listdir(folder)
                          if f.startswith('loss_') and f.endswith('.png'))
        if pictures:
            out['LOSS_PICTURE'] = pictures[0]
        out['LOSS_PICTURES'] = ';'.join(pictures)
        # the layers and tables, loaded when the algorithm ends
        if 'PARAMETERS' in out:
            styles.load(context, out['PARAMETERS'], 'calibration: parameters', 'PARAMETERS')
        if 'EVALUATIONS' in out:
            styles.load(context, out['EVALUATIONS'], 'calibration: evaluations', 'EVALUATIONS')
        if 'BEST_PRESSURE_PEAK' in out:
            styles.load(context, out['BEST_PRESSURE_PEAK'], 'calibration: best run, peak pressure [kPa]',
                        'BEST_PRESSURE_PEAK', styles.RasterStyle(1.0, 'kPa'))
        if 'BEST_OUTLINE' in out:
            styles.load(context, out['BEST_OUTLINE'], 'calibration: best run against the observation',
                        'BEST_OUTLINE', OutlineClasses())
        # the closing summary: the verdict, the best set; unreachable is a
        # result (a warning), not an error
        best = next((l for l in summary if l.startswith('best evaluation ')), '')
        if rc == 3:
            feedback.reportError('WARNING: the observation is unreachable (gfCalibrate exit status 3: a result, not '
                                 'an error): {}; no evaluation reproduces it: the outputs, loaded, show the '
                                 'closest runs ({}), not a calibrated set'
                                 .format(verdict or 'verdict: UNREACHABLE', best or 'the summary has no best'),
                                 False)
        else:
            feedback.pushInfo(verdict)
        if best:
            feedback.pushInfo(best)
        if out.get('BEST'):
            feedback.pushInfo('best set: ' + out['BEST'])
        if pictures:
            feedback.pushInfo('loss pictures: ' + ', '.join(pictures))
        feedback.setProgress(100)
        return out


def results(folder):
    """The evaluations with a result in folder/evals."""
    evals = os.path.join(folder, 'evals')
    if not os.path.isdir(evals):
        return []
    return [e for e in os.listdir(evals) if os.path.isfile(os.path.join(evals, e, 'result'))]


def explain(why, dict_path, keys):
    """gfCalibrate's refusal in the algorithm's words: the dictionary the
    algorithm wrote named as such, and the parameter behind the first
    dictionary key of keys ([(words, parameter)], the most specific
    first) that it names."""
    if not keys:
        return why
    why = why.replace(dict_path, 'the dictionary written from the parameters ({})'.format(dict_path))
    for words, key in keys:
        if re.search(r'(^|[\s:/(])' + re.escape(words) + r'($|[\s:;,)])', why):
            return '{}: {}'.format(key, why)
    return why
