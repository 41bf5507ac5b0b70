// vtkIGANurbsData: Bézier extraction against Cox-de Boor evaluation (through VTK's own cell
// interpolation), the grid round trip, time steps in the pipeline, copies and memory.
#include "NurbsTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGANurbsCells.h"
#include "vtkIGANurbsData.h"

#include "iga/Datasets.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnstructuredGridAlgorithm.h"

#include <cmath>
#include <random>

using namespace igatest;

namespace
{

/// A random open knot vector of `count` control points with repeated interior knots.
std::vector<double> randomKnots(std::mt19937& rng, int degree, int count)
{
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> interior;
  while (static_cast<int>(interior.size()) < count - degree - 1)
  {
    const double knot = 0.05 + 0.9 * unit(rng);
    const int repeat =
      std::min<int>(1 + (unit(rng) < 0.3), count - degree - 1 - int(interior.size()));
    interior.insert(interior.end(), repeat, knot);
  }
  std::sort(interior.begin(), interior.end());
  std::vector<double> knots(degree + 1, -0.5);
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), degree + 1, 2.0);
  return knots;
}

template<int Dim>
iga::BSplinePatch<double, Dim> randomPatch(std::mt19937& rng, int attributes)
{
  std::uniform_real_distribution<double> coord(-1, 1), weight(0.3, 3);
  iga::BSplinePatch<double, Dim> patch;
  patch.channels = iga::kFirstAttributeChannel + attributes;
  size_t points = 1;
  for (int d = 0; d < Dim; ++d)
  {
    patch.degree[d] = std::uniform_int_distribution<int>(1, 3)(rng);
    patch.netSize[d] = patch.degree[d] + std::uniform_int_distribution<int>(1, 4)(rng);
    patch.knots[d] = randomKnots(rng, patch.degree[d], patch.netSize[d]);
    points *= patch.netSize[d];
  }
  for (size_t p = 0; p < points; ++p)
  {
    const double w = weight(rng);
    for (int c = 0; c < patch.channels; ++c)
      patch.net.push_back(c == iga::kWeightChannel ? w : w * coord(rng));
  }
  return patch;
}

iga::NurbsSet<double> randomSet(unsigned seed)
{
  std::mt19937 rng(seed);
  iga::NurbsSet<double> set;
  set.attributeNames = { "pressure", "temperature" };
  set.volumes = { randomPatch<3>(rng, 2), randomPatch<3>(rng, 2) };
  set.surfaces = { randomPatch<2>(rng, 2) };
  return set;
}

vtkIdType expectedCells(const iga::NurbsSet<double>& set)
{
  vtkIdType cells = 0;
  for (const auto& v : set.volumes)
    cells += vtkIdType(
      knotSpans(v.knots[0]).size() * knotSpans(v.knots[1]).size() * knotSpans(v.knots[2]).size());
  for (const auto& s : set.surfaces)
    cells += vtkIdType(knotSpans(s.knots[0]).size() * knotSpans(s.knots[1]).size());
  return cells;
}

TEST(NurbsData, ExtractionMatchesCoxDeBoorThroughVTKCells)
{
  int reversedVolumes = 0;
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    const auto set = randomSet(seed);
    vtkNew<vtkIGANurbsData> data;
    ASSERT_EQ(data->SetPatches(set), "");
    const auto grid = data->ToUnstructuredGrid();
    ASSERT_EQ(grid->GetNumberOfCells(), expectedCells(set));
    ASSERT_EQ(data->GetNumberOfBezierCells(), expectedCells(set));
    int hexahedra = 0, quadrilaterals = 0;
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      hexahedra += grid->GetCellType(c) == VTK_BEZIER_HEXAHEDRON;
      quadrilaterals += grid->GetCellType(c) == VTK_BEZIER_QUADRILATERAL;
    }
    EXPECT_EQ(quadrilaterals,
      knotSpans(set.surfaces[0].knots[0]).size() * knotSpans(set.surfaces[0].knots[1]).size());
    EXPECT_EQ(hexahedra + quadrilaterals, grid->GetNumberOfCells());
    std::mt19937 rng(seed + 100);
    const std::vector<bool> reversed = { data->IsVolumeReversed(0), data->IsVolumeReversed(1) };
    reversedVolumes += reversed[0] + reversed[1];
    const double worst = compareWithCoxDeBoor(set, grid, rng, 40, reversed);
    EXPECT_LT(worst, 1e-9);
  }
  EXPECT_GT(reversedVolumes, 0) << "no left-handed volume among the random ones";
  EXPECT_LT(reversedVolumes, 10) << "no right-handed volume among the random ones";
}

