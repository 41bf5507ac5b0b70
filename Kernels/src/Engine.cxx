// CPU drivers of the isosurface rasterizer: the Shared Subdivision Tree algorithm (Liu et al.),
// the per-pixel basic scheme and a brute-force reference, over the shared pixel-problem kernels,
// and per-pixel Bézier clipping (Nishita et al.) for surfaces, independent of them.
#include "iga/sst/Engine.h"

#include "BlockCache.h"
#include "CudaEngine.h"
#include "FramePlan.h"
#include "ParallelFor.h"
#include "RayCompositionPass.h"
#include "sst/CpuExec.h"
#include "sst/Loop.h"

#include "iga/BezierClipping.h"
#include "iga/Validation.h"
#include "iga/sst/PixelProblem.h"
#include "iga/sst/Tree.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace iga
{
namespace sst
{

void addPassReport(FrameReport& total, const FrameReport& pass)
{
  if (total.method.empty()) // the first pass's
  {
    total.method = pass.method;
    total.backend = pass.backend;
    total.notice = pass.notice;
    total.noticeSeverity = pass.noticeSeverity;
    total.threads = pass.threads;
  }
  total.iterations += pass.iterations;
  total.bands = std::max(total.bands, pass.bands);
  total.unresolvedPixels += pass.unresolvedPixels;
  total.unresolvedAtDepthCap += pass.unresolvedAtDepthCap;
  total.unresolvedAtBudget += pass.unresolvedAtBudget;
  total.unresolvedAtDeadline += pass.unresolvedAtDeadline;
  total.droppedAtEyePlane += pass.droppedAtEyePlane;
  total.constantAttributeRoots += pass.constantAttributeRoots;
  total.newtonSolves += pass.newtonSolves;
  total.newtonRuns += pass.newtonRuns;
  total.newtonEvaluations += pass.newtonEvaluations;
  total.subdividedPatches += pass.subdividedPatches;
  total.sstPatches += pass.sstPatches;
  total.rayCompositionPatches += pass.rayCompositionPatches;
  total.frustumPatches += pass.frustumPatches;
  total.blossomPatches += pass.blossomPatches;
  total.isosurfaceCells += pass.isosurfaceCells;
  total.composedRays += pass.composedRays;
  total.rootFinderSteps += pass.rootFinderSteps;
  total.cappedRays += pass.cappedRays;
  total.seededRays += pass.seededRays;
  total.maxTuples = std::max(total.maxTuples, pass.maxTuples);
  total.maxPatches = std::max(total.maxPatches, pass.maxPatches);
  total.peakBytes = std::max(total.peakBytes, pass.peakBytes);
  total.peakBudgetedBytes = std::max(total.peakBudgetedBytes, pass.peakBudgetedBytes);
  total.uploadedBytes += pass.uploadedBytes;
  total.downloadedBytes += pass.downloadedBytes;
  total.msInput += pass.msInput;
  total.msSetup += pass.msSetup;
  total.msSweepAndGroup += pass.msSweepAndGroup;
  total.msOverlap += pass.msOverlap;
  total.msSolution += pass.msSolution;
  total.msSubdivision += pass.msSubdivision;
  total.msCompaction += pass.msCompaction;
  total.msGBuffer += pass.msGBuffer;
  total.msTotal += pass.msTotal;
}

const char* methodName(Method method)
{
  switch (method)
  {
    case Method::SharedSubdivisionTree:
      return "sst";
    case Method::BasicScheme:
      return "basic";
    case Method::BruteForce:
      return "brute-force";
    case Method::BezierClipping:
      return "bezier-clipping";
    case Method::RayComposition:
      return "ray-composition";
    case Method::Automatic:
      return "auto";
  }
  return "unknown";
}

Method parseMethod(const std::string& name)
{
  std::string names;
  for (Method method : { Method::Automatic, Method::SharedSubdivisionTree, Method::RayComposition,
         Method::BasicScheme, Method::BezierClipping, Method::BruteForce })
  {
    if (name == methodName(method))
    {
      return method;
    }
    names += std::string(names.empty() ? "" : ", ") + methodName(method);
  }
  throw std::invalid_argument("method '" + name + "' is none of " + names);
}

void patchBounds(const Scene& scene, double* bounds)
{
  for (int d = 0; d < 3; ++d)
  {
    bounds[2 * d] = std::numeric_limits<double>::infinity();
    bounds[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (size_t p = 0; p < scene.size(); ++p)
  {
    const auto view = scene[p];
    for (int p = 0; p < view.pointCount(); ++p)
    {
      const double* cp = view.point(p);
      for (int d = 0; d < 3; ++d)
      {
        bounds[2 * d] = std::min(bounds[2 * d], cp[d] / cp[kWeightChannel]);
        bounds[2 * d + 1] = std::max(bounds[2 * d + 1], cp[d] / cp[kWeightChannel]);
      }
    }
  }
}

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Bytes a host container holds.
template<class V>
size_t capacityBytes(const V& v)
{
  return v.capacity() * sizeof(typename V::value_type);
}

class Renderer
{
public:
  Renderer(const Scene& scene, const View& view, const Settings& settings, FrameReport& report)
    : Patches(scene)
    , TheView(view)
    , Config(settings)
    , Report(report)
  {
  }

  void run(Method method, GBuffer& out)
  {
    const Clock::time_point start = Clock::now();
    this->setup();
    this->Report.msSetup = millisecondsSince(start);
    LoopState<CpuExec>& s = this->Loop;
    switch (method)
    {
      case Method::SharedSubdivisionTree:
        this->Report.sstPatches = this->Patches.size();
        drawFrame(s, this->Config, [&] { drawPass(s); });
        break;
      case Method::BasicScheme:
        analyzeRoots(this->Plan, this->Patches);
        drawFrame(s, this->Config, [&] { this->referencePass(&Renderer::basicScheme); });
        break;
      case Method::BruteForce:
        drawFrame(s, this->Config, [&] { this->referencePass(&Renderer::bruteForce); });
        break;
      case Method::BezierClipping:
        if (this->Patches.volumeCount() > 0)
        {
          throw std::invalid_argument("Bézier clipping draws surfaces only, the scene has " +
                                      std::to_string(this->Patches.volumeCount()) + " volumes");
        }
        drawFrame(s, this->Config, [&] { this->referencePass(&Renderer::bezierClipping); });
        break;
      case Method::RayComposition:
        this->prepareComposition(affinePatches);
        drawFrame(s, this->Config, [&] { this->referencePass(&Renderer::rayComposition); });
        break;
      case Method::Automatic:
        this->prepareComposition(affineWherePossible);
        drawFrame(s, this->Config, [&] { this->automaticPass(); });
        break;
    }
    if (this->Forms)
    {
      this->Report.frustumPatches = this->Forms->made();
      this->Report.blossomPatches = this->Forms->blossoms();
    }
    const Clock::time_point stage = Clock::now();
    this->deliver(out);
    this->Report.msGBuffer += millisecondsSince(stage);
    this->Report.msTotal = millisecondsSince(start);
  }

private:
  // ---- frame setup -------------------------------------------------------------------------

  /// The host preparation (planFrame), and the loop's inputs pointing into it.
  void setup()
  {
    this->Plan = planFrame(this->Patches, this->TheView, this->Config, this->Report);
    // Read only for the drawn patches' nodes and hits.
    this->Shapes.resize(this->Patches.size());
    for (size_t p : this->Plan.drawnPatches)
    {
      const auto v = this->Patches[p];
      PatchShape& shape = this->Shapes[p];
      std::copy(v.degree, v.degree + 3, shape.degree);
      shape.channels = v.channels;
      shape.screenValues = v.pointCount() * kScreenChannels;
      shape.world = 0; // the loop reads the screen and shading patches only
      shape.screen = this->Plan.shadingOffsets[p];
    }
    LoopState<CpuExec>& s = this->Loop;
    s.exec.threads = this->Plan.threads;
    setFrame(s, this->Report, this->Config, this->TheView);
    s.frame = this->Plan.frame;
    s.shapes = this->Shapes.data();
    s.initialNodes = this->Plan.initialNodes.data();
    s.initialCount = this->Plan.initialNodes.size();
    s.initialPool = this->Plan.initialPool.data();
    s.initialValues = this->Plan.initialPool.size();
    s.shadingPool = this->Plan.shadingPool.data();
    s.shadingValues = this->Plan.shadingPool.size();
  }

  int valueCount(int patch) const { return this->Patches[patch].pointCount() * kScreenChannels; }

  template<class Pool>
  VolumeView<const double> nodeView(const Node& node, const Pool& pool) const
  {
    return VolumeView<const double>(
      pool.data() + node.coeff, this->Patches[node.patch].degree, kScreenChannels);
  }

  /// A band of a reference method: the shared sweep, then the method per pixel.
  void referencePass(void (Renderer::*method)())
  {
    sweepAndGroup(this->Loop);
    this->Loop.stages.end(this->Report.msSweepAndGroup);
    (this->*method)();
    this->Loop.stages.end(this->Report.msSolution);
  }

  /// A band of the automatic method: the sweep, ray composition on the affine patches' items,
  /// then the SST's rounds on the others, bounded by the hits found (first-hit mode).
  void automaticPass()
  {
    LoopState<CpuExec>& s = this->Loop;
    sweepAndGroup(s);
    s.stages.end(this->Report.msSweepAndGroup);
    if (this->Report.rayCompositionPatches > 0)
    {
      this->rayComposition();
      s.stages.end(this->Report.msSolution);
      if (this->Report.sstPatches == 0)
      {
        return; // no item is left for the tree
      }
      dropAffineItems(s, *this->Affine, this->Plan.initialNodes.data());
    }
    solveRounds(s);
  }

  /// Appends a reference method's hits, lists of pixels in pixel order (one list a pixel, or a
  /// run of them), each kept one bounding its pixel as the hit policy says.
  void appendPixelHits(const std::vector<std::vector<RawHit>>& perPixel)
  {
    LoopState<CpuExec>& s = this->Loop;
    size_t total = s.HitCount;
    for (const auto& hits : perPixel)
    {
      total += hits.size();
    }
    checkIndexable(total, "hits");
    s.Hits.resize(total);
    // Beyond a pixel's far depth (the bound each method starts from) nothing is kept.
    const auto kept = [&](const RawHit& hit)
    { return s.frame.hits.keeps(hit.ndcDepth, s.BestDepth[hit.pixel]); };
    for (const auto& hits : perPixel)
    {
      for (const RawHit& hit : hits)
      {
        if (kept(hit))
        {
          s.Hits[s.HitCount++] = hit;
          s.BestDepth[hit.pixel] = s.frame.hits.afterHit(s.BestDepth[hit.pixel], hit.ndcDepth);
        }
      }
    }
  }

  /// The G-buffer stage's kept hits into the G-buffer.
  void deliver(GBuffer& out)
  {
    LoopState<CpuExec>& s = this->Loop;
    out.width = this->Config.width;
    out.height = this->Config.height;
    out.offsets.resize(s.pixelCount + 1);
    offsetsFromRuns(s.RunPixels.data(), s.KeptStarts.data(), s.RunCount, 0, s.pixelCount,
      this->Plan.threads, out.offsets.data());
    out.hits.resize(s.KeptCount);
    compactHits(s, out.hits.data());
  }

  // ---- basic scheme ------------------------------------------------------------------------

  /// One subdivision tree per pixel, depth first, with the same node tests and Newton solves.
  void basicScheme()
  {
    const LoopState<CpuExec>& s = this->Loop;
    const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
    std::vector<std::vector<RawHit>> perPixel(count);
    std::vector<size_t> peak(count, 0);
    std::atomic<size_t> solves{ 0 }, splits{ 0 }, capped{ 0 };
    parallelFor(count, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        // The arena holds exactly the stacked nodes' coefficient blocks, in stack order.
        std::vector<Node> stack;
        std::vector<double> arena, current, children;
        size_t localSolves = 0, localSplits = 0;
        for (size_t k = begin; k < end; ++k)
        {
          const size_t p = first + k;
          const int i = int(p % this->Config.width), j = int(p / this->Config.width);
          double best = s.BestDepth[p];
          for (uint32_t item = s.ItemOffsets[p]; item < s.ItemOffsets[p + 1]; ++item)
          {
            const Node& initial = this->Plan.initialNodes[s.ItemNodes[item]];
            if (!s.frame.hits.mayMatter(initial.info.box.lo[2], best))
            {
              break;
            }
            const int count = this->valueCount(initial.patch);
            stack.assign(1, initial);
            stack.back().coeff = 0;
            arena.assign(this->Plan.initialPool.begin() + initial.coeff,
              this->Plan.initialPool.begin() + initial.coeff + count);
            while (!stack.empty())
            {
              Node node = stack.back();
              stack.pop_back();
              current.assign(arena.begin() + node.coeff, arena.begin() + node.coeff + count);
              arena.resize(node.coeff);
              node.coeff = 0;
              if (!mayHitPixel(node, uint32_t(p), best, s.frame))
              {
                continue;
              }
              localSolves += node.info.certified ? 1 : 0;
              double u[3], ndc;
              const TupleOutcome result =
                solveNodeTuple(this->nodeView(node, current), node, i, j, s.frame, u, ndc);
              if (result == TupleOutcome::Hit) // kept or not by appendPixelHits
              {
                perPixel[k].push_back(rawHitOf(uint32_t(p), node, u, ndc));
                best = s.frame.hits.afterHit(best, ndc);
              }
              if (result != TupleOutcome::Undecided)
              {
                continue;
              }
              if (node.level >= this->Config.maxSubdivisionDepth)
              {
                this->Loop.Unresolved[p] = 1;
                ++capped;
                continue;
              }
              ++localSplits;
              const auto parent = this->nodeView(node, current);
              const int axes = allAxes(parent);
              children.resize(size_t(childCount(axes)) * count);
              splitNode(parent, axes, children.data());
              // Push far children first so that the near ones are explored first.
              for (int c = childCount(axes) - 1; c >= 0; --c)
              {
                Node child = childOf(node, axes, c);
                child.coeff = size_t(c) * count;
                child.info = analyzeNode(
                  this->nodeView(child, children), isovalueOf(child, s.frame), s.frame.clip);
                if (worthKeeping(child.info, this->Plan.frame))
                {
                  child.coeff = arena.size();
                  arena.insert(arena.end(), children.begin() + size_t(c) * count,
                    children.begin() + size_t(c + 1) * count);
                  stack.push_back(child);
                }
              }
              peak[k] = std::max(
                peak[k], capacityBytes(arena) + capacityBytes(stack) + capacityBytes(children));
            }
          }
        }
        solves += localSolves;
        splits += localSplits;
      });
    this->Report.newtonSolves += solves;
    this->Report.subdividedPatches += splits;
    this->Report.unresolvedAtDepthCap += capped;
    this->appendPixelHits(perPixel);
    trackMemory(this->Loop,
      (count ? *std::max_element(peak.begin(), peak.end()) : 0) * size_t(this->Plan.threads));
  }

  // ---- brute force -------------------------------------------------------------------------

  /// Brute force's leaves: every initial node subdivided uniformly bruteForceLevels times, the
  /// parts in front of the eye that may show surface kept.
  void makeLeaves()
  {
    this->LeafOffsets.assign(this->Plan.initialNodes.size() + 1, 0);
    for (size_t n = 0; n < this->Plan.initialNodes.size(); ++n)
    {
      std::vector<Node> level = { this->Plan.initialNodes[n] };
      level[0].coeff = 0;
      const int count = this->valueCount(level[0].patch);
      std::vector<double> pool(this->Plan.initialPool.begin() + this->Plan.initialNodes[n].coeff,
        this->Plan.initialPool.begin() + this->Plan.initialNodes[n].coeff + count);
      for (int depth = 0; depth < this->Config.bruteForceLevels && !level.empty(); ++depth)
      {
        std::vector<Node> next;
        const int axes = allAxes(this->nodeView(level[0], pool)), children = childCount(axes);
        std::vector<double> nextPool(level.size() * children * size_t(count));
        for (size_t k = 0; k < level.size(); ++k)
        {
          splitNode(this->nodeView(level[k], pool), axes, nextPool.data() + k * children * count);
          for (int c = 0; c < children; ++c)
          {
            Node child = childOf(level[k], axes, c);
            child.coeff = (k * children + c) * size_t(count);
            child.info = analyzeNode(this->nodeView(child, nextPool),
              isovalueOf(child, this->Plan.frame), this->Plan.frame.clip);
            if (worthKeeping(child.info, this->Plan.frame) &&
                child.info.status == ProjectionStatus::InFront)
            {
              next.push_back(child);
            }
          }
        }
        level.swap(next);
        pool.swap(nextPool);
      }
      for (auto& leaf : level)
      {
        const size_t offset = this->LeafPool.size();
        this->LeafPool.insert(
          this->LeafPool.end(), pool.begin() + leaf.coeff, pool.begin() + leaf.coeff + count);
        leaf.coeff = offset;
        this->Leaves.push_back(leaf);
      }
      this->LeafOffsets[n + 1] = uint32_t(this->Leaves.size());
    }
  }

  /// Uniform subdivision of every initial node to a fixed depth and Newton from nine starts in
  /// every leaf covering the pixel, without certificates: slow, independent of the tree logic.
  void bruteForce()
  {
    const LoopState<CpuExec>& s = this->Loop;
    if (this->LeafOffsets.empty()) // the leaves serve every band
    {
      this->makeLeaves();
    }
    const std::vector<Node>& leaves = this->Leaves;
    const std::vector<double>& leafPool = this->LeafPool;
    const std::vector<uint32_t>& leafOffsets = this->LeafOffsets;
    trackMemory(this->Loop, capacityBytes(leafPool) + capacityBytes(leaves));
    const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
    std::vector<std::vector<RawHit>> perPixel(count);
    std::atomic<size_t> solves{ 0 };
    parallelFor(count, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        size_t local = 0;
        for (size_t k = begin; k < end; ++k)
        {
          const size_t p = first + k;
          const int i = int(p % this->Config.width), j = int(p / this->Config.width);
          for (uint32_t item = s.ItemOffsets[p]; item < s.ItemOffsets[p + 1]; ++item)
          {
            const uint32_t n = s.ItemNodes[item];
            for (uint32_t l = leafOffsets[n]; l < leafOffsets[n + 1]; ++l)
            {
              const Node& leaf = leaves[l];
              if (!boxCoversPixel(leaf.info.box, i, j))
              {
                continue;
              }
              // The corners of the leaf's inner box and its centre.
              const auto view = this->nodeView(leaf, leafPool);
              const int centre = childCount(allAxes(view));
              for (int s = 0; s <= centre; ++s)
              {
                double start[3];
                for (int d = 0; d < 3; ++d)
                {
                  start[d] = s == centre ? 0.5 : 0.2 + 0.6 * ((s >> d) & 1);
                }
                double u[3], ndc;
                ++local;
                // Roots up to Newton's domain slack outside the leaf count (those on
                // shared faces would otherwise be lost to rounding); duplicates are
                // merged later.
                if (solvePixel<double>(view, i, j, isovalueOf(leaf, this->Plan.frame),
                      this->Plan.frame.tolerance, start, u, ndc,
                      this->Plan.frame.clip) == TupleOutcome::Hit &&
                    rootInPatch(leaf, u))
                {
                  perPixel[k].push_back(rawHitOf(uint32_t(p), leaf, u, ndc));
                }
              }
            }
          }
        }
        solves += local;
      });
    this->Report.newtonSolves += solves;
    this->appendPixelHits(perPixel);
  }

  // ---- ray composition ---------------------------------------------------------------------

  /// Ray composition's setup, part of the frame's (msSetup): the patches' affine forms (by
  /// `analyze`: where possible, or throwing for a patch without), their frustum forms, the
  /// pixels their isosurface cells cover, and their power forms for shading.
  template<class Analyze>
  void prepareComposition(Analyze analyze)
  {
    const Clock::time_point start = Clock::now();
    this->Affine = analyze(this->Patches, this->Config, this->Plan.threads, this->Report);
    // Curved patches alone (drawn automatically): nothing to compose, the SST draws them all,
    // and the per-patch tables below would cost a large set more than its frame.
    const bool composed = this->Report.rayCompositionPatches > 0 || this->Report.sstPatches == 0;
    if (composed)
    {
      this->Coverage = std::make_unique<CellCoverage>(
        this->Affine, this->TheView, this->Config, this->Plan.threads);
      this->Forms = std::make_unique<FrustumForms>(
        *this->Affine, this->TheView, this->Plan.threads, *this->Coverage);
      this->Report.isosurfaceCells = this->Coverage->cells();
      this->Coverage->narrowNodes(this->Plan.initialNodes.data(), this->Plan.initialNodes.size());
      this->Shading = powerShadingOf(this->Affine);
      this->Loop.powerShading =
        this->Shading->terms.empty() ? nullptr : this->Shading->patches.data();
      this->Loop.powerTerms = this->Shading->terms.data();
    }
    this->Report.msSetup += millisecondsSince(start);
  }

  void rayComposition()
  {
    std::vector<std::vector<RawHit>> runs;
    rayCompositionPass(this->TheView, this->Config, *this->Affine, *this->Forms, *this->Coverage,
      this->Loop, this->Plan.threads, runs, this->Report);
    this->appendPixelHits(runs);
  }

  // ---- Bézier clipping ---------------------------------------------------------------------

  /// Every initial node covering a pixel clipped against its ray (bezierClip), each root kept
  /// where it lies in the clip range, on the kept side of the clipping planes and within
  /// Newton's pixel tolerance of the ray (a check of the clipping, never failed in the tests).
  void bezierClipping()
  {
    const LoopState<CpuExec>& s = this->Loop;
    const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
    std::vector<std::vector<RawHit>> perPixel(count);
    std::atomic<size_t> unresolved{ 0 };
    parallelFor(count, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          const size_t p = first + k;
          const double x = double(p % this->Config.width) + 0.5,
                       y = double(p / this->Config.width) + 0.5;
          bool complete = true;
          for (uint32_t item = s.ItemOffsets[p]; item < s.ItemOffsets[p + 1]; ++item)
          {
            const Node& node = this->Plan.initialNodes[s.ItemNodes[item]];
            const auto view = this->nodeView(node, this->Plan.initialPool);
            const ClippingResult clipped = bezierClip(surfaceOf(view), x, y, 1e-7, 100000);
            complete = complete && clipped.complete;
            for (const glm::dvec2& root : clipped.roots)
            {
              const double u[3] = { root.x, root.y, 0 };
              double values[kScreenChannels];
              evaluateHomogeneous<double, 3>(view, u, values, nullptr);
              const double ndc = values[kScreenZ] / values[kScreenW];
              const bool onRay =
                std::abs(values[kScreenX] / values[kScreenW] - x) <= s.frame.tolerance[0] &&
                std::abs(values[kScreenY] / values[kScreenW] - y) <= s.frame.tolerance[1];
              complete = complete && onRay;
              if (onRay && ndc >= -1 && ndc <= 1 && clipKeeps(s.frame.clip, values))
              {
                perPixel[k].push_back(rawHitOf(uint32_t(p), node, u, ndc));
              }
            }
          }
          if (!complete)
          {
            this->Loop.Unresolved[p] = 1;
            ++unresolved;
          }
        }
      });
    this->Report.unresolvedAtDepthCap += unresolved;
    this->appendPixelHits(perPixel);
  }

  const Scene Patches;
  const View& TheView;
  const Settings& Config;
  FrameReport& Report;
  FramePlan Plan;
  Buffer<PatchShape> Shapes;
  AffineForms Affine;                               // ray composition: each patch's affine form
  std::unique_ptr<FrustumForms> Forms;              // and its frustum form where one pays
  std::unique_ptr<CellCoverage> Coverage;           // and the pixels its isosurface's cells cover
  std::shared_ptr<const PowerShadingTable> Shading; // and its power form for shading
  LoopState<CpuExec> Loop;
  std::vector<Node> Leaves; ///< brute force
  std::vector<double> LeafPool;
  std::vector<uint32_t> LeafOffsets;
};

} // namespace

