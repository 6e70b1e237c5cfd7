/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfStandardTest

Description
    The field's standard analytic tests on the finite-area solver
    (doc/theory/standard-tests.md): the similarity solution of a spreading
    cap on an inclined Coulomb plane (Hutter et al. 1993), the dam break on
    an inclined Coulomb plane (Faccanoni & Mangeney 2013) and the flat-plane
    pile in marginal equilibrium.  The references and the error measures are
    libgranflow's (granflow/standard_tests.h); this program only maps the
    area mesh onto the test's output grid.

    Each test is defined on a DEM grid (lower-left cell centre, cells, cell
    size 5 m); at a cell size csz the output grid keeps the lower-left
    centre and has floor((n0 - 1) 5/csz) + 1 cells a direction.  The area
    mesh is a window of that grid (its face centres are output cell
    centres) large enough for the flow: the cells outside it count in the
    errors with a numerical value of 0, exactly as a whole-DEM run whose
    flow never reached them.

    The energy line (a block down a parabolic slope) and the rotation test
    (a disc across a bowl at three orientations) run on a DEM of the test
    (-dem, meshed by gfTerrainMesh) and are judged from the solver's
    mass-averaged path (controlDict energyLine yes) with libgranflow's
    energy-line analysis; the rotation test's peak rasters are rotated back
    for gfPathAnalysis.

    system/standardTestDict:
        test      similarity;   // similarity | damBreak | flatPlane | energyLine | rotation
        cellSize  5;            // output grid and mesh cell size [m]
        angle     0;            // rotation: the release rotated clockwise [deg]

    -mesh   writes system/blockMeshDict (the window of the inclined plane,
            a slab below it; the area mesh is its top patch "surface", the
            four edges patch "sides"): tests 1-3
    -dem    writes Inputs/dem.asc, the test's DEM on the window (nodes at the
            output grid's cell centres), and for the rotation test the
            thalweg Inputs/thalweg.geojson: tests 4-5
    -init   writes the test's initial thickness into 0/h (cell-centre
            values, as the field does; rotation: each face's fraction in
            the circle) and prints the released volume
    (none)  tests 1-3: for the selected times (default: the latest) the
            relative L2 and Lmax errors of h and of the momentum at the
            exact time of the field, printed and appended to
            postProcessing/standardTest.dat; tests 4-5: the energy-line
            errors of postProcessing/energyLine/0/energyLine.dat, appended
            to postProcessing/energyLineTest.dat
    -ref C  rotation: the differences to the 0 deg run in case C
            (postProcessing/rotationTest.dat) and this run's peak rasters
            rotated back (postProcessing/rotation/{ppr,pft,pfv}.asc), with
            C's rotated forth and back as the resampling's control

Usage
    gfStandardTest [-mesh | -dem | -init] [-time ...] [-ref case]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "timeSelector.H"
#include "OFstream.H"
#include "keyword.H"

#include "granflow/standard_tests.h"
#include "granflow/terrain.h"

#include <fstream>
#include <sstream>
#include <vector>

using namespace Foam;

