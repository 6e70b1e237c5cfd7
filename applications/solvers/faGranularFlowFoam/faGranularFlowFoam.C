/*---------------------------------------------------------------------------*\
    granflow — faGranularFlowFoam

Description
    Shallow granular flow on a curved three-dimensional surface: the
    depth-integrated model of Rauter & Tuković (finite-area paper) with the
    velocity kept in 3D Cartesian components and the basal pressure found
    from the surface-normal projection of the momentum equation.

      pb = rho (-h g.n + xi n.div(h Us Us) + n.grad(K h pb)/(2 rho))   eq. 33/50, explicit
      ddt(h Us) + xi div(h Us Us) + nu Us
          = h g - grad(K h pb)/(2 rho) + n pb/rho                       eq. 31/51, implicit
      ddt(h) + div(h Us) = 0                                            eq. 30/52, implicit

    (n = faceAreaNormals, out of the terrain; the paper's n_b = -n.)  The
    three are solved in sequence and iterated to the initial-residual
    tolerances of faSolution/granularFlow with under-relaxation (section 3.6:
    the initial residual of the h equation; for Us the relative L1 change
    between outer iterations);
    implicit Euler on the first step, then the scheme of faSchemes (backward,
    eq. 46); time step from the Courant number (eqs. 47-48).  Dry faces
    (h < hMin) get Us = 0 on the matrix level, and so do faces that static
    friction holds when staticFriction is on (restFaces.H).  Friction (nu) and earth
    pressure (K) come from libgranflow.  Every patch is a wall, outflow,
    symmetry or inflow (hydrograph) boundary (granularBoundaries.H), and the
    mass balance (volume + outflow - inflow = initial) is printed at every
    written time; the smallest h before the thickness safety net, the steps
    where it acted and any time step capped by maxDeltaT are reported at the end.

Usage
    faGranularFlowFoam [-parallel]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "zeroGradientFaPatchFields.H"
#include "granularModel.H"
#include "faConvectionScheme.H"
#include "fullOperators.H"
#include "relaxConsistent.H"
#include "fixFacesAtRest.H"
#include "granularBoundaries.H"
#include "explicitSurfaceScheme.H"

#ifdef __GLIBC__
#include <malloc.h>
#endif

int main(int argc, char *argv[])
{
#ifdef __GLIBC__
    // Every outer iteration allocates and frees dozens of face and edge
    // fields.  With glibc's defaults, blocks above the (dynamic) mmap
    // threshold are mapped and unmapped each time and the heap top is
    // trimmed back to the kernel: a third of the run time went to page
    // faults and TLB flushes (perf, curved slope at 0.5 m).  Keep the memory.
    if (!mallopt(M_MMAP_THRESHOLD, 1 << 30))
    {
        mallopt(M_MMAP_THRESHOLD, 32 << 20);   // the cap of older glibc
    }
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_TOP_PAD, 64 << 20);
#endif
    argList::addNote
    (
        "Shallow granular flow on curved 3D surfaces (Rauter-Tukovic model)"
        " with libgranflow physics"
    );
    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"
    #include "createFaMesh.H"
    #include "createFields.H"

    // the initial volume of the run; a restart continues the balance of the run
    // it restarts (granularBoundaries.H)
    const scalar mass0 = boundaries.initialVolume(gSum(h.primitiveField()*aMesh.S().field()));
    Info<< "Initial mass (volume) " << mass0 << " m3" << nl << endl;
    cpuTime timer;
    scalar tPressure = 0, tMomentum = 0, tContinuity = 0;
    scalar tSolveUs = 0, tSolveH = 0;   // linear solvers, inside momentum/continuity
    label nIterTotal = 0;
    label nCappedSteps = 0;   // steps whose dt maxDeltaT capped below the maxCo step
    scalar hMinBeforeFix = GREAT;   // smallest h of the continuity solve, before the safety net
    label nNegativeSteps = 0;       // steps where the safety net set negative h to 0
    scalar negativeVolume = 0;      // volume it added [m3]
    label nEulerSteps = 0;          // continuity steps solved again with Euler upwind
    scalar hMinBdf2 = 0;            // smallest h of those before the re-solve
    label nSteps = 0;
    label nSlowSteps = 0;           // accepted with the iteration cap reached
    label nRetries = 0;             // steps repeated with half the time step

    if (explicitScheme)
    {
        #include "explicitLoop.H"
        return 0;
    }

    while (runTime.run())
    {
        #include "readControls.H"
        #include "CourantNo.H"
        #include "setDeltaT.H"
        ++runTime;
        ++nSteps;
        boundaries.setInflow(runTime.value(), h, Us);
        Info<< "Time = " << runTime.timeName() << "  deltaT = " << runTime.deltaTValue()
            << "  Courant " << CoNum << endl;

        scalar resUs = GREAT, resH = GREAT;
        label corr = 0;
        #include "outerIterations.H"
        {
            // final continuity solve without under-relaxation: the relaxed
            // equation is only satisfied at convergence, the unrelaxed one
            // conserves mass to the linear-solver tolerance every step
            const scalar t0 = timer.elapsedCpuTime();
            faScalarMatrix hEqn(fam::ddt(h) + fam::div(phis, h));
            hEqn.solve();
            phi2s = hEqn.flux();
            // Positivity by construction: backward (BDF2, its -h^{n-1}/(2 dt)
            // term) and higher-order convection can make h negative where the
            // flow thins or converges strongly.  Implicit Euler with upwind
            // convection cannot: its matrix has a positive diagonal, non-positive
            // off-diagonals and column sums S/dt > 0 (every outflow of a face is
            // an inflow coefficient of its neighbour), so it is an M-matrix with
            // a non-negative inverse.  A step whose solution goes below round-off
            // is solved again that way (counted and reported).
            bool eulerStep = false;
            if (gMin(h.primitiveField()) < -1e-12*max(gMax(h.primitiveField()), SMALL))
            {
                hMinBdf2 = min(hMinBdf2, gMin(h.primitiveField()));
                const scalarField& S = aMesh.S().field();
                const scalar rDeltaT = 1.0/runTime.deltaTValue();
                faScalarMatrix hE(upwindDiv(phis, h));
                hE.diag() += rDeltaT*S;
                hE.source() += rDeltaT*h.oldTime().primitiveField()*S;
                hE.solve();
                phi2s = hE.flux();
                eulerStep = true;
                ++nEulerSteps;
            }
            boundaries.accumulate(phi2s, runTime.deltaTValue(), runTime.deltaT0Value(), eulerStep);
            // What is left below zero is linear-solver round-off at dry edges
            // (~1e-20 m; at most the solver tolerance): a local net sets h to 0
            // in those faces only; the smallest h, the steps and the volume it
            // added (counted in the mass balance's volume) are reported.
            const scalar hNeg = -gMin(h.primitiveField());
            hMinBeforeFix = min(hMinBeforeFix, -hNeg);
            if (hNeg > 0)
            {
                ++nNegativeSteps;
                scalarField& hf = h.primitiveFieldRef();
                negativeVolume += -gSum(min(hf, scalar(0))*aMesh.S().field());
                hf = max(hf, scalar(0));
                h.correctBoundaryConditions();
            }
            tContinuity += timer.elapsedCpuTime() - t0;
        }
        nIterTotal += min(corr, nOuterCorr);

        runTime.write();
        if (runTime.writeTime())
        {
            const scalar mass = gSum(h.primitiveField()*aMesh.S().field());
            const scalar imbalance = mass + boundaries.netOut() - mass0;
            boundaries.write(runTime, mass);
            Info<< "granflow: t = " << runTime.timeName()
                << " s, wall " << runTime.elapsedClockTime() << " s, mass " << mass
                << " m3, mass balance: volume + outflow - inflow - initial = " << imbalance
                << " m3 (relative " << imbalance/max(max(mass0, mass), VSMALL)
                << ")" << nl;
            boundaries.report(Info);
            Info<< "    max h " << gMax(h.primitiveField())
                << " m, min h " << gMin(h.primitiveField())
                << " m, max |Us| " << gMax(mag(Us.primitiveField())) << " m/s";
            if (model.staticFriction())
            {
                Info<< ", held by static friction "
                    << returnReduce(nHeldLast, sumOp<label>()) << " faces";
            }
            Info<< endl;
        }
    }

    Info<< nl << "CPU seconds: pressure " << tPressure << ", momentum " << tMomentum
        << " (linear solver " << tSolveUs << "), continuity " << tContinuity
        << " (linear solver " << tSolveH << "); outer iterations " << nIterTotal
        << "; total " << runTime.elapsedCpuTime() << nl;
    Info<< "Outer iterations: " << scalar(nIterTotal)/max(nSteps, label(1)) << " per step; "
        << nSlowSteps << " of " << nSteps << " steps accepted at the"
        << " iteration cap (converging slowly, residuals below the rejection levels), "
        << nRetries << " steps repeated with half the time step" << nl;
    Info<< "Positivity: continuity re-solved with implicit Euler upwind in " << nEulerSteps
        << " of " << nSteps << " steps (smallest h of the rejected solutions " << hMinBdf2
        << " m)" << nl;
    Info<< "Thickness safety net: smallest h of the continuity solves " << hMinBeforeFix
        << " m; negative h set to 0 in " << nNegativeSteps << " of " << nSteps
        << " steps (locally), volume added " << negativeVolume << " m3" << nl;
    if (nCappedSteps > 0)
    {
        Info<< "Time step capped by maxDeltaT (controlDict; the Courant number stayed below"
            << " maxCo) in " << nCappedSteps << " of " << nSteps << " steps" << nl;
    }
    Info<< "End" << nl << endl;
    return 0;
}
