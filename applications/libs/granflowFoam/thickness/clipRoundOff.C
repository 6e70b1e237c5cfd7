/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "clipRoundOff.H"

Foam::scalar Foam::granflow::clipRoundOff(areaScalarField& h, scalar& volumeAdded)
{
    const scalar hMin = gMin(h.primitiveField());
    volumeAdded = 0;
    if (hMin < 0)
    {
        scalarField& hf = h.primitiveFieldRef();
        volumeAdded = -gSum(min(hf, scalar(0))*h.mesh().S().field());
        hf = max(hf, scalar(0));
        h.correctBoundaryConditions();
    }
    return hMin;
}
