# SPDX-License-Identifier: GPL-3.0-or-later
"""Regional hazard indication map: gfRegionalMap on a meshed terrain case,
as the command line runs it (doc/guide/regional.md).  The parameters become
a dictionary in the format of system/regionalDict (or a dictionary file is
taken as it is); gfRegionalMap -check refuses what it refuses before
anything runs, then gfRegionalMap -np N -dict FILE -out DIR CASE runs every
release area x scenario and merges them; the merged rasters of every
scenario and the release polygons are loaded.  Exit status 3 (some members
failed) is a result: a warning with the failures, the maps loaded."""
import os
import re
import shutil
import tempfile

from qgis.core import (QgsPalettedRasterRenderer, QgsProcessing, QgsProcessingException,
                       QgsProcessingLayerPostProcessorInterface, QgsProcessingOutputFile,
                       QgsProcessingOutputMultipleLayers, QgsProcessingOutputNumber, QgsProcessingOutputString,
                       QgsProcessingParameterBoolean, QgsProcessingParameterFeatureSource,
                       QgsProcessingParameterField, QgsProcessingParameterFile,
                       QgsProcessingParameterFolderDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterString, QgsProcessingUtils, QgsRasterLayer)
from qgis.PyQt.QtGui import QColor

from . import styles
from .base import GranflowAlgorithm, num
from .calibration import dict_string, openfoam_path
from .inputs import InputError
from .runner import Cancelled, failure, run_tool

_HELP = '''<p>Every release area of a terrain, for every scenario, run and merged into regional hazard
indication maps with granflow's <code>gfRegionalMap</code> (doc/guide/regional.md).</p>
<p><b>Case folder</b>: a terrain case that has been meshed and released, e.g. a tutorial's run folder
(<code>tutorials/avaHelixRegional/run-coarse</code> after its <code>./Allrun -coarse</code>).</p>
<p><b>Regional dictionary</b> (DICT): a file in the format of <code>system/regionalDict</code>, taken as
it is; only the workers, -alphaBeta and the output folder are then the algorithm's. Without it the
algorithm writes the dictionary: the release polygons (RELEASE_AREAS, e.g. <i>Potential release
areas</i>' output; an integer ID_FIELD, and the fields slope_deg and altitude_m for Salm's depth), the
scenarios as <code>NAME:d0*</code> pairs (SCENARIOS, e.g. <code>T30:1.0; T300:1.5</code>), the altitude
gradient of d0* and its reference altitude, the threshold of a reached cell and the pressure zones.
The dictionary is checked first (<code>gfRegionalMap -check</code>: a bad key, value or field is
refused in its words before anything runs).</p>
<p>Writes into the output folder, per scenario, pressurePeakMax.tif, hPeakMax.tif, speedPeakMax.tif
(each cell's largest peak over the releases), count.tif (the releases reaching the cell), releaseId.tif
(the release giving its largest pressure), zones.tif (the pressure classes), outlines.gpkg (the
zones as polygons, the releases with their status, with ALPHA_BETA each release's thalweg and its
alpha-beta and dynamic runout points), and members.csv, summary.txt, regional.qgs (a QGIS project
of all of it, styled; with ALPHA_BETA alphaBeta.csv). Every scenario's maps, releases and runout
points and the release polygons are loaded. Run again with the same parameters into the same folder, a cancelled or killed batch
resumes. Failed members (exit status 3) are a result: a warning lists them, the maps merge the
others.</p>'''

SCENARIO = re.compile(r'^([A-Za-z_][A-Za-z0-9_-]*)\s*:\s*([-+0-9.eE]+)$')
MEMBER = re.compile(r'^member +\S+ +(\d+)/(\d+)')
MAPS = [('pressurePeakMax', 'largest peak pressure [kPa]'), ('hPeakMax', 'largest peak thickness [m]'),
        ('speedPeakMax', 'largest peak speed [m/s]'), ('count', 'releases reaching'),
        ('releaseId', 'release giving the largest pressure'), ('zones', 'pressure zones')]
ZONE_COLOURS = ['#ffdd00', '#1e6edc', '#d7191c', '#780050', '#3c0028', '#000000', '#000000', '#000000', '#000000']


