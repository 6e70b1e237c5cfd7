/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfGmtBatch: GMT modules run one after another in one process (one GMT
 * session, modern mode), for gfReportMaps: a map is some twenty module
 * calls, and as separate `gmt` processes each paid the loading of GMT and
 * its libraries again (most of a map's time).
 *
 *   gfGmtBatch FILE      (or - for standard input)
 *
 * FILE: one call a line, the module's name then its arguments, separated by
 * TAB characters (so that an argument may hold spaces: a title); empty lines
 * and lines starting with '#' are skipped.  The session's name is
 * GMT_SESSION_NAME's, as for the `gmt` program.  Stops at the first call
 * that fails, naming the line and the call; exit status 0 when every call
 * succeeded.  Besides GMT's modules, three calls of its own, so that a
 * report needs no other process than this one and one ghostscript:
 *
 *   gfvector IN OUT [LAYER [WHERE]]
 *                        the lines, polygons or points of the vector file IN
 *                        (any OGR format: a shapefile; its first layer, or
 *                        LAYER of a GeoPackage; only the features of the
 *                        OGR attribute filter WHERE, e.g. "kind = 'alpha'")
 *                        as GMT's OGR/GMT text OUT, without attributes (what
 *                        `ogr2ogr -f OGR_GMT` writes and GMT would run
 *                        ogr2ogr for at each call)
 *   gfcrs RASTER OUT     the name of RASTER's projected or geographic CRS
 *                        (GDAL), one line in OUT (empty without a CRS)
 *   gfcontours EVERY OUT LABELS IN...
 *                        the contour lines of grdcontour -D's files IN (those
 *                        that exist) in OUT, and in LABELS a label for each
 *                        line whose level is a multiple of EVERY: "x y angle
 *                        level" at the line's middle point, the angle along
 *                        the line turned upright (for text -F+a)
 *   gflink TARGET NAME   the symbolic link NAME to TARGET (a script's long
 *                        paths under short names, without an ln process each)
 *   gfifdata FILE CALL...   CALL when FILE exists and is not empty
 *   gftry CALL...        CALL, its failure reported but not stopping the batch
 *   gfsync               prints "gfsync" on standard output once every call
 *                        before it has run (a script feeding the calls on
 *                        standard input waits for it, then reads what they
 *                        wrote: one process for the whole report)
 *   gfconvert DPI MARGIN NAME...
 *                        NAME.ps (a figure of `figure NAME ps`, written by
 *                        `end`) -> NAME.pdf and NAME.png, cropped to the
 *                        drawing plus MARGIN points on each side, the PNG at
 *                        DPI: psconvert's -A+m -E -Tf/-Tg geometry (GMT's
 *                        src/psconvert.c: the HiResBoundingBox plus the
 *                        margins, a landscape page turned by -90 degrees,
 *                        ceil(size * dpi / 72) pixels) and its ghostscript
 *                        settings for the PDF, but for all the figures in
 *                        one ghostscript process (psconvert runs up to
 *                        seven per figure: bbox, PDF, an intermediate PDF
 *                        for transparency, the PNG, each twice
 *                        `gs --version`); the PostScript is rendered once,
 *                        at the PNG's size, straight from the PostScript
 *                        (-dALLOWPSTRANSPARENCY, ghostscript >= 9.53, draws
 *                        GMT's transparency), and the PNG is written here
 *                        (libpng: the Up filter and zlib's fastest level,
 *                        a third of ghostscript's png16m time).
 *
 * GF_GMT_TIMES=1 prints each call's wall and CPU seconds on standard error.
 */
#define _GNU_SOURCE
#include <gmt/gmt.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <png.h>
#include <zlib.h>

#include <errno.h>
#include <malloc.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char** environ;

enum { MAX_ARGS = 256 };

static double seconds(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- gfvector: OGR -> OGR/GMT text ------------------------------------ */

static void write_points(FILE* out, OGRGeometryH g)
{
    const int n = OGR_G_GetPointCount(g);
    for (int i = 0; i < n; ++i)
        fprintf(out, "%.15g %.15g\n", OGR_G_GetX(g, i), OGR_G_GetY(g, i));
}

/* one geometry: a segment per line or ring (a polygon's outer ring @P, its
   holes @H: the OGR/GMT format of GMT's cookbook, chapter "The GMT vector
   data format for OGR compatibility") */
static void write_geometry(FILE* out, OGRGeometryH g)
{
    const OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
    if (t == wkbPolygon) {
        const int n = OGR_G_GetGeometryCount(g);
        for (int r = 0; r < n; ++r) {
            fprintf(out, ">\n# %s\n", r == 0 ? "@P" : "@H");
            write_points(out, OGR_G_GetGeometryRef(g, r));
        }
    } else if (t == wkbLineString) {
        fprintf(out, ">\n");
        write_points(out, g);
    } else if (t == wkbPoint) {
        write_points(out, g); /* a point: one line, no segment header */
    } else if (t == wkbMultiPolygon || t == wkbMultiLineString || t == wkbMultiPoint || t == wkbGeometryCollection) {
        const int n = OGR_G_GetGeometryCount(g);
        for (int k = 0; k < n; ++k)
            write_geometry(out, OGR_G_GetGeometryRef(g, k));
    }
}

static int vector_to_gmt(const char* in, const char* outName, const char* lname, const char* where)
{
    GDALAllRegister();
    GDALDatasetH ds = GDALOpenEx(in, GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds) {
        fprintf(stderr, "gfGmtBatch: gfvector: %s: not a vector file GDAL/OGR reads\n", in);
        return 1;
    }
    OGRLayerH layer = lname && *lname                     ? GDALDatasetGetLayerByName(ds, lname)
                      : GDALDatasetGetLayerCount(ds) > 0 ? GDALDatasetGetLayer(ds, 0)
                                                         : NULL;
    if (!layer) {
        fprintf(stderr, "gfGmtBatch: gfvector: %s: no layer%s%s\n", in, lname && *lname ? " " : "", lname ? lname : "");
        GDALClose(ds);
        return 1;
    }
    if (where && *where && OGR_L_SetAttributeFilter(layer, where) != OGRERR_NONE) {
        fprintf(stderr, "gfGmtBatch: gfvector: %s: the filter \"%s\" (%s)\n", in, where, CPLGetLastErrorMsg());
        GDALClose(ds);
        return 1;
    }
    const OGRwkbGeometryType t = wkbFlatten(OGR_L_GetGeomType(layer));
    const int polygons = t == wkbPolygon || t == wkbMultiPolygon;
    FILE* out = fopen(outName, "w");
    if (!out) {
        fprintf(stderr, "gfGmtBatch: gfvector: %s: %s\n", outName, strerror(errno));
        GDALClose(ds);
        return 1;
    }
    const int points = t == wkbPoint || t == wkbMultiPoint;
    fprintf(out, "# @VGMT1.0 %s\n# FEATURE_DATA\n", polygons ? "@GPOLYGON" : points ? "@GPOINT" : "@GLINESTRING");
    OGR_L_ResetReading(layer);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(layer)) != NULL) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        if (g) write_geometry(out, g);
        OGR_F_Destroy(f);
    }
    const int bad = fclose(out) != 0;
    GDALClose(ds);
    if (bad) fprintf(stderr, "gfGmtBatch: gfvector: %s: cannot write it\n", outName);
    return bad;
}

