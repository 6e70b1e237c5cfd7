/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — libgranflowHazardMaps: the hazard maps (hazardMaps.H, the code
    of gfHazardMaps) and the release (release.H, the code of gfSetRelease)
    for faGranularFlowFoam, which opens this library only when controlDict
    says hazardMaps yes (hazardMapsWriter.H) or lists setFields
    (setFieldsAtStart.H), so that its other runs do not load GDAL.
\*---------------------------------------------------------------------------*/
#include "hazardMaps.H"

extern "C" Foam::granflow::hazardMapsWriter* granflowNewHazardMaps
(
    const Foam::fvMesh& mesh, const Foam::faMesh& aMesh, double threshold
)
{
    return new Foam::granflow::hazardMaps(mesh, aMesh, threshold);
}

#include "release.H"

// The fields of system/<dictName> (the release, or the mass exchange's
// inputs) set and written into the start time folder, as gfSetRelease
// [-dict dictName] sets them (release.H): faGranularFlowFoam's controlDict
// setFields (setFieldsAtStart.H)
extern "C" void granflowSetFields(const Foam::fvMesh& mesh, const Foam::faMesh& aMesh, const char* dictName)
{
    Foam::granflow::release r(mesh, aMesh, Foam::word(dictName));
    const Foam::scalarField v(r.compute(false, 0));
    r.set(v);
    r.write(v);
}
