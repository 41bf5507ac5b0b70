// CPU drivers of the isosurface rasterizer: the Shared Subdivision Tree algorithm (Liu et al.),
// the per-pixel basic scheme and a brute-force reference, over the shared pixel-problem kernels.
#include "iga/sst/Engine.h"

#include "BlockCache.h"
#include "CudaEngine.h"
#include "FramePlan.h"
#include "ParallelFor.h"

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

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Exclusive prefix sum in place into 32-bit offsets; returns the total, which they must
/// index.
template<class Counts>
size_t exclusiveScan(Counts& counts)
{
  size_t total = 0;
  for (auto& c : counts)
  {
    const size_t n = c;
    c = static_cast<uint32_t>(total);
    total += n;
  }
  checkIndexable(total);
  return total;
}

/// Groups tuples or hits by pixel, keeping their order within a pixel: a stable LSD radix sort
/// on the pixel index, 11 bits a pass. O(items) whatever the image size, where a counting sort
/// over the pixels paid for every pixel of a large, sparsely covered image (every iteration, for
/// the tuples). `runs` gets where each pixel's run starts, then the end.
template<class Item>
void groupByPixel(Array<Item>& items, size_t pixelCount, Array<uint32_t>& runs)
{
  constexpr int kRadixBits = 11;
  constexpr uint32_t kDigits = uint32_t(1) << kRadixBits;
  auto digit = [](const Item& item, int shift) { return (item.pixel >> shift) & (kDigits - 1); };
  const bool ordered = std::is_sorted(
    items.begin(), items.end(), [](const Item& a, const Item& b) { return a.pixel < b.pixel; });
  Array<uint32_t> counts;
  Array<Item> scratch;
  for (int shift = 0; !ordered && (size_t(1) << shift) < pixelCount; shift += kRadixBits)
  {
    counts.assign(kDigits, 0);
    for (const Item& item : items)
    {
      ++counts[digit(item, shift)];
    }
    exclusiveScan(counts);
    scratch.resize(items.size());
    for (const Item& item : items)
    {
      scratch[counts[digit(item, shift)]++] = item;
    }
    items.swap(scratch);
  }
  runs.clear();
  runs.reserve(items.size() + 1); // at most one run per item: no growth beyond that
  for (size_t k = 0; k < items.size(); ++k)
  {
    if (k == 0 || items[k].pixel != items[k - 1].pixel)
    {
      runs.push_back(uint32_t(k));
    }
  }
  runs.push_back(uint32_t(items.size()));
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
    this->Report.bands =
      drawInBands(rowBands(this->rowPairDifferences().data(), this->Config), this->Plan.frame,
        [&]
        {
          const Clock::time_point stage = Clock::now();
          this->sweepAndGroup();
          this->Report.msSweepAndGroup += millisecondsSince(stage);
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
        });
    const Clock::time_point stage = Clock::now();
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
    this->Plan = planFrame(this->Patches, this->TheView, this->Config, this->Report);
    this->PixelCount = size_t(this->Config.width) * this->Config.height;
    this->Unresolved.assign(this->PixelCount, 0);
    this->BestDepth.assign(this->PixelCount, kInfinity);
    // Empty groups: a pass sets those of its pixels with work items, and reads no others.
    this->GroupBegin.assign(this->PixelCount, 0);
    this->GroupEnd.assign(this->PixelCount, 0);
  }

  VolumeView<const double> shadingView(int patch) const
  {
    return VolumeView<const double>(
      this->Plan.shadingPool.data() + this->Plan.shadingOffsets[patch],
      this->Patches[patch].view().degree, kShadeChannels);
  }

  int valueCount(int patch) const
  {
    return this->Patches[patch].view().pointCount() * kScreenChannels;
  }

  template<class Pool>
  VolumeView<const double> nodeView(const Node& node, const Pool& pool) const
  {
    return VolumeView<const double>(
      pool.data() + node.coeff, this->Patches[node.patch].view().degree, kScreenChannels);
  }

  // ---- sweep and group ---------------------------------------------------------------------

  /// The sweep's (pixel, initial node) pairs per image row, as differences (addRowPairs).
  std::vector<uint64_t> rowPairDifferences() const
  {
    std::vector<uint64_t> differences(size_t(this->Config.height) + 1, 0);
    for (const Node& node : this->Plan.initialNodes)
    {
      addRowPairs(node.info.box, this->Plan.frame,
        [&](int row, uint64_t value) { differences[row] += value; });
    }
    return differences;
  }

  /// Per pixel of the pass, the initial nodes whose boxes cover it, sorted by nearest depth: the
  /// work items of SAG. Stored as one array with per-pixel offsets; the pixels that have any are
  /// listed.
  void sweepAndGroup()
  {
    // (pixel, initial node) pairs, grouped by pixel with the nodes in order.
    const Buffer<Node>& initial = this->Plan.initialNodes;
    Array<uint32_t> pairStart(initial.size() + 1, 0);
    for (size_t n = 0; n < initial.size(); ++n)
    {
      pairStart[n] = coveredPixelCount(initial[n].info.box, this->Plan.frame);
    }
    Array<Tuple> pairs(exclusiveScan(pairStart));
    parallelFor(initial.size(), this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        for (size_t n = begin; n < end; ++n)
        {
          size_t write = pairStart[n];
          forEachCoveredPixel(initial[n].info.box, this->Plan.frame,
            [&](size_t p) {
              pairs[write++] = { uint32_t(p), uint32_t(n) };
            });
        }
      });
    Array<uint32_t> runs;
    groupByPixel(pairs, this->PixelCount, runs);
    const size_t runCount = runs.size() - 1;
    this->ActivePixels.resize(runCount);
    Array<uint32_t>(pairs.size()).swap(this->Items); // this band's size, not an earlier one's
    parallelFor(runCount, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        for (size_t r = begin; r < end; ++r)
        {
          this->ActivePixels[r] = pairs[runs[r]].pixel;
          for (uint32_t k = runs[r]; k < runs[r + 1]; ++k)
          {
            this->Items[k] = pairs[k].node;
          }
          std::sort(this->Items.begin() + runs[r], this->Items.begin() + runs[r + 1],
            [&](uint32_t a, uint32_t b)
            {
              const double za = initial[a].info.box.lo[2], zb = initial[b].info.box.lo[2];
              return za < zb || (za == zb && a < b);
            });
        }
      });
    this->ItemOffsets.resize(this->PixelCount + 1);
    offsetsFromRuns(this->ActivePixels, runs, passFirstPixel(this->Plan.frame),
      passPixelCount(this->Plan.frame), this->Plan.threads, this->ItemOffsets);
    this->trackMemory(bytesOf(this->Items) + bytesOf(pairs));
  }

  // ---- shared subdivision trees ------------------------------------------------------------

  void sharedSubdivisionTrees()
  {
    // GroupBegin/GroupEnd hold each pixel's group of the round, empty for pixels without work;
    // only the pixels with work left are visited.
    Array<uint32_t> active = this->ActivePixels;
    for (uint32_t p : active)
    {
      this->GroupEnd[p] = this->ItemOffsets[p];
    }
    for (;;)
    {
      // Each round takes every pixel's next depth group (the SAG work sets).
      const Clock::time_point stage = Clock::now();
      std::atomic<size_t> total{ 0 };
      parallelFor(active.size(), this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          size_t local = 0;
          for (size_t k = begin; k < end; ++k)
          {
            const uint32_t p = active[k];
            this->GroupBegin[p] = this->GroupEnd[p];
            this->GroupEnd[p] =
              groupEnd(this->Plan.initialNodes.data(), this->Items.data(), this->GroupBegin[p],
                this->ItemOffsets[p + 1], this->BestDepth[p], this->Config.firstHitOnly);
            local += this->GroupEnd[p] - this->GroupBegin[p];
          }
          total += local;
        });
      // An empty group is final: no items are left, or they lie behind the best hit.
      active.erase(std::remove_if(active.begin(), active.end(),
                     [&](uint32_t p) { return this->GroupEnd[p] == this->GroupBegin[p]; }),
        active.end());
      this->Report.msSweepAndGroup += millisecondsSince(stage);
      if (total == 0)
      {
        break;
      }
      this->solveRound(active);
    }
  }

  /// The SST loop of the paper over one round (the groups in GroupBegin/GroupEnd of the pixels
  /// `active`): overlap (tuples of pixels and node boxes), solution, subdivision and
  /// compaction, until no tuple and no implicit node is left.
  void solveRound(const Array<uint32_t>& active)
  {
    const bool firstHit = this->Config.firstHitOnly;
    // This round's initial nodes, all implicit.
    Buffer<Node> nodes;
    Buffer<double> pool;
    {
      Array<uint8_t> present(this->Plan.initialNodes.size(), 0);
      for (uint32_t p : active)
      {
        for (uint32_t k = this->GroupBegin[p]; k < this->GroupEnd[p]; ++k)
        {
          present[this->Items[k]] = 1;
        }
      }
      for (size_t n = 0; n < this->Plan.initialNodes.size(); ++n)
      {
        if (present[n])
        {
          Node node = this->Plan.initialNodes[n];
          const double* src = this->Plan.initialPool.data() + node.coeff;
          node.coeff = pool.size();
          node.initial = uint32_t(n);
          node.implicit = true;
          pool.insert(pool.end(), src, src + this->valueCount(node.patch));
          nodes.push_back(node);
        }
      }
    }
    Array<Tuple> tuples;
    while (!nodes.empty())
    {
      ++this->Report.iterations;
      this->Report.maxPatches = std::max(this->Report.maxPatches, nodes.size());

      // Overlap stage: implicit nodes that are ready become tuples of the pixels whose centres
      // their boxes cover (members of the round, not behind a nearer hit), as many as the
      // memory budget takes; the others wait.
      Clock::time_point stage = Clock::now();
      Array<uint32_t> ready;
      uint64_t implicitNodes = 0, implicitValues = 0;
      for (size_t n = 0; n < nodes.size(); ++n)
      {
        if (nodes[n].implicit && readyForTuples(nodes[n], this->Plan.frame))
        {
          ready.push_back(uint32_t(n));
        }
        implicitNodes += nodes[n].implicit ? 1 : 0;
        implicitValues += nodes[n].implicit ? this->valueCount(nodes[n].patch) : 0;
      }
      Array<uint32_t> readyCounts(ready.size() + 1, 0);
      auto forCoveredPixels = [&](const Node& node, auto fn)
      {
        forEachCoveredPixel(node.info.box, this->Plan.frame,
          [&](size_t p)
          {
            if (roundTakesPixel(node, this->BestDepth[p], this->Items.data(), this->GroupBegin[p],
                  this->GroupEnd[p], this->Plan.frame))
            {
              fn(p);
            }
          });
      };
      parallelFor(ready.size(), this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          for (size_t k = begin; k < end; ++k)
          {
            forCoveredPixels(nodes[ready[k]], [&](size_t) { ++readyCounts[k]; });
          }
        });
      const size_t existing = tuples.size();
      exclusiveScan(readyCounts);
      // The room left once every implicit node could be carried over unsplit (a copy each).
      ready.resize(admittedNodes(ready.size(), this->Config.memoryBudgetBytes,
        loopBytes(this->Items.size(), nodes.size(), pool.size(), existing) +
          nodeBytes(implicitNodes, implicitValues),
        this->Items.size(), existing == 0, [&](size_t k) { return readyCounts[k + 1]; }));
      const size_t added = readyCounts[ready.size()];
      checkIndexable(existing + added);
      tuples.reserve(existing + added); // exactly: the memory model counts tuples, not capacity
      tuples.resize(existing + added);
      parallelFor(ready.size(), this->Plan.threads,
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
      parallelFor(ready.size(), this->Plan.threads,
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
      Array<uint32_t> runs;
      groupByPixel(tuples, this->PixelCount, runs);
      Array<uint8_t> outcome(tuples.size());
      Buffer<double> solution(tuples.size() * 4); // per tuple: u[3], ndc depth
      std::atomic<size_t> solves{ 0 };
      parallelFor(runs.size() - 1, this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          size_t local = 0;
          for (size_t run = begin; run < end; ++run)
          {
            const uint32_t first = runs[run], last = runs[run + 1];
            const uint32_t pixel = tuples[first].pixel;
            std::sort(tuples.begin() + first, tuples.begin() + last,
              [&](const Tuple& a, const Tuple& b)
              {
                const double za = nodes[a.node].info.box.lo[2], zb = nodes[b.node].info.box.lo[2];
                return za < zb || (za == zb && a.node < b.node);
              });
            uint32_t certified = 0;
            this->BestDepth[pixel] = solvePixelTuples(
              tuples.data(), first, last, pixel, nodes.data(),
              [&](const Node& node) { return this->nodeView(node, pool); }, this->BestDepth[pixel],
              this->Plan.frame, outcome.data(), solution.data(), certified);
            local += certified;
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
      parallelFor(tuples.size(), this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          for (size_t t = begin; t < end; ++t)
          {
            if (outcome[t] == Failed && firstHit &&
                nodes[tuples[t].node].info.box.lo[2] > this->BestDepth[tuples[t].pixel])
            {
              outcome[t] = Dropped; // a nearer hit was found this iteration
            }
          }
        });
      Array<uint8_t> split(nodes.size(), 0);
      Array<uint32_t> failed(nodes.size(), 0); // tuples per node
      for (size_t t = 0; t < tuples.size(); ++t)
      {
        if (outcome[t] == Failed)
        {
          split[tuples[t].node] = 1;
          ++failed[tuples[t].node];
        }
      }
      // Nodes to split, and the implicit nodes that may be carried over unsplit (those waiting
      // for the overlap stage, and those to split): the memory cap charges a copy of each.
      Array<uint32_t> toSplit;
      Array<uint8_t> carry(nodes.size(), 0); // implicit nodes for the next iteration, unsplit
      uint64_t carried = 0, carriedValues = 0;
      for (size_t n = 0; n < nodes.size(); ++n)
      {
        if (nodes[n].implicit && readyForTuples(nodes[n], this->Plan.frame))
        {
          carry[n] = 1; // waiting for room in the overlap stage
        }
        else if (nodes[n].implicit)
        {
          split[n] = coveredPixelCount(nodes[n].info.box, this->Plan.frame) > 0 ? 1 : 0;
        }
        if (split[n] && nodes[n].level >= this->Config.maxSubdivisionDepth)
        {
          split[n] = 2; // at the depth cap: its pixels stay unresolved
        }
        else if (split[n])
        {
          toSplit.push_back(uint32_t(n));
        }
        if (carry[n] || (nodes[n].implicit && split[n] == 1))
        {
          ++carried;
          carriedValues += this->valueCount(nodes[n].patch);
        }
      }
      // Memory cap: split as many nodes as the budget allows, in order; implicit nodes beyond
      // it become tuples in the next iteration instead, explicit ones leave their pixels
      // unresolved. The copies of implicit nodes carried over unsplit are charged first, as if
      // every implicit node were refused.
      const uint64_t budget = this->Config.memoryBudgetBytes;
      Array<size_t> poolOffset(toSplit.size() + 1, 0);  // doubles: past 2^32 with a large budget
      Array<uint64_t> splitCost(toSplit.size() + 1, 0); // running splitBytes
      for (size_t k = 0; k < toSplit.size(); ++k)
      {
        const int values = this->valueCount(nodes[toSplit[k]].patch);
        poolOffset[k + 1] = poolOffset[k] + 8 * values;
        splitCost[k + 1] = splitCost[k] + splitBytes(values, failed[toSplit[k]]);
      }
      const uint64_t carriedBytes = nodeBytes(carried, carriedValues);
      const uint64_t held =
        loopBytes(this->Items.size(), nodes.size(), pool.size(), tuples.size()) + carriedBytes;
      const size_t allowed = prefixWithin(toSplit.size(), held < budget ? budget - held : 0,
        [&](size_t k) { return splitCost[k + 1]; });
      for (size_t k = allowed; k < toSplit.size(); ++k)
      {
        Node& node = nodes[toSplit[k]];
        if (node.implicit)
        {
          node.overBudget = true; // ready for tuples next time
          carry[toSplit[k]] = 1;
          split[toSplit[k]] = 0;
        }
        else
        {
          split[toSplit[k]] = 3; // over budget
        }
      }
      toSplit.resize(allowed);
      poolOffset.resize(allowed + 1);
      Array<uint32_t> deferred; // the carried nodes, in order
      for (size_t n = 0; n < nodes.size(); ++n)
      {
        if (carry[n])
        {
          deferred.push_back(uint32_t(n));
        }
      }
      Buffer<double> childPool(poolOffset.back());
      Buffer<Node> children(toSplit.size() * 8);
      Array<uint8_t> keep(children.size(), 0);
      parallelFor(toSplit.size(), this->Plan.threads,
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
              child.info =
                analyzeNodeBounds(view, this->Config.isovalues[child.iso], this->Plan.frame.clip);
              keep[8 * k + c] = worthKeeping(child.info, this->Plan.frame) ? 1 : 0;
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
      this->Report.msSubdivision += millisecondsSince(stage);

      // Compaction: failed tuples move to the kept children covering their pixel; solved and
      // dropped tuples and unsplit explicit nodes leave.
      stage = Clock::now();
      Array<uint32_t> firstChild(nodes.size(), 0);
      for (size_t k = 0; k < toSplit.size(); ++k)
      {
        firstChild[toSplit[k]] = uint32_t(8 * k);
      }
      auto childCovers = [&](const Tuple& t, size_t c)
      {
        // Children of nodes in front of the eye are in front too (positive weights stay positive).
        return keep[c] &&
               mayHitPixel(children[c], t.pixel, this->BestDepth[t.pixel], this->Plan.frame);
      };
      Array<uint32_t> newOffsets(tuples.size() + 1, 0); // counts, then their exclusive scan
      parallelFor(tuples.size(), this->Plan.threads,
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
              newOffsets[t] += childCovers(tuples[t], c) ? 1 : 0;
            }
          }
        });
      exclusiveScan(newOffsets);
      // Memory cap on the tuples handed on: the tuples whose next ones pass it give them up.
      const size_t handedOn = prefixWithin(tuples.size(),
        nextTupleRoom(budget, held + childBytes(children.size(), childPool.size()),
          this->Items.size(), nodeBytes(children.size(), childPool.size()) + carriedBytes),
        [&](size_t t) { return newOffsets[t + 1]; });
      for (size_t t = 0; t < tuples.size(); ++t)
      {
        const bool givenUp = t >= handedOn && newOffsets[t + 1] > newOffsets[t];
        if ((outcome[t] == Failed && split[tuples[t].node] >= 2) || givenUp)
        {
          this->Unresolved[tuples[t].pixel] = 1;
          ++(split[tuples[t].node] == 2 ? this->Report.unresolvedAtDepthCap
                                        : this->Report.unresolvedAtBudget);
        }
      }
      Array<Tuple> next(newOffsets[handedOn]);
      parallelFor(handedOn, this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          for (size_t t = begin; t < end; ++t)
          {
            uint32_t write = newOffsets[t];
            const size_t base = firstChild[tuples[t].node];
            for (size_t c = base; newOffsets[t + 1] > write && c < base + 8; ++c)
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
      Array<uint8_t> used(children.size(), 0);
      for (const auto& t : next)
      {
        used[t.node] = 1;
      }
      // Which nodes and where their coefficients go, in order; the records are copied below.
      Array<uint32_t> newIndex(children.size(), 0), keptFrom;
      keptFrom.reserve(children.size() + deferred.size());
      Array<size_t> keptOffset(1, 0);
      keptOffset.reserve(children.size() + deferred.size() + 1);
      for (size_t c = 0; c < children.size(); ++c)
      {
        if (keep[c] && (children[c].implicit || used[c]))
        {
          newIndex[c] = uint32_t(keptFrom.size());
          keptFrom.push_back(uint32_t(c));
          keptOffset.push_back(keptOffset.back() + size_t(this->valueCount(children[c].patch)));
        }
      }
      const size_t fromChildren = keptFrom.size();
      for (size_t d = 0; d < deferred.size(); ++d)
      {
        keptFrom.push_back(uint32_t(d));
        keptOffset.push_back(
          keptOffset.back() + size_t(this->valueCount(nodes[deferred[d]].patch)));
      }
      Buffer<Node> kept(keptFrom.size());
      Buffer<double> keptPool(keptOffset.back());
      parallelFor(kept.size(), this->Plan.threads,
        [&](size_t begin, size_t end)
        {
          for (size_t n = begin; n < end; ++n)
          {
            kept[n] = n < fromChildren ? children[keptFrom[n]] : nodes[deferred[keptFrom[n]]];
            const size_t count = keptOffset[n + 1] - keptOffset[n];
            const Buffer<double>& source = n < fromChildren ? childPool : pool;
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
      // The iteration's peak: everything it made is alive.
      this->trackMemory(
        bytesOf(this->Items) + bytesOf(nodes) + bytesOf(pool) + bytesOf(tuples) + bytesOf(outcome) +
        bytesOf(solution) + bytesOf(runs) + bytesOf(split) + bytesOf(failed) + bytesOf(splitCost) +
        bytesOf(poolOffset) + bytesOf(toSplit) + bytesOf(carry) + bytesOf(deferred) +
        bytesOf(children) + bytesOf(childPool) + bytesOf(keep) + bytesOf(firstChild) +
        bytesOf(newOffsets) + bytesOf(next) + bytesOf(used) + bytesOf(newIndex) +
        bytesOf(keptFrom) + bytesOf(keptOffset) + bytesOf(kept) + bytesOf(keptPool));
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

  /// Per-pixel arrays, the copies of the input patches and the hits: what the memory budget
  /// does not cap.
  size_t fixedBytes() const
  {
    return bytesOf(this->ItemOffsets) + bytesOf(this->BestDepth) + bytesOf(this->Unresolved) +
           bytesOf(this->GroupBegin) + bytesOf(this->GroupEnd) + bytesOf(this->ActivePixels) +
           bytesOf(this->Plan.initialNodes) + bytesOf(this->Plan.initialPool) +
           bytesOf(this->Plan.shadingPool) + bytesOf(this->Hits);
  }

  /// Records a working set of `budgeted` bytes besides the fixed ones.
  void trackMemory(size_t budgeted)
  {
    this->Report.peakBudgetedBytes = std::max(this->Report.peakBudgetedBytes, budgeted);
    this->Report.peakBytes = std::max(this->Report.peakBytes, budgeted + this->fixedBytes());
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
    const size_t first = passFirstPixel(this->Plan.frame), count = passPixelCount(this->Plan.frame);
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
          double best = kInfinity;
          for (uint32_t item = this->ItemOffsets[p]; item < this->ItemOffsets[p + 1]; ++item)
          {
            const Node& initial = this->Plan.initialNodes[this->Items[item]];
            if (this->Config.firstHitOnly && initial.info.box.lo[2] > best)
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
              if (!boxCoversPixel(node.info.box, i, j) ||
                  (this->Config.firstHitOnly && node.info.box.lo[2] > best))
              {
                continue;
              }
              localSolves += node.info.certified ? 1 : 0;
              double u[3], ndc;
              const TupleOutcome result = solveTuple(this->nodeView(node, current), node.info, i, j,
                this->Config.isovalues[node.iso], this->Plan.frame.tolerance, u, ndc,
                this->Plan.frame.clip);
              if (result == TupleOutcome::Hit)
              {
                perPixel[k].push_back(rawHitOf(uint32_t(p), node, u, ndc));
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
                child.info = analyzeNode(this->nodeView(child, children),
                  this->Config.isovalues[child.iso], this->Plan.frame.clip);
                if (worthKeeping(child.info, this->Plan.frame))
                {
                  child.coeff = arena.size();
                  arena.insert(arena.end(), children.begin() + size_t(c) * count,
                    children.begin() + size_t(c + 1) * count);
                  stack.push_back(child);
                }
              }
              peak[k] = std::max(peak[k], bytesOf(arena) + bytesOf(stack) + bytesOf(children));
            }
          }
        }
        solves += localSolves;
        splits += localSplits;
      });
    this->Report.newtonSolves += solves;
    this->Report.subdividedPatches += splits;
    this->Report.unresolvedAtDepthCap += capped;
    for (auto& hits : perPixel)
    {
      this->Hits.insert(this->Hits.end(), hits.begin(), hits.end());
    }
    this->trackMemory(
      bytesOf(this->Items) +
      (count ? *std::max_element(peak.begin(), peak.end()) : 0) * size_t(this->Plan.threads));
    this->Report.msSolution += millisecondsSince(stage);
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
            child.info = analyzeNode(this->nodeView(child, nextPool),
              this->Config.isovalues[child.iso], this->Plan.frame.clip);
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
    const Clock::time_point stage = Clock::now();
    if (this->LeafOffsets.empty()) // the leaves serve every band
    {
      this->makeLeaves();
    }
    const std::vector<Node>& leaves = this->Leaves;
    const std::vector<double>& leafPool = this->LeafPool;
    const std::vector<uint32_t>& leafOffsets = this->LeafOffsets;
    this->trackMemory(bytesOf(this->Items) + bytesOf(leafPool) + bytesOf(leaves));
    const size_t first = passFirstPixel(this->Plan.frame), count = passPixelCount(this->Plan.frame);
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
                      this->Config.isovalues[leaf.iso], this->Plan.frame.tolerance, start, u, ndc,
                      this->Plan.frame.clip) == TupleOutcome::Hit)
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
    for (auto& hits : perPixel)
    {
      this->Hits.insert(this->Hits.end(), hits.begin(), hits.end());
    }
    this->Report.msSolution += millisecondsSince(stage);
  }

  // ---- G-buffer ----------------------------------------------------------------------------

  void fillGBuffer(GBuffer& out)
  {
    // Group by pixel, shade, sort front to back and merge duplicates.
    checkIndexable(this->Hits.size(), "hits");
    Array<uint32_t> runs;
    groupByPixel(this->Hits, this->PixelCount, runs);
    const size_t runCount = runs.size() - 1;
    ShadingView viewer{};
    for (int d = 0; d < 3; ++d)
    {
      viewer.eye[d] = this->TheView.eye[d];
      viewer.forward[d] = this->TheView.forward[d];
    }
    viewer.parallel = this->TheView.parallel;
    viewer.hasColor = this->Config.colorAttribute >= 0;
    Array<Hit> shaded(this->Hits.size());
    Array<uint32_t> keptCount(runCount + 1), runPixels(runCount);
    parallelFor(runCount, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        for (size_t r = begin; r < end; ++r)
        {
          runPixels[r] = this->Hits[runs[r]].pixel;
          for (uint32_t k = runs[r]; k < runs[r + 1]; ++k)
          {
            const RawHit& raw = this->Hits[k];
            shaded[k] = shadeHit(this->shadingView(raw.patch), raw, viewer);
          }
          keptCount[r] =
            uint32_t(mergePixelHits(shaded.data() + runs[r], int(runs[r + 1] - runs[r]),
              this->TheView.pixelFootprint, viewer.parallel, this->Config.firstHitOnly));
        }
      });
    out.width = this->Config.width;
    out.height = this->Config.height;
    out.hits.resize(exclusiveScan(keptCount)); // now where each run's kept hits go
    out.offsets.resize(this->PixelCount + 1);
    offsetsFromRuns(runPixels, keptCount, 0, this->PixelCount, this->Plan.threads, out.offsets);
    parallelFor(runCount, this->Plan.threads,
      [&](size_t begin, size_t end)
      {
        for (size_t r = begin; r < end; ++r)
        {
          std::copy(shaded.begin() + runs[r],
            shaded.begin() + runs[r] + (keptCount[r + 1] - keptCount[r]),
            out.hits.begin() + keptCount[r]);
        }
      });
  }

  const std::vector<BezierVolume<double>>& Patches;
  const View& TheView;
  const Settings& Config;
  FrameReport& Report;
  FramePlan Plan;
  size_t PixelCount = 0;
  std::vector<Node> Leaves; ///< brute force
  std::vector<double> LeafPool;
  std::vector<uint32_t> LeafOffsets;
  Array<uint32_t> ItemOffsets;
  Array<uint32_t> Items;
  Array<double> BestDepth;
  Array<uint8_t> Unresolved;
  Array<RawHit> Hits;
  Array<uint32_t> ActivePixels;         ///< pixels with work items
  Array<uint32_t> GroupBegin, GroupEnd; ///< this round's work items per pixel
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
  if (method == Method::SharedSubdivisionTree && wanted != Backend::Cpu)
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
      }
    }
    else
    {
      report.notice =
        (wanted == Backend::Cuda ? "CUDA asked for, but " : "") + why + ": drawing on CPU threads";
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

bool triesGpu(Backend backend)
{
  const Backend wanted = requestedBackend(backend);
  std::string why;
  return wanted == Backend::Cuda || (wanted == Backend::Automatic && cuda::usable(why));
}

FrameReport render(const std::vector<BezierVolume<double>>& patches, const View& view,
  const Settings& settings, Method method, GBuffer& out)
{
  return dispatch(
    settings, method,
    [&](FrameReport& report) { cuda::render(patches, view, settings, out, report); },
    [&](FrameReport& report) { Renderer(patches, view, settings, report).run(method, out); });
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
    [&](FrameReport& report) { cuda::renderNurbs(volumes, view, settings, out, report); },
    [&](FrameReport& report)
    {
      const auto patches = extractElements(volumes);
      Renderer(patches, view, settings, report).run(method, out);
    });
}

FrameReport render(const std::vector<BezierVolume<double>>& patches, const Camera& camera,
  const Settings& settings, Method method, GBuffer& out)
{
  return render(patches, makeView(camera, settings.width, settings.height), settings, method, out);
}

} // namespace sst
} // namespace iga
