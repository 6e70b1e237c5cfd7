/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — the keyword tables of the finite-area programs (keyword.H).

    One table per dictionary; a row: key, type, default, allowed, unit,
    applies to, description.  The programs read every entry through these
    rows, and doc/keywords.md is printed from them (doc/make-keywords), so
    a key, default or range changes here and nowhere else.  The friction
    laws' coefficient tables are made from libgranflow's own table of laws
    (granflow/friction.h), the single source of their ranges and units.
    Papers: FA = finite-area-granular-3d-surfaces.md, SH = the 1D
    Savage-Hutter papers.
\*---------------------------------------------------------------------------*/
#include "keyword.H"

#include "granflow/friction.h"
#include "granflow/mass_exchange.h"

#include <cmath>
#include <sstream>

namespace
{

using Foam::granflow::keyword::row;
using Foam::granflow::keyword::table;

std::string num(double v)
{
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream os;
    os << v;
    return os.str();
}

// the laws with coefficients: "<law>Coeffs" rows and one table each
std::vector<table> frictionTables()
{
    std::vector<table> out;
    for (const gf_friction_type* const* t = gf_friction_types(); *t; ++t)
    {
        const gf_friction_type& law = **t;
        if (law.n_params == 0) continue;
        table tb
        {
            std::string("granularProperties/") + law.name + "Coeffs",
            "constant/granularProperties", std::string(law.name) + "Coeffs/",
            "faGranularFlowFoam, gfFrictionField",
            std::string("Coefficients of frictionLaw ") + law.name + ": " + law.description
          + ". Every coefficient is required (the documented value is libgranflow's"
            " reference value, given in the message when one is missing); the ranges are"
            " libgranflow's (granflow/friction.h).",
            true, "", {}
        };
        for (size_t i = 0; i < law.n_params; ++i)
        {
            const gf_friction_param& p = law.params[i];
            tb.rows.push_back
            ({
                p.name, "scalar", "required (" + num(p.default_value) + ")",
                "[" + num(p.min) + ", " + num(p.max) + "]", p.unit, law.name, p.description
            });
        }
        out.push_back(tb);
    }
    return out;
}

// the laws, and samosATAuto after samosAT (AvaFrame's choice of the samosAT
// set by release volume, gf_samosat_auto; basalFriction.C)
std::string frictionChoices()
{
    std::string s;
    for (const gf_friction_type* const* t = gf_friction_types(); *t; ++t)
    {
        s += (s.empty() ? "" : " | ") + std::string((*t)->name);
        if (*t == gf_friction_samosat)
        {
            s += " | samosATAuto";
        }
    }
    return s;
}

std::vector<row> terrainRows()
{
    return
    {
        {"dem", "fileName", "required", "", "", "",
         "digital elevation model, any raster GDAL reads (ESRI ASCII, GeoTIFF); relative to the case"},
        {"coarsen", "label", "1", ">= 1", "", "",
         "mesh nodes at every k-th DEM node"},
        {"depth", "scalar", "10", "> 0", "m", "",
         "thickness of the slab below the terrain"},
        {"cropBox", "list", "-", "", "m", "",
         "(xmin ymin xmax ymax): crop to a box, georeferenced coordinates"},
        {"cropPolygons", "fileName", "-", "", "", "",
         "crop to the faces whose centres lie inside these polygons (OGR: shapefile, GeoJSON)"},
        {"offset", "vector", "-", "", "m", "",
         "subtracted from the georeferenced coordinates; default the south-west corner of the"
         " mesh nodes and their lowest elevation, rounded down to metres"},
        {"dam", "dictionary", "-", "", "", "",
         "a dam burned into the DEM before meshing (doc/theory/mass-exchange.md, section 3):"
         " entries file, slope; gfTerrainMesh writes the raised DEM to constant/demWithDam.tif"},
    };
}

//- The dam sub-dictionary of terrainDict / terrainProperties
table damTable(const std::string& parent, const std::string& file, const std::string& program)
{
    return
    {
        parent + "/dam", file, "dam/", program,
        "A dam (doc/theory/mass-exchange.md, section 3): the DEM becomes the larger of the"
        " ground and the dam surface z_c - tan(slope) d, z_c the crown elevation at the nearest"
        " point of the crown line and d the horizontal distance to it.",
        true, "",
        {
            {"file", "fileName", "required", "", "", "",
             "the crown line: one 3D line (OGR: shapefile, GeoJSON; AvaFrame Inputs/DAM/*.shp),"
             " z the crown's elevation above sea level at each point; relative to the case"},
            {"slope", "scalar", "-", "(0, 90)", "deg", "",
             "wall slope from the horizontal; default the line's attribute slope (AvaFrame's)"},
        }
    };
}

// The mass exchange (granflow/mass_exchange.h, spec mass-exchange.md):
// the defaults are libgranflow's gf_mass_exchange_config_default, the
// single source of them; the ranges are those gf_mass_exchange_config_check
// applies
table massExchangeTable()
{
    gf_mass_exchange_config d;
    gf_mass_exchange_config_default(&d);
    const std::string onoff = d.detrainment ? "on" : "off";
    return
    {
        "granularProperties/massExchange", "constant/granularProperties", "massExchange/",
        "faGranularFlowFoam",
        "Mass exchange with the bed and obstacles (doc/theory/mass-exchange.md, after AvaFrame"
        " com1DFA): entrainment where the layer 0/hEnt > 0, detrainment or increased friction where"
        " 0/resistance > 0 (both set from polygons by gfSetRelease -dict). Defaults: libgranflow's"
        " (granflow/mass_exchange.h). The explicit scheme only.",
        true, "scheme",
        {
            {"simType", "word", "null", "null | ent | res | entres", "", "explicit",
             "AvaFrame's switch: null (no exchange, costs nothing), ent (entrainment, needs 0/hEnt),"
             " res (resistance areas, needs 0/resistance), entres (both)"},
            {"simType", "word", "null", "null", "", "implicit",
             "the implicit scheme has no mass exchange (it is a pointwise per-step update of the"
             " explicit scheme's kernel): use scheme explicit"},
            {"rhoEnt", "scalar", num(d.rho_ent), "> 0", "kg/m3", "",
             "density of the entrainable snow (spec 1: q_ent = rhoEnt hEnt)"},
            {"entTh", "scalar", num(d.h_ent), ">= 0", "m", "",
             "entrainable thickness the set-up uses where an area gives none (gfSetRelease polygons"
             " value); the solver takes the field 0/hEnt"},
            {"entEroEnergy", "scalar", num(d.e_b), ">= 0", "J/kg", "",
             "specific erosion energy e_b: erosion rate tau_b |u|/e_b (spec 1); 0 selects ploughing"},
            {"entShearResistance", "scalar", num(d.e_s), ">= 0", "J/m2", "",
             "breaking energy per fracture area e_s (spec 1)"},
            {"entDefResistance", "scalar", num(d.e_d), ">= 0", "J/kg", "",
             "deformation energy per entrained mass e_d (spec 1)"},
            {"detrainment", "switch", onoff, "", "", "",
             "detrainment below the speed/thickness windows (spec 2); off: the increased friction"
             " acts everywhere in a resistance area"},
            {"detK", "scalar", num(d.K), ">= 0", "Pa", "",
             "detrainment coefficient K: rate K/|u| per area (spec 2; Feistl et al. 2014)"},
            {"cRes", "scalar", num(d.c_res), ">= 0", "", "",
             "increased-friction coefficient c_res, times the face's 0/resistance factor (spec 2)"},
            {"forestVMin", "scalar", num(d.v_min), ">= 0", "m/s", "",
             "below this speed: detrainment (spec 2 v_min; <= forestVMax)"},
            {"forestVMax", "scalar", num(d.v_max), ">= 0", "m/s", "",
             "above this speed: nothing, the obstacles are overrun (spec 2 v_max)"},
            {"forestThMin", "scalar", num(d.h_min), ">= 0", "m", "",
             "below this thickness: detrainment (spec 2 h_min; <= forestThMax)"},
            {"forestThMax", "scalar", num(d.h_max), ">= 0", "m", "",
             "above this thickness: nothing (spec 2 h_max)"},
        }
    };
}

std::vector<table> makeTables()
{
    std::vector<table> T;

    // ---- constant/granularProperties ----------------------------------------
    {
        table t
        {
            "granularProperties", "constant/granularProperties", "",
            "faGranularFlowFoam, gfFrictionField (rho: gfHazardMaps)",
            "The granular material, the model's terms and the boundary conditions.",
            true, "", {}
        };
        t.rows =
        {
            {"rho", "scalar", "required", "[1e-6, 1e6]", "kg/m3", "",
             "flow (bulk) density: basal pressure pb = rho (...) (FA eq. 33) and mu(I)'s inertial number"},
            {"xi", "scalar", "1", "[1e-6, 2]", "", "",
             "shape factor of the convection term xi div(h Us Us) (FA eq. 31); the explicit scheme needs 1"},
            {"hMin", "scalar", "1e-6", "(0, 1]", "m", "",
             "dry threshold: faces thinner than hMin are dry (Us = 0; friction and pressure divide by h)"},
            {"earthPressure", "word", "isotropic", "isotropic | savageHutter", "", "",
             "earth-pressure coefficient K: 1, or Savage-Hutter's K_act/K_pass from phi and delta"
             " (SH eq. 4); the explicit scheme needs isotropic"},
            {"savageHutterCoeffs", "dictionary", "-", "", "", "savageHutter",
             "phi and delta of earthPressure savageHutter (table below)"},
            {"frictionLaw", "word", "required", frictionChoices(), "", "",
             "basal friction law, evaluated by libgranflow (granflow/friction.h; FA eq. 31's nu);"
             " samosATAuto: the samosAT set AvaFrame's com1DFA takes for the release volume V = sum A h"
             " of the initial h (the volume on the terrain): samosATSmall (mu 0.22) below "
           + num(GF_SAMOSAT_VOL_SMALL) + " m3, samosATMedium (mu 0.17) below " + num(GF_SAMOSAT_VOL_MEDIUM)
           + " m3, else samosAT (mu 0.155); u0 0 (explicit) or 1e-4 m/s (implicit); no samosATCoeffs;"
             " refused with an inflow patch or without a release (doc/guide/friction.md)"},
        };
        for (const gf_friction_type* const* l = gf_friction_types(); *l; ++l)
        {
            if ((*l)->n_params == 0) continue;
            t.rows.push_back
            ({
                std::string((*l)->name) + "Coeffs", "dictionary", "-", "", "", (*l)->name,
                std::string("coefficients of frictionLaw ") + (*l)->name
              + " (table below); those of other laws may be kept"
            });
        }
        const std::vector<row> more
        {
            {"lateralPressure", "switch", "on", "", "", "",
             "the lateral pressure gradient -(K/2 rho) grad(h pb) in the momentum equation (FA eq. 31)"},
            {"centrifugalPressure", "switch", "on", "", "", "",
             "the curvature term xi n.div(h Us Us) in the basal pressure (FA eq. 33)"},
            {"lateralPressureFeedback", "switch", "on", "", "", "",
             "the term n.grad(K h pb)/(2 rho) in the basal pressure (FA eq. 33)"},
            {"staticFriction", "switch", "off", "", "", "implicit",
             "hold faces at rest where the driving force is below the static friction bound"
             " (off: FA eq. 51, a deposit creeps at about u0); the explicit scheme needs off"},
            {"boundaries", "dictionary", "required", "", "", "",
             "one sub-dictionary per area-mesh patch, boundaries/<patch> (table below)"},
            {"massExchange", "dictionary", "-", "", "", "",
             "entrainment, detrainment and resistance areas (AvaFrame's simType; table below);"
             " absent: simType null"},
        };
        t.rows.insert(t.rows.end(), more.begin(), more.end());
        T.push_back(t);
    }
    T.push_back
    ({
        "granularProperties/savageHutterCoeffs", "constant/granularProperties", "savageHutterCoeffs/",
        "faGranularFlowFoam, gfFrictionField",
        "Internal friction and bed friction angles of earthPressure savageHutter (delta <= phi).",
        true, "",
        {
            {"phi", "scalar", "required", "(0, 90)", "deg", "savageHutter", "internal friction angle"},
            {"delta", "scalar", "required", "[0, 90)", "deg", "savageHutter",
             "bed friction angle, at most phi"},
        }
    });
    for (const table& f : frictionTables())
    {
        T.push_back(f);
    }
    T.push_back(massExchangeTable());
    T.push_back
    ({
        "granularProperties/boundaries/<patch>", "constant/granularProperties", "boundaries/<patch>/",
        "faGranularFlowFoam",
        "The boundary condition of one area-mesh patch (every non-coupled patch is listed; 0/h and"
        " 0/Us must carry the matching patch types: wall zeroGradient/slip, outflow"
        " zeroGradient/zeroGradient, symmetry symmetry/symmetry, inflow fixedValue/fixedValue).",
        true, "type",
        {
            {"type", "word", "required", "wall | outflow | symmetry | inflow", "", "",
             "wall: no normal flux; outflow: material leaves, nothing enters; symmetry: a symmetry"
             " plane; inflow: a hydrograph"},
            {"h", "Function1<scalar>", "required", ">= 0", "m", "inflow",
             "thickness of the inflow as a function of time (table, constant, ...)"},
            {"Us", "Function1<vector>", "required", "", "m/s", "inflow",
             "velocity of the inflow as a function of time, made tangential to the surface"},
        }
    });

    // ---- system/faSolution ----------------------------------------------------
    T.push_back
    ({
        "faSolution", "system/faSolution", "", "faGranularFlowFoam",
        "The finite-area solution controls: granflow's sub-dictionaries.",
        false, "scheme",
        {
            {"granularFlow", "dictionary", "required", "", "", "",
             "the scheme and its controls (table below)"},
            {"relaxationFactors", "dictionary", "-", "", "", "implicit",
             "OpenFOAM's; granflow reads equations/Us and equations/h (table below)"},
        }
    });
    T.push_back
    ({
        "faSolution/granularFlow", "system/faSolution", "granularFlow/", "faGranularFlowFoam",
        "The scheme and its controls. The implicit scheme's entries marked preset come from the"
        " control set `controls` unless given; the log names which came from where.",
        true, "scheme",
        {
            {"scheme", "word", "explicit", "implicit | explicit", "", "",
             "explicit (recommended): second-order finite volume, SSP-RK2, pointwise implicit"
             " friction; implicit: the reference scheme, the finite-area paper's iterated"
             " sequence (FA section 3.6)"},
            {"order", "label", "2", "1 | 2", "", "explicit",
             "order of the reconstruction"},
            {"startupLevels", "label", "0", "[0, 3]", "", "explicit",
             "start-up refinement: the first phase of the release on meshes refined 1..startupLevels"
             " times (0 off; only from t = 0)"},
            {"controls", "word", "fast", "paper | fast", "", "implicit",
             "control set: paper = FA Table 1 (50 outer iterations, residuals 1e-6, relaxation"
             " 0.5), fast = 8 iterations, residuals 1e-4, relaxation 0.8"},
            {"nOuterCorrectors", "label", "preset: paper 50, fast 8", ">= 1", "", "implicit",
             "outer (Picard) iterations per time step (FA Table 1 n_max); past it only while the residuals fall (maxOuterCorrectors)"},
            {"residualUs", "scalar", "preset: paper 1e-6, fast 1e-4", "> 0", "", "implicit",
             "convergence: L1 change of Us between outer iterations relative to the mean speed (at least residualUsScale) (FA Table 1 r_u,max)"},
            {"residualH", "scalar", "preset: paper 1e-6, fast 1e-4", "> 0", "", "implicit",
             "convergence: initial residual of the h equation (FA Table 1 r_h,max, section 3.6)"},
            {"residualUsScale", "scalar", "1e-2", "> 0", "m/s", "implicit",
             "the Us residual is the L1 change relative to the wet faces' mean speed, or to this"
             " speed where they are slower (a deposit at rest has no speed to be relative to)"},
            {"maxOuterCorrectors", "label", "4 x nOuterCorrectors", ">= 1", "",
             "implicit",
             "past nOuterCorrectors the iterations go on while the residuals keep falling, up to"
             " this many (>= nOuterCorrectors); then the step is repeated with half the time step"},
            {"rejectResidualUs", "scalar", "residualUs", "> 0", "", "implicit",
             "(>= residualUs) a step whose Us residual stays above residualUs but below this is accepted (counted"
             " and warned in the summary); by default equal to residualUs: no step is accepted"
             " above the target"},
            {"rejectResidualH", "scalar", "residualH", "> 0", "", "implicit",
             "likewise for the h residual (>= residualH)"},
            {"maxRetries", "label", "6", ">= 0", "", "implicit",
             "most halvings of a step that does not converge before the run stops"},
        }
    });
    T.push_back
    ({
        "faSolution/relaxationFactors", "system/faSolution", "relaxationFactors/equations/",
        "faGranularFlowFoam",
        "Under-relaxation of the implicit scheme's outer iterations (OpenFOAM's lookup: a regular"
        " expression matches too); from the control set when not given.",
        false, "scheme",
        {
            {"Us", "scalar", "preset: paper 0.5, fast 0.8", "(0, 1]", "", "implicit",
             "momentum equation (FA Table 1: 0.5); 1 = none"},
            {"h", "scalar", "preset: paper 0.5, fast 0.8", "(0, 1]", "", "implicit",
             "continuity equation (FA Table 1: 0.5); 1 = none"},
        }
    });

    // ---- system/controlDict ---------------------------------------------------
    T.push_back
    ({
        "controlDict", "system/controlDict", "", "faGranularFlowFoam",
        "The solver's time-step and output entries.",
        false, "scheme",
        {
            {"adjustTimeStep", "switch", "yes", "", "", "",
             "adapt the time step to maxCo (FA eqs. 47-48); off: deltaT is kept (the explicit"
             " scheme stops if it exceeds the stable step)"},
            {"maxCo", "scalar", "1", "> 0", "", "implicit",
             "Courant number of the time step (FA Table 1 C_max, eqs. 47-48)"},
            {"maxCo", "scalar", "0.5", "(0, 0.5]", "", "explicit",
             "Courant number of the time step; 0.5 is the positivity bound of the fluxes,"
             " Co = dt sum_e |Le| s_e/(2 S)"},
            {"maxDeltaT", "scalar", "1e15", "> 0", "s", "",
             "largest time step (the default does not cap)"},
            {"deltaT", "scalar", "required", "> 0", "s", "",
             "initial time step (read by OpenFOAM, checked by the solver)"},
            {"peakFields", "switch", "no", "", "", "",
             "write hPeak and speedPeak with every time and the centre of mass"
             " (postProcessing/centreOfMass) for gfHazardMaps; and tArrival, the time each face"
             " first reached arrivalThickness (-1: never), for the arrival-time raster"},
            {"arrivalThickness", "scalar", "0.01", "> 0", "m", "",
             "peakFields: the thickness whose first reaching is a face's arrival time (tArrival, the"
             " hazard maps' arrivalTime raster; gfCalibrate's front observations)"},
            {"hazardMaps", "switch", "no", "", "", "",
             "write the hazard maps (postProcessing/hazardMaps: the rasters, outline, maps, mass.csv and"
             " summary.dat of gfHazardMaps, the same files) at the end of the run, after its last time is"
             " written, with the meshes already loaded; needs peakFields yes and a terrain case"
             " (constant/terrainProperties); a parallel run skips them with a message (reconstructPar,"
             " then gfHazardMaps)"},
            {"hazardMapsThreshold", "scalar", "0.1", "> 0", "m", "",
             "hazardMaps: hPeak of the affected-area outline and area (gfHazardMaps -threshold)"},
            {"pathAnalysis", "dictionary", "-", "", "", "",
             "the path analysis of the hazard maps right after them, in the same process (the files"
             " gfPathAnalysis would write afterwards, byte for byte; controlDict/pathAnalysis); needs"
             " hazardMaps yes; a failure ends the run with an error (the maps are written)"},
            {"stopCriterion", "word", "none", "none | kineticEnergy", "", "explicit",
             "end condition besides endTime (the cap): kineticEnergy ends the run, writing that time,"
             " once the total kinetic energy 1/2 rho sum A h |Us|^2 falls below stopFraction of its"
             " running peak (AvaFrame's end of a run), or after the first step if nothing moves and"
             " no inflow patch can bring material; the log reports the stop time"},
            {"stopCriterion", "word", "none", "none", "", "implicit",
             "the implicit scheme has no stop criterion (it runs to endTime): use scheme explicit"},
            {"stopFraction", "scalar", "0.01", "(0, 1)", "", "explicit",
             "stopCriterion kineticEnergy: the fraction of the peak kinetic energy below which the"
             " run ends (AvaFrame: 1 %)"},
            {"stopReportSpeed", "scalar", "1", ">= 0", "m/s", "",
             "the report at the end of the run (the stop or endTime; the log, <time>/uniform/granflowStopReport"
             " and the hazard maps' summary.dat): the faces with h > hMin faster than this, their volume, the"
             " fastest face and where; a warning when stopCriterion kineticEnergy stopped the run with such"
             " faces, or when endTime ended it with the criterion on"},
            {"setFields", "list", "()", "", "", "",
             "dictionaries of system/ whose fields the solver sets at the start of a run from t = 0,"
             " written into the start time before it reads them, as gfSetRelease [-dict NAME] sets them"
             " (releaseDict: h and Us; entrainmentDict, resistanceDict: the mass exchange's inputs);"
             " a restart keeps its own fields"},
            {"energyLine", "switch", "no", "", "", "",
             "write the mass-averaged path of the energy-line test at the start and every written time"
             " (postProcessing/energyLine: centre of mass, mean |Us|^2, mean horizontal path length;"
             " doc/theory/standard-tests.md section 4); needs a constant mass (no inflow, no mass exchange)"},
        }
    });

    T.push_back
    ({
        "controlDict/pathAnalysis", "system/controlDict", "pathAnalysis/", "faGranularFlowFoam",
        "The path analysis at the end of a run, after the hazard maps (hazardMaps yes): gfPathAnalysis's"
        " analysis (libgranflowTerrain's gf_path_analysis_run) on the maps' rasters, without another"
        " process; each entry is the gfPathAnalysis option named in its description, and the files"
        " are those of gfPathAnalysis run in the case folder with these options. Files relative to the"
        " case. Checked at the start of the run; a parallel run skips it with the maps.",
        true, "",
        {
            {"path", "fileName", "required", "", "", "",
             "-path: the avalanche path, the first line of a vector file (Inputs/LINES/path_aimec.shp)"},
            {"split", "fileName", "-", "", "", "",
             "-split: the split point (Inputs/POINTS/splitPoint.shp): the runout area starts at the beta"
             " point below it"},
            {"dem", "fileName", "the case's DEM", "", "", "",
             "-dem: constant/demWithDam.tif when gfTerrainMesh burnt a dam in, else terrainProperties dem"},
            {"ppr", "fileName", "postProcessing/hazardMaps/pressurePeak.asc", "", "kPa", "",
             "-ppr: the peak pressure raster"},
            {"pft", "fileName", "postProcessing/hazardMaps/hPeak.asc", "", "m", "",
             "-pft: the peak flow thickness raster"},
            {"pfv", "fileName", "postProcessing/hazardMaps/speedPeak.asc", "", "m/s", "",
             "-pfv: the peak flow speed raster"},
            {"field", "word", "ppr", "ppr | pft | pfv", "", "",
             "-field: result type of the runout and the comparison (AvaFrame's runoutResType)"},
            {"threshold", "scalar", "1 (ppr), 0.1 (pft), 1 (pfv)", "", "field's", "",
             "-threshold: reached where the field is above this (thresholdValue)"},
            {"width", "scalar", "600", "> 0", "m", "", "-width: domain width across the path (domainWidth)"},
            {"betaAngle", "scalar", "10", "(0, 90)", "deg", "",
             "-beta-angle: slope below which the runout area starts (startOfRunoutAreaAngle)"},
            {"dsMin", "scalar", "30", ">= 0", "m", "",
             "-ds-min: the slope stays below betaAngle over at least this (dsMin)"},
            {"refPpr", "fileName", "-", "", "kPa", "", "-ref-ppr: a reference run's peak pressure raster"},
            {"refPft", "fileName", "-", "", "m", "", "-ref-pft: its peak flow thickness raster"},
            {"refPfv", "fileName", "-", "", "m/s", "", "-ref-pfv: its peak flow speed raster"},
            {"name", "string", "run", "", "", "", "-name: the run's name in the CSV (simName)"},
            {"refName", "string", "reference", "", "", "", "-ref-name: the reference's name"},
            {"plots", "switch", "yes", "", "", "", "-plots: the PNG plots (gnuplot)"},
            {"out", "fileName", "postProcessing/pathAnalysis", "", "", "", "-out: the output folder"},
        }
    });

    // ---- <time>/uniform/granflowMassBalance -------------------------------------
    T.push_back
    ({
        "granflowMassBalance", "<time>/uniform/granflowMassBalance", "",
        "faGranularFlowFoam (restart), gfFlowSummary, gfHazardMaps",
        "Written by faGranularFlowFoam with every time: the totals of the mass balance"
        " volume + outflow - inflow - entrained + detrained = initial, continued by a restart.",
        true, "",
        {
            {"initialVolume", "scalar", "required", ">= 0", "m3", "", "volume at the start of the run"},
            {"volume", "scalar", "required", ">= 0", "m3", "", "volume in the domain at this time"},
            {"netOutflow", "scalar", "required", "", "m3", "", "net volume out of the domain so far"},
            {"imbalance", "scalar", "required", "", "m3", "",
             "volume + netOutflow - entrained + detrained - initialVolume"},
            {"carried", "scalar", "0", "", "m3", "",
             "BDF2 share of the step before a restart (not attributed to a patch)"},
            {"carriedLastStep", "scalar", "0", "", "m3", "", "its last step"},
            {"entrained", "scalar", "0", ">= 0", "m3", "",
             "volume (at the flow density) entrained from the bed so far (massExchange)"},
            {"detrained", "scalar", "0", ">= 0", "m3", "",
             "volume detrained in resistance areas so far (massExchange)"},
            {"patches", "dictionary", "required", "", "", "",
             "per patch <patch> { type; out (net volume out); lastStep (the last step's) }"},
        }
    });
    T.push_back
    ({
        "granflowMassBalance/patches/<patch>", "<time>/uniform/granflowMassBalance",
        "patches/<patch>/", "faGranularFlowFoam (restart)",
        "Written by faGranularFlowFoam: the totals of one patch.",
        true, "",
        {
            {"type", "word", "required", "wall | outflow | symmetry | inflow", "", "", "its boundary type"},
            {"out", "scalar", "required", "", "m3", "", "net volume out through the patch so far"},
            {"lastStep", "scalar", "required", "", "m3", "", "volume out in the last step (BDF2 history)"},
        }
    });

    // ---- <time>/uniform/granflowStopReport ---------------------------------------
    T.push_back
    ({
        "granflowStopReport", "<time>/uniform/granflowStopReport", "", "gfHazardMaps (summary.dat)",
        "Written by faGranularFlowFoam at the end of a run into its last time (when that time is written):"
        " the faces still moving (applications/utilities/common/stopReport.H; libgranflow's"
        " gf_surface_moving_faces).",
        true, "",
        {
            {"time", "scalar", "required", "", "s", "", "the end of the run"},
            {"stopCriterion", "word", "required", "none | kineticEnergy", "", "", "controlDict stopCriterion"},
            {"stopped", "switch", "required", "", "", "", "the stop criterion ended the run (no: endTime did)"},
            {"endTime", "scalar", "required", "", "s", "", "controlDict endTime, the cap"},
            {"stopFraction", "scalar", "required", "[0, 1)", "", "", "controlDict stopFraction"},
            {"kineticEnergyPercent", "scalar", "required", "", "", "",
             "the kinetic energy at the end in % of its peak (-1: stopCriterion none)"},
            {"stopReportSpeed", "scalar", "required", ">= 0", "m/s", "", "controlDict stopReportSpeed"},
            {"hMin", "scalar", "required", ">= 0", "m", "", "the dry threshold: faces with h > hMin count"},
            {"movingFaces", "label", "required", ">= 0", "", "", "faces faster than stopReportSpeed"},
            {"movingVolume", "scalar", "required", ">= 0", "m3", "", "their volume sum A h"},
            {"volume", "scalar", "required", ">= 0", "m3", "", "the volume in the domain"},
            {"maxSpeed", "scalar", "required", ">= 0", "m/s", "", "the largest |Us| of the faces with h > hMin"},
            {"maxSpeedAt", "vector", "required", "", "m", "", "the centre of that face"},
            {"georeferenced", "switch", "required", "", "", "",
             "maxSpeedAt in the terrain's coordinates (constant/terrainProperties offset added); no: mesh"
             " coordinates"},
        }
    });

    // ---- gfSetRelease: system/releaseDict -----------------------------------------
    T.push_back
    ({
        "releaseDict", "system/releaseDict", "", "gfSetRelease",
        "The initial flow thickness h (and velocity Us) of the start time; later regions override"
        " earlier ones where they give a value.",
        true, "",
        {
            {"field", "word", "h", "h | hEnt | resistance", "", "",
             "the field set: h (the release), hEnt (entrainable layer [m], e.g."
             " system/entrainmentDict) or resistance (resistance factor [-], e.g."
             " system/resistanceDict); gfSetRelease -dict <name> reads another dictionary"},
            {"default", "scalar", "required", ">= 0", "m", "", "the field outside every region"},
            {"factor", "scalar", "1", "[0, 100]", "", "",
             "every value of the field multiplied by it, after the regions (a back-calculation's"
             " release thickness: gfCalibrate's release parameter)"},
            {"Us", "vector", "-", "", "m/s", "",
             "initial velocity everywhere, made tangential (written to Us)"},
            {"regions", "list", "required", "", "", "",
             "( type { entries } ... ) with type sphericalCap, cylindricalCap, box, cylinder,"
             " function or polygons (tables below)"},
        }
    });
    auto region = [&T](const std::string& type, const std::string& desc, std::vector<row> rows)
    {
        T.push_back
        ({
            "releaseDict/regions/" + type, "system/releaseDict", "regions/" + type + "/",
            "gfSetRelease", desc, true, "", rows
        });
    };
    region
    (
        "sphericalCap",
        "h along the face normal up to a sphere, where it lies above the surface (the FA"
        " paper's release: centre (4 0 -1.5) in slope coordinates, radius 2).",
        {
            {"centre", "vector", "required", "", "m", "sphericalCap", "centre of the sphere"},
            {"radius", "scalar", "required", "> 0", "m", "sphericalCap", "radius of the sphere"},
        }
    );
    region
    (
        "cylindricalCap",
        "The same with a cylinder through point1 and point2: a laterally uniform release.",
        {
            {"point1", "vector", "required", "", "m", "cylindricalCap", "a point of the axis"},
            {"point2", "vector", "required", "", "m", "cylindricalCap", "another point of the axis"},
            {"radius", "scalar", "required", "> 0", "m", "cylindricalCap", "radius of the cylinder"},
        }
    );
    region
    (
        "box",
        "Face centres inside an axis-aligned box get value.",
        {
            {"min", "vector", "required", "", "m", "box", "lower corner"},
            {"max", "vector", "required", "", "m", "box", "upper corner"},
            {"value", "scalar", "required", ">= 0", "m", "box", "thickness"},
        }
    );
    region
    (
        "cylinder",
        "Face centres within radius of the segment point1-point2 get value.",
        {
            {"point1", "vector", "required", "", "m", "cylinder", "start of the axis"},
            {"point2", "vector", "required", "", "m", "cylinder", "end of the axis"},
            {"radius", "scalar", "required", "> 0", "m", "cylinder", "radius"},
            {"value", "scalar", "required", ">= 0", "m", "cylinder", "thickness"},
        }
    );
    region
    (
        "function",
        "h as any Function1 (table, polynomial, sine, ...) of one coordinate of the face centre.",
        {
            {"coordinate", "word", "required", "x | y | z | distance", "", "function",
             "the argument: a coordinate, or the distance from origin"},
            {"h", "Function1<scalar>", "required", "", "m", "function", "the thickness"},
            {"origin", "vector", "(0 0 0)", "", "m", "function", "origin of coordinate distance"},
        }
    );
    region
    (
        "polygons",
        "Release polygons of a real terrain (OGR: shapefile, GeoJSON; needs"
        " constant/terrainProperties of gfTerrainMesh for the offset): faces whose centre lies"
        " inside a polygon get its thickness.",
        {
            {"file", "fileName", "required", "", "", "polygons", "the polygons, relative to the case"},
            {"attribute", "word", "thickness", "", "", "polygons",
             "numeric attribute of the polygons with the thickness (not with value)"},
            {"value", "scalar", "-", ">= 0", "m", "polygons",
             "one thickness for every polygon (instead of attribute)"},
            {"measured", "word", "normal", "normal | vertical", "", "polygons",
             "the thickness is along the terrain normal (h = d) or vertical (h = d cos(slope))"},
            {"ci95", "scalar", "-", ">= 0", "m", "polygons",
             "half-width of the 95 % confidence interval of every polygon's thickness: with"
             " gfSetRelease -ci95Sample z the thickness is d + z ci95 (ensembles; not with ci95Attribute)"},
            {"ci95Attribute", "word", "-", "", "", "polygons",
             "numeric attribute of the polygons with each one's ci95 [m] (AvaFrame's ci95;"
             " instead of ci95)"},
        }
    );

    // ---- gfStandardTest: system/standardTestDict ------------------------------------
    T.push_back
    ({
        "standardTestDict", "system/standardTestDict", "", "gfStandardTest",
        "The standard analytic test of a case (tutorials/standardTests; definitions in"
        " doc/theory/standard-tests.md).",
        true, "",
        {
            {"test", "word", "required", "similarity | damBreak | flatPlane | energyLine | rotation", "", "",
             "the test: the similarity solution (Hutter et al. 1993), the dam break on an inclined"
             " Coulomb plane (Faccanoni & Mangeney 2013), the flat-plane pile, the energy line on a"
             " parabolic slope or the rotation test in a bowl"},
            {"cellSize", "scalar", "required", "[0.1, 20]", "m", "",
             "cell size of the output grid and of the mesh (the DEM's lower-left cell centre kept)"},
            {"angle", "scalar", "0", "[0, 360]", "deg", "",
             "rotation: the release at (-350, 0) m rotated clockwise by this angle about the bowl's centre"},
        }
    });

    // ---- gfTerrainMesh: system/terrainDict, constant/terrainProperties --------------
    T.push_back
    ({
        "terrainDict", "system/terrainDict", "", "gfTerrainMesh",
        "A DEM to a terrain-following slab mesh whose top patch is the area mesh.",
        true, "", terrainRows()
    });
    T.push_back(damTable("terrainDict", "system/terrainDict", "gfTerrainMesh"));
    {
        table t
        {
            "terrainProperties", "constant/terrainProperties", "", "gfSetRelease, gfHazardMaps",
            "Written by gfTerrainMesh: the entries of terrainDict with the offset used, and the"
            " mesh's derived data.",
            true, "", terrainRows()
        };
        const std::vector<row> derived
        {
            {"faces", "label", "-", ">= 0", "", "", "faces of the area mesh (written)"},
            {"cellSize", "scalar", "-", "> 0", "m", "", "edge length of the faces in plan (written)"},
            {"terrainArea", "scalar", "-", ">= 0", "m2", "", "area of the terrain surface (written)"},
            {"elevationRange", "list", "-", "", "m", "", "(zmin zmax) of the mesh nodes (written)"},
            {"crs", "string", "\"\"", "", "", "", "coordinate reference system of the DEM, WKT (written)"},
        };
        t.rows.insert(t.rows.end(), derived.begin(), derived.end());
        T.push_back(t);
    }
    T.push_back
    (
        damTable("terrainProperties", "constant/terrainProperties", "gfSetRelease, gfHazardMaps")
    );
    return T;
}

} // namespace


const std::vector<Foam::granflow::keyword::table>& Foam::granflow::keyword::all()
{
    static const std::vector<table> tables(makeTables());
    return tables;
}