/* ---- gfcrs: the CRS's name ---------------------------------------------- */

static int crs_name(const char* raster, const char* outName)
{
    GDALAllRegister();
    GDALDatasetH ds = GDALOpenEx(raster, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds) {
        fprintf(stderr, "gfGmtBatch: gfcrs: %s: not a raster GDAL reads\n", raster);
        return 1;
    }
    const char* name = "";
    OGRSpatialReferenceH srs = NULL;
    const char* wkt = GDALGetProjectionRef(ds);
    if (wkt && *wkt) {
        srs = OSRNewSpatialReference(wkt);
        /* gdalsrsinfo -o wkt's PROJCRS["name" or GEOGCRS["name" */
        if (srs && !OSRIsCompound(srs) && (OSRIsProjected(srs) || OSRIsGeographic(srs)) && OSRGetName(srs))
            name = OSRGetName(srs);
    }
    FILE* out = fopen(outName, "w");
    const int bad = !out || fprintf(out, "%s\n", name) < 0 || fclose(out) != 0;
    if (bad) fprintf(stderr, "gfGmtBatch: gfcrs: %s: cannot write it\n", outName);
    if (srs) OSRDestroySpatialReference(srs);
    GDALClose(ds);
    return bad;
}


/* ---- gfcontours: the lines and their labels ----------------------------- */

