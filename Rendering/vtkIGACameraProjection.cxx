#include "vtkIGACameraProjection.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkIGACameraProjection);

void vtkIGACameraProjection::ComputeModelToClip(
  vtkRenderer* renderer, vtkMatrix4x4* propMatrix, vtkMatrix4x4* modelToClip)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  // Same aspect as vtkViewport::WorldToView and vtkOpenGLCamera: the tiled viewport's.
  vtkMatrix4x4* worldToClip =
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
  if (propMatrix)
  {
    vtkMatrix4x4::Multiply4x4(worldToClip, propMatrix, modelToClip);
  }
  else
  {
    modelToClip->DeepCopy(worldToClip);
  }
}

void vtkIGACameraProjection::ClipToWindow(
  vtkRenderer* renderer, const double clip[4], double window[3])
{
  int size[2], origin[2];
  renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  for (int d = 0; d < 2; ++d)
  {
    window[d] = origin[d] + (clip[d] / clip[3] + 1.0) * 0.5 * size[d];
  }
  window[2] = (clip[2] / clip[3] + 1.0) * 0.5;
}
