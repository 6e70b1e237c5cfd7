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
        );

    Later regions override earlier ones where they give a value; a
    sphericalCap sets h only where the sphere lies above the surface.  Writes
    h (and Us) into the start time folder.  Unknown region types and missing
    entries are FatalIOErrors naming them.
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "faCFD.H"
#include "Function1.H"

int main(int argc, char *argv[])
{
    argList::addNote("Set the initial flow thickness h (and Us) from system/releaseDict");
    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"
    #include "createFaMesh.H"

    IOdictionary dict
    (
        IOobject("releaseDict", runTime.system(), mesh, IOobject::MUST_READ, IOobject::NO_WRITE)
    );

    areaScalarField h
    (
        IOobject("h", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE),
        aMesh
    );
    const vectorField& C = aMesh.areaCentres().primitiveField();
    const vectorField& N = aMesh.faceAreaNormals().primitiveField();

    scalarField hNew(h.size(), dict.get<scalar>("default"));

    const PtrList<entry> regions(dict.lookup("regions"));
    for (const entry& e : regions)
    {
        if (!e.isDict())
        {
            FatalIOErrorInFunction(dict)
                << "regions: entry " << e.keyword() << " is not a dictionary" << exit(FatalIOError);
        }
        const word type = e.keyword();
        const dictionary& r = e.dict();
        label nSet = 0;
        if (type == "sphericalCap")
        {
            const vector c = r.get<vector>("centre");
            const scalar rad = r.get<scalar>("radius");
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
            const vector p1 = r.get<vector>("point1"), p2 = r.get<vector>("point2");
            const scalar rad = r.get<scalar>("radius");
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
            const boundBox bb(r.get<vector>("min"), r.get<vector>("max"));
            const scalar v = r.get<scalar>("value");
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
            const vector p1 = r.get<vector>("point1"), p2 = r.get<vector>("point2");
            const scalar rad = r.get<scalar>("radius"), v = r.get<scalar>("value");
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
            const word coord = r.get<word>("coordinate");
            autoPtr<Function1<scalar>> f = Function1<scalar>::New("h", r);
            const vector origin = r.getOrDefault<vector>("origin", Zero);
            forAll(C, i)
            {
                scalar x = 0;
                if (coord == "x") x = C[i].x();
                else if (coord == "y") x = C[i].y();
                else if (coord == "z") x = C[i].z();
                else if (coord == "distance") x = mag(C[i] - origin);
                else
                {
                    FatalIOErrorInFunction(r)
                        << "Invalid entry coordinate " << coord << "; valid: x, y, z, distance"
                        << exit(FatalIOError);
                }
                hNew[i] = f->value(x);
                ++nSet;
            }
        }
        else
        {
            FatalIOErrorInFunction(dict)
                << "Unknown region type " << type
                << "; valid types: sphericalCap, cylindricalCap, box, cylinder, function"
                << exit(FatalIOError);
        }
        Info<< "    " << type << ": " << returnReduce(nSet, sumOp<label>()) << " faces" << endl;
    }
    forAll(hNew, i)
    {
        if (!(hNew[i] >= 0) || !std::isfinite(hNew[i]))
        {
            FatalIOErrorInFunction(dict)
                << "flow thickness " << hNew[i] << " at face " << i << " (centre " << C[i]
                << ") is negative or not finite" << exit(FatalIOError);
        }
    }
    h.primitiveFieldRef() = hNew;
    h.correctBoundaryConditions();
    h.write();
    Info<< "Wrote h: volume " << gSum(hNew*aMesh.S().field()) << " m3, max " << gMax(hNew)
        << " m" << endl;

    if (dict.found("Us"))
    {
        areaVectorField Us
        (
            IOobject("Us", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE),
            aMesh
        );
        const vector u = dict.get<vector>("Us");
        Us.primitiveFieldRef() = u - N*(N & u);   // tangential part
        Us.correctBoundaryConditions();
        Us.write();
        Info<< "Wrote Us" << endl;
    }
    Info<< "End" << endl;
    return 0;
}
