/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The QGIS project writer (granflow/qgis_project.h): the XML text of a
 * project of all seven styles in two groups and a top-level layer (each
 * layer's datasource, provider, renderer and place in the layer tree, the
 * escaping of a name with & < " '), and each refusal with its status and
 * the words naming the layer.  That QGIS 3.22 reads such a project, every
 * layer valid and styled, is tests/foam/qgisProject's check. */
#include "../gf_test.h"

#include "granflow/qgis_project.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../gf_tmpdir.h"
GF_TMPDIR_FIXTURES("gf_qgis_project")

static const double EXTENT[4] = {400000, 300000, 401000, 301000};
static const char *const WKT = "PROJCRS[\"MGI / Austria Lambert\",ID[\"EPSG\",31287]]";

static const char *const ZONE_LABELS[] = {"low", "medium", "high"};
static const char *const ZONE_COLORS[] = {"#ffff00", "#0000ff", "#ff0000"};
static const char *const KINDS[] = {"release", "runout"};
static const char *const KIND_LABELS[] = {"release point", "runout point"};
static const char *const KIND_COLORS[] = {"#00aa00", "#aa00aa"};
static const char *const SHAPES[] = {"triangle", "diamond"};

/* the seven styles: T30 (ramp, classes, fill classes, outline), a top-level
 * hillshade, base (line, points) */
static size_t all_styles(gf_qgis_layer *l)
{
    memset(l, 0, 7 * sizeof *l);
    l[0] = (gf_qgis_layer){.group = "T30", .name = "peak pressure", .source = "T30/pressurePeakMax.tif",
                           .style = GF_QGIS_RAMP, .visible = 1, .vmin = 1, .vmax = 1000, .unit = "kPa"};
    l[1] = (gf_qgis_layer){.group = "T30", .name = "zones", .source = "T30/zones.tif", .style = GF_QGIS_CLASSES,
                           .visible = 1, .nclass = 3, .labels = ZONE_LABELS, .colors = ZONE_COLORS};
    l[2] = (gf_qgis_layer){.group = "T30", .name = "release areas", .source = "releaseAreas.gpkg",
                           .layer = "release_areas", .style = GF_QGIS_FILL_CLASSES, .visible = 0, .nclass = 3,
                           .labels = ZONE_LABELS, .colors = ZONE_COLORS, .field = "class"};
    l[3] = (gf_qgis_layer){.name = "DEM & <\"hill'>", .source = "/data/dem.tif", .style = GF_QGIS_HILLSHADE,
                           .visible = 1};
    l[4] = (gf_qgis_layer){.group = "base", .name = "paths", .source = "vectors.gpkg", .layer = "paths",
                           .style = GF_QGIS_LINE, .visible = 1, .color = "#00ff00", .width = 0.8, .dashed = 1};
    l[5] = (gf_qgis_layer){.group = "base", .name = "points", .source = "vectors.gpkg", .layer = "points",
                           .style = GF_QGIS_POINT_KINDS, .visible = 1, .nclass = 2, .values = KINDS,
                           .labels = KIND_LABELS, .colors = KIND_COLORS, .shapes = SHAPES, .field = "kind"};
    l[6] = (gf_qgis_layer){.group = "T30", .name = "outline", .source = "../other/outline.gpkg", .layer = "outline",
                           .style = GF_QGIS_OUTLINE, .visible = 1, .color = "#202020", .width = 0.6};
    return 7;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    rewind(f);
    char *s = malloc((size_t)n + 1);
    assert_non_null(s);
    assert_int_equal(fread(s, 1, (size_t)n, f), (size_t)n);
    s[n] = 0;
    fclose(f);
    return s;
}

/* the text of the element <tag ...> that contains needle, from its start to its end tag */
static char *element_with(const char *xml, const char *tag, const char *needle)
{
    const char *hit = strstr(xml, needle);
    if (!hit)
        fail_msg("no '%s' in the project", needle);
    char open[64], close[64];
    snprintf(open, sizeof open, "<%s", tag);
    snprintf(close, sizeof close, "</%s>", tag);
    const char *start = NULL;
    for (const char *p = strstr(xml, open); p && p < hit; p = strstr(p + 1, open))
        start = p;
    const char *end = strstr(hit, close);
    if (!start || !end)
        fail_msg("'%s' is not inside a <%s> element", needle, tag);
    size_t n = (size_t)(end - start) + strlen(close);
    char *s = malloc(n + 1);
    assert_non_null(s);
    memcpy(s, start, n);
    s[n] = 0;
    return s;
}

static size_t count(const char *s, const char *needle)
{
    size_t c = 0;
    for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle))
        ++c;
    return c;
}

