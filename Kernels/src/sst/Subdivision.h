// Stage 4, subdivision: the nodes some pixel failed on, and the implicit ones whose boxes still
// cover pixels, are split at the midpoint of the directions splitAxes picks (up to 8 ways for a
// volume, 4 for a surface), as many as the
// memory budget allows (in order); children without a sign change, off screen or outside the clip
// depth are not kept. Implicit nodes beyond the budget are carried over to become tuples, explicit
// ones leave their pixels unresolved. Also appends the solution stage's hits, whose count is read
// back here.
#pragma once

#include "sst/LoopState.h"
#include "sst/Solution.h"

namespace iga
{
namespace sst
{

/// Child c of a split node, its coefficients already at childPool + `coeff`: placed and
/// analysed in its slot k (the parent's analysis is not copied), and whether it is kept.
/// Explicit children are analysed further once they receive pixels.
IGA_HD inline void finishChild(const Node& parent, int c, size_t coeff, const double* childPool,
  const PatchShape* shapes, const FrameConstants& frame, size_t k, Node* children, uint8_t* keep,
  unsigned int* firstTuple)
{
  Node& child = children[k];
  static_cast<NodePlace&>(child) = parent;
  halvePlace(child, parent.axes, c);
  child.coeff = coeff;
  const auto view = viewOf(child, childPool, shapes);
  analyzeNodeBounds(view, isovalueOf(child, frame), frame.clip, child.info);
  keep[k] = worthKeeping(child.info, frame) ? 1 : 0;
  firstTuple[k] = ~0u;
  if (child.implicit && keep[k])
  {
    analyzeNodeSolver(view, child.info);
  }
}

/// A child slot past a split node's childCount: never kept.
IGA_HD inline void emptySlot(size_t k, uint8_t* keep, unsigned int* firstTuple)
{
  keep[k] = 0;
  firstTuple[k] = ~0u;
}

/// Which nodes to split (SplitFlags, SplitIndex, ToSplit, Deferred), the cap on them, and the
/// new hits; returns how many nodes are split. Totals[4] keeps what the iteration holds for the
/// compaction's cap, ChildValues where each split node's children go.
template<class Exec>
size_t chooseSplits(LoopState<Exec>& s)
{
  const size_t nodeCount = s.NodeCount, tupleCount = s.TupleCount;
  Node* nodes = raw(s.Nodes);
  const double* pool = raw(s.Pool);
  const PatchShape* shapes = s.shapes;
  const FrameConstants frame = s.frame;
  const Tuple* tuples = raw(s.Tuples);
  uint8_t* outcome = raw(s.Outcomes);
  const double* best = raw(s.BestDepth);
  const uint32_t* hitIndex = raw(s.HitIndex);
  uint64_t* totals = raw(s.Totals);
  uint8_t* split = sized(s.SplitFlags, nodeCount);
  s.exec.fill(split, nodeCount, uint8_t(Keep));
  unsigned long long* failed = sized(s.FailedTuples, nodeCount); // per node
  s.exec.fill(failed, nodeCount, 0ull);
  s.exec.forEach(tupleCount,
    [=] IGA_HD(size_t t)
    {
      if (outcome[t] == Failed &&
          !frame.hits.mayMatter(nodes[tuples[t].node].info.box.lo[2], best[tuples[t].pixel]))
      {
        outcome[t] = Dropped; // a nearer hit was found this iteration
      }
      if (outcome[t] == Failed)
      {
        storeShared(&split[tuples[t].node], Split);
        addAtomically(&failed[tuples[t].node], 1);
      }
    });
  // Per node in order: whether it is to be split, and the running totals of split nodes, of
  // their children's coefficients and of what splitting adds (splitBytes); the bytes of the
  // implicit nodes that may be carried over unsplit (those waiting for the overlap stage, and
  // those to split).
  uint32_t* splitIndex = sized(s.SplitIndex, nodeCount + 1);
  uint64_t* childValues = sized(s.ChildValues, nodeCount + 1);
  uint64_t* splitCost = sized(s.SplitCost, nodeCount + 1);
  uint64_t* carriedBytes = sized(s.NodeBytes, nodeCount + 1);
  s.exec.forEach(
    nodeCount,
    [=] IGA_HD(size_t n)
    {
      const bool waiting = nodes[n].implicit && readyForTuples(nodes[n], frame);
      if (nodes[n].implicit && !waiting)
      {
        split[n] = coveredPixelCount(nodes[n].info.box, frame) > 0 ? Split : Keep;
      }
      nodes[n].axes = split[n] == Split
                        ? uint8_t(splitAxes(viewOf(nodes[n], pool, shapes)) &
                                  ~axesAtDepthCap(nodes[n], frame.maxSubdivisionDepth))
                        : uint8_t(0);
      if (split[n] == Split && nodes[n].axes == 0)
      {
        split[n] = AtDepthCap; // its pixels stay unresolved
      }
      const bool splits = split[n] == Split;
      const int values = shapes[nodes[n].patch].screenValues;
      const int children = childCount(nodes[n].axes);
      splitIndex[n] = splits ? 1 : 0;
      childValues[n] = splits ? uint64_t(children) * values : 0;
      splitCost[n] = splits ? splitBytes(values, children, failed[n]) : 0;
      carriedBytes[n] = nodes[n].implicit && (waiting || splits) ? nodeBytes(1, values) : 0;
    },
    kGrainNode); // splitAxes reads the node's coefficients
  s.exec.scan(splitIndex, nodeCount);
  s.exec.scan(childValues, nodeCount);
  s.exec.scan(splitCost, nodeCount);
  s.exec.scan(carriedBytes, nodeCount);
  // The memory cap: the nodes before the first whose split would pass it, the copies of the
  // implicit nodes carried over charged first, as if every implicit node were refused.
  const uint64_t held = loopBytes(s.ItemNodes.size(), nodeCount, s.Pool.size(), tupleCount);
  const uint64_t budget = s.budget;
  s.exec.forEach(1,
    [=] IGA_HD(size_t)
    {
      const uint64_t charged = held + carriedBytes[nodeCount];
      const size_t allowed = prefixWithin(nodeCount, charged < budget ? budget - charged : 0,
        [=](size_t n) { return splitCost[n + 1]; });
      totals[0] = splitIndex[allowed]; // nodes split
      totals[1] = childValues[allowed];
      totals[2] = hitIndex[tupleCount];
      totals[3] = allowed;
      totals[4] = charged; // for the compaction's cap
    });
  uint32_t* toSplit = sized(s.ToSplit, nodeCount);
  uint8_t* deferred = sized(s.Deferred, nodeCount);
  s.exec.forEach(nodeCount,
    [=] IGA_HD(size_t n)
    {
      deferred[n] = nodes[n].implicit && readyForTuples(nodes[n], frame) ? 1 : 0; // waiting
      if (split[n] != Split)
      {
        return;
      }
      if (n < totals[3])
      {
        toSplit[splitIndex[n]] = uint32_t(n);
      }
      else if (nodes[n].implicit)
      {
        nodes[n].overBudget = true; // ready for tuples next time
        deferred[n] = 1;
        split[n] = Keep;
      }
      else
      {
        split[n] = OverBudget;
      }
    });
  uint64_t read[3];
  s.exec.read(totals, 3, read);
  appendHits(s, size_t(read[2]));
  s.ChildPool.resize(size_t(read[1]));
  return size_t(read[0]);
}

/// Splits the chosen nodes into Children, kChildSlots each (coefficients in ChildPool),
/// KeepFlags saying which are kept: the slots past a node's childCount never are.
template<class Exec>
void splitNodes(LoopState<Exec>& s, size_t allowed)
{
  const size_t slots = kChildSlots * allowed;
  checkIndexable(slots + s.NodeCount, "nodes"); // gatherNodes indexes them
  const Node* nodes = raw(s.Nodes);
  const double* pool = raw(s.Pool);
  const PatchShape* shapes = s.shapes;
  const FrameConstants frame = s.frame;
  const uint32_t* toSplit = raw(s.ToSplit);
  const uint64_t* childValues = raw(s.ChildValues);
  double* childPool = raw(s.ChildPool);
  Node* children = sized(s.Children, slots);
  uint8_t* keep = sized(s.KeepFlags, slots);
  // The first tuple that moves to each child (the compaction's cap may stop those after it).
  unsigned int* firstTuple = sized(s.FirstTuple, slots);
  auto coeffOf = [=] IGA_HD(uint32_t n, int c)
  { return childValues[n] + size_t(c) * shapes[nodes[n].patch].screenValues; };
  if constexpr (Exec::kThreadPerChild)
  {
    s.exec.forEach(slots,
      [=] IGA_HD(size_t k)
      {
        const uint32_t n = toSplit[k / kChildSlots];
        const int c = int(k % kChildSlots);
        const auto parent = viewOf(nodes[n], pool, shapes);
        if (c >= childCount(nodes[n].axes))
        {
          emptySlot(k, keep, firstTuple);
          return;
        }
        nodeChild(parent, nodes[n].axes, c, childPool + coeffOf(n, c));
        finishChild(
          nodes[n], c, coeffOf(n, c), childPool, shapes, frame, k, children, keep, firstTuple);
      });
  }
  else
  {
    s.exec.forEach(
      allowed,
      [=] IGA_HD(size_t k)
      {
        const uint32_t n = toSplit[k];
        const auto parent = viewOf(nodes[n], pool, shapes);
        splitNode(parent, nodes[n].axes, childPool + childValues[n]);
        for (int c = 0; c < kChildSlots; ++c)
        {
          c < childCount(nodes[n].axes) ? finishChild(nodes[n], c, coeffOf(n, c), childPool, shapes,
                                            frame, kChildSlots * k + c, children, keep, firstTuple)
                                        : emptySlot(kChildSlots * k + c, keep, firstTuple);
        }
      },
      kGrainSplit);
  }
  s.report->subdividedPatches += allowed;
  trackMemory(s);
}

} // namespace sst
} // namespace iga