# the dictionary's keys -> the parameters that wrote them
KEYS = [('scenarios', 'SCENARIOS'), ('idAttribute', 'ID_FIELD'), ('releaseAreas', 'RELEASE_AREAS'),
        ('gradient', 'GRADIENT'), ('zRef', 'ZREF'), ('threshold', 'THRESHOLD'), ('zones', 'ZONES')]


def explain(why, dict_path):
    """gfRegionalMap's refusal of the dictionary the algorithm wrote: the
    dictionary named as such, the parameter behind the key it names first."""
    why = why.replace(dict_path, 'the dictionary written from the parameters ({})'.format(dict_path))
    found = [(m.start(), key) for words, key in KEYS
             for m in [re.search(r'(^|[\s:(])' + re.escape(words) + r'($|[\s:;,)/])', why)] if m]
    return '{}: {}'.format(min(found)[1], why) if found else why


class ZoneClasses(QgsProcessingLayerPostProcessorInterface):
    """zones.tif: class k (above the k-th limit) in gfReportMaps' colours;
    class 0 not drawn."""

    def __init__(self, limits):
        super().__init__()
        self.limits = limits

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsRasterLayer):
            lim = self.limits + [None]
            classes = [QgsPalettedRasterRenderer.Class(
                k + 1, QColor(ZONE_COLOURS[k]),
                '{:g} - {:g} kPa'.format(lim[k], lim[k + 1]) if lim[k + 1] is not None else '>= {:g} kPa'.format(lim[k]))
                for k in range(len(self.limits))]
            layer.setRenderer(QgsPalettedRasterRenderer(layer.dataProvider(), 1, classes))
            layer.emitStyleChanged()
            layer.triggerRepaint()


