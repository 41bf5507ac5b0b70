/**
 * @class   vtkIGAIsosurfaceRepresentation
 * @brief   ParaView representations "IGA Isosurface", "IGA Surface", "IGA Surface With
 *          Edges" and "IGA CSG": draw the pixel-exact isosurfaces of an unstructured grid of
 *          Bézier hexahedra, its surfaces (the hexahedra's boundary and its Bézier
 *          quadrilaterals), or a CSG solid of its attributes with slices, with
 *          vtkIGAIsosurfaceMapper, without tessellating (vtkGeometryRepresentation would
 *          extract a surface first).
 *
 * Which of the four is drawn comes from ParaView's representation type through
 * SetRepresentation (the XML's RepresentationType subtype), as for vtkGeometryRepresentation's
 * "Surface With Edges"; the edges take the shared EdgeColor and LineWidth.
 *
 * Each rank keeps its own piece of the input (SetPiece) and reports its bounds; the view must
 * render remotely (SetRequiresDistributedRendering), so every pvserver/pvbatch rank draws its
 * patches with correct window depth and IceT composites the ranks' images by depth (in
 * visibility order, from the pieces' bounds, when translucent). Composite inputs go to the mapper
 * as they are. While interacting, the view may ask for a LOD: the piece's outline.
 *
 * Property setters follow the surface representation's names so the XML can share them with it
 * (colouring through ColorArrayName/LookupTable, Opacity, Specular, transforms). The lookup
 * table's range is ParaView's (the mapper's UseLookupTableScalarRange is on, as in
 * vtkGeometryRepresentation).
 *
 * Engine settings go to the mapper: Backend (0 automatic, 1 CPU, 2 CUDA), CPU threads, and the
 * caps MaximumSubdivisionDepth and MemoryBudget (MiB) at which pixels are left unresolved, and
 * the FrameDeadline (seconds) at which a frame stops with what it has found.
 *
 * Progress: the mapper's progress events while the engine runs (vtkCommand::ProgressEvent,
 * see vtkIGAIsosurfaceMapper) are re-fired as this representation's own progress
 * (UpdateProgress, with the progress text "IGA Isosurface"). ParaView registers every proxy's
 * VTK algorithm with the session's vtkPVProgressHandler (vtkSIProxy::CreateVTKObjects), not
 * the helper objects such as this mapper, and enables progress around StillRender and
 * InteractiveRender (vtkSMViewProxy), so the engine's progress reaches the session's progress
 * handler, which feeds the GUI's progress bar. Limits: the handler forwards at most one event per
 * 0.1 s (GUI) or 1 s (server), only rank 0's progress is shown in parallel, progress is off in
 * symmetric pvbatch runs (ParaView's rules). The handler's events are tested from pvpython; the
 * GUI's progress bar (pqProgressManager, fed by the same handler) was not checked.
 */
#ifndef vtkIGAIsosurfaceRepresentation_h
#define vtkIGAIsosurfaceRepresentation_h

#include "IGAViewRepresentationModule.h" // for export macro
#include "vtkNew.h"                      // for vtkNew
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <array>  // for the slices
#include <vector> // for the slices

class vtkIGAIsosurfaceMapper;
class vtkDataObject;
class vtkOutlineSource;
class vtkPolyDataMapper;
class vtkProperty;
class vtkPVLODActor;
class vtkScalarsToColors;

