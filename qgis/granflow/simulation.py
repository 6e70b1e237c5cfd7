# SPDX-License-Identifier: GPL-3.0-or-later
"""Avalanche simulation: the layers into a folder in AvaFrame's layout and
gfRunCase on it, the command line's one-command runner; the peak rasters,
the affected area and the path analysis loaded as layers."""
import os

from qgis.core import (QgsProcessingException, QgsProcessingOutputFile, QgsProcessingOutputFolder,
                       QgsProcessingOutputNumber, QgsProcessingOutputRasterLayer, QgsProcessingOutputString,
                       QgsProcessingOutputVectorLayer, QgsProcessingParameterFolderDestination)

from . import styles
from .base import REPORT_MAPS, GranflowAlgorithm, end_condition, report_end

_HELP = '''<p>Runs an avalanche from a DEM and release polygons to the hazard maps with granflow's
<code>gfRunCase</code>, exactly as the command line does: the layers are written into the output folder
in AvaFrame's input layout (<code>Inputs/</code>: the DEM, <code>REL/release.shp</code> with a
<code>thickness</code> attribute, <code>ENT/</code>, <code>RES/</code>, <code>DAM/</code>,
<code>LINES/path_aimec.shp</code>, <code>POINTS/splitPoint.shp</code>), and
<code>gfRunCase</code> meshes the terrain, sets the release, runs the solver and writes the hazard maps
and the path analysis into <code>run/postProcessing/</code>.</p>
<p><b>Release thickness</b>: a numeric field in metres (a text field is refused), or one value for
every polygon; without either, the field <code>thickness</code> (AvaFrame's). Every thickness must be
&gt; 0 m.</p>
<p><b>Friction</b> (FRICTION: the name, or its number 0 to 3): samosATAuto chooses AvaFrame's samosAT
set by the release volume (small below 25,000 m&sup3;, medium below 60,000 m&sup3;); samosAT (&mu;
0.155), samosATMedium (0.17), samosATSmall (0.22).</p>
<p><b>End time</b> (default 400 s, AvaFrame's): the cap. The run ends when the kinetic energy falls
below the stop fraction of its peak; a run that the cap ends instead had not stopped: the algorithm
says so (END_CONDITION cap, a warning with the volume still moving): raise the end time.</p>
<p><b>Report maps</b> (REPORT_MAPS, default yes): PDF and PNG maps of the peak thickness, speed,
pressure and the pressure zones (ZONES, kPa, default 1 10 30) drawn by <code>gfReportMaps</code>,
a few seconds; outputs REPORT_FOLDER and the four PDFs (pictures, not loaded as layers).</p>
<p><b>Entrainment / resistance</b> polygons switch the mass exchange on (simType ent, res, entres);
a <b>dam</b> line is burnt into the DEM; with a <b>path</b> the path analysis runs (runout, runout
angle, MMPPR, ...), with a <b>split point</b> the runout area starts at the beta point below it.</p>
<p>Refused before anything runs: a DEM without a CRS, a layer in another CRS than the DEM, a release
polygon outside the DEM, a missing or non-positive thickness, an output folder that holds inputs or
a case the plugin did not write (a previous output of the plugin is replaced). Cancel stops the run
and removes its folder. The command that ran is in the log; rerun it in a shell to get the same files.</p>'''


