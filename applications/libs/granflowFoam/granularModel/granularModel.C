#include "granularModel.H"
#include "error.H"
#include "Switch.H"
#include "mathematicalConstants.H"

Foam::scalar Foam::granflow::granularModel::readScalar
(
    const word& key,
    scalar lo,
    scalar hi,
    const scalar* deflt
) const
{
    if (!dict_.found(key))
    {
        if (deflt)
        {
            return *deflt;
        }
        FatalIOErrorInFunction(dict_)
            << "Missing entry " << key << " (allowed range [" << lo << ", " << hi << "])"
            << exit(FatalIOError);
    }
    const scalar v = dict_.get<scalar>(key);
    if (!(v >= lo && v <= hi))
    {
        FatalIOErrorInFunction(dict_)
            << "Invalid entry " << key << " " << v << ": allowed range [" << lo << ", " << hi
            << "]" << exit(FatalIOError);
    }
    return v;
}


bool Foam::granflow::granularModel::readSwitch(const word& key, bool deflt) const
{
    if (!dict_.found(key))
    {
        return deflt;
    }
    const word value(dict_.get<word>(key));
    const Switch s(value, true);
    if (!s.valid())
    {
        FatalIOErrorInFunction(dict_)
            << "Invalid entry " << key << " " << value
            << ": allowed on/off, yes/no, true/false" << exit(FatalIOError);
    }
    return s;
}


Foam::granflow::granularModel::granularModel(const dictionary& dict, bool exactCoulomb)
:
    dict_(dict),
    rho_(readScalar("rho", 1e-6, 1e6)),
    xi_(1),
    hMin_(1e-6),
    earthPressure_(),
    friction_(dict, exactCoulomb),
    lateralPressure_(readSwitch("lateralPressure")),
    centrifugalPressure_(readSwitch("centrifugalPressure")),
    lateralPressureFeedback_(readSwitch("lateralPressureFeedback")),
    staticFriction_(readSwitch("staticFriction", false))
{
    const scalar one = 1, tiny = 1e-6;
    xi_ = readScalar("xi", 1e-6, 2, &one);
    hMin_ = readScalar("hMin", 0, 1, &tiny);
    if (!(hMin_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry hMin " << hMin_ << ": the dry threshold must be > 0 (allowed (0, 1] m;"
            << " faces thinner than hMin are dry, and the friction and pressure terms divide by h)"
            << exit(FatalIOError);
    }

    // every entry must be one the model reads: a misspelled key is an error,
    // not a silently used default
    {
        const wordList known
        ({
            "rho", "xi", "hMin", "earthPressure", "savageHutterCoeffs", "frictionLaw",
            "lateralPressure", "centrifugalPressure", "lateralPressureFeedback", "staticFriction",
            "boundaries"
        });
        for (const word& key : dict.toc())
        {
            if (known.found(key))
            {
                continue;
            }
            // coefficients of any friction law may be kept: <law>Coeffs
            gf_friction probe;
            if
            (
                key.size() > 6 && key.ends_with("Coeffs") && dict.isDict(key)
             && gf_friction_init(&probe, key.substr(0, key.size() - 6).c_str()) == GF_SUCCESS
            )
            {
                continue;
            }
            FatalIOErrorInFunction(dict)
                << "Unknown entry " << key << " in granularProperties; valid entries: rho, xi,"
                << " hMin, earthPressure, savageHutterCoeffs, frictionLaw, <law>Coeffs (law: "
                << gf_friction_names() << "), lateralPressure, centrifugalPressure,"
                << " lateralPressureFeedback, staticFriction, boundaries" << exit(FatalIOError);
        }
    }

    const word model(dict.getOrDefault<word>("earthPressure", "isotropic"));
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
        if (!dict.isDict("savageHutterCoeffs"))
        {
            FatalIOErrorInFunction(dict)
                << "earthPressure savageHutter needs the sub-dictionary savageHutterCoeffs"
                << " with phi and delta [deg]" << exit(FatalIOError);
        }
        const dictionary& c = dict.subDict("savageHutterCoeffs");
        for (const word& key : c.toc())
        {
            if (key != "phi" && key != "delta")
            {
                FatalIOErrorInFunction(c)
                    << "Unknown entry savageHutterCoeffs/" << key
                    << "; valid entries: phi, delta [deg]" << exit(FatalIOError);
            }
        }
        for (const word key : {"phi", "delta"})
        {
            if (!c.found(key))
            {
                FatalIOErrorInFunction(c)
                    << "Missing entry savageHutterCoeffs/" << key << " [deg]" << exit(FatalIOError);
            }
        }
        phi = c.get<scalar>("phi");
        delta = c.get<scalar>("delta");
        // the ranges in the unit of the entries (the library checks radians)
        if (!(phi > 0 && phi < 90) || !(delta >= 0 && delta < 90))
        {
            FatalIOErrorInFunction(c)
                << "Invalid entries savageHutterCoeffs phi " << phi << " deg, delta " << delta
                << " deg: allowed 0 < phi < 90 deg, 0 <= delta < 90 deg" << exit(FatalIOError);
        }
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
        << ", friction " << friction_.lawName()
        << ", earth pressure " << (isotropic() ? "isotropic" : "savageHutter")
        << " (K_act " << earthPressure_.k_act << ", K_pass " << earthPressure_.k_pass << ")"
        << nl << "    terms: lateralPressure " << Switch(lateralPressure_)
        << ", centrifugalPressure " << Switch(centrifugalPressure_)
        << ", lateralPressureFeedback " << Switch(lateralPressureFeedback_)
        << ", staticFriction " << Switch(staticFriction_) << endl;
}
