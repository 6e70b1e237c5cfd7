/* SPDX-License-Identifier: GPL-3.0-or-later */
/*---------------------------------------------------------------------------*\
    granflow — gfSetRelease

Description
    Sets the initial flow thickness h (and optionally a uniform velocity Us)
    on the area mesh from system/releaseDict:

        default  0;                 // h outside every region [m]
        Us       (0 0 0);           // optional: initial velocity everywhere
        regions
        (
            // thickness along the face normal up to a sphere (the finite-area
            // paper's release: centre (4 0 -1.5) in slope coordinates, r = 2)
            sphericalCap { centre (4 0 -1.5); radius 2; }
            // the same with a cylinder (axis through point1, point2): a
            // laterally uniform release
            cylindricalCap { point1 (4 -1 -1.5); point2 (4 1 -1.5); radius 2; }
            // face centres inside an axis-aligned box get 'value'
            box { min (0 -1 -1); max (5 1 1); value 0.5; }
            // face centres within 'radius' of the axis point1-point2
            cylinder { point1 (0 0 -1); point2 (0 0 1); radius 1; value 0.3; }
            // any Function1 (table, polynomial, sine, ...) of one coordinate
            // x, y, z, or distance (from 'origin')
            function { coordinate x; h table ((0 0.5) (5 0.5) (5 0.1) (10 0.1)); }
            // release polygons of a real terrain (shapefile, GeoJSON, ... read
            // by OGR; a case meshed by gfTerrainMesh, whose offset maps the
            // polygons' georeferenced coordinates onto the mesh): faces whose
            // centre lies inside a polygon get its thickness, from a numeric
            // attribute (default thickness) or a value, measured normal to
            // the terrain (h = d, the default)
            // or vertically (h = d cos(slope), the same volume per plan area)
            polygons { file "Inputs/REL/release.shp"; attribute thickness; measured normal; }
            polygons { file "Inputs/REL/release.geojson"; value 1.5; measured vertical; }
        );

    The mass exchange's input fields (constant/granularProperties
    massExchange) are set the same way from another dictionary,
    gfSetRelease -dict <name> with 'field hEnt' (the entrainable layer depth
    [m], 0 outside the entrainment areas; AvaFrame's Inputs/ENT polygons with
    their thickness attribute) or 'field resistance' (the factor on cRes, 0
    outside; Inputs/RES polygons with value 1):

        // system/entrainmentDict
        field    hEnt;
        default  0;
        regions  ( polygons { file "Inputs/ENT/entrainment.shp"; attribute thickness; } );

    An ensemble member's release (gfRunEnsemble; hazard-analysis
    specification, section 4): with -ci95Sample z (z in [-1, 1]) every
    polygons region's thickness d becomes d + z ci95, the half-width of its
    95 % confidence interval given by the region's 'ci95' [m] or its
    polygons' attribute 'ci95Attribute' (AvaFrame's ci95); a region without
    either, and a thickness that would fall below 0, are refused.
    An ensemble's releases in one run (the mesh loaded once): -ci95Samples
    FILE -ci95Out DIR, FILE's lines 'NAME z' (# comments): for each, the
    field that -ci95Sample z writes, byte for byte, into DIR/NAME/ (h, and
    Us when the dictionary sets it), the case's own fields untouched; a
    member refused (z outside [-1, 1], a thickness below 0) gets
    DIR/NAME.refused with the reason and the others are written.

    A missing or negative thickness attribute and a polygon that covers no
    face centre are errors naming the dictionary, the file and the entry.

    Later regions override earlier ones where they give a value; a
    sphericalCap sets h only where the sphere lies above the surface.  Writes
    h (and Us) into the start time folder.  Every entry is read through its
    row of the keyword tables "releaseDict" and "releaseDict/regions/<type>"
    (keywords/keywordTables.C, doc/keywords.md): unknown region types and
    keys, missing entries and values out of range are FatalIOErrors naming them.
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "Function1.H"

#include "terrainCase.H"
#include "keyword.H"
#include "Tuple2.H"

#include <algorithm>
#include <fstream>
#include <sstream>

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Set the initial flow thickness h (and Us) from system/releaseDict, or with -dict the"
        " field it names (field hEnt: the entrainable layer, resistance: the resistance areas)"
    );
    argList::addOption
    (
        "dict", "name",
        "read system/<name> instead of system/releaseDict (e.g. entrainmentDict, resistanceDict)"
    );
    argList::addOption
    (
        "ci95Sample", "z",
        "z in [-1, 1]: every polygons region's thickness d becomes d + z ci95, ci95 the region's"
        " ci95 entry or ci95Attribute (an ensemble member's release thickness; gfRunEnsemble)"
    );
    argList::addOption
    (
        "ci95Samples", "file",
        "lines 'NAME z': for each, the field of -ci95Sample z written to DIR/NAME/ (-ci95Out DIR)"
        " instead of the case's time folder, the mesh loaded once (an ensemble's releases; gfRunEnsemble)"
    );
    argList::addOption("ci95Out", "dir", "where -ci95Samples writes its fields (DIR/NAME/)");
    granflow::keyword::addOptions();   // -keywords, -version
    if (granflow::keyword::earlyOptions(argc, argv))
    {
        return 0;
    }
    #include "setRootCase.H"
    granflow::keyword::banner();
    #include "createTime.H"

    const word dictName(args.getOrDefault<word>("dict", "releaseDict"));
    const bool ci95On = args.found("ci95Sample");
    const scalar ci95Sample = args.getOrDefault<scalar>("ci95Sample", 0);
    auto checkSample = [](const scalar z)
    {
        if (!(z >= -1 && z <= 1))
        {
            FatalErrorInFunction
                << "-ci95Sample " << z << ": outside [-1, 1] (the thickness d + z ci95 spans"
                << " the 95 % confidence interval for z from -1 to 1)" << exit(FatalError);
        }
    };
    if (ci95On)
    {
        checkSample(ci95Sample);
    }
    // -ci95Samples FILE: the list of NAME z (read before the meshes, so that a
    // bad list stops at once); z is read as -ci95Sample reads its value
    const fileName samplesFile(args.getOrDefault<fileName>("ci95Samples", fileName()));
    const fileName samplesOut(args.getOrDefault<fileName>("ci95Out", fileName()));
    DynamicList<Tuple2<word, scalar>> samples;
    if (!samplesFile.empty())
    {
        if (ci95On || samplesOut.empty())
        {
            FatalErrorInFunction
                << "-ci95Samples " << samplesFile << " needs -ci95Out DIR (where the fields go) and"
                << " excludes -ci95Sample" << exit(FatalError);
        }
        std::ifstream is(samplesFile.c_str());
        if (!is.good())
        {
            FatalErrorInFunction << "-ci95Samples " << samplesFile << ": cannot read the file" << exit(FatalError);
        }
        std::string line;
        for (label lineNo = 1; std::getline(is, line); ++lineNo)
        {
            std::istringstream ls(line);
            std::string nm, zs, extra;
            if (!(ls >> nm) || nm[0] == '#') continue;
            double z = 0;
            if (!(ls >> zs) || (ls >> extra) || !Foam::readDouble(zs, z)
             || !std::all_of(nm.begin(), nm.end(), [](char c) { return word::valid(c) && c != '/'; }))
            {
                FatalErrorInFunction
                    << "-ci95Samples " << samplesFile << " line " << lineNo << " '" << line.c_str()
                    << "': a name (a word, no '/') and a number z expected" << exit(FatalError);
            }
            samples.append(Tuple2<word, scalar>(word(nm), z));
        }
        if (samples.empty())
        {
            FatalErrorInFunction << "-ci95Samples " << samplesFile << ": no 'NAME z' line" << exit(FatalError);
        }
    }
    else if (!samplesOut.empty())
    {
        FatalErrorInFunction << "-ci95Out without -ci95Samples" << exit(FatalError);
    }

    #include "createMesh.H"
    #include "createFaMesh.H"
    const fileName dictFile("system"/dictName);
    IOdictionary dict
    (
        IOobject(dictName, runTime.system(), mesh, IOobject::MUST_READ, IOobject::NO_WRITE)
    );

    namespace kw = granflow::keyword;
    const kw::table& rt = kw::get("releaseDict");
    kw::checkKeys(dict, rt);
    // the field set: h, or the mass exchange's inputs hEnt [m] and
    // resistance [-] (a new file with h's patch types when there is none)
    const word fieldName = kw::read<word>(dict, rt, "field");
    areaScalarField h
    (
        IOobject("h", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE),
        aMesh
    );
    autoPtr<areaScalarField> fieldPtr;
    if (fieldName != "h")
    {
        IOobject io(fieldName, runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE);
        if (io.typeHeaderOk<areaScalarField>(true))
        {
            fieldPtr.reset(new areaScalarField(io, aMesh));
        }
        else
        {
            io.readOpt() = IOobject::NO_READ;
            fieldPtr.reset(new areaScalarField(io, h));
        }
        fieldPtr->dimensions().reset(fieldName == "resistance" ? dimless : dimLength);
    }
    if (fieldName != "h" && kw::found(dict, rt, "Us"))
    {
        FatalIOErrorInFunction(dict)
            << dictFile << ": Us (the initial velocity) belongs to the release, field h; this"
            << " dictionary sets field " << fieldName << exit(FatalIOError);
    }
    areaScalarField& field = fieldPtr.valid() ? fieldPtr.ref() : h;
    const vectorField& C = aMesh.areaCentres().primitiveField();
    const vectorField& N = aMesh.faceAreaNormals().primitiveField();
    // the field of the dictionary; with ci95On, every polygons region's
    // thickness d + ci95Sample ci95 (an ensemble member's release)
    auto compute = [&](const bool ci95On, const scalar ci95Sample)
    {
        scalarField hNew(h.size(), kw::read<scalar>(dict, rt, "default"));

        const PtrList<entry> regions(kw::read<PtrList<entry>>(dict, rt, "regions"));
        for (const entry& e : regions)
        {
            if (!e.isDict())
            {
                FatalIOErrorInFunction(dict)
                    << "regions: entry " << e.keyword() << " is not a dictionary" << exit(FatalIOError);
            }
            const word type = e.keyword();
            const dictionary& r = e.dict();
            const char* types[] = {"sphericalCap", "cylindricalCap", "box", "cylinder", "function", "polygons"};
            if (std::find_if(std::begin(types), std::end(types), [&](const char* t) { return type == t; })
                == std::end(types))
            {
                FatalIOErrorInFunction(dict)
                    << "Unknown region type " << type << " in " << dictFile
                    << "; valid types: sphericalCap, cylindricalCap, box, cylinder, function, polygons"
                    << exit(FatalIOError);
            }
            // every region's entries through the rows of its table: unknown keys are errors
            const kw::table& t = kw::get("releaseDict/regions/" + type);
            kw::checkKeys(r, t);
            label nSet = 0;
            if (type == "sphericalCap")
            {
                const vector c = kw::read<vector>(r, t, "centre");
                const scalar rad = kw::read<scalar>(r, t, "radius");
                forAll(C, i)
                {
                    // s >= 0 with |C + s n - c| = r: thickness along the normal
                    const vector d = C[i] - c;
                    const scalar b = N[i] & d;
                    const scalar disc = b*b - magSqr(d) + rad*rad;
                    if (disc > 0)
                    {
                        const scalar s = -b + Foam::sqrt(disc);
                        if (s > 0)
                        {
                            hNew[i] = s;
                            ++nSet;
                        }
                    }
                }
            }
            else if (type == "cylindricalCap")
            {
                const vector p1 = kw::read<vector>(r, t, "point1"), p2 = kw::read<vector>(r, t, "point2");
                const scalar rad = kw::read<scalar>(r, t, "radius");
                if (mag(p2 - p1) < SMALL)
                {
                    FatalIOErrorInFunction(r) << "point1 and point2 coincide" << exit(FatalIOError);
                }
                const vector ax = (p2 - p1)/mag(p2 - p1);
                forAll(C, i)
                {
                    // s >= 0 with |(C + s n - p1)_perp| = r, perp: normal to the axis
                    const vector d = C[i] - p1, dp = d - (d & ax)*ax;
                    const vector np = N[i] - (N[i] & ax)*ax;
                    const scalar a = magSqr(np), b = np & dp;
                    const scalar disc = b*b - a*(magSqr(dp) - rad*rad);
                    if (a > SMALL && disc > 0)
                    {
                        const scalar s = (-b + Foam::sqrt(disc))/a;
                        if (s > 0)
                        {
                            hNew[i] = s;
                            ++nSet;
                        }
                    }
                }
            }
            else if (type == "box")
            {
                const boundBox bb(kw::read<vector>(r, t, "min"), kw::read<vector>(r, t, "max"));
                const scalar v = kw::read<scalar>(r, t, "value");
                forAll(C, i)
                {
                    if (bb.contains(C[i]))
                    {
                        hNew[i] = v;
                        ++nSet;
                    }
                }
            }
            else if (type == "cylinder")
            {
                const vector p1 = kw::read<vector>(r, t, "point1"), p2 = kw::read<vector>(r, t, "point2");
                const scalar rad = kw::read<scalar>(r, t, "radius"), v = kw::read<scalar>(r, t, "value");
                const vector ax = (p2 - p1)/mag(p2 - p1);
                forAll(C, i)
                {
                    const vector d = C[i] - p1;
                    const scalar a = d & ax;
                    if (a >= 0 && a <= mag(p2 - p1) && mag(d - a*ax) <= rad)
                    {
                        hNew[i] = v;
                        ++nSet;
                    }
                }
            }
            else if (type == "function")
            {
                const word coord = kw::read<word>(r, t, "coordinate");
                autoPtr<Function1<scalar>> f = Function1<scalar>::New("h", r);
                const vector origin = kw::read<vector>(r, t, "origin");
                forAll(C, i)
                {
                    scalar x = 0;
                    if (coord == "x") x = C[i].x();
                    else if (coord == "y") x = C[i].y();
                    else if (coord == "z") x = C[i].z();
                    else x = mag(C[i] - origin);   // distance (the row's choices)
                    hNew[i] = f->value(x);
                    ++nSet;
                }
            }
            else if (type == "polygons")
            {
                if (kw::found(r, t, "attribute") && kw::found(r, t, "value"))
                {
                    FatalIOErrorInFunction(r)
                        << "region polygons takes one of attribute (a numeric field of the polygons,"
                        << " default thickness) and value (a thickness for all) [m], not both"
                        << exit(FatalIOError);
                }
                const word measured = kw::read<word>(r, t, "measured");
                IOobject tio("terrainProperties", runTime.constant(), mesh, IOobject::MUST_READ);
                if (!tio.typeHeaderOk<IOdictionary>(false))
                {
                    FatalIOErrorInFunction(r)
                        << "region polygons needs constant/terrainProperties (written by"
                        << " gfTerrainMesh) for the offset between the polygons' georeferenced"
                        << " coordinates and the mesh" << exit(FatalIOError);
                }
                const IOdictionary terrain(tio);
                const kw::table& tp = kw::get("terrainProperties");
                const vector offset = kw::read<vector>(terrain, tp, "offset");
                const fileName file = kw::read<fileName>(r, t, "file");
                const fileName path = granflow::terrainCase::inCase(file, runTime.path());
                scalar value = 0;
                const bool byValue = kw::readIfPresent<scalar>(r, t, "value", value);
                const std::string attr = byValue ? word() : kw::read<word>(r, t, "attribute");
                gf_polygons P;
                if (gf_polygons_read(path.c_str(), attr.empty() ? nullptr : attr.c_str(), value, &P) != GF_SUCCESS)
                {
                    FatalIOErrorInFunction(dict)
                        << "regions/polygons (file " << file
                        << (attr.empty() ? word::null : word(", attribute " + attr))
                        << ") of " << dictFile << ": " << gf_error_detail() << exit(FatalIOError);
                }
                // an ensemble member's thickness: d + z ci95 per polygon
                if (kw::found(r, t, "ci95") && kw::found(r, t, "ci95Attribute"))
                {
                    gf_polygons_free(&P);
                    FatalIOErrorInFunction(r)
                        << "region polygons (file " << file << ") takes one of ci95 [m] and ci95Attribute,"
                        << " not both" << exit(FatalIOError);
                }
                if (ci95On)
                {
                    scalar ci = 0;
                    const bool byCi = kw::readIfPresent<scalar>(r, t, "ci95", ci);
                    if (!byCi && !kw::found(r, t, "ci95Attribute"))
                    {
                        gf_polygons_free(&P);
                        FatalIOErrorInFunction(r)
                            << "-ci95Sample " << ci95Sample << " given, but region polygons (file " << file
                            << ") of " << dictFile << " has no ci95 [m] or ci95Attribute: the confidence"
                            << " interval of its thickness is unknown" << exit(FatalIOError);
                    }
                    gf_polygons C95;
                    const std::string ciAttr = byCi ? std::string() : std::string(kw::read<word>(r, t, "ci95Attribute"));
                    if (gf_polygons_read(path.c_str(), byCi ? nullptr : ciAttr.c_str(), ci, &C95) != GF_SUCCESS)
                    {
                        gf_polygons_free(&P);
                        FatalIOErrorInFunction(dict)
                            << "regions/polygons (file " << file << ", ci95Attribute " << ciAttr << ") of "
                            << dictFile << ": " << gf_error_detail() << exit(FatalIOError);
                    }
                    for (size_t k = 0; k < P.n; ++k)
                    {
                        const scalar d = P.value[k] + ci95Sample*C95.value[k];
                        if (d < 0)
                        {
                            gf_polygons_free(&C95);
                            gf_polygons_free(&P);
                            FatalIOErrorInFunction(r)
                                << "polygon " << label(k) << " of " << file << ": thickness " << P.value[k]
                                << " m + ci95Sample " << ci95Sample << " x ci95 " << C95.value[k] << " m = " << d
                                << " m is negative: the confidence interval reaches below 0" << exit(FatalIOError);
                        }
                        Info<< "    polygon " << label(k) << ": thickness " << P.value[k] << " m + "
                            << ci95Sample << " x ci95 " << C95.value[k] << " m = " << d << " m (-ci95Sample)" << endl;
                        P.value[k] = d;
                    }
                    gf_polygons_free(&C95);
                }
                const string demCrs = kw::read<string>(terrain, tp, "crs");
                if (demCrs.size() && !*P.wkt)
                {
                    Info<< "    polygons " << file << " have no CRS (no .prj): taken to be in the"
                        << " DEM's" << endl;
                }
                if (gf_crs_same(P.wkt, demCrs.c_str()) == 0)
                {
                    gf_polygons_free(&P);
                    FatalIOErrorInFunction(r)
                        << "polygons " << path << " are in another coordinate reference system than"
                        << " the DEM (constant/terrainProperties crs); reproject them (ogr2ogr -t_srs)"
                        << exit(FatalIOError);
                }
                scalarField vol(P.n, 0), area(P.n, 0);
                labelList nIn(P.n, 0);
                const scalarField& S = aMesh.S().field();
                forAll(C, i)
                {
                    const long k = gf_polygons_locate(&P, C[i].x() + offset.x(), C[i].y() + offset.y());
                    if (k < 0) continue;
                    // vertical thickness d over a face of slope theta: h = d cos(theta)
                    const scalar hk = measured == "normal" ? P.value[k] : P.value[k]*mag(N[i].z());
                    hNew[i] = hk;
                    vol[k] += hk*S[i];
                    area[k] += S[i];
                    ++nIn[k];
                    ++nSet;
                }
                Pstream::listCombineGather(vol, plusEqOp<scalar>());
                Pstream::listCombineGather(area, plusEqOp<scalar>());
                Pstream::listCombineGather(nIn, plusEqOp<label>());
                for (size_t k = 0; k < P.n; ++k)
                {
                    if (fieldName == "resistance")
                    {
                        Info<< "    polygon " << label(k) << " of " << file << ": resistance factor "
                            << P.value[k] << ", plan area " << gf_polygons_area(&P, k) << " m2; " << nIn[k]
                            << " faces, terrain area " << area[k] << " m2" << endl;
                        continue;
                    }
                    Info<< "    polygon " << label(k) << " of " << file << ": thickness " << P.value[k]
                        << " m (" << measured << "), plan area " << gf_polygons_area(&P, k)
                        << " m2; " << nIn[k] << " faces, terrain area " << area[k]
                        << (fieldName == "h" ? " m2, released volume " : " m2, layer volume ") << vol[k]
                        << " m3" << endl;
                }
                // a polygon that releases nothing is a mistake (another CRS without
                // a .prj, outside the cropped mesh, smaller than a face)
                for (size_t k = 0; k < P.n; ++k)
                {
                    if (nIn[k] == 0)
                    {
                        const FixedList<scalar, 4> b({P.box[4*k], P.box[4*k + 1], P.box[4*k + 2], P.box[4*k + 3]});
                        const boundBox mb(aMesh.mesh().bounds());
                        gf_polygons_free(&P);
                        FatalIOErrorInFunction(r)
                            << dictFile << " regions/polygons: polygon " << label(k) << " of " << file << " (extent x " << b[0] << " .. "
                            << b[2] << ", y " << b[1] << " .. " << b[3] << ") contains no face centre of"
                            << " the area mesh (x " << mb.min().x() + offset.x() << " .. "
                            << mb.max().x() + offset.x() << ", y " << mb.min().y() + offset.y() << " .. "
                            << mb.max().y() + offset.y() << "): outside the meshed terrain, in another"
                            << " CRS, or smaller than a face" << exit(FatalIOError);
                    }
                }
                gf_polygons_free(&P);
            }
            Info<< "    " << type << ": " << returnReduce(nSet, sumOp<label>()) << " faces" << endl;
        }
        forAll(hNew, i)
        {
            if (!(hNew[i] >= 0) || !std::isfinite(hNew[i]))
            {
                FatalIOErrorInFunction(dict)
                    << dictFile << ": " << fieldName << " = " << hNew[i] << " at face " << i << " (centre " << C[i]
                    << ") is negative or not finite" << exit(FatalIOError);
            }
        }
        return hNew;
    };

    // what was written
    auto report = [&](const scalarField& hNew)
    {
        if (fieldName == "resistance")
        {
            Info<< "Wrote resistance: area " << gSum(pos(hNew)*aMesh.S().field()) << " m2, max factor "
                << gMax(hNew) << endl;
        }
        else
        {
            Info<< "Wrote " << fieldName << ": volume " << gSum(hNew*aMesh.S().field()) << " m3, max "
                << gMax(hNew) << " m" << endl;
        }
    };

    // the release velocity of the dictionary's Us (optional): its tangential part
    autoPtr<areaVectorField> UsPtr;
    vector u0 = Zero;
    if (kw::readIfPresent<vector>(dict, rt, "Us", u0))
    {
        UsPtr.reset
        (
            new areaVectorField
            (
                IOobject("Us", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE),
                aMesh
            )
        );
        const vector u = u0;
        UsPtr->primitiveFieldRef() = u - N*(N & u);   // tangential part
        UsPtr->correctBoundaryConditions();
    }

    if (samples.empty())
    {
        const scalarField hNew(compute(ci95On, ci95Sample));
        field.primitiveFieldRef() = hNew;
        field.correctBoundaryConditions();
        field.write();
        report(hNew);
        if (UsPtr.valid())
        {
            UsPtr->write();
            Info<< "Wrote Us" << endl;
        }
        Info<< "End" << endl;
        return 0;
    }

    // -ci95Samples: one field per line of the list, into DIR/NAME/ as the
    // field's own write() would put it into the time folder (the header, the
    // data and the end divider, in the controlDict's format and precision;
    // regIOobject::writeObject), the case's own fields untouched; a member
    // whose thickness is refused gets DIR/NAME.refused (the reason) and the
    // others go on
    auto writeTo = [&](const regIOobject& f, const fileName& file)
    {
        mkDir(file.path());
        OFstream os(file, runTime.writeFormat(), IOstream::currentVersion, runTime.writeCompression());
        const bool ok = os.good() && f.writeHeader(os) && f.writeData(os);
        IOobject::writeEndDivider(os);
        if (!ok || !os.good())
        {
            FatalErrorInFunction << "Cannot write " << file << exit(FatalError);
        }
    };
    const bool throwing = FatalError.throwExceptions(), ioThrowing = FatalIOError.throwExceptions();
    label nWritten = 0;
    DynamicList<word> refused;
    for (const Tuple2<word, scalar>& smp : samples)
    {
        const fileName dir(samplesOut/smp.first());
        if (isDir(dir)) rmDir(dir);
        if (isFile(dir + ".refused")) rm(dir + ".refused");
        Info<< nl << "Release " << smp.first() << " (-ci95Sample " << smp.second() << "):" << endl;
        try
        {
            checkSample(smp.second());
            const scalarField hNew(compute(true, smp.second()));
            field.primitiveFieldRef() = hNew;
            field.correctBoundaryConditions();
            writeTo(field, dir/field.name());
            report(hNew);
            if (UsPtr.valid())
            {
                writeTo(UsPtr(), dir/"Us");
                Info<< "Wrote Us" << endl;
            }
            ++nWritten;
        }
        catch (const Foam::error& e)
        {
            string why(e.message());
            why.replaceAll("\n", " ");
            OFstream(dir + ".refused")() << why.c_str() << nl;
            Info<< "Refused " << smp.first() << ": " << why.c_str() << endl;
            refused.append(smp.first());
        }
    }
    FatalError.throwExceptions(throwing);
    FatalIOError.throwExceptions(ioThrowing);
    Info<< nl << "Wrote " << fieldName << " of " << nWritten << " of the " << samples.size()
        << " samples of " << samplesFile << " into " << samplesOut << "/NAME/";
    if (refused.size())
    {
        Info<< "; refused " << refused.size() << " (NAME.refused: the reason):";
        for (const word& r : refused) Info<< ' ' << r;
    }
    Info<< nl << "End" << endl;
    return 0;
}
