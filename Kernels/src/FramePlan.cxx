// A frame's host-side preparation, shared by the CPU and CUDA drivers.
#include "FramePlan.h"

#include "iga/NurbsSet.h"
#include "iga/Validation.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

} // namespace

void addRoot(FramePlan& plan, const int* degree, Node root, const double* coeffs,
  const Settings& settings, FrameReport& report)
{
  const int count = (degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1) * kScreenChannels;
  std::vector<Node> level = { root };
  std::vector<double> pool(coeffs, coeffs + count);
  while (!level.empty())
  {
    std::vector<Node> straddling;
    std::vector<double> straddlingPool;
    for (Node node : level)
    {
      const VolumeView<const double> view(pool.data() + node.coeff, degree, kScreenChannels);
      node.info = analyzeNode(view, settings.isovalues[node.iso], plan.frame.clip);
      if (!worthKeeping(node.info, plan.frame))
      {
        continue;
      }
      if (node.info.status == ProjectionStatus::InFront)
      {
        const size_t offset = plan.initialPool.size();
        plan.initialPool.insert(plan.initialPool.end(), view.coeffs, view.coeffs + count);
        node.coeff = offset;
        plan.initialNodes.push_back(node);
        continue;
      }
      if (node.level >= settings.maxSubdivisionDepth || straddling.size() + 8 > kMaxEyePlaneNodes)
      {
        ++report.droppedAtEyePlane;
        continue;
      }
      const size_t offset = straddlingPool.size();
      straddlingPool.resize(offset + size_t(8) * count);
      splitMidpoint<double, 3>(view, straddlingPool.data() + offset);
      for (int c = 0; c < 8; ++c)
      {
        Node child = childOf(node, c);
        child.coeff = offset + size_t(c) * count;
        straddling.push_back(child);
      }
    }
    level.swap(straddling);
    pool.swap(straddlingPool);
  }
}

void checkAttributes(int channels, const Settings& s, const std::string& name)
{
  if (s.surfaceAttribute < 0 || kFirstAttributeChannel + s.surfaceAttribute >= channels ||
      (s.colorAttribute >= 0 && kFirstAttributeChannel + s.colorAttribute >= channels))
  {
    throw std::invalid_argument(name + " has " + std::to_string(channels - kFirstAttributeChannel) +
                                " attributes; the surface uses " +
                                std::to_string(s.surfaceAttribute) + ", the colour " +
                                std::to_string(s.colorAttribute));
  }
}

double checkPatches(const std::vector<BezierVolume<double>>& patches, const Settings& s)
{
  const int attribute = kFirstAttributeChannel + s.surfaceAttribute;
  double attributeLo = kInfinity, attributeHi = -kInfinity;
  for (size_t p = 0; p < patches.size(); ++p)
  {
    const auto patch = patches[p].view();
    const std::string problem = checkPatch<double, 3>(patch);
    if (!problem.empty())
    {
      throw std::invalid_argument("patch " + std::to_string(p) + ": " + problem);
    }
    checkAttributes(patch.channels, s, "patch " + std::to_string(p));
    double lo, hi;
    rationalRange(patch, attribute, kWeightChannel, lo, hi);
    attributeLo = std::min(attributeLo, lo);
    attributeHi = std::max(attributeHi, hi);
  }
  return attributeHi > attributeLo ? attributeHi - attributeLo : 1.0;
}

void checkNurbsVolumes(const NurbsVolumes& volumes)
{
  if (volumes.nets.size() != volumes.extractions.size())
  {
    throw std::invalid_argument(std::to_string(volumes.extractions.size()) + " extractions but " +
                                std::to_string(volumes.nets.size()) + " control nets");
  }
  if (volumes.channels < kFirstAttributeChannel + 1)
  {
    throw std::invalid_argument("control points have " + std::to_string(volumes.channels) +
                                " channels; position, weight and an attribute need " +
                                std::to_string(kFirstAttributeChannel + 1));
  }
  for (size_t v = 0; v < volumes.nets.size(); ++v)
  {
    const std::string name = "volume " + std::to_string(v) + ": ";
    if (!volumes.extractions[v] || !volumes.nets[v])
    {
      throw std::invalid_argument(name + "no extraction or no control net");
    }
    const auto& extraction = *volumes.extractions[v];
    int netSize[3];
    for (int d = 0; d < 3; ++d)
    {
      const int degree = extraction.direction(d).degree;
      if (degree < 1 || degree > kMaxDegree)
      {
        throw std::invalid_argument(name + "degree " + std::to_string(degree) + " is outside 1.." +
                                    std::to_string(kMaxDegree));
      }
      netSize[d] = extraction.netSize(d);
    }
    const std::string problem =
      checkControlNet<double, 3>(netSize, volumes.channels, *volumes.nets[v]);
    if (!problem.empty())
    {
      throw std::invalid_argument(name + problem);
    }
  }
}

