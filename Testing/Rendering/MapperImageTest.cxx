// Regression images of vtkIGAIsosurfaceMapper scenes (baselines in Testing/Data/Baseline, compared
// with vtkTesting's image difference), plus numeric checks of what the images show.
// IGAVIEW_WRITE_BASELINES=1 writes the baselines instead of comparing.
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "iga/sst/Engine.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkSphereSource.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace
{

struct ImageScene : igatest::MapperScene
{
  explicit ImageScene(const iga::VolumeSet<double>& set)
    : MapperScene(300, 240)
  {
    mapper->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(set));
    actor->GetProperty()->SetSpecular(0.3);
    actor->GetProperty()->SetSpecularPower(30);
  }

  /// Compares the window with the baseline `name`.png (or writes it).
  void compare(const std::string& name) { igatest::compareWithBaseline(window, name); }
};

TEST(MapperImage, DefaultDataset)
{
  ImageScene scene(iga::makeTwistedTube<double>(0.5));
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.mapper->SetIsovalue(0, 0.0);
  scene.look(2.4, -3.0, 2.6, 0.2, 0, 1);
  scene.compare("MapperDefaultDataset");
}

TEST(MapperImage, InterpenetratingActors)
{
  ImageScene scene(iga::makeMarsdenSphere<double>(3));
  scene.mapper->SetIsovalue(0, 0.0);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0.6, -0.6, 0.3);
  ball->SetRadius(0.45);
  ball->SetThetaResolution(48);
  ball->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> ballActor;
  ballActor->SetMapper(ballMapper);
  ballActor->GetProperty()->SetColor(0.3, 0.7, 0.9);
  scene.renderer->AddActor(ballActor);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.6, -1.6, -0.2);
  plane->SetPoint1(1.6, -1.6, -0.2);
  plane->SetPoint2(-1.6, 1.6, -0.2);
  vtkNew<vtkPolyDataMapper> planeMapper;
  planeMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> planeActor;
  planeActor->SetMapper(planeMapper);
  planeActor->GetProperty()->SetColor(0.5, 0.8, 0.4);
  scene.renderer->AddActor(planeActor);
  scene.look(2.2, -4.0, 2.5, 0, 0, 0);
  scene.compare("MapperInterpenetratingActors");
}

TEST(MapperImage, ColouredByASecondAttributeWithScalarBar)
{
  ImageScene scene(iga::makeTwistedTube<double>(0.5));
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.mapper->SetIsovalue(0, 0.0);
  vtkNew<vtkColorTransferFunction> lut;
  lut->SetColorSpaceToDiverging();
  lut->AddRGBPoint(0.5, 0.231, 0.298, 0.753);
  lut->AddRGBPoint(1.0, 0.706, 0.016, 0.150);
  scene.mapper->SetLookupTable(lut);
  scene.mapper->SetScalarModeToUsePointFieldData();
  scene.mapper->SelectColorArray("radius");
  scene.mapper->SetScalarRange(0.5, 1.0);
  scene.mapper->ScalarVisibilityOn();
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  bar->SetTitle("radius");
  bar->SetNumberOfLabels(3);
  bar->SetPosition(0.85, 0.1);
  bar->SetWidth(0.12);
  bar->SetHeight(0.8);
  scene.renderer->AddActor2D(bar);
  scene.look(2.4, -3.0, 2.6, 0.2, 0, 1);
  scene.window->Render();
  // Every hit's colour is the lookup table's colour of its radius, shaded: the hue matches.
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  const auto& colours = scene.mapper->GetLastColours();
  int checked = 0;
  for (int p = 0; p < gbuffer.width * gbuffer.height; p += 37)
  {
    const auto* hit = gbuffer.firstHit(p % gbuffer.width, p / gbuffer.width);
    if (!hit)
      continue;
    double expected[3];
    lut->GetColor(hit->color, expected);
    const float* c = &colours[4 * size_t(p)];
    // Shading scales the colour (plus a white specular part): compare the red/blue balance.
    const double expectedBalance = expected[0] / (expected[0] + expected[2]);
    const double balance = c[0] / (c[0] + c[2] + 1e-9);
    if (c[0] + c[2] > 0.2 && std::abs(c[0] - c[1]) + std::abs(c[1] - c[2]) > 0.05)
    {
      EXPECT_NEAR(balance, expectedBalance, 0.15) << "pixel " << p << " radius " << hit->color;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
  scene.compare("MapperColouredWithScalarBar");
}

TEST(MapperImage, TwoIsovalues)
{
  ImageScene scene(iga::makeTwistedTube<double>(0.5));
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.mapper->SetIsovalue(0, -0.35);
  scene.mapper->SetIsovalue(1, 0.35);
  scene.look(2.4, -3.0, 2.6, 0.2, 0, 1);
  scene.compare("MapperTwoIsovalues");
  // Both surfaces are drawn.
  int first = 0, second = 0;
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  for (const auto& hit : gbuffer.hits)
    (hit.isovalue == 0 ? first : second)++;
  EXPECT_GT(first, 1000);
  EXPECT_GT(second, 1000);
}

TEST(MapperImage, ClippingPlane)
{
  ImageScene scene(iga::makeTwistedTube<double>(0.5));
  scene.mapper->SetSurfaceArrayName("radius");
  scene.mapper->SetIsovalue(0, 0.8);
  scene.look(2.4, -3.0, 2.6, 0.2, 0, 1);
  scene.window->Render();
  const size_t whole = scene.mapper->GetLastGBuffer().coveredPixels();
  // Kept: -0.3 x + y - 0.2 z >= -0.1, a plane slanted through the tube that removes its front.
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0, -0.1, 0);
  plane->SetNormal(-0.3, 1, -0.2);
  scene.mapper->AddClippingPlane(plane);
  scene.compare("MapperClippingPlane");
  // Every drawn hit lies on the kept side; hits reach the plane (the cut is exact, not by
  // patches), and the cut opens the view onto the inside of the surface.
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  double nearest = 1e9;
  int inside = 0;
  for (const auto& hit : gbuffer.hits)
  {
    const double value = plane->EvaluateFunction(hit.position[0], hit.position[1], hit.position[2]);
    EXPECT_GE(value, -1e-9);
    nearest = std::min(nearest, value);
    double fromAxis[2] = { hit.position[0], hit.position[1] };
    inside +=
      glm::dot(hit.normal,
        glm::make_vec3(scene.renderer->GetActiveCamera()->GetDirectionOfProjection())) < 0 &&
          fromAxis[0] * hit.normal[0] + fromAxis[1] * hit.normal[1] < 0
        ? 1
        : 0;
  }
  EXPECT_LT(nearest, 0.01);
  EXPECT_LT(gbuffer.coveredPixels(), whole);
  EXPECT_GT(inside, 200) << "the inner wall of the cylinder shows through the cut";
}

} // namespace
