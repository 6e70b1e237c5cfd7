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

    system/standardTestDict:
        test      similarity;   // similarity | damBreak | flatPlane
        cellSize  5;            // output grid and mesh cell size [m]

    -mesh   writes system/blockMeshDict (the window of the inclined plane,
            a slab below it; the area mesh is its top patch "surface", the
            four edges patch "sides")
    -init   writes the test's initial thickness into 0/h (cell-centre
            values, as the field does) and prints the released volume
    (none)  for the selected times (default: the latest) the relative L2
            and Lmax errors of h and of the momentum at the exact time of
            the field, printed and appended to postProcessing/standardTest.dat

Usage
    gfStandardTest [-mesh | -init] [-time ...]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "timeSelector.H"
#include "OFstream.H"
#include "keyword.H"

#include "granflow/standard_tests.h"

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
};

const double csz0 = 5;    // every test's DEM cell size [m]

// similarity: 401 x 101 cells, 35 deg, delta 25 deg; the cap spans
//   x in [-54, 93] m, |y| < 84 m at 5 s;
// damBreak: 242 x 162 cells, 22 deg, delta 21 deg; at 5 s the front is at
//   x = 30 m, the rear edge's rarefaction at -132 m, the sides spread
//   outwards at 2 cL = 6 m/s from |y| = 80 m;
// flatPlane: 201 x 201 cells, z = 0, mu 0.1 (the pile ends at r = 60 m)
const testDef tests[] =
{
    {"similarity", -200.01, -250.01, 401, 101, 35, 25, -100, 150, -110, 110},
    {"damBreak", -602.5, -402.5, 242, 162, 22, 21, -165, 65, -125, 125},
    {"flatPlane", -500, -500, 201, 201, 0, 0, -100, 100, -100, 100},
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

double initialThickness(const testDef& t, const gf_simisol_params& sp, const double x, const double y)
{
    const word name(t.name);
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

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote("The standard analytic tests: mesh, initial state and errors (granflow)");
    timeSelector::addOptions(true, false);
    argList::addBoolOption("mesh", "write system/blockMeshDict for the test's window");
    argList::addBoolOption("init", "write the test's initial thickness into 0/h");
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
    const grid g = makeGrid(t, csz);

    if (args.found("mesh"))
    {
        writeBlockMesh(runTime, t, g);
        return 0;
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
