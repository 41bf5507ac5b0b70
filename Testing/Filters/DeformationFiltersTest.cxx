// The deformation filters: displacement of control points by exactly scale * d, VTK's own
// evaluation of the moved cells, the synthetic time series against closed forms.
#include "FilterErrors.h"

#include "vtkIGABezierHexahedra.h"
#include "vtkIGADisplaceControlPoints.h"
#include "vtkIGASyntheticDeformation.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkGenericCell.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{

/// The tube at rest (8 tri-quadratic rational cells) with a 3-component point array "u".
vtkSmartPointer<vtkUnstructuredGrid> tubeWithDisplacement(int components = 3)
{
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.5, 0.0));
  vtkNew<vtkDoubleArray> u;
  u->SetName("u");
  u->SetNumberOfComponents(components);
  u->SetNumberOfTuples(grid->GetNumberOfPoints());
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      u->SetComponent(i, c, std::sin(0.37 * i + c) * (c + 1));
    }
  }
  grid->GetPointData()->AddArray(u);
  return grid;
}

} // namespace

TEST(DisplaceControlPoints, MovesEveryPointByScaleTimesDisplacement)
{
  auto grid = tubeWithDisplacement();
  double first[3];
  grid->GetPoint(0, first);
  vtkNew<vtkIGADisplaceControlPoints> filter;
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "u");
  filter->SetScaleFactor(2.5);
  ASSERT_TRUE(igatest::runCollectingErrors(filter, grid).empty());
  vtkUnstructuredGrid* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), grid->GetNumberOfPoints());
  ASSERT_EQ(out->GetNumberOfCells(), 8);
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double before[3], after[3];
    grid->GetPoint(i, before);
    out->GetPoint(i, after);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(after[c] - before[c], 2.5 * std::sin(0.37 * i + c) * (c + 1), 1e-14);
    }
  }
  // Weights, degrees and attributes pass unchanged and stay flagged.
  EXPECT_EQ(out->GetPointData()->GetRationalWeights(), grid->GetPointData()->GetRationalWeights());
  EXPECT_EQ(
    out->GetCellData()->GetHigherOrderDegrees(), grid->GetCellData()->GetHigherOrderDegrees());
  EXPECT_EQ(
    out->GetPointData()->GetArray("temperature"), grid->GetPointData()->GetArray("temperature"));
  EXPECT_EQ(grid->GetPoint(0)[0], first[0]); // the input is untouched
}

TEST(DisplaceControlPoints, RoundTripMovesTheRationalCellsRigidly)
{
  // A constant displacement is a translation, which commutes with the rational basis: VTK's
  // evaluation of every moved cell is its evaluation at rest plus scale * d.
  auto grid = tubeWithDisplacement();
  vtkNew<vtkDoubleArray> shift;
  shift->SetName("shift");
  shift->SetNumberOfComponents(3);
  shift->SetNumberOfTuples(grid->GetNumberOfPoints());
  const double d[3] = { 0.25, -1.5, 0.75 };
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    shift->SetTuple(i, d);
  }
  grid->GetPointData()->SetVectors(shift); // the default selection: active vectors
  vtkNew<vtkIGADisplaceControlPoints> filter;
  filter->SetScaleFactor(-0.5);
  ASSERT_TRUE(igatest::runCollectingErrors(filter, grid).empty());
  // Through the Kernels side: the patches read back have moved control points, same weights.
  iga::VolumeSet<double> rest, moved;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, rest, error, warnings)) << error;
  ASSERT_TRUE(
    vtkIGABezierHexahedra::FromUnstructuredGrid(filter->GetOutput(), moved, error, warnings))
    << error;
  ASSERT_EQ(moved.patches.size(), 8u);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0, 1);
  vtkNew<vtkGenericCell> cell;
  std::vector<double> weights(27);
  for (size_t c = 0; c < 8; ++c)
  {
    for (int s = 0; s < 10; ++s)
    {
      double u[3] = { unit(rng), unit(rng), unit(rng) }, a[8], b[8];
      iga::evaluateHomogeneous<double, 3>(rest.patches[c].view(), u, a, nullptr);
      iga::evaluateHomogeneous<double, 3>(moved.patches[c].view(), u, b, nullptr);
      double x[3];
      int subId = 0;
      filter->GetOutput()->GetCell(vtkIdType(c), cell);
      cell->EvaluateLocation(subId, u, x, weights.data());
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(b[k] / b[3], a[k] / a[3] - 0.5 * d[k], 1e-13);
        EXPECT_NEAR(x[k], a[k] / a[3] - 0.5 * d[k], 1e-13);
      }
      EXPECT_NEAR(b[4] / b[3], a[4] / a[3], 1e-14); // temperature stays on the material
    }
  }
}

TEST(DisplaceControlPoints, BadDisplacementsAreReported)
{
  vtkNew<vtkIGADisplaceControlPoints> filter;
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "missing");
  auto errors = igatest::runCollectingErrors(filter, tubeWithDisplacement());
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("no point array 'missing'"), std::string::npos) << errors[0];

  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "u");
  errors = igatest::runCollectingErrors(filter, tubeWithDisplacement(2));
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("'u' has 2 components, expected 3"), std::string::npos) << errors[0];

  auto grid = tubeWithDisplacement();
  vtkNew<vtkDoubleArray> cellVectors;
  cellVectors->SetName("c");
  cellVectors->SetNumberOfComponents(3);
  cellVectors->SetNumberOfTuples(8);
  cellVectors->Fill(0);
  grid->GetCellData()->AddArray(cellVectors);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "c");
  errors = igatest::runCollectingErrors(filter, grid);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("'c' is not a point array"), std::string::npos) << errors[0];

  grid = tubeWithDisplacement();
  vtkDoubleArray::SafeDownCast(grid->GetPointData()->GetArray("u"))
    ->SetComponent(17, 1, std::numeric_limits<double>::quiet_NaN());
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "u");
  errors = igatest::runCollectingErrors(filter, grid);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("non-finite value at point 17, component 1"), std::string::npos)
    << errors[0];
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  vtkNew<vtkIGADisplaceControlPoints> defaults; // no active vectors
  errors = igatest::runCollectingErrors(defaults, tubeWithDisplacement());
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("no active vectors"), std::string::npos) << errors[0];
}