typedef struct {
    char** x;
    char** y;
    size_t n, cap;
} contour_line;

static void label_line(FILE* out, contour_line* c, int haveLevel, double level, double every)
{
    /* a line of 2 or more points whose level is a multiple of every: its
       middle point and the direction of its neighbours there */
    if (c->n > 1 && haveLevel && fmod(level, every) == 0) {
        const size_t m = (c->n + 1) / 2, i0 = m > 1 ? m - 1 : 1, i1 = m < c->n ? m + 1 : c->n;
        double a = atan2(strtod(c->y[i1 - 1], NULL) - strtod(c->y[i0 - 1], NULL),
                         strtod(c->x[i1 - 1], NULL) - strtod(c->x[i0 - 1], NULL)) * 57.29578;
        if (a > 90) a -= 180;
        if (a < -90) a += 180;
        fprintf(out, "%s %s %.1f %g\n", c->x[m - 1], c->y[m - 1], a, level);
    }
    for (size_t i = 0; i < c->n; ++i) free(c->x[i]), free(c->y[i]);
    c->n = 0;
}

static char* field(char** s)
{
    char* p = *s + strspn(*s, " \t");
    const size_t k = strcspn(p, " \t\r\n");
    char* f = strndup(p, k);
    *s = p + k;
    return f;
}

static int contour_labels(const char* everyText, const char* outName, const char* labelsName, int nin, char** in)
{
    char* end;
    const double every = strtod(everyText, &end);
    if (*end || !(every > 0)) {
        fprintf(stderr, "gfGmtBatch: gfcontours: EVERY '%s': a level step > 0\n", everyText);
        return 1;
    }
    FILE* out = fopen(outName, "w");
    FILE* labels = fopen(labelsName, "w");
    if (!out || !labels) {
        fprintf(stderr, "gfGmtBatch: gfcontours: %s: %s\n", out ? labelsName : outName, strerror(errno));
        if (out) fclose(out);
        if (labels) fclose(labels);
        return 1;
    }
    contour_line c = {NULL, NULL, 0, 0};
    int haveLevel = 0;
    double level = 0;
    char* line = NULL;
    size_t cap = 0;
    int status = 0;
    for (int k = 0; k < nin && status == 0; ++k) {
        FILE* f = fopen(in[k], "r");
        if (!f) continue;   /* grdcontour wrote no lines of this kind */
        while (getline(&line, &cap, f) >= 0) {
            fputs(line, out);
            if (line[0] == '>') {
                /* a segment header: the level from its -Z<level> */
                label_line(labels, &c, haveLevel, level, every);
                haveLevel = 0;
                for (char* p = line + 1; (p = strstr(p, "-Z")) != NULL; p += 2)
                    if (p[-1] == ' ' || p[-1] == '\t' || p[-1] == '>') {
                        level = strtod(p + 2, NULL);
                        haveLevel = 1;
                    }
                continue;
            }
            if (c.n == c.cap) {
                c.cap = c.cap ? 2 * c.cap : 1024;
                char** nx = realloc(c.x, c.cap * sizeof *nx);
                if (nx) c.x = nx;
                char** ny = realloc(c.y, c.cap * sizeof *ny);
                if (ny) c.y = ny;
                if (!nx || !ny) {
                    fprintf(stderr, "gfGmtBatch: gfcontours: out of memory\n");
                    status = 1;
                    break;
                }
            }
            char* p = line;
            c.x[c.n] = field(&p);
            c.y[c.n] = field(&p);
            ++c.n;
        }
        fclose(f);
    }
    if (status == 0) label_line(labels, &c, haveLevel, level, every);
    for (size_t i = 0; i < c.n; ++i) free(c.x[i]), free(c.y[i]);
    free(c.x), free(c.y), free(line);
    if (fclose(out) != 0 || fclose(labels) != 0) {
        fprintf(stderr, "gfGmtBatch: gfcontours: cannot write %s or %s\n", outName, labelsName);
        status = 1;
    }
    return status;
}

