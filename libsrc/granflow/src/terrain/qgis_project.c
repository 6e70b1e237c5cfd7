/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A QGIS 3 project file of a command's results (granflow/qgis_project.h).
 * The elements and attributes are those QGIS 3.22 writes itself
 * (QgsProject::write of a project built with PyQGIS, the renderers of
 * qgis/granflow/styles.py): the layer tree (QgsLayerTreeGroup::writeXml),
 * the map layers (QgsMapLayer::writeLayerXml: id, datasource, layername,
 * srs, provider; a raster's <pipe> with its <rasterrenderer>, a vector's
 * <renderer-v2>), the canvas (QgsMapSettings::writeXml) and the default
 * view (QgsProjectViewSettings), reduced to what QGIS needs to read them
 * back: it fills in the rest with its defaults.  The default ramp is the
 * plugin's (styles.py, RAMP). */
#include "granflow/qgis_project.h"
#include "internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* styles.py's RAMP: pale yellow to dark purple */
static const char *const default_ramp[] = {"#fff5b8", "#fdc34d", "#f67e2a", "#d8402b", "#8f1d48", "#3d0f5c"};
static const char *const shape_names[] = {"circle", "square", "triangle", "diamond"};

static int is_vector(gf_qgis_style s)
{
    return s == GF_QGIS_OUTLINE || s == GF_QGIS_FILL_CLASSES || s == GF_QGIS_LINE || s == GF_QGIS_POINT_KINDS;
}

static const char *style_name(gf_qgis_style s)
{
    switch (s) {
    case GF_QGIS_HILLSHADE: return "HILLSHADE";
    case GF_QGIS_RAMP: return "RAMP";
    case GF_QGIS_CLASSES: return "CLASSES";
    case GF_QGIS_OUTLINE: return "OUTLINE";
    case GF_QGIS_FILL_CLASSES: return "FILL_CLASSES";
    case GF_QGIS_LINE: return "LINE";
    case GF_QGIS_POINT_KINDS: return "POINT_KINDS";
    }
    return "?";
}

/* "#rrggbb" into r, g, b; 0 if it is not that */
static int parse_colour(const char *c, int rgb[3])
{
    if (!c || strlen(c) != 7 || c[0] != '#')
        return 0;
    for (int k = 1; k < 7; ++k)
        if (!isxdigit((unsigned char)c[k]))
            return 0;
    for (int k = 0; k < 3; ++k) {
        char h[3] = {c[1 + 2 * k], c[2 + 2 * k], 0};
        rgb[k] = (int)strtol(h, NULL, 16);
    }
    return 1;
}

