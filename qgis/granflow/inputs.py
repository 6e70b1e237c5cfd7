# SPDX-License-Identifier: GPL-3.0-or-later
"""QGIS layers to a folder in AvaFrame's input layout, and the checks before.

    DIR/Inputs/<dem>.asc|.tif       the DEM with its CRS (the layer's file
                                    copied when it is an .asc or GeoTIFF
                                    that carries the layer's CRS, else
                                    written by gdal_translate -a_srs)
    DIR/Inputs/REL/release.shp      release polygons: id, thickness [m]
                                    (from the chosen field or the value), ci95
    DIR/Inputs/ENT/entrainment.shp  entrainment polygons: id, thickness
    DIR/Inputs/RES/resistance.shp   resistance polygons: id
    DIR/Inputs/DAM/dam.shp          the dam's crown line
    DIR/Inputs/LINES/path_aimec.shp the avalanche path
    DIR/Inputs/POINTS/splitPoint.shp the split point

The checks refuse with the command-line tools' words (gfRunCase,
gfSetRelease): a DEM without a CRS, layers in another CRS than the DEM, a
release polygon outside the DEM, a thickness that is missing or not > 0, a
thickness (or ci95) field that is not numeric (a text field); and an output
folder that holds inputs or a case the plugin did not write.
"""
import os
import re
import shutil
import subprocess

from qgis.core import (QgsCoordinateReferenceSystem, QgsFeature, QgsField, QgsFields,
                       QgsProcessingException, QgsRasterLayer, QgsVectorFileWriter)
from qgis.PyQt.QtCore import QVariant

MARKER = '.written-by-granflow-qgis'


class InputError(Exception):
    """Bad input, refused before anything runs: checkParameterValues
    returns its message, processAlgorithm raises it as a
    QgsProcessingException (GranflowAlgorithm.processAlgorithm)."""


def crs_text(crs):
    return crs.authid() or crs.description() or crs.toProj()


def same_crs(a, b):
    """Two CRSs are the same: equal, the same authority id, or the same
    PROJ parameters without the datum shift (gfRunCase's test: an .asc's
    .prj and a shapefile's .prj of one CRS differ in +towgs84, and QGIS
    adds +type=crs to a CRS it found no authority id for)."""
    if a == b:
        return True
    if a.authid() and a.authid() == b.authid():
        return True

    def proj(c):
        return sorted(t for t in c.toProj().split()
                      if not t.startswith('+towgs84=') and t not in ('+type=crs', '+no_defs'))
    return bool(proj(a)) and proj(a) == proj(b)


def check_dem(dem):
    """The DEM layer: a GDAL raster with a CRS."""
    if dem is None or not dem.isValid():
        raise InputError('DEM: not a valid raster layer')
    if not dem.crs().isValid():
        raise InputError('{}: the DEM has no coordinate reference system (add its .prj, or set one: '
                         'gdal_edit.py -a_srs EPSG:..., or the layer\'s Properties > Source in QGIS)'
                         .format(dem.name() or dem.source()))
    if dem.providerType() != 'gdal':
        raise InputError('{}: the DEM must be a raster file GDAL reads (save it as GeoTIFF first)'
                         .format(dem.name()))


def check_vector(name, source, dem):
    """A vector layer: a CRS, the DEM's."""
    crs = source.sourceCrs()
    if not crs.isValid():
        raise InputError('{}: no coordinate reference system (its .prj is missing)'.format(name))
    if not same_crs(crs, dem.crs()):
        raise InputError('{}: in another CRS ({}) than the DEM {} ({}); reproject it (ogr2ogr -t_srs, or '
                         'Processing\'s "Reproject layer")'.format(name, crs_text(crs), dem.name(),
                                                                  crs_text(dem.crs())))


def check_numeric_field(source, field, what, quantity='thickness'):
    """A field that must hold numbers: present, and of a numeric type (a
    text field is refused, even when its texts read as numbers)."""
    i = source.fields().indexOf(field)
    if i < 0:
        raise InputError('{}: no field \'{}\''.format(what, field))
    f = source.fields().at(i)
    if not f.isNumeric():
        kind = 'text' if f.type() == QVariant.String else (f.typeName() or 'non-numeric')
        raise InputError('{}: field \'{}\' is a {} field; a numeric {} field in metres is needed'
                         .format(what, field, kind, quantity))


