# SPDX-License-Identifier: GPL-3.0-or-later
"""Potential release areas: gfReleaseAreas on a DEM, as the command line
runs it (doc/guide/regional.md, doc/theory/regional.md).  The parameters
become its options; its refusals are its own words; its outputs (the
polygons, the label raster, the tables) are loaded."""
import os
import re
import shutil

from qgis.core import (QgsProcessing, QgsProcessingException, QgsProcessingOutputFile, QgsProcessingOutputNumber,
                       QgsProcessingOutputRasterLayer, QgsProcessingOutputString, QgsProcessingOutputVectorLayer,
                       QgsProcessingParameterBoolean,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterFolderDestination,
                       QgsProcessingParameterNumber, QgsProcessingParameterRange,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterString)

from . import styles
from .base import GranflowAlgorithm, num
from .inputs import InputError
from .path_analysis import raster_file
from .runner import Cancelled, failure, run_tool

_HELP = '''<p>The potential release areas of a DEM with granflow's <code>gfReleaseAreas</code>
(doc/guide/regional.md; the criteria and their sources in doc/theory/regional.md): the cells whose
slope is in the window (default 28&ndash;60&deg;), whose vector ruggedness is at most ROUGHNESS, outside
the forest, split into areas by aspect sectors and kept from MIN_AREA on. Each area's id, area, mean
slope, altitude and aspect; with D0 Salm's release depth d0 = (d0* + gradient (z &minus; zref)) f(slope);
with ALPHA_BETA each area's thalweg, &beta; point and &alpha; runout (Lied and Bakkeh&oslash;i 1980);
with COMPARE the fraction of those polygons (e.g. a documented release) that the areas cover.</p>
<p>The command that ran is in the log; every parameter becomes its option, and a value it refuses is
refused with its words (the option and its allowed range). Writes into the output folder
releaseAreas.gpkg (loaded), releaseAreas.csv, releaseAreas_labels.tif (loaded: each cell's area id),
with ALPHA_BETA alphaBeta.csv and thalwegs.csv, with WIND windShelter.tif. Its polygons are the input
of <i>Regional hazard indication map</i> (granflow:regionalMap).</p>'''

VALUE = re.compile(r'^(\w+)=(.*)$')


