#include "vtkIGAGeoPDEsReader.h"

#include "IGAReadError.h"
#include "IGATextLines.h"

#include "vtkIGANurbsData.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkIGAGeoPDEsReader);

namespace
{
/// The major version a comment names ("nurbs geometry v.2.1", "nurbs mesh v.0.7"), or -1.
/// Searched by hand: std::regex recurses once per character matched, and a line of a hundred
/// thousand digits overflowed the stack.
int versionOf(const std::string& line, long number)
{
  for (const char* kind : { "nurbs geometry v.", "nurbs mesh v." })
  {
    const size_t at = line.find(kind);
    if (at == std::string::npos)
    {
      continue;
    }
    const size_t begin = at + std::strlen(kind);
    size_t end = begin;
    while (end < line.size() && end - begin <= 4 && std::isdigit((unsigned char)line[end]))
    {
      ++end;
    }
    if (end == begin)
    {
      continue;
    }
    if (end - begin > 4)
    {
      throw IGAReadError(number, "'" + line.substr(at, 24) + "...' names no GeoPDEs version");
    }
    return std::stoi(line.substr(begin, end - begin));
  }
  return -1;
}

template<int Dim>
void readPatch(IGATextLines& lines, int rdim, iga::BSplinePatch<double, Dim>& patch)
{
  // An optional name line ("PATCH 1"): anything that is not a line of numbers.
  std::vector<double> probe;
  if (!IGATextLines::parseNumbers(lines.peek("a patch").text, probe))
  {
    lines.take("a patch name");
  }
  const auto degrees = lines.integers("degrees", Dim, 1, iga::kMaxDegree);
  const auto counts = lines.integers("numbers of control points", Dim, 1, 1000000);
  size_t points = 1;
  for (int d = 0; d < Dim; ++d)
  {
    const std::string what = "knot vector " + std::to_string(d + 1);
    const long number = lines.peek(what.c_str()).number;
    auto knots = lines.numbers(what.c_str(), counts[d] + degrees[d] + 1);
    try
    {
      iga::validateKnotVector(knots, degrees[d], counts[d]);
    }
    catch (const std::invalid_argument& e)
    {
      throw IGAReadError(number, what + ": " + e.what());
    }
    patch.degree[d] = degrees[d];
    patch.netSize[d] = counts[d];
    patch.knots[d] = std::move(knots);
    points *= static_cast<size_t>(counts[d]);
  }
  static const char* const kCoordinates[3] = { "weighted x coordinates", "weighted y coordinates",
    "weighted z coordinates" };
  std::vector<double> coordinates[3];
  for (int c = 0; c < rdim; ++c)
  {
    coordinates[c] = lines.numbers(kCoordinates[c], static_cast<long>(points));
  }
  const long weightLine = lines.peek("weights").number;
  const auto weights = lines.numbers("weights", static_cast<long>(points));
  std::vector<double> euclidean(3 * points, 0.0);
  for (size_t p = 0; p < points; ++p)
  {
    if (!(weights[p] > 0))
    {
      throw IGAReadError(weightLine, "weights: weight " + std::to_string(p + 1) + " is " +
                                       std::to_string(weights[p]) + ", weights must be positive");
    }
    for (int c = 0; c < rdim; ++c)
    {
      euclidean[3 * p + c] = coordinates[c][p] / weights[p];
    }
  }
  iga::setGeometryNet(patch, euclidean, weights);
}

/// The kinds of section in the order a GeoPDEs file holds them.
const char* const kSectionKinds[4] = { "PATCH", "INTERFACE", "SUBDOMAIN", "BOUNDARY" };

/// The kind (index in kSectionKinds) a section's name line begins with, or -1 for free text.
int sectionKind(const IGATextLine& line)
{
  std::istringstream in(line.text);
  std::string word;
  in >> word;
  const auto* kind = std::find(kSectionKinds, kSectionKinds + 4, word);
  return kind == kSectionKinds + 4 ? -1 : int(kind - kSectionKinds);
}

/// One side "patch side" of an interface or boundary, checked against the patches.
void readSide(IGATextLines& lines, const char* what, int ndim, int patches)
{
  const long number = lines.peek(what).number;
  const auto side = lines.integers(what, 2, 1, 1000000);
  if (side[0] > patches || side[1] > 2 * ndim)
  {
    throw IGAReadError(number, std::string(what) + ": patch " + std::to_string(side[0]) + " side " +
                                 std::to_string(side[1]) + " does not exist");
  }
}

/// Checks the sections after the patches as GeoPDEs reads them: the header's count of
/// interfaces (a name, two sides, an orientation), then of subdomains (a name, the patches),
/// then boundaries to the end (a name, a count, the sides). Names are free text (GeoPDEs' own
/// files have "EXTERNAL BOUNDARY"); one that begins a kind of section where the counts say
/// another follows means the header's counts are wrong, and says so.
void checkSections(IGATextLines& lines, int ndim, int patches, int interfaces, int subdomains)
{
  const int counts[3] = { patches, interfaces, subdomains };
  const char* const plural[4] = { "patches", "interfaces", "subdomains", "boundaries" };
  // A section named for a kind the file should be past means the header counted too few of it;
  // one named for a kind still to come means it counted too many of the current one.
  const auto checkName = [&](const IGATextLine& name, int expected, int found)
  {
    const int kind = sectionKind(name);
    if (kind >= 0 && kind < expected)
    {
      throw IGAReadError(name.number, "'" + name.text + "' follows where " + plural[expected] +
                                        " do: more " + plural[kind] + " than the header's " +
                                        std::to_string(counts[kind]));
    }
    if (kind > expected)
    {
      throw IGAReadError(name.number, "'" + name.text + "': the header announces " +
                                        std::to_string(counts[expected]) + " " + plural[expected] +
                                        ", the file has " + std::to_string(found));
    }
  };
  for (int k = 0; k < interfaces; ++k)
  {
    checkName(lines.take("an interface"), 1, k);
    readSide(lines, "interface side", ndim, patches);
    readSide(lines, "interface side", ndim, patches);
    lines.integers("interface orientation", ndim == 3 ? 3 : 1, -1, 1);
  }
  for (int k = 0; k < subdomains; ++k)
  {
    checkName(lines.take("a subdomain"), 2, k);
    lines.integers("subdomain patches", -1, 1, patches);
  }
  while (!lines.atEnd())
  {
    checkName(lines.take("a boundary"), 3, 0);
    const int sides = lines.integers("number of boundary sides", 1, 0, 1000000)[0];
    for (int k = 0; k < sides; ++k)
    {
      readSide(lines, "boundary side", ndim, patches);
    }
  }
}
}

void vtkIGAGeoPDEsReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

bool vtkIGAGeoPDEsReader::IsOwnFormat(const std::string& head) const
{
  // GeoPDEs writes its format and version in the first comments.
  return head.find("nurbs geometry v.") != std::string::npos ||
         head.find("nurbs mesh v.") != std::string::npos;
}

std::string vtkIGAGeoPDEsReader::ReadNurbs(const std::string& text, vtkIGANurbsData* data)
{
  iga::NurbsSet<double> set;
  set.attributeNames = iga::geometryAttributeNames();
  try
  {
    int major = -1; // the version the first comment naming one names
    IGATextLines lines(text, '#',
      [&major](const std::string& comment, long number)
      {
        if (major < 0)
          major = versionOf(comment, number);
      });
    const long headerLine = lines.peek("the header (dimensions and number of patches)").number;
    const auto header = lines.integers("header (dimensions and number of patches)", -1, 0, 1000000);
    // v.0.x: "N Np [Ni Ns]"; v.1 and later: "ndim rdim Np [Ni Ns]".
    const bool old = major == 0;
    const size_t dims = old ? 1 : 2;
    if (header.size() < dims || header.size() > dims + 3)
    {
      throw IGAReadError(
        headerLine, "header: " + std::to_string(header.size()) + " values, expected " +
                      (old ? "N Np [Ni Ns] (v.0.7)" : "ndim rdim Np [Ni Ns] (v.2.1)"));
    }
    const int ndim = header[0];
    const int rdim = old ? header[0] : header[1];
    const int patches = header.size() > dims ? header[dims] : 1;
    const int interfaces = header.size() > dims + 1 ? header[dims + 1] : 0;
    const int subdomains = header.size() > dims + 2 ? header[dims + 2] : 0;
    if (ndim < 2 || ndim > 3 || rdim < ndim || rdim > 3)
    {
      throw IGAReadError(headerLine, "header: parametric dimension " + std::to_string(ndim) +
                                       " in physical dimension " + std::to_string(rdim) +
                                       " is not supported (volumes 3 in 3, surfaces 2 in 2 or 3)");
    }
    if (patches < 1)
    {
      throw IGAReadError(headerLine, "header: the number of patches is 0");
    }
    for (int p = 0; p < patches; ++p)
    {
      if (ndim == 3)
      {
        set.volumes.emplace_back();
        readPatch(lines, rdim, set.volumes.back());
      }
      else
      {
        set.surfaces.emplace_back();
        readPatch(lines, rdim, set.surfaces.back());
      }
    }
    checkSections(lines, ndim, patches, interfaces, subdomains);
  }
  catch (const IGAReadError& e)
  {
    return e.what();
  }
  return data->SetPatches(set);
}
