/**
 * @class   vtkIGAIsosurfaceMapper
 * @brief   Draws pixel-exact isosurfaces of rational Bézier volumes into VTK's framebuffer,
 *          colour and depth, so they composite with every other prop.
 *
 * Input: a vtkUnstructuredGrid of VTK_BEZIER_HEXAHEDRON and VTK_BEZIER_QUADRILATERAL cells
 * (RationalWeights, HigherOrderDegrees; see vtkIGABezierHexahedra), or a composite dataset whose
 * grid leaves share their point arrays. DrawMode says what is drawn: the hexahedra's
 * isosurfaces (DRAW_ISOSURFACES, the default) or their boundary (DRAW_SURFACES: the faces of
 * the volumes that no other volume shares and that are not collapsed, found once per topology
 * and sliced from the control nets every time the data change, so a deforming volume's
 * boundary moves with it); quadrilateral cells are drawn as the surfaces they are in both.
 * With the property's EdgeVisibility on (ParaView's "Surface With Edges") the element edges are
 * drawn over the shading in EdgeColor, LineWidth pixels wide and anti-aliased: where a hit's
 * parameter in its Bézier element reaches 0 or 1 (iga/sst/ElementEdges.h), so at every knot line
 * of NURBS input, exactly at any zoom. Each render the mapper runs the SST engine for
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
 * A property opacity below 1 draws every layer of the surface (every hit along a pixel's ray,
 * the 8 nearest where a pixel has more), each blended over what lies behind it. VTK's
 * translucency techniques hook into this mapper's shader like into vtkOpenGLPolyDataMapper's
 * (render passes' DepthPeeling markers), the layers are drawn as fragments of their own at
 * every peel: the default translucent pass (order-independent: an alpha-weighted average of
 * the layers), dual depth peeling (vtkRenderer::UseDepthPeeling on OpenGL >= 3.2, ParaView's
 * default for translucent geometry) and the classic vtkDepthPeelingPass; under depth peeling
 * each layer blends in exact depth order with the others and with other translucent props
 * (given enough peels: vtkRenderer::SetMaximumNumberOfPeels). Depth
 * peeling needs a render window without multisampling (SetMultiSamples(0), as vtkRenderer
 * documents and ParaView does): with VTK 9.2 on a multisampled window the peeling passes' copy
 * of the opaque depth fails on strict drivers (Mesa) and no translucent prop at all is drawn;
 * the mapper warns about it (once until its settings or the input change).
 *
 * Engine settings: Backend (automatic: CUDA where the library was built with it and a device
 * is usable, else CPU threads; CPU; CUDA, which falls back to CPU threads when it cannot run),
 * NumberOfThreads (CPU), MaximumSubdivisionDepth and MemoryBudgetMB (the caps at which a pixel
 * with work left is given up and counted as unresolved), FrameDeadline (seconds after which a
 * frame stops with what it has found), Method (automatic: patches with affine geometry, as
 * algebraic surfaces over a box, by ray composition, the rest by the shared subdivision tree,
 * composited in one frame; one of them for all) and RootFinder (ray composition's).
 * GetLastRayCompositionPatches() and GetLastSstPatches() say how many patches took each path
 * (a CUDA frame draws every patch by the tree). Changing any of them re-runs the engine.
 * GetLastBackend() says where the last frame ran; when that is not where it was asked to run, the
 * engine's one-line notice is printed once per mapper and notice: a warning when CUDA was asked for
 * (Backend CUDA, or IGAVIEW_BACKEND=cuda) or a CUDA frame failed, a plain message (vtkOutputWindow
 * text) when the automatic choice fell back to CPU threads.
 *
 * NURBS input on a GPU: when a frame is tried on a GPU and the input is one grid that carries
 * the NURBS description vtkIGANurbsData writes (the readers' and sources' output), the mapper
 * hands the engine the control nets and knot vectors instead of the Bézier cells, provided the
 * extracted elements equal the grid's cells (checked once per input change: a filter that moved
 * the points or dropped cells without updating that description fails it). The GPU then
 * extracts the elements itself, so a new time step sends only the moved control nets, and the
 * extraction operators stay on the device while the knots do not change.
 * GetLastEngineInput() says which form the last frame used.
 *
 * Progress: while the engine runs, the mapper fires vtkCommand::ProgressEvent (vtkAlgorithm's
 * UpdateProgress) with a monotone estimate in [0, 1) after every subdivision round, from the
 * (pixel, sub-patch) pairs left relative to the most seen in the frame, and 1 at the end of
 * the frame. Frames reused from the last render report nothing. The mapper brings its input up
 * to date through the producer's pipeline (not a pipeline pass of its own, which would fire
 * progress 0 and 1 around the engine's).
 *
 * Messages: unresolved pixels (a warning naming the cap that was hit, once per cap), a missing
 * surface array and engine errors are reported once until the mapper's own settings (not the
 * lookup table) or the input change, not on every render or camera move;
 * GetLastUnresolvedPixels() gives the count of the last frame computed.
 *
 * Curvature: with DRAW_ISOSURFACES, ScalarVisibility on and the colour array named
 * "curvature_mean" or "curvature_gauss" (SelectColorArray; no such attribute is needed), the
 * surface is coloured by its mean or Gaussian curvature at each hit, in world coordinates
 * (iga::isosurfaceCurvature: through the geometry's second derivatives; the mean with respect
 * to the normal towards lower values of the surface array, so that a sphere around a minimum
 * has 1/r), mapped through the lookup table and its ScalarRange like an attribute.
 *
 * Lookup table: with UseLookupTableScalarRange off (vtkMapper's default) the table's range is
 * set to ScalarRange when colouring by scalars; with it on the table's own range is left alone,
 * as vtkOpenGLPolyDataMapper does.
 */
