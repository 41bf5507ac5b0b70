// Kernels patches <-> VTK Bézier hexahedra, checked against VTK's own rational interpolation
// (vtkBezierHexahedron), which is an independent implementation of the point ordering and
// the rational basis.
#include "NurbsTestUtilities.h"
#include "TestPatches.h"
#include "vtkIGABezierHexahedra.h"

#include "iga/Boundary.h"

#include "vtkBezierHexahedron.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <functional>
#include <utility>

using namespace igatest;

namespace
{

iga::VolumeSet<double> randomSet(std::mt19937& rng, int count)
{
  iga::VolumeSet<double> set;
  set.attributeNames = { "pressure", "temperature" };
  for (int c = 0; c < count; ++c)
  {
    int degree[3];
    randomDegrees<3>(rng, degree, 4);
    set.patches.push_back(randomPatch<double, 3>(rng, degree, 2));
  }
  return set;
}

TEST(BezierHexahedra, VTKInterpolationOfConvertedCellsMatchesKernels)
{
  std::mt19937 rng(100);
  const auto set = randomSet(rng, 12);
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(set);
  ASSERT_EQ(grid->GetNumberOfCells(), 12);
  ASSERT_NE(grid->GetPointData()->GetRationalWeights(), nullptr);
  ASSERT_NE(grid->GetCellData()->GetHigherOrderDegrees(), nullptr);
  std::uniform_real_distribution<double> unit(0, 1);
  vtkNew<vtkGenericCell> cell;
  int mirrored = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    EXPECT_EQ(grid->GetCellType(c), VTK_BEZIER_HEXAHEDRON);
    grid->GetCell(c, cell);
    const auto patch = rightHanded(set.patches[c]);
    mirrored += patch.coeffs() != set.patches[c].coeffs();
    const auto view = patch.view();
    std::vector<double> weights(cell->GetNumberOfPoints());
    for (int s = 0; s < 10; ++s)
    {
      double pcoords[3] = { unit(rng), unit(rng), unit(rng) };
      double x[3];
      int subId = 0;
      cell->EvaluateLocation(subId, pcoords, x, weights.data());
      const auto reference = evaluateEuclidean(view, pcoords);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(x[d], double(reference[d]), 1e-10) << "cell " << c << " coordinate " << d;
      }
      for (int a = 0; a < 2; ++a)
      {
        vtkDataArray* array = grid->GetPointData()->GetArray(set.attributeNames[a].c_str());
        double value = 0;
        for (vtkIdType p = 0; p < cell->GetNumberOfPoints(); ++p)
        {
          value += weights[p] * array->GetComponent(cell->GetPointId(p), 0);
        }
        EXPECT_NEAR(value, double(reference[iga::kFirstAttributeChannel + a]), 1e-10)
          << "cell " << c << " attribute " << a;
      }
    }
  }
  EXPECT_GT(mirrored, 0) << "no left-handed patch among the random ones";
  EXPECT_LT(mirrored, 12) << "no right-handed patch among the random ones";
}

TEST(BezierHexahedra, RoundTripIsExact)
{
  std::mt19937 rng(101);
  const auto set = randomSet(rng, 5);
  iga::VolumeSet<double> back;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(
    vtkIGABezierHexahedra::ToUnstructuredGrid(set), back, error, warnings))
    << error;
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(back.attributeNames, set.attributeNames);
  ASSERT_EQ(back.patches.size(), set.patches.size());
  for (size_t c = 0; c < set.patches.size(); ++c)
  {
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(back.patches[c].degree(d), set.patches[c].degree(d));
    const auto expected = rightHanded(set.patches[c]);
    for (size_t v = 0; v < expected.coeffs().size(); ++v)
      EXPECT_NEAR(back.patches[c].coeffs()[v], expected.coeffs()[v], 1e-12);
  }
}

/// The error from converting a grid that `damage` modified, or "" if it converted.
template<class Fn>
std::string conversionError(Fn damage, std::vector<std::string>* warnings = nullptr)
{
  std::mt19937 rng(102);
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(randomSet(rng, 3));
  damage(grid.Get());
  iga::VolumeSet<double> set;
  std::string error;
  std::vector<std::string> localWarnings;
  vtkIGABezierHexahedra::FromUnstructuredGrid(
    grid, set, error, warnings ? *warnings : localWarnings);
  return error;
}

TEST(BezierHexahedra, WrittenCellsAreRightHandedAndInsideOutOnesAreReadWithOneWarning)
{
  std::mt19937 rng(103);
  iga::VolumeSet<double> set;
  set.attributeNames = { "f" };
  for (int c = 0; c < 8; ++c)
  {
    set.patches.push_back(nearAffinePatch<double>(rng, 0.05));
    if (c % 2) // mirrored in x: left-handed
    {
      const auto view = set.patches.back().view();
      for (int p = 0; p < view.pointCount(); ++p)
        view.point(p)[0] = -view.point(p)[0];
    }
  }
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(set);
  EXPECT_EQ(validatorStates(grid), std::vector<int>(8, 0));

  // Mirroring space (x -> -x) turns every cell inside out; VTK says so, and so does reading.
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
  {
    double x[3];
    grid->GetPoint(p, x);
    grid->GetPoints()->SetPoint(p, -x[0], x[1], x[2]);
  }
  for (int state : validatorStates(grid))
    EXPECT_TRUE(state & vtkCellValidator::State::FacesAreOrientedIncorrectly) << state;
  iga::VolumeSet<double> back;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, back, error, warnings)) << error;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("8 of 8 cells are inside-out for VTK", 0), 0u) << warnings[0];
}

