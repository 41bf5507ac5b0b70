#include "vtkIGAGismoReader.h"

#include "IGAReadError.h"
#include "IGAXMLDocument.h"

#include "vtkBase64Utilities.h"
#include "vtkByteSwap.h"
#include "vtkIGANurbsData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkIGAGismoReader);

namespace
{
class GismoParser
{
public:
  explicit GismoParser(const std::string& text)
    : Text(text)
  {
  }

  long lineOf(const vtkXMLDataElement* element) const
  {
    const auto end = static_cast<size_t>(
      std::clamp<vtkTypeInt64>(const_cast<vtkXMLDataElement*>(element)->GetXMLByteIndex(), 0,
        static_cast<vtkTypeInt64>(this->Text.size())));
    return 1 + static_cast<long>(std::count(this->Text.begin(), this->Text.begin() + end, '\n'));
  }

  [[noreturn]] void fail(const vtkXMLDataElement* element, const std::string& what) const
  {
    throw IGAReadError(this->lineOf(element),
      "<" + std::string(const_cast<vtkXMLDataElement*>(element)->GetName()) + "> " + what);
  }

  /// The numbers in an element's text, as its format attribute says G+Smo wrote them: decimal
  /// text (ascii, the default) or base64 of little-endian doubles or floats (b64float64,
  /// b64float32; the flag in any case, as G+Smo reads it).
  std::vector<double> numbers(vtkXMLDataElement* element) const
  {
    const char* attribute = element->GetAttribute("format");
    std::string format = attribute ? attribute : "ascii";
    std::transform(format.begin(), format.end(), format.begin(),
      [](unsigned char c) { return char(std::tolower(c)); });
    if (format == "ascii")
    {
      return this->decimalNumbers(element);
    }
    if (format == "b64float64" || format == "b64float32")
    {
      return this->base64Numbers(element, attribute, format == "b64float64" ? 8 : 4);
    }
    this->fail(element,
      std::string("format '") + attribute + "' is not supported (ascii, b64float64, b64float32)");
  }

