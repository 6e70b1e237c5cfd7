/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfDecompose

Description
    A decomposition of a terrain case along its avalanche path, for a
    decomposed run of the explicit scheme (doc/guide/parallel.md).  The
    explicit scheme computes only the faces the avalanche covers, so a rank
    whose part the avalanche never reaches idles, and OpenFOAM's geometric
    cuts (simple, hierarchical) balance the mesh, not the avalanche: on a
    path a few hundred metres wide they leave most of the work on one rank.
    gfDecompose cuts *along* the path instead: every face gets its signed
    distance l across the path (libgranflowTerrain gf_path_locate, the path
    analysis' l), and the faces are split at N - 1 values of l into N strips
    that run the whole length of the path, each with an equal share of the
    weight, so that every rank holds part of the avalanche all the way down.
    The weight of a face is its peak thickness in a raster of an earlier
    run (-weights: any run on the same DEM, e.g. the -coarse one's
    postProcessing/hazardMaps/hPeak.tif), or 1 within -width of the path
    (default 200 m) without one.

    Writes constant/cellDecomposition (the rank of every cell of the slab
    mesh, the column under each area face) and system/decomposeParDict
    (method manual) for decomposePar; prints each rank's faces and share of
    the weight.

Usage
    gfDecompose -np N [-path Inputs/LINES/path_aimec.shp]
                [-weights RASTER] [-width 200]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "OFstream.H"

#include "terrainCase.H"
#include "keyword.H"

extern "C"
{
#include "granflow/terrain.h"
#include "granflow/path_analysis.h"
}

#include <algorithm>
#include <numeric>

namespace
{

using namespace Foam;

// The options checked: ranks, width, the path's points and the weights raster
struct options
{
    label np;
    scalar width;
    fileName pathFile;
    size_t npath = 0;
    double* pxy = nullptr;
    bool byRaster = false;
    gf_raster weights;
};

options readOptions(const argList& args, const Time& runTime)
{
    options o;
    o.np = args.getOrDefault<label>("np", 0);
    if (o.np < 2)
    {
        FatalErrorInFunction << "-np " << o.np << ": give the number of ranks, >= 2" << exit(FatalError);
    }
    o.width = args.getOrDefault<scalar>("width", 200);
    if (!(o.width > 0))
    {
        FatalErrorInFunction << "-width " << o.width << ": allowed > 0 [m]" << exit(FatalError);
    }
    o.pathFile = granflow::terrainCase::inCase
    (
        args.getOrDefault<fileName>("path", "Inputs/LINES/path_aimec.shp"), runTime.path()
    );
    if (gf_path_read(o.pathFile.c_str(), &o.npath, &o.pxy) != GF_SUCCESS)
    {
        FatalErrorInFunction << "-path " << o.pathFile << ": " << gf_error_detail() << exit(FatalError);
    }
    o.byRaster = args.found("weights");
    if (o.byRaster)
    {
        const fileName wf = granflow::terrainCase::inCase(args.get<fileName>("weights"), runTime.path());
        if (gf_raster_read(wf.c_str(), &o.weights) != GF_SUCCESS)
        {
            FatalErrorInFunction << "-weights " << wf << ": " << gf_error_detail() << exit(FatalError);
        }
    }
    return o;
}

// Per face: l across the path and the weight (the raster's value, or 1
// within the width of the path)
void distancesAndWeights
(
    const options& o, const vectorField& C, const vector& offset, scalarField& l, scalarField& w
)
{
    forAll(C, f)
    {
        const double x = C[f].x() + offset.x(), y = C[f].y() + offset.y();
        double s = 0, lf = 0;
        gf_path_locate(o.npath, o.pxy, x, y, &s, &lf);
        l[f] = lf;
        if (o.byRaster)
        {
            const double v = gf_raster_bilinear(&o.weights, x, y);
            w[f] = std::isfinite(v) && v > 0 ? v : 0;
        }
        else
        {
            w[f] = mag(lf) <= o.width ? 1 : 0;
        }
    }
    if (!(sum(w) > 0))
    {
        FatalErrorInFunction
            << (o.byRaster ? "-weights: the raster has no positive value under the mesh"
                           : "-width: no face lies that close to the path")
            << " (nothing to balance)" << exit(FatalError);
    }
}

// The faces in the order of l, cut where the running weight passes k/N of
// the total: each face's rank, each rank's weight and faces
labelList stripRanks
(
    const label np, const scalarField& l, const scalarField& w, scalarField& share, labelList& count
)
{
    const label nf = l.size();
    const scalar wSum = sum(w);
    labelList order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](label a, label b) { return l[a] < l[b]; });
    labelList rank(nf, 0);
    share.setSize(np, 0);
    count.setSize(np, 0);
    scalar run = 0;
    label r = 0;
    for (const label f : order)
    {
        while (r < np - 1 && run >= (r + 1)*wSum/np)
        {
            ++r;
        }
        rank[f] = r;
        run += w[f];
        share[r] += w[f];
        ++count[r];
    }
    return rank;
}

