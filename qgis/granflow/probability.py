# SPDX-License-Identifier: GPL-3.0-or-later
"""Probability map: an ensemble over the friction coefficient and the
release thickness, as the command line runs it: gfRunCase writes and runs
the reference case, gfRunEnsemble the members around it (the ensembleDict
of doc/guide/ensembles.md) and maps the probability of ppr > threshold."""
import os
import re
import shlex

from qgis.core import (QgsProcessingException, QgsProcessingOutputFile, QgsProcessingOutputFolder,
                       QgsProcessingOutputNumber, QgsProcessingOutputRasterLayer, QgsProcessingOutputString,
                       QgsProcessingOutputVectorLayer, QgsProcessingParameterBoolean, QgsProcessingParameterField,
                       QgsProcessingParameterFolderDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterString)

from . import styles
from .base import GranflowAlgorithm, end_condition, num, remove_outputs, report_end
from .inputs import InputError, check_numeric_field
from .runner import Cancelled, failure, run_tool

_HELP = '''<p>The probability that a point is reached (peak pressure above a threshold) over an
ensemble of runs around the reference case, with granflow's <code>gfRunCase</code> (the reference
run: mesh, release, hazard maps) and <code>gfRunEnsemble</code> (the members and the map), as
the command line runs them (doc/guide/ensembles.md).</p>
<p><b>Variations</b>: the friction coefficient &mu; of the samosAT set by &plusmn;P % (Latin hypercube
sample, or one at a time); the release thickness within its 95 % confidence interval, d + z ci95
with z in [-1, 1] (ci95 from a field, a value, or the release layer's field <code>ci95</code>,
AvaFrame's). With samosATAuto the ensemble's reference is the set the reference run chose by its
release volume.</p>
<p>The inputs and their checks are the avalanche simulation's. Writes <code>run/</code> (the
reference) and <code>ensemble/</code> (members.txt, results.csv, summary.txt,
probability/probability.tif, contours.geojson) into the output folder and loads the probability
raster and its contours. results.csv names each column with its unit (the release's factor z
releaseThickness_ci95Factor and its thickness releaseThickness_m, tEnd_s, affectedArea_m2, ...); a
member that the end time's cap ended (the flow had not stopped) has status <code>cap</code>, and the
log's closing summary warns (MEMBERS_CAP). Cancel stops every member and removes both folders.</p>'''

SAMOS = re.compile(r'^samosATAuto: release volume \S+ m3 -> (\w+) \(mu (\S+), tau0 (\S+) Pa, Rs0 (\S+), '
                   r'kappa (\S+), R (\S+) m, B (\S+), u0 (\S+) m/s\)')


def ensemble_dict(method, members, steps, seed, mu_percent, release, threshold, levels):
    """The ensembleDict text (doc/guide/ensembles.md)."""
    lines = ['FoamFile { version 2.0; format ascii; class dictionary; object ensembleDict; }',
             '// written by the granflow QGIS plugin (Probability map)',
             'method      {};'.format(method)]
    if method == 'latinHypercube':
        lines += ['members     {};'.format(members), 'seed        {};'.format(seed)]
    else:
        lines += ['steps       {};'.format(steps)]
    lines += ['variations', '{']
    if mu_percent > 0:
        lines += ['    mu { file constant/granularProperties; entry samosATCoeffs/mu; percent %s; }'
                  % num(mu_percent)]
    if release:
        lines += ['    releaseThickness { release ci95; }']
    lines += ['}', 'threshold   {};'.format(num(threshold)),
              'levels      ({});'.format(' '.join(num(v) for v in levels)), '']
    return '\n'.join(lines)