/* ---- gfconvert: PostScript figures -> PDF and PNG ------------------------- */

/* a PS string literal of s (the names are gfReportMaps' short ones; escape
   anyway) */
static void ps_string(FILE* f, const char* s)
{
    fputc('(', f);
    for (; *s; ++s) {
        if (*s == '(' || *s == ')' || *s == '\\') fputc('\\', f);
        fputc(*s, f);
    }
    fputc(')', f);
}

/* read exactly n bytes from fd */
static int read_all(int fd, unsigned char* buf, size_t n)
{
    while (n > 0) {
        const ssize_t r = read(fd, buf, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return -1;
        buf += r;
        n -= (size_t)r;
    }
    return 0;
}

/* a PPM header (P6, comments, width, height, 255) from fd, a byte at a time */
static int read_ppm_header(int fd, int* w, int* h)
{
    int v[3], k = 0, c = 0;
    unsigned char ch;
    if (read_all(fd, &ch, 1) || ch != 'P' || read_all(fd, &ch, 1) || ch != '6') return -1;
    while (k < 3) {
        if (read_all(fd, &ch, 1)) return -1;
        if (ch == '#') {
            do {
                if (read_all(fd, &ch, 1)) return -1;
            } while (ch != '\n');
            continue;
        }
        if (ch >= '0' && ch <= '9') {
            c = c * 10 + (ch - '0');
            if (c > 1000000) return -1;
            if (read_all(fd, &ch, 1)) return -1;
            while (ch >= '0' && ch <= '9') {
                c = c * 10 + (ch - '0');
                if (c > 1000000) return -1;
                if (read_all(fd, &ch, 1)) return -1;
            }
            v[k++] = c;
            c = 0;
        }
    }
    if (v[2] != 255 || v[0] < 1 || v[1] < 1) return -1;
    *w = v[0];
    *h = v[1];
    return 0;
}

/* the PNG NAME.png from w x h RGB rows read from fd (row by row: the image
   is never whole in memory) */
static int ppm_rows_to_png(int fd, int w, int h, double dpi, const char* name)
{
    char file[4096];
    snprintf(file, sizeof file, "%s.png", name);
    FILE* out = fopen(file, "wb");
    if (!out) {
        fprintf(stderr, "gfGmtBatch: gfconvert: %s: %s\n", file, strerror(errno));
        return 1;
    }
    unsigned char* row = malloc((size_t)w * 3);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    volatile int status = 1;
    if (row && info && setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, out);
        png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        const png_uint_32 ppm = (png_uint_32)lrint(dpi / 0.0254);   /* pixels per metre, as png16m */
        png_set_pHYs(png, info, ppm, ppm, PNG_RESOLUTION_METER);
        /* the Up filter with zlib's fastest level and run-length matches:
           measured on avaKot's maps, 0.06 s a map against 0.15 s for
           ghostscript's png16m (adaptive filters, level 6), 15 % larger */
        png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
        png_set_compression_level(png, 1);
        png_set_compression_strategy(png, Z_RLE);
        png_write_info(png, info);
        int y = 0;
        for (; y < h; ++y) {
            if (read_all(fd, row, (size_t)w * 3)) break;
            png_write_row(png, row);
        }
        if (y == h) {
            png_write_end(png, info);
            status = 0;
        } else {
            fprintf(stderr, "gfGmtBatch: gfconvert: %s: the raster from ghostscript ended at row %d of %d\n",
                    file, y, h);
        }
    } else {
        fprintf(stderr, "gfGmtBatch: gfconvert: %s: libpng could not write it\n", file);
    }
    png_destroy_write_struct(png ? &png : NULL, info ? &info : NULL);
    free(row);
    if (fclose(out) != 0) status = 1;
    return status;
}