TEST(NurbsData, GridRoundTripRebuildsTheSameNurbs)
{
  const auto set = randomSet(7);
  vtkNew<vtkIGANurbsData> data;
  ASSERT_EQ(data->SetPatches(set, 2.5), "");
  const auto grid = data->ToUnstructuredGrid();
  vtkNew<vtkIGANurbsData> back;
  ASSERT_EQ(vtkIGANurbsData::FromUnstructuredGrid(grid, back), "");
  EXPECT_EQ(back->GetTimeSteps(), std::vector<double>{ 2.5 });
  const auto rebuilt = back->GetPatches();
  EXPECT_EQ(rebuilt.attributeNames, set.attributeNames);
  ASSERT_EQ(rebuilt.volumes.size(), 2u);
  ASSERT_EQ(rebuilt.surfaces.size(), 1u);
  for (int v = 0; v < 2; ++v)
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_EQ(rebuilt.volumes[v].degree[d], set.volumes[v].degree[d]);
      EXPECT_EQ(rebuilt.volumes[v].knots[d], set.volumes[v].knots[d]);
    }
  EXPECT_EQ(rebuilt.volumes[1].net, set.volumes[1].net);
  EXPECT_EQ(rebuilt.surfaces[0].net, set.surfaces[0].net);
  EXPECT_EQ(rebuilt.surfaces[0].knots[1], set.surfaces[0].knots[1]);
  // grid -> class -> grid gives the same cells and points.
  const auto again = back->ToUnstructuredGrid();
  ASSERT_EQ(again->GetNumberOfPoints(), grid->GetNumberOfPoints());
  ASSERT_EQ(again->GetNumberOfCells(), grid->GetNumberOfCells());
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); p += 7)
  {
    double a[3], b[3];
    grid->GetPoint(p, a);
    again->GetPoint(p, b);
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(a[d], b[d]);
    EXPECT_EQ(grid->GetPointData()->GetRationalWeights()->GetComponent(p, 0),
      again->GetPointData()->GetRationalWeights()->GetComponent(p, 0));
  }
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    EXPECT_EQ(grid->GetCellType(c), again->GetCellType(c));
}

TEST(NurbsData, BadInputIsNamed)
{
  vtkNew<vtkIGANurbsData> data;
  auto set = randomSet(3);
  set.volumes[1].net[iga::kWeightChannel] = -2; // control point (0, 0, 0) of patch 1
  EXPECT_NE(data->SetPatches(set).find("patch 1 (volume): control point (0, 0, 0) has "
                                       "non-positive weight"),
    std::string::npos);
  EXPECT_EQ(data->GetNumberOfPatches(), 0);
  set = randomSet(3);
  set.surfaces[0].knots[1][1] = 5; // non-monotone
  EXPECT_NE(data->SetPatches(set).find("patch 2 (surface): direction 1: knots are not "
                                       "non-decreasing"),
    std::string::npos);
  set = randomSet(3);
  set.volumes[0].net.pop_back();
  EXPECT_NE(data->SetPatches(set).find("patch 0 (volume): control net has"), std::string::npos);
  set = randomSet(3);
  set.volumes[0].net[5] = NAN;
  EXPECT_NE(data->SetPatches(set).find(
              "control point (0, 0, 0) has a non-finite attribute 1 (channel 5): nan"),
    std::string::npos);

  // Control point (0, 0) of the surface weighing 1e7 times its neighbours: it is element
  // (0, 0)'s corner, at the first step or a later one.
  set = randomSet(3);
  auto skewed =
    std::vector<std::vector<double>>{ set.volumes[0].net, set.volumes[1].net, set.surfaces[0].net };
  for (int c = 0; c < set.channels(); ++c)
    skewed[2][size_t(c)] *= 1e7;
  const std::string skewedElement = "element (0, 0): its Bézier weights range over ";
  ASSERT_EQ(data->SetPatches(set, 1.0), "");
  const std::string later = data->AddTimeStep(2.0, skewed);
  EXPECT_EQ(later.rfind("time 2.000000, patch 2: " + skewedElement, 0), 0u) << later;
  set.surfaces[0].net = skewed[2];
  const std::string first = data->SetPatches(set);
  EXPECT_EQ(first.rfind("patch 2 (surface): " + skewedElement, 0), 0u) << first;
  EXPECT_NE(first.find(": more than the 1e+06 that subdivision resolves"), std::string::npos);

  set = randomSet(3);
  ASSERT_EQ(data->SetPatches(randomSet(3), 1.0), "");
  auto nets = std::vector<std::vector<double>>{ set.volumes[0].net };
  EXPECT_NE(
    data->AddTimeStep(2.0, nets).find("1 control nets given for 3 patches"), std::string::npos);
  EXPECT_NE(data->AddTimeStep(0.5, {}).find("does not follow"), std::string::npos);

  vtkNew<vtkUnstructuredGrid> plain;
  EXPECT_NE(vtkIGANurbsData::FromUnstructuredGrid(plain, data).find("carries no NURBS description"),
    std::string::npos);
  EXPECT_EQ(data->GetNumberOfPatches(), 0);
}

