#include "vtkIGANurbsData.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArrayCollection.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIGAAttributeRanges.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Orientation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace
{
const char* const kPatchArray = "NurbsPatch";
const char* const kSpanArray = "NurbsKnotSpan";
const char* const kInfoArray = "NurbsPatchInfo";
const char* const kKnotsArray = "NurbsKnots";
const char* const kNetArray = "NurbsControlNet";
const char* const kNamesArray = "NurbsAttributeNames";
const char* const kTimeArray = "NurbsTime";
constexpr int kInfoComponents = 7;

using Net = std::shared_ptr<const std::vector<double>>;

template<int Dim>
using Extraction = std::shared_ptr<const iga::BezierExtraction<double, Dim>>;

/// Builds the extraction of a patch and checks its net; throws std::invalid_argument naming the
/// patch by `name`.
template<int Dim>
Extraction<Dim> prepare(
  const iga::BSplinePatch<double, Dim>& patch, int channels, const std::string& name)
{
  try
  {
    if (patch.channels != channels)
    {
      throw std::invalid_argument("has " + std::to_string(patch.channels) +
                                  " channels, the set has " + std::to_string(channels));
    }
    auto extraction = std::make_shared<iga::BezierExtraction<double, Dim>>(
      patch.knots, patch.degree, patch.netSize);
    std::string problem = iga::checkControlNet(patch, patch.net);
    if (problem.empty())
    {
      problem = iga::skewedElementProblem(*extraction, patch.net, patch.channels);
    }
    if (!problem.empty())
    {
      throw std::invalid_argument(problem);
    }
    return extraction;
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(name + ": " + e.what());
  }
}

/// Checks a volume and makes it right-handed for VTK in place: one of negative signed volume
/// gets its first parametric direction reversed (the same volume). Returns its extraction.
Extraction<3> orientVolume(
  iga::BSplinePatch<double, 3>& patch, int channels, const std::string& name, bool& reversed)
{
  const std::string named = name + " (volume)";
  Extraction<3> extraction = prepare(patch, channels, named);
  reversed = iga::signedVolume(*extraction, patch.net, channels) < 0;
  if (!reversed)
  {
    return extraction;
  }
  iga::reverseDirection(patch, 0);
  return prepare(patch, channels, named);
}

template<class Patch>
struct PatchDimension;
template<int Dim>
struct PatchDimension<iga::BSplinePatch<double, Dim>> : std::integral_constant<int, Dim>
{
};

/// Control points of each Bézier element of a patch.
template<int Dim>
vtkIdType pointsPerElement(const iga::BSplinePatch<double, Dim>& patch, bool elevated = false)
{
  vtkIdType points = 1;
  for (int degree : patch.degree)
  {
    points *= degree + (elevated ? 2 : 1);
  }
  return points;
}

/// Whether a net's weights vary (a rational patch).
bool weightsVary(const std::vector<double>& net, size_t channels)
{
  for (size_t p = channels; p < net.size(); p += channels)
  {
    if (net[p + iga::kWeightChannel] != net[iga::kWeightChannel])
    {
      return true;
    }
  }
  return false;
}

/// What vtkIGANurbsData::ExactParameters changes: the channel of each parameter attribute
/// ("parameter_u/v/w", -1 where the set has none), and per patch (volumes, then surfaces) whether
/// its cells rise by one degree: exact parameters asked for, a parameter attribute to make exact,
/// every degree below kMaxDegree, and weights that vary in some time step (so that every step's
/// cells are alike).
struct ExactParameterCells
{
  int channel[3] = { -1, -1, -1 };
  std::vector<bool> elevated;

  ExactParameterCells(
    bool exact, const iga::NurbsSet<double>& set, const std::vector<std::vector<Net>>& steps)
    : elevated(size_t(set.patchCount()), false)
  {
    const char* const names[3] = { "parameter_u", "parameter_v", "parameter_w" };
    const auto& all = set.attributeNames;
    for (int d = 0; d < 3; ++d)
    {
      const auto found = std::find(all.begin(), all.end(), names[d]);
      this->channel[d] =
        found == all.end() ? -1 : iga::kFirstAttributeChannel + int(found - all.begin());
    }
    if (!exact || *std::max_element(this->channel, this->channel + 3) < 0)
    {
      return;
    }
    const auto below = [](const auto& patch) {
      return *std::max_element(std::begin(patch.degree), std::end(patch.degree)) < iga::kMaxDegree;
    };
    for (size_t p = 0; p < this->elevated.size(); ++p)
    {
      const bool volume = p < set.volumes.size();
      bool raised = volume ? below(set.volumes[p]) : below(set.surfaces[p - set.volumes.size()]);
      bool varies = false;
      for (size_t step = 0; raised && !varies && step < steps.size(); ++step)
      {
        varies = weightsVary(*steps[step][p], size_t(set.channels()));
      }
      this->elevated[p] = raised && varies;
    }
  }
};

/// Element e of a patch with exact parameters (iga::withExactParameters): the parameter runs over
/// the element's knot spans, against the stored direction where the volume was reversed.
template<int Dim>
iga::BezierPatch<double, Dim> exactParameterElement(const iga::BezierPatch<double, Dim>& element,
  const int* channel, const iga::BSplinePatch<double, Dim>& patch,
  const iga::BezierExtraction<double, Dim>& extraction, int e, bool reversed)
{
  int span[Dim];
  extraction.elementIndex(e, span);
  double start[Dim], end[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    start[d] = extraction.direction(d).spanStart[size_t(span[d])];
    end[d] = extraction.direction(d).spanEnd[size_t(span[d])];
  }
  if (reversed)
  {
    const double sum = patch.knots[0].front() + patch.knots[0].back();
    start[0] = sum - start[0];
    end[0] = sum - end[0];
  }
  return iga::withExactParameters(element, channel, start, end);
}

template<int Dim>
size_t knotCount(const iga::BSplinePatch<double, Dim>& patch)
{
  size_t count = 0;
  for (int d = 0; d < Dim; ++d)
  {
    count += patch.knots[d].size();
  }
  return count;
}
}

