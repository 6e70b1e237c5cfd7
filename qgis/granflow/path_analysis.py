# SPDX-License-Identifier: GPL-3.0-or-later
"""Path analysis: gfPathAnalysis on any tool's peak rasters (granflow's,
AvaFrame's ppr/pft/pfv, RAMMS exports) along an avalanche path, with the
command line's options; optionally against a reference run."""
import os

from qgis.core import (QgsProcessing, QgsProcessingException, QgsProcessingOutputFile,
                       QgsProcessingParameterBoolean,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterFolderDestination,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterLayer,
                       QgsProcessingParameterString, QgsProcessingUtils)

from . import styles
from .base import GranflowAlgorithm, num
from .inputs import InputError, check_dem, check_vector, crs_text, same_crs, write_vector
from .runner import failure, run_tool

_HELP = '''<p>The path analysis of peak rasters with granflow's <code>gfPathAnalysis</code>
(AvaFrame's ana3AIMEC): the rasters on the path-following (s, l) grid, the runout along the path
(sRunout, runout angle) of the chosen field above its threshold, the peak-value indicators
(MMPPR, AMPPR, MMPFT, ...) and, with a reference run's rasters, the TP/FP/FN/TN areas in the runout
area. The rasters may come from any tool (granflow, AvaFrame, RAMMS) and lie on different grids:
each is interpolated onto the path's grid on its own; each must cover the path.</p>
<p>The options are the command line's (<code>gfPathAnalysis -help</code>): field (ppr, pft, pfv) and
threshold (default 1 kPa, 0.1 m, 1 m/s), domain width (600 m), beta angle (10&deg;) and ds-min
(30 m) of the runout area below the split point, the run's and the reference's names in the CSV.</p>
<p>Writes pathAnalysis.csv (one row per run), pathProfile.csv, pathGrid.csv, summary.dat and the
plots into the output folder and loads the table.</p>'''


def raster_file(layer, what):
    """A raster layer's file for the command line (a local GDAL file)."""
    src = layer.source()
    if layer.providerType() != 'gdal' or not os.path.isfile(src):
        raise InputError('{} {}: a raster file GDAL reads is needed (save it as GeoTIFF first)'
                         .format(what, layer.name()))
    return src