def thickness_source(source, field, value, what):
    """How a polygon layer's thickness is given: (field, None) or (None,
    value); the field named 'thickness' (AvaFrame's) when neither is."""
    if field:
        check_numeric_field(source, field, what)
        return field, None
    if value is not None:
        if not value > 0:
            raise InputError('{}: thickness {} m; a thickness must be > 0 m'.format(what, value))
        return None, value
    if source.fields().indexOf('thickness') >= 0:
        check_numeric_field(source, 'thickness', what)
        return 'thickness', None
    raise InputError('{}: no \'thickness\' attribute (the thickness [m] of each polygon, AvaFrame\'s): '
                     'choose a thickness field or give a thickness'.format(what))


def feature_thickness(feature, field, value, what):
    if field is None:
        return value
    v = feature[field]
    try:
        v = float(v)
    except (TypeError, ValueError):
        raise InputError('{}: feature {} has no {} value'.format(what, feature.id(), field))
    if not v > 0:
        raise InputError('{}: feature {} has {} = {:g}; the thickness must be > 0 m'
                         .format(what, feature.id(), field, v))
    return v


def check_polygons(source, field, value, dem, what):
    """Every polygon: its thickness > 0, its extent on the DEM (gfSetRelease
    refuses a polygon that covers no face of the mesh)."""
    ext = dem.extent()
    n = 0
    for f in source.getFeatures():
        n += 1
        feature_thickness(f, field, value, what)
        g = f.geometry()
        if g is None or g.isEmpty():
            raise InputError('{}: feature {} has no geometry'.format(what, f.id()))
        b = g.boundingBox()
        if not b.intersects(ext):
            raise InputError(
                '{}: polygon {} (extent x {:.1f} .. {:.1f}, y {:.1f} .. {:.1f}) lies outside the DEM {} '
                '(x {:.1f} .. {:.1f}, y {:.1f} .. {:.1f}): outside the terrain, or in another CRS'
                .format(what, f.id(), b.xMinimum(), b.xMaximum(), b.yMinimum(), b.yMaximum(), dem.name(),
                        ext.xMinimum(), ext.xMaximum(), ext.yMinimum(), ext.yMaximum()))
    if n == 0:
        raise InputError('{}: no polygons'.format(what))


def check_folder(folder):
    """The output folder: new, empty, or a previous output of the plugin
    (Inputs/ with the plugin's marker: its Inputs/ is replaced, run/ and
    ensemble/ rewritten).  Refused: a file, a folder with an Inputs/ the
    plugin did not write (a case's own inputs are never overwritten), an
    OpenFOAM case."""
    what = 'OUTPUT {}'.format(folder)
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise InputError('{}: a file, not a folder; choose a new or empty folder'.format(what))
    inputs = os.path.join(folder, 'Inputs')
    if os.path.lexists(inputs) and not os.path.exists(os.path.join(inputs, MARKER)):
        raise InputError('{}: holds an Inputs/ folder the granflow plugin did not write (its inputs are not '
                         'overwritten); choose a new or empty folder, or a previous output of the plugin, or run '
                         'gfRunCase on that folder in a shell'.format(what))
    if os.path.exists(os.path.join(folder, 'system', 'controlDict')):
        raise InputError('{}: holds an OpenFOAM case (system/controlDict); choose a new or empty folder'
                         .format(what))


def prepare_folder(folder):
    """The case folder: made, or a previous output of the plugin (its
    Inputs/ replaced); refused when it holds other inputs or a case."""
    check_folder(folder)
    inputs = os.path.join(folder, 'Inputs')
    if os.path.isdir(inputs):
        shutil.rmtree(inputs)
    os.makedirs(inputs)
    open(os.path.join(inputs, MARKER), 'w').close()
    return inputs