static int convert_figures(int n, char** names, const char* dpiText, const char* marginText)
{
    char* end;
    const double dpi = strtod(dpiText, &end);
    if (*end || !(dpi >= 10 && dpi <= 2400)) {
        fprintf(stderr, "gfGmtBatch: gfconvert: DPI '%s': a number in 10 .. 2400\n", dpiText);
        return 1;
    }
    const double margin = strtod(marginText, &end);
    if (*end || !(margin >= 0 && margin <= 200)) {
        fprintf(stderr, "gfGmtBatch: gfconvert: MARGIN '%s': points in 0 .. 200\n", marginText);
        return 1;
    }
    if (n < 1) {
        fprintf(stderr, "gfGmtBatch: gfconvert: no figure named\n");
        return 1;
    }
    /* the PostScript program ghostscript runs: bounding boxes (the bbox
       device), the rasters (ppmraw to standard output), the PDFs (the
       command line's pdfwrite, one file a page) */
    const char* driver = "gfconvert.ps";
    FILE* ps = fopen(driver, "w");
    if (!ps) {
        fprintf(stderr, "gfGmtBatch: gfconvert: %s: %s\n", driver, strerror(errno));
        return 1;
    }
    fprintf(ps, "%%!PS\n%% gfGmtBatch gfconvert\n/gfmargin %.6f def /gfdpi %.6f def /gfbbres 1200 def\n", margin, dpi);
    /* a file run as an included EPS is (Adobe Technical Note 5002, section
       "Including an EPS file": state saved, the stacks cleaned after) */
    /* an image in the bounding-box pass: its data read through (inline
       data, currentfile), then its rectangle filled (the unit square of
       its user space): the same box as the image drawn, without rendering
       its pixels at the pass's resolution (GMT's images lie in the map's
       frame or the colour bar: avaKot's four boxes the same to the bit) */
    fputs("/gfimagebox { dup type /dicttype eq {\n"
          "    /DataSource get dup type /filetype eq { { dup 65536 string readstring exch pop not { exit } if } loop } if pop\n"
          "  } { pop pop pop pop pop } ifelse gsave 0 0 1 1 rectfill grestore } bind def\n",
          ps);
    fputs("/gfrun { /gfs save def /gfd countdictstack def /gfo count 2 sub def userdict begin run\n"
          "  count gfo sub {pop} repeat countdictstack gfd sub {end} repeat gfs restore } bind def\n"
          "/gfpdf currentdevice def\n"
          /* the drawing's bounding box in points: the bbox device at 1200
             dpi (psconvert's is ghostscript's 4000 dpi default; 1200 dpi is
             within 0.06 pt of it and three times faster on GMT's images) */
          "/gfbox { mark /HWResolution [gfbbres gfbbres] (bbox) finddevice copydevice putdeviceprops setdevice\n"
          "  /showpage {} def /image /gfimagebox load def gfrun /showpage systemdict /showpage get def\n"
          "  userdict /image undef\n"
          "  currentdevice getdeviceprops >> /PageBoundingBox get { 72 mul gfbbres div } forall\n"
          "  gfmargin add 4 1 roll gfmargin add 4 1 roll gfmargin sub 4 1 roll gfmargin sub 4 1 roll\n"
          "  4 array astore } bind def\n"
          /* file box landscape resolution -> - : one page of the file, the
             box's size rounded up to whole pixels at resolution (psconvert:
             -g ceil(w dpi / 72) -r dpi), a landscape page turned */
          "/gfpage { /gfr exch def /gfl exch def aload pop /gfy1 exch def /gfx1 exch def /gfy0 exch def /gfx0 exch def\n"
          "  gfl { gfy1 gfy0 sub gfx1 gfx0 sub } { gfx1 gfx0 sub gfy1 gfy0 sub } ifelse\n"
          "  gfr mul 72 div ceiling 72 mul gfr div exch gfr mul 72 div ceiling 72 mul gfr div exch\n"
          "  2 array astore << /PageSize 3 -1 roll >> setpagedevice\n"
          "  gfl { -90 rotate gfx1 neg gfy0 neg translate } { gfx0 neg gfy0 neg translate } ifelse\n"
          "  gfrun } bind def\n",
          ps);
    fputs("/gffigs [\n", ps);
    for (int i = 0; i < n; ++i) {
        char file[4096];
        snprintf(file, sizeof file, "%s.ps", names[i]);
        FILE* f = fopen(file, "r");
        if (!f) {
            fprintf(stderr, "gfGmtBatch: gfconvert: %s: %s\n", file, strerror(errno));
            fclose(ps);
            return 1;
        }
        /* GMT's modern mode writes a landscape page (psconvert reads the
           same %%Orientation comment in the first 20 lines) */
        int landscape = 0;
        char line[512];
        for (int k = 0; k < 20 && fgets(line, sizeof line, f); ++k)
            if (strncmp(line, "%%Orientation: Landscape", 24) == 0) landscape = 1;
        fclose(f);
        fputs("  [ ", ps);
        ps_string(ps, file);
        fprintf(ps, " %s ]\n", landscape ? "true" : "false");
    }
    fputs("] def\n"
          "/gfboxes [ gffigs { 0 get gfbox } forall ] def\n"
          "mark /OutputFile (-) /HWResolution [gfdpi gfdpi] /GraphicsAlphaBits 2 /TextAlphaBits 4\n"
          "  /UseFastColor true /MaxBitmap 2147483647 (ppmraw) finddevice putdeviceprops setdevice\n"
          "0 1 gffigs length 1 sub { dup gffigs exch get aload pop 3 -1 roll gfboxes exch get exch gfdpi gfpage } for\n"
          "gfpdf setdevice\n"
          "0 1 gffigs length 1 sub { dup gffigs exch get aload pop 3 -1 roll gfboxes exch get exch 300 gfpage } for\n",
          ps);
    if (fclose(ps) != 0) {
        fprintf(stderr, "gfGmtBatch: gfconvert: %s: cannot write it\n", driver);
        return 1;
    }
    /* ghostscript, with psconvert's options for the PDF (GMT 6.4's
       psconvert -Tf: prepress settings, no downsampling, Flate images);
       PostScript's own %stdout to standard error, so that standard output
       carries the rasters alone (ghostscript's Use.htm, -sstdout) */
    char* const argv[] = {
        "gs", "-q", "-sstdout=%stderr", "-dNOPAUSE", "-dBATCH", "-dNOSAFER", "-dALLOWPSTRANSPARENCY", "-dPDFSETTINGS=/prepress",
        "-dDownsampleColorImages=false", "-dDownsampleGrayImages=false", "-dDownsampleMonoImages=false",
        "-dUseFlateCompression=true", "-dEmbedAllFonts=true", "-dSubsetFonts=true", "-dMonoImageFilter=/FlateEncode",
        "-dAutoFilterGrayImages=false", "-dGrayImageFilter=/FlateEncode", "-dAutoFilterColorImages=false",
        "-dColorImageFilter=/FlateEncode", "-dMaxBitmap=2147483647", "-dUseFastColor=true", "-sDEVICE=pdfwrite",
        "-sOutputFile=gfconvert%d.pdf", (char*)driver, NULL};
    int pipefd[2];
    if (pipe(pipefd) != 0) {
        fprintf(stderr, "gfGmtBatch: gfconvert: pipe: %s\n", strerror(errno));
        return 1;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, pipefd[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&fa, pipefd[0]);
    posix_spawn_file_actions_addclose(&fa, pipefd[1]);
    pid_t pid;
    const int spawned = posix_spawnp(&pid, "gs", &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(pipefd[1]);
    if (spawned != 0) {
        fprintf(stderr, "gfGmtBatch: gfconvert: cannot run ghostscript (gs): %s\n", strerror(spawned));
        close(pipefd[0]);
        return 1;
    }
    int status = 0;
    for (int i = 0; i < n && status == 0; ++i) {
        int w, h;
        if (read_ppm_header(pipefd[0], &w, &h) != 0) {
            fprintf(stderr, "gfGmtBatch: gfconvert: ghostscript gave no raster for %s.ps\n", names[i]);
            status = 1;
        } else {
            status = ppm_rows_to_png(pipefd[0], w, h, dpi, names[i]);
        }
    }
    /* what is left (after a failure) so that ghostscript is not blocked */
    unsigned char sink[65536];
    while (read(pipefd[0], sink, sizeof sink) > 0) {
    }
    close(pipefd[0]);
    int ws;
    while (waitpid(pid, &ws, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
        fprintf(stderr, "gfGmtBatch: gfconvert: ghostscript failed (exit status %d; its messages above)\n",
                WIFEXITED(ws) ? WEXITSTATUS(ws) : -1);
        status = 1;
    }
    /* the PDFs, one a page, under their figures' names */
    for (int i = 0; i < n && status == 0; ++i) {
        char from[64], to[4096];
        snprintf(from, sizeof from, "gfconvert%d.pdf", i + 1);
        snprintf(to, sizeof to, "%s.pdf", names[i]);
        if (rename(from, to) != 0) {
            fprintf(stderr, "gfGmtBatch: gfconvert: ghostscript wrote no %s (%s)\n", from, strerror(errno));
            status = 1;
        }
    }
    return status;
}


/* one call of the batch: a built-in or a GMT module; GMT_NOERROR (0) when
   it succeeded */
static int call(void* api, int n, char** args, const char* file, long nline)
{
    if (strcmp(args[0], "gfvector") == 0 && n >= 3 && n <= 5)
        return vector_to_gmt(args[1], args[2], n > 3 ? args[3] : NULL, n > 4 ? args[4] : NULL);
    if (strcmp(args[0], "gfvector") == 0 || strcmp(args[0], "gfcrs") == 0) {
        if (n != 3) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: %s takes %s, not %d\n", file, nline, args[0],
                    args[0][2] == 'v' ? "2 to 4 arguments (IN OUT [LAYER [WHERE]])" : "2 arguments (IN OUT)", n - 1);
            return 1;
        }
        return args[0][2] == 'v' ? vector_to_gmt(args[1], args[2], NULL, NULL) : crs_name(args[1], args[2]);
    }
    if (strcmp(args[0], "gflink") == 0) {
        if (n != 3) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gflink TARGET NAME\n", file, nline);
            return 1;
        }
        if (symlink(args[1], args[2]) != 0) {
            fprintf(stderr, "gfGmtBatch: gflink: cannot link %s as %s: %s\n", args[1], args[2], strerror(errno));
            return 1;
        }
        return 0;
    }
    if (strcmp(args[0], "gfcontours") == 0) {
        if (n < 5) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gfcontours EVERY OUT LABELS IN...\n", file, nline);
            return 1;
        }
        return contour_labels(args[1], args[2], args[3], n - 4, args + 4);
    }
    if (strcmp(args[0], "gfconvert") == 0) {
        if (n < 4) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gfconvert DPI MARGIN NAME...\n", file, nline);
            return 1;
        }
        return convert_figures(n - 3, args + 3, args[1], args[2]);
    }
    if (strcmp(args[0], "gfsync") == 0) {
        const int bad = printf("gfsync\n") < 0 || fflush(stdout) != 0;
        if (bad) fprintf(stderr, "gfGmtBatch: %s line %ld: gfsync: standard output is closed\n", file, nline);
        return bad;
    }
    if (strcmp(args[0], "gfifdata") == 0) {
        if (n < 3) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gfifdata FILE CALL...\n", file, nline);
            return 1;
        }
        FILE* f = fopen(args[1], "r");
        const int data = f != NULL && fgetc(f) != EOF;
        if (f) fclose(f);
        return data ? call(api, n - 2, args + 2, file, nline) : 0;
    }
    if (strcmp(args[0], "gftry") == 0) {
        if (n < 2) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gftry CALL...\n", file, nline);
            return 1;
        }
        if (call(api, n - 1, args + 1, file, nline) != 0)
            fprintf(stderr, "gfGmtBatch: %s line %ld: %s failed; going on (gftry)\n", file, nline, args[1]);
        return 0;
    }
    /* a module: its argument count as the mode, its arguments as argv
       (GMT_MODULE_CMD, a single string, for a module without any) */
    return n > 1 ? GMT_Call_Module(api, args[0], n - 1, args + 1) : GMT_Call_Module(api, args[0], GMT_MODULE_CMD, NULL);
}

