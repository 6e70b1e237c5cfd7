# SPDX-License-Identifier: GPL-3.0-or-later
"""The look of the loaded results: the peak rasters in a colour ramp from
their threshold (below it transparent, as not reached) to their maximum,
the affected-area outline and probability contours as lines."""
from qgis.core import (QgsColorRampShader, QgsFillSymbol, QgsLineSymbol, QgsProcessingContext,
                       QgsProcessingLayerPostProcessorInterface, QgsRasterBandStats, QgsRasterLayer,
                       QgsRasterShader, QgsSingleBandPseudoColorRenderer, QgsSingleSymbolRenderer, QgsVectorLayer,
                       QgsWkbTypes)
from qgis.PyQt.QtGui import QColor

# the post-processors must outlive processAlgorithm (Processing keeps no
# reference to them)
_KEEP = []

RAMP = ['#fff5b8', '#fdc34d', '#f67e2a', '#d8402b', '#8f1d48', '#3d0f5c']
BLUES = ['#eff6fc', '#b9d6ee', '#6aaed6', '#2f7ebc', '#0b4d93']


class RasterStyle(QgsProcessingLayerPostProcessorInterface):
    """A single-band colour ramp from vmin to the raster's maximum; values
    below vmin are not drawn."""

    def __init__(self, vmin, unit, colors=None, vmax=None):
        super().__init__()
        self.vmin, self.unit, self.colors, self.vmax = vmin, unit, colors or RAMP, vmax

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsRasterLayer):
            style_raster(layer, self.vmin, self.unit, self.colors, self.vmax)


def style_raster(layer, vmin, unit, colors=None, vmax=None):
    colors = colors or RAMP
    if vmax is None:
        stats = layer.dataProvider().bandStatistics(1, QgsRasterBandStats.Max)
        vmax = stats.maximumValue
    vmax = max(vmax, vmin * 1.0001 + 1e-9)
    fn = QgsColorRampShader(vmin, vmax)
    fn.setColorRampType(QgsColorRampShader.Interpolated)
    n = len(colors)
    items = []
    for i, c in enumerate(colors):
        v = vmin + (vmax - vmin) * i / (n - 1)
        items.append(QgsColorRampShader.ColorRampItem(v, QColor(c), '{:.3g} {}'.format(v, unit)))
    fn.setColorRampItemList(items)
    fn.setClip(True)
    shader = QgsRasterShader()
    shader.setRasterShaderFunction(fn)
    r = QgsSingleBandPseudoColorRenderer(layer.dataProvider(), 1, shader)
    r.setClassificationMin(vmin)
    r.setClassificationMax(vmax)
    layer.setRenderer(r)
    layer.emitStyleChanged()
    layer.triggerRepaint()


class OutlineStyle(QgsProcessingLayerPostProcessorInterface):
    """Lines (contours) or polygon outlines without fill."""

    def __init__(self, color='#202020', width='0.6'):
        super().__init__()
        self.color, self.width = color, width

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsVectorLayer):
            style_outline(layer, self.color, self.width)


def style_outline(layer, color='#202020', width='0.6'):
    if layer.geometryType() == QgsWkbTypes.PolygonGeometry:
        sym = QgsFillSymbol.createSimple({'style': 'no', 'outline_color': color, 'outline_width': width})
    else:
        sym = QgsLineSymbol.createSimple({'color': color, 'width': width})
    layer.setRenderer(QgsSingleSymbolRenderer(sym))
    layer.emitStyleChanged()
    layer.triggerRepaint()


def load(context, path, name, output, style=None):
    """Loads path as a layer when the algorithm ends (in QGIS: into the
    project), styled by the post-processor style."""
    details = QgsProcessingContext.LayerDetails(name, context.project(), output)
    if style is not None:
        _KEEP.append(style)
        details.setPostProcessor(style)
    context.addLayerToLoadOnCompletion(path, details)
