// Stage 1, sweep and group (SAG): per pixel of the pass, the initial nodes whose boxes cover
// it, sorted by nearest depth (its work items); then round by round each pixel's next group of
// them, as the hit policy takes them. Also the bands of rows a frame is drawn in.
#pragma once

#include "sst/LoopState.h"

#include <vector>

namespace iga
{
namespace sst
{

/// The bands of rows the frame is drawn in (rowBands), from the sweep's pairs per row.
template<class Exec>
std::vector<int> frameBands(LoopState<Exec>& s, const Settings& settings)
{
  const Node* nodes = s.initialNodes;
  const FrameConstants frame = s.frame;
  const size_t rows = size_t(frame.height) + 1;
  unsigned long long* differences = sized(s.RowPairs, rows);
  s.exec.fill(differences, rows, 0ull);
  s.exec.forEach(s.initialCount,
    [=] IGA_HD(size_t n)
    {
      addRowPairs(nodes[n].info.box, frame,
        [=](int row, uint64_t value) { addAtomically(differences + row, value); });
    });
  std::vector<unsigned long long> read(rows);
  s.exec.read(differences, rows, read.data());
  return rowBands(std::vector<uint64_t>(read.begin(), read.end()).data(), settings);
}

/// The pass's work items: (pixel, initial node) pairs sorted by pixel and nearest depth, their
/// per-pixel offsets, and the pixels that have any (Active), each with an empty group and no
/// Newton solves yet.
template<class Exec>
void sweepAndGroup(LoopState<Exec>& s)
{
  const size_t nodeCount = s.initialCount;
  const Node* nodes = s.initialNodes;
  const FrameConstants frame = s.frame;
  uint64_t* counts = sized(s.Counts, nodeCount + 1);
  s.exec.forEach(
    nodeCount, [=] IGA_HD(size_t n) { counts[n] = coveredPixelCount(nodes[n].info.box, frame); });
  const size_t total = scanCounts(s.exec, s.Counts, nodeCount);
  Tuple* items = sized(s.Items, total);
  s.exec.forEachCoveredPixel(
    counts, nodeCount, total, frame, [=] IGA_HD(size_t n) { return nodes[n].info.box; },
    [=] IGA_HD(uint32_t n, size_t k, size_t p) {
      items[k] = { uint32_t(p), n };
    });
  s.exec.sortByPixelThenDepth(items, total, nodes, s.pixelCount);
  uint32_t* itemNodes = sized(s.ItemNodes, total);
  s.exec.forEach(total, [=] IGA_HD(size_t k) { itemNodes[k] = items[k].node; });
  // Runs of items by pixel: the pixels with work and where their items start.
  uint32_t* runStarts = sized(s.Index, total + 1);
  const size_t runCount = pixelRuns(s.exec, items, total, runStarts);
  uint32_t* active = sized(s.Active, runCount);
  s.exec.forEach(runCount, [=] IGA_HD(size_t r) { active[r] = items[runStarts[r]].pixel; });
  uint32_t* offsets = raw(s.ItemOffsets);
  s.exec.offsetsFromRuns(
    active, runStarts, runCount, passFirstPixel(frame), passPixelCount(frame), offsets);
  uint32_t* begin = raw(s.GroupBegin);
  uint32_t* end = raw(s.GroupEnd);
  uint32_t* solves = raw(s.PixelSolves);
  s.exec.forEach(runCount,
    [=] IGA_HD(size_t r)
    {
      begin[active[r]] = offsets[active[r]];
      end[active[r]] = offsets[active[r]];
      solves[active[r]] = 0;
    });
  s.Index.resize(0);
  trackMemory(s);
}

/// Moves every active pixel to its next group of work items (groupEnd) and drops the pixels
/// whose group is empty: they are finished. Returns the work items of the round.
template<class Exec>
size_t nextGroups(LoopState<Exec>& s)
{
  const Node* initial = s.initialNodes;
  const uint32_t* items = raw(s.ItemNodes);
  const uint32_t* offsets = raw(s.ItemOffsets);
  const double* best = raw(s.BestDepth);
  uint32_t* begin = raw(s.GroupBegin);
  uint32_t* end = raw(s.GroupEnd);
  const uint32_t* active = raw(s.Active);
  const HitPolicy policy = s.frame.hits;
  const size_t activeCount = s.Active.size();
  s.exec.forEach(activeCount,
    [=] IGA_HD(size_t k)
    {
      const uint32_t p = active[k];
      begin[p] = end[p];
      end[p] = groupEnd(initial, items, begin[p], offsets[p + 1], best[p], policy);
    });
  const size_t total =
    s.exec.sum(activeCount, [=] IGA_HD(size_t k) { return end[active[k]] - begin[active[k]]; });
  uint32_t* next = sized(s.NextActive, activeCount);
  s.NextActive.resize(s.exec.select(
    activeCount, [=] IGA_HD(size_t k) { return end[active[k]] > begin[active[k]]; },
    [=] IGA_HD(size_t k) { return active[k]; }, next));
  s.Active.swap(s.NextActive);
  return total;
}

} // namespace sst
} // namespace iga
