// Attribute ranges cached in the arrays against independent references: analytic extremes, and
// dense samples of the cells through VTK's own Bézier evaluation.
#include "NurbsTestUtilities.h"
#include "vtkIGAAlgebraicSource.h"
#include "vtkIGAAttributeRanges.h"
#include "vtkIGAGismoReader.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace
{
/// The smallest and largest of the array's values (its control values).
std::pair<double, double> valueRange(vtkDataArray* array)
{
  double lo = array->GetComponent(0, 0), hi = lo;
  for (vtkIdType i = 1; i < array->GetNumberOfTuples(); ++i)
  {
    lo = std::min(lo, array->GetComponent(i, 0));
    hi = std::max(hi, array->GetComponent(i, 0));
  }
  return { lo, hi };
}

/// The array's range over n^3 parameters per cell, by VTK's evaluation of the cells.
std::pair<double, double> sampledRange(vtkUnstructuredGrid* grid, const std::string& name, int n)
{
  double lo = INFINITY, hi = -INFINITY;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        for (int k = 0; k <= n; ++k)
        {
          const double pcoords[3] = { double(i) / n, double(j) / n, double(k) / n };
          const double value = igatest::evaluateCell(grid, c, pcoords, { name })[3];
          lo = std::min(lo, value);
          hi = std::max(hi, value);
        }
  return { lo, hi };
}

void expectRange(vtkDataArray* array, double lo, double hi, double tolerance)
{
  double range[2], finite[2];
  array->GetRange(range, 0);
  array->GetFiniteRange(finite, 0);
  EXPECT_NEAR(range[0], lo, tolerance) << array->GetName();
  EXPECT_NEAR(range[1], hi, tolerance) << array->GetName();
  EXPECT_EQ(finite[0], range[0]) << array->GetName();
  EXPECT_EQ(finite[1], range[1]) << array->GetName();
  EXPECT_EQ(array->GetRange(-1)[0], range[0]) << array->GetName(); // VTK: a scalar's own
}
} // namespace

// f = r^2 - 1 over [-1.2, 1.2]^3 takes -1 (the centre) .. 3.32 (the corners); the degree-2
// Bernstein coefficients of each x^2 reach -1.44, so the control values reach -5.32.
TEST(AttributeRanges, AlgebraicSphereSourceGivesTheFieldsRange)
{
  vtkNew<vtkIGAAlgebraicSource> source;
  source->SetGallerySurfaceByName("sphere");
  source->Update();
  vtkDataArray* f = source->GetOutput()->GetPointData()->GetArray("f");
  ASSERT_NE(f, nullptr);
  EXPECT_NEAR(valueRange(f).first, -5.32, 1e-12);
  expectRange(f, -1.0, 3.32, 1e-5 * 4.32);
}

// The Marsden sphere's f = r^2 - 1 takes -1 .. 5.75 over its cell, its control values -3.25 ..
// 5.75 (docs/engine.md); a modified array is its values again.
TEST(AttributeRanges, AttachedToAVtuGridUntilItsArrayChanges)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(IGAVIEW_DATA_DIR "/marsden_sphere_p3.vtu");
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  vtkDataArray* f = grid->GetPointData()->GetArray("sphere");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->GetRange(0)[0], -3.25);
  EXPECT_EQ(vtkIGAAttributeRanges::Attach(grid), 1);
  expectRange(f, -1.0, 5.75, 1e-5 * 6.75);
  const auto sampled = sampledRange(grid, "sphere", 24);
  EXPECT_GE(sampled.first, f->GetRange(0)[0] - 1e-12);
  EXPECT_LE(sampled.second, f->GetRange(0)[1] + 1e-12);
  f->Modified();
  EXPECT_EQ(f->GetRange(0)[0], -3.25);
}

// Every scalar attribute of a NURBS reader's output: its cached range holds the dense samples
// and is within 1e-5 of their spread of them; temperature = x - 2z also against the positions.
TEST(AttributeRanges, NurbsReadersAttachTheirAttributesRanges)
{
  vtkNew<vtkIGAGismoReader> reader;
  reader->SetFileName(IGAVIEW_DATA_DIR "/gismo_quarter_ring_solution.xml");
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  ASSERT_GT(grid->GetNumberOfCells(), 0);
  int checked = 0;
  for (int a = 0; a < grid->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = grid->GetPointData()->GetArray(a);
    const std::string name = array->GetName();
    if (array->GetNumberOfComponents() != 1 || name == "RationalWeights")
      continue;
    const auto sampled = sampledRange(grid, name, 24);
    const double spread = sampled.second - sampled.first;
    double range[2];
    array->GetRange(range, 0);
    EXPECT_LE(range[0], sampled.first + 1e-12) << name;
    EXPECT_GE(range[1], sampled.second - 1e-12) << name;
    EXPECT_NEAR(range[0], sampled.first, 2e-3 * spread + 1e-12) << name;
    EXPECT_NEAR(range[1], sampled.second, 2e-3 * spread + 1e-12) << name;
    ++checked;
  }
  EXPECT_GE(checked, 4); // temperature, displacement_0..2, parameter_u/v/w
  double lo = INFINITY, hi = -INFINITY;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    for (int s = 0; s < 25 * 25 * 25; ++s)
    {
      const double pcoords[3] = { (s % 25) / 24.0, (s / 25 % 25) / 24.0, (s / 625) / 24.0 };
      const auto x = igatest::evaluateCell(grid, c, pcoords, {});
      lo = std::min(lo, x[0] - 2 * x[2]);
      hi = std::max(hi, x[0] - 2 * x[2]);
    }
  double temperature[2];
  grid->GetPointData()->GetArray("temperature")->GetRange(temperature, 0);
  EXPECT_NEAR(temperature[0], lo, 2e-3 * (hi - lo));
  EXPECT_NEAR(temperature[1], hi, 2e-3 * (hi - lo));
}

// Tetrahedra are not Bézier hexahedra or quadrilaterals: nothing is attached.
TEST(AttributeRanges, OtherCellsAreLeftAlone)
{
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> f;
  f->SetName("f");
  for (int p = 0; p < 4; ++p)
  {
    points->InsertNextPoint(p == 1, p == 2, p == 3);
    f->InsertNextValue(p - 3.0);
  }
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(f);
  const vtkIdType tetrahedron[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, tetrahedron);
  EXPECT_EQ(vtkIGAAttributeRanges::Attach(grid), 0);
  EXPECT_EQ(f->GetRange(0)[0], -3.0);
  EXPECT_EQ(f->GetRange(0)[1], 0.0);
  EXPECT_FALSE(f->GetInformation()->Has(vtkDataArray::L2_NORM_RANGE()));
}
