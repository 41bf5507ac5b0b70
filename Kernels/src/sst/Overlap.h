// Stage 2, overlap: implicit nodes that are ready become (pixel, node) tuples of the pixels
// whose centres their boxes cover (members of the round that the node may matter to), as many
// as the memory budget takes; the others wait, implicit.
#pragma once

#include "sst/LoopState.h"

namespace iga
{
namespace sst
{

template<class Exec>
void overlapStage(LoopState<Exec>& s)
{
  const size_t nodeCount = s.NodeCount;
  Node* nodes = raw(s.Nodes);
  const double* pool = raw(s.Pool);
  const PatchShape* shapes = s.shapes;
  const FrameConstants frame = s.frame;
  const uint32_t* items = raw(s.ItemNodes);
  const uint32_t* begin = raw(s.GroupBegin);
  const uint32_t* end = raw(s.GroupEnd);
  const double* best = raw(s.BestDepth);
  uint64_t* totals = raw(s.Totals);
  // Candidates: the covered pixels of the ready nodes; those the round takes become tuples, in
  // node and row order. Each implicit node's bytes are summed too: the budget keeps room to
  // carry every one over unsplit.
  uint64_t* counts = sized(s.Counts, nodeCount + 1);
  uint64_t* implicitBytes = sized(s.NodeBytes, nodeCount + 1);
  s.exec.forEach(nodeCount,
    [=] IGA_HD(size_t n)
    {
      counts[n] = nodes[n].implicit && readyForTuples(nodes[n], frame)
                    ? coveredPixelCount(nodes[n].info.box, frame)
                    : 0;
      implicitBytes[n] = nodes[n].implicit ? nodeBytes(1, shapes[nodes[n].patch].screenValues) : 0;
    });
  s.exec.scan(implicitBytes, nodeCount);
  const size_t candidates = scanCounts(s.exec, s.Counts, nodeCount);
  uint32_t* taken = sized(s.Taken, candidates + 1);
  auto boxOf = [=] IGA_HD(size_t n) { return nodes[n].info.box; };
  s.exec.forEachCoveredPixel(counts, nodeCount, candidates, frame, boxOf,
    [=] IGA_HD(uint32_t n, size_t k, size_t p)
    { taken[k] = roundTakesPixel(nodes[n], p, best[p], items, begin[p], end[p], frame) ? 1 : 0; });
  s.exec.scan(taken, candidates);
  const uint64_t itemCount = s.ItemNodes.size();
  const uint64_t held = loopBytes(itemCount, nodeCount, s.Pool.size(), s.TupleCount);
  const uint64_t budget = s.budget;
  const bool noTuples = s.TupleCount == 0;
  s.exec.forEach(1,
    [=] IGA_HD(size_t)
    {
      const size_t admitted = admittedNodes(nodeCount, budget, held + implicitBytes[nodeCount],
        itemCount, noTuples, [=](size_t n) { return taken[counts[n + 1]]; });
      totals[0] = admitted;
      totals[1] = taken[counts[admitted]];
    });
  uint64_t read[2];
  s.exec.read(totals, 2, read);
  const size_t admitted = size_t(read[0]), added = size_t(read[1]);
  checkIndexable(s.TupleCount + added);
  s.Tuples.resize(s.TupleCount + added);
  Tuple* tuples = raw(s.Tuples) + s.TupleCount;
  s.exec.forEachCoveredPixel(counts, nodeCount, candidates, frame, boxOf,
    [=] IGA_HD(uint32_t n, size_t k, size_t p)
    {
      if (taken[k + 1] != taken[k] && taken[k] < added)
      {
        tuples[taken[k]] = { uint32_t(p), n };
      }
    });
  s.exec.forEach(
    admitted,
    [=] IGA_HD(size_t n)
    {
      Node& node = nodes[n];
      if (node.implicit && readyForTuples(node, frame))
      {
        node.implicit = false;
        analyzeNodeCentre(viewOf(node, pool, shapes), node.info);
      }
    },
    kGrainNode);
  s.TupleCount += added;
  s.Taken.resize(0); // scratch: out of the working set
  s.report->maxTuples = std::max(s.report->maxTuples, s.TupleCount);
}

} // namespace sst
} // namespace iga