class ReleaseAreas(GranflowAlgorithm):

    def name(self):
        return 'releaseAreas'

    def displayName(self):
        return 'Potential release areas (gfReleaseAreas)'

    HELP = _HELP

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterRasterLayer('DEM', 'DEM (elevation raster, projected CRS in metres)'))
        self.addParameter(QgsProcessingParameterRange(
            'SLOPE', 'Slope window [deg] (-slope)', QgsProcessingParameterNumber.Double, '28,60', True))
        self.addParameter(QgsProcessingParameterNumber(
            'MIN_AREA', 'Smallest release area [m2] (-minArea)', QgsProcessingParameterNumber.Double, 10000.0))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'FOREST', 'Forest (polygons; excluded, -forest)', [QgsProcessing.TypeVectorPolygon], optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'D0', 'Salm\'s d0* [m]: each area\'s release depth d0_m (-d0; empty: none)',
            QgsProcessingParameterNumber.Double, None, True))
        self.addParameter(QgsProcessingParameterNumber(
            'GRADIENT', 'd0* change per metre of altitude [m/m] (-gradient)', QgsProcessingParameterNumber.Double,
            0.0))
        self.addParameter(QgsProcessingParameterNumber(
            'ZREF', 'Altitude of d0* [m] (-zref; needed with a gradient)', QgsProcessingParameterNumber.Double,
            None, True))
        self.addParameter(QgsProcessingParameterBoolean(
            'ALPHA_BETA', 'Alpha-beta screening of each area (-alphaBeta)', False))
        self.addParameter(QgsProcessingParameterFeatureSource(
            'COMPARE', 'Compare with (polygons, e.g. a documented release; -compare)',
            [QgsProcessing.TypeVectorPolygon], optional=True))
        self.advanced(QgsProcessingParameterString(
            'ROUGHNESS', 'Largest vector ruggedness (-roughness: a number, or none)', '0.05'))
        self.advanced(QgsProcessingParameterNumber(
            'ROUGHNESS_WINDOW', 'Ruggedness window [cells], odd (-roughnessWindow)',
            QgsProcessingParameterNumber.Integer, 5))
        self.advanced(QgsProcessingParameterNumber(
            'CURVATURE', 'Largest |plan curvature| [1/m] (-curvature; empty: no criterion)',
            QgsProcessingParameterNumber.Double, None, True))
        self.advanced(QgsProcessingParameterNumber(
            'SECTORS', 'Aspect sectors that split the areas (-sectors)', QgsProcessingParameterNumber.Integer, 8))
        self.advanced(QgsProcessingParameterString(
            'WIND', 'Wind shelter: the wind from FROM[,HALF[,DMAX]] deg, deg, m (-wind; empty: none)', '',
            optional=True))
        self.addParameter(QgsProcessingParameterFolderDestination('OUTPUT', 'Output folder'))
        self.addOutput(QgsProcessingOutputVectorLayer('RELEASE_AREAS', 'Release areas (polygons)'))
        self.addOutput(QgsProcessingOutputRasterLayer('LABELS', 'Release area of each cell (id; 0 none)'))
        self.addOutput(QgsProcessingOutputFile('TABLE', 'Release areas (CSV)'))
        self.addOutput(QgsProcessingOutputFile('ALPHA_BETA_TABLE', 'Alpha-beta of each area (CSV)'))
        self.addOutput(QgsProcessingOutputRasterLayer('WIND_SHELTER', 'Wind shelter index [deg]'))
        self.addOutput(QgsProcessingOutputNumber('COUNT', 'Release areas'))
        self.addOutput(QgsProcessingOutputNumber('AREA_TOTAL', 'Their area [m2]'))
        self.addOutput(QgsProcessingOutputNumber('OVERLAP', 'Fraction of COMPARE covered'))
        self.addOutput(QgsProcessingOutputString('COMMAND', 'The command that ran'))

    def vector_file(self, parameters, key, context, feedback):
        path = self.parameterAsCompatibleSourceLayerPath(parameters, key, context, ['shp', 'gpkg', 'geojson'],
                                                         'shp', feedback)
        if not path:
            raise InputError('{}: not a vector layer'.format(key))
        return os.path.abspath(path.split('|')[0])

    def arguments(self, parameters, context, feedback, folder):
        """gfReleaseAreas' command line for the parameters."""
        dem = self.parameterAsRasterLayer(parameters, 'DEM', context)
        if dem is None:
            raise InputError('DEM: required (an elevation raster)')
        args = ['gfReleaseAreas', '-dem', os.path.abspath(raster_file(dem, 'DEM'))]
        r = self.parameterAsRange(parameters, 'SLOPE', context)
        if len(r) != 2:
            raise InputError('SLOPE \'{}\': MIN,MAX in degrees'.format(parameters.get('SLOPE')))
        args += ['-slope', '{},{}'.format(num(r[0]), num(r[1])),
                 '-minArea', num(self.parameterAsDouble(parameters, 'MIN_AREA', context))]
        rough = (self.parameterAsString(parameters, 'ROUGHNESS', context) or '').strip()
        if rough:
            args += ['-roughness', rough]
        args += ['-roughnessWindow', str(self.parameterAsInt(parameters, 'ROUGHNESS_WINDOW', context))]
        if self.has_value(parameters, 'CURVATURE'):
            args += ['-curvature', num(self.parameterAsDouble(parameters, 'CURVATURE', context))]
        args += ['-sectors', str(self.parameterAsInt(parameters, 'SECTORS', context))]
        if self.has_value(parameters, 'FOREST'):
            args += ['-forest', self.vector_file(parameters, 'FOREST', context, feedback)]
        args += ['-out', folder]
        if self.has_value(parameters, 'D0'):
            args += ['-d0', num(self.parameterAsDouble(parameters, 'D0', context))]
            g = self.parameterAsDouble(parameters, 'GRADIENT', context)
            if g != 0:
                args += ['-gradient', num(g)]
            if self.has_value(parameters, 'ZREF'):
                args += ['-zref', num(self.parameterAsDouble(parameters, 'ZREF', context))]
        elif self.parameterAsDouble(parameters, 'GRADIENT', context) != 0 or self.has_value(parameters, 'ZREF'):
            raise InputError('GRADIENT, ZREF: Salm\'s depth needs D0 (d0* [m]); give D0 or leave them out')
        if self.parameterAsBoolean(parameters, 'ALPHA_BETA', context):
            args += ['-alphaBeta']
        wind = (self.parameterAsString(parameters, 'WIND', context) or '').strip()
        if wind:
            args += ['-wind', wind]
        if self.has_value(parameters, 'COMPARE'):
            args += ['-compare', self.vector_file(parameters, 'COMPARE', context, feedback)]
        return args

    def check(self, parameters, context):
        out = self.parameterAsString(parameters, 'OUTPUT', context) if self.has_value(parameters, 'OUTPUT') else ''
        if out and out != 'TEMPORARY_OUTPUT' and os.path.isfile(out):
            raise InputError('OUTPUT {}: a file, not a folder'.format(out))

    def process(self, parameters, context, feedback):
        self.check(parameters, context)
        folder = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        made = not os.path.exists(folder)
        args = self.arguments(parameters, context, feedback, folder)
        try:
            rc, lines = run_tool(args, feedback)
        except Cancelled:
            if made:
                shutil.rmtree(folder, ignore_errors=True)
            raise QgsProcessingException('Cancelled: gfReleaseAreas was stopped')
        if rc != 0:
            if made:   # a refusal writes nothing the user keeps
                shutil.rmtree(folder, ignore_errors=True)
            raise QgsProcessingException('gfReleaseAreas refused or failed (exit status {}): {}'
                                         .format(rc, failure('gfReleaseAreas', lines)))
        values = dict(VALUE.match(l).groups() for l in lines if VALUE.match(l))
        out = {'OUTPUT': folder, 'COMMAND': ' '.join(args)}
        gpkg = os.path.join(folder, 'releaseAreas.gpkg')
        shp = os.path.join(folder, 'releaseAreas.shp')
        files = {'RELEASE_AREAS': gpkg if os.path.isfile(gpkg) else shp,
                 'LABELS': os.path.join(folder, 'releaseAreas_labels.tif'),
                 'TABLE': os.path.join(folder, 'releaseAreas.csv'),
                 'ALPHA_BETA_TABLE': os.path.join(folder, 'alphaBeta.csv'),
                 'WIND_SHELTER': os.path.join(folder, 'windShelter.tif')}
        out.update({k: v for k, v in files.items() if os.path.isfile(v)})
        for key, name in (('COUNT', 'releaseAreas'), ('AREA_TOTAL', 'areaTotal_m2'), ('OVERLAP', 'overlap')):
            if name in values:
                out[key] = float(values[name]) if key != 'COUNT' else int(values[name])
        if 'RELEASE_AREAS' in out:
            styles.load(context, out['RELEASE_AREAS'], 'release areas', 'RELEASE_AREAS',
                        styles.OutlineStyle('#7a0177', '0.5'))
        if 'LABELS' in out:
            styles.load(context, out['LABELS'], 'release area id', 'LABELS',
                        styles.RasterStyle(0.5, '', styles.BLUES))
        if 'WIND_SHELTER' in out:
            styles.load(context, out['WIND_SHELTER'], 'wind shelter [deg]', 'WIND_SHELTER')
        feedback.pushInfo('{} release areas, {} m2{}'.format(
            values.get('releaseAreas', '?'), values.get('areaTotal_m2', '?'),
            '; COMPARE covered {}'.format(values['overlap']) if 'overlap' in values else ''))
        feedback.setProgress(100)
        return out