class ProbabilityMap(GranflowAlgorithm):

    def name(self):
        return 'probability'

    def displayName(self):
        return 'Probability map'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.add_case_parameters(ranks=False)
        self.addParameter(QgsProcessingParameterField(
            'CI95_FIELD', 'Release thickness: half-width of its 95 % interval, field [m] (default: \'ci95\')',
            None, 'RELEASE', QgsProcessingParameterField.Numeric, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'CI95', 'Release thickness: half-width of its 95 % interval for every polygon [m]',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.add_enum('METHOD', 'Sampling', ['latinHypercube', 'oneAtATime'], 'latinHypercube')
        self.addParameter(QgsProcessingParameterNumber('MEMBERS', 'Members (latinHypercube)',
                                                       QgsProcessingParameterNumber.Integer, 40, False, 1))
        self.advanced(QgsProcessingParameterNumber('STEPS', 'Steps of each input (oneAtATime)',
                                                   QgsProcessingParameterNumber.Integer, 5, False, 2))
        self.advanced(QgsProcessingParameterNumber('SEED', 'Seed of the sample',
                                                   QgsProcessingParameterNumber.Integer, 12345, False, 0))
        self.addParameter(QgsProcessingParameterNumber(
            'MU_PERCENT', 'Friction coefficient mu varied by +/- [%] (0: not varied)',
            QgsProcessingParameterNumber.Double, 30.0, False, 0.0, 99.0))
        self.addParameter(QgsProcessingParameterBoolean(
            'VARY_RELEASE', 'Vary the release thickness within its 95 % interval', True))
        self.addParameter(QgsProcessingParameterNumber(
            'PPR_THRESHOLD', 'Reached where the peak pressure exceeds [kPa]',
            QgsProcessingParameterNumber.Double, 1.0, False, 0.0))
        self.advanced(QgsProcessingParameterString('LEVELS', 'Probability contours', '0.05, 0.5, 0.95'))
        self.advanced(QgsProcessingParameterNumber('PROCESSES', 'Members at once (processes)',
                                                   QgsProcessingParameterNumber.Integer,
                                                   os.cpu_count() or 1, False, 1))
        self.addParameter(QgsProcessingParameterFolderDestination(
            'OUTPUT', 'Output folder (Inputs/, run/ and ensemble/ are written there)'))
        self.addOutput(QgsProcessingOutputRasterLayer('PROBABILITY', 'Probability of being reached'))
        self.addOutput(QgsProcessingOutputVectorLayer('CONTOURS', 'Probability contours'))
        self.addOutput(QgsProcessingOutputFile('RESULTS', 'Members\' results (CSV)'))
        self.addOutput(QgsProcessingOutputFile('SUMMARY', 'Summary of the ensemble'))
        self.addOutput(QgsProcessingOutputFolder('ENSEMBLE_FOLDER', 'Ensemble folder'))
        self.addOutput(QgsProcessingOutputNumber(
            'MEMBERS_CAP', 'Members that ended at the endTime cap (the flow had not stopped; status cap)'))
        self.addOutput(QgsProcessingOutputString(
            'END_CONDITION', 'The reference run\'s end: stopped, cap (the endTime cap: the flow had not stopped) '
            'or endTime'))

    def levels(self, parameters, context):
        text = self.parameterAsString(parameters, 'LEVELS', context)
        try:
            v = [float(x) for x in re.split(r'[,;\s]+', text.strip()) if x]
        except ValueError:
            raise InputError('levels \'{}\': probabilities in (0, 1), e.g. 0.05, 0.5, 0.95'.format(text))
        if not v or any(not 0 < x < 1 for x in v):
            raise InputError('levels \'{}\': probabilities in (0, 1), e.g. 0.05, 0.5, 0.95'.format(text))
        return v

    def check(self, parameters, context):
        super().check(parameters, context)
        self.levels(parameters, context)
        mu = self.parameterAsDouble(parameters, 'MU_PERCENT', context)
        release = self.parameterAsBoolean(parameters, 'VARY_RELEASE', context)
        if mu <= 0 and not release:
            raise InputError('nothing varies: give mu a percentage or vary the release thickness')
        if release:
            inputs = self.case_inputs(parameters, context)
            if not (inputs.ci95_field or inputs.ci95_value is not None
                    or inputs.release.fields().indexOf('ci95') >= 0):
                raise InputError('release thickness varied: its ci95 is needed (a field, a value, or the '
                                 'release layer\'s field \'ci95\')')
            if not inputs.ci95_field and inputs.ci95_value is None:
                check_numeric_field(inputs.release, 'ci95', 'release layer {}'.format(inputs.release.sourceName()),
                                    'ci95')

    def process(self, parameters, context, feedback):
        self.check(parameters, context)
        folder = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        made = not os.path.exists(folder)
        folder, run, lines, _ = self.run_case(parameters, context, feedback, 0.0, 25.0)
        reference_end = end_condition(run)
        release = self.parameterAsBoolean(parameters, 'VARY_RELEASE', context)
        mu = self.parameterAsDouble(parameters, 'MU_PERCENT', context)
        # samosATAuto: the set the reference run chose is the ensemble's reference
        props = os.path.join(run, 'constant', 'granularProperties')
        if self.enum_string(parameters, 'FRICTION') == 'samosATAuto':
            m = next((SAMOS.match(l) for l in lines if SAMOS.match(l)), None)
            if m is None:
                raise QgsProcessingException('samosATAuto: the reference run\'s choice is not in its log')
            keys = ['mu', 'tau0', 'Rs0', 'kappa', 'R', 'B', 'u0']
            q = shlex.quote(props)
            cmd = ['foamDictionary -entry frictionLaw -set samosAT {}'.format(q)]
            cmd += ['foamDictionary -entry samosATCoeffs/{} -set {} {}'.format(k, v, q)
                    for k, v in zip(keys, m.groups()[1:])]
            rc, out = run_tool(['bash', '-c', ' > /dev/null && '.join(cmd) + ' > /dev/null'], feedback)
            if rc != 0:
                raise QgsProcessingException('setting the samosAT set {} in {}: {}'.format(m.group(1), props,
                                                                                         '\n'.join(out)))
            feedback.pushInfo('samosATAuto chose {} for the reference run: the members vary around it'
                              .format(m.group(1)))
        if release:
            rel = os.path.join(run, 'system', 'releaseDict')
            with open(rel) as f:
                text = f.read()
            text, n = re.subn(r'(\n(\s*)attribute\s+thickness;)', r'\1\n\2ci95Attribute ci95;', text, count=1)
            if n != 1:
                raise QgsProcessingException('{}: no "attribute thickness;" to add ci95Attribute to'.format(rel))
            with open(rel, 'w') as f:
                f.write(text)
        members = self.parameterAsInt(parameters, 'MEMBERS', context)
        method = self.enum_string(parameters, 'METHOD')
        with open(os.path.join(run, 'system', 'ensembleDict'), 'w') as f:
            f.write(ensemble_dict(method, members, self.parameterAsInt(parameters, 'STEPS', context),
                                  self.parameterAsInt(parameters, 'SEED', context), mu, release,
                                  self.parameterAsDouble(parameters, 'PPR_THRESHOLD', context),
                                  self.levels(parameters, context)))
        ens = os.path.join(folder, 'ensemble')
        n = [members]

        def progress(line):
            m = re.match(r'gfRunEnsemble: (\d+) members', line)
            if m:
                n[0] = int(m.group(1))
            m = re.match(r'member (\d+)( FAILED|:)', line)
            if m:
                progress.done += 1
                return 25.0 + 73.0 * progress.done / max(n[0], 1)
            return None
        progress.done = 0
        args = ['gfRunEnsemble', '-np', str(self.parameterAsInt(parameters, 'PROCESSES', context)), '-out', ens, run]
        try:
            rc, lines = run_tool(args, feedback, progress)
        except Cancelled:
            remove_outputs(folder, made, ['run', 'ensemble'], feedback)
            raise QgsProcessingException('Cancelled: the ensemble was stopped and {} removed'
                                         .format(folder if made else ens))
        prob = os.path.join(ens, 'probability')
        out = {'OUTPUT': folder, 'ENSEMBLE_FOLDER': ens, 'PROBABILITY': os.path.join(prob, 'probability.tif'),
               'CONTOURS': os.path.join(prob, 'contours.geojson'), 'RESULTS': os.path.join(ens, 'results.csv'),
               'SUMMARY': os.path.join(ens, 'summary.txt')}
        if rc != 0:
            if not os.path.isfile(out['PROBABILITY']):
                raise QgsProcessingException('gfRunEnsemble failed: {}'.format(failure('gfRunEnsemble', lines)))
            feedback.reportError('gfRunEnsemble: members failed (see {}); the map is over the others'
                                 .format(out['SUMMARY']), False)
        styles.load(context, out['PROBABILITY'], 'probability of ppr > {:g} kPa'.format(
            self.parameterAsDouble(parameters, 'PPR_THRESHOLD', context)), 'PROBABILITY',
            styles.RasterStyle(1e-6, '', styles.BLUES, 1.0))
        if os.path.isfile(out['CONTOURS']):
            styles.load(context, out['CONTOURS'], 'probability contours', 'CONTOURS', styles.OutlineStyle('#08306b'))
        styles.load(context, out['RESULTS'], 'ensemble members', 'RESULTS')
        # the closing summary: the reference run's end, the members by
        # status; members at the endTime cap flagged (results.csv's status cap)
        out['END_CONDITION'] = reference_end['status']
        summary = []
        if os.path.isfile(out['SUMMARY']):
            with open(out['SUMMARY'], errors='replace') as f:
                summary = f.read().splitlines()
        counts = next((l for l in summary if l.startswith('members ok ')), '')
        m = re.search(r'ended at the endTime cap (\d+)', counts)
        out['MEMBERS_CAP'] = int(m.group(1)) if m else 0
        if reference_end['line']:
            feedback.pushInfo('reference run: ' + reference_end['line'])
        if counts:
            feedback.pushInfo(counts)
        if out['MEMBERS_CAP']:
            feedback.reportError('\n'.join(l for l in summary if l.startswith('WARNING: ') or l.startswith('  CAP: ')
                                           or l.startswith('  their maps')), False)
        if reference_end['status'] == 'cap':
            report_end(reference_end, feedback, 'the reference run')
        feedback.setProgress(100)
        return out
