/**
 * @class   vtkIGACameraProjection
 * @brief   The projective map from a prop's model coordinates to the clip space a renderer uses,
 *          as the isosurface engine needs it.
 *
 * VTK keeps its key matrices transposed for OpenGL (vtkOpenGLCamera::GetKeyMatrices); this class
 * returns them in VTK's row-major, column-vector convention instead, built from the renderer's
 * tiled viewport aspect (so tiled and multi-viewport rendering agree with VTK's own props) and
 * the prop's matrix. NDC depth lies in [-1, 1]; the window depth VTK writes is (z_ndc + 1) / 2.
 */
#ifndef vtkIGACameraProjection_h
#define vtkIGACameraProjection_h

#include "IGAViewRenderingModule.h" // for export macro
#include "vtkObject.h"

class vtkMatrix4x4;
class vtkRenderer;

class IGAVIEWRENDERING_EXPORT vtkIGACameraProjection : public vtkObject
{
public:
  static vtkIGACameraProjection* New();
  vtkTypeMacro(vtkIGACameraProjection, vtkObject);

  /**
   * Sets `modelToClip` = projection * view * propMatrix for the renderer's active camera.
   * `propMatrix` may be null (identity).
   */
  static void ComputeModelToClip(
    vtkRenderer* renderer, vtkMatrix4x4* propMatrix, vtkMatrix4x4* modelToClip);

  /// Window coordinates (pixels, origin bottom left, centre of pixel i at i + 0.5) and window
  /// depth in [0, 1] of a clip-space point, for the renderer's tiled viewport.
  static void ClipToWindow(vtkRenderer* renderer, const double clip[4], double window[3]);

protected:
  vtkIGACameraProjection() = default;
  ~vtkIGACameraProjection() override = default;

private:
  vtkIGACameraProjection(const vtkIGACameraProjection&) = delete;
  void operator=(const vtkIGACameraProjection&) = delete;
};

#endif
