/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfTerrainMesh

Description
    A digital elevation model to a terrain-following slab mesh whose top
    patch is the area mesh of the terrain, and that area mesh (constant/faMesh:
    faceLabels and faBoundary, byte for byte what makeFaMesh writes from
    constant/faMesh/faMeshDefinition; areaMeshFiles.H), from
    system/terrainDict (entries in terrainCase.H): GDAL reads the DEM (ESRI
    ASCII grid, GeoTIFF, ...), NODATA cells are left out, the mesh can be
    cropped to a box or polygons and coarsened.  One hexahedron per DEM
    quad between four valid nodes (every k-th node with coarsening k); its
    top face on the terrain, its bottom 'depth' metres below.  An optional
    dam (a 3D crown line and a wall slope) raises the DEM before meshing;
    the raised DEM is written to constant/demWithDam.tif.  Patches:
        terrain  the top faces: the area mesh (faMeshDefinition polyMeshPatches)
                 with its boundary edges on the faPatch whose neighbourPolyPatch
                 is 'sides'
        sides    the lateral faces: the area mesh's boundary
        base     the bottom faces
    Points are the georeferenced coordinates minus the offset, which is
    written with the other entries to constant/terrainProperties for
    gfSetRelease (release polygons) and gfHazardMaps (rasters on the DEM's
    grid).

Usage
    gfTerrainMesh [-cellShapes] [-keywords] [-version]

    -cellShapes: the slab through polyMesh's construction from cell shapes
    (slower, more memory; the same files), the check of the direct one.
\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "polyMesh.H"
#include "cellModel.H"
#include "IOdictionary.H"
#include "OFstream.H"
#include "SubField.H"

#include "terrainCase.H"
#include "areaMeshFiles.H"

using namespace Foam;

