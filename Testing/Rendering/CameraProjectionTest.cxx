// vtkIGACameraProjection against VTK's own world-to-display transform, with a tiled viewport and
// a prop matrix.
#include "vtkIGACameraProjection.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <gtest/gtest.h>

#include <random>

namespace
{

void checkAgainstVTK(vtkRenderer* renderer, vtkActor* actor)
{
  vtkNew<vtkMatrix4x4> modelToClip;
  vtkIGACameraProjection::ComputeModelToClip(renderer, actor->GetMatrix(), modelToClip);
  std::mt19937 rng(120);
  std::uniform_real_distribution<double> coord(-1, 1);
  for (int s = 0; s < 50; ++s)
  {
    const double model[4] = { coord(rng), coord(rng), coord(rng), 1.0 };
    double clip[4], window[3], world[4];
    modelToClip->MultiplyPoint(model, clip);
    vtkIGACameraProjection::ClipToWindow(renderer, clip, window);
    actor->GetMatrix()->MultiplyPoint(model, world);
    renderer->SetWorldPoint(world);
    renderer->WorldToDisplay();
    double display[3];
    renderer->GetDisplayPoint(display);
    EXPECT_NEAR(window[0], display[0], 1e-9);
    EXPECT_NEAR(window[1], display[1], 1e-9);
    EXPECT_NEAR(window[2], display[2], 1e-12); // VTK's display z is the window depth in [0, 1]
  }
}

TEST(CameraProjection, MatchesWorldToDisplayInATiledViewportWithAPropMatrix)
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(640, 480);
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(0.2, 0.1, 0.9, 0.8);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(4, -3, 5);
  camera->SetFocalPoint(0.2, 0.1, -0.3);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(35);
  camera->SetClippingRange(1, 20);
  vtkNew<vtkActor> actor;
  actor->SetPosition(0.3, -0.2, 0.5);
  actor->SetOrientation(10, 25, -40);
  actor->SetScale(1.5, 0.7, 1.1);
  checkAgainstVTK(renderer, actor);

  camera->ParallelProjectionOn();
  camera->SetParallelScale(2.5);
  checkAgainstVTK(renderer, actor);
}

} // namespace