View makeView(const Camera& camera, int width, int height)
{
  View view;
  view.worldToClip = worldToClip(camera, double(width) / double(height));
  view.forward = viewDirection(camera);
  view.eye = camera.position;
  view.parallel = camera.parallelProjection;
  view.pixelFootprint =
    camera.parallelProjection
      ? 2 * camera.parallelScale / height
      : 2 * std::tan(camera.viewAngle * 3.14159265358979323846 / 360.0) / height;
  return view;
}

const char* backendName(Backend backend)
{
  switch (backend)
  {
    case Backend::Automatic:
      return "auto";
    case Backend::Cpu:
      return "cpu";
    case Backend::Cuda:
      return "cuda";
  }
  return "unknown";
}

Backend parseBackend(const std::string& name)
{
  for (Backend backend : { Backend::Automatic, Backend::Cpu, Backend::Cuda })
  {
    if (name == backendName(backend))
    {
      return backend;
    }
  }
  throw std::invalid_argument("backend '" + name + "' is not auto, cpu or cuda");
}

namespace
{

/// The backend asked for: the setting, or for Automatic, IGAVIEW_BACKEND where it is set.
Backend requestedBackend(Backend setting)
{
  const char* forced = std::getenv("IGAVIEW_BACKEND");
  if (setting != Backend::Automatic || !forced || !*forced)
  {
    return setting;
  }
  try
  {
    return parseBackend(forced);
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("IGAVIEW_BACKEND: ") + e.what());
  }
}