/* the checks of one layer (k its index) before anything is written */
static gf_status check_layer(const char *path, size_t k, const gf_qgis_layer *l)
{
    int rgb[3];
    const char *name = l->name ? l->name : "(no name)";
#define BAD(...) gf_fail(GF_EINVAL, "QGIS project %s: layer %zu '%s' (%s): " __VA_ARGS__)
    if (!l->name || !*l->name)
        return gf_fail(GF_EINVAL, "QGIS project %s: layer %zu has no name (a legend name is required)", path, k);
    if ((unsigned)l->style > (unsigned)GF_QGIS_POINT_KINDS)
        return gf_fail(GF_EINVAL,
                       "QGIS project %s: layer %zu '%s': unknown style %d (allowed: HILLSHADE, RAMP, CLASSES, "
                       "OUTLINE, FILL_CLASSES, LINE, POINT_KINDS)",
                       path, k, name, (int)l->style);
    const char *st = style_name(l->style);
    if (!l->source || !*l->source)
        return BAD("no source file", path, k, name, st);
    if (l->group && !*l->group)
        return BAD("group \"\" (NULL for the top level)", path, k, name, st);
    if (!is_vector(l->style) && l->layer)
        return BAD("a raster style with a vector layer '%s' (NULL for a raster)", path, k, name, st, l->layer);
    if (l->layer && !*l->layer)
        return BAD("vector layer \"\" (NULL for the file's only layer)", path, k, name, st);
    switch (l->style) {
    case GF_QGIS_HILLSHADE:
        break;
    case GF_QGIS_RAMP:
        if (!isfinite(l->vmin) || !isfinite(l->vmax) || !(l->vmax > l->vmin))
            return BAD("vmin = %g, vmax = %g: finite with vmax > vmin", path, k, name, st, l->vmin, l->vmax);
        if (l->colors) {
            if (l->ncolor < 2)
                return BAD("%zu colours: a ramp needs >= 2 (colors NULL: the default ramp)", path, k, name, st,
                           l->ncolor);
            for (size_t c = 0; c < l->ncolor; ++c)
                if (!parse_colour(l->colors[c], rgb))
                    return BAD("colour %zu '%s' is not #rrggbb", path, k, name, st, c,
                               l->colors[c] ? l->colors[c] : "(NULL)");
        }
        break;
    case GF_QGIS_CLASSES:
    case GF_QGIS_FILL_CLASSES:
    case GF_QGIS_POINT_KINDS:
        if (l->nclass == 0)
            return BAD("nclass = 0: at least one class", path, k, name, st);
        if (!l->labels || !l->colors)
            return BAD("no %s: nclass = %zu of them required", path, k, name, st, l->labels ? "colors" : "labels",
                       l->nclass);
        if (l->style == GF_QGIS_POINT_KINDS && (!l->values || !l->shapes))
            return BAD("no %s: nclass = %zu of them required", path, k, name, st, l->values ? "shapes" : "values",
                       l->nclass);
        if (l->style != GF_QGIS_CLASSES && (!l->field || !*l->field))
            return BAD("no attribute field to categorize on", path, k, name, st);
        for (size_t c = 0; c < l->nclass; ++c) {
            if (!l->labels[c])
                return BAD("label %zu is NULL", path, k, name, st, c);
            if (!parse_colour(l->colors[c], rgb))
                return BAD("colour %zu '%s' is not #rrggbb", path, k, name, st, c,
                           l->colors[c] ? l->colors[c] : "(NULL)");
            if (l->style != GF_QGIS_POINT_KINDS)
                continue;
            if (!l->values[c])
                return BAD("value %zu is NULL", path, k, name, st, c);
            size_t s = 0;
            while (s < sizeof shape_names / sizeof *shape_names && !(l->shapes[c] && !strcmp(l->shapes[c], shape_names[s])))
                ++s;
            if (s == sizeof shape_names / sizeof *shape_names)
                return BAD("shape %zu '%s' (allowed: circle, square, triangle, diamond)", path, k, name, st, c,
                           l->shapes[c] ? l->shapes[c] : "(NULL)");
        }
        break;
    case GF_QGIS_OUTLINE:
    case GF_QGIS_LINE:
        if (l->color && !parse_colour(l->color, rgb))
            return BAD("colour '%s' is not #rrggbb", path, k, name, st, l->color);
        if (!isfinite(l->width))
            return BAD("width %g mm is not finite", path, k, name, st, l->width);
        break;
    }
#undef BAD
    return GF_SUCCESS;
}

/* ---- XML text ------------------------------------------------------------ */

/* s with & < > " ' escaped (text and attribute values alike) */
static void xml(FILE *f, const char *s)
{
    for (; s && *s; ++s)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default: fputc(*s, f);
        }
}

/* a layer's datasource as QGIS reads it: a relative file "./file" (QGIS's
 * QgsPathResolver resolves "./" and "../" paths against the project's
 * folder), then "|layername=..." for a layer of an OGR data source */
static void datasource(FILE *f, const gf_qgis_layer *l)
{
    if (l->source[0] != '/' && strncmp(l->source, "./", 2) && strncmp(l->source, "../", 3) &&
        !strstr(l->source, "://") && strncmp(l->source, "/vsi", 4))
        fputs("./", f);
    xml(f, l->source);
    if (l->layer) {
        fputs("|layername=", f);
        xml(f, l->layer);
    }
}

/* a layer's id: its position and name (letters, digits, _), unique by the
 * position; longer than 10 characters, since QgsMapLayer::readLayerXml
 * (QGIS 3.22) ignores a shorter <id> and makes up a new one, which the
 * layer tree then does not find */
static void layer_id(FILE *f, size_t k, const char *name)
{
    fprintf(f, "granflow_%zu_", k + 1);
    for (size_t c = 0; name[c] && c < 40; ++c)
        fputc(isalnum((unsigned char)name[c]) ? name[c] : '_', f);
}

