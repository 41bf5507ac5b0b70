// A frame's host-side preparation, shared by the CPU and CUDA drivers.
#include "FramePlan.h"
#include "ParallelFor.h"

#include "iga/NurbsSet.h"
#include "iga/Validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

namespace iga
{
namespace sst
{

namespace
{

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Sub-patches per level kept while splitting a patch at the eye plane.
constexpr size_t kMaxEyePlaneNodes = size_t(1) << 16;

/// The view's sides (a pixel outside the image) as planes on homogeneous window values. They
/// pass through the eye, so clippedAway settles with them parts straddling the eye plane, which
/// have no window box. Only the parts near the eye meet the view there (its sides meet the eye
/// plane at the eye alone), so the splitting at the eye plane stays near the eye.
ClipPlanes<double> viewSides(const FrameConstants& frame)
{
  ClipPlanes<double> sides;
  const double planes[4][4] = { { 1, 0, 0, 1 }, { -1, 0, 0, frame.width + 1.0 }, { 0, 1, 0, 1 },
    { 0, -1, 0, frame.height + 1.0 } };
  for (const auto& plane : planes)
  {
    std::copy(plane, plane + 4, sides.plane[sides.count++]);
  }
  return sides;
}

/// Parts a loop over patches is cut into: several per thread, so that uneven parts even out.
size_t partsFor(size_t patches, int threads)
{
  return std::min(patches, size_t(threads) * 8);
}

/// Whether control points of `channels` values hold the settings' surface attribute (a volume's)
/// and colour attribute.
bool holdsAttributes(int channels, bool volume, const Settings& s)
{
  const bool surface =
    !volume || (s.surfaceAttribute >= 0 && kFirstAttributeChannel + s.surfaceAttribute < channels);
  return surface && (s.colorAttribute < 0 || kFirstAttributeChannel + s.colorAttribute < channels);
}

/// Empty when control points of `channels` values hold the attributes the settings need of a
/// volume or a surface; otherwise the problem, to follow the name of what has them.
std::string attributeProblem(int channels, bool volume, const Settings& s)
{
  if (holdsAttributes(channels, volume, s))
  {
    return std::string();
  }
  const std::string has =
    "has " + std::to_string(channels - kFirstAttributeChannel) + " attributes; ";
  return has + (volume ? "the surface uses " + std::to_string(s.surfaceAttribute) + ", " : "") +
         "the colour " + std::to_string(s.colorAttribute);
}

/// Bytes in MiB, to a tenth below 10 MiB, rounded up (a need) or down (a budget), so that a need
/// above a budget never reads as equal to it.
std::string mebibytes(size_t bytes, bool up)
{
  const double scale = bytes < (size_t(10) << 20) ? 10 : 1;
  const double value = double(bytes) / 1048576.0 * scale;
  std::ostringstream text;
  text << std::fixed << std::setprecision(scale > 1 ? 1 : 0)
       << (up ? std::ceil(value) : std::floor(value)) / scale << " MiB";
  return text.str();
}

} // namespace

int threadCount(const Settings& s)
{
  return s.threads > 0 ? s.threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

void addRoot(FramePlan& plan, const int* degree, Node root, const double* coeffs,
  const Settings& settings, FrameReport& report)
{
  const int count = (degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1) * kScreenChannels;
  const double isovalue = root.iso >= 0 ? settings.isovalues[root.iso] : 0.0;
  // Analyses a node: keeps it when it lies in front of the eye, drops it when it cannot show
  // surface; true when it straddles the eye plane and must be split.
  auto straddles = [&](Node& node, const double* values)
  {
    const VolumeView<const double> view(values, degree, kScreenChannels);
    analyzeNodeBounds(view, isovalue, plan.frame.clip, node.info);
    report.constantAttributeRoots += node.level == 0 && node.info.constantAttribute ? 1 : 0;
    if (!worthKeeping(node.info, plan.frame))
    {
      return false;
    }
    if (node.info.status == ProjectionStatus::InFront)
    {
      node.coeff = plan.initialPool.size();
      plan.initialPool.insert(plan.initialPool.end(), values, values + count);
      plan.initialNodes.push_back(node);
      return false;
    }
    return !clippedAway(view, viewSides(plan.frame));
  };
  // Most roots lie in front of the eye: settled here, without copies.
  if (!straddles(root, coeffs))
  {
    return;
  }
  root.coeff = 0;
  std::vector<Node> level = { root };
  std::vector<double> pool(coeffs, coeffs + count);
  while (!level.empty())
  {
    std::vector<Node> straddling;
    std::vector<double> straddlingPool;
    for (const Node& node : level)
    {
      const VolumeView<const double> view(pool.data() + node.coeff, degree, kScreenChannels);
      const int axes = allAxes(view), children = childCount(axes);
      if (node.level >= settings.maxSubdivisionDepth ||
          straddlingPool.size() / count + children > kMaxEyePlaneNodes)
      {
        ++report.droppedAtEyePlane;
        continue;
      }
      const size_t offset = straddlingPool.size();
      straddlingPool.resize(offset + size_t(children) * count);
      splitNode(view, axes, straddlingPool.data() + offset);
      for (int c = 0; c < children; ++c)
      {
        Node child = childOf(node, axes, c);
        child.coeff = offset + size_t(c) * count;
        if (straddles(child, straddlingPool.data() + child.coeff))
        {
          straddling.push_back(child);
        }
      }
    }
    level.swap(straddling);
    pool.swap(straddlingPool);
  }
}

/// Room for the roots of patches [first, last) of a list that lie in front of the eye (most do).
void reserveRoots(
  FramePlan& part, const Scene& scene, const size_t* first, const size_t* last, const Settings& s)
{
  size_t roots = 0, values = 0;
  for (const size_t* patch = first; patch != last; ++patch)
  {
    const size_t p = *patch;
    const size_t count = size_t(rootsOf(scene[p].degree, s));
    roots += count;
    values += count * size_t(scene[p].pointCount()) * kScreenChannels;
  }
  part.initialNodes.reserve(roots);
  part.initialPool.reserve(values);
}

/// The parts' roots and screen patches, one after another in part order, copied on all threads.
void joinRoots(FramePlan& plan, const std::vector<FramePlan>& parts)
{
  std::vector<size_t> nodeStarts(parts.size() + 1, 0), valueStarts(parts.size() + 1, 0);
  for (size_t k = 0; k < parts.size(); ++k)
  {
    nodeStarts[k + 1] = nodeStarts[k] + parts[k].initialNodes.size();
    valueStarts[k + 1] = valueStarts[k] + parts[k].initialPool.size();
  }
  plan.initialNodes.resize(nodeStarts.back());
  plan.initialPool.resize(valueStarts.back());
  parallelFor(parts.size(), plan.threads,
    [&](size_t begin, size_t end)
    {
      for (size_t k = begin; k < end; ++k)
      {
        std::copy(parts[k].initialPool.begin(), parts[k].initialPool.end(),
          plan.initialPool.begin() + std::ptrdiff_t(valueStarts[k]));
        for (size_t n = 0; n < parts[k].initialNodes.size(); ++n)
        {
          Node& node = plan.initialNodes[nodeStarts[k] + n];
          node = parts[k].initialNodes[n];
          node.coeff += valueStarts[k];
        }
      }
    });
}

void analyzeRoots(FramePlan& plan, const Scene& scene)
{
  parallelFor(plan.initialNodes.size(), plan.threads,
    [&](size_t begin, size_t end)
    {
      for (size_t n = begin; n < end; ++n)
      {
        Node& node = plan.initialNodes[n];
        const VolumeView<const double> view(
          plan.initialPool.data() + node.coeff, scene[size_t(node.patch)].degree, kScreenChannels);
        analyzeNodeSolver(view, node.info);
        analyzeNodeCentre(view, node.info);
      }
    });
}

bool usableShape(const int* degree, int channels, const Settings& s)
{
  const bool volume = degree[2] != 0;
  for (int d = 0; d < (volume ? 3 : 2); ++d)
  {
    if (degree[d] < 1 || degree[d] > kMaxDegree)
    {
      return false;
    }
  }
  return channels >= kFirstAttributeChannel && holdsAttributes(channels, volume, s);
}

int surfaceChannelOf(const int* degree, const Settings& s)
{
  return degree[2] == 0 ? kWeightChannel : kFirstAttributeChannel + s.surfaceAttribute;
}

void checkAttributes(int channels, const Settings& s, const std::string& name)
{
  const std::string problem = attributeProblem(channels, true, s);
  if (!problem.empty())
  {
    throw std::invalid_argument(name + " " + problem);
  }
}

CheckedPatches checkPatchRanges(const Scene& scene, const Settings& s)
{
  CheckedPatches checked;
  checked.patches.resize(scene.size());
  const int attribute = kFirstAttributeChannel + s.surfaceAttribute;
  // Per part: the attribute's range, or the first bad patch and its problem. Parts are joined in
  // order, so the message names the first bad patch whatever the thread count.
  struct Part
  {
    double lo = kInfinity, hi = -kInfinity;
    std::string problem;
  };
  const size_t parts = partsFor(scene.size(), threadCount(s));
  std::vector<Part> found(parts);
  parallelParts(scene.size(), parts, threadCount(s),
    [&](size_t k, size_t begin, size_t end)
    {
      Part& part = found[k];
      for (size_t p = begin; p < end; ++p)
      {
        const auto patch = scene[p];
        const bool volume = !isSurface(patch);
        const std::string problem =
          volume ? checkPatch<double, 3>(patch) : checkPatch<double, 2>(surfaceOf(patch));
        if (!problem.empty())
        {
          part.problem = scene.name(p) + ": " + problem;
          return;
        }
        const std::string attributes = attributeProblem(patch.channels, volume, s);
        if (!attributes.empty())
        {
          part.problem = scene.name(p) + " " + attributes;
          return;
        }
        if (!volume)
        {
          continue;
        }
        PatchRange& range = checked.patches[p];
        range.known = rationalRange(patch, attribute, kWeightChannel, range.lo, range.hi);
        part.lo = std::min(part.lo, range.lo);
        part.hi = std::max(part.hi, range.hi);
      }
    });
  for (const Part& part : found)
  {
    if (!part.problem.empty())
    {
      throw std::invalid_argument(part.problem);
    }
    checked.range.lo = std::min(checked.range.lo, part.lo);
    checked.range.hi = std::max(checked.range.hi, part.hi);
  }
  return checked;
}

DataKey::DataKey(const Scene& scene, const Settings& settings)
  : version(settings.dataVersion)
  , surfaceAttribute(settings.surfaceAttribute)
  , colorAttribute(settings.colorAttribute)
{
  const size_t sampled = std::min(scene.size(), kSampledPatches);
  fingerprint.reserve(4 * sampled + 2);
  fingerprint.push_back(double(scene.size()));
  fingerprint.push_back(double(scene.volumeCount()));
  for (size_t k = 0; k < sampled; ++k)
  {
    const auto v = scene[k * scene.size() / sampled];
    fingerprint.push_back(v.degree[0] + 32.0 * (v.degree[1] + 32.0 * v.degree[2]));
    fingerprint.push_back(v.channels);
    fingerprint.push_back(v.coeffs[0]);
    fingerprint.push_back(v.coeffs[v.valueCount() - 1]);
  }
}

std::shared_ptr<const CheckedPatches> checkedPatches(const Scene& scene, const Settings& s)
{
  static KeptByDataKey<std::shared_ptr<const CheckedPatches>> kept;
  return kept.get(
    scene, s, [&] { return std::make_shared<const CheckedPatches>(checkPatchRanges(scene, s)); });
}

void checkIndexable(size_t count, const char* what)
{
  if (count > std::numeric_limits<uint32_t>::max())
  {
    throw std::length_error("the frame needs " + std::to_string(count) + " " + what +
                            ", more than the engine's 32-bit indices "
                            "allow (4294967295): lower the resolution or draw fewer patches");
  }
}

std::vector<int> rowBands(const uint64_t* rowDifferences, const Settings& s)
{
  // A band's pairs stay within the budget at the sweep's peak, and as work items next to a
  // tuple each, which the loop holds at once in all-hits mode.
  const uint64_t pairBytes =
    std::max<uint64_t>(kBytesPerSweepPair, kBytesPerWorkItem + kBytesPerTuple);
  const uint64_t limit =
    std::min<uint64_t>(loopBudgetBytes(s) / pairBytes, std::numeric_limits<uint32_t>::max());
  std::vector<int> starts = { 0 };
  uint64_t rowPairs = 0, bandPairs = 0;
  for (int row = 0; row < s.height; ++row)
  {
    rowPairs += rowDifferences[row];
    if (rowPairs > std::numeric_limits<uint32_t>::max())
    {
      checkIndexable(
        rowPairs, ("(pixel, patch) pairs in image row " + std::to_string(row)).c_str());
    }
    // A row over the budget alone is a band of its own: rows are not split.
    if (bandPairs > 0 && bandPairs + rowPairs > limit)
    {
      starts.push_back(row);
      bandPairs = 0;
    }
    bandPairs += rowPairs;
  }
  starts.push_back(s.height);
  return starts;
}

size_t imageBytes(const Settings& s)
{
  return size_t(std::max(s.width, 0)) * size_t(std::max(s.height, 0)) * kBytesPerImagePixel;
}

size_t loopBudgetBytes(const Settings& s)
{
  const size_t image = imageBytes(s);
  return s.memoryBudgetBytes > image ? s.memoryBudgetBytes - image : 0;
}

void checkSettings(const Settings& s, bool volumes)
{
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
  {
    throw std::invalid_argument("image size " + std::to_string(s.width) + "x" +
                                std::to_string(s.height) + " is outside 1..16384 per side");
  }
  if (imageBytes(s) > s.memoryBudgetBytes)
  {
    throw std::length_error(
      "a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image needs " +
      mebibytes(imageBytes(s), true) + " (" + std::to_string(kBytesPerImagePixel) +
      " bytes a pixel), more than the memory budget of " + mebibytes(s.memoryBudgetBytes, false) +
      ": lower the resolution or raise the budget");
  }
  if (volumes && s.isovalues.empty())
  {
    throw std::invalid_argument("no isovalue given");
  }
  for (double iso : s.isovalues)
  {
    if (!std::isfinite(iso))
    {
      throw std::invalid_argument("isovalue is not finite");
    }
  }
  if (s.maxSubdivisionDepth < 0 || s.maxSubdivisionDepth > 40)
  {
    throw std::invalid_argument("maximum subdivision depth must lie in 0..40");
  }
  if (!(s.deadlineMs >= 0 && std::isfinite(s.deadlineMs)))
  {
    throw std::invalid_argument("frame deadline of " + std::to_string(s.deadlineMs) +
                                " ms is not a finite, non-negative time");
  }
  if (s.transferChunkBytes < 4096)
  {
    throw std::invalid_argument(
      "transfer chunk of " + std::to_string(s.transferChunkBytes) + " bytes is below 4096");
  }
  if (!s.farDepths.empty() && s.farDepths.size() != size_t(s.width) * size_t(s.height))
  {
    throw std::invalid_argument("far depths for " + std::to_string(s.farDepths.size()) +
                                " pixels, not one per pixel of the image");
  }
  for (double depth : s.farDepths)
  {
    if (std::isnan(depth))
    {
      throw std::invalid_argument("a far depth is NaN");
    }
  }
  checkClipPlanes(s);
}

void checkClipPlanes(const Settings& s)
{
  if (s.clipPlanes.size() > size_t(kMaxClipPlanes))
  {
    throw std::invalid_argument("at most " + std::to_string(kMaxClipPlanes) +
                                " clipping planes are supported, got " +
                                std::to_string(s.clipPlanes.size()));
  }
  for (size_t k = 0; k < s.clipPlanes.size(); ++k)
  {
    const auto& plane = s.clipPlanes[k];
    const bool finite = std::isfinite(plane[0]) && std::isfinite(plane[1]) &&
                        std::isfinite(plane[2]) && std::isfinite(plane[3]);
    if (!finite || (plane[0] == 0 && plane[1] == 0 && plane[2] == 0))
    {
      throw std::invalid_argument("clipping plane " + std::to_string(k) + " is not a finite plane");
    }
  }
}

glm::dmat4 windowFromWorld(const View& view, int width, int height)
{
  const double W = width, H = height;
  glm::dmat4 window(1.0);
  window[0][0] = 0.5 * W;
  window[3][0] = 0.5 * W;
  window[1][1] = 0.5 * H;
  window[3][1] = 0.5 * H;
  return window * view.worldToClip;
}

FramePlan planView(const View& view, const Settings& s, const AttributeRange& attribute,
  bool volumes, FrameReport& report)
{
  checkSettings(s, volumes);
  const double determinant = glm::determinant(view.worldToClip);
  if (!(std::isfinite(determinant) && determinant != 0))
  {
    throw std::invalid_argument(
      "the view's world-to-clip matrix is singular or not finite: a camera at its focal point, a "
      "view-up along the view direction, or clipping range and distances beyond what double "
      "precision frames (1e-100 .. 1e+100)");
  }
  FramePlan plan;
  plan.threads = threadCount(s);
  report.threads = plan.threads;
  plan.frame.tolerance[0] = plan.frame.tolerance[1] = s.pixelTolerance;
  plan.frame.tolerance[2] = s.isoTolerance * attribute.width();
  report.attributeRange[0] = attribute.lo;
  report.attributeRange[1] = attribute.hi;

  plan.windowFromWorld = windowFromWorld(view, s.width, s.height);
  plan.frame.clip.count = 0;
  for (const auto& plane : s.clipPlanes)
  {
    glm::dvec4 inWindow; // finite, with a normal (checkSettings)
    if (!transformPlane(plan.windowFromWorld, glm::make_vec4(plane.data()), inWindow))
    {
      throw std::invalid_argument(
        "clipping plane " + std::to_string(plan.frame.clip.count) + " is not a finite plane");
    }
    std::copy_n(glm::value_ptr(inWindow), 4, plan.frame.clip.plane[plan.frame.clip.count++]);
  }
  plan.frame.width = s.width;
  plan.frame.height = s.height;
  plan.frame.rowBegin = 0;
  plan.frame.rowEnd = s.height;
  plan.frame.hits.firstHitOnly = s.firstHitOnly;
  plan.frame.maxSubdivisionDepth = s.maxSubdivisionDepth;
  plan.frame.isovalues = s.isovalues.data();
  return plan;
}

namespace
{

/// Whether root `root` of patch p may show surface, by the patch's attribute range (the verdict
/// its analysis in addRoot would take); counts a constant attribute at the isovalue.
bool rootMayShow(const PatchRange& range, const Settings& s, int root, size_t& constantRoots)
{
  if (root < 0)
  {
    return true; // a surface
  }
  bool constant = false, may = true;
  attributeVerdict(range.known, range.lo, range.hi, s.isovalues[root], constant, may);
  constantRoots += constant ? 1 : 0;
  return may;
}

/// Root `root` of patch p: the isovalue's index for a volume, -1 for a surface.
int rootIndex(const VolumeView<const double>& patch, int root)
{
  return isSurface(patch) ? -1 : root;
}

/// The patches a root of which may show surface, ascending (counting the constant attributes at
/// an isovalue): only they are projected and shaded, so an isovalue outside most patches' ranges
/// (a large set) leaves the others untouched.
std::vector<size_t> drawnPatches(const Scene& scene, const Settings& s,
  const CheckedPatches& checked, int threads, FrameReport& report)
{
  const size_t parts = partsFor(scene.size(), threads);
  std::vector<std::vector<size_t>> drawnParts(parts);
  std::vector<size_t> constantRoots(parts, 0);
  parallelParts(scene.size(), parts, threads,
    [&](size_t k, size_t begin, size_t end)
    {
      for (size_t p = begin; p < end; ++p)
      {
        bool drawn = false;
        for (int root = 0; root < rootsOf(scene[p].degree, s); ++root)
        {
          drawn |= rootMayShow(checked.patches[p], s, rootIndex(scene[p], root), constantRoots[k]);
        }
        if (drawn)
        {
          drawnParts[k].push_back(p);
        }
      }
    });
  std::vector<size_t> drawn;
  for (size_t k = 0; k < parts; ++k)
  {
    drawn.insert(drawn.end(), drawnParts[k].begin(), drawnParts[k].end());
    report.constantAttributeRoots += constantRoots[k];
  }
  return drawn;
}

/// The drawn patches' shading patches go where their sizes put them (only their offsets are
/// set).
void placeShadingPatches(FramePlan& plan, const Scene& scene)
{
  plan.shadingOffsets.resize(scene.size());
  size_t shadingValues = 0;
  for (size_t p : plan.drawnPatches)
  {
    plan.shadingOffsets[p] = shadingValues;
    shadingValues += size_t(scene[p].pointCount()) * kShadeChannels;
  }
  plan.shadingPool.resize(shadingValues);
}

/// The drawn patches' screen and shading patches, then their subdivision-tree roots: one per
/// (patch, isovalue) with a possible sign change; roots straddling the eye plane are split
/// until their parts lie in front of or behind it. Found per part of the drawn patches and
/// joined in order: the same plan for any thread count.
void addDrawnRoots(FramePlan& plan, const Scene& scene, const Settings& s,
  const CheckedPatches& checked, FrameReport& report)
{
  const int colour = s.colorAttribute >= 0 ? kFirstAttributeChannel + s.colorAttribute : -1;
  const std::vector<size_t>& drawn = plan.drawnPatches;
  const size_t parts = partsFor(drawn.size(), plan.threads);
  std::vector<FramePlan> found(parts);
  std::vector<FrameReport> partReports(parts);
  parallelParts(drawn.size(), parts, plan.threads,
    [&](size_t k, size_t begin, size_t end)
    {
      FramePlan& part = found[k];
      part.frame = plan.frame;
      FrameReport& partReport = partReports[k];
      reserveRoots(part, scene, drawn.data() + begin, drawn.data() + end, s);
      std::vector<double> screen;
      size_t counted = 0; // constant roots, counted by drawnPatches
      for (size_t d = begin; d < end; ++d)
      {
        const size_t p = drawn[d];
        const auto world = scene[p];
        const int attribute = surfaceChannelOf(world.degree, s);
        screen.resize(size_t(world.pointCount()) * kScreenChannels);
        makeScreenPatch<double>(world, plan.windowFromWorld, attribute, screen.data());
        makeShadingPatch(
          world, attribute, colour, plan.shadingPool.data() + plan.shadingOffsets[p]);
        for (int root = 0; root < rootsOf(world.degree, s); ++root)
        {
          const int index = rootIndex(world, root);
          if (rootMayShow(checked.patches[p], s, index, counted))
          {
            addRoot(part, world.degree, rootNode(int(p), index), screen.data(), s, partReport);
          }
        }
      }
    });
  joinRoots(plan, found);
  for (const FrameReport& partReport : partReports)
  {
    report.droppedAtEyePlane += partReport.droppedAtEyePlane;
    report.constantAttributeRoots += partReport.constantAttributeRoots;
  }
}

} // namespace

FramePlan planFrame(const Scene& scene, const View& view, const Settings& s, FrameReport& report)
{
  const auto start = std::chrono::steady_clock::now();
  const auto checked = checkedPatches(scene, s);
  report.msInput =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  FramePlan plan = planView(view, s, checked->range, scene.volumeCount() > 0, report);
  plan.drawnPatches = drawnPatches(scene, s, *checked, plan.threads, report);
  placeShadingPatches(plan, scene);
  addDrawnRoots(plan, scene, s, *checked, report);
  return plan;
}

} // namespace sst
} // namespace iga