TEST(BezierHexahedra, BadInputIsNamed)
{
  // Points by the file's id, values by their array's name.
  EXPECT_EQ(conversionError([](vtkUnstructuredGrid* g)
              { g->GetPointData()->GetRationalWeights()->SetComponent(5, 0, -1.0); }),
    "cell 0: point 5: its rational weight ('RationalWeights') is -1, weights must be positive "
    "and finite");
  const std::string skewed = conversionError([](vtkUnstructuredGrid* g)
    { g->GetPointData()->GetRationalWeights()->SetComponent(5, 0, 1e9); });
  EXPECT_EQ(skewed.rfind("cell 0: its weights range over ", 0), 0u) << skewed;
  EXPECT_NE(skewed.find(" .. 1e+09, a ratio of "), std::string::npos) << skewed;
  EXPECT_NE(
    skewed.find(": more than the 1e+06 that subdivision resolves (array 'RationalWeights')"),
    std::string::npos)
    << skewed;
  vtkIdType last = 0;
  conversionError([&](vtkUnstructuredGrid* g) { last = g->GetNumberOfPoints() - 1; });
  EXPECT_EQ(conversionError([&](vtkUnstructuredGrid* g)
              { g->GetPointData()->GetArray("pressure")->SetComponent(last, 0, NAN); }),
    "cell 2: point " + std::to_string(last) + ": its value of 'pressure' is nan");
  EXPECT_EQ(
    conversionError([](vtkUnstructuredGrid* g) { g->GetPoints()->SetPoint(7, 0, 1e200, 0); }),
    "cell 0: point 7 at (0, 1e+200, 0) lies beyond 1e+100, farther than double precision can "
    "frame");
  EXPECT_NE(conversionError(
              [](vtkUnstructuredGrid* g)
              {
                g->GetPointData()->GetArray("pressure")->SetComponent(7, 0, 1e308);
                g->GetPointData()->GetRationalWeights()->SetComponent(7, 0, 10);
              })
              .find("): its values times its rational weight ('RationalWeights'), 10, pass "
                    "what double precision holds"),
    std::string::npos);
  EXPECT_NE(conversionError([](vtkUnstructuredGrid* g)
              { g->GetCellData()->GetHigherOrderDegrees()->SetComponent(1, 2, 40); })
              .find("cell 1: degree 40"),
    std::string::npos);
  EXPECT_NE(conversionError(
              [](vtkUnstructuredGrid* g)
              {
                auto* degrees = g->GetCellData()->GetHigherOrderDegrees();
                degrees->SetComponent(0, 0, degrees->GetComponent(0, 0) + 1);
              })
              .find("cell 0: has"),
    std::string::npos);
  EXPECT_NE(conversionError([](vtkUnstructuredGrid* g) { g->Initialize(); }).find("no cells"),
    std::string::npos);
}

/// What a hand-written file may hold that the converter must not coerce or read past.
TEST(BezierHexahedra, MalformedArraysAreRefusedNotCoerced)
{
  EXPECT_EQ(conversionError(
              [](vtkUnstructuredGrid* g)
              {
                vtkNew<vtkDoubleArray> degrees;
                degrees->DeepCopy(g->GetCellData()->GetHigherOrderDegrees());
                degrees->SetComponent(0, 0, 2.9);
                g->GetCellData()->SetHigherOrderDegrees(degrees);
              }),
    "cell 0: degree 2.9 in direction 0 is not a whole number in 1..16");
  EXPECT_EQ(conversionError(
              [](vtkUnstructuredGrid* g)
              {
                vtkNew<vtkDoubleArray> weights;
                weights->SetName("RationalWeights");
                weights->SetNumberOfComponents(3);
                weights->SetNumberOfTuples(g->GetNumberOfPoints());
                weights->Fill(1.0);
                // VTK takes no such array as the active weights: found by its name.
                g->GetPointData()->RemoveArray("RationalWeights");
                g->GetPointData()->AddArray(weights);
              }),
    "rational weights 'RationalWeights' have 3 components, expected 1");
  vtkIdType points = 0;
  EXPECT_EQ(conversionError([&](vtkUnstructuredGrid* g) { points = g->GetNumberOfPoints(); }), "");
  EXPECT_EQ(conversionError([&](vtkUnstructuredGrid* g)
              { g->GetPointData()->GetArray("pressure")->SetNumberOfTuples(points - 1); }),
    "point array 'pressure' has " + std::to_string(points - 1) + " values for " +
      std::to_string(points) + " points");
  EXPECT_EQ(conversionError([](vtkUnstructuredGrid* g)
              { g->GetPointData()->GetRationalWeights()->SetNumberOfTuples(3); }),
    "rational weights have 3 values for " + std::to_string(points) + " points");
}

