/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granularModel.H"
#include "error.H"
#include "Switch.H"
#include "mathematicalConstants.H"
#include "keyword.H"

namespace
{
    const Foam::granflow::keyword::table& props()
    {
        return Foam::granflow::keyword::get("granularProperties");
    }
}


Foam::granflow::granularModel::granularModel
(
    const dictionary& dict, bool exactCoulomb, const scalar releaseVolume
)
:
    dict_(dict),
    rho_(keyword::read<scalar>(dict, props(), "rho")),
    xi_(keyword::read<scalar>(dict, props(), "xi")),
    hMin_(keyword::read<scalar>(dict, props(), "hMin")),
    earthPressure_(),
    friction_(dict, exactCoulomb, releaseVolume),
    lateralPressure_(keyword::read<bool>(dict, props(), "lateralPressure")),
    centrifugalPressure_(keyword::read<bool>(dict, props(), "centrifugalPressure")),
    lateralPressureFeedback_(keyword::read<bool>(dict, props(), "lateralPressureFeedback")),
    staticFriction_(keyword::read<bool>(dict, props(), "staticFriction"))
{
    // every entry must be one the model reads: a misspelled key is an error,
    // not a silently used default (the coefficients of any law may be kept)
    keyword::checkKeys(dict, props());

    const word model(keyword::read<word>(dict, props(), "earthPressure"));
    gf_earth_pressure_model m;
    if (gf_earth_pressure_model_from_name(model.c_str(), &m) != GF_SUCCESS)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry earthPressure " << model << ": " << gf_error_detail()
            << exit(FatalIOError);
    }
    scalar phi = 0, delta = 0;
    if (m == GF_EARTH_PRESSURE_SAVAGE_HUTTER)
    {
        const keyword::table& sh = keyword::get("granularProperties/savageHutterCoeffs");
        const dictionary& c = keyword::subDict(dict, props(), "savageHutterCoeffs");
        keyword::checkKeys(c, sh);
        // the ranges in the unit of the entries (the library checks radians)
        phi = keyword::read<scalar>(c, sh, "phi");
        delta = keyword::read<scalar>(c, sh, "delta");
    }
    const scalar deg = constant::mathematical::pi/180;
    if (gf_earth_pressure_init(&earthPressure_, m, phi*deg, delta*deg) != GF_SUCCESS)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry savageHutterCoeffs: " << gf_error_detail() << exit(FatalIOError);
    }
}


void Foam::granflow::granularModel::earthPressure
(
    const areaScalarField& divUs,
    areaScalarField& K
) const
{
    forAll(K, facei)
    {
        K[facei] = gf_earth_pressure_k(&earthPressure_, divUs[facei]);
    }
    K.correctBoundaryConditions();
}


void Foam::granflow::granularModel::report(Ostream& os) const
{
    os  << "Granular model: rho = " << rho_ << ", xi = " << xi_ << ", hMin = " << hMin_
        << ", friction " << friction_.describe().c_str()
        << ", earth pressure " << (isotropic() ? "isotropic" : "savageHutter")
        << " (K_act " << earthPressure_.k_act << ", K_pass " << earthPressure_.k_pass << ")"
        << nl << "    terms: lateralPressure " << Switch(lateralPressure_)
        << ", centrifugalPressure " << Switch(centrifugalPressure_)
        << ", lateralPressureFeedback " << Switch(lateralPressureFeedback_)
        << ", staticFriction " << Switch(staticFriction_) << endl;
}
