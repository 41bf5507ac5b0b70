// vtkIGAIsosurfaceMapper hands a GPU the NURBS form of its input (control nets and knots) when
// the grid's NURBS description matches its cells, and the cells otherwise. Without a GPU, a CUDA
// request runs the NURBS form through the engine's CPU fallback (host extraction): its image
// must equal the cells' image, over time steps, under an actor matrix, and after a filter made
// the description stale or kept only part of the cells.
#include "RenderingTestUtilities.h"
#include "vtkIGAIsosurfaceMapper.h"
#include "vtkIGANurbsData.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkExtractCells.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkUnstructuredGrid.h"

#include "iga/NurbsSet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{

/// A bent, rational B-spline cube of 3 x 3 x 3 quadratic elements, with the geometry
/// attributes; step 1 moves its control points.
vtkSmartPointer<vtkIGANurbsData> bentCube()
{
  iga::BSplinePatch<double, 3> volume;
  std::vector<double> euclidean, weights;
  for (int d = 0; d < 3; ++d)
  {
    volume.degree[d] = 2;
    volume.netSize[d] = 5;
    volume.knots[d] = { 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1 };
  }
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
      {
        const double x = i / 4.0, y = j / 4.0, z = k / 4.0;
        euclidean.insert(euclidean.end(), { x, y + 0.15 * std::sin(3 * x), z });
        weights.push_back(1.0 + 0.3 * ((i + j + k) % 2));
      }
  iga::setGeometryNet(volume, euclidean, weights);
  iga::NurbsSet<double> set;
  set.volumes.push_back(volume);
  set.attributeNames = iga::geometryAttributeNames();
  auto data = vtkSmartPointer<vtkIGANurbsData>::New();
  EXPECT_EQ(data->SetPatches(set, 0.0), "");
  std::vector<double> moved = volume.net;
  for (size_t p = 0; p < moved.size() / volume.channels; ++p)
  {
    double* cp = moved.data() + p * volume.channels;
    cp[2] += 0.2 * cp[0]; // shear in z (homogeneous: w z += 0.2 w x)
  }
  EXPECT_EQ(data->AddTimeStep(1.0, { moved }), "");
  return data;
}

/// The x = 0.55 isosurface of a grid, coloured by parameter_v, in a small offscreen window.
struct Scene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkSmartPointer<vtkImageData> image;

  explicit Scene(bool cuda)
  {
    window->SetOffScreenRendering(1);
    window->SetSize(160, 140);
    window->AddRenderer(renderer);
    mapper->SetSurfaceArrayName("x");
    mapper->SetIsovalue(0, 0.55);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("parameter_v");
    mapper->SetScalarRange(0, 1);
    if (cuda)
    {
      mapper->SetBackendToCUDA();
    }
    else
    {
      mapper->SetBackendToCPU();
    }
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(2.6, -1.2, 1.6);
    camera->SetFocalPoint(0.5, 0.5, 0.5);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(35);
  }

  void render(vtkDataObject* input)
  {
    mapper->SetInputData(input);
    renderer->ResetCameraClippingRange();
    image = igatest::renderAndGrab(window);
  }
};

/// Pixels whose colour differs by more than 2 in some channel.
int differingPixels(vtkImageData* a, vtkImageData* b)
{
  int dims[3];
  a->GetDimensions(dims);
  int differ = 0;
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i)
    {
      const auto* pa = static_cast<unsigned char*>(a->GetScalarPointer(i, j, 0));
      const auto* pb = static_cast<unsigned char*>(b->GetScalarPointer(i, j, 0));
      differ +=
        std::abs(pa[0] - pb[0]) > 2 || std::abs(pa[1] - pb[1]) > 2 || std::abs(pa[2] - pb[2]) > 2;
    }
  return differ;
}