  std::vector<double> base64Numbers(
    vtkXMLDataElement* element, const char* format, size_t width) const
  {
    std::string text;
    for (const char* c = element->GetCharacterData() ? element->GetCharacterData() : ""; *c; ++c)
    {
      if (!std::isspace(static_cast<unsigned char>(*c)))
      {
        text += *c;
      }
    }
    const size_t padding = text.size() - std::min(text.size(), text.find_last_not_of('=') + 1);
    const bool base64 =
      text.size() % 4 == 0 && padding <= 2 &&
      std::all_of(text.begin(), text.end() - long(padding),
        [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/'; });
    std::vector<unsigned char> bytes(text.size() / 4 * 3);
    const size_t decoded =
      base64 && !text.empty()
        ? vtkBase64Utilities::DecodeSafely(reinterpret_cast<const unsigned char*>(text.data()),
            text.size(), bytes.data(), bytes.size())
        : 0;
    if (!base64 || decoded != bytes.size() - padding || decoded % width != 0)
    {
      this->fail(element, std::string("format '") + format + "': the text is not base64 of " +
                            (width == 8 ? "doubles" : "floats"));
    }
    std::vector<double> values(decoded / width);
    for (size_t k = 0; k < values.size(); ++k)
    {
      if (width == 8)
      {
        std::memcpy(&values[k], &bytes[8 * k], 8);
        vtkByteSwap::Swap8LE(&values[k]);
      }
      else
      {
        float value;
        std::memcpy(&value, &bytes[4 * k], 4);
        vtkByteSwap::Swap4LE(&value);
        values[k] = value;
      }
      if (!std::isfinite(values[k]))
      {
        this->fail(element,
          "value " + std::to_string(k + 1) + " is not finite (" + std::to_string(values[k]) + ")");
      }
    }
    return values;
  }

  std::vector<double> decimalNumbers(vtkXMLDataElement* element) const
  {
    std::vector<double> values;
    std::istringstream in(element->GetCharacterData() ? element->GetCharacterData() : "");
    std::string token;
    while (in >> token)
    {
      errno = 0;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || errno == ERANGE)
      {
        this->fail(element,
          "value " + std::to_string(values.size() + 1) + " '" + token + "' is not a number");
      }
      if (!std::isfinite(value))
      {
        this->fail(
          element, "value " + std::to_string(values.size() + 1) + " '" + token + "' is not finite");
      }
      values.push_back(value);
    }
    return values;
  }

  int integerAttribute(vtkXMLDataElement* element, const char* name) const
  {
    const char* text = element->GetAttribute(name);
    char* end = nullptr;
    const long value = text ? std::strtol(text, &end, 10) : 0;
    if (!text || end == text || *end != '\0' || value < -1000000 || value > 1000000)
    {
      this->fail(element, std::string("needs an integer attribute ") + name);
    }
    return static_cast<int>(value);
  }

  vtkXMLDataElement* child(vtkXMLDataElement* element, const char* name) const
  {
    vtkXMLDataElement* found = element->FindNestedElementWithName(name);
    if (!found)
    {
      this->fail(element, std::string("has no <") + name + "> element");
    }
    return found;
  }

  /// One Geometry element into `set`.
  void readGeometry(vtkXMLDataElement* geometry, iga::NurbsSet<double>& set) const
  {
    const std::string type = geometry->GetAttribute("type") ? geometry->GetAttribute("type") : "";
    static const std::map<std::string, std::pair<int, bool>> kTypes = {
      { "TensorBSpline3", { 3, false } }, { "TensorNurbs3", { 3, true } },
      { "TensorBSpline2", { 2, false } }, { "TensorNurbs2", { 2, true } }
    };
    const auto known = kTypes.find(type);
    if (known == kTypes.end())
    {
      this->fail(geometry, "type '" + type +
                             "' is not supported (TensorBSpline3, TensorNurbs3, TensorBSpline2, "
                             "TensorNurbs2)");
    }
    const int dim = known->second.first;
    const bool rational = known->second.second;
    if (dim == 3)
    {
      set.volumes.emplace_back();
      this->readPatch(geometry, rational, set.volumes.back());
    }
    else
    {
      set.surfaces.emplace_back();
      this->readPatch(geometry, rational, set.surfaces.back());
    }
  }

  template<int Dim>
  void readPatch(
    vtkXMLDataElement* geometry, bool rational, iga::BSplinePatch<double, Dim>& patch) const
  {
    const auto weights = this->readBasis(geometry, rational, patch);
    const size_t points = iga::controlPointCount(patch);
    vtkXMLDataElement* coefs = this->child(geometry, "coefs");
    const int geoDim = this->integerAttribute(coefs, "geoDim");
    if (geoDim != 2 && geoDim != 3)
    {
      this->fail(coefs, "geoDim " + std::to_string(geoDim) + " is not 2 or 3");
    }
    const auto values = this->coefficients(coefs, points, geoDim);
    std::vector<double> euclidean(3 * points, 0.0);
    for (size_t p = 0; p < points; ++p)
    {
      std::copy_n(values.begin() + p * geoDim, geoDim, euclidean.begin() + 3 * p);
    }
    iga::setGeometryNet(patch, euclidean, weights);
  }

  /// `points` rows of geoDim values.
  std::vector<double> coefficients(vtkXMLDataElement* coefs, size_t points, int geoDim) const
  {
    auto values = this->numbers(coefs);
    if (values.size() != points * geoDim)
    {
      this->fail(coefs, "has " + std::to_string(values.size()) + " values, expected " +
                          std::to_string(points * geoDim) + " (" + std::to_string(points) +
                          " control points of geoDim " + std::to_string(geoDim) + ")");
    }
    return values;
  }

  /// The patch's degrees, knots and net size from the Geometry's Basis; its weights (all 1 for a
  /// B-spline).
  template<int Dim>
  std::vector<double> readBasis(
    vtkXMLDataElement* geometry, bool rational, iga::BSplinePatch<double, Dim>& patch) const
  {
    vtkXMLDataElement* basis = this->child(geometry, "Basis");
    vtkXMLDataElement* weightsElement = nullptr;
    if (rational)
    {
      weightsElement = this->child(basis, "weights");
      basis = this->child(basis, "Basis");
    }
    // One BSplineBasis per direction, placed by its index attribute when it has one.
    int found = 0;
    for (int n = 0; n < basis->GetNumberOfNestedElements(); ++n)
    {
      vtkXMLDataElement* direction = basis->GetNestedElement(n);
      if (std::string(direction->GetName()) != "Basis")
      {
        continue;
      }
      const int d =
        direction->GetAttribute("index") ? this->integerAttribute(direction, "index") : found;
      if (d < 0 || d >= Dim || !patch.knots[d].empty())
      {
        this->fail(direction, "direction index " + std::to_string(d) + " is out of 0.." +
                                std::to_string(Dim - 1) + " or repeated");
      }
      vtkXMLDataElement* knotVector = this->child(direction, "KnotVector");
      const int degree = this->integerAttribute(knotVector, "degree");
      auto knots = this->numbers(knotVector);
      const int count = static_cast<int>(knots.size()) - degree - 1;
      try
      {
        iga::validateKnotVector(knots, degree, count);
      }
      catch (const std::invalid_argument& e)
      {
        this->fail(knotVector, "(direction " + std::to_string(d) + "): " + e.what());
      }
      patch.degree[d] = degree;
      patch.netSize[d] = count;
      patch.knots[d] = std::move(knots);
      ++found;
    }
    if (found != Dim)
    {
      this->fail(basis,
        "has " + std::to_string(found) + " direction bases, expected " + std::to_string(Dim));
    }
    const size_t points = iga::controlPointCount(patch);
    std::vector<double> weights(points, 1.0);
    if (weightsElement)
    {
      weights = this->numbers(weightsElement);
      if (weights.size() != points)
      {
        this->fail(weightsElement, "has " + std::to_string(weights.size()) + " values, expected " +
                                     std::to_string(points) + " (one per control point)");
      }
      for (size_t p = 0; p < points; ++p)
      {
        if (!(weights[p] > 0))
        {
          this->fail(weightsElement, "weight " + std::to_string(p + 1) + " is " +
                                       std::to_string(weights[p]) + ", weights must be positive");
        }
      }
    }
    return weights;
  }

  /// The file's top-level Geometry elements, by id, and its MultiPatch elements.
  struct Contents
  {
    std::vector<vtkXMLDataElement*> geometries, multiPatches;
    std::map<long long, vtkXMLDataElement*> byId;
  };

  Contents contents(vtkXMLDataElement* root) const
  {
    Contents found;
    for (int n = 0; n < root->GetNumberOfNestedElements(); ++n)
    {
      vtkXMLDataElement* element = root->GetNestedElement(n);
      const std::string name = element->GetName();
      if (name == "Geometry")
      {
        found.geometries.push_back(element);
        if (element->GetAttribute("id"))
        {
          found.byId[this->integerAttribute(element, "id")] = element;
        }
      }
      else if (name == "MultiPatch")
      {
        found.multiPatches.push_back(element);
      }
    }
    if (found.geometries.empty() && found.multiPatches.empty())
    {
      this->fail(root, "has no <Geometry> or <MultiPatch> element");
    }
    return found;
  }

  /// The Geometry elements of the geometry: the first MultiPatch's, or all top-level ones.
  std::vector<vtkXMLDataElement*> selectGeometries(const Contents& contents) const
  {
    return contents.multiPatches.empty() ? contents.geometries
                                         : this->patchesOf(contents.multiPatches[0], contents);
  }

  /// A MultiPatch's Geometry elements: nested in it, then those its <patches> name.
  std::vector<vtkXMLDataElement*> patchesOf(
    vtkXMLDataElement* multiPatch, const Contents& contents) const
  {
    std::vector<vtkXMLDataElement*> selected;
    for (int n = 0; n < multiPatch->GetNumberOfNestedElements(); ++n)
    {
      vtkXMLDataElement* element = multiPatch->GetNestedElement(n);
      if (std::string(element->GetName()) == "Geometry")
      {
        selected.push_back(element);
      }
    }
    if (vtkXMLDataElement* patches = multiPatch->FindNestedElementWithName("patches"))
    {
      for (long long id : this->patchIds(patches))
      {
        const auto geometry = contents.byId.find(id);
        if (geometry == contents.byId.end())
        {
          this->fail(patches,
            "refers to geometry id " + std::to_string(id) + ", which no top-level <Geometry> has");
        }
        selected.push_back(geometry->second);
      }
    }
    if (selected.empty())
    {
      this->fail(multiPatch, "lists no patches");
    }
    return selected;
  }

  /// The ids a <patches> element lists (id_range: first..last; id_index: each).
  std::vector<long long> patchIds(vtkXMLDataElement* patches) const
  {
    const std::string type = patches->GetAttribute("type") ? patches->GetAttribute("type") : "";
    std::vector<long long> ids;
    for (double value : this->numbers(patches))
    {
      if (value != std::floor(value) || !(std::abs(value) <= 9007199254740992.0))
      {
        char number[32];
        std::snprintf(number, sizeof number, "%.17g", value);
        this->fail(patches, std::string("id ") + number + " is not an integer in -2^53..2^53");
      }
      ids.push_back(static_cast<long long>(value));
    }
    if (type == "id_range")
    {
      if (ids.size() != 2 || ids[1] < ids[0] || ids[1] - ids[0] > 1000000)
      {
        this->fail(patches, "of type id_range needs two ids, first <= last");
      }
      const long long first = ids[0], last = ids[1];
      ids.clear();
      for (long long id = first; id <= last; ++id)
      {
        ids.push_back(id);
      }
    }
    else if (type != "id_index")
    {
      this->fail(patches, "type '" + type + "' is not id_range or id_index");
    }
    return ids;
  }

  /// Every MultiPatch after the geometry's with a patch per geometry patch in the geometry's
  /// basis (G+Smo writes a solution so): its coefficients, geoDim of them per control point, as
  /// attributes named by its label (field1, field2, ... without one), a vector's components
  /// NAME_0, NAME_1, ... `order[k]` says where geometry patch k went: (volume?, index).
  void readFields(const Contents& contents, const std::vector<std::pair<bool, size_t>>& order,
    iga::NurbsSet<double>& set) const
  {
    for (size_t f = 1; f < contents.multiPatches.size(); ++f)
    {
      vtkXMLDataElement* multiPatch = contents.multiPatches[f];
      const auto patches = this->patchesOf(multiPatch, contents);
      if (patches.size() != order.size())
      {
        this->fail(multiPatch, "has " + std::to_string(patches.size()) + " patches, the geometry " +
                                 std::to_string(order.size()) +
                                 ": a field has one patch per geometry patch");
      }
      const char* label = multiPatch->GetAttribute("label");
      const std::string name = label && *label ? label : "field" + std::to_string(f);
      int components = 0;
      for (size_t k = 0; k < patches.size(); ++k)
      {
        components = order[k].first
                       ? this->readField(patches[k], set.volumes[order[k].second], components)
                       : this->readField(patches[k], set.surfaces[order[k].second], components);
      }
      for (int c = 0; c < components; ++c)
      {
        set.attributeNames.push_back(components == 1 ? name : name + "_" + std::to_string(c));
      }
    }
  }

  /// One patch of a field onto geometry patch `target`: its basis must be the target's; returns
  /// its geoDim (which must equal `components` when that is set).
  template<int Dim>
  int readField(
    vtkXMLDataElement* geometry, iga::BSplinePatch<double, Dim>& target, int components) const
  {
    const std::string type = geometry->GetAttribute("type") ? geometry->GetAttribute("type") : "";
    const std::string dim = std::to_string(Dim);
    if (type != "TensorBSpline" + dim && type != "TensorNurbs" + dim)
    {
      this->fail(geometry, "a field patch of type '" + type + "' on a geometry patch of " + dim +
                             " parameters (TensorBSpline" + dim + ", TensorNurbs" + dim + ")");
    }
    iga::BSplinePatch<double, Dim> field;
    const auto weights = this->readBasis(geometry, type == "TensorNurbs" + dim, field);
    for (int d = 0; d < Dim; ++d)
    {
      if (field.degree[d] != target.degree[d] || field.knots[d] != target.knots[d])
      {
        this->fail(geometry, "a field patch whose basis is not its geometry patch's (direction " +
                               std::to_string(d) + ")");
      }
    }
    // Its rational basis is the geometry's when the weights agree (to a common factor).
    const size_t points = iga::controlPointCount(target);
    const double scale = weights[0] / target.net[iga::kWeightChannel];
    for (size_t p = 0; p < points; ++p)
    {
      const double mine = weights[p],
                   theirs = target.net[p * target.channels + iga::kWeightChannel];
      if (std::abs(mine - scale * theirs) > 1e-12 * std::abs(mine))
      {
        this->fail(geometry, "a field patch whose weights are not its geometry patch's (control "
                             "point " +
                               std::to_string(p + 1) + "): not in the geometry's basis");
      }
    }
    vtkXMLDataElement* coefs = this->child(geometry, "coefs");
    const int geoDim = this->integerAttribute(coefs, "geoDim");
    if (geoDim < 1 || geoDim > 3 || (components > 0 && geoDim != components))
    {
      this->fail(coefs, "geoDim " + std::to_string(geoDim) + " is not 1..3" +
                          (components > 0 ? " and the field's " + std::to_string(components) : ""));
    }
    iga::appendAttributes(target, this->coefficients(coefs, points, geoDim), geoDim);
    return geoDim;
  }

private:
  const std::string& Text;
};

} // namespace

void vtkIGAGismoReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

bool vtkIGAGismoReader::IsOwnFormat(const std::string& head) const
{
  // G+Smo's root element is <xml>, holding geometries (or a multipatch of them).
  return head.find("<xml") != std::string::npos && (head.find("<Geometry") != std::string::npos ||
                                                     head.find("<MultiPatch") != std::string::npos);
}

std::string vtkIGAGismoReader::ReadNurbs(const std::string& text, vtkIGANurbsData* data)
{
  std::string error;
  const auto parser = igaParseXML(text, error);
  if (!parser)
  {
    return error;
  }
  GismoParser gismo(text);
  iga::NurbsSet<double> set;
  set.attributeNames = iga::geometryAttributeNames();
  try
  {
    const auto contents = gismo.contents(parser->GetRootElement());
    std::vector<std::pair<bool, size_t>> order; // where each geometry patch went
    for (vtkXMLDataElement* geometry : gismo.selectGeometries(contents))
    {
      const size_t volumes = set.volumes.size();
      gismo.readGeometry(geometry, set);
      const bool volume = set.volumes.size() > volumes;
      order.emplace_back(volume, volume ? volumes : set.surfaces.size() - 1);
    }
    gismo.readFields(contents, order, set);
  }
  catch (const IGAReadError& e)
  {
    return e.what();
  }
  // Volumes precede surfaces in the output whatever the file's order; the description is
  // already checked, so this only fails on limits such as degrees above iga::kMaxDegree.
  return data->SetPatches(set);
}