// The slab mesh's cells: every cell takes the rank of the area face above
// its column (the face's owner cell, and the cells below it: their
// neighbours' rank, sweeping until every cell has one)
labelList cellRanks(const fvMesh& mesh, const faMesh& aMesh, const labelList& rank)
{
    labelList cells(mesh.nCells(), -1);
    const labelList& faceLabels = aMesh.faceLabels();
    forAll(faceLabels, f)
    {
        cells[mesh.faceOwner()[faceLabels[f]]] = rank[f];
    }
    for (bool again = true; again;)
    {
        again = false;
        forAll(cells, c)
        {
            if (cells[c] >= 0) continue;
            for (const label nb : mesh.cellCells()[c])
            {
                if (cells[nb] >= 0)
                {
                    cells[c] = cells[nb];
                    break;
                }
            }
            again = again || cells[c] < 0;
        }
    }
    return cells;
}

// constant/cellDecomposition (in ASCII, whatever the case writes: a list a
// user can read and edit) and system/decomposeParDict (method manual)
void writeDecomposition
(
    const Time& runTime, const fvMesh& mesh, const labelList& cells, const options& o, const argList& args
)
{
    labelIOList cellDecomposition
    (
        IOobject("cellDecomposition", runTime.constant(), mesh, IOobject::NO_READ, IOobject::NO_WRITE),
        cells
    );
    cellDecomposition.writeObject(IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true);
    OFstream os(runTime.system()/"decomposeParDict");
    os  << "// written by gfDecompose: strips along the path " << o.pathFile.name()
        << (o.byRaster ? " with equal shares of -weights " + args.get<fileName>("weights")
                       : " with equal shares of the faces within -width of the path") << nl
        << "FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }" << nl
        << "numberOfSubdomains " << o.np << ";" << nl
        << "method          manual;" << nl
        << "coeffs          { dataFile \"cellDecomposition\"; }" << nl
        << "manualCoeffs    { dataFile \"cellDecomposition\"; }" << nl;
}

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Decompose a terrain case along its avalanche path (strips across the path with equal"
        " shares of an earlier run's peak thickness): constant/cellDecomposition and"
        " system/decomposeParDict (method manual)"
    );
    argList::noParallel();
    argList::addOption("np", "N", "number of ranks (>= 2)");
    argList::addOption("path", "file", "the path (default Inputs/LINES/path_aimec.shp)");
    argList::addOption("weights", "raster", "peak thickness of an earlier run on the same DEM (hPeak.tif)");
    argList::addOption("width", "m", "without -weights: faces within this distance of the path weigh 1 (default 200)");
    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    #include "createTime.H"
    #include "createMesh.H"
    #include "createFaMesh.H"

    options o = readOptions(args, runTime);
    const IOdictionary props
    (
        IOobject("terrainProperties", runTime.constant(), mesh, IOobject::MUST_READ, IOobject::NO_WRITE)
    );
    const vector offset =
        granflow::keyword::read<vector>(props, granflow::keyword::get("terrainProperties"), "offset");
    const vectorField& C = aMesh.areaCentres().primitiveField();
    scalarField l(C.size()), w(C.size()), share;
    labelList count;
    distancesAndWeights(o, C, offset, l, w);
    const labelList rank = stripRanks(o.np, l, w, share, count);
    writeDecomposition(runTime, mesh, cellRanks(mesh, aMesh, rank), o, args);

    Info<< "Decomposition along " << o.pathFile << " into " << o.np << " strips across it:" << nl;
    forAll(share, i)
    {
        Info<< "    rank " << i << ": " << count[i] << " faces, " << 100*share[i]/sum(w) << " % of the weight" << nl;
    }
    Info<< "Wrote constant/cellDecomposition and system/decomposeParDict (method manual): run decomposePar"
        << nl << "End" << nl << endl;
    free(o.pxy);
    if (o.byRaster) gf_raster_free(&o.weights);
    return 0;
}