/// The nets of `set` moved by `shift` along x, with the first attribute set to `shift` too.
std::vector<std::vector<double>> shiftedNets(const iga::NurbsSet<double>& set, double shift)
{
  std::vector<std::vector<double>> nets;
  auto add = [&](const auto& patch)
  {
    nets.push_back(patch.net);
    for (size_t p = 0; p < nets.back().size(); p += patch.channels)
    {
      const double w = nets.back()[p + iga::kWeightChannel];
      nets.back()[p] += w * shift;
      nets.back()[p + iga::kFirstAttributeChannel] = w * shift;
    }
  };
  for (const auto& v : set.volumes)
    add(v);
  for (const auto& s : set.surfaces)
    add(s);
  return nets;
}

/// A minimal time-aware source around vtkIGANurbsData, as readers use it.
class NurbsSource : public vtkUnstructuredGridAlgorithm
{
public:
  static NurbsSource* New();
  vtkTypeMacro(NurbsSource, vtkUnstructuredGridAlgorithm);
  vtkNew<vtkIGANurbsData> Data;

protected:
  NurbsSource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    this->Data->FillTimeInformation(out->GetInformationObject(0));
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    this->Data->FillOutput(out->GetInformationObject(0));
    return 1;
  }
};
vtkStandardNewMacro(NurbsSource);

TEST(NurbsData, LeftHandedVolumesAreStoredRightHandedForVTK)
{
  iga::NurbsSet<double> set;
  set.attributeNames = { "f" };
  set.volumes = { iga::makeNurbsBall<double>(2, 1.0), iga::makeNurbsBall<double>(3, -1.0) };
  vtkNew<vtkIGANurbsData> data;
  ASSERT_EQ(data->SetPatches(set), "");
  EXPECT_FALSE(data->IsVolumeReversed(0));
  EXPECT_TRUE(data->IsVolumeReversed(1)) << "mirrored in x: left-handed";
  const auto grid = data->ToUnstructuredGrid();
  EXPECT_EQ(validatorStates(grid), std::vector<int>(grid->GetNumberOfCells(), 0));
  std::mt19937 rng(12);
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 40, { false, true }), 1e-12);
  // A later step's nets come in the layout given to SetPatches and are turned the same way.
  ASSERT_EQ(data->AddTimeStep(1.0, shiftedNets(set, 0.5)), "");
  const auto moved = data->ToUnstructuredGrid(1);
  iga::NurbsSet<double> shifted = set;
  const auto nets = shiftedNets(set, 0.5);
  shifted.volumes[0].net = nets[0];
  shifted.volumes[1].net = nets[1];
  EXPECT_LT(compareWithCoxDeBoor(shifted, moved, rng, 40, { false, true }), 1e-12);
  EXPECT_EQ(validatorStates(moved), std::vector<int>(moved->GetNumberOfCells(), 0));
}

namespace
{
vtkSmartPointer<vtkDoubleArray> arrayOf(const std::vector<double>& values, int components)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetNumberOfComponents(components);
  for (double value : values)
    array->InsertNextValue(value);
  return array;
}
} // namespace

