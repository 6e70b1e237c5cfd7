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
    gfTerrainMesh [-keywords] [-version]
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

    // hexahedra: bottom SW SE NE NW, then top; rows J run southwards
    const cellModel& hex = cellModel::ref(cellModel::HEX);
    cellShapeList shapes(g.n_quads);
    faceListList patchFaces(3);
    faceList& top = patchFaces[0];
    faceList& base = patchFaces[1];
    DynamicList<face> sides;
    top.setSize(g.n_quads);
    base.setSize(g.n_quads);
    auto inMesh = [&](label I, label J)
    {
        return I >= 0 && J >= 0 && I < nqi && J < nj - 1 && quad(I, J);
    };
    label c = 0, nInternalEdges = 0;   // top edges shared by two top faces
    for (label J = 0; J < nj - 1; ++J)
    {
        for (label I = 0; I < nqi; ++I)
        {
            if (!quad(I, J)) continue;
            const label sw = id[I + ni*(J + 1)], se = id[I + 1 + ni*(J + 1)];
            const label ne = id[I + 1 + ni*J], nw = id[I + ni*J];
            labelList v({sw + nUsed, se + nUsed, ne + nUsed, nw + nUsed, sw, se, ne, nw});
            shapes[c] = cellShape(hex, v);
            top[c] = face(labelList({sw, se, ne, nw}));                    // normal up
            base[c] = face(labelList({sw + nUsed, nw + nUsed, ne + nUsed, se + nUsed})); // down
            // lateral faces without a neighbouring cell, normals outwards
            const label b = nUsed;
            if (!inMesh(I - 1, J)) sides.append(face(labelList({sw + b, sw, nw, nw + b})));
            if (!inMesh(I + 1, J)) sides.append(face(labelList({se + b, ne + b, ne, se})));
            if (!inMesh(I, J + 1)) sides.append(face(labelList({sw + b, se + b, se, sw})));
            if (!inMesh(I, J - 1)) sides.append(face(labelList({nw + b, nw, ne, ne + b})));
            nInternalEdges += label(inMesh(I + 1, J)) + label(inMesh(I, J + 1));
            ++c;
        }
    }
    const label nBoundaryEdges = sides.size();   // a side face per boundary edge of the top
    patchFaces[2].transfer(sides);

    IOstream::defaultPrecision(max(IOstream::defaultPrecision(), 12u));
    polyMesh mesh
    (
        IOobject(polyMesh::defaultRegion, runTime.constant(), runTime, IOobject::NO_READ,
                 IOobject::AUTO_WRITE),
        std::move(pts), shapes, patchFaces, wordList({"terrain", "base", "sides"}),
        wordList({"patch", "patch", "patch"}), "defaultFaces", "patch", wordList()
    );
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
