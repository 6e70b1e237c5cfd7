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
        entrainedDepth.asc/.tif, detrainedDepth.asc/.tif
                               cumulative entrained / detrained flow thickness
                               [m] (when the time has hEntrained, hDetrained:
                               granularProperties massExchange)
        affectedArea.geojson   outline of hPeak >= threshold (area per polygon)
        comPath.geojson        the path of the centre of mass (3D line) over
                               every time step (the solver's centreOfMass.dat)
                               or else the written times, its horizontal
                               travel, drop and travel angle atan(drop/travel)
        hPeak.png, pressurePeak.png   hillshade of the DEM tinted by the peak field
        mass.csv               volume, net outflow, balance, entrained and
                               detrained volume at every written time
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
#include <fstream>
#include <sstream>
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
    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
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
    const granflow::terrainCase tc(props, runTime.path(), granflow::keyword::get("terrainProperties"));
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
    const scalar rho = granflow::keyword::read<scalar>
    (
        granularProperties, granflow::keyword::get("granularProperties"), "rho"
    );

    auto readPeak = [&](const word& name)
    {
        IOobject io(name, runTime.timeName(), mesh, IOobject::MUST_READ);
        if (!io.typeHeaderOk<areaScalarField>(true))
        {
            FatalErrorInFunction
                << "No field " << name << " in time " << runTime.timeName()
                << ": run the solver with 'peakFields yes;' in system/controlDict (and"
                << " reconstructPar a decomposed run first)" << exit(FatalError);
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

    // the mass exchange's depths (massExchange in granularProperties: the
    // solver writes hEntrained and hDetrained, cumulative flow thickness at
    // the flow density), when the time has them
    word exchangeRasters;
    scalar entrainedMax = -1, detrainedMax = -1;
    for (const word name : {"hEntrained", "hDetrained"})
    {
        IOobject io(name, runTime.timeName(), mesh, IOobject::MUST_READ);
        if (!io.typeHeaderOk<areaScalarField>(true)) continue;
        const scalarField v(areaScalarField(io, aMesh).primitiveField());
        std::vector<double> r;
        toRaster(v, r);
        const word rn(name == "hEntrained" ? "entrainedDepth" : "detrainedDepth");
        write(rn, r);
        (name == "hEntrained" ? entrainedMax : detrainedMax) = gMax(v);
        exchangeRasters += (exchangeRasters.empty() ? "" : ",") + rn;
    }

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
    const granflow::keyword::table& mt = granflow::keyword::get("granflowMassBalance");
    massCsv.precision(15);
    massCsv << "time,volume,netOutflow,imbalance,entrained,detrained" << nl;
    scalar initialVolume = -1, lastEntrained = 0, lastDetrained = 0, lastVolume = 0;
    bool first = true;
    for (const instant& t : times)
    {
        IFstream is(runTime.path()/t.name()/"uniform"/"granflowMassBalance");
        if (!is.good()) continue;
        const dictionary mb(is);
        if (first && t.value() > times.first().value())
        {
            // the start: the initial volume of the run
            massCsv << times.first().value() << ',' << granflow::keyword::read<scalar>(mb, mt, "initialVolume") << ",0,0,0,0" << nl;
        }
        first = false;
        initialVolume = granflow::keyword::read<scalar>(mb, mt, "initialVolume");
        lastVolume = granflow::keyword::read<scalar>(mb, mt, "volume");
        lastEntrained = granflow::keyword::read<scalar>(mb, mt, "entrained");
        lastDetrained = granflow::keyword::read<scalar>(mb, mt, "detrained");
        massCsv << t.value() << ',' << lastVolume << ','
                << granflow::keyword::read<scalar>(mb, mt, "netOutflow")
                << ',' << granflow::keyword::read<scalar>(mb, mt, "imbalance")
                << ',' << lastEntrained << ',' << lastDetrained << nl;
    }

    // the centre of mass at every time step (the solver's
    // postProcessing/centreOfMass/<start>/centreOfMass.dat, the files of a
    // restarted run joined), else at every written time: its path (GeoJSON),
    // the horizontal distance it travelled, its drop and the travel angle
    // atan(drop/distance) of the energy line of the centre of mass
    DynamicList<double> com;
    word comSource("written times");
    {
        const fileName comDir = runTime.globalPath()/"postProcessing"/"centreOfMass";
        instantList starts;
        for (const fileName& d : readDir(comDir, fileName::DIRECTORY))
        {
            scalar t0;
            if (readScalar(d, t0)) starts.append(instant(t0, d));
        }
        Foam::sort(starts);
        forAll(starts, k)
        {
            const scalar tNext = k + 1 < starts.size() ? starts[k + 1].value() : GREAT;
            std::ifstream is((comDir/starts[k].name()/"centreOfMass.dat").c_str());
            std::string line;
            while (std::getline(is, line))
            {
                if (line.empty() || line[0] == '#') continue;
                std::istringstream ls(line);
                double t, v, x, y, z;
                if (!(ls >> t >> v >> x >> y >> z))
                {
                    FatalErrorInFunction
                        << "Bad line '" << line.c_str() << "' in " << comDir/starts[k].name()
                        << "/centreOfMass.dat" << exit(FatalError);
                }
                if (t >= tNext) break;
                com.append(x + tc.offset.x());
                com.append(y + tc.offset.y());
                com.append(z + tc.offset.z());
            }
        }
        if (com.size() >= 6) comSource = "time steps";
    }
    for (const instant& t : times)
    {
        if (comSource == "time steps") break;
        IOobject hio("h", t.name(), mesh, IOobject::MUST_READ);
        if (!hio.typeHeaderOk<areaScalarField>(true)) continue;
        const areaScalarField ht(hio, aMesh);
        const scalar v = gSum(ht.primitiveField()*S);
        if (!(v > 0)) continue;
        const vector c = gSum(ht.primitiveField()*S*C)/v + tc.offset;
        com.append(c.x());
        com.append(c.y());
        com.append(c.z());
    }
    scalar travel = 0, drop = 0;
    const label nCom = com.size()/3;
    for (label i = 1; i < nCom; ++i)
    {
        travel += Foam::sqrt(sqr(com[3*i] - com[3*i - 3]) + sqr(com[3*i + 1] - com[3*i - 2]));
    }
    if (nCom >= 2)
    {
        drop = com[2] - com[3*nCom - 1];
        const scalar angle = radToDeg(Foam::atan2(drop, travel));
        const char* keys[3] = {"travel_m", "drop_m", "travel_angle_deg"};
        const double vals[3] = {travel, drop, angle};
        granflow::terrainCase::check
        (
            props, "dem",
            gf_line_geojson
            (
                (outDir/"comPath.geojson").c_str(), tc.dem.wkt, size_t(nCom), com.cdata(),
                "centre of mass", 3, keys, vals
            )
        );
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
    if (nCom >= 2)
    {
        say("centre of mass: " + name(travel) + " m travelled (horizontal, over " + name(nCom)
            + " " + comSource + "), " + name(drop) + " m drop, travel angle "
            + name(radToDeg(Foam::atan2(drop, travel))) + " deg");
    }
    if (!exchangeRasters.empty() && initialVolume > 0)
    {
        say("mass exchange: released " + name(rho*initialVolume) + " kg, entrained " + name(rho*lastEntrained)
            + " kg, detrained " + name(rho*lastDetrained) + " kg, flowing at the end " + name(rho*lastVolume) + " kg, growth index m_end/m_release "
            + name(lastVolume/initialVolume)
            + "; max entrained depth " + name(max(entrainedMax, scalar(0))) + " m, max detrained depth "
            + name(max(detrainedMax, scalar(0))) + " m");
    }
    say("wrote postProcessing/hazardMaps/{hPeak,speedPeak,pressurePeak"
        + (exchangeRasters.empty() ? string() : string("," + exchangeRasters))
        + "}.{asc,tif}, affectedArea.geojson, comPath.geojson, hPeak.png, pressurePeak.png, mass.csv");
    Info<< "End" << endl;
    return 0;
}