int main(int argc, char** argv)
{
    if (argc != 2 || strcmp(argv[1], "-help") == 0 || strcmp(argv[1], "--help") == 0) {
        fprintf(argc == 2 ? stdout : stderr,
                "usage: gfGmtBatch FILE   (one GMT module call a line: the module, then its\n"
                "                          arguments, TAB-separated; FILE - : standard input;\n"
                "                          and gfvector IN OUT, gfcrs RASTER OUT,\n"
                "                          gfconvert DPI MARGIN NAME...: see the source's head)\n");
        return argc == 2 ? 0 : 2;
    }
    /* GMT's modules allocate (calloc) and free 32 MB of temporary columns
       each (gmt_memory.c, GMT_INITIAL_MEM_ROW_ALLOC: 16 MB a column), and
       copy their 2 MB state: with glibc's dynamic mmap threshold every
       module then faults the state's pages in again (mallopt(3)).  A fixed
       threshold between the two (4 MB) and no trimming keep the state's
       pages in the heap, while the columns are mapped fresh: zero pages
       that calloc need not clear, and only the rows a module touches are
       faulted in (from the heap, each calloc cleared all 32 MB: over a
       gigabyte of memset for a report's 36 plot calls): avaKot's four maps
       31,600 -> 24,800 page faults */
    mallopt(M_MMAP_THRESHOLD, 4 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
    FILE* in = strcmp(argv[1], "-") == 0 ? stdin : fopen(argv[1], "r");
    if (!in) {
        fprintf(stderr, "gfGmtBatch: %s: %s\n", argv[1], strerror(errno));
        return 1;
    }
    /* modern mode (gmt begin ... gmt end), errors returned, not exit() */
    void* api = GMT_Create_Session("gfGmtBatch", 2U, GMT_SESSION_NOEXIT | GMT_SESSION_RUNMODE, NULL);
    if (!api) {
        fprintf(stderr, "gfGmtBatch: GMT could not start a session\n");
        if (in != stdin) fclose(in);
        return 1;
    }
    const char* te = getenv("GF_GMT_TIMES");
    const int times = te != NULL && *te != '\0' && strcmp(te, "0") != 0;
    char* line = NULL;
    size_t cap = 0;
    long nline = 0;
    int status = 0;
    while (getline(&line, &cap, in) >= 0) {
        ++nline;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0' || line[0] == '#') continue;
        char* args[MAX_ARGS];
        int n = 0;
        for (char* tok = line; tok != NULL;) {
            char* tab = strchr(tok, '\t');
            if (tab) *tab = '\0';
            char* here = tok;
            tok = tab ? tab + 1 : NULL;
            if (*here == '\0') continue;
            if (n == MAX_ARGS) {
                fprintf(stderr, "gfGmtBatch: %s line %ld: more than %d arguments\n", argv[1], nline, MAX_ARGS - 1);
                status = 1;
                break;
            }
            args[n++] = here;
        }
        if (status) break;
        const double t0 = seconds(CLOCK_MONOTONIC), c0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
        const int err = call(api, n, args, argv[1], nline);
        if (times) {
            const double c1 = seconds(CLOCK_PROCESS_CPUTIME_ID), t1 = seconds(CLOCK_MONOTONIC);
            fprintf(stderr, "gfGmtBatch: %s line %ld: %s %.3f s wall %.3f s cpu\n", argv[1], nline, args[0], t1 - t0,
                    c1 - c0);
        }
        if (err != GMT_NOERROR) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: %s%s failed (error %d)\n", argv[1], nline,
                    strncmp(args[0], "gf", 2) == 0 ? "" : "gmt ", args[0], err);
            status = 1;
            break;
        }
    }
    free(line);
    if (in != stdin) fclose(in);
    if (GMT_Destroy_Session(api) != GMT_NOERROR && status == 0) status = 1;
    return status;
}