// The VTK-typed building (Python's): volumes added one at a time, the second left-handed, give
// SetPatches' description and cells, and read back through the VTK-typed accessors as given
// (the left-handed one not turned).
TEST(NurbsData, VolumesAddedFromArraysEqualSetPatches)
{
  iga::NurbsSet<double> set;
  set.attributeNames = { "f" };
  set.volumes = { iga::makeNurbsBall<double>(2, 1.0), iga::makeNurbsBall<double>(3, -1.0) };
  vtkNew<vtkIGANurbsData> whole, added;
  ASSERT_EQ(whole->SetPatches(set), "");
  vtkNew<vtkStringArray> names;
  names->InsertNextValue("f");
  ASSERT_EQ(added->SetAttributeNames(names), "");
  for (const auto& volume : set.volumes)
  {
    const auto u = arrayOf(volume.knots[0], 1), v = arrayOf(volume.knots[1], 1),
               w = arrayOf(volume.knots[2], 1);
    ASSERT_EQ(added->AddVolume(volume.degree, u, v, w, arrayOf(volume.net, set.channels())), "");
  }
  ASSERT_EQ(added->GetNumberOfPatches(), 2);
  EXPECT_FALSE(added->IsVolumeReversed(0));
  EXPECT_TRUE(added->IsVolumeReversed(1)) << "still known after the second volume came";
  const auto a = whole->ToUnstructuredGrid(), b = added->ToUnstructuredGrid();
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
    for (int d = 0; d < 3; ++d)
      ASSERT_EQ(a->GetPoint(p)[d], b->GetPoint(p)[d]);
  for (int patch = 0; patch < 2; ++patch)
  {
    int degrees[3], size[3];
    added->GetPatchDegrees(patch, degrees);
    added->GetPatchNetSize(patch, size);
    vtkNew<vtkDoubleArray> knots, net;
    added->GetPatchKnots(patch, 0, knots);
    added->GetPatchControlNet(0, patch, net);
    const auto& given = set.volumes[size_t(patch)]; // read back as given, not turned
    EXPECT_EQ(added->GetPatchDimension(patch), 3);
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_EQ(degrees[d], given.degree[d]);
      EXPECT_EQ(size[d], given.netSize[d]);
    }
    ASSERT_EQ(size_t(knots->GetNumberOfTuples()), given.knots[0].size());
    for (size_t k = 0; k < given.knots[0].size(); ++k)
      EXPECT_NEAR(knots->GetValue(vtkIdType(k)), given.knots[0][k], 1e-15);
    ASSERT_EQ(size_t(net->GetNumberOfValues()), given.net.size());
    EXPECT_EQ(net->GetNumberOfComponents(), set.channels());
    for (size_t k = 0; k < given.net.size(); ++k)
      ASSERT_EQ(net->GetValue(vtkIdType(k)), given.net[k]);
  }
  EXPECT_EQ(added->GetPatchDimension(2), 0);
  EXPECT_STREQ(added->GetAttributeName(0), "f");
  EXPECT_EQ(added->GetAttributeName(1), nullptr);
}

// ExactParameters: the cells of rational volumes (a left-handed one among them, stored turned)
// carry parameter_u/v/w equal to the patch's parameter (the file's, not the turned one) at random
// points to 1e-12, where the Greville blend of the same cells is off by more than 1e-3.
TEST(NurbsData, ExactParametersOnRationalVolumes)
{
  iga::NurbsSet<double> set;
  set.attributeNames = iga::geometryAttributeNames();
  for (double stretch : { 1.0, -1.0 })
  {
    auto ball = iga::makeNurbsBall<double>(3, stretch);
    std::vector<double> euclidean, weights;
    for (size_t p = 0; p < ball.net.size(); p += size_t(ball.channels))
    {
      weights.push_back(ball.net[p + iga::kWeightChannel]);
      for (int c = 0; c < 3; ++c)
        euclidean.push_back(ball.net[p + size_t(c)] / weights.back());
    }
    iga::setGeometryNet(ball, euclidean, weights);
    set.volumes.push_back(ball);
  }
  vtkNew<vtkIGANurbsData> data;
  ASSERT_EQ(data->SetPatches(set), "");
  ASSERT_TRUE(data->IsVolumeReversed(1));
  const double bytes = data->GetBezierCellBytes();
  const std::vector<std::string> names = { "parameter_u", "parameter_v", "parameter_w" };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (bool exact : { false, true })
  {
    data->SetExactParameters(exact);
    const auto grid = data->ToUnstructuredGrid();
    ASSERT_EQ(grid->GetNumberOfCells(), 54);
    EXPECT_EQ(grid->GetNumberOfPoints(), 54 * (exact ? 64 : 27));
    vtkDataArray* patchIds = grid->GetCellData()->GetArray("NurbsPatch");
    vtkDataArray* spans = grid->GetCellData()->GetArray("NurbsKnotSpan");
    double worst = 0;
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      const bool reversed = patchIds->GetComponent(c, 0) == 1;
      for (int sample = 0; sample < 5; ++sample)
      {
        const double pcoords[3] = { unit(rng), unit(rng), unit(rng) };
        const auto value = igatest::evaluateCell(grid, c, pcoords, names);
        for (int d = 0; d < 3; ++d)
        {
          // Spans of a third; the turned volume's first direction runs from 1 to 0.
          const double stored = (spans->GetComponent(c, d) + pcoords[d]) / 3;
          const double expected = reversed && d == 0 ? 1 - stored : stored;
          worst = std::max(worst, std::abs(value[size_t(3 + d)] - expected));
        }
      }
    }
    if (exact)
      EXPECT_LT(worst, 1e-12);
    else
      EXPECT_GT(worst, 1e-3);
  }
  EXPECT_NEAR(data->GetBezierCellBytes() / bytes, 64.0 / 27.0, 0.2)
    << "the memory check counts them";
}

