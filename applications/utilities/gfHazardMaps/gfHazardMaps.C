/*---------------------------------------------------------------------------*\
    granflow — gfHazardMaps

Description
    Hazard maps of a run on a real terrain (a case meshed by gfTerrainMesh,
    run with controlDict peakFields yes): the peak fields of the latest (or
    the selected) time onto the DEM's own grid and georeferencing
    (constant/terrainProperties), in postProcessing/hazardMaps/:
        hPeak.asc/.tif         peak flow thickness [m]
        speedPeak.asc/.tif     peak speed [m/s]
        pressurePeak.asc/.tif  peak dynamic pressure rho speedPeak^2 [kPa]
        affectedArea.geojson   outline of hPeak >= threshold (area per polygon)
        hPeak.png, pressurePeak.png   hillshade of the DEM tinted by the peak field
        mass.csv               volume, net outflow and balance at every written time
        summary.dat            the numbers printed at the end
    A DEM pixel that is a mesh node takes the area-weighted mean of its
    faces, pixels between nodes (coarsened meshes) the bilinear value, pixels
    off the mesh (NODATA, cropped) NODATA.  ESRI ASCII grids carry the DEM's
    CRS in a .prj when the DEM had one.

Usage
    gfHazardMaps [-time T] [-threshold 0.1]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "OFstream.H"
#include "IFstream.H"
#include "timeSelector.H"

#include "terrainCase.H"
#include "granflow/source.h"

using namespace Foam;

int main(int argc, char *argv[])
{
    argList::addNote("Peak-field rasters, outline and maps on the DEM's grid (granflow)");
    argList::noParallel();
    argList::addOption("time", "time", "the time of the peak fields (default: the latest)");
    argList::addOption("threshold", "scalar", "hPeak of the affected-area outline [m] (0.1)");
    #include "setRootCase.H"
    #include "createTime.H"
    const instantList times = runTime.times();
    if (args.found("time"))
    {
        runTime.setTime(instant(args.get<scalar>("time")), 0);
    }
    else
    {
        runTime.setTime(times.last(), times.size() - 1);
    }
    #include "createMesh.H"
    #include "createFaMesh.H"

    const scalar threshold = args.getOrDefault<scalar>("threshold", 0.1);
    if (!(threshold > 0))
    {
        FatalErrorInFunction << "-threshold " << threshold << ": allowed > 0 [m]" << exit(FatalError);
    }
    const IOdictionary props
    (
        IOobject("terrainProperties", runTime.constant(), mesh, IOobject::MUST_READ, IOobject::NO_WRITE)
    );
    const granflow::terrainCase tc
    (
        props, runTime.path(),
        wordList({"faces", "cellSize", "terrainArea", "elevationRange", "crs"})
    );
    if (tc.nFaces() != aMesh.nFaces())
    {
        FatalErrorInFunction
            << "constant/terrainProperties describes " << tc.nFaces() << " faces but the area mesh has "
            << aMesh.nFaces() << ": mesh the case again with gfTerrainMesh and makeFaMesh"
            << exit(FatalError);
    }
    const IOdictionary granularProperties
    (
        IOobject("granularProperties", runTime.constant(), mesh, IOobject::MUST_READ, IOobject::NO_WRITE)
    );
    const scalar rho = granularProperties.get<scalar>("rho");

    auto readPeak = [&](const word& name)
    {
        IOobject io(name, runTime.timeName(), mesh, IOobject::MUST_READ);
        if (!io.typeHeaderOk<areaScalarField>(true))
        {
            FatalErrorInFunction
                << "No field " << name << " in time " << runTime.timeName()
                << ": run the solver with 'peakFields yes;' in system/controlDict" << exit(FatalError);
        }
        return areaScalarField(io, aMesh).primitiveField();
    };
    const scalarField hPeak(readPeak("hPeak")), speedPeak(readPeak("speedPeak"));

    const vectorField& C = aMesh.areaCentres().primitiveField();
    const scalarField& S = aMesh.S().field();
    const label n = C.size();
    std::vector<double> xy(2*n), area(S.begin(), S.end());
    forAll(C, f)
    {
        xy[2*f] = C[f].x() + tc.offset.x();
        xy[2*f + 1] = C[f].y() + tc.offset.y();
    }
    const size_t np = size_t(tc.dem.nx)*size_t(tc.dem.ny);
    const fileName outDir = runTime.globalPath()/"postProcessing"/"hazardMaps";
    mkDir(outDir);

    auto toRaster = [&](const scalarField& v, std::vector<double>& out)
    {
        out.resize(np);
        granflow::terrainCase::check
        (
            props, "faces",
            gf_terrain_to_raster(&tc.dem, &tc.grid, n, xy.data(), area.data(), v.cdata(), out.data())
        );
    };
    auto write = [&](const word& name, const std::vector<double>& r)
    {
        for (const char* drv : {"AAIGrid", "GTiff"})
        {
            const fileName file = outDir/name + (std::string(drv) == "AAIGrid" ? ".asc" : ".tif");
            granflow::terrainCase::check(props, "dem", gf_raster_write(file.c_str(), drv, &tc.dem, r.data()));
        }
    };
    scalarField pressure(n);
    forAll(pressure, f)
    {
        pressure[f] = 1e-3*gf_dynamic_pressure(rho, speedPeak[f]);   // kPa
    }
    std::vector<double> rh, ru, rp;
    toRaster(hPeak, rh);
    toRaster(speedPeak, ru);
    toRaster(pressure, rp);
    write("hPeak", rh);
    write("speedPeak", ru);
    write("pressurePeak", rp);

    double affected = 0;
    granflow::terrainCase::check
    (
        props, "dem",
        gf_raster_outline((outDir/"affectedArea.geojson").c_str(), &tc.dem, rh.data(), threshold, &affected)
    );
    const scalar hMax = gMax(hPeak), uMax = gMax(speedPeak), pMax = gMax(pressure);
    granflow::terrainCase::check
    (
        props, "dem", gf_raster_png((outDir/"hPeak.png").c_str(), &tc.dem, rh.data(), threshold, max(hMax, 2*threshold))
    );
    granflow::terrainCase::check
    (
        props, "dem", gf_raster_png((outDir/"pressurePeak.png").c_str(), &tc.dem, rp.data(), 1.0, max(pMax, 2.0))
    );

    // the reach of the affected faces: lowest elevation, horizontal extent
    scalar zLow = GREAT, zHigh = -GREAT;
    boundBox reach;
    label nAffected = 0;
    forAll(C, f)
    {
        if (hPeak[f] >= threshold)
        {
            zLow = min(zLow, C[f].z() + tc.offset.z());
            zHigh = max(zHigh, C[f].z() + tc.offset.z());
            reach.add(C[f] + tc.offset);
            ++nAffected;
        }
    }

    // the mass balance at every written time
    OFstream massCsv(outDir/"mass.csv");
    massCsv.precision(15);
    massCsv << "time,volume,netOutflow,imbalance" << nl;
    bool first = true;
    for (const instant& t : times)
    {
        IFstream is(runTime.path()/t.name()/"uniform"/"granflowMassBalance");
        if (!is.good()) continue;
        const dictionary mb(is);
        if (first && t.value() > times.first().value())
        {
            // the start: the initial volume of the run
            massCsv << times.first().value() << ',' << mb.get<scalar>("initialVolume") << ",0,0" << nl;
        }
        first = false;
        massCsv << t.value() << ',' << mb.get<scalar>("volume") << ',' << mb.get<scalar>("netOutflow")
                << ',' << mb.get<scalar>("imbalance") << nl;
    }

    OFstream summary(outDir/"summary.dat");
    summary.precision(8);
    const auto say = [&](const string& line) { Info<< line.c_str() << nl; summary << line.c_str() << nl; };
    say("time " + name(runTime.value()) + " s, DEM " + tc.demFile + " (" + name(tc.dem.nx) + " x "
        + name(tc.dem.ny) + " cells of " + name(tc.dem.gt[1]) + " m), mesh " + name(n) + " faces");
    say("max peak thickness " + name(hMax) + " m");
    say("max peak speed " + name(uMax) + " m/s");
    say("max peak pressure " + name(pMax) + " kPa (rho " + name(rho) + " kg/m3)");
    say("affected area (hPeak >= " + name(threshold) + " m) " + name(affected) + " m2 on the DEM grid, "
        + name(nAffected) + " faces");
    if (nAffected > 0)
    {
        say("affected reach: x " + name(reach.min().x()) + " .. " + name(reach.max().x()) + " m, y "
            + name(reach.min().y()) + " .. " + name(reach.max().y()) + " m, elevation "
            + name(zLow) + " .. " + name(zHigh) + " m");
    }
    say("wrote postProcessing/hazardMaps/{hPeak,speedPeak,pressurePeak}.{asc,tif}, affectedArea.geojson,"
        " hPeak.png, pressurePeak.png, mass.csv");
    Info<< "End" << endl;
    return 0;
}
