// Helpers shared by the rendering tests.
#pragma once

#include "vtkIGAIsosurfaceMapper.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkTesting.h>
#include <vtkWindowToImageFilter.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#ifndef IGAVIEW_BASELINE_DIR
#error "IGAVIEW_BASELINE_DIR must name the baseline image folder"
#endif

namespace igatest
{

/// Renders the window and returns its back buffer as an RGB image (row 0 at the bottom).
inline vtkSmartPointer<vtkImageData> renderAndGrab(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  return grab->GetOutput();
}

/// The camera of the unit-sphere scenes: 4 units down -y, looking at the origin, z up, a 40
/// degree view angle and fixed clipping planes (depths in tests do not move with the data).
inline void lookAtTheOriginFromMinusY(vtkCamera* camera)
{
  camera->SetPosition(0, -4, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(40);
  camera->SetClippingRange(1, 10);
}

/// A mapper of a finely tessellated polydata sphere (an ordinary VTK prop to composite with).
inline vtkSmartPointer<vtkPolyDataMapper> sphereMapper(double x, double y, double z, double radius)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(x, y, z);
  source->SetRadius(radius);
  source->SetThetaResolution(64);
  source->SetPhiResolution(64);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  return mapper;
}

/// The image tests' scene: an offscreen window (no multisampling) of width x height, a dark
/// background, and an actor of the IGA mapper in a sand colour.
struct MapperScene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkActor> actor;

  MapperScene(int width, int height)
  {
    window->SetOffScreenRendering(1);
    window->SetSize(width, height);
    window->SetMultiSamples(0);
    window->AddRenderer(renderer);
    renderer->SetBackground(0.1, 0.1, 0.15);
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.9, 0.75, 0.45);
    renderer->AddActor(actor);
  }

  /// A z-up camera at (x, y, z) looking at (fx, fy, fz), 30 degrees, clipping range to the data.
  void look(double x, double y, double z, double fx, double fy, double fz)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(x, y, z);
    camera->SetFocalPoint(fx, fy, fz);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(30);
    renderer->ResetCameraClippingRange();
  }
};

/// Renders the window and compares it with the baseline `name`.png of Testing/Data/Baseline
/// (vtkTesting's image difference, threshold 10); IGAVIEW_WRITE_BASELINES=1 writes it instead
/// and skips the test, visibly.
inline void compareWithBaseline(vtkRenderWindow* window, const std::string& name)
{
  window->Render();
  const std::string baseline = std::string(IGAVIEW_BASELINE_DIR) + "/" + name + ".png";
  if (std::getenv("IGAVIEW_WRITE_BASELINES"))
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(baseline.c_str());
    writer->Write();
    GTEST_SKIP() << "wrote " << baseline;
  }
  vtkNew<vtkTesting> testing;
  testing->AddArgument("-V");
  testing->AddArgument(baseline.c_str());
  testing->AddArgument("-T");
  testing->AddArgument(::testing::TempDir().c_str());
  testing->SetRenderWindow(window);
  EXPECT_EQ(testing->RegressionTest(10), vtkTesting::PASSED) << "image differs from " << baseline;
}

} // namespace igatest
