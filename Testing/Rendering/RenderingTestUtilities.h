// Helpers shared by the rendering tests.
#pragma once

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
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

} // namespace igatest