def dem_file(dem):
    """The DEM layer's file: (path, True) when GDAL reads a local .asc or
    GeoTIFF that carries the layer's CRS itself, else (source, False)."""
    src = dem.source()
    if os.path.isfile(src) and os.path.splitext(src)[1].lower() in ('.asc', '.tif', '.tiff'):
        own = QgsRasterLayer(src, 'crs', 'gdal')
        if own.isValid() and own.crs().isValid() and same_crs(own.crs(), dem.crs()):
            return src, True
    return src, False


def write_dem(dem, inputs, feedback):
    """The DEM into Inputs/: its file and sidecars copied (the same bytes
    as the command-line run reads), or a GeoTIFF with the layer's CRS."""
    src, own = dem_file(dem)
    if own:
        base = os.path.splitext(src)[0]
        name = os.path.basename(src)
        shutil.copyfile(src, os.path.join(inputs, name))
        stem = os.path.splitext(name)[0]
        for side in ('.prj', '.tfw', '.tifw', '.wld'):
            if os.path.isfile(base + side):
                shutil.copyfile(base + side, os.path.join(inputs, stem + side))
        feedback.pushInfo('DEM: {} copied to Inputs/{}'.format(src, name))
        return name
    name = 'dem.tif'
    wkt = os.path.join(inputs, 'dem.wkt')
    with open(wkt, 'w') as f:
        f.write(dem.crs().toWkt(QgsCoordinateReferenceSystem.WKT_PREFERRED_GDAL))
    cmd = ['gdal_translate', '-q', '-of', 'GTiff', '-a_srs', wkt, src, os.path.join(inputs, name)]
    feedback.pushCommandInfo(' '.join(cmd))
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    os.remove(wkt)
    if r.returncode != 0:
        raise QgsProcessingException('DEM {}: gdal_translate failed: {}'.format(src, r.stdout.strip()))
    feedback.pushInfo('DEM: {} written as Inputs/{} with the layer\'s CRS {}'
                      .format(src, name, crs_text(dem.crs())))
    return name