class PathAnalysis(GranflowAlgorithm):
    RASTERS = [('PPR', '-ppr', 'Peak pressure raster ppr [kPa]'),
               ('PFT', '-pft', 'Peak flow thickness raster pft [m]'),
               ('PFV', '-pfv', 'Peak flow speed raster pfv [m/s]'),
               ('REF_PPR', '-ref-ppr', 'Reference run: peak pressure [kPa]'),
               ('REF_PFT', '-ref-pft', 'Reference run: peak flow thickness [m]'),
               ('REF_PFV', '-ref-pfv', 'Reference run: peak flow speed [m/s]')]

    def name(self):
        return 'pathanalysis'

    def displayName(self):
        return 'Path analysis'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterRasterLayer('DEM', 'DEM'))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'PATH', 'Avalanche path (the first line, from the release down)', [QgsProcessing.TypeVectorLine]))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'SPLIT_POINT', 'Split point (the runout area starts at the beta point below it)',
            [QgsProcessing.TypeVectorPoint], optional=True))
        for key, _, text in self.RASTERS:
            self.addParameter(QgsProcessingParameterRasterLayer(key, text, optional=True))
        self.add_enum('FIELD', 'Result type of the runout and the comparison', ['ppr', 'pft', 'pfv'], 'ppr')
        self.addParameter(QgsProcessingParameterNumber(
            'THRESHOLD', 'Threshold: reached where the field exceeds it (default 1 kPa, 0.1 m, 1 m/s)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.advanced(QgsProcessingParameterNumber('WIDTH', 'Domain width across the path [m]',
                                                   QgsProcessingParameterNumber.Double, 600.0, False, 1e-6))
        self.advanced(QgsProcessingParameterNumber('BETA_ANGLE', 'Beta angle: the runout area starts below [deg]',
                                                   QgsProcessingParameterNumber.Double, 10.0, False, 0.0, 90.0))
        self.advanced(QgsProcessingParameterNumber('DS_MIN', 'ds-min: over at least [m]',
                                                   QgsProcessingParameterNumber.Double, 30.0, False, 0.0))
        self.addParameter(QgsProcessingParameterString('NAME', 'Name of the run in the table', 'run'))
        self.advanced(QgsProcessingParameterString('REF_NAME', 'Name of the reference run', 'reference'))
        self.advanced(QgsProcessingParameterBoolean('PLOTS', 'Draw the PNG plots (gnuplot)', True))
        self.addParameter(QgsProcessingParameterFolderDestination('OUTPUT', 'Output folder'))
        self.addOutput(QgsProcessingOutputFile('PATH_ANALYSIS', 'Path analysis table (CSV)'))
        self.addOutput(QgsProcessingOutputFile('PROFILE', 'Profiles along the path (CSV)'))
        self.addOutput(QgsProcessingOutputFile('SUMMARY', 'Summary'))

    def check(self, parameters, context):
        dem = self.parameterAsRasterLayer(parameters, 'DEM', context)
        check_dem(dem)
        path = self.parameterAsSource(parameters, 'PATH', context)
        if path is None:
            raise InputError('path: a line layer is needed')
        check_vector('path layer {}'.format(path.sourceName()), path, dem)
        split = self.parameterAsSource(parameters, 'SPLIT_POINT', context)
        if split is not None:
            check_vector('split point layer {}'.format(split.sourceName()), split, dem)
        field = self.enum_string(parameters, 'FIELD')
        if self.parameterAsRasterLayer(parameters, field.upper(), context) is None:
            raise InputError('-field {}: its raster is required (-{})'.format(field, field))
        for key, opt, text in self.RASTERS:
            r = self.parameterAsRasterLayer(parameters, key, context)
            if r is not None:
                raster_file(r, text)
                if r.crs().isValid() and not same_crs(r.crs(), dem.crs()):
                    raise InputError('{} {}: in another CRS ({}) than the DEM {} ({})'
                                     .format(text, r.name(), crs_text(r.crs()), dem.name(), crs_text(dem.crs())))

    def process(self, parameters, context, feedback):
        self.check(parameters, context)
        dem = self.parameterAsRasterLayer(parameters, 'DEM', context)
        out = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        tmp = QgsProcessingUtils.tempFolder()
        path = os.path.join(tmp, 'path_aimec.shp')
        write_vector(self.parameterAsSource(parameters, 'PATH', context), path, dem.crs(), context, feedback)
        args = ['gfPathAnalysis', '-dem', raster_file(dem, 'DEM'), '-path', path]
        split = self.parameterAsSource(parameters, 'SPLIT_POINT', context)
        if split is not None:
            sp = os.path.join(tmp, 'splitPoint.shp')
            write_vector(split, sp, dem.crs(), context, feedback)
            args += ['-split', sp]
        for key, opt, text in self.RASTERS:
            r = self.parameterAsRasterLayer(parameters, key, context)
            if r is not None:
                args += [opt, raster_file(r, text)]
        args += ['-field', self.enum_string(parameters, 'FIELD')]
        if self.has_value(parameters, 'THRESHOLD'):
            args += ['-threshold', num(self.parameterAsDouble(parameters, 'THRESHOLD', context))]
        args += ['-width', num(self.parameterAsDouble(parameters, 'WIDTH', context)),
                 '-beta-angle', num(self.parameterAsDouble(parameters, 'BETA_ANGLE', context)),
                 '-ds-min', num(self.parameterAsDouble(parameters, 'DS_MIN', context)),
                 '-name', self.parameterAsString(parameters, 'NAME', context) or 'run',
                 '-ref-name', self.parameterAsString(parameters, 'REF_NAME', context) or 'reference',
                 '-plots', 'yes' if self.parameterAsBoolean(parameters, 'PLOTS', context) else 'no',
                 '-out', out]
        rc, lines = run_tool(args, feedback)
        if rc != 0:
            raise QgsProcessingException('gfPathAnalysis failed: {}'.format(failure('gfPathAnalysis', lines)))
        res = {'OUTPUT': out, 'PATH_ANALYSIS': os.path.join(out, 'pathAnalysis.csv'),
               'PROFILE': os.path.join(out, 'pathProfile.csv'), 'SUMMARY': os.path.join(out, 'summary.dat')}
        if not os.path.isfile(res['PATH_ANALYSIS']):
            raise QgsProcessingException('gfPathAnalysis wrote no {}'.format(res['PATH_ANALYSIS']))
        styles.load(context, res['PATH_ANALYSIS'], 'path analysis', 'PATH_ANALYSIS')
        feedback.setProgress(100)
        return res
