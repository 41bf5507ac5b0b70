/**
 * @class   vtkIGAIsosurfaceMapper
 * @brief   Draws pixel-exact isosurfaces of rational Bézier volumes into VTK's framebuffer,
 *          colour and depth, so they composite with every other prop.
 *
 * Input: a vtkUnstructuredGrid of VTK_BEZIER_HEXAHEDRON cells (RationalWeights,
 * HigherOrderDegrees; see vtkIGABezierHexahedra), or a composite dataset whose grid leaves share
 * their point arrays. Each render the mapper runs the SST engine for
 * the renderer's camera, the actor's matrix and the tiled viewport (only when one of them, the
 * data, the properties or the lights changed), shades the first hits with the actor's property
 * and the renderer's lights, and draws them with a full-screen pass that writes gl_FragDepth:
 * the depth VTK's own projection gives the same world point.
 *
 * Colouring follows vtkMapper: with ScalarVisibility on and a point array selected through
 * SelectColorArray (ScalarMode UsePointFieldData), the attribute is sampled at each hit and
 * mapped through the lookup table over ScalarRange; otherwise the property's colour is used.
 *
 * Lights follow vtkLight: directional (headlight, light kit) and positional ones with
 * attenuation and spot cone. Clipping planes (AddClippingPlane) cut the surface exactly: each
 * root is tested against them and patches entirely on the cut side are dropped. Hardware
 * selection (vtkHardwareSelector, vtkPropPicker) draws VTK's ids: the prop, the composite block,
 * the process and the cell (the patch the hit lies in); point ids are not drawn.
 *
 * A property opacity below 1 blends the first hit over what lies behind it in VTK's default
 * translucent pass, whose order-independent translucency hooks into this mapper's shader like
 * into vtkOpenGLPolyDataMapper's (render passes' DepthPeeling markers); the surface's own
 * further layers are not drawn. Known limit: with depth peeling (vtkDualDepthPeelingPass,
 * ParaView's default for translucent geometry) a translucent isosurface is not drawn yet.
 */
#ifndef vtkIGAIsosurfaceMapper_h
#define vtkIGAIsosurfaceMapper_h

#include "IGAViewRenderingModule.h" // for export macro
#include "vtkMapper.h"

#ifndef __VTK_WRAP__
#include "iga/sst/Engine.h" // for GBuffer
#endif

#include <memory> // for std::unique_ptr

class vtkDataObject;
#include <string> // for std::string
#include <vector> // for std::vector

class IGAVIEWRENDERING_EXPORT vtkIGAIsosurfaceMapper : public vtkMapper
{
public:
  static vtkIGAIsosurfaceMapper* New();
  vtkTypeMacro(vtkIGAIsosurfaceMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The grid of Bézier hexahedra, or composite dataset of them, to draw (or connect an input
  /// port).
  void SetInputData(vtkDataObject* input);

  ///@{
  /// Isovalues of the surface attribute (at least one is needed to draw anything).
  void SetNumberOfIsovalues(int count);
  int GetNumberOfIsovalues() const;
  void SetIsovalue(int index, double value);
  double GetIsovalue(int index) const;
  ///@}

  ///@{
  /// The point array whose isosurfaces are drawn; empty: the first attribute.
  void SetSurfaceArrayName(const char* name);
  const char* GetSurfaceArrayName() const { return this->SurfaceArrayName.c_str(); }
  ///@}

  ///@{
  /// CPU threads for the engine; 0 (default) uses all.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Milliseconds the engine took for the last frame it computed.
  double GetLastEngineTime() const { return this->LastEngineTime; }

#ifndef __VTK_WRAP__
  /// The last frame's G-buffer (all first hits) and its shaded colours (RGBA, premultiplied,
  /// row 0 at the bottom), e.g. for an OpenEXR export of what was drawn.
  const iga::sst::GBuffer& GetLastGBuffer() const;
  const std::vector<float>& GetLastColours() const;
#endif

  void Render(vtkRenderer* renderer, vtkActor* actor) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override
  {
    this->Superclass::GetBounds(bounds);
  }

protected:
  vtkIGAIsosurfaceMapper();
  ~vtkIGAIsosurfaceMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

private:
  vtkIGAIsosurfaceMapper(const vtkIGAIsosurfaceMapper&) = delete;
  void operator=(const vtkIGAIsosurfaceMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
  std::vector<double> Isovalues;
  std::string SurfaceArrayName;
  int NumberOfThreads = 0;
  double LastEngineTime = 0;
};

#endif