TEST(SyntheticDeformation, DeclaresTimeStepsAndTwistsByTheRequestedTime)
{
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.5, 0.0));
  vtkNew<vtkIGASyntheticDeformation> filter;
  filter->SetInputData(grid);
  filter->SetNumberOfTimeSteps(5);
  filter->SetAmount(0.8); // radians over the height 2 at time 1
  filter->UpdateInformation();
  vtkInformation* info = filter->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 5);
  const double* steps = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  for (int i = 0; i < 5; ++i)
  {
    EXPECT_DOUBLE_EQ(steps[i], 0.25 * i);
  }
  for (double t : { 0.0, 0.75 })
  {
    filter->UpdateTimeStep(t);
    vtkUnstructuredGrid* out = filter->GetOutput();
    EXPECT_EQ(out->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), t);
    ASSERT_EQ(out->GetNumberOfPoints(), grid->GetNumberOfPoints());
    // The tube's bounds are [-1, 1]^2 x [0, 2] (the quadrant corners reach +-1): rotation about
    // the z axis by t * 0.8 * z / 2.
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
    {
      double x[3], y[3];
      grid->GetPoint(i, x);
      out->GetPoint(i, y);
      const double angle = t * 0.4 * x[2];
      EXPECT_NEAR(y[0], std::cos(angle) * x[0] - std::sin(angle) * x[1], 1e-14);
      EXPECT_NEAR(y[1], std::sin(angle) * x[0] + std::cos(angle) * x[1], 1e-14);
      EXPECT_NEAR(y[2], x[2], 1e-15);
    }
  }
}

TEST(SyntheticDeformation, LatticeBulgeBendAndWaveAtARequestedTime)
{
  // The dice: bounds [-1.25, 1.25]^3, so along z (length 2.5) s = (z + 1.25) / 2.5.
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeDice<double>());
  vtkNew<vtkIGASyntheticDeformation> filter;
  filter->SetInputData(grid);
  filter->SetAmount(0.4);
  filter->SetGenerateDisplacement(true);
  for (int mode : { vtkIGASyntheticDeformation::LATTICE, vtkIGASyntheticDeformation::BEND,
         vtkIGASyntheticDeformation::WAVE })
  {
    filter->SetMode(mode);
    filter->UpdateTimeStep(0.6);
    vtkUnstructuredGrid* out = filter->GetOutput();
    vtkDataArray* displacement = out->GetPointData()->GetVectors();
    ASSERT_NE(displacement, nullptr);
    ASSERT_NE(out->GetPointData()->GetArray("DisplacementMagnitude"), nullptr);
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); i += 7)
    {
      double x[3], y[3], expected[3];
      grid->GetPoint(i, x);
      out->GetPoint(i, y);
      const double s = (x[2] + 1.25) / 2.5;
      expected[0] = x[0];
      expected[1] = x[1];
      expected[2] = x[2];
      if (mode == vtkIGASyntheticDeformation::LATTICE)
      {
        expected[0] *= 1 + 0.6 * 0.4 * 2 * s * (1 - s);
        expected[1] *= 1 + 0.6 * 0.4 * 2 * s * (1 - s);
      }
      else if (mode == vtkIGASyntheticDeformation::BEND)
      {
        expected[0] += 0.6 * 0.4 * 2.5 * s * s;
      }
      else // wavelength 0.5 * 2.5, amplitude 0.4 * 2.5
      {
        expected[0] += 0.6 * 1.0 * std::sin(6.283185307179586 * (s * 2.5 / 1.25 - 0.6));
      }
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(y[c], expected[c], 1e-13) << "mode " << mode << " point " << i;
        EXPECT_NEAR(displacement->GetComponent(i, c), y[c] - x[c], 1e-15);
      }
    }
  }
  // The displacement undoes itself through vtkIGADisplaceControlPoints with scale -1.
  vtkNew<vtkIGADisplaceControlPoints> undo;
  undo->SetInputConnection(filter->GetOutputPort());
  undo->SetScaleFactor(-1);
  undo->UpdateTimeStep(0.6);
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); i += 5)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(undo->GetOutput()->GetPoint(i)[c], grid->GetPoint(i)[c], 1e-14);
    }
  }
}

TEST(SyntheticDeformation, FlatInputIsReported)
{
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.5, 0.0));
  vtkNew<vtkPoints> flat;
  flat->DeepCopy(grid->GetPoints());
  for (vtkIdType i = 0; i < flat->GetNumberOfPoints(); ++i)
  {
    double x[3];
    flat->GetPoint(i, x);
    flat->SetPoint(i, x[0], x[1], 0.0);
  }
  grid->SetPoints(flat);
  vtkNew<vtkIGASyntheticDeformation> filter;
  const auto errors = igatest::runCollectingErrors(filter, grid);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("not finite"), std::string::npos) << errors[0];
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}
