/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — libgranflowHazardMaps: the hazard maps (hazardMaps.H, the code
    of gfHazardMaps) for faGranularFlowFoam, which opens this library only
    when controlDict says hazardMaps yes (hazardMapsWriter.H), so that its
    other runs do not load GDAL.
\*---------------------------------------------------------------------------*/
#include "hazardMaps.H"

extern "C" Foam::granflow::hazardMapsWriter* granflowNewHazardMaps
(
    const Foam::fvMesh& mesh, const Foam::faMesh& aMesh, double threshold
)
{
    return new Foam::granflow::hazardMaps(mesh, aMesh, threshold);
}
