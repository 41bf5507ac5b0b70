// Stage 5, compaction: failed tuples move to the kept children covering their pixel (as many as
// the memory budget hands on); solved and dropped tuples and unsplit explicit nodes leave. The
// next node list is the implicit children kept, the explicit children that received pixels and
// the implicit nodes carried over, stored contiguously. Also the gathering of a round's
// initial nodes, which is the same node compaction.
#pragma once

#include "sst/LoopState.h"

namespace iga
{
namespace sst
{

/// Gathers the nodes flagged in `take` (with their coefficients) into Nodes and Pool, in order,
/// followed by the flagged nodes of a second source; Index holds the new index of each. Returns
/// the node count. `alsoRead`, when given, is a value of the execution's memory read back in
/// the same wait as the count, into `alsoReadValue`. `asRound`: the nodes start a round, all
/// implicit.
template<class Exec>
size_t gatherNodes(LoopState<Exec>& s, const Node* first, const double* firstPool,
  const uint8_t* firstTake, size_t firstCount, const Node* second, const double* secondPool,
  const uint8_t* secondTake, size_t secondCount, bool asRound, const uint64_t* alsoRead = nullptr,
  size_t* alsoReadValue = nullptr)
{
  const size_t count = firstCount + secondCount;
  const PatchShape* shapes = s.shapes;
  uint32_t* index = sized(s.Index, count + 1);
  uint64_t* offsets = sized(s.Offsets, count + 1);
  s.exec.forEach(count,
    [=] IGA_HD(size_t n)
    {
      const bool fromFirst = n < firstCount;
      const bool take = fromFirst ? firstTake[n] : secondTake[n - firstCount];
      const Node& node = fromFirst ? first[n] : second[n - firstCount];
      index[n] = take ? 1 : 0;
      offsets[n] = take ? uint64_t(shapes[node.patch].screenValues) : 0;
    });
  s.exec.scan(index, count);
  s.exec.scan(offsets, count);
  uint64_t* totals = raw(s.Totals);
  s.exec.forEach(1,
    [=] IGA_HD(size_t)
    {
      totals[0] = index[count];
      totals[1] = offsets[count];
      totals[2] = alsoRead ? *alsoRead : 0;
    });
  uint64_t read[3];
  s.exec.read(totals, 3, read);
  const size_t kept = size_t(read[0]), values = size_t(read[1]);
  if (alsoReadValue)
  {
    *alsoReadValue = size_t(read[2]);
  }
  Node* nodes = sized(s.NextNodes, kept);
  double* pool = sized(s.NextPool, values);
  s.exec.forEach(
    count,
    [=] IGA_HD(size_t n)
    {
      const bool fromFirst = n < firstCount;
      if (!(fromFirst ? firstTake[n] : secondTake[n - firstCount]))
      {
        return;
      }
      Node& node = nodes[index[n]];
      node = fromFirst ? first[n] : second[n - firstCount];
      const double* source = (fromFirst ? firstPool : secondPool) + node.coeff;
      const int valueCount = shapes[node.patch].screenValues;
      for (int v = 0; v < valueCount; ++v)
      {
        pool[offsets[n] + v] = source[v];
      }
      node.coeff = offsets[n];
      if (asRound)
      {
        node.initial = uint32_t(n);
        node.implicit = true;
      }
      // Explicit children are analysed once they are known to receive pixels, roots once a
      // round takes them (most roots of a first-hit frame never are: they lie behind nearer
      // hits).
      if (asRound || (fromFirst && !node.implicit))
      {
        const auto view = viewOf(node, pool, shapes);
        analyzeNodeSolver(view, node.info);
        analyzeNodeCentre(view, node.info);
      }
    },
    kGrainNode);
  s.Nodes.swap(s.NextNodes);
  s.Pool.swap(s.NextPool);
  return kept;
}

template<class Exec>
void compactionStage(LoopState<Exec>& s, size_t allowed)
{
  const size_t nodeCount = s.NodeCount, tupleCount = s.TupleCount;
  const FrameConstants frame = s.frame;
  const Tuple* tuples = raw(s.Tuples);
  const uint8_t* outcome = raw(s.Outcomes);
  const uint8_t* split = raw(s.SplitFlags);
  const uint32_t* splitIndex = raw(s.SplitIndex);
  const Node* children = raw(s.Children);
  const uint8_t* keep = raw(s.KeepFlags);
  unsigned int* firstTuple = raw(s.FirstTuple);
  const double* best = raw(s.BestDepth);
  uint8_t* unresolved = raw(s.Unresolved);
  unsigned long long* tallies = raw(s.Tallies);
  uint64_t* totals = raw(s.Totals);
  // The children each failed tuple moves to, and how many; a child is used when it receives a
  // tuple.
  uint64_t* newCounts = sized(s.Counts, tupleCount + 1);
  uint8_t* childMasks = sized(s.ChildMasks, tupleCount);
  static_assert(kChildSlots <= 8, "a child mask has a bit per slot");
  s.exec.forEach(tupleCount,
    [=] IGA_HD(size_t t)
    {
      uint32_t count = 0, mask = 0;
      const uint8_t state = split[tuples[t].node];
      if (outcome[t] == Failed && state == Split)
      {
        const size_t first = kChildSlots * size_t(splitIndex[tuples[t].node]);
        for (int c = 0; c < kChildSlots; ++c)
        {
          const Node& child = children[first + size_t(c)];
          if (keep[first + size_t(c)] &&
              mayHitPixel(child, tuples[t].pixel, best[tuples[t].pixel], frame))
          {
            ++count;
            mask |= 1u << c;
            lowerAtomically(&firstTuple[first + size_t(c)], unsigned(t));
          }
        }
      }
      else if (outcome[t] == Failed && state >= AtDepthCap)
      {
        storeShared(&unresolved[tuples[t].pixel], 1);
        addAtomically(&tallies[state == AtDepthCap ? TuplesAtDepthCap : TuplesOverBudget], 1);
      }
      newCounts[t] = count;
      childMasks[t] = uint8_t(mask);
    });
  s.exec.scan(newCounts, tupleCount);
  // The memory cap on the tuples handed on: the tuples whose next ones pass it give them up.
  const uint64_t itemCount = s.ItemNodes.size(), childCount = kChildSlots * allowed;
  const uint64_t childValueCount = s.ChildPool.size();
  const uint64_t budget = s.budget;
  const uint64_t* carriedBytes = raw(s.NodeBytes);
  s.exec.forEach(1,
    [=] IGA_HD(size_t)
    {
      const uint64_t charged = totals[4], carried = carriedBytes[nodeCount];
      const size_t handedOn = prefixWithin(tupleCount,
        nextTupleRoom(budget, charged + childBytes(childCount, childValueCount), itemCount,
          nodeBytes(childCount, childValueCount) + carried),
        [=](size_t t) { return newCounts[t + 1]; });
      totals[4] = handedOn;
      totals[5] = newCounts[handedOn];
    });
  uint8_t* used = sized(s.Used, childCount);
  s.exec.forEach(childCount, [=] IGA_HD(size_t c)
    { used[c] = keep[c] && (children[c].implicit || firstTuple[c] < totals[4]) ? 1 : 0; });
  size_t nextCount = 0;
  s.NodeCount = gatherNodes(s, children, raw(s.ChildPool), used, childCount, raw(s.Nodes),
    raw(s.Pool), raw(s.Deferred), nodeCount, false, totals + 5, &nextCount);
  checkIndexable(nextCount);
  const uint32_t* newIndex = raw(s.Index);
  Tuple* next = sized(s.Next, nextCount);
  trackMemory(s); // the iteration's peak: the old and the new nodes and tuples
  s.exec.forEach(tupleCount,
    [=] IGA_HD(size_t t)
    {
      size_t write = newCounts[t];
      if (newCounts[t + 1] == write)
      {
        return;
      }
      if (t >= totals[4]) // given up at the cap
      {
        storeShared(&unresolved[tuples[t].pixel], 1);
        addAtomically(&tallies[TuplesOverBudget], 1);
        return;
      }
      const size_t first = kChildSlots * size_t(splitIndex[tuples[t].node]);
      for (int c = 0; c < kChildSlots; ++c)
      {
        if (childMasks[t] & (1u << c))
        {
          next[write++] = { tuples[t].pixel, newIndex[first + size_t(c)] };
        }
      }
    });
  s.Tuples.swap(s.Next);
  s.TupleCount = nextCount;
}

} // namespace sst
} // namespace iga
