/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "basalFriction.H"
#include "error.H"
#include "keyword.H"

#include <string>

void Foam::granflow::basalFriction::samosATAuto
(
    const dictionary& dict, const bool exactCoulomb, const scalar releaseVolume
)
{
    const keyword::table& props = keyword::get("granularProperties");
    // an inflow patch brings material that no release volume counts
    if (keyword::found(dict, props, "boundaries"))
    {
        const keyword::table& bt = keyword::get("granularProperties/boundaries/<patch>");
        const dictionary& bd = keyword::subDict(dict, props, "boundaries");
        for (const entry& e : bd)
        {
            if (e.isDict() && keyword::read<word>(e.dict(), bt, "type") == "inflow")
            {
                FatalIOErrorInFunction(dict)
                    << "Invalid entry frictionLaw samosATAuto in constant/granularProperties: the patch "
                    << e.keyword() << " is an inflow (boundaries/" << e.keyword() << " type inflow), whose"
                    << " hydrograph brings material that no release volume counts, and samosATAuto"
                    << " chooses the samosAT set by the release volume (AvaFrame's com1DFA: below "
                    << GF_SAMOSAT_VOL_SMALL << " m3 samosATSmall, below " << GF_SAMOSAT_VOL_MEDIUM
                    << " m3 samosATMedium, else samosAT). Give the set: frictionLaw samosAT with samosATCoeffs"
                    << " (mu 0.22, 0.17 or 0.155; tau0 0, Rs0 0.222, kappa 0.43, R 0.05, B 4.13)"
                    << exit(FatalIOError);
            }
        }
    }
    if (releaseVolume < 0)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry frictionLaw samosATAuto in constant/granularProperties: this program does not"
            << " know the release volume that chooses the samosAT set (faGranularFlowFoam and"
            << " gfFrictionField do); give the set: frictionLaw samosAT with samosATCoeffs"
            << exit(FatalIOError);
    }
    const gf_samosat_set* set = nullptr;
    if (gf_samosat_auto(releaseVolume, &set) != GF_SUCCESS)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry frictionLaw samosATAuto in constant/granularProperties: " << gf_error_detail()
            << "; the release volume is sum A h of the initial thickness h (the start time's h, set by gfSetRelease): a"
            << " case without a release cannot choose a set; give it: frictionLaw samosAT with samosATCoeffs"
            << exit(FatalIOError);
    }
    if (gf_friction_init_samosat_set(&law_, set) != GF_SUCCESS)
    {
        FatalErrorInFunction << "samosATAuto: " << gf_error_detail() << exit(FatalError);
    }
    // u0: exact Coulomb where the scheme takes it (explicit), else the law's
    // regularised default (the implicit scheme needs u0 > 0)
    if (exactCoulomb)
    {
        gf_friction_set(&law_, "u0", 0);
    }
    autoSet_ = set->name;
    double u0 = 0;
    gf_friction_get(&law_, "u0", &u0);
    Info<< "samosATAuto: release volume " << releaseVolume << " m3 -> " << autoSet_ << " (mu " << set->mu
        << ", tau0 " << set->tau0 << " Pa, Rs0 " << set->Rs0 << ", kappa " << set->kappa << ", R " << set->R
        << " m, B " << set->B << ", u0 " << u0 << " m/s); AvaFrame's com1DFA volume classes: samosATSmall below "
        << GF_SAMOSAT_VOL_SMALL << " m3, samosATMedium below " << GF_SAMOSAT_VOL_MEDIUM
        << " m3, else samosAT; the volume is sum A h of the initial h on the terrain" << endl;
    if (keyword::found(dict, props, "samosATCoeffs"))
    {
        Info<< "samosATAuto: the entry samosATCoeffs is not used (frictionLaw samosAT takes a set as given)"
            << endl;
    }
}