static void spatialrefsys(FILE *f, const char *indent, const char *wkt)
{
    fprintf(f, "%s<spatialrefsys>\n%s  <wkt>", indent, indent);
    xml(f, wkt);
    fprintf(f, "</wkt>\n%s</spatialrefsys>\n", indent);
}

/* ---- vector symbols (QgsSymbolLayerUtils::saveSymbol) ---------------------- */

typedef struct {
    const char *k;
    char v[64];
} prop;

/* one symbol of one symbol layer: its properties written twice, as the
 * <Option> map QGIS >= 3.20 writes and as the <prop> list older 3.x read */
static void symbol(FILE *f, size_t name, const char *type, const char *cls, const prop *p, size_t np)
{
    fprintf(f, "          <symbol name=\"%zu\" type=\"%s\" alpha=\"1\" clip_to_extent=\"1\" force_rhr=\"0\">\n", name,
            type);
    fprintf(f, "            <layer class=\"%s\" pass=\"0\" locked=\"0\" enabled=\"1\">\n", cls);
    fputs("              <Option type=\"Map\">\n", f);
    for (size_t i = 0; i < np; ++i)
        fprintf(f, "                <Option name=\"%s\" type=\"QString\" value=\"%s\"/>\n", p[i].k, p[i].v);
    fputs("              </Option>\n", f);
    for (size_t i = 0; i < np; ++i)
        fprintf(f, "              <prop k=\"%s\" v=\"%s\"/>\n", p[i].k, p[i].v);
    fputs("            </layer>\n          </symbol>\n", f);
}

/* property k = the printf of fmt appended to p (np of them) */
__attribute__((format(printf, 4, 5))) static void put(prop *p, size_t *np, const char *k, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    p[*np].k = k;
    vsnprintf(p[*np].v, sizeof p[*np].v, fmt, ap);
    va_end(ap);
    ++*np;
}

/* a colour property: r,g,b,alpha */
static void put_rgba(prop *p, size_t *np, const char *k, const int rgb[3], int alpha)
{
    put(p, np, k, "%d,%d,%d,%d", rgb[0], rgb[1], rgb[2], alpha);
}

static double width_or(double w, double dflt) { return w > 0 ? w : dflt; }

static void vector_renderer(FILE *f, const gf_qgis_layer *l)
{
    int rgb[3] = {32, 32, 32};
    if (l->color)
        parse_colour(l->color, rgb);
    if (l->style == GF_QGIS_OUTLINE || l->style == GF_QGIS_LINE) {
        fputs("      <renderer-v2 type=\"singleSymbol\" symbollevels=\"0\" forceraster=\"0\" enableorderby=\"0\">\n"
              "        <symbols>\n",
              f);
        prop p[6];
        size_t np = 0;
        const int poly = l->style == GF_QGIS_OUTLINE;
        put_rgba(p, &np, poly ? "outline_color" : "line_color", rgb, 255);
        put(p, &np, poly ? "outline_width" : "line_width", "%.6g", width_or(l->width, 0.26));
        put(p, &np, poly ? "outline_width_unit" : "line_width_unit", "MM");
        put(p, &np, poly ? "outline_style" : "line_style", "%s", l->dashed ? "dash" : "solid");
        if (poly) {
            put(p, &np, "style", "no");
            put_rgba(p, &np, "color", rgb, 0);
        }
        symbol(f, 0, poly ? "fill" : "line", poly ? "SimpleFill" : "SimpleLine", p, np);
        fputs("        </symbols>\n      </renderer-v2>\n", f);
        return;
    }
    /* categorized: FILL_CLASSES on the integer values 1..nclass, POINT_KINDS on the strings */
    const int fill = l->style == GF_QGIS_FILL_CLASSES;
    fputs("      <renderer-v2 type=\"categorizedSymbol\" attr=\"", f);
    xml(f, l->field);
    fputs("\" symbollevels=\"0\" forceraster=\"0\" enableorderby=\"0\">\n        <categories>\n", f);
    for (size_t c = 0; c < l->nclass; ++c) {
        fputs("          <category render=\"true\" value=\"", f);
        if (fill)
            fprintf(f, "%zu", c + 1);
        else
            xml(f, l->values[c]);
        fprintf(f, "\" symbol=\"%zu\" label=\"", c);
        xml(f, l->labels[c]);
        fputs("\"/>\n", f);
    }
    fputs("        </categories>\n        <symbols>\n", f);
    for (size_t c = 0; c < l->nclass; ++c) {
        parse_colour(l->colors[c], rgb);
        prop p[6];
        size_t np = 0;
        if (fill) {
            /* the fill at 50 % opacity (alpha 128 of 255), the outline the
             * colour at 60 % brightness, opaque */
            const int dark[3] = {rgb[0] * 3 / 5, rgb[1] * 3 / 5, rgb[2] * 3 / 5};
            put_rgba(p, &np, "color", rgb, 128);
            put(p, &np, "style", "solid");
            put_rgba(p, &np, "outline_color", dark, 255);
            put(p, &np, "outline_style", "solid");
            put(p, &np, "outline_width", "0.4");
            put(p, &np, "outline_width_unit", "MM");
            symbol(f, c, "fill", "SimpleFill", p, np);
        } else {
            put_rgba(p, &np, "color", rgb, 255);
            put(p, &np, "name", "%s", l->shapes[c]);
            put(p, &np, "size", "%.6g", width_or(l->width, 3));
            put(p, &np, "size_unit", "MM");
            put(p, &np, "outline_color", "35,35,35,255");
            put(p, &np, "outline_width", "0.2");
            symbol(f, c, "marker", "SimpleMarker", p, np);
        }
    }
    fputs("        </symbols>\n      </renderer-v2>\n", f);
}

