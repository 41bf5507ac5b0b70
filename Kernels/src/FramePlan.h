// A frame's host-side preparation, shared by the CPU and CUDA drivers: input and settings
// checked, screen and shading patches made, and the subdivision-tree roots found.
#pragma once

#include "BlockCache.h"
#include "iga/sst/Engine.h"
#include "iga/sst/Tree.h"

#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace iga
{
namespace sst
{

struct FramePlan
{
  FrameConstants frame{}; ///< its isovalues point into the settings
  glm::dmat4 windowFromWorld;
  int threads = 1;
  /// Roots (one per patch and isovalue with a possible sign change, in front of the eye) and
  /// their screen coefficients.
  Buffer<Node> initialNodes;
  Buffer<double> initialPool;
  /// The patches a root of which may show surface (planFrame), ascending: only they have screen
  /// and shading patches, and only their entries of shadingOffsets are set.
  std::vector<size_t> drawnPatches;
  /// Shading patches of the drawn patches, kShadeChannels per control point.
  Buffer<double> shadingPool;
  Buffer<size_t> shadingOffsets;
};

/// The CPU threads a frame with these settings uses (Settings::threads, 0: all).
int threadCount(const Settings& settings);

/// Checks that control points of `channels` values hold the settings' surface and colour
/// attributes; throws std::invalid_argument starting with `name` otherwise.
void checkAttributes(int channels, const Settings& settings, const std::string& name);

/// The surface attribute's range over all patches (their Bernstein bounds).
struct AttributeRange
{
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  /// What the Newton tolerance is relative to (1 for a constant attribute).
  double width() const { return hi > lo ? hi - lo : 1.0; }
};

/// A patch's surface attribute range (rationalRange over its control points, which its screen
/// patch carries unchanged): known false for a surface, which has none.
struct PatchRange
{
  double lo = 0, hi = 0;
  bool known = false;
};

/// What checking the patches finds: the surface attribute's range over the volumes, and each
/// patch's own.
struct CheckedPatches
{
  AttributeRange range;
  std::vector<PatchRange> patches;
};

/// Checks every patch against the settings (degrees, values, weights, attribute indices) and
/// returns the surface attribute's range over the volumes, and over each patch. Throws
/// std::invalid_argument naming the first bad patch and its problem. Runs on
/// threadCount(settings) threads.
CheckedPatches checkPatchRanges(const Scene& scene, const Settings& settings);

/// checkPatchRanges' range over the volumes.
inline AttributeRange checkPatches(const Scene& scene, const Settings& settings)
{
  return checkPatchRanges(scene, settings).range;
}

/// What names a scene's patches between frames, for what is kept from one frame to the next:
/// Settings::dataVersion (the same non-zero version, the same patches, as for the CUDA driver's
/// copy of them) and the attributes a frame reads; as a check against a version reused for other
/// patches (a caller's mistake), the patch counts and the shapes and first and last values of up
/// to kSampledPatches patches spread over the scene (a bounded cost however many there are).
struct DataKey
{
  static constexpr size_t kSampledPatches = 64;
  uint64_t version = 0;
  int surfaceAttribute = 0, colorAttribute = -1;
  std::vector<double> fingerprint;

  DataKey(const Scene& scene, const Settings& settings);
  bool operator==(const DataKey& other) const
  {
    return version == other.version && surfaceAttribute == other.surfaceAttribute &&
           colorAttribute == other.colorAttribute && fingerprint == other.fingerprint;
  }
};

/// One value a frame makes from its patches, kept for the next frame with the same DataKey (a
/// non-zero data version); frames without a version make their own and keep nothing.
template<class T>
class KeptByDataKey
{
public:
  /// The kept value where the key is the last one's, else make()'s (kept for the next frame).
  template<class Make>
  T get(const Scene& scene, const Settings& settings, Make make)
  {
    std::unique_ptr<DataKey> key;
    if (settings.dataVersion != 0)
    {
      key = std::make_unique<DataKey>(scene, settings);
      std::lock_guard<std::mutex> lock(this->Mutex);
      if (this->Key && *this->Key == *key)
      {
        return this->Value;
      }
    }
    T value = make();
    if (key)
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Key = std::move(key);
      this->Value = value;
    }
    return value;
  }

private:
  std::mutex Mutex;
  std::unique_ptr<DataKey> Key;
  T Value{};
};

/// checkPatchRanges, or what it found for the frame before when that had the same DataKey (a
/// non-zero data version): a camera move or a new isovalue does not check the patches again.
std::shared_ptr<const CheckedPatches> checkedPatches(const Scene& scene, const Settings& settings);

/// Whether patches of these degrees (a surface's third 0, flatVolume) and channels suit the
/// settings: what checkPatches tests besides control point values, for drivers that test those
/// on the device.
bool usableShape(const int* degree, int channels, const Settings& settings);

/// The world channel of the attribute a patch's screen and shading patches carry as the
/// surface attribute: the settings' for a volume, the weight for a surface (which has none).
int surfaceChannelOf(const int* degree, const Settings& settings);

/// Both drivers index (pixel, patch) pairs, tuples, nodes and hits with 32 bits: throws
/// std::length_error, naming the count and what it counts, when a frame needs more than
/// 2^32 - 1.
void checkIndexable(size_t count, const char* what = "(pixel, patch) pairs");

/// Settings::memoryBudgetBytes less imageBytes: the share of the sweep's pairs and the loop.
size_t loopBudgetBytes(const Settings& settings);

/// Bytes a (pixel, node) pair of the sweep takes at its peak in either driver: the pair, the
/// sort's scratch copy, the work item it becomes and its run start (pixelRuns).
constexpr size_t kBytesPerSweepPair = 24;

/// The bands of rows a frame is drawn in, as their starts followed by the image height: as few
/// as keep every band's (pixel, node) pairs within the 32-bit indices and within the memory
/// budget, at kBytesPerSweepPair and as work items with a tuple each (Tree.h), except that a
/// row over the budget is a band of its own. `rowDifferences` (height + 1 entries, see addRowPairs)
/// counts the pairs per row. Throws std::length_error (checkIndexable) for a row beyond the 32-bit
/// indices.
std::vector<int> rowBands(const uint64_t* rowDifferences, const Settings& settings);

/// Runs pass() once per band of `bands` (rowBands) with the frame's rows set to it; returns the
/// number of bands.
template<class Pass>
int drawInBands(const std::vector<int>& bands, FrameConstants& frame, Pass pass)
{
  for (size_t b = 0; b + 1 < bands.size(); ++b)
  {
    frame.rowBegin = bands[b];
    frame.rowEnd = bands[b + 1];
    pass();
  }
  return int(bands.size()) - 1;
}

/// Throws std::invalid_argument for bad settings (image size, isovalues, depth cap, transfer
/// chunk, clipping plane count). A scene without volumes needs no isovalue.
void checkSettings(const Settings& settings, bool volumes = true);

/// The clipping planes: at most kMaxClipPlanes, each finite with a normal. Throws
/// std::invalid_argument naming the plane.
void checkClipPlanes(const Settings& settings);

/// The plan's view part (frame constants, window matrix, clipping planes), without roots.
/// Throws std::invalid_argument for bad settings.
FramePlan planView(const View& view, const Settings& settings, const AttributeRange& attribute,
  bool volumes, FrameReport& report);

/// Appends a root (`coeffs`: its screen patch) to the plan's initial nodes if it may show
/// surface. A root straddling the eye plane has no finite window box: it is split breadth first
/// until its parts lie in front of the eye, behind it, or in front of the near plane. Parts
/// still straddling at the depth cap or beyond a node budget are counted in
/// report.droppedAtEyePlane, not drawn. Roots carry the cheap part of their analysis
/// (analyzeNodeBounds); the SST loop completes it when a round takes them, the reference methods
/// with analyzeRoots.
void addRoot(FramePlan& plan, const int* degree, Node root, const double* coeffs,
  const Settings& settings, FrameReport& report);

/// The roots of patch p: one per isovalue for a volume, one (iso -1) for a surface.
inline int rootsOf(const int* degree, const Settings& settings)
{
  return degree[2] == 0 ? 1 : int(settings.isovalues.size());
}

/// The solver and centre parts of the analysis of the plan's roots (of the scene's patches), on
/// the plan's threads.
void analyzeRoots(FramePlan& plan, const Scene& scene);

/// All of the above for every patch and isovalue, plus the shading patches, on the settings'
/// threads (the same plan for any thread count).
FramePlan planFrame(
  const Scene& scene, const View& view, const Settings& settings, FrameReport& report);

} // namespace sst
} // namespace iga
