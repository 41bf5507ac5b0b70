// CPU drivers of the isosurface rasterizer: the Shared Subdivision Tree algorithm (Liu et al.),
// the per-pixel basic scheme and a brute-force reference, over the shared pixel-problem kernels.
#include "iga/sst/Engine.h"

#include "CudaEngine.h"

#include "iga/Validation.h"
#include "iga/sst/PixelProblem.h"
#include "iga/sst/Tree.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace iga
{
namespace sst
{

size_t GBuffer::coveredPixels() const
{
  size_t covered = 0;
  for (size_t p = 0; p + 1 < this->offsets.size(); ++p)
  {
    covered += this->offsets[p + 1] > this->offsets[p] ? 1 : 0;
  }
  return covered;
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
  }
  return "unknown";
}

void patchBounds(const std::vector<BezierVolume<double>>& patches, double* bounds)
{
  for (int d = 0; d < 3; ++d)
  {
    bounds[2 * d] = std::numeric_limits<double>::infinity();
    bounds[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (const auto& patch : patches)
  {
    const auto view = patch.view();
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
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Sub-patches per level kept while splitting a patch at the eye plane.
constexpr size_t kMaxEyePlaneNodes = size_t(1) << 16;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Runs fn(begin, end) over [0, n) on `threads` threads pulling chunks. Callers write results
/// per index, so outputs never depend on the thread count or scheduling.
template<class Fn>
void parallelFor(size_t n, int threads, Fn&& fn)
{
  const size_t grain = std::max<size_t>(1, n / (size_t(std::max(threads, 1)) * 16));
  if (threads <= 1 || n <= grain)
  {
    if (n > 0)
    {
      fn(size_t(0), n);
    }
    return;
  }
  std::atomic<size_t> next{ 0 };
  auto worker = [&]()
  {
    for (;;)
    {
      const size_t begin = next.fetch_add(grain);
      if (begin >= n)
      {
        break;
      }
      fn(begin, std::min(n, begin + grain));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
  {
    pool.emplace_back(worker);
  }
  worker();
  for (auto& thread : pool)
  {
    thread.join();
  }
}

/// Exclusive prefix sum in place; returns the total.
size_t exclusiveScan(std::vector<uint32_t>& counts)
{
  size_t total = 0;
  for (auto& c : counts)
  {
    const size_t n = c;
    c = static_cast<uint32_t>(total);
    total += n;
  }
  return total;
}

template<class V>
size_t bytesOf(const V& v)
{
  return v.capacity() * sizeof(typename V::value_type);
}

class Renderer
{
public:
  Renderer(const std::vector<BezierVolume<double>>& patches, const View& view,
    const Settings& settings, FrameReport& report)
    : Patches(patches)
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
    Clock::time_point stage = Clock::now();
    this->sweepAndGroup();
    this->Report.msSweepAndGroup = millisecondsSince(stage);
    switch (method)
    {
      case Method::SharedSubdivisionTree:
        this->sharedSubdivisionTrees();
        break;
      case Method::BasicScheme:
        this->basicScheme();
        break;
      case Method::BruteForce:
        this->bruteForce();
        break;
    }
    stage = Clock::now();
    this->fillGBuffer(out);
    this->Report.msGBuffer = millisecondsSince(stage);
    for (uint8_t flag : this->Unresolved)
    {
      this->Report.unresolvedPixels += flag ? 1 : 0;
    }
    this->Report.msTotal = millisecondsSince(start);
  }

private:
  // ---- frame setup -------------------------------------------------------------------------

  void setup()
  {
    const Settings& s = this->Config;
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
    this->Threads = s.threads > 0 ? s.threads : std::max(1u, std::thread::hardware_concurrency());
    this->Report.threads = this->Threads;
    const int attribute = kFirstAttributeChannel + s.surfaceAttribute;
    double attributeLo = kInfinity, attributeHi = -kInfinity;
    for (size_t p = 0; p < this->Patches.size(); ++p)
    {
      const auto view = this->Patches[p].view();
      const std::string problem = checkPatch<double, 3>(view);
      if (!problem.empty())
      {
        throw std::invalid_argument("patch " + std::to_string(p) + ": " + problem);
      }
      if (s.surfaceAttribute < 0 || attribute >= view.channels ||
          (s.colorAttribute >= 0 && kFirstAttributeChannel + s.colorAttribute >= view.channels))
      {
        throw std::invalid_argument("patch " + std::to_string(p) + " has " +
                                    std::to_string(view.channels - kFirstAttributeChannel) +
                                    " attributes; the surface uses " +
                                    std::to_string(s.surfaceAttribute) + ", the colour " +
                                    std::to_string(s.colorAttribute));
      }
      double lo, hi;
      rationalRange(view, attribute, kWeightChannel, lo, hi);
      attributeLo = std::min(attributeLo, lo);
      attributeHi = std::max(attributeHi, hi);
    }
    const double range = attributeHi > attributeLo ? attributeHi - attributeLo : 1.0;
    if (s.clipPlanes.size() > size_t(kMaxClipPlanes))
    {
      throw std::invalid_argument("at most " + std::to_string(kMaxClipPlanes) +
                                  " clipping planes are supported, got " +
                                  std::to_string(s.clipPlanes.size()));
    }
    this->Tolerance[0] = this->Tolerance[1] = s.pixelTolerance;
    this->Tolerance[2] = s.isoTolerance * range;

    // Window coordinates: x, y in pixels (pixel i covers [i, i+1]), z the NDC depth.
    const double W = s.width, H = s.height;
    Matrix4<double> window = Matrix4<double>::identity();
    window.m[0][0] = 0.5 * W;
    window.m[0][3] = 0.5 * W;
    window.m[1][1] = 0.5 * H;
    window.m[1][3] = 0.5 * H;
    this->WindowFromWorld = multiply(window, this->TheView.worldToClip);
    this->Clip.count = 0;
    for (const auto& plane : s.clipPlanes)
    {
      const bool finite = std::isfinite(plane[0]) && std::isfinite(plane[1]) &&
                          std::isfinite(plane[2]) && std::isfinite(plane[3]);
      if (!finite || (plane[0] == 0 && plane[1] == 0 && plane[2] == 0) ||
          !transformPlane(this->WindowFromWorld, plane.data(), this->Clip.plane[this->Clip.count]))
      {
        throw std::invalid_argument(
          "clipping plane " + std::to_string(this->Clip.count) + " is not a finite plane");
      }
      ++this->Clip.count;
    }
    this->Frame.width = s.width;
    this->Frame.height = s.height;
    this->Frame.firstHitOnly = s.firstHitOnly;
    this->Frame.maxSubdivisionDepth = s.maxSubdivisionDepth;
    for (int d = 0; d < 3; ++d)
    {
      this->Frame.tolerance[d] = this->Tolerance[d];
    }
    this->Frame.clip = this->Clip;
    this->Frame.isovalues = s.isovalues.data();
    this->PixelCount = size_t(s.width) * s.height;
    this->Unresolved.assign(this->PixelCount, 0);
    this->BestDepth.assign(this->PixelCount, kInfinity);

    // Screen patches of every input patch, then the subdivision-tree roots: one per (patch,
    // isovalue) with a possible sign change. Roots straddling the eye plane are split until
    // their parts lie in front of or behind it.
    for (size_t p = 0; p < this->Patches.size(); ++p)
    {
      const auto world = this->Patches[p].view();
      std::vector<double> screen(size_t(world.pointCount()) * kScreenChannels);
      makeScreenPatch<double>(world, this->WindowFromWorld, attribute, screen.data());
      this->ShadingOffsets.push_back(this->ShadingPool.size());
      this->ShadingPool.resize(this->ShadingPool.size() + world.pointCount() * kShadeChannels);
      makeShadingPatch(world, attribute,
        s.colorAttribute >= 0 ? kFirstAttributeChannel + s.colorAttribute : -1,
        this->ShadingPool.data() + this->ShadingOffsets.back());
      for (int iso = 0; iso < int(s.isovalues.size()); ++iso)
      {
        Node root = rootNode(int(p), iso);
        this->addInitialNode(root, screen.data());
      }
    }
    this->trackMemory(bytesOf(this->InitialPool));
  }

  VolumeView<const double> shadingView(int patch) const
  {
    return VolumeView<const double>(this->ShadingPool.data() + this->ShadingOffsets[patch],
      this->Patches[patch].view().degree, kShadeChannels);
  }

  int valueCount(int patch) const
  {
    return this->Patches[patch].view().pointCount() * kScreenChannels;
  }

  VolumeView<const double> nodeView(const Node& node, const std::vector<double>& pool) const
  {
    return VolumeView<const double>(
      pool.data() + node.coeff, this->Patches[node.patch].view().degree, kScreenChannels);
  }

  /// Adds a root to the initial nodes if it may show surface. A root straddling the eye plane
  /// has no finite window box: it is split breadth first until its parts lie in front of the
  /// eye, behind it, or in front of the near plane (all invisible but the first). Parts still
  /// straddling at the depth cap or beyond the node budget are counted, not drawn.
  void addInitialNode(Node root, const double* coeffs)
  {
    const int count = this->valueCount(root.patch);
    const auto rootView = this->Patches[root.patch].view();
    const int* degree = rootView.degree;
    std::vector<Node> level = { root };
    std::vector<double> pool(coeffs, coeffs + count);
    while (!level.empty())
    {
      std::vector<Node> straddling;
      std::vector<double> straddlingPool;
      for (Node node : level)
      {
        const VolumeView<const double> view(pool.data() + node.coeff, degree, kScreenChannels);
        node.info = analyzeNode(view, this->Config.isovalues[node.iso], this->Clip);
        if (!worthKeeping(node.info, this->Frame))
        {
          continue;
        }
        if (node.info.status == ProjectionStatus::InFront)
        {
          const size_t offset = this->InitialPool.size();
          this->InitialPool.insert(this->InitialPool.end(), view.coeffs, view.coeffs + count);
          node.coeff = offset;
          this->InitialNodes.push_back(node);
          continue;
        }
        if (node.level >= this->Config.maxSubdivisionDepth ||
            straddling.size() + 8 > kMaxEyePlaneNodes)
        {
          ++this->Report.droppedAtEyePlane;
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

  // ---- sweep and group ---------------------------------------------------------------------

  /// Calls fn(pixel index) for every pixel whose centre the box covers.
  template<class Fn>
  void forEachCoveredPixel(const Box3<double>& box, Fn fn) const
  {
    int range[4];
    pixelRange(box, this->Config.width, this->Config.height, range);
    for (int j = range[2]; j <= range[3]; ++j)
    {
      for (int i = range[0]; i <= range[1]; ++i)
      {
        if (boxCoversPixel(box, i, j))
        {
          fn(size_t(j) * this->Config.width + i);
        }
      }
    }
  }

  /// Per pixel, the initial nodes whose boxes cover it, sorted by nearest depth: the work items
  /// of SAG. Stored as one array with per-pixel offsets.
  void sweepAndGroup()
  {
    std::vector<uint32_t> counts(this->PixelCount + 1, 0);
    for (size_t n = 0; n < this->InitialNodes.size(); ++n)
    {
      this->forEachCoveredPixel(this->InitialNodes[n].info.box, [&](size_t p) { ++counts[p]; });
    }
    const size_t total = exclusiveScan(counts);
    this->ItemOffsets = counts;
    this->Items.resize(total);
    std::vector<uint32_t> fill(counts.begin(), counts.end() - 1);
    for (size_t n = 0; n < this->InitialNodes.size(); ++n)
    {
      this->forEachCoveredPixel(
        this->InitialNodes[n].info.box, [&](size_t p) { this->Items[fill[p]++] = uint32_t(n); });
    }
    parallelFor(this->PixelCount, this->Threads,
      [&](size_t begin, size_t end)
      {
        for (size_t p = begin; p < end; ++p)
        {
          std::sort(this->Items.begin() + this->ItemOffsets[p],
            this->Items.begin() + this->ItemOffsets[p + 1],
            [&](uint32_t a, uint32_t b)
            {
              const double za = this->InitialNodes[a].info.box.lo[2],
                           zb = this->InitialNodes[b].info.box.lo[2];
              return za < zb || (za == zb && a < b);
            });
        }
      });
    this->trackMemory(
      bytesOf(this->Items) + bytesOf(this->ItemOffsets) + bytesOf(this->InitialPool));
  }

  /// The next group of a pixel's work items from `cursor`: in first-hit mode the nearest item
  /// and all items overlapping it in depth (none when the best hit is nearer), else all items.
  size_t groupEnd(size_t pixel, size_t cursor) const
  {
    const size_t end = this->ItemOffsets[pixel + 1];
    if (!this->Config.firstHitOnly)
    {
      return end;
    }
    if (cursor >= end ||
        this->InitialNodes[this->Items[cursor]].info.box.lo[2] > this->BestDepth[pixel])
    {
      return cursor;
    }
    double groupFar = this->InitialNodes[this->Items[cursor]].info.box.hi[2];
    size_t last = cursor + 1;
    while (last < end && this->InitialNodes[this->Items[last]].info.box.lo[2] <= groupFar)
    {
      groupFar = std::max(groupFar, this->InitialNodes[this->Items[last]].info.box.hi[2]);
      ++last;
    }
    return last;
  }

  // ---- shared subdivision trees ------------------------------------------------------------

  enum Outcome : uint8_t
  {
    Solved,
    Failed,
    Dropped
  };

  void sharedSubdivisionTrees()
  {
    std::vector<uint32_t> cursor(this->ItemOffsets.begin(), this->ItemOffsets.end() - 1);
    for (;;)
    {
      // Each round takes every pixel's next depth group (the SAG work sets).
      const Clock::time_point stage = Clock::now();
      std::vector<uint32_t> ends(this->PixelCount);
      std::atomic<size_t> total{ 0 };
      parallelFor(this->PixelCount, this->Threads,
        [&](size_t begin, size_t end)
        {
          size_t local = 0;
          for (size_t p = begin; p < end; ++p)
          {
            ends[p] = uint32_t(this->groupEnd(p, cursor[p]));
            local += ends[p] - cursor[p];
          }
          total += local;
        });
      this->Report.msSweepAndGroup += millisecondsSince(stage);
      if (total == 0)
      {
        break;
      }
      this->solveRound(cursor, ends);
      cursor = ends;
    }
  }

  /// Whether pixel p works on initial node n in this round (n is in its current group).
  bool inGroup(size_t p, uint32_t n) const
  {
    for (uint32_t k = this->GroupBegin[p]; k < this->GroupEnd[p]; ++k)
    {
      if (this->Items[k] == n)
      {
        return true;
      }
    }
    return false;
  }

  /// The SST loop of the paper over one round: overlap (tuples of pixels and node boxes),
  /// solution, subdivision and compaction, until no tuple and no implicit node is left.
  void solveRound(const std::vector<uint32_t>& groupBegin, const std::vector<uint32_t>& groupEnd)
  {
    this->GroupBegin = groupBegin;
    this->GroupEnd = groupEnd;
    const bool firstHit = this->Config.firstHitOnly;
    // This round's initial nodes, all implicit.
    std::vector<Node> nodes;
    std::vector<double> pool;
    {
      std::vector<uint8_t> present(this->InitialNodes.size(), 0);
      for (size_t p = 0; p < this->PixelCount; ++p)
      {
        for (uint32_t k = groupBegin[p]; k < groupEnd[p]; ++k)
        {
          present[this->Items[k]] = 1;
        }
      }
      for (size_t n = 0; n < this->InitialNodes.size(); ++n)
      {
        if (present[n])
        {
          Node node = this->InitialNodes[n];
          const double* src = this->InitialPool.data() + node.coeff;
          node.coeff = pool.size();
          node.initial = uint32_t(n);
          node.implicit = true;
          pool.insert(pool.end(), src, src + this->valueCount(node.patch));
          nodes.push_back(node);
        }
      }
    }
    std::vector<Tuple> tuples;
    std::vector<uint8_t> outcome;
    std::vector<double> solution; // per tuple: u[3], ndc depth
    while (!nodes.empty())
    {
      ++this->Report.iterations;
      this->Report.maxPatches = std::max(this->Report.maxPatches, nodes.size());

      // Overlap stage: implicit nodes that are ready become tuples of the pixels whose centres
      // their boxes cover (members of the round, not behind a nearer hit).
      Clock::time_point stage = Clock::now();
      std::vector<uint32_t> ready;
      for (size_t n = 0; n < nodes.size(); ++n)
      {
        if (nodes[n].implicit && readyForTuples(nodes[n], this->Frame))
        {
          ready.push_back(uint32_t(n));
        }
      }
      std::vector<uint32_t> readyCounts(ready.size() + 1, 0);
      auto forCoveredPixels = [&](const Node& node, auto fn)
      {
        this->forEachCoveredPixel(node.info.box,
          [&](size_t p)
          {
            if (!(firstHit && node.info.box.lo[2] > this->BestDepth[p]) &&
                this->inGroup(p, node.initial))
            {
              fn(p);
            }
          });
      };
      parallelFor(ready.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t k = begin; k < end; ++k)
          {
            forCoveredPixels(nodes[ready[k]], [&](size_t) { ++readyCounts[k]; });
          }
        });
      const size_t existing = tuples.size();
      tuples.resize(existing + exclusiveScan(readyCounts));
      parallelFor(ready.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t k = begin; k < end; ++k)
          {
            size_t write = existing + readyCounts[k];
            forCoveredPixels(nodes[ready[k]],
              [&](size_t p) {
                tuples[write++] = { uint32_t(p), ready[k] };
              });
          }
        });
      parallelFor(ready.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t k = begin; k < end; ++k)
          {
            Node& node = nodes[ready[k]];
            node.implicit = false;
            analyzeNodeCentre(this->nodeView(node, pool), node.info);
          }
        });
      this->Report.maxTuples = std::max(this->Report.maxTuples, tuples.size());
      this->Report.msOverlap += millisecondsSince(stage);

      // Solution stage: exclusions, and Newton where a node certifies a unique root. Each
      // pixel's tuples are solved in order of nearest depth by one thread, so that in first-hit
      // mode a hit drops the tuples behind it at once.
      stage = Clock::now();
      {
        std::vector<uint32_t> start(this->PixelCount + 1, 0);
        for (const auto& t : tuples)
        {
          ++start[t.pixel];
        }
        exclusiveScan(start);
        std::vector<Tuple> byPixel(tuples.size());
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (const auto& t : tuples)
        {
          byPixel[fill[t.pixel]++] = t;
        }
        tuples.swap(byPixel);
        this->PixelStart.swap(start);
      }
      outcome.assign(tuples.size(), Failed);
      solution.resize(tuples.size() * 4);
      std::atomic<size_t> solves{ 0 };
      parallelFor(this->PixelCount, this->Threads,
        [&](size_t begin, size_t end)
        {
          size_t local = 0;
          for (size_t pixel = begin; pixel < end; ++pixel)
          {
            const uint32_t first = this->PixelStart[pixel], last = this->PixelStart[pixel + 1];
            std::sort(tuples.begin() + first, tuples.begin() + last,
              [&](const Tuple& a, const Tuple& b)
              {
                const double za = nodes[a.node].info.box.lo[2], zb = nodes[b.node].info.box.lo[2];
                return za < zb || (za == zb && a.node < b.node);
              });
            double best = this->BestDepth[pixel];
            for (uint32_t t = first; t < last; ++t)
            {
              const Node& node = nodes[tuples[t].node];
              if (firstHit && node.info.box.lo[2] > best)
              {
                outcome[t] = Dropped;
                continue;
              }
              const int i = int(pixel % this->Config.width), j = int(pixel / this->Config.width);
              local += node.info.certified ? 1 : 0;
              switch (solveTuple(this->nodeView(node, pool), node.info, i, j,
                this->Config.isovalues[node.iso], this->Tolerance, &solution[4 * t],
                solution[4 * t + 3], this->Clip))
              {
                case TupleOutcome::Hit:
                  outcome[t] = Solved;
                  best = std::min(best, solution[4 * t + 3]);
                  break;
                case TupleOutcome::Miss:
                  outcome[t] = Dropped;
                  break;
                case TupleOutcome::Undecided:
                  break;
              }
            }
          }
          solves += local;
        });
      this->Report.newtonSolves += solves;
      for (size_t t = 0; t < tuples.size(); ++t)
      {
        if (outcome[t] == Solved)
        {
          this->recordHit(
            tuples[t].pixel, nodes[tuples[t].node], &solution[4 * t], solution[4 * t + 3]);
        }
      }
      this->Report.msSolution += millisecondsSince(stage);

      // Subdivision stage: split the nodes some pixel failed on, and the implicit ones whose
      // boxes still cover pixels.
      stage = Clock::now();
      std::vector<uint8_t> split(nodes.size(), 0);
      for (size_t t = 0; t < tuples.size(); ++t)
      {
        if (outcome[t] == Failed && firstHit &&
            nodes[tuples[t].node].info.box.lo[2] > this->BestDepth[tuples[t].pixel])
        {
          outcome[t] = Dropped; // a nearer hit was found this iteration
        }
        if (outcome[t] == Failed)
        {
          split[tuples[t].node] = 1;
        }
      }
      std::vector<uint32_t> toSplit;
      for (size_t n = 0; n < nodes.size(); ++n)
      {
        if (nodes[n].implicit)
        {
          int range[4];
          pixelRange(nodes[n].info.box, this->Config.width, this->Config.height, range);
          split[n] = range[0] <= range[1] && range[2] <= range[3] ? 1 : 0;
        }
        if (split[n] && nodes[n].level >= this->Config.maxSubdivisionDepth)
        {
          split[n] = 2; // at the depth cap: its pixels stay unresolved
        }
        else if (split[n])
        {
          toSplit.push_back(uint32_t(n));
        }
      }
      // Memory cap: split as many nodes as the budget allows, in order; implicit nodes beyond
      // it become tuples in the next iteration instead, explicit ones leave their pixels
      // unresolved.
      size_t childBytes = 0, allowed = 0;
      for (; allowed < toSplit.size(); ++allowed)
      {
        const size_t bytes =
          size_t(8) * this->valueCount(nodes[toSplit[allowed]].patch) * sizeof(double) +
          8 * sizeof(Node);
        if (childBytes + bytes + bytesOf(pool) + bytesOf(tuples) > this->Config.memoryBudgetBytes)
        {
          break;
        }
        childBytes += bytes;
      }
      std::vector<Node> deferred;
      std::vector<double> deferredPool;
      for (size_t k = allowed; k < toSplit.size(); ++k)
      {
        Node& node = nodes[toSplit[k]];
        if (node.implicit)
        {
          node.overBudget = true; // ready for tuples next time
          deferred.push_back(node);
          split[toSplit[k]] = 0;
        }
        else
        {
          split[toSplit[k]] = 3; // over budget
        }
      }
      toSplit.resize(allowed);
      std::vector<uint32_t> poolOffset(toSplit.size() + 1, 0);
      for (size_t k = 0; k < toSplit.size(); ++k)
      {
        poolOffset[k + 1] = poolOffset[k] + 8 * this->valueCount(nodes[toSplit[k]].patch);
      }
      if (this->ChildPool.size() < poolOffset.back())
      {
        this->ChildPool.resize(poolOffset.back()); // grows only: no zeroing every iteration
      }
      std::vector<double>& childPool = this->ChildPool;
      std::vector<Node> children(toSplit.size() * 8);
      std::vector<uint8_t> keep(children.size(), 0);
      parallelFor(toSplit.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t k = begin; k < end; ++k)
          {
            const Node& parent = nodes[toSplit[k]];
            const int count = this->valueCount(parent.patch);
            splitMidpoint<double, 3>(
              this->nodeView(parent, pool), childPool.data() + poolOffset[k]);
            for (int c = 0; c < 8; ++c)
            {
              Node child = childOf(parent, c);
              child.coeff = poolOffset[k] + size_t(c) * count;
              const auto view = this->nodeView(child, childPool);
              child.info = analyzeNodeBounds(view, this->Config.isovalues[child.iso], this->Clip);
              keep[8 * k + c] = worthKeeping(child.info, this->Frame) ? 1 : 0;
              // Explicit children are analysed once they are known to receive pixels.
              if (child.implicit && keep[8 * k + c])
              {
                analyzeNodeSolver(view, child.info);
              }
              children[8 * k + c] = child;
            }
          }
        });
      this->Report.subdividedPatches += toSplit.size();
      this->trackMemory(bytesOf(pool) + bytesOf(childPool) + bytesOf(tuples) + bytesOf(children) +
                        bytesOf(outcome) + bytesOf(solution) + this->baseBytes());
      this->Report.msSubdivision += millisecondsSince(stage);

      // Compaction: failed tuples move to the kept children covering their pixel; solved and
      // dropped tuples and unsplit explicit nodes leave.
      stage = Clock::now();
      std::vector<uint32_t> firstChild(nodes.size(), 0);
      for (size_t k = 0; k < toSplit.size(); ++k)
      {
        firstChild[toSplit[k]] = uint32_t(8 * k);
      }
      auto childCovers = [&](const Tuple& t, size_t c)
      {
        // Children of nodes in front of the eye are in front too (positive weights stay positive).
        return keep[c] &&
               boxCoversPixel(children[c].info.box, int(t.pixel % this->Config.width),
                 int(t.pixel / this->Config.width)) &&
               !(firstHit && children[c].info.box.lo[2] > this->BestDepth[t.pixel]);
      };
      std::vector<uint32_t> newCounts(tuples.size(), 0);
      parallelFor(tuples.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t t = begin; t < end; ++t)
          {
            if (outcome[t] != Failed || split[tuples[t].node] != 1)
            {
              continue;
            }
            const size_t base = firstChild[tuples[t].node];
            for (size_t c = base; c < base + 8; ++c)
            {
              newCounts[t] += childCovers(tuples[t], c) ? 1 : 0;
            }
          }
        });
      for (size_t t = 0; t < tuples.size(); ++t)
      {
        if (outcome[t] == Failed && split[tuples[t].node] >= 2)
        {
          this->Unresolved[tuples[t].pixel] = 1;
          ++(split[tuples[t].node] == 2 ? this->Report.unresolvedAtDepthCap
                                        : this->Report.unresolvedAtBudget);
        }
      }
      std::vector<uint32_t> newOffsets = newCounts;
      std::vector<Tuple> next(exclusiveScan(newOffsets));
      parallelFor(tuples.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t t = begin; t < end; ++t)
          {
            uint32_t write = newOffsets[t];
            const size_t base = firstChild[tuples[t].node];
            for (size_t c = base; newCounts[t] > 0 && c < base + 8; ++c)
            {
              if (childCovers(tuples[t], c))
              {
                next[write++] = { tuples[t].pixel, uint32_t(c) };
              }
            }
          }
        });
      // The next nodes: implicit children that were kept, explicit children that received
      // pixels, and deferred implicit nodes; stored contiguously.
      std::vector<uint8_t> used(children.size(), 0);
      for (const auto& t : next)
      {
        used[t.node] = 1;
      }
      std::vector<uint32_t> newIndex(children.size(), 0);
      std::vector<Node> kept;
      std::vector<size_t> keptOffset(1, 0);
      for (size_t c = 0; c < children.size(); ++c)
      {
        if (keep[c] && (children[c].implicit || used[c]))
        {
          newIndex[c] = uint32_t(kept.size());
          kept.push_back(children[c]);
          keptOffset.push_back(keptOffset.back() + size_t(this->valueCount(children[c].patch)));
        }
      }
      const size_t fromChildren = kept.size();
      for (const Node& node : deferred)
      {
        kept.push_back(node);
        keptOffset.push_back(keptOffset.back() + size_t(this->valueCount(node.patch)));
      }
      std::vector<double> keptPool(keptOffset.back());
      parallelFor(kept.size(), this->Threads,
        [&](size_t begin, size_t end)
        {
          for (size_t n = begin; n < end; ++n)
          {
            const size_t count = keptOffset[n + 1] - keptOffset[n];
            const std::vector<double>& source = n < fromChildren ? childPool : pool;
            std::copy(source.begin() + kept[n].coeff, source.begin() + kept[n].coeff + count,
              keptPool.begin() + keptOffset[n]);
            kept[n].coeff = keptOffset[n];
            if (n < fromChildren && !kept[n].implicit)
            {
              const auto view = this->nodeView(kept[n], keptPool);
              analyzeNodeSolver(view, kept[n].info);
              analyzeNodeCentre(view, kept[n].info);
            }
          }
        });
      for (auto& t : next)
      {
        t.node = newIndex[t.node];
      }
      nodes.swap(kept);
      pool.swap(keptPool);
      tuples.swap(next);
      this->Report.msCompaction += millisecondsSince(stage);
      if (this->Config.progress)
      {
        this->Config.progress(this->Report.iterations, tuples.size());
      }
    }
  }

  size_t baseBytes() const
  {
    return bytesOf(this->Items) + bytesOf(this->ItemOffsets) + bytesOf(this->InitialPool) +
           bytesOf(this->Hits) + bytesOf(this->BestDepth) + bytesOf(this->Unresolved);
  }

  void trackMemory(size_t bytes)
  {
    this->Report.peakBytes = std::max(this->Report.peakBytes, bytes);
  }

  void recordHit(uint32_t pixel, const Node& node, const double* u, double ndcDepth)
  {
    this->Hits.push_back(rawHitOf(pixel, node, u, ndcDepth));
    this->BestDepth[pixel] = std::min(this->BestDepth[pixel], ndcDepth);
  }

  // ---- basic scheme ------------------------------------------------------------------------

  /// One subdivision tree per pixel, depth first, with the same node tests and Newton solves.
  void basicScheme()
  {
    const Clock::time_point stage = Clock::now();
    std::vector<std::vector<RawHit>> perPixel(this->PixelCount);
    std::vector<size_t> peak(this->PixelCount, 0);
    std::atomic<size_t> solves{ 0 }, splits{ 0 }, capped{ 0 };
    parallelFor(this->PixelCount, this->Threads,
      [&](size_t begin, size_t end)
      {
        // The arena holds exactly the stacked nodes' coefficient blocks, in stack order.
        std::vector<Node> stack;
        std::vector<double> arena, current, children;
        size_t localSolves = 0, localSplits = 0;
        for (size_t p = begin; p < end; ++p)
        {
          const int i = int(p % this->Config.width), j = int(p / this->Config.width);
          double best = kInfinity;
          for (uint32_t item = this->ItemOffsets[p]; item < this->ItemOffsets[p + 1]; ++item)
          {
            const Node& initial = this->InitialNodes[this->Items[item]];
            if (this->Config.firstHitOnly && initial.info.box.lo[2] > best)
            {
              break;
            }
            const int count = this->valueCount(initial.patch);
            stack.assign(1, initial);
            stack.back().coeff = 0;
            arena.assign(this->InitialPool.begin() + initial.coeff,
              this->InitialPool.begin() + initial.coeff + count);
            while (!stack.empty())
            {
              Node node = stack.back();
              stack.pop_back();
              current.assign(arena.begin() + node.coeff, arena.begin() + node.coeff + count);
              arena.resize(node.coeff);
              node.coeff = 0;
              if (!boxCoversPixel(node.info.box, i, j) ||
                  (this->Config.firstHitOnly && node.info.box.lo[2] > best))
              {
                continue;
              }
              localSolves += node.info.certified ? 1 : 0;
              double u[3], ndc;
              const TupleOutcome result = solveTuple(this->nodeView(node, current), node.info, i, j,
                this->Config.isovalues[node.iso], this->Tolerance, u, ndc, this->Clip);
              if (result == TupleOutcome::Hit)
              {
                perPixel[p].push_back(rawHitOf(uint32_t(p), node, u, ndc));
                best = std::min(best, ndc);
              }
              if (result != TupleOutcome::Undecided)
              {
                continue;
              }
              if (node.level >= this->Config.maxSubdivisionDepth)
              {
                this->Unresolved[p] = 1;
                ++capped;
                continue;
              }
              ++localSplits;
              children.resize(size_t(8) * count);
              splitMidpoint<double, 3>(this->nodeView(node, current), children.data());
              // Push far children first so that the near ones are explored first.
              for (int c = 7; c >= 0; --c)
              {
                Node child = childOf(node, c);
                child.coeff = size_t(c) * count;
                child.info = analyzeNode(
                  this->nodeView(child, children), this->Config.isovalues[child.iso], this->Clip);
                if (worthKeeping(child.info, this->Frame))
                {
                  child.coeff = arena.size();
                  arena.insert(arena.end(), children.begin() + size_t(c) * count,
                    children.begin() + size_t(c + 1) * count);
                  stack.push_back(child);
                }
              }
              peak[p] = std::max(peak[p], bytesOf(arena) + bytesOf(stack) + bytesOf(children));
            }
          }
        }
        solves += localSolves;
        splits += localSplits;
      });
    this->Report.newtonSolves = solves;
    this->Report.subdividedPatches = splits;
    this->Report.unresolvedAtDepthCap = capped;
    for (auto& hits : perPixel)
    {
      this->Hits.insert(this->Hits.end(), hits.begin(), hits.end());
    }
    this->trackMemory(
      this->baseBytes() + *std::max_element(peak.begin(), peak.end()) * size_t(this->Threads));
    this->Report.msSolution = millisecondsSince(stage);
  }

  // ---- brute force -------------------------------------------------------------------------

  /// Uniform subdivision of every initial node to a fixed depth and Newton from nine starts in
  /// every leaf covering the pixel, without certificates: slow, independent of the tree logic.
  void bruteForce()
  {
    const Clock::time_point stage = Clock::now();
    std::vector<Node> leaves;
    std::vector<double> leafPool;
    std::vector<uint32_t> leafOffsets(this->InitialNodes.size() + 1, 0);
    for (size_t n = 0; n < this->InitialNodes.size(); ++n)
    {
      std::vector<Node> level = { this->InitialNodes[n] };
      level[0].coeff = 0;
      const int count = this->valueCount(level[0].patch);
      std::vector<double> pool(this->InitialPool.begin() + this->InitialNodes[n].coeff,
        this->InitialPool.begin() + this->InitialNodes[n].coeff + count);
      for (int depth = 0; depth < this->Config.bruteForceLevels; ++depth)
      {
        std::vector<Node> next;
        std::vector<double> nextPool(level.size() * 8 * size_t(count));
        for (size_t k = 0; k < level.size(); ++k)
        {
          splitMidpoint<double, 3>(this->nodeView(level[k], pool), nextPool.data() + k * 8 * count);
          for (int c = 0; c < 8; ++c)
          {
            Node child = childOf(level[k], c);
            child.coeff = (k * 8 + c) * size_t(count);
            child.info = analyzeNode(
              this->nodeView(child, nextPool), this->Config.isovalues[child.iso], this->Clip);
            if (worthKeeping(child.info, this->Frame) &&
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
        const size_t offset = leafPool.size();
        leafPool.insert(
          leafPool.end(), pool.begin() + leaf.coeff, pool.begin() + leaf.coeff + count);
        leaf.coeff = offset;
        leaves.push_back(leaf);
      }
      leafOffsets[n + 1] = uint32_t(leaves.size());
    }
    this->trackMemory(this->baseBytes() + bytesOf(leafPool) + bytesOf(leaves));
    std::vector<std::vector<RawHit>> perPixel(this->PixelCount);
    std::atomic<size_t> solves{ 0 };
    parallelFor(this->PixelCount, this->Threads,
      [&](size_t begin, size_t end)
      {
        size_t local = 0;
        for (size_t p = begin; p < end; ++p)
        {
          const int i = int(p % this->Config.width), j = int(p / this->Config.width);
          for (uint32_t item = this->ItemOffsets[p]; item < this->ItemOffsets[p + 1]; ++item)
          {
            const uint32_t n = this->Items[item];
            for (uint32_t l = leafOffsets[n]; l < leafOffsets[n + 1]; ++l)
            {
              const Node& leaf = leaves[l];
              if (!boxCoversPixel(leaf.info.box, i, j))
              {
                continue;
              }
              for (int s = 0; s < 9; ++s)
              {
                const double start[3] = { s == 8 ? 0.5 : 0.2 + 0.6 * (s & 1),
                  s == 8 ? 0.5 : 0.2 + 0.6 * ((s >> 1) & 1),
                  s == 8 ? 0.5 : 0.2 + 0.6 * ((s >> 2) & 1) };
                double u[3], ndc;
                ++local;
                // Roots up to Newton's domain slack outside the leaf count (those on
                // shared faces would otherwise be lost to rounding); duplicates are
                // merged later.
                if (solvePixel<double>(this->nodeView(leaf, leafPool), i, j,
                      this->Config.isovalues[leaf.iso], this->Tolerance, start, u, ndc,
                      this->Clip) == TupleOutcome::Hit)
                {
                  perPixel[p].push_back(rawHitOf(uint32_t(p), leaf, u, ndc));
                }
              }
            }
          }
        }
        solves += local;
      });
    this->Report.newtonSolves = solves;
    for (auto& hits : perPixel)
    {
      this->Hits.insert(this->Hits.end(), hits.begin(), hits.end());
    }
    this->Report.msSolution = millisecondsSince(stage);
  }

  // ---- G-buffer ----------------------------------------------------------------------------

  void fillGBuffer(GBuffer& out)
  {
    // Group by pixel, shade, sort front to back and merge duplicates.
    std::vector<uint32_t> offsets(this->PixelCount + 1, 0);
    for (const auto& hit : this->Hits)
    {
      ++offsets[hit.pixel];
    }
    exclusiveScan(offsets);
    std::vector<uint32_t> source(this->Hits.size());
    {
      std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
      for (size_t h = 0; h < this->Hits.size(); ++h)
      {
        source[fill[this->Hits[h].pixel]++] = uint32_t(h);
      }
    }
    ShadingView viewer{};
    for (int d = 0; d < 3; ++d)
    {
      viewer.eye[d] = this->TheView.eye[d];
      viewer.forward[d] = this->TheView.forward[d];
    }
    viewer.parallel = this->TheView.parallel;
    viewer.hasColor = this->Config.colorAttribute >= 0;
    std::vector<Hit> shaded(this->Hits.size());
    std::vector<uint32_t> keptCount(this->PixelCount, 0);
    parallelFor(this->PixelCount, this->Threads,
      [&](size_t begin, size_t end)
      {
        for (size_t p = begin; p < end; ++p)
        {
          for (uint32_t k = offsets[p]; k < offsets[p + 1]; ++k)
          {
            const RawHit& raw = this->Hits[source[k]];
            shaded[k] = shadeHit(this->shadingView(raw.patch), raw, viewer);
          }
          keptCount[p] =
            uint32_t(mergePixelHits(shaded.data() + offsets[p], int(offsets[p + 1] - offsets[p]),
              this->TheView.pixelFootprint, viewer.parallel, this->Config.firstHitOnly));
        }
      });
    out.width = this->Config.width;
    out.height = this->Config.height;
    out.offsets.assign(keptCount.begin(), keptCount.end());
    out.offsets.push_back(0);
    out.hits.resize(exclusiveScan(out.offsets));
    for (size_t p = 0; p < this->PixelCount; ++p)
    {
      std::copy(shaded.begin() + offsets[p], shaded.begin() + offsets[p] + keptCount[p],
        out.hits.begin() + out.offsets[p]);
    }
  }

  const std::vector<BezierVolume<double>>& Patches;
  const View& TheView;
  const Settings& Config;
  FrameReport& Report;
  int Threads = 1;
  double Tolerance[3] = {};
  Matrix4<double> WindowFromWorld;
  ClipPlanes<double> Clip; ///< Settings::clipPlanes in homogeneous window coordinates
  FrameConstants Frame{};
  std::vector<double> ShadingPool; ///< shading patches of the input patches
  std::vector<size_t> ShadingOffsets;
  size_t PixelCount = 0;
  std::vector<Node> InitialNodes;
  std::vector<double> InitialPool;
  std::vector<uint32_t> ItemOffsets;
  std::vector<uint32_t> Items;
  std::vector<double> BestDepth;
  std::vector<uint8_t> Unresolved;
  std::vector<RawHit> Hits;
  std::vector<uint32_t> GroupBegin, GroupEnd; ///< this round's work items per pixel
  std::vector<uint32_t> PixelStart;           ///< SST: each pixel's first tuple
  std::vector<double> ChildPool;              ///< SST: children's coefficients, reused
};

} // namespace

View makeView(const Camera& camera, int width, int height)
{
  View view;
  view.worldToClip = worldToClip(camera, double(width) / double(height));
  viewDirection(camera, view.forward);
  for (int d = 0; d < 3; ++d)
  {
    view.eye[d] = camera.position[d];
  }
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

FrameReport render(const std::vector<BezierVolume<double>>& patches, const View& view,
  const Settings& settings, Method method, GBuffer& out)
{
  FrameReport report;
  report.method = methodName(method);
  Backend wanted = settings.backend;
  if (wanted == Backend::Automatic)
  {
    const char* forced = std::getenv("IGAVIEW_BACKEND");
    if (forced && *forced)
    {
      try
      {
        wanted = parseBackend(forced);
      }
      catch (const std::invalid_argument& e)
      {
        throw std::invalid_argument(std::string("IGAVIEW_BACKEND: ") + e.what());
      }
    }
  }
  if (method == Method::SharedSubdivisionTree && wanted != Backend::Cpu)
  {
    std::string why;
    if (cuda::usable(why))
    {
      try
      {
        cuda::render(patches, view, settings, out, report);
        report.backend = backendName(Backend::Cuda);
        return report;
      }
      catch (const cuda::Failure& e)
      {
        report = FrameReport();
        report.method = methodName(method);
        report.notice = std::string("CUDA frame failed (") + e.what() + "), drawn on CPU threads";
      }
    }
    else
    {
      report.notice =
        (wanted == Backend::Cuda ? "CUDA asked for, but " : "") + why + ": drawing on CPU threads";
    }
  }
  Renderer(patches, view, settings, report).run(method, out);
  report.backend = backendName(Backend::Cpu);
  return report;
}

FrameReport render(const std::vector<BezierVolume<double>>& patches, const Camera& camera,
  const Settings& settings, Method method, GBuffer& out)
{
  return render(patches, makeView(camera, settings.width, settings.height), settings, method, out);
}

} // namespace sst
} // namespace iga