/* ---- raster renderers (QgsRasterRenderer::writeXml and its subclasses) ------ */

static void raster_renderer(FILE *f, const gf_qgis_layer *l)
{
    fputs("      <pipe>\n", f);
    switch (l->style) {
    case GF_QGIS_HILLSHADE:
        /* bilinear resampling of the elevations when zoomed in (the
         * provider's, resamplingStage provider): QGIS shades the resampled
         * block, whose nearest-neighbour steps would show as stripes */
        fputs("        <provider>\n          <resampling enabled=\"true\" zoomedInResamplingMethod=\"bilinear\""
              " zoomedOutResamplingMethod=\"nearestNeighbour\" maxOversampling=\"2\"/>\n        </provider>\n",
              f);
        fputs("        <rasterrenderer type=\"hillshade\" band=\"1\" azimuth=\"315\" angle=\"45\" zfactor=\"1\""
              " multidirection=\"0\" opacity=\"1\" alphaBand=\"-1\"/>\n        <resamplingStage>provider</resamplingStage>\n",
              f);
        break;
    case GF_QGIS_CLASSES:
        fputs("        <rasterrenderer type=\"paletted\" band=\"1\" opacity=\"1\" alphaBand=\"-1\">\n"
              "          <colorPalette>\n",
              f);
        for (size_t c = 0; c < l->nclass; ++c) {
            fprintf(f, "            <paletteEntry value=\"%zu\" color=\"", c + 1);
            xml(f, l->colors[c]);
            fputs("\" alpha=\"255\" label=\"", f);
            xml(f, l->labels[c]);
            fputs("\"/>\n", f);
        }
        fputs("          </colorPalette>\n        </rasterrenderer>\n", f);
        break;
    default: { /* RAMP */
        const char *const *colors = l->colors ? l->colors : default_ramp;
        const size_t n = l->colors ? l->ncolor : sizeof default_ramp / sizeof *default_ramp;
        /* no clip: values above vmax take the last colour; below vmin a
         * transparent range (QgsRasterTransparency, inclusive) that ends a
         * hair below vmin so that vmin itself is drawn */
        const double below = l->vmin - 1e-9 * fmax(1.0, fabs(l->vmin));
        fprintf(f,
                "        <rasterrenderer type=\"singlebandpseudocolor\" band=\"1\" opacity=\"1\" alphaBand=\"-1\""
                " classificationMin=\"%.17g\" classificationMax=\"%.17g\">\n",
                l->vmin, l->vmax);
        fprintf(f,
                "          <rasterTransparency>\n            <singleValuePixelList>\n"
                "              <pixelListEntry min=\"-1.7976931348623157e+308\" max=\"%.17g\" percentTransparent=\"100\"/>\n"
                "            </singleValuePixelList>\n          </rasterTransparency>\n",
                below);
        fprintf(f,
                "          <rastershader>\n            <colorrampshader colorRampType=\"INTERPOLATED\" classificationMode=\"1\""
                " clip=\"0\" minimumValue=\"%.17g\" maximumValue=\"%.17g\" labelPrecision=\"3\">\n",
                l->vmin, l->vmax);
        for (size_t c = 0; c < n; ++c) {
            const double v = c + 1 == n ? l->vmax : l->vmin + (l->vmax - l->vmin) * (double)c / (double)(n - 1);
            char label[64];
            snprintf(label, sizeof label, "%.3g", v);
            fprintf(f, "              <item value=\"%.17g\" color=\"", v);
            xml(f, colors[c]);
            fputs("\" alpha=\"255\" label=\"", f);
            xml(f, label);
            if (l->unit && *l->unit) {
                fputc(' ', f);
                xml(f, l->unit);
            }
            fputs("\"/>\n", f);
        }
        fputs("            </colorrampshader>\n          </rastershader>\n        </rasterrenderer>\n", f);
    }
    }
    fputs("      </pipe>\n", f);
}