/* every layer's <maplayer>: its datasource (relative ones "./", the
 * GeoPackage's "|layername="), provider, renderer; the layer tree: group T30
 * (first used first) with its four layers in order, the top-level hillshade,
 * group base; the CRS in projectCrs and each layer's srs; the extent */
static void seven_styles_are_written_with_their_renderers_and_groups(void **state)
{
    (void)state;
    gf_qgis_layer l[7];
    size_t n = all_styles(l);
    const char *path = tmp("regional.qgs");
    assert_int_equal(gf_qgis_project_write(path, "Regional map & <T30>", WKT, EXTENT, n, l), GF_SUCCESS);
    char *x = slurp(path);

    assert_non_null(strstr(x, "<title>Regional map &amp; &lt;T30&gt;</title>"));
    assert_non_null(strstr(x, "<projectCrs>\n    <spatialrefsys>\n      <wkt>PROJCRS[&quot;MGI / Austria Lambert&quot;,"
                              "ID[&quot;EPSG&quot;,31287]]</wkt>"));
    assert_int_equal(count(x, "<srs>"), 7);
    assert_non_null(strstr(x, "<Absolute type=\"bool\">false</Absolute>"));
    assert_non_null(strstr(x, "<ProjectionsEnabled type=\"int\">1</ProjectionsEnabled>"));
    assert_non_null(strstr(x, "<xmin>400000</xmin>\n      <ymin>300000</ymin>\n      <xmax>401000</xmax>\n      "
                              "<ymax>301000</ymax>"));
    assert_non_null(strstr(x, "<DefaultViewExtent xmin=\"400000\" ymin=\"300000\" xmax=\"401000\" ymax=\"301000\">"));

    /* each layer: datasource, provider, renderer */
    static const struct {
        const char *datasource, *provider, *renderer;
    } want[7] = {
        {"<datasource>./T30/pressurePeakMax.tif</datasource>", "<provider>gdal</provider>",
         "type=\"singlebandpseudocolor\""},
        {"<datasource>./T30/zones.tif</datasource>", "<provider>gdal</provider>", "type=\"paletted\""},
        {"<datasource>./releaseAreas.gpkg|layername=release_areas</datasource>",
         "<provider encoding=\"UTF-8\">ogr</provider>", "type=\"categorizedSymbol\" attr=\"class\""},
        {"<datasource>/data/dem.tif</datasource>", "<provider>gdal</provider>", "type=\"hillshade\""},
        {"<datasource>./vectors.gpkg|layername=paths</datasource>", "<provider encoding=\"UTF-8\">ogr</provider>",
         "type=\"singleSymbol\""},
        {"<datasource>./vectors.gpkg|layername=points</datasource>", "<provider encoding=\"UTF-8\">ogr</provider>",
         "type=\"categorizedSymbol\" attr=\"kind\""},
        {"<datasource>../other/outline.gpkg|layername=outline</datasource>",
         "<provider encoding=\"UTF-8\">ogr</provider>", "type=\"singleSymbol\""},
    };
    assert_int_equal(count(x, "<maplayer "), 7);
    for (size_t k = 0; k < n; ++k) {
        char *m = element_with(x, "maplayer", want[k].datasource);
        if (!strstr(m, want[k].provider) || !strstr(m, want[k].renderer))
            fail_msg("layer %zu: no %s or no %s in\n%s", k, want[k].provider, want[k].renderer, m);
        free(m);
    }
    /* the ramp: 6 default colours from 1 to 1000 kPa, below 1 transparent, no clip */
    char *ramp = element_with(x, "maplayer", "pressurePeakMax.tif</datasource>");
    assert_int_equal(count(ramp, "<item "), 6);
    assert_non_null(strstr(ramp, "classificationMin=\"1\" classificationMax=\"1000\""));
    assert_non_null(strstr(ramp, "<item value=\"1\" color=\"#fff5b8\" alpha=\"255\" label=\"1 kPa\"/>"));
    assert_non_null(strstr(ramp, "<item value=\"1000\" color=\"#3d0f5c\" alpha=\"255\" label=\"1e+03 kPa\"/>"));
    assert_non_null(strstr(ramp, "<item value=\"200.80000000000001\" color=\"#fdc34d\" alpha=\"255\" label=\"201 kPa\"/>"));
    assert_non_null(strstr(ramp, "clip=\"0\""));
    assert_non_null(strstr(ramp, "max=\"0.99999999900000003\" percentTransparent=\"100\""));
    free(ramp);
    char *zones = element_with(x, "maplayer", "zones.tif</datasource>");
    assert_int_equal(count(zones, "<paletteEntry "), 3);
    assert_non_null(strstr(zones, "<paletteEntry value=\"3\" color=\"#ff0000\" alpha=\"255\" label=\"high\"/>"));
    free(zones);
    char *fill = element_with(x, "maplayer", "layername=release_areas</datasource>");
    assert_non_null(strstr(fill, "<category render=\"true\" value=\"2\" symbol=\"1\" label=\"medium\"/>"));
    assert_non_null(strstr(fill, "<Option name=\"color\" type=\"QString\" value=\"0,0,255,128\"/>"));
    assert_non_null(strstr(fill, "<prop k=\"outline_color\" v=\"0,0,153,255\"/>"));
    free(fill);
    char *pts = element_with(x, "maplayer", "layername=points</datasource>");
    assert_non_null(strstr(pts, "<category render=\"true\" value=\"runout\" symbol=\"1\" label=\"runout point\"/>"));
    assert_non_null(strstr(pts, "<prop k=\"name\" v=\"diamond\"/>"));
    free(pts);
    char *hill = element_with(x, "maplayer", "<datasource>/data/dem.tif</datasource>");
    assert_non_null(strstr(hill, "azimuth=\"315\" angle=\"45\""));
    assert_non_null(strstr(hill, "zoomedInResamplingMethod=\"bilinear\""));
    assert_non_null(strstr(hill, "<resamplingStage>provider</resamplingStage>"));
    free(hill);
    char *line = element_with(x, "maplayer", "layername=paths</datasource>");
    assert_non_null(strstr(line, "<prop k=\"line_style\" v=\"dash\"/>"));
    assert_non_null(strstr(line, "<prop k=\"line_width\" v=\"0.8\"/>"));
    assert_non_null(strstr(line, "<prop k=\"line_color\" v=\"0,255,0,255\"/>"));
    free(line);
    char *outl = element_with(x, "maplayer", "layername=outline</datasource>");
    assert_non_null(strstr(outl, "<prop k=\"style\" v=\"no\"/>"));
    assert_non_null(strstr(outl, "<prop k=\"outline_style\" v=\"solid\"/>"));
    free(outl);

    /* ids longer than 10 characters (QGIS 3.22 replaces shorter ones), unique */
    for (const char *p = strstr(x, "<id>"); p; p = strstr(p + 1, "<id>")) {
        const size_t len = strcspn(p + 4, "<");
        if (len <= 10)
            fail_msg("a layer id of %zu characters: %.*s", len, (int)len, p + 4);
        char tree_ref[96];
        snprintf(tree_ref, sizeof tree_ref, "<layer-tree-layer id=\"%.*s\"", (int)len, p + 4);
        assert_int_equal(count(x, tree_ref), 1);
    }

    /* the escaped name, in the tree and the layer */
    assert_non_null(strstr(x, "name=\"DEM &amp; &lt;&quot;hill&apos;&gt;\""));
    assert_non_null(strstr(x, "<layername>DEM &amp; &lt;&quot;hill&apos;&gt;</layername>"));
    assert_null(strstr(x, "<\"hill"));

    /* the tree: T30 first (peak, zones, release areas unchecked, outline), then the hillshade, then base */
    const char *t30 = strstr(x, "<layer-tree-group name=\"T30\" checked=\"Qt::Checked\"");
    const char *hs = strstr(x, "<layer-tree-layer id=\"granflow_4_DEM_____hill__\"");
    const char *base = strstr(x, "<layer-tree-group name=\"base\"");
    assert_non_null(t30);
    assert_non_null(hs);
    assert_non_null(base);
    assert_true(t30 < hs && hs < base);
    assert_int_equal(count(x, "<layer-tree-group name="), 2);
    char *g = element_with(x, "layer-tree-group", "<layer-tree-layer id=\"granflow_1_");
    assert_non_null(g);
    const char *a = strstr(g, "id=\"granflow_1_peak_pressure\""), *b = strstr(g, "id=\"granflow_2_zones\""),
               *c = strstr(g, "id=\"granflow_3_release_areas\" name=\"release areas\" checked=\"Qt::Unchecked\""),
               *d = strstr(g, "id=\"granflow_7_outline\"");
    assert_true(a && b && c && d && a < b && b < c && c < d);
    assert_null(strstr(g, "granflow_4_"));
    assert_int_equal(count(g, "<layer-tree-layer "), 4);
    free(g);
    assert_non_null(strstr(hs, "providerKey=\"gdal\" source=\"/data/dem.tif\""));
    free(x);
}