struct vtkIGANurbsData::State
{
  iga::NurbsSet<double> Set; // description; the nets live in Nets
  std::vector<double> Times;
  std::vector<std::vector<Net>> Nets; // [step][patch]
  std::vector<Extraction<3>> VolumeExtractions;
  std::vector<Extraction<2>> SurfaceExtractions;
  std::vector<bool> ReversedVolumes; // first direction reversed to be right-handed
};

vtkStandardNewMacro(vtkIGANurbsData);

vtkIGANurbsData::vtkIGANurbsData()
  : Contents(std::make_shared<State>())
{
}

vtkIGANurbsData::~vtkIGANurbsData() = default;

void vtkIGANurbsData::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const State& s = *this->Contents;
  os << indent << "Volumes: " << s.Set.volumes.size() << "\n";
  os << indent << "Surfaces: " << s.Set.surfaces.size() << "\n";
  os << indent << "Attributes:";
  for (const auto& name : s.Set.attributeNames)
  {
    os << " " << name;
  }
  os << "\n" << indent << "TimeSteps: " << s.Times.size() << "\n";
  os << indent << "BezierCells: " << this->GetNumberOfBezierCells() << "\n";
}

std::string vtkIGANurbsData::SetPatches(const iga::NurbsSet<double>& set, double time)
{
  // Left empty on error.
  this->Contents = std::make_shared<State>();
  this->Modified();
  if (!std::isfinite(time))
  {
    return "time " + std::to_string(time) + " is not finite";
  }
  auto state = std::make_shared<State>();
  state->Set = set;
  const int channels = set.channels();
  std::vector<Net> nets;
  try
  {
    for (size_t v = 0; v < set.volumes.size(); ++v)
    {
      bool reversed = false;
      state->VolumeExtractions.push_back(
        orientVolume(state->Set.volumes[v], channels, "patch " + std::to_string(v), reversed));
      state->ReversedVolumes.push_back(reversed);
      nets.push_back(std::make_shared<const std::vector<double>>(state->Set.volumes[v].net));
    }
    for (size_t s = 0; s < set.surfaces.size(); ++s)
    {
      const size_t index = set.volumes.size() + s;
      state->SurfaceExtractions.push_back(
        prepare(set.surfaces[s], channels, "patch " + std::to_string(index) + " (surface)"));
      nets.push_back(std::make_shared<const std::vector<double>>(set.surfaces[s].net));
    }
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  for (auto& volume : state->Set.volumes)
  {
    volume.net.clear();
  }
  for (auto& surface : state->Set.surfaces)
  {
    surface.net.clear();
  }
  state->Times.push_back(time);
  state->Nets.push_back(std::move(nets));
  this->Contents = state;
  return std::string();
}

std::string vtkIGANurbsData::AddTimeStep(double time, const std::vector<std::vector<double>>& nets)
{
  const State& current = *this->Contents;
  if (current.Times.empty())
  {
    return "there are no patches yet (call SetPatches first)";
  }
  if (!(time > current.Times.back()) || !std::isfinite(time))
  {
    return "time " + std::to_string(time) + " does not follow the last time step " +
           std::to_string(current.Times.back());
  }
  if (static_cast<int>(nets.size()) != current.Set.patchCount())
  {
    return std::to_string(nets.size()) + " control nets given for " +
           std::to_string(current.Set.patchCount()) + " patches";
  }
  const size_t volumes = current.Set.volumes.size();
  const int channels = current.Set.channels();
  // The nets as kept (a reversed volume's reversed), checked: control points in the caller's
  // numbering, elements in the kept one (a reversed volume's mirrored along u).
  std::vector<Net> kept;
  for (size_t p = 0; p < nets.size(); ++p)
  {
    const bool volume = p < volumes;
    std::string problem = volume ? iga::checkControlNet(current.Set.volumes[p], nets[p])
                                 : iga::checkControlNet(current.Set.surfaces[p - volumes], nets[p]);
    auto net = std::make_shared<std::vector<double>>(nets[p]);
    if (problem.empty() && volume && current.ReversedVolumes[p])
    {
      iga::reverseNetDirection(net->data(), current.Set.volumes[p].netSize, 3, channels, 0);
    }
    if (problem.empty())
    {
      problem = volume ? iga::skewedElementProblem(*current.VolumeExtractions[p], *net, channels)
                       : iga::skewedElementProblem(
                           *current.SurfaceExtractions[p - volumes], *net, channels);
    }
    if (!problem.empty())
    {
      return "time " + std::to_string(time) + ", patch " + std::to_string(p) + ": " + problem;
    }
    kept.push_back(std::move(net));
  }
  // Copy on write: a shallow copy keeps seeing the old steps.
  auto state = std::make_shared<State>(current);
  state->Times.push_back(time);
  state->Nets.push_back(std::move(kept));
  this->Contents = state;
  this->Modified();
  return std::string();
}

iga::NurbsSet<double> vtkIGANurbsData::GetPatches(int step) const
{
  iga::NurbsSet<double> set = this->Contents->Set;
  const size_t volumes = set.volumes.size();
  for (int p = 0; p < set.patchCount(); ++p)
  {
    const auto& net = this->GetControlNet(step, p);
    if (static_cast<size_t>(p) < volumes)
    {
      set.volumes[p].net = net;
    }
    else
    {
      set.surfaces[p - volumes].net = net;
    }
  }
  return set;
}

int vtkIGANurbsData::GetNumberOfPatches() const
{
  return this->Contents->Set.patchCount();
}

bool vtkIGANurbsData::IsVolumeReversed(int volume) const
{
  const auto& reversed = this->Contents->ReversedVolumes;
  return volume >= 0 && volume < static_cast<int>(reversed.size()) && reversed[volume];
}

int vtkIGANurbsData::GetNumberOfTimeSteps() const
{
  return static_cast<int>(this->Contents->Times.size());
}

std::vector<double> vtkIGANurbsData::GetTimeSteps() const
{
  return this->Contents->Times;
}

std::shared_ptr<const iga::BezierExtraction<double, 3>> vtkIGANurbsData::GetVolumeExtraction(
  int volume) const
{
  const auto& extractions = this->Contents->VolumeExtractions;
  return volume >= 0 && volume < static_cast<int>(extractions.size()) ? extractions[volume]
                                                                      : nullptr;
}

const std::vector<double>& vtkIGANurbsData::GetControlNet(int step, int patch) const
{
  static const std::vector<double> empty;
  const State& s = *this->Contents;
  if (step < 0 || step >= static_cast<int>(s.Nets.size()) || patch < 0 ||
      patch >= s.Set.patchCount())
  {
    return empty;
  }
  return *s.Nets[step][patch];
}

double vtkIGANurbsData::GetTimeStep(int step) const
{
  const auto& times = this->Contents->Times;
  return step >= 0 && step < static_cast<int>(times.size()) ? times[size_t(step)] : 0.0;
}

namespace
{
/// Calls fn(patch) with patch `index` of the set (a BSplinePatch of 3 or 2 directions); false
/// when out of range.
template<class Fn>
bool withPatch(const iga::NurbsSet<double>& set, int index, Fn&& fn)
{
  const int volumes = static_cast<int>(set.volumes.size());
  if (index >= 0 && index < volumes)
  {
    fn(set.volumes[size_t(index)]);
    return true;
  }
  if (index >= volumes && index < set.patchCount())
  {
    fn(set.surfaces[size_t(index - volumes)]);
    return true;
  }
  return false;
}

std::vector<double> valuesOf(vtkDataArray* array)
{
  std::vector<double> values;
  if (array)
  {
    values.resize(size_t(array->GetNumberOfValues()));
    for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
    {
      values[size_t(i)] = array->GetComponent(
        i / array->GetNumberOfComponents(), int(i % array->GetNumberOfComponents()));
    }
  }
  return values;
}

/// A patch from VTK arrays: degrees, knot vectors, a homogeneous net of `channels` components;
/// "" or the problem.
template<int Dim>
std::string patchFromArrays(const int* degrees, vtkDataArray* const* knots, vtkDataArray* net,
  int channels, iga::BSplinePatch<double, Dim>& patch)
{
  if (!net || net->GetNumberOfComponents() != channels)
  {
    return "the control net needs " + std::to_string(channels) +
           " components (w x, w y, w z, w and w a per attribute), it has " +
           std::to_string(net ? net->GetNumberOfComponents() : 0);
  }
  for (int d = 0; d < Dim; ++d)
  {
    if (!knots[d] || knots[d]->GetNumberOfComponents() != 1)
    {
      return "direction " + std::to_string(d) + " needs a knot vector of one component";
    }
    patch.degree[d] = degrees[d];
    patch.knots[d] = valuesOf(knots[d]);
    patch.netSize[d] = static_cast<int>(patch.knots[d].size()) - degrees[d] - 1;
  }
  patch.channels = channels;
  patch.net = valuesOf(net);
  return std::string();
}
}

int vtkIGANurbsData::GetPatchDimension(int patch) const
{
  int dimension = 0;
  withPatch(this->Contents->Set, patch,
    [&](const auto& p) { dimension = PatchDimension<std::decay_t<decltype(p)>>::value; });
  return dimension;
}

void vtkIGANurbsData::GetPatchDegrees(int patch, int degrees[3]) const
{
  std::fill(degrees, degrees + 3, 0);
  withPatch(this->Contents->Set, patch,
    [&](const auto& p) { std::copy(std::begin(p.degree), std::end(p.degree), degrees); });
}

void vtkIGANurbsData::GetPatchNetSize(int patch, int size[3]) const
{
  std::fill(size, size + 3, 1);
  withPatch(this->Contents->Set, patch,
    [&](const auto& p) { std::copy(std::begin(p.netSize), std::end(p.netSize), size); });
}

void vtkIGANurbsData::GetPatchKnots(int patch, int direction, vtkDoubleArray* knots) const
{
  if (!knots)
  {
    return;
  }
  knots->SetNumberOfTuples(0);
  // A turned volume's first knots back as given.
  const bool turned = direction == 0 && this->IsVolumeReversed(patch);
  withPatch(this->Contents->Set, patch,
    [&](const auto& p)
    {
      if (direction >= 0 && direction < PatchDimension<std::decay_t<decltype(p)>>::value)
      {
        for (double knot : turned ? iga::mirroredKnots(p.knots[0]) : p.knots[direction])
        {
          knots->InsertNextValue(knot);
        }
      }
    });
}

int vtkIGANurbsData::GetNumberOfAttributes() const
{
  return static_cast<int>(this->Contents->Set.attributeNames.size());
}

const char* vtkIGANurbsData::GetAttributeName(int index) const
{
  const auto& names = this->Contents->Set.attributeNames;
  return index >= 0 && index < static_cast<int>(names.size()) ? names[size_t(index)].c_str()
                                                              : nullptr;
}

void vtkIGANurbsData::GetPatchControlNet(int step, int patch, vtkDoubleArray* net) const
{
  if (!net)
  {
    return;
  }
  const int channels = this->Contents->Set.channels();
  const std::vector<double>& values = this->GetControlNet(step, patch);
  net->SetNumberOfComponents(channels);
  net->SetNumberOfTuples(vtkIdType(values.size() / size_t(channels)));
  std::copy(values.begin(), values.end(), net->GetPointer(0));
  if (!values.empty() && this->IsVolumeReversed(patch))
  {
    iga::reverseNetDirection(
      net->GetPointer(0), this->Contents->Set.volumes[size_t(patch)].netSize, 3, channels, 0);
  }
}

std::string vtkIGANurbsData::SetAttributeNames(vtkStringArray* names)
{
  if (this->GetNumberOfPatches() > 0)
  {
    return "attribute names are set before the patches, and there are " +
           std::to_string(this->GetNumberOfPatches());
  }
  auto state = std::make_shared<State>();
  for (vtkIdType i = 0; names && i < names->GetNumberOfValues(); ++i)
  {
    state->Set.attributeNames.push_back(names->GetValue(i));
  }
  this->Contents = state;
  this->Modified();
  return std::string();
}

std::string vtkIGANurbsData::AddVolume(const int degrees[3], vtkDataArray* knotsU,
  vtkDataArray* knotsV, vtkDataArray* knotsW, vtkDataArray* net)
{
  vtkDataArray* const knots[3] = { knotsU, knotsV, knotsW };
  iga::BSplinePatch<double, 3> volume;
  return this->AddPatch(
    patchFromArrays<3>(degrees, knots, net, this->Contents->Set.channels(), volume),
    "volume " + std::to_string(this->Contents->Set.volumes.size()),
    [&](iga::NurbsSet<double>& set) { set.volumes.push_back(volume); });
}

std::string vtkIGANurbsData::AddSurface(
  const int degrees[2], vtkDataArray* knotsU, vtkDataArray* knotsV, vtkDataArray* net)
{
  vtkDataArray* const knots[2] = { knotsU, knotsV };
  iga::BSplinePatch<double, 2> surface;
  return this->AddPatch(
    patchFromArrays<2>(degrees, knots, net, this->Contents->Set.channels(), surface),
    "surface " + std::to_string(this->Contents->Set.surfaces.size()),
    [&](iga::NurbsSet<double>& set) { set.surfaces.push_back(surface); });
}

std::string vtkIGANurbsData::AddPatch(const std::string& problem, const std::string& name,
  const std::function<void(iga::NurbsSet<double>&)>& add)
{
  if (!problem.empty())
  {
    return name + ": " + problem;
  }
  const std::shared_ptr<const State> before = this->Contents;
  if (before->Times.size() > 1)
  {
    return "patches are added while there is one time step, there are " +
           std::to_string(before->Times.size());
  }
  // The patches as given: volumes turned right-handed are turned back, so that SetPatches
  // finds (and reports) them again.
  iga::NurbsSet<double> set = this->GetPatches(0);
  for (size_t v = 0; v < set.volumes.size(); ++v)
  {
    if (this->IsVolumeReversed(int(v)))
    {
      iga::reverseDirection(set.volumes[v], 0);
    }
  }
  add(set);
  const std::string refused = this->SetPatches(set, before->Times.empty() ? 0.0 : before->Times[0]);
  if (!refused.empty())
  {
    this->Contents = before;
  }
  return refused;
}

std::string vtkIGANurbsData::AddTimeStepNets(double time, vtkDataArrayCollection* nets)
{
  std::vector<std::vector<double>> values;
  const int channels = this->Contents->Set.channels();
  for (int i = 0; nets && i < nets->GetNumberOfItems(); ++i)
  {
    vtkDataArray* net = nets->GetItem(i);
    if (!net || net->GetNumberOfComponents() != channels)
    {
      return "time " + std::to_string(time) + ", patch " + std::to_string(i) +
             ": the control net needs " + std::to_string(channels) + " components, it has " +
             std::to_string(net ? net->GetNumberOfComponents() : 0);
    }
    values.push_back(valuesOf(net));
  }
  return this->AddTimeStep(time, values);
}

vtkIdType vtkIGANurbsData::GetNumberOfBezierCells() const
{
  vtkIdType count = 0;
  for (const auto& e : this->Contents->VolumeExtractions)
  {
    count += e->elementCount();
  }
  for (const auto& e : this->Contents->SurfaceExtractions)
  {
    count += e->elementCount();
  }
  return count;
}

double vtkIGANurbsData::GetBezierCellBytes() const
{
  const State& s = *this->Contents;
  // Per control point the grid's coordinates, weight and attributes and its connectivity entry;
  // the elements are made one at a time. The surfaces' points are appended to the volumes'
  // arrays, which may double them while they grow.
  const double perPoint = 8.0 * s.Set.channels() + 8.0;
  const ExactParameterCells exact(this->ExactParameters, s.Set, s.Nets);
  auto points = [&](const auto& patches, const auto& extractions, size_t first)
  {
    double count = 0;
    for (size_t p = 0; p < patches.size(); ++p)
    {
      count += double(extractions[p]->elementCount()) *
               double(pointsPerElement(patches[p], exact.elevated[first + p]));
    }
    return count;
  };
  const double volumes = points(s.Set.volumes, s.VolumeExtractions, 0);
  const double surfaces = points(s.Set.surfaces, s.SurfaceExtractions, s.Set.volumes.size());
  // And the grid's field-data copy of the step's control nets.
  double netValues = 0;
  for (const auto& net : s.Nets.empty() ? std::vector<Net>() : s.Nets.front())
  {
    netValues += double(net->size());
  }
  // vtkIGAAttributeRanges::Attach reads the finished grid back as patches: its coefficients once
  // more.
  const double attachCopy = 8.0 * s.Set.channels() * (volumes + surfaces);
  return perPoint * (surfaces > 0 ? 2 * (volumes + surfaces) : volumes) + attachCopy +
         8.0 * netValues;
}

namespace
{

/// The cell arrays naming each cell's patch and knot span.
struct CellOrigins
{
  vtkNew<vtkIntArray> patchIds, spans;
  CellOrigins()
  {
    patchIds->SetName(kPatchArray);
    spans->SetName(kSpanArray);
    spans->SetNumberOfComponents(3);
  }
  void add(int patch, const int* span)
  {
    patchIds->InsertNextValue(patch);
    spans->InsertNextTypedTuple(span);
  }
};

/// The volumes' Bézier elements as a grid of hexahedra through the shared conversion, built one
/// element at a time (only the grid and one element held); whole patches were oriented by
/// SetPatches, so the cells stay the elements as extracted.
vtkSmartPointer<vtkUnstructuredGrid> volumeCells(const iga::NurbsSet<double>& set,
  const std::vector<Extraction<3>>& extractions, const std::vector<Net>& nets,
  const std::vector<bool>& reversed, const ExactParameterCells& exact, CellOrigins& origins)
{
  const int channels = set.channels();
  std::vector<vtkIdType> firstCell{ 0 };
  vtkIdType pointCount = 0;
  for (size_t v = 0; v < nets.size() && v < set.volumes.size(); ++v)
  {
    firstCell.push_back(firstCell.back() + extractions[v]->elementCount());
    pointCount += vtkIdType(extractions[v]->elementCount()) *
                  pointsPerElement(set.volumes[v], exact.elevated[v]);
  }
  iga::BezierVolume<double> element;
  std::vector<double> work;
  size_t volume = 0;
  auto extract = [&](vtkIdType c) -> const iga::BezierVolume<double>&
  {
    while (c >= firstCell[volume + 1])
    {
      ++volume;
    }
    const auto& extraction = *extractions[volume];
    const int e = int(c - firstCell[volume]);
    element = iga::BezierVolume<double>(set.volumes[volume].degree, channels);
    work.resize(2 * element.coeffs().size());
    extraction.extract(e, nets[volume]->data(), channels, element.coeffs().data(), work.data());
    if (exact.elevated[volume])
    {
      element = exactParameterElement(
        element, exact.channel, set.volumes[volume], extraction, e, reversed[volume]);
    }
    int span[3];
    extraction.elementIndex(e, span);
    origins.add(int(volume), span);
    return element;
  };
  return vtkIGABezierHexahedra::ToUnstructuredGrid(firstCell.back(), pointCount, set.attributeNames,
    extract, vtkIGABezierHexahedra::CellLayout::AsGiven);
}

/// Appends the surfaces' Bézier elements to `grid` as quadrilaterals, one element at a time.
void appendSurfaceCells(vtkUnstructuredGrid* grid, const iga::NurbsSet<double>& set,
  const std::vector<Extraction<2>>& extractions, const std::vector<Net>& nets,
  const ExactParameterCells& exact, CellOrigins& origins)
{
  const int channels = set.channels();
  const size_t volumeCount = set.volumes.size();
  std::vector<vtkDataArray*> attributes;
  for (const auto& name : set.attributeNames)
  {
    attributes.push_back(grid->GetPointData()->GetArray(name.c_str()));
  }
  std::vector<double> work;
  for (size_t f = 0; f < set.surfaces.size() && volumeCount + f < nets.size(); ++f)
  {
    const auto& extraction = *extractions[f];
    iga::BezierPatch<double, 2> element(set.surfaces[f].degree, channels);
    work.resize(2 * element.coeffs().size());
    for (int e = 0; e < extraction.elementCount(); ++e)
    {
      extraction.extract(
        e, nets[volumeCount + f]->data(), channels, element.coeffs().data(), work.data());
      if (exact.elevated[volumeCount + f])
      {
        const auto raised =
          exactParameterElement(element, exact.channel, set.surfaces[f], extraction, e, false);
        vtkIGABezierHexahedra::AppendQuadrilateral(grid, raised.view(), attributes);
      }
      else
      {
        vtkIGABezierHexahedra::AppendQuadrilateral(grid, std::as_const(element).view(), attributes);
      }
      int span[3] = { 0, 0, 0 };
      extraction.elementIndex(e, span);
      origins.add(static_cast<int>(volumeCount + f), span);
    }
  }
}

/// The NURBS description in the grid's field data, so that the class can be rebuilt from the
/// grid alone (see the class description).
void describe(vtkUnstructuredGrid* grid, const iga::NurbsSet<double>& set,
  const std::vector<Net>& nets, double time)
{
  const int channels = set.channels();
  vtkNew<vtkIntArray> info;
  info->SetName(kInfoArray);
  info->SetNumberOfComponents(kInfoComponents);
  vtkNew<vtkDoubleArray> knots;
  knots->SetName(kKnotsArray);
  vtkNew<vtkDoubleArray> net;
  net->SetName(kNetArray);
  net->SetNumberOfComponents(channels);
  auto add = [&](int dim, const int* degree, const int* netSize,
               const std::vector<double>* knotVectors, const std::vector<double>& values)
  {
    int tuple[kInfoComponents] = { dim, 0, 0, 0, 1, 1, 1 };
    for (int d = 0; d < dim; ++d)
    {
      tuple[1 + d] = degree[d];
      tuple[4 + d] = netSize[d];
      for (double knot : knotVectors[d])
      {
        knots->InsertNextValue(knot);
      }
    }
    info->InsertNextTypedTuple(tuple);
    for (size_t v = 0; v < values.size(); v += channels)
    {
      net->InsertNextTuple(values.data() + v);
    }
  };
  const size_t volumeCount = set.volumes.size();
  for (size_t p = 0; p < nets.size(); ++p)
  {
    if (p < volumeCount)
    {
      const auto& v = set.volumes[p];
      add(3, v.degree, v.netSize, v.knots, *nets[p]);
    }
    else
    {
      const auto& f = set.surfaces[p - volumeCount];
      add(2, f.degree, f.netSize, f.knots, *nets[p]);
    }
  }
  vtkNew<vtkStringArray> names;
  names->SetName(kNamesArray);
  for (const auto& name : set.attributeNames)
  {
    names->InsertNextValue(name);
  }
  vtkNew<vtkDoubleArray> times;
  times->SetName(kTimeArray);
  times->InsertNextValue(time);
  vtkFieldData* fd = grid->GetFieldData();
  fd->AddArray(info);
  fd->AddArray(knots);
  fd->AddArray(net);
  fd->AddArray(names);
  fd->AddArray(times);
}
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGANurbsData::ToUnstructuredGrid(int step)
{
  const std::shared_ptr<const State> contents = this->Contents;
  const State& s = *contents;
  step = std::clamp(step, 0, std::max(0, static_cast<int>(s.Times.size()) - 1));
  if (this->CachedGrid && this->CachedContents == contents && this->CachedStep == step &&
      this->CachedExactParameters == this->ExactParameters)
  {
    return this->CachedGrid;
  }
  const std::vector<Net> none;
  const std::vector<Net>& nets = s.Nets.empty() ? none : s.Nets[step];
  CellOrigins origins;
  const ExactParameterCells exact(this->ExactParameters, s.Set, s.Nets);
  auto grid = volumeCells(s.Set, s.VolumeExtractions, nets, s.ReversedVolumes, exact, origins);
  appendSurfaceCells(grid, s.Set, s.SurfaceExtractions, nets, exact, origins);
  grid->GetCellData()->AddArray(origins.patchIds);
  grid->GetCellData()->AddArray(origins.spans);
  describe(grid, s.Set, nets, s.Times.empty() ? 0.0 : s.Times[step]);
  vtkIGAAttributeRanges::Attach(grid);
  this->CachedGrid = grid;
  this->CachedContents = contents;
  this->CachedStep = step;
  this->CachedExactParameters = this->ExactParameters;
  return grid;
}

std::string vtkIGANurbsData::FromUnstructuredGrid(vtkUnstructuredGrid* grid, vtkIGANurbsData* data)
{
  data->Contents = std::make_shared<State>();
  data->Modified();
  vtkFieldData* fd = grid ? grid->GetFieldData() : nullptr;
  auto* info = fd ? vtkIntArray::SafeDownCast(fd->GetAbstractArray(kInfoArray)) : nullptr;
  auto* knots = fd ? vtkDoubleArray::SafeDownCast(fd->GetAbstractArray(kKnotsArray)) : nullptr;
  auto* net = fd ? vtkDoubleArray::SafeDownCast(fd->GetAbstractArray(kNetArray)) : nullptr;
  auto* names = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(kNamesArray)) : nullptr;
  if (!info || !knots || !net || !names)
  {
    return std::string("the grid carries no NURBS description (field data '") + kInfoArray +
           "', '" + kKnotsArray + "', '" + kNetArray + "' and '" + kNamesArray + "')";
  }
  if (info->GetNumberOfComponents() != kInfoComponents)
  {
    return std::string("field array '") + kInfoArray + "' has " +
           std::to_string(info->GetNumberOfComponents()) + " components, expected " +
           std::to_string(kInfoComponents);
  }
  iga::NurbsSet<double> set;
  for (vtkIdType n = 0; n < names->GetNumberOfValues(); ++n)
  {
    set.attributeNames.push_back(names->GetValue(n));
  }
  const int channels = set.channels();
  if (net->GetNumberOfComponents() != channels)
  {
    return std::string("field array '") + kNetArray + "' has " +
           std::to_string(net->GetNumberOfComponents()) + " components, expected " +
           std::to_string(channels) + " for " + std::to_string(set.attributeNames.size()) +
           " attributes";
  }
  vtkIdType knotAt = 0, pointAt = 0;
  std::string error;
  auto fill = [&](auto& patch, int p, const int* tuple) -> bool
  {
    constexpr int dim = PatchDimension<std::remove_reference_t<decltype(patch)>>::value;
    size_t points = 1;
    for (int d = 0; d < dim; ++d)
    {
      patch.degree[d] = tuple[1 + d];
      patch.netSize[d] = tuple[4 + d];
      const vtkIdType count = static_cast<vtkIdType>(tuple[1 + d]) + tuple[4 + d] + 1;
      if (tuple[1 + d] < 1 || tuple[4 + d] < 1 || knotAt + count > knots->GetNumberOfTuples())
      {
        error = "patch " + std::to_string(p) + ": degree " + std::to_string(tuple[1 + d]) +
                " and " + std::to_string(tuple[4 + d]) + " control points in direction " +
                std::to_string(d) + " do not fit field array '" + kKnotsArray + "'";
        return false;
      }
      patch.knots[d].assign(knots->GetPointer(knotAt), knots->GetPointer(knotAt) + count);
      knotAt += count;
      points *= static_cast<size_t>(tuple[4 + d]);
    }
    if (pointAt + static_cast<vtkIdType>(points) > net->GetNumberOfTuples())
    {
      error = "patch " + std::to_string(p) + ": its " + std::to_string(points) +
              " control points do not fit field array '" + kNetArray + "'";
      return false;
    }
    patch.channels = channels;
    patch.net.assign(
      net->GetPointer(pointAt * channels), net->GetPointer(pointAt * channels) + points * channels);
    pointAt += static_cast<vtkIdType>(points);
    return true;
  };
  for (vtkIdType p = 0; p < info->GetNumberOfTuples(); ++p)
  {
    int tuple[kInfoComponents];
    info->GetTypedTuple(p, tuple);
    if (tuple[0] == 3 && set.surfaces.empty())
    {
      set.volumes.emplace_back();
      if (!fill(set.volumes.back(), static_cast<int>(p), tuple))
      {
        return error;
      }
    }
    else if (tuple[0] == 2)
    {
      set.surfaces.emplace_back();
      if (!fill(set.surfaces.back(), static_cast<int>(p), tuple))
      {
        return error;
      }
    }
    else
    {
      return "patch " + std::to_string(p) + ": parametric dimension " + std::to_string(tuple[0]) +
             " is not 3 (volumes, first) or 2 (surfaces, after the volumes)";
    }
  }
  if (knotAt != knots->GetNumberOfTuples() || pointAt != net->GetNumberOfTuples())
  {
    return std::string("field arrays '") + kKnotsArray + "' and '" + kNetArray +
           "' hold more values than the patches of '" + kInfoArray + "' use";
  }
  auto* time = vtkDoubleArray::SafeDownCast(fd->GetAbstractArray(kTimeArray));
  const double t = time && time->GetNumberOfTuples() > 0 ? time->GetValue(0) : 0.0;
  return data->SetPatches(set, t);
}

void vtkIGANurbsData::FillTimeInformation(vtkInformation* outInfo) const
{
  const auto& times = this->Contents->Times;
  if (times.size() > 1)
  {
    outInfo->Set(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { times.front(), times.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  else
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
}

int vtkIGANurbsData::FindTimeStep(double time) const
{
  const auto& times = this->Contents->Times;
  const auto after = std::upper_bound(times.begin(), times.end(), time);
  return after == times.begin() ? 0 : static_cast<int>(after - times.begin()) - 1;
}

int vtkIGANurbsData::RequestedTimeStep(vtkInformation* outInfo) const
{
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    return this->FindTimeStep(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
  }
  return 0;
}

void vtkIGANurbsData::FillOutput(vtkInformation* outInfo)
{
  const int step = this->RequestedTimeStep(outInfo);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outInfo);
  output->ShallowCopy(this->ToUnstructuredGrid(step));
  if (!this->Contents->Times.empty())
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), this->Contents->Times[step]);
  }
}

