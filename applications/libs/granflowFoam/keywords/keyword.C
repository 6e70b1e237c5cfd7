/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "keyword.H"
#include "faMesh.H"
#include "argList.H"

#include "granflow/version.h"

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>

namespace
{

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

double number(const std::string& s)
{
    const std::string t = trim(s);
    if (t == "inf") return std::numeric_limits<double>::infinity();
    if (t == "-inf") return -std::numeric_limits<double>::infinity();
    return std::stod(t);
}

struct interval
{
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool loOpen = false, hiOpen = false;
};

// "(a, b]", "> a", ">= a", "< a", "<= a", "" (any); false: not an interval
bool parseInterval(const std::string& text, interval& iv)
{
    const std::string a = trim(text);
    iv = interval();
    if (a.empty()) return true;
    if (a.compare(0, 2, ">=") == 0) { iv.lo = number(a.substr(2)); return true; }
    if (a.compare(0, 2, "<=") == 0) { iv.hi = number(a.substr(2)); return true; }
    if (a[0] == '>') { iv.lo = number(a.substr(1)); iv.loOpen = true; return true; }
    if (a[0] == '<') { iv.hi = number(a.substr(1)); iv.hiOpen = true; return true; }
    if ((a[0] == '(' || a[0] == '[') && (a.back() == ')' || a.back() == ']'))
    {
        const auto c = a.find(',');
        iv.lo = number(a.substr(1, c - 1));
        iv.hi = number(a.substr(c + 1, a.size() - c - 2));
        iv.loOpen = a[0] == '(';
        iv.hiOpen = a.back() == ')';
        return true;
    }
    return false;
}

std::vector<std::string> choices(const std::string& text)
{
    std::vector<std::string> out;
    std::stringstream ss(text);
    std::string c;
    while (std::getline(ss, c, '|'))
    {
        if (!trim(c).empty()) out.push_back(trim(c));
    }
    return out;
}

std::string join(const std::vector<std::string>& v, const char* sep, const char* last)
{
    std::string s;
    for (size_t i = 0; i < v.size(); ++i)
    {
        s += (i == 0 ? "" : i + 1 == v.size() ? last : sep) + v[i];
    }
    return s;
}

// " <unit>" for messages ("" and "-": dimensionless)
std::string unitText(const Foam::granflow::keyword::row& r)
{
    return r.unit.empty() || r.unit == "-" ? "" : " " + r.unit;
}

bool matches(const Foam::granflow::keyword::row& r, const std::string& variant)
{
    return variant.empty() || r.applies.empty() || r.applies == variant;
}

std::string forVariant(const Foam::granflow::keyword::table& t, const std::string& variant)
{
    return variant.empty() || t.variantKey.empty() ? "" : " for " + t.variantKey + " " + variant;
}

} // namespace


const Foam::granflow::keyword::table& Foam::granflow::keyword::get(const std::string& name)
{
    for (const table& t : all())
    {
        if (t.name == name) return t;
    }
    FatalErrorInFunction << "granflow: no keyword table " << name.c_str() << exit(FatalError);
    return all().front();
}


const Foam::granflow::keyword::row& Foam::granflow::keyword::find
(
    const table& t, const std::string& key, const std::string& variant
)
{
    for (const row& r : t.rows)
    {
        if (r.key == key && matches(r, variant)) return r;
    }
    const std::string msg =
        "granflow: key " + key + " is not in the keyword table " + t.name
      + (variant.empty() ? "" : " for " + variant)
      + " (applications/libs/granflowFoam/keywords/keywordTables.C)";
    FatalErrorInFunction << msg.c_str() << exit(FatalError);
    return t.rows.front();
}


bool Foam::granflow::keyword::inRange(const row& r, double v)
{
    interval iv;
    if (parseInterval(r.allowed, iv))
    {
        return (iv.loOpen ? v > iv.lo : v >= iv.lo) && (iv.hiOpen ? v < iv.hi : v <= iv.hi);
    }
    for (const std::string& c : choices(r.allowed))   // numeric choices "1 | 2"
    {
        if (number(c) == v) return true;
    }
    return false;
}


bool Foam::granflow::keyword::isChoice(const row& r, const std::string& w)
{
    const std::vector<std::string> c = choices(r.allowed);
    if (c.empty()) return true;
    for (const std::string& s : c)
    {
        if (s == w) return true;
    }
    return false;
}


std::string Foam::granflow::keyword::allowedText(const row& r)
{
    interval iv;
    if (r.type == "switch") return "on/off, yes/no, true/false";
    if (r.allowed.empty()) return "any " + r.type;
    if (parseInterval(r.allowed, iv)) return r.allowed;
    return join(choices(r.allowed), ", ", " or ");
}