namespace
{

// One standard test: its DEM grid and plane, its material, and the window of
// the output grid that the area mesh covers (doc/theory/standard-tests.md).
struct testDef
{
    const char* name;
    double xll, yll;      // lower-left DEM cell centre [m]
    label n0x, n0y;       // DEM cells
    double incl;          // plane inclination [deg], descending towards +x
    double delta;         // bed friction angle [deg] (flat plane: atan(0.1))
    double wx0, wx1, wy0, wy1;   // horizontal window of the mesh [m]
    bool terrain;         // a DEM meshed by gfTerrainMesh (-dem), not a plane (-mesh)
};

const double csz0 = 5;    // every test's DEM cell size [m]

// similarity: 401 x 101 cells, 35 deg, delta 25 deg; the cap spans
//   x in [-54, 93] m, |y| < 84 m at 5 s;
// damBreak: 242 x 162 cells, 22 deg, delta 21 deg; at 5 s the front is at
//   x = 30 m, the rear edge's rarefaction at -132 m, the sides spread
//   outwards at 2 cL = 6 m/s from |y| = 80 m;
// flatPlane: 201 x 201 cells, z = 0, mu 0.1 (the pile ends at r = 60 m)
// energyLine: 1001 x 401 cells, the parabola of C = 2200 m, f_L = C/tan 34 deg
//   beginning at x = 1000 m, mu 0.4; the release (x 2519-2866 m,
//   y -4125..-3875 m) comes to rest above x = 4000 m (the alpha line from
//   its centre of mass meets the parabola near x = 3900 m);
// rotation: the bowl of radius 500 m, 201 x 201 cells, mu 0.45; a circle of
//   50 m at r = 350 m crosses the bowl (the whole DEM is the window)
const testDef tests[] =
{
    {"similarity", -200.01, -250.01, 401, 101, 35, 25, -100, 150, -110, 110, false},
    {"damBreak", -602.5, -402.5, 242, 162, 22, 21, -165, 65, -125, 125, false},
    {"flatPlane", -500, -500, 201, 201, 0, 0, -100, 100, -100, 100, false},
    {"energyLine", 1000, -5000, 1001, 401, 0, 21.801409486351812, 2400, 5400, -4300, -3700, true},
    {"rotation", -500, -500, 201, 201, 0, 24.227745317954163, -500, 500, -500, 500, true},
};

const double deg = M_PI/180;

// Python's round(): halves to even (the dam break's error box)
long pyRound(const double v)
{
    const double f = std::floor(v);
    const double d = v - f;
    if (d > 0.5) return long(f) + 1;
    if (d < 0.5) return long(f);
    return (long(f) % 2 == 0) ? long(f) : long(f) + 1;
}

void check(const gf_status s, const char* what)
{
    if (s != GF_SUCCESS)
    {
        FatalErrorInFunction << what << ": " << gf_strerror(s) << exit(FatalError);
    }
}

// The output grid at cell size csz and the mesh's window on it
struct grid
{
    double xll, yll, csz;
    label nx, ny;
    label i0, i1, j0, j1;   // the window's first and last column and row
    double x(label i) const { return xll + i*csz; }
    double y(label j) const { return yll + j*csz; }
};

grid makeGrid(const testDef& t, const double csz)
{
    grid g;
    g.xll = t.xll;
    g.yll = t.yll;
    g.csz = csz;
    g.nx = label(gf_output_grid_cells(size_t(t.n0x), csz0, csz));
    g.ny = label(gf_output_grid_cells(size_t(t.n0y), csz0, csz));
    g.i0 = max(label(0), label(std::ceil((t.wx0 - t.xll)/csz)));
    g.i1 = min(g.nx - 1, label(std::floor((t.wx1 - t.xll)/csz)));
    g.j0 = max(label(0), label(std::ceil((t.wy0 - t.yll)/csz)));
    g.j1 = min(g.ny - 1, label(std::floor((t.wy1 - t.yll)/csz)));
    return g;
}

double planeZ(const testDef& t, const double x)
{
    return -std::tan(t.incl*deg)*x;
}

// the terrain tests' DEMs (doc/theory/standard-tests.md sections 4 and 5)
double demZ(const testDef& t, const double x, const double y)
{
    if (word(t.name) == "energyLine")
    {
        // z = C (1 - x_l/f_L)^2 for x_l < f_L, 0 beyond; x_l = x - 1000 m
        const double C = 2200, fL = C/std::tan(34*deg), xl = x - 1000;
        return xl < fL ? C*(1 - xl/fL)*(1 - xl/fL) : 0.0;
    }
    // the bowl: z = R - sqrt(R^2 - r^2) for r <= R = 500 m, R beyond
    const double R = 500, r2 = x*x + y*y;
    return r2 < R*R ? R - std::sqrt(R*R - r2) : R;
}

// Write the terrain test's DEM on the mesh's window of the output grid (the
// grid's cell centres are the DEM's nodes) as an ESRI ASCII grid
void writeDem(const Time& runTime, const testDef& t, const grid& g)
{
    const fileName dir(runTime.globalPath()/"Inputs");
    mkDir(dir);
    OFstream os(dir/"dem.asc");
    os.precision(12);
    os  << "ncols " << g.i1 - g.i0 + 1 << nl << "nrows " << g.j1 - g.j0 + 1 << nl
        << "xllcenter " << g.x(g.i0) << nl << "yllcenter " << g.y(g.j0) << nl
        << "cellsize " << g.csz << nl << "NODATA_value -9999" << nl;
    for (label j = g.j1; j >= g.j0; --j)
    {
        for (label i = g.i0; i <= g.i1; ++i)
        {
            os  << demZ(t, g.x(i), g.y(j)) << (i < g.i1 ? " " : "\n");
        }
    }
    Info<< "Wrote " << dir/"dem.asc" << ": " << t.name << ", " << g.i1 - g.i0 + 1 << " x "
        << g.j1 - g.j0 + 1 << " nodes of " << g.csz << " m" << endl;
    if (word(t.name) == "rotation")
    {
        // the comparison's path: the thalweg from (-450, 0) to (200, 0)
        OFstream path(dir/"thalweg.geojson");
        path << "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\","
             << " \"properties\": {\"name\": \"thalweg\"}, \"geometry\": {\"type\": \"LineString\","
             << " \"coordinates\": [[-450, 0], [200, 0]]}}]}" << nl;
        Info<< "Wrote " << dir/"thalweg.geojson" << ": the rotation test's path" << endl;
    }
}

// the rotation test's release centre: (-350, 0) rotated clockwise by angle
void rotationCentre(const double angle, double& x, double& y)
{
    const double a = angle*deg;
    x = -350*std::cos(a);
    y = 350*std::sin(a);
}

void writeBlockMesh(const Time& runTime, const testDef& t, const grid& g)
{
    const double x0 = g.x(g.i0) - 0.5*g.csz, x1 = g.x(g.i1) + 0.5*g.csz;
    const double y0 = g.y(g.j0) - 0.5*g.csz, y1 = g.y(g.j1) + 0.5*g.csz;
    OFstream os(runTime.system()/"blockMeshDict");
    os.precision(15);
    os  << "FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }" << nl
        << "// gfStandardTest -mesh: " << t.name << ", cells of " << g.csz << " m (horizontal),"
        << " columns " << g.i0 << ".." << g.i1 << " of " << g.nx << ", rows " << g.j0 << ".."
        << g.j1 << " of " << g.ny << nl
        << "vertices" << nl << "(" << nl;
    const double xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int top = 0; top < 2; ++top)
    {
        for (int k = 0; k < 4; ++k)
        {
            os  << "    (" << xs[k] << ' ' << ys[k] << ' '
                << planeZ(t, xs[k]) - (top ? 0.0 : 1.0) << ")" << nl;
        }
    }
    os  << ");" << nl
        << "blocks ( hex (0 1 2 3 4 5 6 7) (" << g.i1 - g.i0 + 1 << ' ' << g.j1 - g.j0 + 1
        << " 1) simpleGrading (1 1 1) );" << nl
        << "edges ();" << nl
        << "boundary" << nl << "(" << nl
        << "    surface { type patch; faces ((4 5 6 7)); }" << nl
        << "    terrain { type patch; faces ((0 3 2 1)); }" << nl
        << "    sides   { type patch; faces ((0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7)); }" << nl
        << ");" << nl;
    Info<< "Wrote " << runTime.system()/"blockMeshDict" << ": " << t.name << ", "
        << (g.i1 - g.i0 + 1)*(g.j1 - g.j0 + 1) << " faces of " << g.csz << " m" << endl;
}