TEST(NurbsData, TimeStepsFollowThePipelineRequest)
{
  const auto set = randomSet(11);
  vtkNew<NurbsSource> source;
  ASSERT_EQ(source->Data->SetPatches(set, 0.0), "");
  ASSERT_EQ(source->Data->AddTimeStep(1.0, shiftedNets(set, 1.0)), "");
  ASSERT_EQ(source->Data->AddTimeStep(3.0, shiftedNets(set, 3.0)), "");
  source->UpdateInformation();
  vtkInformation* info = source->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 3);
  EXPECT_EQ(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[2], 3.0);
  EXPECT_EQ(info->Get(vtkStreamingDemandDrivenPipeline::TIME_RANGE())[1], 3.0);

  vtkNew<vtkIGANurbsData> still;
  ASSERT_EQ(still->SetPatches(set), "");
  const auto rest = still->ToUnstructuredGrid();
  // Between steps the earlier one is shown; before the first, the first.
  for (const auto& [request, step] : std::vector<std::pair<double, double>>{
         { 1.7, 1.0 }, { 3.0, 3.0 }, { -4.0, 0.0 }, { 0.0, 0.0 } })
  {
    source->UpdateTimeStep(request);
    auto* output = vtkUnstructuredGrid::SafeDownCast(source->GetOutputDataObject(0));
    ASSERT_EQ(output->GetNumberOfPoints(), rest->GetNumberOfPoints());
    EXPECT_EQ(output->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), step);
    for (vtkIdType p = 0; p < output->GetNumberOfPoints(); p += 5)
    {
      EXPECT_NEAR(output->GetPoint(p)[0], rest->GetPoint(p)[0] + step, 1e-12);
      EXPECT_NEAR(output->GetPoint(p)[1], rest->GetPoint(p)[1], 1e-12);
      if (step > 0)
      {
        EXPECT_NEAR(output->GetPointData()->GetArray("pressure")->GetComponent(p, 0), step, 1e-12);
      }
    }
    EXPECT_EQ(output->GetFieldData()->GetArray("NurbsTime")->GetComponent(0, 0), step);
  }
}