class Simulation(GranflowAlgorithm):

    def name(self):
        return 'simulation'

    def displayName(self):
        return 'Avalanche simulation'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.add_case_parameters()
        self.addParameter(QgsProcessingParameterFolderDestination(
            'OUTPUT', 'Case folder (Inputs/ and the run are written there)'))
        self.addOutput(QgsProcessingOutputRasterLayer('HPEAK', 'Peak flow thickness hPeak [m]'))
        self.addOutput(QgsProcessingOutputRasterLayer('SPEED_PEAK', 'Peak flow speed [m/s]'))
        self.addOutput(QgsProcessingOutputRasterLayer('PRESSURE_PEAK', 'Peak pressure [kPa]'))
        self.addOutput(QgsProcessingOutputVectorLayer('AFFECTED_AREA', 'Affected area (outline)'))
        self.addOutput(QgsProcessingOutputFile('PATH_ANALYSIS', 'Path analysis table (CSV)'))
        self.addOutput(QgsProcessingOutputFile('SUMMARY', 'Summary of the run'))
        self.addOutput(QgsProcessingOutputFolder('RUN_FOLDER', 'OpenFOAM case (logs, fields for ParaView)'))
        self.addOutput(QgsProcessingOutputString(
            'END_CONDITION', 'How the run ended: stopped (the stop criterion), cap (the endTime cap: the flow had '
            'not stopped) or endTime'))
        self.addOutput(QgsProcessingOutputNumber(
            'MOVING_PERCENT', 'Volume still moving at the end (faster than 1 m/s) [% of the volume]'))
        self.addOutput(QgsProcessingOutputFolder('REPORT_FOLDER', 'Report maps (PDF and PNG)'))
        for key, _, text in REPORT_MAPS:
            self.addOutput(QgsProcessingOutputFile(key, text))

    def process(self, parameters, context, feedback):
        folder, run, lines, rc = self.run_case(parameters, context, feedback)
        maps = os.path.join(run, 'postProcessing', 'hazardMaps')
        out = {'OUTPUT': folder, 'RUN_FOLDER': run,
               'HPEAK': os.path.join(maps, 'hPeak.tif'),
               'SPEED_PEAK': os.path.join(maps, 'speedPeak.tif'),
               'PRESSURE_PEAK': os.path.join(maps, 'pressurePeak.tif'),
               'AFFECTED_AREA': os.path.join(maps, 'affectedArea.geojson'),
               'SUMMARY': os.path.join(maps, 'summary.dat')}
        for k, v in out.items():
            if k != 'OUTPUT' and not os.path.exists(v):
                raise QgsProcessingException('gfRunCase wrote no {} ({})'.format(os.path.basename(v), k))
        threshold = self.parameterAsDouble(parameters, 'THRESHOLD', context)
        styles.load(context, out['HPEAK'], 'peak flow thickness [m]', 'HPEAK',
                    styles.RasterStyle(threshold, 'm'))
        styles.load(context, out['SPEED_PEAK'], 'peak flow speed [m/s]', 'SPEED_PEAK',
                    styles.RasterStyle(1.0, 'm/s'))
        styles.load(context, out['PRESSURE_PEAK'], 'peak pressure [kPa]', 'PRESSURE_PEAK',
                    styles.RasterStyle(1.0, 'kPa'))
        styles.load(context, out['AFFECTED_AREA'], 'affected area (hPeak >= {:g} m)'.format(threshold),
                    'AFFECTED_AREA', styles.OutlineStyle())
        csv = os.path.join(run, 'postProcessing', 'pathAnalysis', 'pathAnalysis.csv')
        if os.path.isfile(csv):
            out['PATH_ANALYSIS'] = csv
            styles.load(context, csv, 'path analysis', 'PATH_ANALYSIS')
        # the report maps: framed pictures (PDF, PNG), not georeferenced
        # layers: outputs, not loaded
        report = os.path.join(maps, 'report')
        drawn = []
        if self.report_maps(parameters, context):
            for key, name, _ in REPORT_MAPS:
                pdf = os.path.join(report, name + '.pdf')
                if os.path.isfile(pdf):
                    out[key] = pdf
                    drawn.append(name)
            if drawn:
                out['REPORT_FOLDER'] = report
            missing = [n for _, n, _ in REPORT_MAPS if n not in drawn]
            if missing:
                feedback.reportError('report maps not drawn: {} (log {}); gfReportMaps {} draws them again'
                                     .format(', '.join(missing), os.path.join(run, 'log.gfReportMaps'), run), False)
        end = end_condition(run)
        out['END_CONDITION'] = end['status']
        if end['moving_percent'] is not None:
            out['MOVING_PERCENT'] = end['moving_percent']
        # the closing summary: the headline numbers, how the run ended, where
        # the report maps are; a run that the endTime cap ended is flagged
        for line in lines:
            if line.startswith('max peak') or line.startswith('affected area') or 'runout along the path' in line \
                    or line.startswith('samosATAuto: release volume'):
                feedback.pushInfo(line.strip())
        if end['line']:
            feedback.pushInfo(end['line'])
        if drawn:
            feedback.pushInfo('report maps: {}/{{{}}}.{{pdf,png}}'.format(report, ','.join(drawn)))
        elif not self.report_maps(parameters, context):
            feedback.pushInfo('report maps: not drawn (REPORT_MAPS off; gfReportMaps {} draws them)'.format(run))
        report_end(end, feedback)
        feedback.setProgress(100)
        return out
