/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfFlowSummary

Description
    For every selected time: volume (mass/rho) sum(h S), max thickness, max
    speed, mass-weighted mean speed sum(h |Us| S)/sum(h S), the runout — the
    furthest point, projected on a direction, of the h = threshold level curve
    (default 0.01 m, the paper's),
    interpolated linearly between face centres across edges — and the max
    speed of the faces with h >= threshold (the deposit inside that curve),
    appended as a row to postProcessing/gfFlowSummary.dat.
    With -csv, also writes postProcessing/profiles/<time>.csv with every face:
    x,y,z,h,speed,Ux,Uy,Uz[,pb]; -csvTimes '(10 40)' writes those times'
    files only (the table has every selected time), -csvMinH H only the
    faces with h >= H.

Usage
    gfFlowSummary [-time ...] [-direction '(1 0 0)'] [-threshold 0.01] [-csv]
                  [-csvTimes '(T ...)'] [-csvMinH H]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "IFstream.H"
#include "timeSelector.H"
#include "OFstream.H"
#include "keyword.H"

int main(int argc, char *argv[])
{
    argList::addNote("Mass, max thickness, max speed and runout per time (granflow)");
    timeSelector::addOptions(true, false);
    argList::addOption("direction", "vector", "runout direction (default (1 0 0))");
    argList::addOption("threshold", "scalar", "thickness of the runout level curve (0.01 m)");
    argList::addBoolOption("csv", "write every face to postProcessing/profiles/<time>.csv");
    argList::addOption("csvTimes", "list", "-csv at these times only, e.g. '(10 40 80)' (default: every selected time)");
    argList::addOption("csvMinH", "scalar", "-csv: only the faces with h >= this [m] (default: every face)");
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

    vector dir = args.getOrDefault<vector>("direction", vector(1, 0, 0));
    if (mag(dir) < SMALL)
    {
        FatalErrorInFunction << "-direction must not be zero" << exit(FatalError);
    }
    dir /= mag(dir);
    const scalar threshold = args.getOrDefault<scalar>("threshold", 0.01);
    const bool csv = args.found("csv");
    const bool csvSome = args.found("csvTimes");
    const scalarList csvTimes(args.getOrDefault<scalarList>("csvTimes", scalarList()));
    const scalar csvMinH = args.getOrDefault<scalar>("csvMinH", -GREAT);
    // a listed time is a written one to the time name's precision
    auto near = [](const scalar t, const scalar listed) { return mag(t - listed) <= 1e-9*max(mag(listed), 1.0); };
    auto isCsvTime = [&](const scalar t)
    {
        for (const scalar c : csvTimes)
        {
            if (near(t, c)) return true;
        }
        return false;
    };
    if ((csvSome || args.found("csvMinH")) && !csv)
    {
        FatalErrorInFunction << "-csvTimes and -csvMinH go with -csv" << exit(FatalError);
    }
    if (csvSome)
    {
        // every listed time must be one of the selected times: a typo is an
        // error, not a missing file
        for (const scalar t : csvTimes)
        {
            bool found = false;
            for (const instant& i : timeDirs)
            {
                found = found || near(i.value(), t);
            }
            if (!found)
            {
                FatalErrorInFunction
                    << "-csvTimes: time " << t << " is not among the selected times "
                    << timeDirs << exit(FatalError);
            }
        }
    }

    const fileName outDir = runTime.globalPath()/"postProcessing";
    mkDir(outDir);
    OFstream table(outDir/"gfFlowSummary.dat");
    table.precision(12);
    table << "# time volume max_h max_speed mean_speed runout(h>=" << threshold
          << ") max_speed(h>=" << threshold << ") net_outflow mass_balance_rel" << nl;

    forAll(timeDirs, timei)
    {
        runTime.setTime(timeDirs[timei], timei);
        IOobject hHeader("h", runTime.timeName(), mesh, IOobject::MUST_READ);
        if (!hHeader.typeHeaderOk<areaScalarField>(true))
        {
            continue;
        }
        const areaScalarField h(hHeader, aMesh);
        const areaVectorField Us
        (
            IOobject("Us", runTime.timeName(), mesh, IOobject::MUST_READ), aMesh
        );
        IOobject pbHeader("pb", runTime.timeName(), mesh, IOobject::MUST_READ);
        autoPtr<areaScalarField> pb;
        if (pbHeader.typeHeaderOk<areaScalarField>(true))
        {
            pb.reset(new areaScalarField(pbHeader, aMesh));
        }
        const vectorField& C = aMesh.areaCentres().primitiveField();
        const scalarField speed(mag(Us.primitiveField()));
        // runout: the furthest point of the h = threshold level curve along
        // dir, interpolated linearly between the centres of a face above the
        // threshold and its edge neighbour below it (boundary faces above it
        // count with their centre)
        scalar runout = -GREAT;
        const labelUList& own = aMesh.edgeOwner();
        const labelUList& nei = aMesh.edgeNeighbour();
        forAll(nei, edgei)
        {
            const label a = own[edgei], b = nei[edgei];
            const scalar ha = h[a], hb = h[b];
            if ((ha >= threshold) != (hb >= threshold))
            {
                const scalar w = (threshold - ha)/(hb - ha);
                runout = max(runout, ((1 - w)*C[a] + w*C[b]) & dir);
            }
        }
        forAll(h.boundaryField(), patchi)
        {
            const labelUList& fc = aMesh.boundary()[patchi].edgeFaces();
            forAll(fc, i)
            {
                if (h[fc[i]] >= threshold)
                {
                    runout = max(runout, C[fc[i]] & dir);
                }
            }
        }
        reduce(runout, maxOp<scalar>());
        scalar maxSpeedThick = 0;
        forAll(h, i)
        {
            if (h[i] >= threshold)
            {
                maxSpeedThick = max(maxSpeedThick, speed[i]);
            }
        }
        reduce(maxSpeedThick, maxOp<scalar>());
        const scalar volume = gSum(h.primitiveField()*aMesh.S().field());
        // mass-weighted mean speed: |momentum| density averaged over the mass
        const scalar meanSpeed =
            gSum(h.primitiveField()*speed*aMesh.S().field())/max(volume, VSMALL);
        // the solver's mass balance of this time (faGranularFlowFoam writes
        // uniform/granflowMassBalance): net outflow so far and
        // (volume + outflow - inflow - initial)/initial; "-" where absent
        // (the initial time, other solvers)
        word netOut("-"), balance("-");
        {
            const fileName bf(runTime.timePath()/"uniform"/"granflowMassBalance");
            if (isFile(bf))
            {
                IFstream is(bf);
                const dictionary bd(is);
                const granflow::keyword::table& mt = granflow::keyword::get("granflowMassBalance");
                const scalar v0 = granflow::keyword::read<scalar>(bd, mt, "initialVolume");
                const scalar out = granflow::keyword::read<scalar>(bd, mt, "netOutflow");
                netOut = Foam::name(out);
                balance = Foam::name((volume + out - v0)/max(v0, VSMALL));
            }
        }
        table << runTime.timeName() << ' ' << volume << ' ' << gMax(h.primitiveField()) << ' '
              << gMax(speed) << ' ' << meanSpeed << ' ' << (runout > -GREAT ? runout : NAN) << ' '
              << maxSpeedThick << ' ' << netOut << ' ' << balance << nl;
        Info<< "Time " << runTime.timeName() << ": volume " << volume << " m3, max h "
            << gMax(h.primitiveField()) << " m, max speed " << gMax(speed) << " m/s, runout "
            << runout << " m" << endl;

        if (csv && (!csvSome || isCsvTime(runTime.value())))
        {
            mkDir(outDir/"profiles");
            OFstream os(outDir/"profiles"/(runTime.timeName() + ".csv"));
            os.precision(12);
            os << "x,y,z,h,speed,Ux,Uy,Uz" << (pb.valid() ? ",pb" : "") << nl;
            forAll(h, i)
            {
                if (h[i] < csvMinH)
                {
                    continue;
                }
                const vector& u = Us[i];
                os << C[i].x() << ',' << C[i].y() << ',' << C[i].z() << ',' << h[i] << ','
                   << speed[i] << ',' << u.x() << ',' << u.y() << ',' << u.z();
                if (pb.valid())
                {
                    os << ',' << pb()[i];
                }
                os << nl;
            }
        }
    }
    Info<< "End" << endl;
    return 0;
}