TEST(MapperNurbsInput, TheGpuGetsNetsAndTheImageEqualsTheCells)
{
  auto data = bentCube();
  vtkSmartPointer<vtkUnstructuredGrid> step0 = data->ToUnstructuredGrid(0);
  Scene cells(false), nurbs(true);
  cells.render(step0);
  nurbs.render(step0);
  EXPECT_STREQ(cells.mapper->GetLastEngineInput(), "Bezier cells");
  EXPECT_EQ(cells.mapper->GetLastExtractionVersion(), 0u);
  EXPECT_STREQ(nurbs.mapper->GetLastEngineInput(), "NURBS volumes");
  const auto extraction = nurbs.mapper->GetLastExtractionVersion();
  EXPECT_NE(extraction, 0u);
  EXPECT_GT(nurbs.mapper->GetLastGBuffer().coveredPixels(), 2500u);
  EXPECT_LE(differingPixels(cells.image, nurbs.image), 3);

  // The next time step moves only the nets: same operators, new data, the moved image.
  vtkSmartPointer<vtkImageData> before = nurbs.image;
  const auto version = nurbs.mapper->GetLastDataVersion();
  vtkSmartPointer<vtkUnstructuredGrid> step1 = data->ToUnstructuredGrid(1);
  cells.render(step1);
  nurbs.render(step1);
  EXPECT_STREQ(nurbs.mapper->GetLastEngineInput(), "NURBS volumes");
  EXPECT_EQ(nurbs.mapper->GetLastExtractionVersion(), extraction);
  EXPECT_NE(nurbs.mapper->GetLastDataVersion(), version);
  EXPECT_GT(differingPixels(before, nurbs.image), 200) << "the shear did not move the surface";
  EXPECT_LE(differingPixels(cells.image, nurbs.image), 3);

  // An actor matrix moves the nets as it moves the cells.
  vtkNew<vtkTransform> turn;
  turn->RotateZ(20);
  turn->Translate(0.1, 0, 0);
  cells.actor->SetUserTransform(turn);
  nurbs.actor->SetUserTransform(turn);
  cells.render(step1);
  nurbs.render(step1);
  EXPECT_STREQ(nurbs.mapper->GetLastEngineInput(), "NURBS volumes");
  EXPECT_GT(nurbs.mapper->GetLastGBuffer().coveredPixels(), 1500u);
  EXPECT_LE(differingPixels(cells.image, nurbs.image), 3);
}

TEST(MapperNurbsInput, StaleOrPartialDescriptionFallsBackToTheCells)
{
  auto data = bentCube();
  // A filter that moves the points and passes the field data on: the description is stale.
  vtkNew<vtkUnstructuredGrid> moved;
  moved->DeepCopy(data->ToUnstructuredGrid(0));
  vtkPoints* points = moved->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    double x[3];
    points->GetPoint(p, x);
    x[2] += 0.1 * x[0];
    points->SetPoint(p, x);
  }
  points->Modified();
  Scene cells(false), nurbs(true);
  cells.render(moved);
  nurbs.render(moved);
  EXPECT_STREQ(nurbs.mapper->GetLastEngineInput(), "Bezier cells");
  EXPECT_EQ(nurbs.mapper->GetLastExtractionVersion(), 0u);
  EXPECT_EQ(differingPixels(cells.image, nurbs.image), 0);
  EXPECT_GT(nurbs.mapper->GetLastGBuffer().coveredPixels(), 2500u);

  // Part of the cells with the whole description, as a rank holds after redistribution.
  vtkNew<vtkExtractCells> part;
  part->SetInputData(data->ToUnstructuredGrid(0));
  part->AddCellRange(0, 13);
  part->Update();
  ASSERT_EQ(part->GetOutput()->GetNumberOfCells(), 14);
  ASSERT_NE(part->GetOutput()->GetFieldData()->GetAbstractArray("NurbsPatchInfo"), nullptr);
  cells.render(part->GetOutput());
  nurbs.render(part->GetOutput());
  EXPECT_STREQ(nurbs.mapper->GetLastEngineInput(), "Bezier cells");
  EXPECT_EQ(differingPixels(cells.image, nurbs.image), 0);
  EXPECT_GT(nurbs.mapper->GetLastGBuffer().coveredPixels(), 500u);

  // The automatic backend without a GPU draws the cells on CPU threads: no NURBS work at all.
  Scene automatic(false);
  automatic.mapper->SetBackendToAutomatic();
  automatic.render(data->ToUnstructuredGrid(0));
  if (std::string(automatic.mapper->GetLastBackend()) == "cuda")
  {
    GTEST_SKIP() << "a CUDA device drew the frame";
  }
  EXPECT_STREQ(automatic.mapper->GetLastEngineInput(), "Bezier cells");
}

} // namespace
