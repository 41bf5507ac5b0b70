// Stage 3, solution: exclusions, and Newton where a node certifies a unique root. Each pixel's
// tuples are solved in order of nearest depth by one thread, so that a hit drops the tuples
// behind it that can no longer matter (the hit policy) in the same iteration. The thread of a
// pixel's first tuple takes its run: a thread per pixel of the image cost more than the
// solutions in sparse frames on a GPU, whose register use lets few mostly idle threads run.
#pragma once

#include "sst/LoopState.h"

namespace iga
{
namespace sst
{

template<class Exec>
void solutionStage(LoopState<Exec>& s)
{
  const size_t tupleCount = s.TupleCount;
  const Node* nodes = raw(s.Nodes);
  const double* pool = raw(s.Pool);
  const PatchShape* shapes = s.shapes;
  const FrameConstants frame = s.frame;
  Tuple* tuples = raw(s.Tuples);
  s.exec.sortByPixelThenDepth(tuples, tupleCount, nodes, s.pixelCount);
  uint8_t* outcome = sized(s.Outcomes, tupleCount);
  double* solution = sized(s.Solution, 4 * tupleCount);
  uint32_t* hitIndex = sized(s.HitIndex, tupleCount + 1);
  double* bestDepth = raw(s.BestDepth);
  uint32_t* certified = raw(s.PixelSolves);
  unsigned long long* tallies = raw(s.Tallies);
  s.exec.template forEachCounting<NewtonWork>(
    tupleCount,
    [=] IGA_HD(size_t first, NewtonWork & newton)
    {
      const uint32_t pixel = tuples[first].pixel;
      if (first > 0 && tuples[first - 1].pixel == pixel)
      {
        return;
      }
      size_t end = first + 1;
      while (end < tupleCount && tuples[end].pixel == pixel)
      {
        ++end;
      }
      bestDepth[pixel] = solvePixelTuples(
        tuples, uint32_t(first), uint32_t(end), pixel, nodes,
        [=](const Node& node) { return viewOf(node, pool, shapes); }, bestDepth[pixel], frame,
        outcome, solution, certified[pixel], newton);
      for (size_t t = first; t < end; ++t)
      {
        hitIndex[t] = outcome[t] == Solved ? 1 : 0;
      }
    },
    [=] IGA_HD(const NewtonWork& newton)
    {
      if (newton.runs > 0)
      {
        addAtomically(&tallies[NewtonRuns], newton.runs);
        addAtomically(&tallies[NewtonEvaluations], newton.evaluations);
      }
    },
    kGrainPixel);
  s.exec.scan(hitIndex, tupleCount);
}

/// Appends the solution stage's hits (`newHits` of them, read back with the subdivision's
/// totals) to the frame's hits, in tuple order.
template<class Exec>
void appendHits(LoopState<Exec>& s, size_t newHits)
{
  checkIndexable(s.HitCount + newHits, "hits");
  s.Hits.resize(s.HitCount + newHits);
  RawHit* hits = raw(s.Hits) + s.HitCount;
  const Tuple* tuples = raw(s.Tuples);
  const Node* nodes = raw(s.Nodes);
  const uint8_t* outcome = raw(s.Outcomes);
  const double* solution = raw(s.Solution);
  const uint32_t* hitIndex = raw(s.HitIndex);
  s.exec.forEach(s.TupleCount,
    [=] IGA_HD(size_t t)
    {
      if (outcome[t] == Solved)
      {
        hits[hitIndex[t]] =
          rawHitOf(tuples[t].pixel, nodes[tuples[t].node], &solution[4 * t], solution[4 * t + 3]);
      }
    });
  s.HitCount += newHits;
}

} // namespace sst
} // namespace iga