class RegionalMap(GranflowAlgorithm):

    def name(self):
        return 'regionalMap'

    def displayName(self):
        return 'Regional hazard indication map (gfRegionalMap)'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            'CASE', 'Case folder (a meshed terrain case, e.g. tutorials/avaHelixRegional/run-coarse)',
            QgsProcessingParameterFile.Folder))
        self.addParameter(QgsProcessingParameterFile(
            'DICT', 'Regional dictionary (system/regionalDict format; given: it replaces the parameters below but '
            'the workers, alpha-beta and the output folder)', QgsProcessingParameterFile.File, '', None, True,
            'All files (*)'))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'RELEASE_AREAS', 'Release areas (polygons with an integer id, slope_deg and altitude_m)',
            [QgsProcessing.TypeVectorPolygon], optional=True))
        self.addParameter(QgsProcessingParameterField(
            'ID_FIELD', 'Release id field (integer; default: id)', None, 'RELEASE_AREAS',
            QgsProcessingParameterField.Numeric, optional=True))
        self.addParameter(QgsProcessingParameterString(
            'SCENARIOS', 'Scenarios: NAME:d0* [m] pairs, ; between (Salm\'s depth)', 'T30:1.0; T300:1.5',
            optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'GRADIENT', 'd0* change per metre of altitude [m/m]', QgsProcessingParameterNumber.Double, 0.0))
        self.addParameter(QgsProcessingParameterNumber(
            'ZREF', 'Altitude of d0* [m] (needed with a gradient)', QgsProcessingParameterNumber.Double, None, True))
        self.advanced(QgsProcessingParameterNumber(
            'THRESHOLD', 'A cell is reached above this peak pressure [kPa]', QgsProcessingParameterNumber.Double,
            1.0))
        self.advanced(QgsProcessingParameterString('ZONES', 'Pressure zone limits [kPa], increasing', '1 10 30'))
        self.addParameter(QgsProcessingParameterBoolean(
            'ALPHA_BETA', 'Alpha-beta runout of each release beside its dynamic runout (-alphaBeta)', False))
        self.addParameter(QgsProcessingParameterNumber(
            'NP', 'Workers (runs at once)', QgsProcessingParameterNumber.Integer, os.cpu_count() or 1))
        self.addParameter(QgsProcessingParameterFolderDestination(
            'OUTPUT', 'Output folder (the batch\'s results; the same folder again resumes it)'))
        self.addOutput(QgsProcessingOutputMultipleLayers('MAPS', 'Merged maps of every scenario'))
        self.addOutput(QgsProcessingOutputFile('MEMBERS', 'Every member (members.csv)'))
        self.addOutput(QgsProcessingOutputFile('SUMMARY', 'Summary (summary.txt)'))
        self.addOutput(QgsProcessingOutputFile('ALPHA_BETA_TABLE', 'Alpha-beta beside the dynamic runout (CSV)'))
        self.addOutput(QgsProcessingOutputMultipleLayers(
            'OUTLINES', 'Outlines of every scenario (outlines.gpkg: zones, releases, with alpha-beta thalwegs and '
            'runouts)'))
        self.addOutput(QgsProcessingOutputFile('PROJECT', 'The QGIS project of the results (regional.qgs)'))
        self.addOutput(QgsProcessingOutputString('SCENARIO_NAMES', 'The scenarios (; between)'))
        self.addOutput(QgsProcessingOutputNumber('MEMBERS_COUNT', 'Members'))
        self.addOutput(QgsProcessingOutputNumber('FAILED', 'Members that failed'))

    # ---- the parameters ------------------------------------------------------
    def scenarios(self, parameters, context):
        text = (self.parameterAsString(parameters, 'SCENARIOS', context) or '').strip()
        out = []
        for part in [p.strip() for p in re.split(r'[;\n]', text) if p.strip()]:
            m = SCENARIO.match(part)
            if not m:
                raise InputError('SCENARIOS \'{}\': \'{}\' is not NAME:d0* (a name of letters, digits, _ and -, '
                                 'a depth in m), e.g. T30:1.0; T300:1.5'.format(text, part))
            try:
                v = float(m.group(2))
            except ValueError:
                raise InputError('SCENARIOS \'{}\': \'{}\': d0* is not a number'.format(text, part))
            if m.group(1) in [n for n, _ in out]:
                raise InputError('SCENARIOS \'{}\': {} twice'.format(text, m.group(1)))
            out.append((m.group(1), v))
        if not out:
            raise InputError('SCENARIOS: none given: NAME:d0* pairs, e.g. T30:1.0; T300:1.5 (or a DICT)')
        return out

    def case_folder(self, parameters, context):
        case = self.parameterAsFile(parameters, 'CASE', context)
        if not case:
            raise InputError('CASE: the case folder is required (a meshed terrain case)')
        case = os.path.abspath(case)
        if not os.path.isfile(os.path.join(case, 'system', 'controlDict')):
            raise InputError('CASE {}: no system/controlDict: not an OpenFOAM case (a tutorial\'s run folder, e.g. '
                             'tutorials/avaHelixRegional/run-coarse after its ./Allrun -coarse)'.format(case))
        if not os.path.isdir(os.path.join(case, 'constant', 'polyMesh')):
            raise InputError('CASE {}: no constant/polyMesh: the case is not meshed (gfRunCase, a tutorial\'s '
                             './Allrun)'.format(case))
        openfoam_path('CASE', case)
        return case

    def output_folder(self, parameters, context, case):
        out = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        if os.path.isfile(out):
            raise InputError('OUTPUT {}: a file, not a folder'.format(out))
        openfoam_path('OUTPUT', out)
        if os.path.realpath(out) == os.path.realpath(case):
            raise InputError('OUTPUT {}: the case folder itself; choose another folder (gfRegionalMap\'s default: '
                             'CASE-regional)'.format(out))
        return out

    def check(self, parameters, context):
        case = self.case_folder(parameters, context)
        d = self.check_batch(parameters, context, case)
        if d:
            given = [k for k in ('RELEASE_AREAS', 'ID_FIELD', 'ZREF') if self.has_value(parameters, k)]
            if given:
                raise InputError('DICT {} is given, and {} too: the dictionary names its releases and scenarios; '
                                 'give the dictionary or these, not both'.format(d, ', '.join(given)))
            return
        if not self.has_value(parameters, 'RELEASE_AREAS'):
            raise InputError('RELEASE_AREAS: required without DICT (polygons, e.g. the output of Potential release '
                             'areas)')
        self.scenarios(parameters, context)
        self.zones(parameters, context)

    def dictionary(self, parameters, context, feedback):
        path = self.parameterAsCompatibleSourceLayerPath(parameters, 'RELEASE_AREAS', context,
                                                         ['gpkg', 'shp', 'geojson'], 'gpkg', feedback)
        if not path:
            raise InputError('RELEASE_AREAS: not a vector layer')
        path = os.path.abspath(path.split('|')[0])
        lines = ['FoamFile { version 2.0; format ascii; class dictionary; object regionalDict; }',
                 '// written by the granflow QGIS plugin (Regional hazard indication map)',
                 'releaseAreas {};'.format(dict_string('RELEASE_AREAS', path))]
        field = self.parameterAsString(parameters, 'ID_FIELD', context) if self.has_value(parameters, 'ID_FIELD') \
            else ''
        if field:
            lines.append('idAttribute {};'.format(field))
        g = self.parameterAsDouble(parameters, 'GRADIENT', context)
        if g != 0:
            lines.append('gradient {};'.format(num(g)))
        if self.has_value(parameters, 'ZREF'):
            lines.append('zRef {};'.format(num(self.parameterAsDouble(parameters, 'ZREF', context))))
        lines += ['threshold {};'.format(num(self.parameterAsDouble(parameters, 'THRESHOLD', context))),
                  'zones ({});'.format(self.zones(parameters, context)), 'scenarios', '{']
        lines += ['    {} {{ d0Star {}; }}'.format(n, num(v)) for n, v in self.scenarios(parameters, context)]
        lines.append('}')
        return '\n'.join(lines) + '\n'

    # ---- the run -------------------------------------------------------------------
    def process(self, parameters, context, feedback):
        self.check(parameters, context)
        case = self.case_folder(parameters, context)
        folder = self.output_folder(parameters, context, case)
        made = not os.path.exists(folder)
        if self.has_value(parameters, 'DICT'):
            dict_path = os.path.abspath(self.parameterAsFile(parameters, 'DICT', context))
        else:
            text = self.dictionary(parameters, context, feedback)
            dict_path = os.path.join(tempfile.mkdtemp(prefix='regional', dir=QgsProcessingUtils.tempFolder()),
                                     'regionalDict')
            with open(dict_path, 'w', encoding='utf-8') as f:
                f.write(text)
            feedback.pushInfo('the regional dictionary (from the parameters), {}:'.format(dict_path))
            for line in text.splitlines()[2:]:
                feedback.pushInfo('    ' + line)
        # gfRegionalMap's own check first: nothing written when it refuses
        rc, lines = run_tool(['gfRegionalMap', '-check', '-dict', dict_path, case], feedback)
        if rc != 0:
            why = failure('gfRegionalMap', lines)
            if not self.has_value(parameters, 'DICT'):
                why = explain(why, dict_path)
            raise QgsProcessingException('gfRegionalMap refused the dictionary (exit status {}): {}'.format(rc, why))
        m = next((re.search(r'= (\d+) members', l) for l in lines if re.search(r'= (\d+) members', l)), None)
        feedback.pushInfo('{} members'.format(m.group(1) if m else 'no'))

        def progress(line):
            m = MEMBER.match(line)
            if m:
                return 2.0 + 95.0 * min(1.0, int(m.group(1)) / max(1, int(m.group(2))))
            return None
        args = ['gfRegionalMap', '-np', str(self.parameterAsInt(parameters, 'NP', context)), '-dict', dict_path,
                '-out', folder]
        if self.parameterAsBoolean(parameters, 'ALPHA_BETA', context):
            args.append('-alphaBeta')
        args.append(case)
        try:
            rc, lines = run_tool(args, feedback, progress)
        except Cancelled:
            raise QgsProcessingException(
                'Cancelled: the batch was stopped; its finished members are kept in {}: run the algorithm again '
                'with the same parameters and output folder to resume'.format(folder))
        if rc not in (0, 3):
            if made and not os.path.isdir(os.path.join(folder, 'members')):
                shutil.rmtree(folder, ignore_errors=True)
            raise QgsProcessingException('gfRegionalMap failed (exit status {}): {}'
                                         .format(rc, failure('gfRegionalMap', lines)))
        return self.outputs(folder, case, rc, lines, feedback, context)

    def outputs(self, folder, case, rc, lines, feedback, context):
        values = dict(re.match(r'^(\w+)=(.*)$', l).groups() for l in lines if re.match(r'^(\w+)=(.*)$', l))
        out = {'OUTPUT': folder, 'MEMBERS': os.path.join(folder, 'members.csv'),
               'SUMMARY': os.path.join(folder, 'summary.txt')}
        ab = os.path.join(folder, 'alphaBeta.csv')
        if os.path.isfile(ab):
            out['ALPHA_BETA_TABLE'] = ab
        out['MEMBERS_COUNT'] = int(values.get('members', 0) or 0)
        out['FAILED'] = int(values.get('failed', 0) or 0)
        # the scenarios: the folders gfRegionalMap merged into, in members.csv's order
        names = []
        with open(out['MEMBERS'], encoding='utf-8', errors='replace') as f:
            for row in list(f)[1:]:
                s = row.split(',')[1] if ',' in row else ''
                if s and s not in names and os.path.isdir(os.path.join(folder, s)):
                    names.append(s)
        out['SCENARIO_NAMES'] = ';'.join(names)
        limits = [1.0, 10.0, 30.0]
        with open(os.path.join(folder, 'regionalDict'), encoding='utf-8', errors='replace') as f:
            text = f.read()
            m = re.search(r'^\s*zones\s*\(([^)]*)\)', text, re.M)
            if m:
                limits = [float(x) for x in m.group(1).split()]
        maps = []
        for s in names:
            for f, what in MAPS:
                p = os.path.join(folder, s, f + '.tif')
                if not os.path.isfile(p):
                    continue
                maps.append(p)
                if f in ('pressurePeakMax', 'zones', 'count'):   # the three to look at; the rest returned
                    style = ZoneClasses(limits) if f == 'zones' else \
                        styles.RasterStyle(1.0, 'kPa') if f == 'pressurePeakMax' else \
                        styles.RasterStyle(0.5, '', styles.BLUES)
                    styles.load(context, p, '{}: {}'.format(s, what), 'MAPS', style)
        # the release polygons: the dictionary's releaseAreas (relative to the case, or absolute)
        m = re.search(r'^\s*releaseAreas\s+"([^"]*)"', text, re.M)
        if m:
            rel = m.group(1) if os.path.isabs(m.group(1)) else os.path.join(case, m.group(1))
            if os.path.isfile(rel):
                styles.load(context, os.path.normpath(rel), 'release areas', 'MAPS',
                            styles.OutlineStyle('#202020', '0.5'))
        out['MAPS'] = maps
        # the outlines: each scenario's releases (with their status and alpha-beta), its runout points
        outlines = []
        for s in names:
            g = os.path.join(folder, s, 'outlines.gpkg')
            if not os.path.isfile(g):
                continue
            outlines.append(g)
            styles.load(context, g + '|layername=releases', '{}: releases'.format(s), 'OUTLINES',
                        styles.OutlineStyle('#202020', '0.5'))
            if 'ALPHA_BETA_TABLE' in out:
                styles.load(context, g + '|layername=runouts', '{}: alpha-beta and dynamic runouts'.format(s),
                            'OUTLINES')
        out['OUTLINES'] = outlines
        project = os.path.join(folder, 'regional.qgs')
        if os.path.isfile(project):
            out['PROJECT'] = project
        styles.load(context, out['MEMBERS'], 'regional: members', 'MEMBERS')
        if rc == 3:
            with open(out['SUMMARY'], encoding='utf-8', errors='replace') as f:
                failed = [l.rstrip() for l in f if l.startswith('FAILED ')]
            feedback.reportError('WARNING: {} member(s) failed (gfRegionalMap exit status 3: a result, not an error); '
                                 'the maps merge the others:\n{}'.format(out['FAILED'], '\n'.join(failed)), False)
        feedback.pushInfo('{} members: {} ran, {} resumed, {} failed; scenarios {}'.format(
            values.get('members', '?'), values.get('ran', '?'), values.get('resumed', '?'), values.get('failed', '?'),
            ', '.join(names)))
        feedback.setProgress(100)
        return out
