// The isosurface rasterizer's host interface: world-space rational Bézier volumes and a camera
// in, a G-buffer of sorted hits per pixel and a frame report out.
#pragma once

#include "iga/BSpline.h"
#include "iga/BernsteinRoots.h"
#include "iga/BezierPatch.h"
#include "iga/Camera.h"
#include "iga/sst/GBuffer.h"
#include "iga/sst/NurbsVolumes.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace iga
{
namespace sst
{

enum class Method
{
  SharedSubdivisionTree, ///< the paper's algorithm: one subdivision tree per patch, shared by
                         ///< pixels
  BasicScheme,           ///< one subdivision tree per pixel (the paper's comparison baseline)
  BruteForce,            ///< uniform subdivision and multi-start Newton: slow, for tests only
  BezierClipping,        ///< per pixel, Nishita et al.'s Bézier clipping: surfaces only
  /// Per pixel and patch the ray's univariate polynomial and its roots (Settings::rootFinder):
  /// volumes with affine geometry only (algebraic surfaces over a box, ABS patches).
  RayComposition,
  /// Per patch: affine geometry (with a degree along rays of at most 16) by ray composition,
  /// the rest by the SST, both into the frame's one G-buffer. On CPU threads; a CUDA frame
  /// draws every patch by the SST (FrameReport::sstPatches, rayCompositionPatches).
  Automatic,
};

/// Where the shared-subdivision-tree engine runs. Automatic picks CUDA when the library was
/// built with it and a usable device exists, else CPU threads; the environment variable
/// IGAVIEW_BACKEND (cpu, cuda or auto) overrides Automatic. The basic scheme and brute force
/// always run on CPU threads.
enum class Backend
{
  Automatic,
  Cpu,
  Cuda,
};

struct Settings
{
  int width = 512;
  int height = 512;
  std::vector<double> isovalues; ///< at least one where the scene has volumes
  int surfaceAttribute = 0;      ///< attribute index (channel kFirstAttributeChannel + index)
  int colorAttribute = -1;       ///< attribute sampled at each hit, -1 for none
  bool firstHitOnly = true;      ///< the fast path: keep only the nearest hit per pixel
  /// World-space clipping planes (a, b, c, d): the surface is kept where a x + b y + c z + d >= 0
  /// for every plane (vtkPlane's normal side); at most kMaxClipPlanes. Cut exactly at each hit.
  std::vector<std::array<double, 4>> clipPlanes;
  /// Per pixel (width * height, row 0 at the bottom) an NDC depth beyond which its work is
  /// dropped and no hit is kept (infinity: none; below -1: the pixel is skipped), or empty for
  /// none: CSG frames bound their passes by the result's nearest surface known so far.
  std::vector<double> farDepths;
  /// Halvings of an input patch along one parametric direction before it is halved no further
  /// along it; a pixel whose work needs more is given up.
  int maxSubdivisionDepth = 22;
  /// Cap on a shared-subdivision-tree frame's memory besides its copies of the input. The image
  /// takes imageBytes (its per-pixel arrays and a G-buffer of one hit a pixel): a size needing
  /// more than the budget is refused before anything is allocated. The rest is the loop's: the
  /// sweep's (pixel, patch) pairs at 66 bytes a pair (a frame that needs more is drawn in
  /// several passes over bands of rows), the loop's nodes, coefficients, tuples and children
  /// (Tree.h's memory model; FrameReport::peakBudgetedBytes). Pixels whose work would pass it
  /// are left unresolved and counted (FrameReport::unresolvedAtBudget). Hits past one a pixel
  /// (all-hits mode's layers) are not capped: FrameReport::peakBytes counts their raw records.
  size_t memoryBudgetBytes = size_t(4) << 30;
  /// CUDA: size of the page-locked host buffer that uploads and the G-buffer pass through, a
  /// chunk at a time (kept between frames); at least 4096.
  size_t transferChunkBytes = size_t(64) << 20;
  int threads = 0; ///< 0: all hardware threads (CPU backend)
  Backend backend = Backend::Automatic;
  /// Names the patches' content for drivers that keep a copy of it (CUDA): a frame with the
  /// same non-zero version as the previous one reuses that copy (no checks, no upload), so a
  /// camera move costs no transfer. 0: unknown, always checked and copied.
  uint64_t dataVersion = 0;
  /// Newton's acceptance window: a fraction of a pixel, and of the attribute's range.
  double pixelTolerance = 1e-3;
  double isoTolerance = 1e-7;
  /// Frame deadline in milliseconds from the start of the frame, 0 for none: a
  /// shared-subdivision-tree frame still running then stops between iterations, keeps the hits
  /// found and leaves the pixels with work left unresolved (FrameReport::unresolvedAtDeadline),
  /// so that an interactive view never waits long for a frame.
  double deadlineMs = 0;
  /// Ray composition only: the roots' finder.
  RootFinder rootFinder = RootFinder::PointInsertion;
  /// Ray composition only: compose only the rays through the window boxes of the cells that may
  /// hold the isosurface (IsosurfaceCells.h), over the part of them those boxes span. Off, every
  /// ray through a patch's box is composed whole (for comparisons): the same hits, to rounding.
  bool isosurfaceCells = true;
  /// Ray composition only, frame coherency: the previous frame's G-buffer (the same size), whose
  /// first hits seed first-hit rays through the same pixels (findNearestRoot: a seed is taken
  /// only where it is proved, so the hits are a cold frame's); null for none.
  const GBuffer* seedFrame = nullptr;
  /// Brute force only: uniform subdivision levels per patch.
  int bruteForceLevels = 4;
  /// Called after every SST iteration with its number and the (pixel, patch) pairs left.
  std::function<void(int iteration, size_t pairsLeft)> progress;
};

/// How much a frame's notice matters to a user.
enum class NoticeSeverity
{
  None,    ///< no notice
  Info,    ///< the automatic choice took CPU threads (no GPU): worth saying once
  Warning, ///< CUDA was asked for and could not be used, or a CUDA frame failed
};

struct FrameReport
{
  std::string method;
  std::string backend; ///< "cpu" or "cuda": where the frame was computed
  /// One line when the backend differs from the one asked for or a CUDA frame fell back to the
  /// CPU (why), empty otherwise.
  std::string notice;
  NoticeSeverity noticeSeverity = NoticeSeverity::None;
  int threads = 0;
  int iterations = 0; ///< solution/subdivision rounds
  int bands = 0;      ///< passes over bands of rows: 1 unless the sweep's pairs exceed a pass
  size_t unresolvedPixels = 0; ///< pixels with work left when a cap was hit
  /// (pixel, sub-patch) pairs given up at each cap (a pixel may count more than once).
  size_t unresolvedAtDepthCap = 0;
  size_t unresolvedAtBudget = 0;
  /// Pixels with work left when Settings::deadlineMs passed (drawn with the hits found by then,
  /// which may not be their nearest).
  size_t unresolvedAtDeadline = 0;
  size_t droppedAtEyePlane = 0; ///< sub-patches at the depth cap still straddling the eye plane
  /// (patch, isovalue) pairs whose attribute is constant at the isovalue: a region, not a
  /// surface, so not drawn (NodeInfo::constantAttribute).
  size_t constantAttributeRoots = 0;
  /// The surface attribute's range over the patches (their Bernstein bounds): where an
  /// isovalue must lie for anything to be drawn.
  double attributeRange[2] = { 0, 0 };
  size_t newtonSolves = 0; ///< tuples tried on nodes that certify a unique root
  /// The SST loop's Newton solves (tuples that reached Newton) and their evaluations of F and J:
  /// evaluations / runs is the mean number of iterations a solve takes.
  size_t newtonRuns = 0, newtonEvaluations = 0;
  size_t subdividedPatches = 0;
  size_t sstPatches = 0;            ///< patches the SST drew
  size_t rayCompositionPatches = 0; ///< patches ray composition drew
  size_t frustumPatches = 0;        ///< of those, composed through a frustum form
  size_t blossomPatches = 0;        ///< of those, composed by their power form's blossom
  size_t isosurfaceCells = 0;       ///< ray composition: cells bounding the pixels composed
  size_t composedRays = 0;          ///< ray composition: (pixel, patch) polynomials composed
  size_t rootFinderSteps = 0;       ///< their finders' knot insertions and evaluations
  size_t cappedRays = 0;            ///< rays whose finder ran out of splits (roots may be missing)
  size_t seededRays = 0;            ///< rays whose root the previous frame's hit settled
  size_t maxTuples = 0;
  size_t maxPatches = 0;
  size_t peakBytes = 0; ///< largest engine-owned working set
  /// Of that, the loop's part, which Settings::memoryBudgetBytes less imageBytes caps (at its
  /// own peak).
  size_t peakBudgetedBytes = 0;
  size_t uploadedBytes = 0; ///< CUDA: bytes copied to the device for this frame
  /// CUDA: bytes copied back for the G-buffer (a copy to host memory: there is no CUDA-GL
  /// interop), the pixel offsets and the hits
  size_t downloadedBytes = 0;
  /// Of msSetup: checking the input (and for CUDA copying it to the device and extracting NURBS
  /// elements there); zero when the data version says the device copy is current.
  double msInput = 0;
  double msSetup = 0, msSweepAndGroup = 0, msOverlap = 0, msSolution = 0, msSubdivision = 0,
         msCompaction = 0, msGBuffer = 0, msTotal = 0;
};

/// What the engine needs of a view: the projection VTK would apply and the eye.
struct View
{
  glm::dmat4 worldToClip; ///< clip depth from -1 (near plane) to 1 (far plane)
  glm::dvec3 eye;         ///< eye position (perspective)
  glm::dvec3 forward;     ///< unit view direction
  bool parallel = false;
  /// Height of a pixel in world units: at unit eye depth (perspective) or anywhere (parallel).
  double pixelFootprint = 0;
};

/// The view of a camera for an image of width x height pixels.
View makeView(const Camera& camera, int width, int height);

/// The view's map from homogeneous world points to homogeneous window coordinates of a width x
/// height image: x, y in pixels (pixel i covers [i, i + 1]), z / w the NDC depth.
glm::dmat4 windowFromWorld(const View& view, int width, int height);

/// What a frame draws: the isosurfaces of volumes (one per isovalue) and surfaces themselves,
/// both world-space rational Bézier patches in the standard layout. Hits number the patches in
/// one sequence, the volumes first (Hit::patch); a surface's hits have Hit::isovalue -1. A
/// surface needs no attribute; it is coloured by Settings::colorAttribute where that is set.
class Scene
{
public:
  Scene(const std::vector<BezierVolume<double>>& volumes)
    : Volumes(&volumes)
  {
  }
  Scene(const std::vector<BezierVolume<double>>& volumes,
    const std::vector<BezierSurface<double>>& surfaces)
    : Volumes(&volumes)
    , Surfaces(&surfaces)
  {
  }
  size_t volumeCount() const { return this->Volumes->size(); }
  size_t surfaceCount() const { return this->Surfaces ? this->Surfaces->size() : 0; }
  size_t size() const { return this->volumeCount() + this->surfaceCount(); }
  /// Patch p of the sequence; a surface as the engine stores it (flatVolume).
  VolumeView<const double> operator[](size_t p) const
  {
    return p < this->volumeCount() ? (*this->Volumes)[p].view()
                                   : flatVolume((*this->Surfaces)[p - this->volumeCount()].view());
  }
  /// "patch 3" for a volume, "surface 2" for a surface (counted among the surfaces).
  std::string name(size_t p) const
  {
    return p < this->volumeCount() ? "patch " + std::to_string(p)
                                   : "surface " + std::to_string(p - this->volumeCount());
  }

private:
  const std::vector<BezierVolume<double>>* Volumes;
  const std::vector<BezierSurface<double>>* Surfaces = nullptr;
};

/// Bytes a frame of the settings' size holds whatever it draws, out of
/// Settings::memoryBudgetBytes: per pixel its arrays and a G-buffer of one hit.
size_t imageBytes(const Settings& settings);

/// Renders the scene's isosurfaces and surfaces as seen by `view`. Throws
/// std::invalid_argument naming the patch and the problem for bad input (degree, non-finite
/// values, non-positive weights, missing attributes) or bad settings.
FrameReport render(
  const Scene& scene, const View& view, const Settings& settings, Method method, GBuffer& out);

/// The Bézier elements of NURBS volumes, in the engine's numbering (host extraction). Throws
/// std::invalid_argument naming the volume and the problem for a malformed net.
std::vector<BezierVolume<double>> extractElements(const NurbsVolumes& volumes);

/// Renders the isosurfaces of NURBS volumes (see NurbsVolumes), with the errors of the
/// patch overload, the volume named for a bad net.
FrameReport render(const NurbsVolumes& volumes, const View& view, const Settings& settings,
  Method method, GBuffer& out);

/// The same for a camera.
FrameReport render(
  const Scene& scene, const Camera& camera, const Settings& settings, Method method, GBuffer& out);

/// Data bounds (xmin, xmax, ymin, ymax, zmin, zmax) of the patches' control points, which contain
/// the patches (convex hull property).
void patchBounds(const Scene& scene, double* bounds);

/// Adds a pass's report to a frame's made of several passes (CSG, supersampling): counts and
/// stage times summed, peaks and the largest sizes kept, the first pass's method and backend.
void addPassReport(FrameReport& total, const FrameReport& pass);

const char* methodName(Method method);

/// The method of that name (methodName's inverse); std::invalid_argument listing the names
/// otherwise.
Method parseMethod(const std::string& name);

/// "auto", "cpu" or "cuda"; parseBackend is its inverse and throws std::invalid_argument.
const char* backendName(Backend backend);
Backend parseBackend(const std::string& name);

/// The input form a shared-subdivision-tree frame with this backend setting runs best on, for
/// callers holding their data in both: NURBS volumes where the frame is tried on a GPU (CUDA
/// asked for, here or for Automatic by IGAVIEW_BACKEND, or Automatic with a usable device),
/// which extracts their elements there and so receives only moved nets; the Bézier patches
/// otherwise, which CPU threads would extract again.
enum class InputForm
{
  BezierPatches,
  NurbsVolumes,
};
InputForm preferredInput(Backend backend);

/// The CPU engine keeps the large host blocks its frames free (up to 512 MiB) for the next
/// frame, so steady frames touch no fresh pages; this gives them back to the system.
void releaseHostCache();

} // namespace sst
} // namespace iga