/// Runs a frame where the settings and IGAVIEW_BACKEND say: `onCuda` when CUDA is wanted and
/// usable (a cuda::Failure redoes the frame with `onCpu`), else `onCpu`.
FrameReport dispatch(const Settings& settings, Method method,
  const std::function<void(FrameReport&)>& onCuda, const std::function<void(FrameReport&)>& onCpu)
{
  FrameReport report;
  report.method = methodName(method);
  const Backend wanted = requestedBackend(settings.backend);
  if ((method == Method::SharedSubdivisionTree || method == Method::Automatic) &&
      wanted != Backend::Cpu)
  {
    std::string why;
    if (cuda::usable(why))
    {
      try
      {
        onCuda(report);
        report.backend = backendName(Backend::Cuda);
        return report;
      }
      catch (const cuda::Failure& e)
      {
        report = FrameReport();
        report.method = methodName(method);
        report.notice = std::string("CUDA frame failed (") + e.what() + "), drawn on CPU threads";
        report.noticeSeverity = NoticeSeverity::Warning;
      }
    }
    else
    {
      report.notice =
        (wanted == Backend::Cuda ? "CUDA asked for, but " : "") + why + ": drawing on CPU threads";
      report.noticeSeverity =
        wanted == Backend::Cuda ? NoticeSeverity::Warning : NoticeSeverity::Info;
    }
  }
  onCpu(report);
  report.backend = backendName(Backend::Cpu);
  return report;
}

} // namespace

