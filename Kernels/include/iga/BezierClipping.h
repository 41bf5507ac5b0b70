// Bézier clipping (Nishita, Sederberg and Kakimoto, "Ray tracing trimmed rational surface
// patches", 1990): the roots of a pixel's ray in a rational surface patch, found by cutting away
// the parameter ranges where the convex hull of a distance function's Bernstein coefficients
// proves the ray misses, and by halving where that cuts too little. Host code, for the engine's
// reference method: independent of the subdivision trees and of Newton's method.
#pragma once

#include "iga/BezierPatch.h"
#include "iga/sst/PixelProblem.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace iga
{

/// The range [lo, hi] of t where the convex hull of the points (c / n, low[c]) and
/// (c / n, high[c]), c = 0..n, meets value 0; false when it lies on one side.
inline bool hullCrossing(const double* low, const double* high, int n, double& lo, double& hi)
{
  lo = HUGE_VAL;
  hi = -HUGE_VAL;
  auto point = [&](int k, double& t, double& v)
  {
    t = double(k / 2) / n;
    v = k % 2 ? high[k / 2] : low[k / 2];
  };
  const int points = 2 * (n + 1);
  for (int a = 0; a < points; ++a)
  {
    double ta, va;
    point(a, ta, va);
    if (va == 0)
    {
      lo = std::min(lo, ta);
      hi = std::max(hi, ta);
    }
    for (int b = 0; b < points; ++b)
    {
      double tb, vb;
      point(b, tb, vb);
      if (va < 0 && vb > 0) // the segment between them crosses 0
      {
        const double t = ta + (tb - ta) * va / (va - vb);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
    }
  }
  lo = std::max(lo, 0.0);
  hi = std::min(hi, 1.0);
  return lo <= hi;
}

/// One sub-patch of the clipping: its parameter range in the input patch and its coefficients.
struct ClippingRegion
{
  double lo[2], hi[2];
  std::vector<double> coeffs;
};

/// What bezierClip found for one ray.
struct ClippingResult
{
  std::vector<glm::dvec2> roots; ///< parameters in the patch (duplicates possible at seams)
  bool complete = true;          ///< false when the step budget ran out first
};

namespace detail
{

/// The distance functions of the ray through window point (x, y) whose zero sets contain the
/// ray: X - x W, Y - y W and their combination across the patch's other direction `other`
/// (Nishita's line through the ray along that direction), at a control point.
inline void rayDistances(
  const double* cp, double x, double y, const glm::dvec2& across, double* distance)
{
  const double g0 = cp[sst::kScreenX] - x * cp[sst::kScreenW];
  const double g1 = cp[sst::kScreenY] - y * cp[sst::kScreenW];
  distance[0] = g0;
  distance[1] = g1;
  distance[2] = across.x * g0 + across.y * g1;
}

/// The window direction of a patch's parameter direction d: the mean of its control polygon's
/// edges along d, projected, turned by 90 degrees (the normal of Nishita's line).
inline glm::dvec2 normalAcross(const SurfaceView<const double>& patch, int d)
{
  glm::dvec2 along(0.0);
  const int other = 1 - d;
  for (int k = 0; k <= patch.degree[other]; ++k)
  {
    int first[2], last[2];
    first[d] = 0;
    last[d] = patch.degree[d];
    first[other] = last[other] = k;
    const double* a = patch.point(first[0] + patch.order(0) * first[1]);
    const double* b = patch.point(last[0] + patch.order(0) * last[1]);
    if (a[sst::kScreenW] > 0 && b[sst::kScreenW] > 0)
    {
      along += glm::dvec2(b[0] / b[sst::kScreenW] - a[0] / a[sst::kScreenW],
        b[1] / b[sst::kScreenW] - a[1] / a[sst::kScreenW]);
    }
  }
  const double length = glm::length(along);
  return length > 0 ? glm::dvec2(-along.y, along.x) / length : glm::dvec2(1, 0);
}

/// The part of the region's patch over [a, b] of direction d (of its current range [0, 1]).
inline void clipRegion(ClippingRegion& region, const int* degree, int d, double a, double b)
{
  const SurfaceView<double> patch(region.coeffs.data(), degree, sst::kScreenChannels);
  if (b < 1)
  {
    splitParts<double, 2>(patch, d, b, patch.coeffs, nullptr);
  }
  if (a > 0)
  {
    splitParts<double, 2>(patch, d, a / b, nullptr, patch.coeffs);
  }
  const double width = region.hi[d] - region.lo[d];
  region.hi[d] = region.lo[d] + b * width;
  region.lo[d] = region.lo[d] + a * width;
}

/// The range of direction d where every distance function may vanish: for each, the hull of
/// its coefficients' extremes over the other direction's index. Widened by 1e-6 of the region:
/// a hull crossing at a root is computed with rounding, and a range clipped exactly to it may
/// miss the root by that rounding.
inline bool clipRange(
  const SurfaceView<const double>& patch, int d, double x, double y, double& lo, double& hi)
{
  const glm::dvec2 across = normalAcross(patch, 1 - d);
  const int n = patch.degree[d];
  double low[3][kMaxOrder], high[3][kMaxOrder];
  for (int f = 0; f < 3; ++f)
  {
    std::fill_n(low[f], n + 1, HUGE_VAL);
    std::fill_n(high[f], n + 1, -HUGE_VAL);
  }
  for (int j = 0; j < patch.order(1); ++j)
  {
    for (int i = 0; i < patch.order(0); ++i)
    {
      double distance[3];
      rayDistances(patch.point(i + patch.order(0) * j), x, y, across, distance);
      const int c = d == 0 ? i : j;
      for (int f = 0; f < 3; ++f)
      {
        low[f][c] = std::min(low[f][c], distance[f]);
        high[f][c] = std::max(high[f][c], distance[f]);
      }
    }
  }
  lo = 0;
  hi = 1;
  for (int f = 0; f < 3; ++f)
  {
    double a, b;
    if (!hullCrossing(low[f], high[f], n, a, b))
    {
      return false;
    }
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  lo = std::max(0.0, lo - 1e-6);
  hi = std::min(1.0, hi + 1e-6);
  return lo <= hi;
}

} // namespace detail

namespace detail
{

/// Whether a region's window box (its control points after the perspective division) is
/// narrower than `size` pixels in x and y; `covers` then says whether it holds (x, y).
inline bool tinyRegion(
  const SurfaceView<const double>& patch, double x, double y, double size, bool& covers)
{
  double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    const double* cp = patch.point(p);
    for (int d = 0; d < 2; ++d)
    {
      lo[d] = std::min(lo[d], cp[d] / cp[sst::kScreenW]);
      hi[d] = std::max(hi[d], cp[d] / cp[sst::kScreenW]);
    }
  }
  covers = lo[0] - size <= x && x <= hi[0] + size && lo[1] - size <= y && y <= hi[1] + size;
  return hi[0] - lo[0] < size && hi[1] - lo[1] < size;
}

} // namespace detail

/// The roots of the ray through window point (x, y) in a screen surface patch (the engine's
/// screen layout, positive W): a region whose window box is narrower than `size` pixels is a
/// root at its centre if the box holds the point (the clip's own arithmetic fails on regions
/// that small); others are clipped in u and v in turn, and halved in the wider direction when
/// a clip keeps more than 80 % of it. At most `steps` regions are examined.
inline ClippingResult bezierClip(
  const SurfaceView<const double>& patch, double x, double y, double size, int steps)
{
  ClippingResult result;
  std::vector<ClippingRegion> stack(1);
  stack[0].lo[0] = stack[0].lo[1] = 0;
  stack[0].hi[0] = stack[0].hi[1] = 1;
  stack[0].coeffs.assign(patch.coeffs, patch.coeffs + patch.valueCount());
  while (!stack.empty())
  {
    if (steps-- <= 0)
    {
      result.complete = false;
      return result;
    }
    ClippingRegion region = std::move(stack.back());
    stack.pop_back();
    bool missed = false, shrunk = false, covers = false;
    if (detail::tinyRegion(
          SurfaceView<const double>(region.coeffs.data(), patch.degree, sst::kScreenChannels), x, y,
          size, covers))
    {
      if (covers)
      {
        result.roots.emplace_back(
          0.5 * (region.lo[0] + region.hi[0]), 0.5 * (region.lo[1] + region.hi[1]));
      }
      continue;
    }
    for (int d = 0; d < 2 && !missed; ++d)
    {
      const SurfaceView<const double> current(
        region.coeffs.data(), patch.degree, sst::kScreenChannels);
      double a, b;
      missed = !detail::clipRange(current, d, x, y, a, b);
      if (!missed && b - a < 0.8)
      {
        detail::clipRegion(region, patch.degree, d, a, b);
        shrunk = true;
      }
    }
    if (missed)
    {
      continue;
    }
    if (!shrunk) // two roots or more, or a slow clip: halve the wider direction
    {
      const int d = region.hi[0] - region.lo[0] >= region.hi[1] - region.lo[1] ? 0 : 1;
      ClippingRegion upper = region;
      detail::clipRegion(region, patch.degree, d, 0, 0.5);
      detail::clipRegion(upper, patch.degree, d, 0.5, 1);
      stack.push_back(std::move(upper));
    }
    stack.push_back(std::move(region));
  }
  return result;
}

} // namespace iga
