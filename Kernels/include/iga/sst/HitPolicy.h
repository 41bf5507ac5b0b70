// The per-pixel hit policy: what a pixel keeps of the hits the SST loop finds, and so what the
// loop may prune on the way. The one place where first-hit pruning lives; all hits sorted, and
// later CSG classification and transparency, plug in here.
#pragma once

#include "iga/Portability.h"
#include "iga/sst/GBuffer.h"

namespace iga
{
namespace sst
{

IGA_HD inline bool hitBefore(const Hit& a, const Hit& b)
{
  if (a.eyeDepth != b.eyeDepth)
  {
    return a.eyeDepth < b.eyeDepth;
  }
  if (a.isovalue != b.isovalue)
  {
    return a.isovalue < b.isovalue;
  }
  return a.patch < b.patch;
}

/// Sorts one pixel's hits front to back and merges duplicates (a root on a face shared by two
/// sub-patches is found in both: two roots of one isovalue closer along the ray than 1e-4 of a
/// pixel's footprint are one, as Newton places roots within 1e-6 pixel of the ray). Returns how
/// many are kept at the front.
IGA_HD inline int sortAndMergeHits(Hit* hits, int count, double footprint, bool parallel)
{
  for (int k = 1; k < count; ++k) // insertion sort: a pixel has a handful of hits
  {
    const Hit moving = hits[k];
    int at = k;
    for (; at > 0 && hitBefore(moving, hits[at - 1]); --at)
    {
      hits[at] = hits[at - 1];
    }
    hits[at] = moving;
  }
  int kept = 0;
  for (int k = 0; k < count; ++k)
  {
    const double tolerance = 1e-4 * footprint * (parallel ? 1.0 : absValue(hits[k].eyeDepth));
    bool duplicate = false;
    for (int previous = 0; previous < kept && !duplicate; ++previous)
    {
      duplicate = hits[previous].isovalue == hits[k].isovalue &&
                  hits[k].eyeDepth - hits[previous].eyeDepth <= tolerance;
    }
    if (!duplicate)
    {
      hits[kept++] = hits[k];
    }
  }
  return kept;
}

/// What a pixel keeps of its hits. A pixel's bound `best` (NDC depth) starts at its far depth
/// (Settings::farDepths, else infinity); in first-hit mode each hit nearer than it becomes it.
struct HitPolicy
{
  /// The nearest hit only (the fast path), else all hits sorted front to back.
  bool firstHitOnly = true;

  /// Whether work on a pixel nearest at depth `near` may still change what the pixel keeps when
  /// its bound lies at `best`. The loop drops work that cannot.
  IGA_HD bool mayMatter(double near, double best) const { return !(near > best); }

  /// Whether a root at `depth` is kept next to the bound `best`.
  IGA_HD bool keeps(double depth, double best) const { return !(depth > best); }

  /// The bound after a kept root at `depth`.
  IGA_HD double afterHit(double best, double depth) const
  {
    return firstHitOnly && depth < best ? depth : best;
  }

  /// Whether a pixel's work is taken one depth group at a time (the nearest group first, the
  /// next only while it may matter), rather than all at once.
  IGA_HD bool byDepthGroups() const { return firstHitOnly; }

  /// Whether a pixel's hit at NDC depth `depth` may be among what resolve keeps, the pixel's
  /// nearest hit lying at `nearest`. In first-hit mode only a hit within 1e-6 of the nearest
  /// may: the nearest itself or its duplicates, which resolve orders by eye depth, where rounding
  /// may reorder depths a few ulps apart; a hit further behind is never the first.
  IGA_HD bool mayResolveTo(double depth, double nearest) const
  {
    return !firstHitOnly || !(depth > nearest + 1e-6);
  }

  /// Sorts and merges one pixel's hits (sortAndMergeHits) and returns how many it keeps, at the
  /// front.
  IGA_HD int resolve(Hit* hits, int count, double footprint, bool parallel) const
  {
    const int kept = sortAndMergeHits(hits, count, footprint, parallel);
    return firstHitOnly && kept > 1 ? 1 : kept;
  }
};

} // namespace sst
} // namespace iga
