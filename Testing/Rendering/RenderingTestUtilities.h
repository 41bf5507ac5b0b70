// Helpers shared by the rendering tests.
#pragma once

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkWindowToImageFilter.h>

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

} // namespace igatest
