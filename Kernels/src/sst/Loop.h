// The shared-subdivision-tree loop of the paper, once for both drivers: per band of rows the
// sweep, then round by round the SAG groups, each solved by iterations of overlap, solution,
// subdivision and compaction until no tuple and no implicit node is left; then the G-buffer.
// The driver sets the LoopState's inputs and brings the G-buffer stage's hits home.
#pragma once

#include "sst/Compaction.h"
#include "sst/GBufferStage.h"
#include "sst/LoopState.h"
#include "sst/Overlap.h"
#include "sst/Solution.h"
#include "sst/Subdivision.h"
#include "sst/Sweep.h"

#include <chrono>
#include <limits>

namespace iga
{
namespace sst
{

/// The frame's per-pixel arrays and counters, before its first band.
template<class Exec>
void beginFrame(LoopState<Exec>& s, const Settings& settings)
{
  const size_t pixels = s.pixelCount;
  // Each pixel's bound starts at its far depth (HitPolicy).
  if (settings.farDepths.empty())
    s.exec.fill(sized(s.BestDepth, pixels), pixels, std::numeric_limits<double>::infinity());
  else
    s.exec.upload(settings.farDepths.data(), pixels, sized(s.BestDepth, pixels));
  s.exec.fill(sized(s.Unresolved, pixels), pixels, uint8_t(0));
  sized(s.PixelSolves, pixels); // zeroed per pass for its pixels with work
  // Empty groups: a pass sets those of its pixels with work items, and reads no others.
  s.exec.fill(sized(s.GroupBegin, pixels), pixels, uint32_t(0));
  s.exec.fill(sized(s.GroupEnd, pixels), pixels, uint32_t(0));
  sized(s.ItemOffsets, pixels + 1);
  s.exec.fill(sized(s.Tallies, TallyCount), TallyCount, 0ull);
  sized(s.Totals, 6);
  s.HitCount = 0;
  s.peak = s.peakBudgeted = 0;
}

/// Whether the frame's deadline has passed (checked on the host between iterations).
template<class Exec>
bool deadlinePassed(LoopState<Exec>& s)
{
  s.pastDeadline = s.pastDeadline || std::chrono::steady_clock::now() >= s.deadline;
  return s.pastDeadline;
}

/// At the deadline: the band's pixels with work left (the active ones) are given up, unresolved,
/// with the hits found so far.
template<class Exec>
void giveUpActivePixels(LoopState<Exec>& s)
{
  uint8_t* unresolved = raw(s.Unresolved);
  const uint32_t* active = raw(s.Active);
  s.exec.forEach(s.Active.size(), [=] IGA_HD(size_t k) { unresolved[active[k]] = 1; });
  s.report->unresolvedAtDeadline += s.Active.size();
  s.Active.resize(0);
}

/// One round's iterations over the groups in GroupBegin/GroupEnd of the active pixels, until
/// none is left or the deadline passes.
template<class Exec>
void solveRound(LoopState<Exec>& s)
{
  FrameReport& report = *s.report;
  // The round's initial nodes, all implicit.
  {
    const size_t initialCount = s.initialCount;
    uint8_t* present = sized(s.Present, initialCount);
    s.exec.fill(present, initialCount, uint8_t(0));
    const uint32_t* items = raw(s.ItemNodes);
    const uint32_t* begin = raw(s.GroupBegin);
    const uint32_t* end = raw(s.GroupEnd);
    const uint32_t* active = raw(s.Active);
    s.exec.forEach(s.Active.size(),
      [=] IGA_HD(size_t k)
      {
        for (uint32_t i = begin[active[k]]; i < end[active[k]]; ++i)
        {
          if (!present[items[i]]) // stores only where needed: threads share the few flags
          {
            storeShared(&present[items[i]], 1);
          }
        }
      });
    s.NodeCount = gatherNodes(
      s, s.initialNodes, s.initialPool, present, initialCount, nullptr, nullptr, nullptr, 0, true);
  }
  s.TupleCount = 0;
  while (s.NodeCount > 0)
  {
    ++report.iterations;
    report.maxPatches = std::max(report.maxPatches, s.NodeCount);
    overlapStage(s);
    s.stages.end(report.msOverlap);
    solutionStage(s);
    s.stages.end(report.msSolution);
    const size_t allowed = chooseSplits(s);
    splitNodes(s, allowed);
    s.stages.end(report.msSubdivision);
    compactionStage(s, allowed);
    endIteration(s);
    s.stages.end(report.msCompaction);
    if (*s.progress)
    {
      (*s.progress)(report.iterations, s.TupleCount);
    }
    if (deadlinePassed(s))
    {
      break;
    }
  }
  s.Tuples.resize(0);
  // The round's Newton solves, counted per pixel.
  uint32_t* solves = raw(s.PixelSolves);
  const uint32_t* active = raw(s.Active);
  report.newtonSolves +=
    s.exec.sum(s.Active.size(), [=] IGA_HD(size_t k) { return size_t(solves[active[k]]); });
  s.exec.forEach(s.Active.size(), [=] IGA_HD(size_t k) { solves[active[k]] = 0; });
}

/// The rounds over the band's work items (the sweep's); after the deadline, its pixels with
/// work are given up.
template<class Exec>
void solveRounds(LoopState<Exec>& s)
{
  for (;;)
  {
    const size_t work = nextGroups(s);
    s.stages.end(s.report->msSweepAndGroup);
    if (work == 0)
    {
      break;
    }
    if (!deadlinePassed(s))
    {
      solveRound(s);
    }
    if (s.pastDeadline)
    {
      giveUpActivePixels(s);
      break;
    }
  }
}

/// The sweep and the rounds of one band of rows (s.frame's).
template<class Exec>
void drawPass(LoopState<Exec>& s)
{
  sweepAndGroup(s);
  s.stages.end(s.report->msSweepAndGroup);
  solveRounds(s);
}

/// The report's counts of the frame, once its bands are drawn.
template<class Exec>
void reportFrame(LoopState<Exec>& s)
{
  FrameReport& report = *s.report;
  const uint8_t* unresolved = raw(s.Unresolved);
  report.unresolvedPixels =
    s.exec.sum(s.pixelCount, [=] IGA_HD(size_t p) { return size_t(unresolved[p]); });
  unsigned long long tallies[TallyCount];
  s.exec.read(raw(s.Tallies), TallyCount, tallies);
  report.unresolvedAtDepthCap += size_t(tallies[TuplesAtDepthCap]);
  report.unresolvedAtBudget += size_t(tallies[TuplesOverBudget]);
  report.newtonRuns += size_t(tallies[NewtonRuns]);
  report.newtonEvaluations += size_t(tallies[NewtonEvaluations]);
  report.peakBytes = s.peak;
  report.peakBudgetedBytes = s.peakBudgeted;
}

/// The whole frame: pass() for each band of rows (drawPass, or a reference method's), then the
/// G-buffer stage and the report's counts.
template<class Exec, class Pass>
void drawFrame(LoopState<Exec>& s, const Settings& settings, Pass pass)
{
  s.stages.begin();
  beginFrame(s, settings);
  s.stages.end(s.report->msSetup);
  s.report->bands = drawInBands(frameBands(s, settings), s.frame, pass);
  gBufferStage(s);
  s.stages.end(s.report->msGBuffer);
  s.stages.finish();
  reportFrame(s);
}

} // namespace sst
} // namespace iga