class IGAVIEWREPRESENTATION_EXPORT vtkIGAIsosurfaceRepresentation : public vtkPVDataRepresentation
{
public:
  static vtkIGAIsosurfaceRepresentation* New();
  vtkTypeMacro(vtkIGAIsosurfaceRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;
  void SetVisibility(bool val) override;

  ///@{
  /// Isosurface settings, forwarded to the mapper.
  void SetNumberOfIsovalues(int count);
  void SetIsovalue(int index, double value);
  /// The point array defining the surface (ParaView's 5-element array selection).
  void SetSurfaceArray(int idx, int port, int connection, int fieldAssociation, const char* name);
  void SetNumberOfThreads(int threads);
  /// 0 automatic, 1 CPU, 2 CUDA (vtkIGAIsosurfaceMapper::BackendType).
  void SetBackend(int backend);
  /// 0 automatic, 1 SST, 2 ray composition (vtkIGAIsosurfaceMapper::MethodType).
  void SetMethod(int method);
  /// Ray composition's root finder (vtkIGAIsosurfaceMapper::RootFinderType).
  void SetRootFinder(int finder);
  /// Ray composition's roots seeded by the previous frame's hits (the mapper's FrameCoherency).
  void SetFrameCoherency(int coherent);
  /// Silhouette anti-aliasing, its threshold and the pixels it took (the mapper's).
  void SetAntialiasing(int antialias);
  void SetAntialiasingThreshold(double threshold);
  int GetLastAntialiasedPixels();
  /// The patches the last frame drew by ray composition and by the SST (the mapper's).
  int GetLastRayCompositionPatches();
  int GetLastSstPatches();
  /// Rays of the last frame whose root the frame before settled (the mapper's).
  int GetLastSeededRays();
  void SetMaximumSubdivisionDepth(int depth);
  /// The engine's memory budget in MiB.
  void SetMemoryBudget(int megabytes);
  /// Seconds after which a frame stops (0: never).
  void SetFrameDeadline(double seconds);
  ///@}

  /// "IGA Isosurface", "IGA Surface", "IGA Surface With Edges" or "IGA CSG" (any other name is
  /// an error).
  void SetRepresentation(const char* name);

  /// "IGA CSG": the solid (vtkIGAIsosurfaceMapper::SetCsgExpression) and the slices.
  void SetCsgExpression(const char* expression);
  void SetNumberOfSlices(int count);
  void SetSlice(int index, double a, double b, double c, double d);

  /// What "IGA CSG" does with the plane of ParaView's plane widget (origin and normal): nothing,
  /// one more slice, or a capped clip (the solid cut by the half-space the normal points into,
  /// its cut face drawn, the slices cut with it).
  enum PlaneUse
  {
    PLANE_OFF = 0,
    PLANE_SLICE = 1,
    PLANE_CLIP = 2
  };
  void SetPlaneUse(int use);
  void SetPlaneOrigin(double x, double y, double z);
  void SetPlaneNormal(double x, double y, double z);

  ///@{
  /// The element edges of "IGA Surface With Edges", forwarded to the property.
  void SetEdgeColor(double r, double g, double b);
  void SetLineWidth(double width);
  ///@}

  ///@{
  /// Colouring: ColorArrayName (index 0) selects a point array mapped through the lookup table.
  void SetInputArrayToProcess(
    int idx, int port, int connection, int fieldAssociation, const char* name) override;
  using Superclass::SetInputArrayToProcess;
  void SetLookupTable(vtkScalarsToColors* lut);
  ///@}

  ///@{
  /// Forwarded to the property.
  void SetOpacity(double value);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  void SetAmbientColor(double r, double g, double b);
  void SetDiffuseColor(double r, double g, double b);
  void SetSpecularColor(double r, double g, double b);
  ///@}

  ///@{
  /// Forwarded to the actor.
  void SetOrientation(double x, double y, double z);
  void SetOrigin(double x, double y, double z);
  void SetPosition(double x, double y, double z);
  void SetScale(double x, double y, double z);
  void SetUserTransform(const double matrix[16]);
  void SetPickable(int value);
  ///@}

  vtkIGAIsosurfaceMapper* GetMapper() { return this->Mapper; }

protected:
  vtkIGAIsosurfaceRepresentation();
  ~vtkIGAIsosurfaceRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  vtkIGAIsosurfaceRepresentation(const vtkIGAIsosurfaceRepresentation&) = delete;
  void operator=(const vtkIGAIsosurfaceRepresentation&) = delete;

  /// The mapper's progress, fired again as this representation's.
  void OnMapperProgress(vtkObject* caller, unsigned long event, void* data);
  /// Hands the slices and the widget's plane (one more slice, or a capped clip) to the mapper.
  void UpdateCsg();
  /// The widget's plane as a x + b y + c z + d, the normal's side positive.
  std::array<double, 4> WidgetPlane() const;

  vtkNew<vtkIGAIsosurfaceMapper> Mapper;
  vtkNew<vtkPolyDataMapper> OutlineMapper;
  vtkNew<vtkOutlineSource> Outline;
  vtkNew<vtkProperty> Property;
  vtkNew<vtkPVLODActor> Actor;
  /// This rank's piece: a grid of Bézier hexahedra or a composite of them (possibly empty).
  vtkSmartPointer<vtkDataObject> Cache;
  double DataBounds[6];
  std::vector<std::array<double, 4>> Slices;
  int PlaneUse = PLANE_OFF;
  double PlaneOrigin[3] = { 0, 0, 0 };
  double PlaneNormal[3] = { 1, 0, 0 };
};

#endif