void releaseHostCache()
{
  BlockCache::instance().release();
}

InputForm preferredInput(Backend backend)
{
  const Backend wanted = requestedBackend(backend);
  std::string why;
  return wanted == Backend::Cuda || (wanted == Backend::Automatic && cuda::usable(why))
           ? InputForm::NurbsVolumes
           : InputForm::BezierPatches;
}

FrameReport render(
  const Scene& scene, const View& view, const Settings& settings, Method method, GBuffer& out)
{
  return dispatch(
    settings, method,
    [&](FrameReport& report)
    {
      cuda::render(scene, view, settings, out, report);
      report.sstPatches = scene.size();
    },
    [&](FrameReport& report) { Renderer(scene, view, settings, report).run(method, out); });
}

std::vector<BezierVolume<double>> extractElements(const NurbsVolumes& volumes)
{
  checkNurbsVolumes(volumes);
  // Elements numbered volume by volume, extracted on all threads.
  std::vector<size_t> first(volumes.extractions.size() + 1, 0);
  std::vector<BezierVolume<double>> patches;
  for (size_t v = 0; v < volumes.extractions.size(); ++v)
  {
    const auto& extraction = *volumes.extractions[v];
    first[v + 1] = first[v] + size_t(extraction.elementCount());
    int degree[3];
    for (int d = 0; d < 3; ++d)
    {
      degree[d] = extraction.direction(d).degree;
    }
    patches.resize(first[v + 1], BezierVolume<double>(degree, volumes.channels));
  }
  parallelFor(patches.size(), int(std::max(1u, std::thread::hardware_concurrency())),
    [&](size_t begin, size_t end)
    {
      std::vector<double> work;
      for (size_t e = begin; e < end; ++e)
      {
        const size_t v =
          size_t(std::upper_bound(first.begin(), first.end(), e) - first.begin()) - 1;
        work.resize(2 * patches[e].coeffs().size());
        volumes.extractions[v]->extract(int(e - first[v]), volumes.nets[v]->data(),
          volumes.channels, patches[e].coeffs().data(), work.data());
      }
    });
  return patches;
}

FrameReport render(const NurbsVolumes& volumes, const View& view, const Settings& settings,
  Method method, GBuffer& out)
{
  checkNurbsVolumes(volumes);
  return dispatch(
    settings, method,
    [&](FrameReport& report)
    {
      cuda::renderNurbs(volumes, view, settings, out, report);
      for (const auto& extraction : volumes.extractions)
      {
        report.sstPatches += size_t(extraction->elementCount());
      }
    },
    [&](FrameReport& report)
    {
      const auto patches = extractElements(volumes);
      Renderer(patches, view, settings, report).run(method, out);
    });
}

FrameReport render(
  const Scene& scene, const Camera& camera, const Settings& settings, Method method, GBuffer& out)
{
  return render(scene, makeView(camera, settings.width, settings.height), settings, method, out);
}

} // namespace sst
} // namespace iga
