// vtkIGABoundarySurface: the boundary faces of Bézier hexahedra as Bézier quadrilaterals, checked
// through VTK's own evaluation of both cell types.
#include "FilterErrors.h"
#include "NurbsTestUtilities.h"

#include "vtkIGABezierHexahedra.h"
#include "vtkIGABoundarySurface.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Boundary.h"
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <random>

namespace
{

vtkSmartPointer<vtkUnstructuredGrid> boundaryOf(vtkUnstructuredGrid* grid)
{
  vtkNew<vtkIGABoundarySurface> boundary;
  boundary->SetInputData(grid);
  boundary->Update();
  auto output = vtkSmartPointer<vtkUnstructuredGrid>::New();
  output->ShallowCopy(boundary->GetOutput());
  return output;
}

/// Each boundary quadrilateral of the deformed tube, evaluated by VTK at (s, t), equals the
/// hexahedron it comes from evaluated by VTK on that face: position and every attribute.
TEST(BoundarySurface, QuadrilateralsAreTheHexahedraOnTheirFaces)
{
  const auto tube = iga::makeTube<double>(0.25, 0.6);
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(tube);
  const auto surface = boundaryOf(grid);
  ASSERT_EQ(surface->GetNumberOfCells(), 24);
  ASSERT_NE(surface->GetPointData()->GetRationalWeights(), nullptr);
  vtkDataArray* fromCell = surface->GetCellData()->GetArray("BoundaryCell");
  vtkDataArray* fromFace = surface->GetCellData()->GetArray("BoundaryFace");
  ASSERT_NE(fromCell, nullptr);
  ASSERT_NE(fromFace, nullptr);
  std::mt19937 random(12);
  std::uniform_real_distribution<double> unit(0, 1);
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    EXPECT_EQ(surface->GetCellType(c), VTK_BEZIER_QUADRILATERAL);
    const int face = int(fromFace->GetComponent(c, 0)), direction = face / 2;
    int s, t;
    iga::faceDirections(direction, s, t);
    for (int sample = 0; sample < 5; ++sample)
    {
      const double st[3] = { unit(random), unit(random), 0 };
      double u[3];
      u[direction] = face % 2;
      u[s] = st[0];
      u[t] = st[1];
      const auto onFace = igatest::evaluateCell(surface, c, st, tube.attributeNames);
      const auto inVolume = igatest::evaluateCell(
        grid, vtkIdType(fromCell->GetComponent(c, 0)), u, tube.attributeNames);
      for (size_t k = 0; k < onFace.size(); ++k)
        EXPECT_NEAR(onFace[k], inVolume[k], 1e-12) << "cell " << c << " value " << k;
    }
  }
}

TEST(BoundarySurface, CollapsedAndSharedFacesAreLeftOut)
{
  const auto cylinder =
    boundaryOf(vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.0, 0.0)));
  EXPECT_EQ(cylinder->GetNumberOfCells(), 16);
  const auto blade = boundaryOf(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeBlade<double>(iga::bladeLayout(400), 0.5)));
  const auto layout = iga::bladeLayout(400);
  EXPECT_EQ(blade->GetNumberOfCells(),
    2 * layout.around * layout.along + 2 * layout.around * layout.through);
}

TEST(BoundarySurface, InputOtherThanBezierHexahedraIsOneError)
{
  vtkNew<vtkUnstructuredGrid> empty;
  vtkNew<vtkIGABoundarySurface> boundary;
  const auto errors = igatest::runCollectingErrors(boundary, empty);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("cannot take the boundary of the input: the grid has no cells"),
    std::string::npos);
  EXPECT_EQ(boundary->GetOutput()->GetNumberOfCells(), 0);
}

} // namespace
