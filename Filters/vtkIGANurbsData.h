/**
 * @class   vtkIGANurbsData
 * @brief   Tensor-product NURBS / B-spline volumes and surfaces with a time-varying control net,
 *          and their Bézier cells for the pipeline.
 *
 * Holds one or more patches (iga::NurbsSet: degrees, knot vectors, homogeneous control nets with
 * weights and any number of named attributes on the control points) and one control net per
 * patch and time step; the attributes live in the nets, so they may vary in time too.
 *
 * Design: ParaView only transports, describes and redistributes VTK's own data types, so this
 * class is not a vtkDataObject and never travels down a pipeline. Readers and sources keep it and
 * put out what ToUnstructuredGrid() makes of the requested time step: a vtkUnstructuredGrid of
 * VTK_BEZIER_HEXAHEDRON (volumes) and VTK_BEZIER_QUADRILATERAL (surfaces) cells, one per
 * non-empty knot span, laid out as vtkIGABezierHexahedra does (VTK point ordering, no shared
 * points, "RationalWeights" and "HigherOrderDegrees" flagged active, one point array per
 * attribute). That grid also carries the NURBS description, so FromUnstructuredGrid() rebuilds
 * this class from any such grid after transport:
 *  - cell data "NurbsPatch" (source patch index) and "NurbsKnotSpan" (3 components: element
 *    index along each parametric direction, 0 for a surface's third);
 *  - field data "NurbsPatchInfo" (7 int components per patch: parametric dimension, degree[3],
 *    netSize[3]; a surface has degree 0 and netSize 1 in direction 2), "NurbsKnots" (all knot
 *    vectors, patch by patch, direction by direction), "NurbsControlNet" (the homogeneous control
 *    points of the grid's time step, channels() components, patch by patch, first direction
 *    fastest), "NurbsAttributeNames" and "NurbsTime" (the grid's time).
 *
 * VTK's hexahedra are right-handed and its filters (Contour, Clip, Integrate Variables) rely on
 * it, while G+Smo and GeoPDEs volumes are often left-handed. A volume of negative signed volume
 * is therefore stored with its first parametric direction reversed (knots t -> a + b - t, net
 * mirrored): the same volume, right-handed. GetPatches(), GetControlNet() and the grid describe
 * the stored patches; IsVolumeReversed() says which were turned.
 *
 * The knot vectors are fixed, so the Bézier extraction operators are built once and every time
 * step is extracted by small matrix products; the grid of the last requested step is cached.
 * Shallow copies share the (immutable) description, nets and extraction operators.
 */
#ifndef vtkIGANurbsData_h
#define vtkIGANurbsData_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for return value

#include <functional> // for AddPatch
#include <memory>     // for shared_ptr
#include <string>     // for error messages
#include <vector>     // for time steps

#ifndef __VTK_WRAP__
#include "iga/NurbsSet.h" // for NurbsSet
#endif

class vtkDataArray;
class vtkDataArrayCollection;
class vtkDoubleArray;
class vtkInformation;
class vtkStringArray;
class vtkUnstructuredGrid;