// the output cell of each face (the face centres are output cell centres)
labelList faceCells(const faMesh& aMesh, const grid& g)
{
    const vectorField& C = aMesh.areaCentres().primitiveField();
    labelList cell(C.size());
    forAll(C, facei)
    {
        const double fi = (C[facei].x() - g.xll)/g.csz, fj = (C[facei].y() - g.yll)/g.csz;
        const long i = std::lround(fi), j = std::lround(fj);
        if
        (
            std::abs(fi - i) > 1e-6 || std::abs(fj - j) > 1e-6
         || i < 0 || i >= g.nx || j < 0 || j >= g.ny
        )
        {
            FatalErrorInFunction
                << "face " << facei << " (centre " << C[facei] << ") is not a cell centre of the"
                << " output grid (lower-left " << g.xll << ' ' << g.yll << ", " << g.csz
                << " m): write the mesh with gfStandardTest -mesh and the same cellSize"
                << exit(FatalError);
        }
        cell[facei] = label(j*g.nx + i);
    }
    return cell;
}

double initialThickness
(
    const testDef& t, const gf_simisol_params& sp, const double x, const double y, const double angle = 0
)
{
    const word name(t.name);
    if (name == "energyLine")
    {
        // 1 m in the rectangle x in [2519.315, 2865.725], y in [-4125, -3875]
        return (x >= 2519.315 && x <= 2865.725 && y >= -4125 && y <= -3875) ? 1.0 : 0.0;
    }
    if (name == "rotation")
    {
        // 1 m in a circle of 50 m about (-350, 0) rotated clockwise by angle
        double xc, yc;
        rotationCentre(angle, xc, yc);
        return sqr(x - xc) + sqr(y - yc) <= 50*50 ? 1.0 : 0.0;
    }
    if (name == "similarity")
    {
        return gf_simisol_h0(&sp, x, y);
    }
    if (name == "damBreak")
    {
        // hL = 1 m in the rectangle x in [-120, 0], y in [-80, 80]
        return (x >= -120 && x <= 0 && y >= -80 && y <= 80) ? 1.0 : 0.0;
    }
    return gf_flatpile_h0(4, 20, 0.1, x, y);   // H0 4 m, flat top to r = 20 m, slope 0.1
}