/* ---- the project ------------------------------------------------------------ */

static void tree_layer(FILE *f, const char *indent, size_t k, const gf_qgis_layer *l)
{
    fprintf(f, "%s<layer-tree-layer id=\"", indent);
    layer_id(f, k, l->name);
    fputs("\" name=\"", f);
    xml(f, l->name);
    fprintf(f, "\" checked=\"%s\" expanded=\"%d\" providerKey=\"%s\" source=\"", l->visible ? "Qt::Checked" : "Qt::Unchecked",
            l->style != GF_QGIS_HILLSHADE, is_vector(l->style) ? "ogr" : "gdal");
    datasource(f, l);
    fputs("\"/>\n", f);
}

static void map_layer(FILE *f, size_t k, const gf_qgis_layer *l, const char *crs_wkt)
{
    const int vec = is_vector(l->style);
    if (vec) {
        const char *geom = l->style == GF_QGIS_LINE ? "Line" : l->style == GF_QGIS_POINT_KINDS ? "Point" : "Polygon";
        fprintf(f, "    <maplayer type=\"vector\" geometry=\"%s\" hasScaleBasedVisibilityFlag=\"0\">\n", geom);
    } else
        fputs("    <maplayer type=\"raster\" hasScaleBasedVisibilityFlag=\"0\">\n", f);
    fputs("      <id>", f);
    layer_id(f, k, l->name);
    fputs("</id>\n      <datasource>", f);
    datasource(f, l);
    fputs("</datasource>\n      <layername>", f);
    xml(f, l->name);
    fputs("</layername>\n", f);
    if (crs_wkt && *crs_wkt) {
        fputs("      <srs>\n", f);
        spatialrefsys(f, "        ", crs_wkt);
        fputs("      </srs>\n", f);
    }
    fprintf(f, "      <provider%s>%s</provider>\n", vec ? " encoding=\"UTF-8\"" : "", vec ? "ogr" : "gdal");
    if (vec)
        vector_renderer(f, l);
    else
        raster_renderer(f, l);
    fputs("      <blendMode>0</blendMode>\n    </maplayer>\n", f);
}