FramePlan planView(const View& view, const Settings& s, double attributeRange, FrameReport& report)
{
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
  {
    throw std::invalid_argument("image size " + std::to_string(s.width) + "x" +
                                std::to_string(s.height) + " is outside 1..16384 per side");
  }
  if (s.isovalues.empty())
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
  if (s.clipPlanes.size() > size_t(kMaxClipPlanes))
  {
    throw std::invalid_argument("at most " + std::to_string(kMaxClipPlanes) +
                                " clipping planes are supported, got " +
                                std::to_string(s.clipPlanes.size()));
  }
  FramePlan plan;
  plan.threads = s.threads > 0 ? s.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  report.threads = plan.threads;
  plan.frame.tolerance[0] = plan.frame.tolerance[1] = s.pixelTolerance;
  plan.frame.tolerance[2] = s.isoTolerance * attributeRange;

  // Window coordinates: x, y in pixels (pixel i covers [i, i+1]), z the NDC depth.
  const double W = s.width, H = s.height;
  Matrix4<double> window = Matrix4<double>::identity();
  window.m[0][0] = 0.5 * W;
  window.m[0][3] = 0.5 * W;
  window.m[1][1] = 0.5 * H;
  window.m[1][3] = 0.5 * H;
  plan.windowFromWorld = multiply(window, view.worldToClip);
  plan.frame.clip.count = 0;
  for (const auto& plane : s.clipPlanes)
  {
    const bool finite = std::isfinite(plane[0]) && std::isfinite(plane[1]) &&
                        std::isfinite(plane[2]) && std::isfinite(plane[3]);
    if (!finite || (plane[0] == 0 && plane[1] == 0 && plane[2] == 0) ||
        !transformPlane(
          plan.windowFromWorld, plane.data(), plan.frame.clip.plane[plan.frame.clip.count]))
    {
      throw std::invalid_argument(
        "clipping plane " + std::to_string(plan.frame.clip.count) + " is not a finite plane");
    }
    ++plan.frame.clip.count;
  }
  plan.frame.width = s.width;
  plan.frame.height = s.height;
  plan.frame.firstHitOnly = s.firstHitOnly;
  plan.frame.maxSubdivisionDepth = s.maxSubdivisionDepth;
  plan.frame.isovalues = s.isovalues.data();
  return plan;
}

FramePlan planFrame(const std::vector<BezierVolume<double>>& patches, const View& view,
  const Settings& s, FrameReport& report)
{
  FramePlan plan = planView(view, s, checkPatches(patches, s), report);
  const int attribute = kFirstAttributeChannel + s.surfaceAttribute;
  // Screen patches of every input patch, then the subdivision-tree roots: one per (patch,
  // isovalue) with a possible sign change. Roots straddling the eye plane are split until
  // their parts lie in front of or behind it.
  for (size_t p = 0; p < patches.size(); ++p)
  {
    const auto world = patches[p].view();
    std::vector<double> screen(size_t(world.pointCount()) * kScreenChannels);
    makeScreenPatch<double>(world, plan.windowFromWorld, attribute, screen.data());
    plan.shadingOffsets.push_back(plan.shadingPool.size());
    plan.shadingPool.resize(plan.shadingPool.size() + world.pointCount() * kShadeChannels);
    makeShadingPatch(world, attribute,
      s.colorAttribute >= 0 ? kFirstAttributeChannel + s.colorAttribute : -1,
      plan.shadingPool.data() + plan.shadingOffsets.back());
    for (int iso = 0; iso < int(s.isovalues.size()); ++iso)
    {
      Node root = rootNode(int(p), iso);
      addRoot(plan, patches[p].view().degree, root, screen.data(), s, report);
    }
  }
  return plan;
}

} // namespace sst
} // namespace iga