class IGAVIEWFILTERS_EXPORT vtkIGANurbsData : public vtkObject
{
public:
  static vtkIGANurbsData* New();
  vtkTypeMacro(vtkIGANurbsData, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /// Replaces the contents by `set` as the only time step, at `time`. Returns an empty string,
  /// or one sentence naming the patch and the problem (bad knots, net size, non-finite values,
  /// non-positive weights); the object is then left empty.
  std::string SetPatches(const iga::NurbsSet<double>& set, double time = 0.0);

  /// Appends a time step: one control net per patch (volumes first, then surfaces), each the
  /// size of that patch's net and laid out like the nets given to SetPatches (reversed volumes
  /// are turned here too). Times must increase. Returns "" or the problem.
  std::string AddTimeStep(double time, const std::vector<std::vector<double>>& nets);

  /// The patches with the control nets of `step`.
  iga::NurbsSet<double> GetPatches(int step = 0) const;
  std::vector<double> GetTimeSteps() const;
  /// Control net of one patch at one step (empty when out of range).
  const std::vector<double>& GetControlNet(int step, int patch) const;
  /// The Bézier extraction of volume `volume` (null when out of range), shared, immutable.
  std::shared_ptr<const iga::BezierExtraction<double, 3>> GetVolumeExtraction(int volume) const;
#endif

  int GetNumberOfPatches() const;
  /// Whether SetPatches reversed volume `volume`'s first parametric direction (it was
  /// left-handed).
  bool IsVolumeReversed(int volume) const;
  int GetNumberOfTimeSteps() const;
  /// The time of step `step` (0 when out of range).
  double GetTimeStep(int step) const;

  ///@{
  /// The description in VTK's types (Python). Patch `patch` counts the volumes first, then the
  /// surfaces: its parametric dimension (3 or 2; 0 when out of range), its degree and control
  /// net size along each direction (a surface's third 0 and 1), and its knot vector along
  /// `direction` (left empty when out of range).
  int GetPatchDimension(int patch) const;
  void GetPatchDegrees(int patch, int degrees[3]) const;
  void GetPatchNetSize(int patch, int size[3]) const;
  void GetPatchKnots(int patch, int direction, vtkDoubleArray* knots) const;
  int GetNumberOfAttributes() const;
  const char* GetAttributeName(int index) const;
  /// Step `step`'s control net of patch `patch`: a tuple per control point, first direction
  /// fastest, its homogeneous channels as components (w x, w y, w z, w, then w a per attribute).
  /// As stored: a reversed volume's first direction runs backwards (IsVolumeReversed).
  void GetPatchControlNet(int step, int patch, vtkDoubleArray* net) const;
  ///@}

  ///@{
  /// Building in VTK's types (Python), while there is one time step (at time 0, or SetPatches'
  /// time): the attribute names (only while there are no patches), then the volumes and
  /// surfaces, each from its degrees, knot vectors and homogeneous control net laid out as
  /// GetPatchControlNet gives it (4 components and one per attribute). Each returns "" or the
  /// problem (the object keeps what it had then); a volume added after a surface still counts among
  /// the volumes. Each add checks every patch again: thousands of patches go in faster at once,
  /// through C++'s SetPatches.
  std::string SetAttributeNames(vtkStringArray* names);
  std::string AddVolume(const int degrees[3], vtkDataArray* knotsU, vtkDataArray* knotsV,
    vtkDataArray* knotsW, vtkDataArray* net);
  std::string AddSurface(
    const int degrees[2], vtkDataArray* knotsU, vtkDataArray* knotsV, vtkDataArray* net);
  /// AddTimeStep with one net a patch, as GetPatchControlNet lays it out.
  std::string AddTimeStepNets(double time, vtkDataArrayCollection* nets);
  ///@}

  /// Number of Bézier cells ToUnstructuredGrid() produces.
  vtkIdType GetNumberOfBezierCells() const;
  /// Bytes ToUnstructuredGrid() holds at its peak for one step: the grid (its elements are
  /// extracted one at a time) and the copy of its cells the attribute ranges are found on.
  double GetBezierCellBytes() const;

  ///@{
  /// Off (default): the attributes "parameter_u/v/w" the readers add hold Greville abscissae,
  /// exact on polynomial patches and a rational blend of them (off by up to a few percent of the
  /// span) where weights vary. On: the cells of patches whose weights vary are elevated by one
  /// degree in every direction, the same geometry and attributes, with parameter channels that
  /// give the patch's parameter exactly (iga::withExactParameters), at (p + 2)^3 / (p + 1)^3 the
  /// points (2.4 times for quadratics). The grid's NURBS description is the file's either way;
  /// a mapper then draws the cells rather than re-extracting the patches.
  vtkSetMacro(ExactParameters, bool);
  vtkGetMacro(ExactParameters, bool);
  vtkBooleanMacro(ExactParameters, bool);
  ///@}

  /// The Bézier cells of `step` with the NURBS description (see the class description). Cached:
  /// asking for the same step again returns the same grid until the contents change.
  vtkSmartPointer<vtkUnstructuredGrid> ToUnstructuredGrid(int step = 0);

  /// Rebuilds `data` (one time step, the grid's "NurbsTime") from a grid made by
  /// ToUnstructuredGrid(). Returns "" or the problem; `data` is left empty then.
  static std::string FromUnstructuredGrid(vtkUnstructuredGrid* grid, vtkIGANurbsData* data);

  ///@{
  /// Temporal pipeline: advertises TIME_STEPS / TIME_RANGE (only when there is more than one
  /// step), picks the step for UPDATE_TIME_STEP (the last one not after it, or the first), and
  /// fills the output grid of `outInfo` with it (DATA_TIME_STEP set).
  void FillTimeInformation(vtkInformation* outInfo) const;
  int FindTimeStep(double time) const;
  int RequestedTimeStep(vtkInformation* outInfo) const;
  void FillOutput(vtkInformation* outInfo);
  ///@}

  ///@{
  /// Shallow copies share the description, nets and operators (copy on write); deep copies own
  /// theirs. Neither copies the cached grid.
  void ShallowCopy(vtkIGANurbsData* other);
  void DeepCopy(vtkIGANurbsData* other);
  ///@}

  /// Memory in KiB (vtkDataObject's convention): description, nets, operators and cached grid.
  unsigned long GetActualMemorySize();

protected:
  vtkIGANurbsData();
  ~vtkIGANurbsData() override;

private:
#ifndef __VTK_WRAP__
  /// SetPatches with the first step's patches (as given) and what `add` appends, unless the
  /// patch `name` has a `problem` already; the contents stay as they were where either fails.
  std::string AddPatch(const std::string& problem, const std::string& name,
    const std::function<void(iga::NurbsSet<double>&)>& add);
#endif

  vtkIGANurbsData(const vtkIGANurbsData&) = delete;
  void operator=(const vtkIGANurbsData&) = delete;

  struct State;
  std::shared_ptr<const State> Contents;
  bool ExactParameters = false;
  vtkSmartPointer<vtkUnstructuredGrid> CachedGrid;
  int CachedStep = -1;
  bool CachedExactParameters = false;
  std::shared_ptr<const State> CachedContents; // what CachedGrid was made from
};

#endif
