// vtkIGAIsosurfaceMapper in a real render window: its depth equals VTK's projection of the
// analytic hit, and it occludes and is occluded by ordinary actors exactly where each is in front.
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Camera.h"
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace
{

struct Scene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkActor> isosurface;
  vtkSmartPointer<vtkImageData> image;

  Scene()
  {
    window->SetOffScreenRendering(1);
    window->SetSize(200, 160);
    window->AddRenderer(renderer);
    renderer->SetBackground(0, 0, 0);
    mapper->SetInputData(
      vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeMarsdenSphere<double>(2)));
    mapper->SetIsovalue(0, 0.0);
    isosurface->SetMapper(mapper);
    isosurface->GetProperty()->SetColor(1, 0, 0);
    renderer->AddActor(isosurface);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0, -4, 0);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(40);
    camera->SetClippingRange(1, 10);
  }

  void addSphere(double x, double y, double z, double radius)
  {
    vtkNew<vtkSphereSource> source;
    source->SetCenter(x, y, z);
    source->SetRadius(radius);
    source->SetThetaResolution(64);
    source->SetPhiResolution(64);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0, 1, 0);
    actor->GetProperty()->SetAmbient(1);
    actor->GetProperty()->SetDiffuse(0);
    renderer->AddActor(actor);
  }

  void render()
  {
    window->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    image = grab->GetOutput();
  }

  /// Display coordinates (pixel centre) and VTK's window depth of a world point.
  void display(const double* world, int& i, int& j, double& depth)
  {
    renderer->SetWorldPoint(world[0], world[1], world[2], 1);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    i = int(std::floor(d[0]));
    j = int(std::floor(d[1]));
    depth = d[2];
  }

  const unsigned char* pixel(int i, int j)
  {
    return static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
  }
};

TEST(IsosurfaceMapper, DepthMatchesVTKsProjectionOfTheAnalyticHit)
{
  Scene scene;
  scene.render();
  // Rays through a few pixels: analytic first hit with the unit sphere, projected by VTK.
  int checked = 0;
  for (const auto& target : { std::array<double, 3>{ 0, -1, 0 },
         std::array<double, 3>{ 0.5, -0.7, 0.3 }, std::array<double, 3>{ -0.6, -0.6, -0.4 } })
  {
    int i, j;
    double ignored;
    scene.display(target.data(), i, j, ignored);
    // The pixel centre's ray, from VTK's inverse projection.
    double nearPoint[4], farPoint[4];
    scene.renderer->SetDisplayPoint(i + 0.5, j + 0.5, 0);
    scene.renderer->DisplayToWorld();
    scene.renderer->GetWorldPoint(nearPoint);
    scene.renderer->SetDisplayPoint(i + 0.5, j + 0.5, 1);
    scene.renderer->DisplayToWorld();
    scene.renderer->GetWorldPoint(farPoint);
    double o[3], d[3];
    for (int k = 0; k < 3; ++k)
    {
      o[k] = nearPoint[k] / nearPoint[3];
      d[k] = farPoint[k] / farPoint[3] - o[k];
    }
    const double a = iga::dot3(d, d), b = 2 * iga::dot3(o, d), c = iga::dot3(o, o) - 1;
    const double t = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
    const double hit[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
    int hi, hj;
    double expected;
    scene.display(hit, hi, hj, expected);
    ASSERT_EQ(hi, i);
    ASSERT_EQ(hj, j);
    const double depth = scene.window->GetZbufferDataAtPoint(i, j);
    EXPECT_NEAR(depth, expected, 2e-6) << "pixel " << i << "," << j;
    EXPECT_GT(scene.pixel(i, j)[0], 40) << "the isosurface is red";
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // Nothing is drawn outside the sphere: the depth buffer keeps its clear value.
  EXPECT_EQ(scene.window->GetZbufferDataAtPoint(3, 3), 1.0f);
}

TEST(IsosurfaceMapper, OccludesAndIsOccludedByOrdinaryActors)
{
  Scene scene;
  // In front of the isosurface: its near cap pokes out towards the camera.
  scene.addSphere(0, -1.0, 0, 0.25);
  // Inside the isosurface: hidden.
  scene.addSphere(0.55, 0, 0.2, 0.3);
  scene.render();
  const double front[3] = { 0, -1.2, 0 }, inside[3] = { 0.55, -0.3, 0.2 };
  int i, j;
  double depth;
  scene.display(front, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[1], 200) << "the sphere in front is green";
  EXPECT_LT(scene.pixel(i, j)[0], 30);
  scene.display(inside, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[0], 40) << "the isosurface hides the inner sphere";
  EXPECT_LT(scene.pixel(i, j)[1], 30);
  // Next to the front sphere's rim the isosurface is in front again.
  const double beside[3] = { 0.35, -0.93, 0 };
  scene.display(beside, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[0], 40);
  EXPECT_LT(scene.pixel(i, j)[1], 30);
}

TEST(IsosurfaceMapper, ReusesTheFrameUntilSomethingChanges)
{
  Scene scene;
  scene.render();
  const double first = scene.mapper->GetLastEngineTime();
  EXPECT_GT(first, 0);
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastEngineTime(), first) << "an unchanged frame ran the engine again";
  scene.renderer->GetActiveCamera()->Azimuth(10);
  scene.render();
  EXPECT_NE(scene.mapper->GetLastEngineTime(), first);
}

} // namespace