Foam::granflow::basalFriction::basalFriction
(
    const dictionary& dict, bool exactCoulomb, const scalar releaseVolume
)
{
    const keyword::table& props = keyword::get("granularProperties");
    const word lawName(keyword::read<word>(dict, props, "frictionLaw"));
    if (lawName == "samosATAuto")
    {
        samosATAuto(dict, exactCoulomb, releaseVolume);
        return;
    }
    if (gf_friction_init(&law_, lawName.c_str()) != GF_SUCCESS)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry frictionLaw " << lawName << ": " << gf_error_detail()
            << exit(FatalIOError);
    }

    const gf_friction_type& t = *law_.type;
    const word coeffsName(lawName + "Coeffs");
    if (t.n_params == 0)
    {
        return;
    }
    // the rows of <law>Coeffs are made from libgranflow's table of the law
    const keyword::table& ct = keyword::get("granularProperties/" + coeffsName);
    const dictionary& coeffs = keyword::subDict(dict, props, coeffsName);
    keyword::checkKeys(coeffs, ct);
    for (size_t i = 0; i < t.n_params; ++i)
    {
        const gf_friction_param& p = t.params[i];
        const scalar value = keyword::read<scalar>(coeffs, ct, p.name);
        if (gf_friction_set(&law_, p.name, value) != GF_SUCCESS)
        {
            FatalIOErrorInFunction(coeffs)
                << "Invalid entry " << coeffsName << '/' << p.name << ": " << gf_error_detail()
                << exit(FatalIOError);
        }
    }
    // u0 = 0 (exact Coulomb) is not usable by the implicit scheme: its
    // coefficient nu = tau/|u| is unbounded at rest (a division by zero)
    double u0;
    if (!exactCoulomb && gf_friction_get(&law_, "u0", &u0) == GF_SUCCESS && !(u0 > 0))
    {
        FatalIOErrorInFunction(coeffs)
            << "Invalid entry " << coeffsName << "/u0 " << u0 << ": the implicit finite-area"
            << " scheme needs u0 > 0 (allowed (0, 1] m/s): with u0 = 0 (exact Coulomb) the"
            << " friction coefficient nu = tau_b/(rho |u|) is infinite at rest. Use the"
            << " regularised value of the paper's Table 1 (1e-4 m/s) and staticFriction on"
            << " for deposits exactly at rest, or the explicit scheme (faSolution granularFlow/scheme"
            << " explicit), which takes u0 = 0" << exit(FatalIOError);
    }
    if (gf_friction_check(&law_) != GF_SUCCESS)
    {
        FatalIOErrorInFunction(coeffs)
            << "Invalid coefficients in " << coeffsName << ": " << gf_error_detail()
            << exit(FatalIOError);
    }
}


void Foam::granflow::basalFriction::evaluate
(
    const areaScalarField& h,
    const areaVectorField& Us,
    const areaScalarField& pb,
    const scalar rho,
    const scalar g,
    const scalar hMin,
    areaScalarField& tau,
    areaScalarField& nu
) const
{
    forAll(h, facei)
    {
        if (h[facei] < hMin)
        {
            tau[facei] = 0;
            nu[facei] = 0;
            continue;
        }
        const gf_friction_state s{h[facei], mag(Us[facei]), pb[facei], rho, g};
        gf_friction_result r;
        if (gf_friction_eval(&law_, &s, &r) != GF_SUCCESS)
        {
            FatalErrorInFunction
                << "Friction law " << lawName() << " failed on face " << facei
                << " (h = " << s.h << ", |Us| = " << s.speed << ", pb = " << s.pb
                << "): " << gf_error_detail() << exit(FatalError);
        }
        tau[facei] = r.tau;
        nu[facei] = r.nu;
    }
    tau.correctBoundaryConditions();
    nu.correctBoundaryConditions();
}


void Foam::granflow::basalFriction::staticBound
(
    const areaScalarField& h,
    const areaScalarField& pb,
    const scalar rho,
    const scalar g,
    const scalar hMin,
    scalarField& tauS
) const
{
    tauS.setSize(h.size());
    forAll(h, facei)
    {
        if (h[facei] < hMin)
        {
            tauS[facei] = 0;
            continue;
        }
        const gf_friction_state s{h[facei], 0, pb[facei], rho, g};
        if (gf_friction_static_bound(&law_, &s, &tauS[facei]) != GF_SUCCESS)
        {
            FatalErrorInFunction
                << "Static bound of friction law " << lawName() << " failed on face " << facei
                << " (h = " << s.h << ", pb = " << s.pb << "): " << gf_error_detail()
                << exit(FatalError);
        }
    }
}
