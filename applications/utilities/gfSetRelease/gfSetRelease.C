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

    An ensemble member's release (gfRunEnsemble; doc/theory/hazard-analysis.md, section 4): with -ci95Sample z (z in [-1, 1]) every
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

#include "release.H"
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
    granflow::release rel(mesh, aMesh, dictName);
    if (samples.empty())
    {
        const scalarField hNew(rel.compute(ci95On, ci95Sample));
        rel.set(hNew);
        rel.write(hNew);
        Info<< "End" << endl;
        return 0;
    }
    areaScalarField& field = rel.field();
    const word& fieldName = rel.name();
    autoPtr<areaVectorField>& UsPtr = rel.Us();

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
            const scalarField hNew(rel.compute(true, smp.second()));
            rel.set(hNew);
            writeTo(field, dir/field.name());
            rel.report(hNew);
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
