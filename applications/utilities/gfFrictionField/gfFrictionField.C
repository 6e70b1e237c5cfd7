/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfFrictionField

Description
    Evaluates the basal friction law of constant/granularProperties on the
    area mesh for the selected times and writes
        tauB  |tau_b| [Pa]   basal shear stress
        nuB   nu      [m/s]  implicit friction coefficient, tau_b/rho = nu Us
        pbB   p_b     [Pa]   basal pressure used (field pb if present, else
                             the lithostatic rho h max(0, -g.n))
    from the fields h and Us.  The formulas are libgranflow's.

Usage
    gfFrictionField [-time ...] [-latestTime]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "timeSelector.H"
#include "IFstream.H"
#include "uniformDimensionedFields.H"
#include "granularModel.H"
#include "keyword.H"

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Evaluate the basal friction law of constant/granularProperties"
        " (libgranflow) on the fields h and Us; write tauB, nuB and pbB"
    );
    timeSelector::addOptions(true, false);

    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    #include "createTime.H"
    instantList timeDirs = timeSelector::select0(runTime, args);
    #include "createMesh.H"
    #include "createFaMesh.H"

    IOdictionary granularProperties
    (
        IOobject
        (
            "granularProperties",
            runTime.constant(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    );
    // frictionLaw samosATAuto: the release volume that chooses the set, as
    // the solver takes it - the run's initial volume (uniform/granflowMassBalance
    // of the first selected time, written by the solver), else sum A h of
    // that time's h
    scalar releaseVolume = -1;
    const granflow::keyword::table& props = granflow::keyword::get("granularProperties");
    if
    (
        granflow::keyword::read<word>(granularProperties, props, "frictionLaw") == "samosATAuto"
     && timeDirs.size()
    )
    {
        const fileName mb(runTime.path()/timeDirs[0].name()/"uniform"/"granflowMassBalance");
        IOobject hio("h", timeDirs[0].name(), mesh, IOobject::MUST_READ);
        if (isFile(mb))
        {
            IFstream is(mb);
            const dictionary d(is);
            releaseVolume = granflow::keyword::read<scalar>
            (
                d, granflow::keyword::get("granflowMassBalance"), "initialVolume"
            );
        }
        else if (hio.typeHeaderOk<areaScalarField>(true))
        {
            releaseVolume = gSum(areaScalarField(hio, aMesh).primitiveField()*aMesh.S().field());
        }
        Info<< "samosATAuto: the release volume of time " << timeDirs[0].name() << " ("
            << (isFile(mb) ? "initialVolume of uniform/granflowMassBalance" : "sum A h of h") << ")" << endl;
    }
    // the same reading and checks of rho and the friction law as the solver
    const granflow::granularModel model(granularProperties, false, releaseVolume);
    const granflow::basalFriction& friction = model.friction();
    const scalar rho = model.rho();

    #include "readGravitationalAcceleration.H"
    Info<< "Friction law " << friction.describe().c_str() << ", rho = " << rho
        << ", g = " << g.value() << nl << endl;

    forAll(timeDirs, timei)
    {
        runTime.setTime(timeDirs[timei], timei);
        Info<< "Time = " << runTime.timeName() << endl;

        const areaScalarField h
        (
            IOobject("h", runTime.timeName(), mesh, IOobject::MUST_READ),
            aMesh
        );
        const areaVectorField Us
        (
            IOobject("Us", runTime.timeName(), mesh, IOobject::MUST_READ),
            aMesh
        );

        IOobject pbHeader("pb", runTime.timeName(), mesh, IOobject::MUST_READ);
        areaScalarField pb
        (
            IOobject("pbB", runTime.timeName(), mesh),
            aMesh,
            dimensionedScalar(dimPressure, Zero)
        );
        if (pbHeader.typeHeaderOk<areaScalarField>(true))
        {
            pb.primitiveFieldRef() = areaScalarField(pbHeader, aMesh).primitiveField();
        }
        else
        {
            const vectorField& n = aMesh.faceAreaNormals().primitiveField();
            pb.primitiveFieldRef() = rho*h.primitiveField()*max(-(g.value() & n), scalar(0));
        }

        areaScalarField tau
        (
            IOobject("tauB", runTime.timeName(), mesh),
            aMesh,
            dimensionedScalar(sqr(dimVelocity), Zero)
        );
        areaScalarField nu
        (
            IOobject("nuB", runTime.timeName(), mesh),
            aMesh,
            dimensionedScalar(dimVelocity, Zero)
        );
        friction.evaluate(h, Us, pb, rho, mag(g.value()), 0, tau, nu);
        tau *= dimensionedScalar("rho", dimDensity, rho);

        Info<< "    max |tau_b| = " << gMax(tau.primitiveField()) << " Pa, max nu = "
            << gMax(nu.primitiveField()) << " m/s" << nl << endl;
        tau.write();
        nu.write();
        pb.write();
    }

    Info<< "End" << nl << endl;
    return 0;
}