void vtkIGANurbsData::ShallowCopy(vtkIGANurbsData* other)
{
  if (other && other != this)
  {
    this->Contents = other->Contents;
    this->ExactParameters = other->ExactParameters;
    this->Modified();
  }
}

void vtkIGANurbsData::DeepCopy(vtkIGANurbsData* other)
{
  if (!other || other == this)
  {
    return;
  }
  this->ExactParameters = other->ExactParameters;
  auto state = std::make_shared<State>(*other->Contents);
  for (auto& step : state->Nets)
  {
    for (auto& net : step)
    {
      net = std::make_shared<const std::vector<double>>(*net);
    }
  }
  for (auto& e : state->VolumeExtractions)
  {
    e = std::make_shared<const iga::BezierExtraction<double, 3>>(*e);
  }
  for (auto& e : state->SurfaceExtractions)
  {
    e = std::make_shared<const iga::BezierExtraction<double, 2>>(*e);
  }
  this->Contents = state;
  this->Modified();
}

unsigned long vtkIGANurbsData::GetActualMemorySize()
{
  const State& s = *this->Contents;
  size_t bytes = sizeof(State);
  auto operatorBytes = [](const auto& extraction, int dim)
  {
    size_t b = 0;
    for (int d = 0; d < dim; ++d)
    {
      const auto& op = extraction.direction(d);
      b += (op.matrices.size() + op.spanStart.size() + op.spanEnd.size()) * sizeof(double) +
           op.firstBasis.size() * sizeof(int);
    }
    return b;
  };
  for (size_t v = 0; v < s.Set.volumes.size(); ++v)
  {
    bytes +=
      knotCount(s.Set.volumes[v]) * sizeof(double) + operatorBytes(*s.VolumeExtractions[v], 3);
  }
  for (size_t f = 0; f < s.Set.surfaces.size(); ++f)
  {
    bytes +=
      knotCount(s.Set.surfaces[f]) * sizeof(double) + operatorBytes(*s.SurfaceExtractions[f], 2);
  }
  for (const auto& step : s.Nets)
  {
    for (const auto& net : step)
    {
      bytes += net->size() * sizeof(double);
    }
  }
  for (const auto& name : s.Set.attributeNames)
  {
    bytes += name.size();
  }
  unsigned long kib = static_cast<unsigned long>((bytes + 1023) / 1024);
  if (this->CachedGrid)
  {
    kib += this->CachedGrid->GetActualMemorySize();
  }
  return kib;
}
