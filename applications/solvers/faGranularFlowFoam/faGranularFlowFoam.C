/* SPDX-License-Identifier: GPL-3.0-or-later */
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

    (n = faceAreaNormals, out of the terrain; the paper's n_b = -n.)  Two
    schemes (faSolution granularFlow/scheme): explicit, the default and
    recommended one (libgranflow's surface kernels: second-order finite
    volume, SSP-RK2, pointwise implicit friction; explicitLoop.H), and
    implicit, the reference scheme of the paper (implicitLoop.H): the
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
    The last step lands on endTime as on a write time and is written even
    off the write grid (memberRuns.H, memberTime::setDeltaTToEnd), so that
    the hazard maps, reconstructPar and a restart find the final state.
    The explicit scheme can end a run before endTime once the flow has
    stopped (controlDict stopCriterion kineticEnergy: the total kinetic
    energy below stopFraction, 1 %, of its running peak, as AvaFrame ends its
    runs); the log reports the stop time and which end condition applied.
    With controlDict hazardMaps yes (and peakFields yes) a terrain run ends
    with its hazard maps, the files gfHazardMaps would write afterwards
    (hazardMaps.H, opened through hazardMapsWriter.H), without loading the
    meshes again; a parallel run skips them with a message.  With controlDict
    energyLine yes the run writes its mass-averaged path for the energy-line
    test (energyLine.H).  With controlDict setFields (releaseDict ...) a run
    that starts at t = 0 sets its release (and the mass exchange's inputs)
    itself, as gfSetRelease would (setFieldsAtStart.H).  The profile at the
    end of the log counts from the process's start (runProfile.H), and a
    serial run ends without its teardown once every file is closed
    (fastExit.H).

Usage
    faGranularFlowFoam [-parallel] [-keywords] [-version] [-members FILE]

    -keywords prints the keyword reference of every granflow dictionary
    (Markdown, doc/keywords.md) and -version the granflow version.
    -members FILE runs the case folders listed in FILE back to back on this
    case's meshes, loaded once (an ensemble worker of gfRunEnsemble;
    memberRuns.H); -members - reads them from standard input as they come
    and answers each with a line "member FOLDER: ok" (or FAILED: why) on
    standard output (gfCalibrate's workers).
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "zeroGradientFaPatchFields.H"
#include "granularModel.H"
#include "faConvectionScheme.H"
#include "fullOperators.H"
#include "implicitDeferred.H"
#include "relaxConsistent.H"
#include "fixFacesAtRest.H"
#include "granularBoundaries.H"
#include "explicitSurfaceScheme.H"
#include "massExchange.H"
#include "peakFields.H"
#include "cpuSections.H"
#include "runProfile.H"
#include "hazardMapsWriter.H"
#include "setFieldsAtStart.H"
#include "stopReport.H"

#include "keyword.H"
#include "keepFreedMemory.H"
#include "clipRoundOff.H"
#include "repeatStep.H"
#include "energyLine.H"
#include "memberRuns.H"
#include "createMeshes.H"
#include "releaseFreedMemory.H"
#include "fastExit.H"

int main(int argc, char *argv[])
{
    granflow::keepFreedMemory();   // the implicit scheme's many temporary fields (keepFreedMemory.H)
    granflow::runProfile setupProfile;  // where the wall time and memory go (runProfile.H)
    setupProfile.markProcessStart();    // the process before main: libraries loaded and initialised
    argList::addNote
    (
        "Shallow granular flow on curved 3D surfaces (Rauter-Tukovic model)"
        " with libgranflow physics"
    );
    granflow::keyword::addOptions();   // -keywords (the keyword reference), -version
    granflow::memberRuns::addOptions(); // -members FILE|- (memberRuns.H)
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    // createTime.H's Time, whose case can move to an ensemble member's (memberRuns.H)
    granflow::memberTime runTime(Foam::Time::controlDictName, args);
    setupProfile.mark("start and controls");
    // the volume mesh, only what the area mesh needs of it in a serial run,
    // and the area mesh (createMeshes.H)
    granflow::areaMeshes meshes(runTime, setupProfile);
    fvMesh& mesh = meshes.mesh();
    faMesh& aMesh = meshes.aMesh();
    // -members FILE: the listed cases run back to back on these meshes
    // (memberRuns.H, an ensemble worker); without it, one run of this case
    granflow::memberRuns members(args, runTime);
    while (members.next())
    {
        granflow::runProfile memberProfile;   // a member's own stages (worker)
        granflow::runProfile& profile = members.on() ? memberProfile : setupProfile;
        try
        {
            members.start(runTime);
            // the initial fields set by the solver itself (controlDict setFields:
            // as gfSetRelease would set them, into the start time; setFieldsAtStart.H)
            granflow::setFieldsAtStart(mesh, aMesh);
            profile.mark("set fields");
            #include "createFields.H"

            // the initial volume of the run; a restart continues the balance of the run
            // it restarts (granularBoundaries.H)
            const scalar mass0 = boundaries.initialVolume(gSum(h.primitiveField()*aMesh.S().field()));
            Info<< "Initial mass (volume) " << mass0 << " m3" << nl << endl;
            granflow::peakFields peaks(mesh, aMesh);   // controlDict peakFields yes (peakFields.H)
            peaks.update(h, Us);
            profile.mark("fields");
            // the hazard maps at the end (controlDict hazardMaps yes; hazardMapsWriter.H):
            // the terrain and its DEM read now, so that a bad case stops before the run
            const autoPtr<granflow::hazardMapsWriter> maps(granflow::hazardMapsAtEnd(mesh, aMesh, peaks.on()));
            if (maps.valid()) profile.mark("hazard maps set-up (terrain)");
            if (explicitScheme)
            {
                #include "explicitLoop.H"
            }
            else
            {
                // the end condition on the kinetic energy is the explicit scheme's
                // (explicitLoop.H): controlDict stopCriterion kineticEnergy is refused here
                granflow::keyword::read<word>
                (
                    runTime.controlDict(), granflow::keyword::get("controlDict"), "stopCriterion", "implicit"
                );
                // the mass exchange is the explicit scheme's (a per-step update of
                // its kernel): massExchange simType other than null is refused here
                granflow::readMassExchange(granularProperties, "implicit");
                #include "implicitFields.H"
                #include "implicitLoop.H"
                profile.mark("time loop");
            }
            if (maps.valid())
            {
                // after the last time and its mass balance are written (the last
                // step is written on the write grid or not: explicitLoop.H,
                // implicitLoop.H): the maps of the final state, the latest
                // written time, as gfHazardMaps makes them afterwards
                peaks.flush();
                instant last(runTime.value(), runTime.timeName());
                if (!isDir(runTime.timePath()))
                {
                    // only stopAt noWriteNow ends a run without writing its last step
                    last = runTime.times().last();
                    Info<< "hazardMaps: the run ended at t = " << runTime.timeName() << " s without"
                        << " writing it (stopAt noWriteNow); the maps are those of the latest written"
                        << " time " << last.name() << " s" << nl;
                }
                Info<< nl << "Hazard maps of time " << last.name() << " s:" << nl;
                maps->write(last);
                Info<< endl;
                profile.mark("hazard maps");
                // the path analysis of the maps (controlDict pathAnalysis), the files
                // gfPathAnalysis writes, in this process (pathAnalysisAtEnd.H)
                if (granflow::pathAnalysisAtEnd(runTime))
                {
                    profile.mark("path analysis");
                }
            }
            else if (Pstream::parRun() && granflow::keyword::read<bool>(runTime.controlDict(), granflow::keyword::get("controlDict"), "hazardMaps"))
            {
                Info<< "hazardMaps yes: skipped in this parallel run: reconstructPar, then gfHazardMaps" << nl;
            }
            if (members.on())
            {
                profile.report(Info);
                Info<< "End" << nl << endl;
            }
            members.done();
        }
        catch (const Foam::error& e)
        {
            if (!members.on()) throw;
            members.failed(e.message());
        }
        catch (const std::exception& e)
        {
            if (!members.on()) throw;
            members.failed(e.what());
        }
    }
    if (!members.on())
    {
        // the run's fields, scheme, peaks and maps were freed with its scope
        setupProfile.mark("end of the run (its fields freed)");
        setupProfile.report(Info);
        Info<< "End" << nl << endl;
    }
    // every file is written and closed: a serial process ends here, without
    // destroying the meshes, the Time and the libraries' static objects (fastExit.H)
    granflow::fastExit(runTime);
    return 0;
}