int main(int argc, char *argv[])
{
    argList::addNote("DEM (GDAL) to a terrain-following slab mesh (top patch 'terrain') and its area mesh (constant/faMesh, as makeFaMesh writes it)");
    argList::noParallel();
    argList::addBoolOption
    (
        "cellShapes",
        "build the slab through polyMesh's construction from hexahedral cell shapes (slower; "
        "the same files: the check of the direct construction, tests/foam/terrain)"
    );
    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    #include "createTime.H"

    IOdictionary dict
    (
        IOobject("terrainDict", runTime.system(), runTime, IOobject::MUST_READ, IOobject::NO_WRITE)
    );
    const granflow::terrainCase tc(dict, runTime.path(), granflow::keyword::get("terrainDict"));
    const gf_terrain_grid& g = tc.grid;
    Info<< "DEM " << tc.demFile << ": " << tc.dem.nx << " x " << tc.dem.ny << " cells of "
        << tc.dem.gt[1] << " m, " << tc.dem.n_valid << " valid" << nl
        << "Mesh: nodes every " << g.k << " DEM node(s), " << g.ni << " x " << g.nj
        << " node grid, " << g.n_quads << " faces of " << g.k*tc.dem.gt[1] << " m" << nl
        << "Offset (subtracted from the georeferenced coordinates) " << tc.offset << endl;
    if (tc.hasDam)
    {
        // the raised DEM beside the case, on the DEM's grid and georeferencing
        const fileName raised = runTime.path()/"constant"/"demWithDam.tif";
        granflow::terrainCase::check
        (
            dict, "dam", gf_raster_write(raised.c_str(), "GTiff", &tc.dem, tc.dem.z)
        );
        Info<< "Dam " << tc.damFile << ": crown line of " << label(tc.dam.n) << " points, wall slope "
            << tc.dam.slope << " deg; " << label(tc.damRaised) << " DEM cells raised, by at most "
            << tc.damRise << " m; the raised DEM (meshed) written to constant/demWithDam.tif"
            << endl;
    }

    // nodes used by a face: top points 0..n-1, bottom n..2n-1
    const label ni = g.ni, nj = g.nj, nqi = ni - 1;
    labelList id(ni*nj, -1);
    label nUsed = 0;
    auto quad = [&](label I, label J) { return g.quad[I + nqi*J] != 0; };
    for (label J = 0; J < nj - 1; ++J)
    {
        for (label I = 0; I < nqi; ++I)
        {
            if (!quad(I, J)) continue;
            for (label b = 0; b < 4; ++b)
            {
                label& n = id[(I + (b & 1)) + ni*(J + (b >> 1))];
                if (n < 0) n = nUsed++;
            }
        }
    }
    pointField pts(2*nUsed);
    scalar zMin = GREAT, zMax = -GREAT;
    for (label J = 0; J < nj; ++J)
    {
        for (label I = 0; I < ni; ++I)
        {
            const label n = id[I + ni*J];
            if (n < 0) continue;
            double p[3];
            gf_terrain_node(&tc.dem, &g, int(I), int(J), p);
            zMin = min(zMin, p[2]);
            zMax = max(zMax, p[2]);
            pts[n] = point(p[0], p[1], p[2]) - tc.offset;
            pts[n + nUsed] = pts[n] - vector(0, 0, tc.depth);
        }
    }

    // hexahedra: bottom SW SE NE NW, then top; rows J run southwards.  The
    // faces, owners and neighbours directly, in the order and with the
    // vertices that polyMesh's construction from hexahedral cell shapes gives
    // (the same files byte for byte, without its face matching): internal
    // faces cell by cell, each cell's to higher cells in increasing order of
    // the neighbour (east: the next cell, then south: the next row), as the
    // owner's hex face (east 1 2 6 5, south 0 1 5 4 of the cell's vertices
    // SW SE NE NW bottom, SW SE NE NW top); then the patches terrain (hex
    // face 4 5 6 7), base (0 3 2 1) and sides (west 0 4 7 3, east, south,
    // north 3 7 6 2 where no cell is beside), each cell by cell.
    auto inMesh = [&](label I, label J)
    {
        return I >= 0 && J >= 0 && I < nqi && J < nj - 1 && quad(I, J);
    };
    labelList cellOf(nqi*(nj - 1), -1);
    label nCells = 0, nInternalEdges = 0, nBoundaryEdges = 0;
    for (label J = 0; J < nj - 1; ++J)
    {
        for (label I = 0; I < nqi; ++I)
        {
            if (!quad(I, J)) continue;
            cellOf[I + nqi*J] = nCells++;
            // top edges shared by two top faces (= internal faces), and the
            // others (= side faces)
            const label nNgb = label(inMesh(I + 1, J)) + label(inMesh(I, J + 1));
            nInternalEdges += nNgb;
            nBoundaryEdges += 4 - nNgb - label(inMesh(I - 1, J)) - label(inMesh(I, J - 1));
        }
    }
    const label nInternal = nInternalEdges, nTop = nCells;
    faceList faces(nInternal + 2*nTop + nBoundaryEdges);
    labelList owner(faces.size()), neighbour(nInternal);
    label fi = 0, ft = nInternal, fb = nInternal + nTop, fs = nInternal + 2*nTop;
    for (label J = 0; J < nj - 1; ++J)
    {
        for (label I = 0; I < nqi; ++I)
        {
            const label c = cellOf[I + nqi*J];
            if (c < 0) continue;
            const label b = nUsed;
            const label sw = id[I + ni*(J + 1)], se = id[I + 1 + ni*(J + 1)];
            const label ne = id[I + 1 + ni*J], nw = id[I + ni*J];
            auto add = [&](label& f, std::initializer_list<label> v)
            {
                face& fc = faces[f];
                fc.setSize(4);
                label k = 0;
                for (const label p : v) fc[k++] = p;
                owner[f] = c;
                return f++;
            };
            if (inMesh(I + 1, J)) neighbour[add(fi, {se + b, ne + b, ne, se})] = cellOf[I + 1 + nqi*J];
            if (inMesh(I, J + 1)) neighbour[add(fi, {sw + b, se + b, se, sw})] = cellOf[I + nqi*(J + 1)];
            add(ft, {sw, se, ne, nw});                    // terrain, normal up
            add(fb, {sw + b, nw + b, ne + b, se + b});    // base, down
            // lateral faces without a neighbouring cell, normals outwards
            if (!inMesh(I - 1, J)) add(fs, {sw + b, sw, nw, nw + b});
            if (!inMesh(I + 1, J)) add(fs, {se + b, ne + b, ne, se});
            if (!inMesh(I, J + 1)) add(fs, {sw + b, se + b, se, sw});
            if (!inMesh(I, J - 1)) add(fs, {nw + b, nw, ne, ne + b});
        }
    }
    cellOf.clear();

    IOstream::defaultPrecision(max(IOstream::defaultPrecision(), 12u));
    const IOobject meshIO
    (
        polyMesh::defaultRegion, runTime.constant(), runTime, IOobject::NO_READ, IOobject::AUTO_WRITE
    );
    const wordList patchNames({"terrain", "base", "sides"});
    const labelList patchSizes({nTop, nTop, nBoundaryEdges});
    autoPtr<polyMesh> meshPtr;
    if (args.found("cellShapes"))
    {
        // the cells as hexahedra (bottom SW SE NE NW, then top) and the patch
        // faces: polyMesh finds the faces and orders them itself
        const cellModel& hex = cellModel::ref(cellModel::HEX);
        cellShapeList shapes(nCells);
        label c = 0;
        for (label J = 0; J < nj - 1; ++J)
        {
            for (label I = 0; I < nqi; ++I)
            {
                if (!quad(I, J)) continue;
                const label sw = id[I + ni*(J + 1)], se = id[I + 1 + ni*(J + 1)];
                const label ne = id[I + 1 + ni*J], nw = id[I + ni*J], b = nUsed;
                shapes[c++] = cellShape(hex, labelList({sw + b, se + b, ne + b, nw + b, sw, se, ne, nw}));
            }
        }
        faceListList patchFaces(3);
        label start = nInternal;
        forAll(patchFaces, i)
        {
            patchFaces[i] = SubList<face>(faces, patchSizes[i], start);
            start += patchSizes[i];
        }
        faces.clear();
        meshPtr.reset
        (
            new polyMesh
            (
                meshIO, std::move(pts), shapes, patchFaces, patchNames,
                wordList(3, "patch"), "defaultFaces", "patch", wordList()
            )
        );
    }
    else
    {
        meshPtr.reset
        (
            new polyMesh(meshIO, std::move(pts), std::move(faces), std::move(owner), std::move(neighbour))
        );
        List<polyPatch*> patches(3);
        label start = nInternal;
        forAll(patches, i)
        {
            patches[i] =
                polyPatch::New("patch", patchNames[i], patchSizes[i], start, i, meshPtr->boundaryMesh()).ptr();
            start += patchSizes[i];
        }
        meshPtr->addPatches(patches);
    }
    polyMesh& mesh = meshPtr();
    mesh.removeFiles();
    if (!mesh.write())
    {
        FatalErrorInFunction << "writing constant/polyMesh failed" << exit(FatalError);
    }
    // constant/faMesh as makeFaMesh writes it from faMeshDefinition
    const bool areaMesh =
        granflow::writeAreaMesh(runTime, mesh.boundaryMesh(), nInternalEdges, nBoundaryEdges);
    const label iTerrain = mesh.boundaryMesh().findPatchID("terrain");
    const scalar area = gSum(mag(vectorField(mesh.boundaryMesh()[iTerrain].faceAreas())));

    // constant/terrainProperties: the entries, the offset and the grid
    IOdictionary props
    (
        IOobject("terrainProperties", runTime.constant(), runTime, IOobject::NO_READ, IOobject::NO_WRITE)
    );
    props.add("dem", tc.demFile);
    props.add("coarsen", tc.coarsen);
    props.add("depth", tc.depth);
    if (tc.hasBox) props.add("cropBox", tc.box);
    if (!tc.cropFile.empty()) props.add("cropPolygons", tc.cropFile);
    if (tc.hasDam) props.add("dam", tc.damDict);
    props.add("offset", tc.offset);
    props.add("faces", label(g.n_quads));
    props.add("cellSize", g.k*tc.dem.gt[1]);
    props.add("terrainArea", area);
    props.add("elevationRange", Pair<scalar>(zMin, zMax));
    props.add("crs", string(tc.dem.wkt));
    props.regIOobject::writeObject(IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true);

    Info<< "Wrote constant/polyMesh (" << mesh.nCells() << " cells; patches terrain "
        << mesh.boundaryMesh()[iTerrain].size() << ", sides "
        << mesh.boundaryMesh()[mesh.boundaryMesh().findPatchID("sides")].size() << ", base "
        << g.n_quads << " faces)"
        << (areaMesh ? ", constant/faMesh (faceLabels, faBoundary: the area mesh of 'terrain')" : "")
        << " and constant/terrainProperties" << nl
        << "Terrain area " << area << " m2 (plan " << g.n_quads*sqr(g.k*tc.dem.gt[1])
        << " m2), elevations " << zMin << " .. " << zMax << " m" << nl << "End" << endl;
    return 0;
}