// (OpenFOAM's Ostream quotes a std::string: the messages are made as one
// std::string and written as characters)
void Foam::granflow::keyword::invalid
(
    const dictionary& dict, const table& t, const row& r, const std::string& value,
    const std::string& variant
)
{
    const std::string msg =
        "Invalid entry " + t.path + r.key + " " + value + " in " + t.file + ": allowed "
      + allowedText(r) + unitText(r) + forVariant(t, variant)
      + " (" + r.description + ")";
    FatalIOErrorInFunction(dict) << msg.c_str() << exit(FatalIOError);
    std::abort();
}


void Foam::granflow::keyword::missing(const dictionary& dict, const table& t, const row& r)
{
    const std::string msg =
        "Missing entry " + t.path + r.key + " in " + t.file + ": " + r.type
      + (r.allowed.empty() ? "" : ", allowed " + allowedText(r))
      + unitText(r)
      + (r.deflt.compare(0, 10, "required (") == 0
         ? ", reference value " + r.deflt.substr(10, r.deflt.size() - 11) : std::string())
      + " (" + r.description + ")";
    FatalIOErrorInFunction(dict) << msg.c_str() << exit(FatalIOError);
    std::abort();
}


void Foam::granflow::keyword::checkKeys
(
    const dictionary& dict, const table& t, const std::string& variant
)
{
    for (const word& key : dict.toc())
    {
        if (key == "FoamFile") continue;
        bool ok = false;
        for (const row& r : t.rows)
        {
            ok = ok || (r.key == key && matches(r, variant));
        }
        if (!ok)
        {
            std::vector<std::string> valid;
            for (const row& r : t.rows)
            {
                if (matches(r, variant)) valid.push_back(r.key);
            }
            const std::string msg =
                "Unknown entry " + t.path + key + " in " + t.file + forVariant(t, variant)
              + "; valid entries: " + join(valid, ", ", ", ");
            FatalIOErrorInFunction(dict) << msg.c_str() << exit(FatalIOError);
        }
    }
}


bool Foam::granflow::keyword::found(const dictionary& dict, const table& t, const std::string& key)
{
    return dict.found(find(t, key).key);
}


const Foam::dictionary& Foam::granflow::keyword::subDict
(
    const dictionary& dict, const table& t, const std::string& key
)
{
    const row& r = find(t, key);
    if (!dict.isDict(r.key))
    {
        const std::string msg =
            "Missing sub-dictionary " + t.path + r.key + " in " + t.file + " (" + r.description + ")";
        FatalIOErrorInFunction(dict) << msg.c_str() << exit(FatalIOError);
    }
    return dict.subDict(r.key);
}


Foam::scalar Foam::granflow::keyword::relaxationFactor
(
    const faMesh& mesh, const std::string& name, scalar preset, bool& fromFile
)
{
    const table& t = get("faSolution/relaxationFactors");
    const row& r = find(t, name);
    fromFile = mesh.relaxEquation(r.key);
    if (!fromFile)
    {
        return preset;
    }
    const scalar alpha = mesh.equationRelaxationFactor(r.key);
    check<scalar>(mesh.solutionDict(), t, r, alpha, "");
    return alpha;
}


void Foam::granflow::keyword::printMarkdown(std::ostream& os)
{
    auto cell = [](const std::string& s)
    {
        std::string o;
        for (const char c : s)
        {
            if (c == '|') o += "\\|";
            else o += c;
        }
        return o;
    };
    for (const table& t : all())
    {
        os  << "### `" << t.file << "`" << (t.path.empty() ? "" : " " + t.path.substr(0, t.path.size() - 1))
            << "\n\n" << t.description << " Read by " << t.program << ". "
            << (t.closed ? "An entry not listed here is an error." :
                "Other entries of this file belong to OpenFOAM.") << "\n\n"
            << "| key | type | default | allowed | unit | applies to | description |\n"
            << "|---|---|---|---|---|---|---|\n";
        for (const row& r : t.rows)
        {
            os  << "| `" << r.key << "` | " << r.type << " | " << cell(r.deflt) << " | "
                << cell(r.allowed.empty() && r.type != "switch" ? "" : allowedText(r)) << " | "
                << cell(r.unit) << " | " << cell(r.applies) << " | " << cell(r.description) << " |\n";
        }
        os  << "\n";
    }
}


bool Foam::granflow::keyword::earlyOptions(int argc, char* argv[])
{
    for (int i = 1; i < argc; ++i)
    {
        if (!std::strcmp(argv[i], "-keywords"))
        {
            printMarkdown(std::cout);
            return true;
        }
        if (!std::strcmp(argv[i], "-version") || !std::strcmp(argv[i], "--version"))
        {
            const char* slash = std::strrchr(argv[0], '/');
            std::cout << "granflow " << gf_version() << " (" << (slash ? slash + 1 : argv[0])
                      << ", OpenFOAM v1912)"
                      << std::endl;
            return true;
        }
    }
    return false;
}


void Foam::granflow::keyword::addOptions()
{
    argList::addBoolOption("keywords", "print the keyword reference (Markdown) and exit");
    argList::addBoolOption("version", "print the granflow version and exit");
}


void Foam::granflow::keyword::banner()
{
    Info<< "granflow " << gf_version() << nl << endl;
}