// The energy-line series of a run (energyLine.H): rows of t, volume,
// centre x y z, mean |Us|^2, mean path length s
struct series
{
    std::vector<double> t, vol, x, y, z, v2, s;
};

series readSeries(const fileName& file)
{
    std::ifstream is(file.c_str());
    if (!is)
    {
        FatalErrorInFunction
            << file << ": not found (run faGranularFlowFoam with controlDict energyLine yes)"
            << exit(FatalError);
    }
    series r;
    std::string line;
    while (std::getline(is, line))
    {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        double v[7];
        for (double& x : v)
        {
            if (!(ls >> x))
            {
                FatalErrorInFunction << file << ": a row without its 7 numbers: " << line.c_str()
                    << exit(FatalError);
            }
        }
        r.t.push_back(v[0]); r.vol.push_back(v[1]); r.x.push_back(v[2]); r.y.push_back(v[3]);
        r.z.push_back(v[4]); r.v2.push_back(v[5]); r.s.push_back(v[6]);
    }
    if (r.t.size() < 2)
    {
        FatalErrorInFunction << file << ": fewer than two rows" << exit(FatalError);
    }
    // the path length is the tracer's mean only while the mass is constant
    const double dv = std::abs(r.vol.back() - r.vol.front())/r.vol.front();
    if (dv > 1e-9)
    {
        FatalErrorInFunction
            << file << ": the volume changed by " << dv << " (relative) between t = " << r.t.front()
            << " and " << r.t.back() << " s: mass left the mesh, the energy line does not apply"
            << exit(FatalError);
    }
    return r;
}

// The energy-line quantities of a series (libgranflow's analysis)
gf_energy_line analyseSeries(const series& r, const double mu, const double csz, const fileName& file)
{
    std::vector<double> z(r.z), s(r.s);
    gf_energy_line e;
    const gf_status st = gf_energy_line_analyse(s.data(), z.data(), r.v2.data(), s.size(), mu, 9.81, csz, &e);
    if (st != GF_SUCCESS && st != GF_ENOCONV)
    {
        FatalErrorInFunction << file << ": energy line: " << gf_strerror(st) << exit(FatalError);
    }
    return e;
}