gf_status gf_qgis_project_write(const char *path, const char *title, const char *crs_wkt, const double extent[4],
                                size_t n, const gf_qgis_layer *layers)
{
    if (!path || !*path)
        return gf_fail(GF_EINVAL, "QGIS project: no file name");
    if (n == 0 || !layers)
        return gf_fail(GF_EINVAL, "QGIS project %s: no layers (n = %zu; at least one)", path, n);
    if (!extent || !isfinite(extent[0]) || !isfinite(extent[1]) || !isfinite(extent[2]) || !isfinite(extent[3]) ||
        !(extent[2] > extent[0]) || !(extent[3] > extent[1]))
        return extent ? gf_fail(GF_EINVAL,
                                "QGIS project %s: view extent xmin %g, ymin %g, xmax %g, ymax %g: finite with "
                                "xmax > xmin and ymax > ymin",
                                path, extent[0], extent[1], extent[2], extent[3])
                      : gf_fail(GF_EINVAL, "QGIS project %s: no view extent (xmin, ymin, xmax, ymax)", path);
    for (size_t k = 0; k < n; ++k) {
        gf_status st = check_layer(path, k, &layers[k]);
        if (st)
            return st;
    }
    const int has_crs = crs_wkt && *crs_wkt;
    FILE *f = fopen(path, "w");
    if (!f)
        return gf_fail(GF_EIO, "QGIS project %s: cannot be written: %s", path, strerror(errno));

    fputs("<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis version=\"3.22.0\" projectname=\"", f);
    xml(f, title);
    fputs("\">\n  <homePath path=\"\"/>\n  <title>", f);
    xml(f, title);
    fputs("</title>\n", f);
    if (has_crs) {
        fputs("  <projectCrs>\n", f);
        spatialrefsys(f, "    ", crs_wkt);
        fputs("  </projectCrs>\n", f);
    }

    /* the layer tree: the top level in order of first use, a group's layers
     * in their order */
    fputs("  <layer-tree-group>\n", f);
    for (size_t k = 0; k < n; ++k) {
        const char *g = layers[k].group;
        if (!g) {
            tree_layer(f, "    ", k, &layers[k]);
            continue;
        }
        size_t first = 0;
        while (!(layers[first].group && !strcmp(layers[first].group, g)))
            ++first;
        if (first < k)
            continue; /* written with its group */
        fputs("    <layer-tree-group name=\"", f);
        xml(f, g);
        fputs("\" checked=\"Qt::Checked\" expanded=\"1\">\n", f);
        for (size_t m = k; m < n; ++m)
            if (layers[m].group && !strcmp(layers[m].group, g))
                tree_layer(f, "      ", m, &layers[m]);
        fputs("    </layer-tree-group>\n", f);
    }
    fputs("  </layer-tree-group>\n", f);

    fputs("  <projectlayers>\n", f);
    for (size_t k = 0; k < n; ++k)
        map_layer(f, k, &layers[k], crs_wkt);
    fputs("  </projectlayers>\n", f);

    /* the initial view: the canvas of QGIS desktop, and the project's default view */
    fprintf(f,
            "  <mapcanvas name=\"theMapCanvas\" annotationsVisible=\"1\">\n    <extent>\n"
            "      <xmin>%.17g</xmin>\n      <ymin>%.17g</ymin>\n      <xmax>%.17g</xmax>\n      <ymax>%.17g</ymax>\n"
            "    </extent>\n    <rotation>0</rotation>\n",
            extent[0], extent[1], extent[2], extent[3]);
    if (has_crs) {
        fputs("    <destinationsrs>\n", f);
        spatialrefsys(f, "      ", crs_wkt);
        fputs("    </destinationsrs>\n", f);
    }
    fputs("    <rendermaptile>0</rendermaptile>\n  </mapcanvas>\n", f);
    fprintf(f,
            "  <ProjectViewSettings UseProjectScales=\"0\" rotation=\"0\">\n    <Scales/>\n"
            "    <DefaultViewExtent xmin=\"%.17g\" ymin=\"%.17g\" xmax=\"%.17g\" ymax=\"%.17g\">\n",
            extent[0], extent[1], extent[2], extent[3]);
    if (has_crs)
        spatialrefsys(f, "      ", crs_wkt);
    fputs("    </DefaultViewExtent>\n  </ProjectViewSettings>\n", f);

    /* relative paths; ProjectionsEnabled: without it QgsProject::read (3.22)
     * ignores <projectCrs> */
    fputs("  <properties>\n    <Paths>\n      <Absolute type=\"bool\">false</Absolute>\n    </Paths>\n"
          "    <SpatialRefSys>\n      <ProjectionsEnabled type=\"int\">1</ProjectionsEnabled>\n    </SpatialRefSys>\n"
          "  </properties>\n"
          "  <projectMetadata>\n    <title>",
          f);
    xml(f, title);
    fputs("</title>\n  </projectMetadata>\n</qgis>\n", f);

    const int bad = ferror(f);
    if (fclose(f) || bad)
        return gf_fail(GF_EIO, "QGIS project %s: writing failed: %s", path, strerror(errno));
    return GF_SUCCESS;
}
