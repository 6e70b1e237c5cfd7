/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "basalFriction.H"
#include "error.H"
#include "keyword.H"

#include <string>

Foam::granflow::basalFriction::basalFriction(const dictionary& dict, bool exactCoulomb)
{
    const keyword::table& props = keyword::get("granularProperties");
    const word lawName(keyword::read<word>(dict, props, "frictionLaw"));
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