TEST(NurbsData, CopiesShareOrOwnAndTheGridIsCached)
{
  const auto set = randomSet(5);
  vtkNew<vtkIGANurbsData> data;
  ASSERT_EQ(data->SetPatches(set), "");
  const auto first = data->ToUnstructuredGrid();
  EXPECT_EQ(data->ToUnstructuredGrid().Get(), first.Get()) << "same step: cached grid";

  vtkNew<vtkIGANurbsData> shallow;
  shallow->ShallowCopy(data);
  EXPECT_EQ(&shallow->GetControlNet(0, 1), &data->GetControlNet(0, 1)) << "shared net";
  ASSERT_EQ(shallow->AddTimeStep(1.0, shiftedNets(set, 1.0)), "");
  EXPECT_EQ(shallow->GetNumberOfTimeSteps(), 2);
  EXPECT_EQ(data->GetNumberOfTimeSteps(), 1) << "copy on write";

  vtkNew<vtkIGANurbsData> deep;
  deep->DeepCopy(shallow);
  EXPECT_EQ(deep->GetNumberOfTimeSteps(), 2);
  EXPECT_NE(&deep->GetControlNet(1, 0), &shallow->GetControlNet(1, 0));
  EXPECT_EQ(deep->GetControlNet(1, 0), shallow->GetControlNet(1, 0));

  ASSERT_EQ(data->AddTimeStep(2.0, shiftedNets(set, 2.0)), "");
  EXPECT_NE(data->ToUnstructuredGrid(0).Get(), first.Get()) << "contents changed: new grid";

  // Memory: the two steps' nets (doubles) plus the cached grid, in KiB.
  size_t values = 0;
  for (int p = 0; p < data->GetNumberOfPatches(); ++p)
    values += data->GetControlNet(0, p).size() + data->GetControlNet(1, p).size();
  vtkNew<vtkIGANurbsData> fresh;
  fresh->DeepCopy(data);
  const unsigned long withoutGrid = fresh->GetActualMemorySize();
  EXPECT_GE(withoutGrid, values * sizeof(double) / 1024);
  EXPECT_LT(withoutGrid, values * sizeof(double) / 1024 + 16);
  const auto grid = fresh->ToUnstructuredGrid(1);
  EXPECT_EQ(fresh->GetActualMemorySize(), withoutGrid + grid->GetActualMemorySize());
}

/// The grid's cells, as the mapper collects them.
iga::VolumeSet<double> cellsOf(vtkUnstructuredGrid* grid)
{
  iga::VolumeSet<double> cells;
  std::string error;
  std::vector<std::string> warnings;
  EXPECT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, cells, error, warnings)) << error;
  return cells;
}

/// Volumes only: the engine takes no surfaces.
vtkSmartPointer<vtkUnstructuredGrid> volumesGrid(unsigned seed, double time = 0.0)
{
  iga::NurbsSet<double> set = randomSet(seed);
  set.surfaces.clear();
  vtkNew<vtkIGANurbsData> data;
  EXPECT_EQ(data->SetPatches(set, time), "");
  return data->ToUnstructuredGrid();
}

TEST(NurbsCells, TheCellsOfTheirOwnNurbsVolumesAreRecognised)
{
  const auto grid = volumesGrid(7);
  vtkIGANurbsCells form;
  ASSERT_TRUE(form.Collect(grid, cellsOf(grid)));
  ASSERT_EQ(form.Nets.size(), 2u);
  EXPECT_GT(form.ExtractionVersion, 0u);
  const auto volumes = form.Volumes();
  EXPECT_EQ(volumes.nets.size(), 2u);
  EXPECT_EQ(volumes.extractionVersion, form.ExtractionVersion);
  EXPECT_EQ(volumes.channels, iga::kFirstAttributeChannel + 2);
  // The same knots again (another time step of the same volumes) keep the version.
  const uint64_t version = form.ExtractionVersion;
  const auto again = volumesGrid(7, 1.0);
  ASSERT_TRUE(form.Collect(again, cellsOf(again)));
  EXPECT_EQ(form.ExtractionVersion, version);
}

TEST(NurbsCells, MovedOrMissingCellsAndBadNetsLeaveTheCells)
{
  const auto grid = volumesGrid(7);
  vtkIGANurbsCells form;
  // A filter moved a point but passed the field data on.
  vtkNew<vtkUnstructuredGrid> moved;
  moved->DeepCopy(grid);
  double point[3];
  moved->GetPoint(5, point);
  point[1] += 0.01;
  moved->GetPoints()->SetPoint(5, point);
  EXPECT_FALSE(form.Collect(moved, cellsOf(moved)));
  // Part of the cells (an MPI rank's).
  auto part = cellsOf(grid);
  part.patches.pop_back();
  EXPECT_FALSE(form.Collect(grid, part));
  // A net the engine would refuse: a non-positive weight, a NaN.
  for (double bad : { -1.0, std::nan("") })
  {
    vtkNew<vtkUnstructuredGrid> tampered;
    tampered->DeepCopy(grid);
    auto* net =
      vtkDoubleArray::SafeDownCast(tampered->GetFieldData()->GetAbstractArray("NurbsControlNet"));
    ASSERT_NE(net, nullptr);
    net->SetComponent(0, iga::kWeightChannel, bad);
    EXPECT_FALSE(form.Collect(tampered, cellsOf(tampered))) << bad;
  }
  EXPECT_TRUE(form.Collect(grid, cellsOf(grid)));
}

} // namespace
