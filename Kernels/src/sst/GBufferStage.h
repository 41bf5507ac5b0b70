// Stage 6, G-buffer: the frame's hits grouped by pixel, those the hit policy may keep shaded on
// their input patches in double precision, and per pixel resolved by the policy (sorted front to
// back, duplicates merged, what the policy keeps). Run r of pixel RunPixels[r] keeps
// KeptStarts[r + 1] - KeptStarts[r] hits, which compactHits puts at KeptStarts[r] where the
// driver wants them.
#pragma once

#include "sst/LoopState.h"

namespace iga
{
namespace sst
{

template<class Exec>
void gBufferStage(LoopState<Exec>& s)
{
  const size_t hitCount = s.HitCount;
  RawHit* raws = raw(s.Hits);
  s.exec.sortByPixel(raws, hitCount, s.pixelCount);
  uint32_t* runStarts = sized(s.RunStarts, hitCount + 1);
  const size_t runCount = pixelRuns(s.exec, raws, hitCount, runStarts);
  // A pixel's hits by one thread: a handful in all-hits mode, one or two in first-hit mode.
  const PatchShape* shapes = s.shapes;
  const double* shadingPool = s.shadingPool;
  const ShadingView viewer = s.viewer;
  // Patches with a power form are shaded from it, unless a colour attribute is read.
  const PowerShading* powerShading = viewer.hasColor ? nullptr : s.powerShading;
  const PowerTerm* powerTerms = s.powerTerms;
  const HitPolicy policy = s.frame.hits;
  const double footprint = s.pixelFootprint;
  Hit* shaded = sized(s.Shaded, hitCount);
  uint32_t* pixels = sized(s.RunPixels, runCount);
  uint32_t* kept = sized(s.KeptStarts, runCount + 1);
  s.exec.forEach(
    runCount,
    [=] IGA_HD(size_t r)
    {
      // Only the hits the policy may keep are shaded, at the front of the run.
      double nearest = raws[runStarts[r]].ndcDepth;
      for (uint32_t h = runStarts[r] + 1; h < runStarts[r + 1]; ++h)
      {
        nearest = raws[h].ndcDepth < nearest ? raws[h].ndcDepth : nearest;
      }
      uint32_t candidates = runStarts[r];
      for (uint32_t h = runStarts[r]; h < runStarts[r + 1]; ++h)
      {
        if (policy.mayResolveTo(raws[h].ndcDepth, nearest))
        {
          const PatchShape& shape = shapes[raws[h].patch];
          const VolumeView<const double> shading(
            shadingPool + shape.screen, shape.degree, kShadeChannels);
          shaded[candidates++] =
            powerShading && powerShading[raws[h].patch].count > 0
              ? shadePowerHit(powerShading[raws[h].patch], powerTerms, raws[h], viewer)
              : shadeHit(shading, raws[h], viewer);
        }
      }
      pixels[r] = raws[runStarts[r]].pixel;
      kept[r] = uint32_t(policy.resolve(
        shaded + runStarts[r], int(candidates - runStarts[r]), footprint, viewer.parallel));
    },
    kGrainHit);
  s.KeptCount = scanCounts(s.exec, s.KeptStarts, runCount); // at most the hit count
  s.RunCount = runCount;
}

/// Copies the kept hits, run by run, to `out` (KeptCount of them, in the execution's memory).
template<class Exec>
void compactHits(LoopState<Exec>& s, Hit* out)
{
  const uint32_t* runStarts = raw(s.RunStarts);
  const uint32_t* kept = raw(s.KeptStarts);
  const Hit* shaded = raw(s.Shaded);
  s.exec.forEach(s.RunCount,
    [=] IGA_HD(size_t r)
    {
      for (uint32_t k = kept[r]; k < kept[r + 1]; ++k)
      {
        out[k] = shaded[runStarts[r] + (k - kept[r])];
      }
    });
}

} // namespace sst
} // namespace iga