/* no CRS: no projectCrs and no layer srs; a colour list of the caller for the ramp */
static void without_crs_the_layers_have_none(void **state)
{
    (void)state;
    static const char *const two[] = {"#000000", "#FFFFFF"};
    gf_qgis_layer l = {.name = "h", .source = "h.tif", .style = GF_QGIS_RAMP, .visible = 1, .vmin = -2, .vmax = 2,
                       .colors = two, .ncolor = 2};
    const char *path = tmp("nocrs.qgs");
    assert_int_equal(gf_qgis_project_write(path, NULL, "", EXTENT, 1, &l), GF_SUCCESS);
    char *x = slurp(path);
    assert_null(strstr(x, "<projectCrs>"));
    assert_null(strstr(x, "<srs>"));
    assert_non_null(strstr(x, "<item value=\"-2\" color=\"#000000\" alpha=\"255\" label=\"-2\"/>"));
    assert_non_null(strstr(x, "<item value=\"2\" color=\"#FFFFFF\" alpha=\"255\" label=\"2\"/>"));
    assert_non_null(strstr(x, "<layer-tree-layer id=\"granflow_1_h\" name=\"h\" checked=\"Qt::Checked\""));
    free(x);
}

/* each refusal: its status, and the words naming the layer and the fault */
static void bad_layers_are_refused_naming_the_layer(void **state)
{
    (void)state;
    static const char *const bad_colour[] = {"#ffff00", "red", "#ff0000"};
    static const char *const bad_shape[] = {"circle", "star"};
    static const char *const one[] = {"#ffffff"};
    const char *path = tmp("bad.qgs");
    gf_qgis_layer l[7];
    size_t n = all_styles(l);

    assert_int_equal(gf_qgis_project_write(path, "t", WKT, EXTENT, 0, l), GF_EINVAL);
    assert_non_null(strstr(gf_error_detail(), "no layers (n = 0"));
    const double flat[4] = {0, 0, 0, 1};
    assert_int_equal(gf_qgis_project_write(path, "t", WKT, flat, n, l), GF_EINVAL);
    assert_non_null(strstr(gf_error_detail(), "view extent xmin 0, ymin 0, xmax 0, ymax 1"));

    typedef struct {
        size_t k;
        gf_qgis_layer layer;
        const char *words;
    } bad;
    bad b[20];
    size_t nb = 0;
    gf_qgis_layer x;
#define SPOIL(k_, stmt, w)                                                                                          \
    do {                                                                                                            \
        x = l[k_];                                                                                                  \
        stmt;                                                                                                       \
        b[nb++] = (bad){(k_), x, (w)};                                                                              \
    } while (0)
    SPOIL(0, x.name = NULL, "layer 0 has no name");
    SPOIL(1, x.source = NULL, "layer 1 'zones' (CLASSES): no source file");
    SPOIL(3, x.style = (gf_qgis_style)42, "layer 3 'DEM & <\"hill'>': unknown style 42 (allowed: HILLSHADE, RAMP,");
    SPOIL(0, x.vmax = 1, "layer 0 'peak pressure' (RAMP): vmin = 1, vmax = 1: finite with vmax > vmin");
    SPOIL(0, x.vmin = NAN, "layer 0 'peak pressure' (RAMP): vmin = nan, vmax = 1000");
    SPOIL(0, (x.colors = one, x.ncolor = 1), "(RAMP): 1 colours: a ramp needs >= 2");
    SPOIL(0, (x.colors = bad_colour, x.ncolor = 3), "(RAMP): colour 1 'red' is not #rrggbb");
    SPOIL(1, x.nclass = 0, "layer 1 'zones' (CLASSES): nclass = 0: at least one class");
    SPOIL(1, x.labels = NULL, "layer 1 'zones' (CLASSES): no labels: nclass = 3 of them required");
    SPOIL(2, x.colors = NULL, "layer 2 'release areas' (FILL_CLASSES): no colors: nclass = 3 of them required");
    SPOIL(2, x.colors = bad_colour, "layer 2 'release areas' (FILL_CLASSES): colour 1 'red' is not #rrggbb");
    SPOIL(2, x.field = NULL, "layer 2 'release areas' (FILL_CLASSES): no attribute field");
    SPOIL(5, x.values = NULL, "layer 5 'points' (POINT_KINDS): no values: nclass = 2 of them required");
    SPOIL(5, x.shapes = NULL, "layer 5 'points' (POINT_KINDS): no shapes");
    SPOIL(5, x.shapes = bad_shape, "layer 5 'points' (POINT_KINDS): shape 1 'star' (allowed: circle, square, triangle, diamond)");
    SPOIL(4, x.color = "#12345", "layer 4 'paths' (LINE): colour '#12345' is not #rrggbb");
    SPOIL(6, x.color = "#12345g", "layer 6 'outline' (OUTLINE): colour '#12345g' is not #rrggbb");
    SPOIL(1, x.layer = "zones", "layer 1 'zones' (CLASSES): a raster style with a vector layer 'zones'");
#undef SPOIL
    for (size_t i = 0; i < nb; ++i) {
        gf_qgis_layer copy[7];
        memcpy(copy, l, sizeof copy);
        copy[b[i].k] = b[i].layer;
        unlink(path);
        const gf_status st = gf_qgis_project_write(path, "t", WKT, EXTENT, n, copy);
        if (st != GF_EINVAL || !strstr(gf_error_detail(), b[i].words) || !strstr(gf_error_detail(), path))
            fail_msg("case %zu: status %d, '%s'; expected GF_EINVAL naming %s and '%s'", i, (int)st, gf_error_detail(),
                     path, b[i].words);
        if (access(path, F_OK) == 0)
            fail_msg("case %zu: refused, but %s was written", i, path);
    }

    /* a folder that does not exist: GF_EIO naming the path */
    const char *nowhere = tmp("no/such/folder/p.qgs");
    assert_int_equal(gf_qgis_project_write(nowhere, "t", WKT, EXTENT, n, l), GF_EIO);
    assert_non_null(strstr(gf_error_detail(), nowhere));
    assert_non_null(strstr(gf_error_detail(), "cannot be written"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(seven_styles_are_written_with_their_renderers_and_groups),
        cmocka_unit_test(without_crs_the_layers_have_none),
        cmocka_unit_test(bad_layers_are_refused_naming_the_layer),
    };
    return gf_run_tests("tests", tests, setup, teardown);
}
