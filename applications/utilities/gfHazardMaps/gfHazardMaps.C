/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfHazardMaps

Description
    Hazard maps of a run on a real terrain (a case meshed by gfTerrainMesh,
    run with controlDict peakFields yes): the peak fields of the latest (or
    the selected) time onto the DEM's own grid and georeferencing, in
    postProcessing/hazardMaps/ (hPeak, speedPeak, pressurePeak rasters,
    affectedArea.geojson, comPath.geojson, PNG maps, mass.csv, summary.dat;
    the list in applications/utilities/common/hazardMaps.H, the code both
    this program and faGranularFlowFoam's controlDict hazardMaps yes run).

Usage
    gfHazardMaps [-time T] [-threshold 0.1]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "timeSelector.H"

#include "hazardMaps.H"

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
    const granflow::hazardMaps maps(mesh, aMesh, threshold);
    maps.write(instant(runTime.value(), runTime.timeName()));
    Info<< "End" << endl;
    return 0;
}