// energyLine and rotation: the release (-init) and, after the run, the
// energy-line errors; rotation with -ref: the differences to the reference
// run and this run's peak rasters rotated back
int terrainTest(Time& runTime, const argList& args, const testDef& t, const grid& g, const double angle)
{
    const double mu = std::tan(t.delta*deg);
    const word name(t.name);
    if (args.found("init"))
    {
        #include "createMesh.H"
        #include "createFaMesh.H"
        const IOdictionary props
        (
            IOobject("terrainProperties", runTime.constant(), runTime, IOobject::MUST_READ)
        );
        const vector offset
        (
            granflow::keyword::read<vector>(props, granflow::keyword::get("terrainProperties"), "offset")
        );
        areaScalarField h(IOobject("h", "0", mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE), aMesh);
        const vectorField& C = aMesh.areaCentres().primitiveField();
        const gf_simisol_params sp = gf_simisol_default();
        // energyLine: the value at the face centre (as the plane tests);
        // rotation: 1 m times the face's plan fraction inside the circle (20 x
        // 20 points over the face's square), so that every orientation
        // releases the same volume to 0.1 % and the comparison sees the
        // flow, not how a circle falls on the grid
        const label nSub = name == "rotation" ? 20 : 1;
        forAll(h, facei)
        {
            double sum = 0;
            for (label a = 0; a < nSub; ++a)
            {
                for (label b = 0; b < nSub; ++b)
                {
                    const double dx = nSub > 1 ? ((a + 0.5)/nSub - 0.5)*g.csz : 0;
                    const double dy = nSub > 1 ? ((b + 0.5)/nSub - 0.5)*g.csz : 0;
                    sum += initialThickness
                    (
                        t, sp, C[facei].x() + offset.x() + dx, C[facei].y() + offset.y() + dy, angle
                    );
                }
            }
            h[facei] = sum/(nSub*nSub);
        }
        h.correctBoundaryConditions();
        h.write();
        const scalar v = gSum(h.primitiveField()*aMesh.S().field());
        Info<< "gfStandardTest: " << t.name << ", " << g.csz << " m";
        if (name == "rotation") Info<< ", angle " << angle << " deg";
        Info<< ": released volume " << v << " m3 ("
            << (nSub > 1 ? "1 m times each face's fraction in the circle" : "1 m at the face centres")
            << ")" << endl;
        if (!(v > 0))
        {
            FatalErrorInFunction << "the release does not meet the mesh" << exit(FatalError);
        }
        return 0;
    }

    const fileName file(runTime.globalPath()/"postProcessing"/"energyLine"/"0"/"energyLine.dat");
    const series r = readSeries(file);
    const gf_energy_line e = analyseSeries(r, mu, g.csz, file);
    const double drop = r.z.front() - r.z.back(), travel = r.s.back() - r.s.front();
    Info<< "gfStandardTest: " << t.name << ", " << g.csz << " m";
    if (name == "rotation") Info<< ", angle " << angle << " deg";
    Info<< ", t = " << r.t.back() << " s: travel " << travel << " m, drop " << drop
        << " m, runout angle " << e.gamma/deg << " deg (alpha " << t.delta << " deg);"
        << " errors: runout " << e.err_s << " m, elevation " << e.err_z << " m, angle "
        << e.err_angle/deg << " deg, RMSE_v " << e.rmse_v << " m"
        << (e.extrapolated ? " (intersection extrapolated)" : "") << endl;
    const fileName outDir = runTime.globalPath()/"postProcessing";
    mkDir(outDir);
    {
        const fileName out(outDir/"energyLineTest.dat");
        const bool fresh = !isFile(out);
        OFstream table(out, IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true);
        table.precision(8);
        if (fresh)
        {
            table << "# test cellSize angle tEnd travel drop gammaDeg alphaDeg errS errZ errAngleDeg rmseV"
                  << " extrapolated" << nl;
        }
        table << t.name << ' ' << g.csz << ' ' << angle << ' ' << r.t.back() << ' ' << travel << ' '
              << drop << ' ' << e.gamma/deg << ' ' << t.delta << ' ' << e.err_s << ' ' << e.err_z << ' '
              << e.err_angle/deg << ' ' << e.rmse_v << ' ' << e.extrapolated << nl;
    }
    if (!args.found("ref"))
    {
        return 0;
    }
    if (name != "rotation")
    {
        FatalErrorInFunction << "-ref belongs to the rotation test" << exit(FatalError);
    }
    // (a) the energy-line quantities against the reference run's
    const fileName refCase(args.get<fileName>("ref"));
    const fileName refFile(refCase/"postProcessing"/"energyLine"/"0"/"energyLine.dat");
    const series rr = readSeries(refFile);
    const gf_energy_line er = analyseSeries(rr, mu, g.csz, refFile);
    const double dS = travel - (rr.s.back() - rr.s.front());
    const double dZ = drop - (rr.z.front() - rr.z.back());
    Info<< "gfStandardTest: rotation " << angle << " deg against " << refCase << ": travel "
        << dS << " m, drop " << dZ << " m, runout angle " << (e.gamma - er.gamma)/deg << " deg" << endl;
    {
        const fileName out(outDir/"rotationTest.dat");
        OFstream table(out);
        table.precision(8);
        table << "# angle dTravel dDrop dGammaDeg (this run minus the reference)" << nl
              << angle << ' ' << dS << ' ' << dZ << ' ' << (e.gamma - er.gamma)/deg << nl;
    }
    // (b) this run's peak rasters rotated back about the bowl's centre
    // (bilinear, libgranflow's gf_grid_rotate_back) for the path analysis
    const fileName rotDir(outDir/"rotation");
    mkDir(rotDir);
    const char* rasters[3][2] = {{"pressurePeak", "ppr"}, {"hPeak", "pft"}, {"speedPeak", "pfv"}};
    for (const auto& rs : rasters)
    {
        const fileName in(outDir/"hazardMaps"/(word(rs[0]) + ".asc"));
        gf_raster ras;
        if (gf_raster_read(in.c_str(), &ras) != GF_SUCCESS)
        {
            FatalErrorInFunction << in << ": " << gf_error_detail()
                << " (run with controlDict peakFields yes and hazardMaps yes)" << exit(FatalError);
        }
        std::vector<double> back(size_t(ras.nx)*size_t(ras.ny));
        check(gf_grid_rotate_back(ras.nx, ras.ny, ras.gt, ras.z, angle, 0, 0, back.data()), "rotate back");
        const fileName out(rotDir/(word(rs[1]) + ".asc"));
        check(gf_raster_write(out.c_str(), "AAIGrid", &ras, back.data()), "write the rotated raster");
        gf_raster_free(&ras);
        // the control: the reference's raster rotated forth and back by the
        // same angle, what the bilinear resampling alone makes of it
        const fileName refIn(refCase/"postProcessing"/"hazardMaps"/(word(rs[0]) + ".asc"));
        if (gf_raster_read(refIn.c_str(), &ras) != GF_SUCCESS)
        {
            FatalErrorInFunction << refIn << ": " << gf_error_detail() << exit(FatalError);
        }
        std::vector<double> forth(size_t(ras.nx)*size_t(ras.ny));
        check(gf_grid_rotate_back(ras.nx, ras.ny, ras.gt, ras.z, -angle, 0, 0, forth.data()), "rotate forth");
        check(gf_grid_rotate_back(ras.nx, ras.ny, ras.gt, forth.data(), angle, 0, 0, back.data()), "rotate back");
        const fileName outRef(rotDir/("refRoundTrip_" + word(rs[1]) + ".asc"));
        check(gf_raster_write(outRef.c_str(), "AAIGrid", &ras, back.data()), "write the round trip");
        gf_raster_free(&ras);
    }
    Info<< "gfStandardTest: peak rasters rotated back by " << angle << " deg: " << rotDir
        << "/{ppr,pft,pfv}.asc; the reference's rotated forth and back (the resampling alone):"
        << " refRoundTrip_{ppr,pft,pfv}.asc" << endl;
    return 0;
}

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote("The standard analytic tests: mesh, initial state and errors (granflow)");
    timeSelector::addOptions(true, false);
    argList::addBoolOption("mesh", "write system/blockMeshDict for the test's window");
    argList::addBoolOption("init", "write the test's initial thickness into 0/h");
    argList::addBoolOption("dem", "write the terrain test's DEM to Inputs/dem.asc (energyLine, rotation)");
    argList::addOption
    (
        "ref", "case", "rotation: the reference run (angle 0) to compare with; this run's peak rasters"
        " are rotated back into postProcessing/rotation"
    );
    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    #include "createTime.H"

    const IOdictionary dict
    (
        IOobject("standardTestDict", runTime.system(), runTime, IOobject::MUST_READ)
    );
    const granflow::keyword::table& kt = granflow::keyword::get("standardTestDict");
    granflow::keyword::checkKeys(dict, kt);
    const word testName(granflow::keyword::read<word>(dict, kt, "test"));
    const testDef* tp = nullptr;
    for (const testDef& t : tests)
    {
        if (testName == t.name) tp = &t;
    }
    const testDef& t = *tp;   // the table allows only the three names
    const scalar csz = granflow::keyword::read<scalar>(dict, kt, "cellSize");
    const scalar angle = granflow::keyword::read<scalar>(dict, kt, "angle");
    const grid g = makeGrid(t, csz);

    if (args.found("mesh") || args.found("dem"))
    {
        if (t.terrain != args.found("dem"))
        {
            FatalErrorInFunction
                << "system/standardTestDict test " << t.name << ": its mesh comes from "
                << (t.terrain ? "a DEM (gfStandardTest -dem, then gfTerrainMesh)"
                              : "blockMesh (gfStandardTest -mesh)") << exit(FatalError);
        }
        if (t.terrain) writeDem(runTime, t, g);
        else writeBlockMesh(runTime, t, g);
        return 0;
    }
    if (t.terrain)
    {
        return terrainTest(runTime, args, t, g, angle);
    }

    #include "createMesh.H"
    #include "createFaMesh.H"
    const labelList cell(faceCells(aMesh, g));
    const double cosTheta = std::cos(t.incl*deg);
    const double w = csz*csz/cosTheta;   // the sloping area of an output cell
    gf_simisol_params sp = gf_simisol_default();

    if (args.found("init"))
    {
        areaScalarField h
        (
            IOobject("h", "0", mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE), aMesh
        );
        const vectorField& C = aMesh.areaCentres().primitiveField();
        forAll(h, facei)
        {
            h[facei] = initialThickness(t, sp, C[facei].x(), C[facei].y());
        }
        h.correctBoundaryConditions();
        h.write();
        // the volume of the whole output grid's initial field (cells outside
        // the window included: none may hold material)
        double vGrid = 0;
        for (label j = 0; j < g.ny; ++j)
        {
            for (label i = 0; i < g.nx; ++i)
            {
                vGrid += initialThickness(t, sp, g.x(i), g.y(j))*w;
            }
        }
        const scalar vMesh = gSum(h.primitiveField()*aMesh.S().field());
        Info<< "gfStandardTest: " << t.name << ", " << csz << " m: released volume " << vMesh
            << " m3 on the mesh, " << vGrid << " m3 on the whole output grid" << endl;
        if (std::abs(vMesh - vGrid) > 1e-9*vGrid)
        {
            FatalErrorInFunction << "the release does not fit in the mesh's window"
                << exit(FatalError);
        }
        return 0;
    }

    instantList timeDirs = timeSelector::select0(runTime, args);
    if (!args.found("time") && !args.found("latestTime") && timeDirs.size())
    {
        timeDirs = instantList(1, timeDirs.last());
    }
    gf_simisol* simi = nullptr;
    if (testName == "similarity")
    {
        double tMax = 0;
        forAll(timeDirs, ti) tMax = max(tMax, timeDirs[ti].value());
        check(gf_simisol_alloc(&simi, &sp, max(tMax, 1e-3), 1e-10), "the similarity solution");
    }
    gf_incdam dam;
    check(gf_incdam_init(&dam, 9.81, 22*deg, 21*deg, 1.0, -120), "the inclined dam break");

    const fileName outDir = runTime.globalPath()/"postProcessing";
    mkDir(outDir);
    const fileName outFile(outDir/"standardTest.dat");
    const bool fresh = !isFile(outFile);
    OFstream table(outFile, IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true);
    table.precision(8);
    if (fresh)
    {
        table << "# test cellSize time hErrorL2 hErrorLMax vhErrorL2 vhErrorLMax cells maxSpeed" << nl;
    }

    const size_t nCells = size_t(g.nx)*size_t(g.ny);
    forAll(timeDirs, ti)
    {
        runTime.setTime(timeDirs[ti], ti);
        const double time = runTime.value();
        IOobject hHeader("h", runTime.timeName(), mesh, IOobject::MUST_READ);
        if (!hHeader.typeHeaderOk<areaScalarField>(true))
        {
            continue;
        }
        const areaScalarField h(hHeader, aMesh);
        const areaVectorField Us(IOobject("Us", runTime.timeName(), mesh, IOobject::MUST_READ), aMesh);

        // numerical fields on the whole output grid (0 outside the window)
        std::vector<double> ft(nCells, 0.0), vel(3*nCells, 0.0);
        forAll(h, facei)
        {
            ft[cell[facei]] = h[facei];
            for (int k = 0; k < 3; ++k) vel[3*cell[facei] + k] = Us[facei][k];
        }
        scalar maxSpeed = gMax(mag(Us.primitiveField()));

        std::vector<double> ha, hn, ma, mn;   // analytic and numerical h and momentum over the set
        size_t nSet = 0;
        bool vectorMomentum = true;
        if (testName == "damBreak")
        {
            // the error box: downstream of the rear rarefaction's influence,
            // x < 220 m, |y| < 50 m; momentum h u along the slope (scalar)
            vectorMomentum = false;
            const double phi = 22*deg;
            const long c0 = pyRound((gf_incdam_xmid(&dam, time) - g.xll)/csz);
            const long c1 = pyRound((220 - g.xll)/csz) - 1;
            const long r0 = pyRound((-50 - g.yll)/csz), r1 = pyRound((50 - g.yll)/csz) - 1;
            for (long j = r0; j <= r1; ++j)
            {
                for (long i = c0; i <= c1; ++i)
                {
                    double hA, uA;
                    gf_incdam_sample(&dam, g.x(label(i)), time, &hA, &uA);
                    const size_t c = size_t(j)*size_t(g.nx) + size_t(i);
                    const double uN = vel[3*c]*std::cos(phi) - vel[3*c + 2]*std::sin(phi);
                    ha.push_back(hA);
                    hn.push_back(ft[c]);
                    ma.push_back(hA*uA);
                    mn.push_back(ft[c]*uN);
                    ++nSet;
                }
            }
        }
        else
        {
            // the whole output grid; momentum as a Cartesian vector
            ha.resize(nCells);
            ma.resize(3*nCells);
            hn = ft;
            mn.resize(3*nCells);
            for (label j = 0; j < g.ny; ++j)
            {
                for (label i = 0; i < g.nx; ++i)
                {
                    const size_t c = size_t(j)*size_t(g.nx) + size_t(i);
                    double hA = 0, vA[3] = {0, 0, 0};
                    if (simi)
                    {
                        check(gf_simisol_sample(simi, g.x(i), g.y(j), time, &hA, vA), "similarity sample");
                    }
                    else
                    {
                        hA = initialThickness(t, sp, g.x(i), g.y(j));   // the pile at rest
                    }
                    ha[c] = hA;
                    for (int k = 0; k < 3; ++k)
                    {
                        ma[3*c + k] = hA*vA[k];
                        mn[3*c + k] = ft[c]*vel[3*c + k];
                    }
                }
            }
            nSet = nCells;
        }
        gf_error_norms eh, em;
        check(gf_error_scalar(ha.data(), hn.data(), nSet, w, &eh), "the thickness error");
        if (vectorMomentum)
        {
            check(gf_error_vector(ma.data(), mn.data(), nSet, w, &em), "the momentum error");
        }
        else
        {
            check(gf_error_scalar(ma.data(), mn.data(), nSet, w, &em), "the momentum error");
        }
        Info<< "gfStandardTest: " << t.name << ", " << csz << " m, t = " << time << " s, "
            << label(nSet) << " cells: h relative L2 " << eh.rel_l2 << ", Lmax " << eh.rel_lmax
            << "; momentum relative L2 " << em.rel_l2 << ", Lmax " << em.rel_lmax
            << "; max speed " << maxSpeed << " m/s" << endl;
        table << t.name << ' ' << csz << ' ' << time << ' ' << eh.rel_l2 << ' ' << eh.rel_lmax
              << ' ' << em.rel_l2 << ' ' << em.rel_lmax << ' ' << label(nSet) << ' ' << maxSpeed << nl;
    }
    gf_simisol_free(simi);
    return 0;
}