TEST(BezierHexahedra, InactiveWeightsAreUsedWithAWarning)
{
  std::vector<std::string> warnings;
  const std::string error = conversionError(
    [](vtkUnstructuredGrid* g)
    {
      // Keep the array but drop its "active rational weights" flag, as many writers do.
      vtkSmartPointer<vtkDataArray> weights = g->GetPointData()->GetRationalWeights();
      g->GetPointData()->SetRationalWeights(nullptr);
      g->GetPointData()->AddArray(weights);
    },
    &warnings);
  EXPECT_EQ(error, "");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not flagged as the active rational weights"), std::string::npos);
}

} // namespace

namespace
{

/// The teapot's 32 quadrilaterals and, appended one by one, the tube's outer wall (8), all with
/// the height as attribute.
vtkSmartPointer<vtkUnstructuredGrid> mixedGrid()
{
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTeapot<double>());
  const auto tube = iga::makeTube<double>(0.5, 0.0);
  std::vector<vtkDataArray*> attributes = { grid->GetPointData()->GetArray("height") };
  for (const auto& patch : tube.patches)
  {
    auto face = iga::faceSurface(patch, 1, 1);
    iga::BezierSurface<double> surface(face.view().degree, iga::kFirstAttributeChannel + 1);
    for (int p = 0; p < face.view().pointCount(); ++p)
    {
      std::copy_n(face.view().point(p), iga::kFirstAttributeChannel + 1, surface.view().point(p));
      surface.view().point(p)[iga::kFirstAttributeChannel] = face.view().point(p)[2];
    }
    vtkIGABezierHexahedra::AppendQuadrilateral(grid, std::as_const(surface).view(), attributes);
  }
  return grid;
}

TEST(BezierHexahedra, QuadrilateralsRoundTripAsSurfaces)
{
  const auto teapot = iga::makeTeapot<double>();
  const auto grid = mixedGrid();
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, patches, error, warnings)) << error;
  ASSERT_EQ(patches.surfaces.size(), 40u);
  EXPECT_TRUE(patches.volumes.patches.empty());
  EXPECT_EQ(patches.volumes.attributeNames, std::vector<std::string>{ "height" });
  for (size_t s = 0; s < 32; ++s)
  {
    EXPECT_EQ(patches.surfaceCells[s], vtkIdType(s));
    const auto& a = teapot.patches[s].coeffs();
    const auto& b = patches.surfaces[s].coeffs();
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k)
      EXPECT_NEAR(a[k], b[k], 1e-14 * (1 + std::abs(a[k])));
  }
  // The volume-only reading refuses them, naming the first.
  iga::VolumeSet<double> set;
  EXPECT_FALSE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, set, error, warnings));
  EXPECT_EQ(error, "cell 0 is a quadrilateral (a surface), where hexahedra are needed");
}

TEST(BezierHexahedra, BadQuadrilateralsAreNamed)
{
  auto errorOf = [](const std::function<void(vtkUnstructuredGrid*)>& breakIt)
  {
    auto grid = mixedGrid();
    breakIt(grid);
    vtkIGABezierHexahedra::Patches patches;
    std::string error;
    std::vector<std::string> warnings;
    vtkIGABezierHexahedra::FromUnstructuredGrid(grid, patches, error, warnings);
    return error;
  };
  EXPECT_EQ(errorOf([](vtkUnstructuredGrid* g)
              { g->GetPointData()->GetRationalWeights()->SetComponent(20, 0, NAN); }),
    "cell 1: point 20: its rational weight ('RationalWeights') is nan, weights must be positive "
    "and finite");
  EXPECT_EQ(errorOf([](vtkUnstructuredGrid* g)
              { g->GetCellData()->GetHigherOrderDegrees()->SetComponent(3, 1, 4); }),
    "cell 3: has 16 points, degrees 3x4 need 20");
  EXPECT_EQ(errorOf([](vtkUnstructuredGrid* g)
              { g->GetCellData()->GetHigherOrderDegrees()->SetComponent(2, 0, 0); }),
    "cell 2: degree 0 in direction 0 is not a whole number in 1..16");
  EXPECT_EQ(errorOf(
              [](vtkUnstructuredGrid* g)
              {
                const vtkIdType triangle[3] = { 0, 1, 2 };
                g->InsertNextCell(VTK_TRIANGLE, 3, triangle);
                g->GetCellData()->GetHigherOrderDegrees()->InsertNextTuple3(1, 1, 0);
              }),
    "cell 40: cell type 5 is neither a hexahedron (VTK_BEZIER_HEXAHEDRON = 79, VTK_HEXAHEDRON = "
    "12) nor a quadrilateral (VTK_BEZIER_QUADRILATERAL = 77, VTK_QUAD = 9)");
}

} // namespace