#ifndef vtkIGAIsosurfaceMapper_h
#define vtkIGAIsosurfaceMapper_h

#include "IGAViewRenderingModule.h" // for export macro
#include "vtkMapper.h"

#ifndef __VTK_WRAP__
#include "iga/sst/GBuffer.h" // for GBuffer
namespace iga
{
namespace sst
{
struct FrameReport;
struct Settings;
struct View;
class Scene;
}
}
#endif

#include <array>  // for the planes
#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkDataObject;
class vtkFieldData;
class vtkHardwareSelector;
class vtkMatrix4x4;
class vtkOpenGLRenderPass;
class vtkOpenGLRenderWindow;
class vtkProperty;

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
  /// Isovalues of the surface attribute (at least one is needed to draw isosurfaces).
  void SetNumberOfIsovalues(int count);
  int GetNumberOfIsovalues() const;
  void SetIsovalue(int index, double value);
  double GetIsovalue(int index) const;
  ///@}

  enum DrawModeType
  {
    DRAW_ISOSURFACES = 0, ///< the hexahedra's isosurfaces (and quadrilaterals as surfaces)
    DRAW_SURFACES = 1,    ///< the hexahedra's boundary faces and the quadrilaterals
    DRAW_CSG = 2,         ///< the CsgExpression's solid and the slices, of the hexahedra
  };

  ///@{
  /// What is drawn (DrawModeType); default the isosurfaces. Surfaces need no isovalue.
  vtkSetClampMacro(DrawMode, int, DRAW_ISOSURFACES, DRAW_CSG);
  vtkGetMacro(DrawMode, int);
  void SetDrawModeToIsosurfaces() { this->SetDrawMode(DRAW_ISOSURFACES); }
  void SetDrawModeToSurfaces() { this->SetDrawMode(DRAW_SURFACES); }
  void SetDrawModeToCsg() { this->SetDrawMode(DRAW_CSG); }
  ///@}

  ///@{
  /// The solid DRAW_CSG draws (iga/Csg.h's grammar): point arrays' solids `NAME<VALUE` and
  /// `NAME>VALUE`, the hexahedra's whole `domain` and half-spaces `plane(a,b,c,d)` (a x + b y +
  /// c z + d >= 0), joined by `|` (union), `&` (intersection, binding tighter) and `-`
  /// (difference), grouped by parentheses; e.g. "cube<0 - pips<0". Every solid lies within the
  /// hexahedra, whose boundary closes it (the caps are drawn, coloured like the rest); each
  /// block of a composite input is closed by its own boundary, so blocks may overlap. Empty
  /// (the default): only the slices. An expression that does not parse is refused with an
  /// error naming the position, and the previous one kept; a point array no grid has is said
  /// when drawing. Hits name their operand (iga::sst::Hit::isovalue in GetLastGBuffer).
  /// Quadrilateral cells are not drawn in DRAW_CSG.
  void SetCsgExpression(const char* expression);
  const char* GetCsgExpression() const { return this->CsgExpression.c_str(); }
  ///@}

  ///@{
  /// Slices DRAW_CSG draws with the solid: the sections a x + b y + c z + d = 0 of the
  /// hexahedra, exact, coloured like the rest (by the colour array through the lookup table).
  /// Setting slice `index` adds slices up to it as needed (the new ones x = 0).
  void SetNumberOfSlices(int count);
  int GetNumberOfSlices() const { return static_cast<int>(this->Slices.size()); }
  void SetSlice(int index, double a, double b, double c, double d);
  ///@}

  ///@{
  /// Capped clips of DRAW_CSG: each keeps the part a x + b y + c z + d >= 0 (world coordinates,
  /// like clipping planes) of the solid, or of the hexahedra when there is no expression, with
  /// its cut face drawn and coloured like the rest, and cuts the slices: the solid drawn is
  /// CsgExpression intersected with the half-spaces (iga::csg::cutByHalfSpaces). A clipping
  /// plane (AddClippingPlane) cuts the surface open; a capped clip closes it. A zero normal is
  /// refused with an error. Setting clip `index` adds clips up to it as needed (the new ones
  /// x >= 0).
  void SetNumberOfCappedClips(int count);
  int GetNumberOfCappedClips() const { return static_cast<int>(this->CappedClips.size()); }
  void SetCappedClip(int index, double a, double b, double c, double d);
  ///@}

  ///@{
  /// The point array whose isosurfaces are drawn; empty: the first attribute.
  void SetSurfaceArrayName(const char* name);
  const char* GetSurfaceArrayName() const { return this->SurfaceArrayName.c_str(); }
  ///@}

  ///@{
  /// Find every layer of the surface even when it is opaque, so that GetLastGBuffer holds every
  /// hit of every pixel (a deep G-buffer); off by default (a translucent surface finds them all
  /// anyway). What is drawn does not change.
  vtkSetMacro(AllLayers, bool);
  vtkGetMacro(AllLayers, bool);
  vtkBooleanMacro(AllLayers, bool);
  ///@}

  ///@{
  /// CPU threads for the engine; 0 (default) uses all.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  enum BackendType
  {
    BACKEND_AUTOMATIC = 0, ///< CUDA when built with it and a device is usable, else CPU threads
    BACKEND_CPU = 1,
    BACKEND_CUDA = 2, ///< falls back to CPU threads, with a warning, when CUDA cannot run
  };

  ///@{
  /// Where the engine runs (BackendType); default automatic. The environment variable
  /// IGAVIEW_BACKEND (auto, cpu, cuda) overrides the automatic choice.
  vtkSetClampMacro(Backend, int, BACKEND_AUTOMATIC, BACKEND_CUDA);
  vtkGetMacro(Backend, int);
  void SetBackendToAutomatic() { this->SetBackend(BACKEND_AUTOMATIC); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  void SetBackendToCUDA() { this->SetBackend(BACKEND_CUDA); }
  ///@}

  enum MethodType
  {
    METHOD_AUTOMATIC = 0, ///< per patch: affine geometry by ray composition, the rest by the SST
    METHOD_SHARED_SUBDIVISION_TREE = 1,
    METHOD_RAY_COMPOSITION = 2, ///< every patch; one without affine geometry is an error
  };

  ///@{
  /// How the engine draws the patches (MethodType); default automatic.
  vtkSetClampMacro(Method, int, METHOD_AUTOMATIC, METHOD_RAY_COMPOSITION);
  vtkGetMacro(Method, int);
  void SetMethodToAutomatic() { this->SetMethod(METHOD_AUTOMATIC); }
  void SetMethodToSharedSubdivisionTree() { this->SetMethod(METHOD_SHARED_SUBDIVISION_TREE); }
  void SetMethodToRayComposition() { this->SetMethod(METHOD_RAY_COMPOSITION); }
  ///@}

  enum RootFinderType
  {
    ROOT_FINDER_SUBDIVISION = 0,     ///< de Casteljau at the midpoint (Lane-Riesenfeld)
    ROOT_FINDER_KNOT_INSERTION = 1,  ///< Mørken-Reimers
    ROOT_FINDER_BEZIER_CLIPPING = 2, ///< Nishita-Sederberg-Kakimoto
    ROOT_FINDER_POINT_INSERTION = 3, ///< Wei-Feng's Bézier point insertion
    ROOT_FINDER_POLAR_NEWTON = 4,    ///< Wei-Feng's Newton and regula falsi, polar isolation
  };

  ///@{
  /// Ray composition's root finder (RootFinderType, iga::RootFinder's order); default point
  /// insertion. SetRootFinderByName takes iga::rootFinderName's names and reports an unknown
  /// one as an error, keeping the finder.
  vtkSetClampMacro(RootFinder, int, ROOT_FINDER_SUBDIVISION, ROOT_FINDER_POLAR_NEWTON);
  vtkGetMacro(RootFinder, int);
  void SetRootFinderByName(const char* name);
  ///@}

  ///@{
  /// Frame coherency (ray composition, first hits without clipping planes): the previous frame's
  /// hits seed this frame's roots, so a small camera move or a deformation draws faster. A seed
  /// is taken only where it is proved (iga::findNearestRoot): the image is a cold frame's. Keeps
  /// the previous G-buffer (its memory again); default off.
  vtkSetMacro(FrameCoherency, bool);
  vtkGetMacro(FrameCoherency, bool);
  vtkBooleanMacro(FrameCoherency, bool);
  /// Rays of the last frame whose root its seed settled.
  vtkGetMacro(LastSeededRays, vtkIdType);
  ///@}

  ///@{
  /// Silhouette anti-aliasing (default off): the pixels whose shaded colour differs from a
  /// neighbour's by more than AntialiasingThreshold in a channel (0..1, default 0.1; a hit beside
  /// a miss always does) are drawn again with four rays each on a rotated grid (Wei and Feng's
  /// RGSS) and take the mean of their colours, a ray that misses adding nothing, so that a
  /// silhouette pixel covers what lies behind it in proportion. The nearest surface's pixels
  /// (the first layer of a translucent one); the G-buffer stays the pixel centres'. The passes
  /// are part of GetLastEngineTime and of FrameDeadline's time; a frame whose samples reach the
  /// deadline is drawn without them.
  vtkSetMacro(Antialiasing, bool);
  vtkGetMacro(Antialiasing, bool);
  vtkBooleanMacro(Antialiasing, bool);
  vtkSetClampMacro(AntialiasingThreshold, double, 0.0, 1.0);
  vtkGetMacro(AntialiasingThreshold, double);
  /// Pixels the last frame supersampled.
  vtkGetMacro(LastAntialiasedPixels, vtkIdType);
  ///@}

  ///@{
  /// Halvings of an input patch along one parametric direction before it is halved no further
  /// along it; a pixel whose work needs more is given up (default 22).
  vtkSetClampMacro(MaximumSubdivisionDepth, int, 0, 40);
  vtkGetMacro(MaximumSubdivisionDepth, int);
  ///@}

  ///@{
  /// Cap on a frame's memory in MiB (default 4096) besides the copies of the data: the image
  /// (GetImageBytes) and the engine's working set (iga::sst::Settings::memoryBudgetBytes; in
  /// DRAW_CSG per pass, the passes' hits kept besides). A translucent surface's further layers
  /// (20 bytes a pixel each, at most 7, in host memory and as textures) and their hits are not
  /// counted. A
  /// viewport whose image needs more is not drawn (said once); a frame with more (pixel, patch)
  /// pairs than a pass takes is drawn in bands of rows, and pixels whose subdivision would pass
  /// it are left unresolved.
  vtkSetClampMacro(MemoryBudgetMB, int, 16, 1048576);
  vtkGetMacro(MemoryBudgetMB, int);
  ///@}

  /// Bytes an image of width x height pixels takes out of MemoryBudgetMB whatever it shows:
  /// the engine's per-pixel arrays and G-buffer of one hit a pixel (iga::sst::imageBytes), and
  /// the mapper's colour and depth, in host memory and as textures.
  static vtkTypeUInt64 GetImageBytes(int width, int height);

  ///@{
  /// Frame deadline in seconds, 0 for none (default): a frame still being computed then stops,
  /// draws the hits found so far and leaves the pixels with work left unresolved (said once
  /// until the settings or the input change), so that an interactive view never waits longer.
  /// A frame cut short is not kept: the next render computes it again.
  vtkSetClampMacro(FrameDeadline, double, 0.0, 1e6);
  vtkGetMacro(FrameDeadline, double);
  ///@}

  /// Milliseconds the engine took for the last frame it computed (0 after a refused render).
  double GetLastEngineTime() const { return this->LastEngineTime; }

  /// Why the last render drew nothing of the input: the input, or a setting, was refused (the
  /// error reported, once, says the same). Empty when it was not refused (it drew, or had
  /// nothing to draw). A render that draws nothing forgets the frame before it: GetLastGBuffer
  /// is then empty.
  const char* GetLastRefusal() const;

  /// Where the last frame computed ran: "cpu" or "cuda" (empty before the first frame).
  const char* GetLastBackend() const;

  /// The engine's notice for the last frame computed (why it did not run where asked), or "".
  const char* GetLastNotice() const;

  /// Names the world patches of the last frame computed (input data and actor matrix) for
  /// engines that keep a copy of them on a GPU: unchanged by camera moves and property edits,
  /// new when the input or the actor's matrix changes, never shared by two mappers.
  vtkTypeUInt64 GetLastDataVersion() const;

  /// The form the last frame computed handed the engine: "NURBS volumes" or "Bezier cells"
  /// (empty before the first frame).
  const char* GetLastEngineInput() const;

  /// Names the knot vectors, degrees and net sizes of the last frame's NURBS input (0 when it
  /// used the cells): unchanged over time steps that only move the control nets.
  vtkTypeUInt64 GetLastExtractionVersion() const;

  /// Patches the last frame computed drew by ray composition and by the SST.
  vtkIdType GetLastRayCompositionPatches() const { return this->LastRayCompositionPatches; }
  vtkIdType GetLastSstPatches() const { return this->LastSstPatches; }

  /// Pixels of the last frame computed that still had work left at a cap.
  vtkIdType GetLastUnresolvedPixels() const { return this->LastUnresolvedPixels; }

#ifndef __VTK_WRAP__
  /// Every point attribute at a hit of the last frame (GetAttributeName's order), evaluated from
  /// its patch; `values` holds GetNumberOfAttributes() entries.
  void HitAttributes(const iga::sst::Hit& hit, double* values) const;
  /// The input cell and composite block (flat index) a hit's patch (the engine's numbering)
  /// came from.
  void PatchSource(int patch, vtkIdType& cell, unsigned int& block) const;
  /// A hit's parameter in that cell (a boundary face's hit lies on the face of its volume).
  void CellParameter(const iga::sst::Hit& hit, double uvw[3]) const;

  /// The last frame's G-buffer (its first hits; every hit of a translucent surface) and the
  /// first hits' shaded colours (RGBA, premultiplied, row 0 at the bottom), e.g. for an OpenEXR
  /// export of what was drawn.
  const iga::sst::GBuffer& GetLastGBuffer() const;
  const std::vector<float>& GetLastColours() const;
#endif

  /// Computes, with no OpenGL and no render window, what Render draws for `renderer`'s active
  /// camera and lights and `actor`'s matrix and property at width x height pixels: afterwards
  /// GetLastGBuffer, GetLastColours and ProbePixel describe that frame (vtkIGAIsosurfaceImage
  /// runs on it). The renderer's lights are taken as they are (a headlight follows the camera
  /// only once vtkRenderer::UpdateLightsGeometryToFollowCamera has run). False when nothing was
  /// computed: nothing to draw, or refused (GetLastRefusal says why).
  bool ComputeImage(vtkRenderer* renderer, vtkActor* actor, int width, int height);

  /// Writes the last frame's G-buffer, every hit it holds (all of a ray's with AllLayers on), as
  /// a deep OpenEXR image (vtkIGADeepEXR: depth, position, normal, uvw, patch, ... a sample per
  /// hit), as `igaview --deep-exr` does. False, with an error, where there is no frame or the
  /// file cannot be written.
  bool WriteDeepEXR(const char* fileName);

  ///@{
  /// The point attributes of the last input drawn (ProbePixel's values), by name.
  int GetNumberOfAttributes() const;
  const char* GetAttributeName(int index) const;
  ///@}

  /// The range the named point attribute of the last input drawn takes over its hexahedra and
  /// quadrilaterals, found by subdivision to 1e-5 of its spread (iga::attributeExtremes): for a
  /// lookup table's range, where the array's own range, its control values', may pass the
  /// field's by far. False (range untouched) without such an attribute or patches.
  bool GetAttributeRange(const char* name, double range[2]) const;

  /// Probing: the first hit of pixel (x, y) of the last frame computed (x from the left, y from
  /// the bottom of the viewport), exactly: its world position, its parameter in its Bézier
  /// cell and, when `attributes` is given, every point attribute evaluated from that cell at
  /// the parameter (not interpolated from pixels), one array of one value per attribute, named
  /// as the input's. Returns the cell's id in its grid (the block's, for composite input:
  /// GetLastProbedBlock), or -1 where the pixel has no hit or lies outside the frame; then
  /// nothing is written.
  vtkIdType ProbePixel(int x, int y, double position[3], double uvw[3], vtkFieldData* attributes);
  /// The composite block (flat index; 0 for a grid) of the cell the last ProbePixel returned.
  unsigned int GetLastProbedBlock() const
  {
    return this->LastProbedBlock;
  }

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

  /// The frame Render draws and ComputeImage computes: computed again when what it depends on
  /// changed. False when there is nothing to draw.
  bool UpdateFrame(vtkRenderer* renderer, vtkActor* actor, const int size[2], double aspect);

  /// Brings the input up to date (its producer's pipeline).
  void UpdateInput();

  /// Reports `message` (a warning, or an error) unless the same key was reported since the
  /// settings or the input last changed.
  void ReportOnce(const std::string& key, const std::string& message, bool error);
  /// This render draws nothing: forgets the last frame and remembers the refusal that is why
  /// (GetLastRefusal; empty when nothing was refused, only nothing left to draw).
  void DrawNothing(const std::string& refusal);

#ifndef __VTK_WRAP__
  // The steps of Render: the input as patches, what the frame depends on, the engine's frame
  // when that changed, its shading, and the draw.
  struct Frame;
  /// The input's patches, converted when it changed; false when there is nothing to draw.
  bool CollectInput(Frame& frame);
  /// The surfaces drawn: the quadrilaterals, and in DRAW_SURFACES the volumes' boundary faces.
  void UpdateSurfaces();
  /// Per block of the hexahedra, its boundary faces (DRAW_CSG), found again when the topology
  /// changed.
  void UpdateBlockFaces();
  /// The engine's frame for a view and settings (the frame's, or its supersampling passes'), in
  /// the input form ComputeFrame chose, with the curvature as the hits' colour where it is
  /// coloured by.
  iga::sst::FrameReport RunEngine(const Frame& frame, const iga::sst::View& view,
    const iga::sst::Settings& settings, iga::sst::GBuffer& out);
  /// The engine's frame of the CSG solid and the slices.
  iga::sst::FrameReport ComputeCsgFrame(const Frame& frame, const iga::sst::View& view,
    const iga::sst::Settings& settings, iga::sst::GBuffer& out);
  void ColourByCurvature(const Frame& frame, iga::sst::GBuffer& gbuffer);
  /// The scene the engine draws, in world space.
  iga::sst::Scene EngineScene(bool identity) const;
  /// Size, view, lights, clipping planes and engine settings of the frame, and its key.
  bool DescribeFrame(vtkRenderer* renderer, vtkActor* actor, Frame& frame);
  void DescribeLights(vtkRenderer* renderer, Frame& frame);
  void ReportImageOverBudget(const Frame& frame);
  /// Whether `key` is the last frame's (to rounding VTK adds); remembers it when not.
  bool SameFrame(const std::vector<double>& key);
  /// The engine's G-buffer of the frame, in the input form the engine prefers.
  bool ComputeFrame(vtkActor* actor, Frame& frame);
  /// A new data version (and world patches) when the data or the actor's matrix changed.
  void UpdateDataVersion(vtkMatrix4x4* matrix);
  /// The input's NURBS form (vtkIGANurbsCells), moved by the matrix; false when it has none.
  bool UpdateNurbs(vtkMatrix4x4* matrix);
  /// The report's notice and caps, each said once.
  void ReportEngine(const iga::sst::FrameReport& report);
  /// Says once why a frame drew nothing: isovalues outside the attribute's range, or a surface
  /// outside the view or clipped away.
  void ReportEmptyFrame(const iga::sst::FrameReport& report);
  /// Says once that a frame stopped at FrameDeadline, and has the next render compute it again.
  void ReportDeadline(const iga::sst::FrameReport& report);
  /// Colour and window depth of every pixel from the G-buffer, with VTK's lights.
  void ShadeFrame(vtkActor* actor, const Frame& frame);
  /// A hit's colour (premultiplied RGBA) with the property, the lookup table and the lights.
  void ShadeHit(const Frame& frame, vtkProperty* property, const iga::sst::Hit& hit, float* rgba);
  /// Antialiasing: the first layer's contrasting pixels supersampled within what is left of the
  /// frame's deadline. Where the samples' passes fail (said once) or reach the deadline, the
  /// frame is drawn as it is.
  void SmoothSilhouettes(vtkActor* actor, const Frame& frame);
  /// The frame's layer images, cleared: one, or a translucent surface's layers.
  void AllocateLayers(const Frame& frame);
  /// The element edges over the shaded colours (the property's EdgeVisibility).
  void DrawEdges(vtkProperty* property);
  /// Colours, or a hardware selector's ids, drawn as a full-screen pass with gl_FragDepth.
  void DrawFrame(vtkRenderer* renderer, vtkActor* actor, vtkDataObject* input);
  void SelectionIds(vtkHardwareSelector* selector, vtkDataObject* input, std::vector<float>& ids);
  void UploadTextures(vtkOpenGLRenderWindow* window, std::vector<float>* ids);
  std::vector<vtkOpenGLRenderPass*> RenderPasses(vtkOpenGLRenderWindow* window, vtkActor* actor);
  bool UpdateShader(vtkOpenGLRenderWindow* window, vtkActor* actor,
    const std::vector<vtkOpenGLRenderPass*>& passes);
  void DrawQuad(vtkOpenGLRenderWindow* window, vtkActor* actor, bool selecting);
#endif

  struct Internals;
  std::unique_ptr<Internals> Internal;
  std::vector<double> Isovalues;
  std::string CsgExpression;
  std::vector<std::array<double, 4>> Slices, CappedClips; ///< a, b, c, d each
  std::string SurfaceArrayName;
  int DrawMode = DRAW_ISOSURFACES;
  bool AllLayers = false;
  int NumberOfThreads = 0;
  int Backend = BACKEND_AUTOMATIC;
  int Method = METHOD_AUTOMATIC;
  int RootFinder = ROOT_FINDER_POINT_INSERTION;
  bool FrameCoherency = false;
  vtkIdType LastSeededRays = 0;
  bool Antialiasing = false;
  double AntialiasingThreshold = 0.1;
  vtkIdType LastAntialiasedPixels = 0;
  int MaximumSubdivisionDepth = 22;
  double FrameDeadline = 0;
  int MemoryBudgetMB = 4096;
  double LastEngineTime = 0;
  vtkIdType LastUnresolvedPixels = 0;
  vtkIdType LastRayCompositionPatches = 0, LastSstPatches = 0;
  unsigned int LastProbedBlock = 0;
};

#endif