def write_vector(source, path, crs, context, feedback, extra=None):
    """A layer's features as a shapefile with an 'id' and the extra fields
    extra = [(name, function(feature) -> float)]; the geometries as they are."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fields = QgsFields()
    fields.append(QgsField('id', QVariant.Int))
    for name, _ in extra or []:
        fields.append(QgsField(name, QVariant.Double, 'double', 24, 15))
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = 'ESRI Shapefile'
    options.fileEncoding = 'UTF-8'
    writer = QgsVectorFileWriter.create(path, fields, source.wkbType(), crs, context.transformContext(),
                                        options)
    if writer.hasError() != QgsVectorFileWriter.NoError:
        raise QgsProcessingException('{}: {}'.format(path, writer.errorMessage()))
    n = 0
    for f in source.getFeatures():
        out = QgsFeature(fields)
        out.setGeometry(f.geometry())
        out.setAttributes([int(f.id())] + [fn(f) for _, fn in extra or []])
        if not writer.addFeature(out):
            raise QgsProcessingException('{}: {}'.format(path, writer.errorMessage()))
        n += 1
    del writer
    feedback.pushInfo('{} feature(s) written to {}'.format(n, path))
    return n


class CaseInputs:
    """The inputs of a gfRunCase folder, from the algorithm's parameters:
    checked (check()) and written (write())."""

    def __init__(self, alg, parameters, context):
        p = parameters
        self.dem = alg.parameterAsRasterLayer(p, 'DEM', context)
        self.release = alg.parameterAsSource(p, 'RELEASE', context)
        self.rel_field = alg.parameterAsString(p, 'THICKNESS_FIELD', context) or None
        self.rel_value = alg.parameterAsDouble(p, 'THICKNESS', context) if alg.has_value(p, 'THICKNESS') else None
        self.ci95_field = alg.parameterAsString(p, 'CI95_FIELD', context) or None \
            if 'CI95_FIELD' in alg.parameter_names() else None
        self.ci95_value = alg.parameterAsDouble(p, 'CI95', context) \
            if 'CI95' in alg.parameter_names() and alg.has_value(p, 'CI95') else None
        self.ent = alg.parameterAsSource(p, 'ENTRAINMENT', context)
        self.ent_field = alg.parameterAsString(p, 'ENT_THICKNESS_FIELD', context) or None
        self.ent_value = alg.parameterAsDouble(p, 'ENT_THICKNESS', context) \
            if alg.has_value(p, 'ENT_THICKNESS') else None
        self.res = alg.parameterAsSource(p, 'RESISTANCE', context)
        self.dam = alg.parameterAsSource(p, 'DAM', context)
        self.path = alg.parameterAsSource(p, 'PATH', context)
        self.split = alg.parameterAsSource(p, 'SPLIT_POINT', context)

    def check(self):
        check_dem(self.dem)
        if self.release is None:
            raise InputError('release: a polygon layer is needed')
        check_vector('release layer {}'.format(self.release.sourceName()), self.release, self.dem)
        what = 'release layer {}'.format(self.release.sourceName())
        self.rel_field, self.rel_value = thickness_source(self.release, self.rel_field, self.rel_value, what)
        check_polygons(self.release, self.rel_field, self.rel_value, self.dem, what)
        if self.ci95_field:
            check_numeric_field(self.release, self.ci95_field, what, 'ci95')
        if self.ent is not None:
            what = 'entrainment layer {}'.format(self.ent.sourceName())
            check_vector(what, self.ent, self.dem)
            self.ent_field, self.ent_value = thickness_source(self.ent, self.ent_field, self.ent_value, what)
            check_polygons(self.ent, self.ent_field, self.ent_value, self.dem, what)
        for what, src in (('resistance layer', self.res), ('dam layer', self.dam), ('path layer', self.path),
                          ('split point layer', self.split)):
            if src is not None:
                check_vector('{} {}'.format(what, src.sourceName()), src, self.dem)
        if self.split is not None and self.path is None:
            raise InputError('split point: it needs the avalanche path')

    def ci95(self, feature):
        if self.ci95_field:
            v = feature[self.ci95_field]
            try:
                return float(v)
            except (TypeError, ValueError):
                raise InputError('release: feature {} has no {} value'.format(feature.id(), self.ci95_field))
        if self.ci95_value is not None:
            return self.ci95_value
        if self.release.fields().indexOf('ci95') >= 0:
            try:
                return float(feature['ci95'])
            except (TypeError, ValueError):
                return 0.0
        return 0.0

    def sim_type(self):
        if self.ent is not None and self.res is not None:
            return 'entres'
        return 'ent' if self.ent is not None else 'res' if self.res is not None else 'null'

    def write(self, folder, context, feedback):
        """Inputs/ in AvaFrame's layout; returns the DEM's file name."""
        inputs = prepare_folder(folder)
        crs = self.dem.crs()
        name = write_dem(self.dem, inputs, feedback)
        rf, rv = self.rel_field, self.rel_value
        what = 'release layer {}'.format(self.release.sourceName())
        write_vector(self.release, os.path.join(inputs, 'REL', 'release.shp'), crs, context, feedback,
                     [('thickness', lambda f: feature_thickness(f, rf, rv, what)), ('ci95', self.ci95)])
        if self.ent is not None:
            ef, ev = self.ent_field, self.ent_value
            write_vector(self.ent, os.path.join(inputs, 'ENT', 'entrainment.shp'), crs, context, feedback,
                         [('thickness', lambda f: feature_thickness(f, ef, ev, 'entrainment'))])
        if self.res is not None:
            write_vector(self.res, os.path.join(inputs, 'RES', 'resistance.shp'), crs, context, feedback)
        if self.dam is not None:
            write_vector(self.dam, os.path.join(inputs, 'DAM', 'dam.shp'), crs, context, feedback)
        if self.path is not None:
            write_vector(self.path, os.path.join(inputs, 'LINES', 'path_aimec.shp'), crs, context, feedback)
        if self.split is not None:
            write_vector(self.split, os.path.join(inputs, 'POINTS', 'splitPoint.shp'), crs, context, feedback)
        return name
