// Element edges drawn from a G-buffer, as ParaView's "Surface With Edges" draws cell edges: per
// pixel, how much of it lines of a given width centred on the element boundaries cover. The
// boundaries are where a hit's parameter in its patch reaches 0 or 1 (a patch is a Bézier
// element, so these are the knot lines of NURBS input); the distance to them in pixels comes
// from the parameter and its screen gradient, so the lines lie where the elements end at any
// zoom, with no tessellation. Host code, VTK-free.
#pragma once

#include "iga/sst/GBuffer.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace iga
{
namespace sst
{

namespace detail
{

/// A parameter's first and second screen derivatives at a pixel, in pixels.
struct ParameterDerivatives
{
  double x = 0, y = 0, xx = 0, xy = 0, yy = 0;
};

/// Derivatives of parameter d at pixel (i, j) from the neighbours' first hits on the same patch:
/// central differences, second-order one-sided ones at a patch's border (where edges are drawn),
/// the mixed one from the quadrants whose three neighbours lie on the patch. False when no
/// neighbour in x or in y lies on the patch.
inline bool parameterDerivatives(const GBuffer& g, int i, int j, int d, ParameterDerivatives& out)
{
  const Hit& centre = *g.firstHit(i, j);
  const double f0 = centre.uvw[d];
  auto at = [&](int a, int b, double& f)
  {
    if (a < 0 || b < 0 || a >= g.width || b >= g.height)
    {
      return false;
    }
    const Hit* hit = g.firstHit(a, b);
    const bool same = hit && hit->patch == centre.patch && hit->isovalue == centre.isovalue;
    f = same ? hit->uvw[d] : 0.0;
    return same;
  };
  // Along one axis (step (di, dj)): the first and second derivative, false with no neighbour.
  auto alongAxis = [&](int di, int dj, double& first, double& second)
  {
    double before, after, far;
    const bool hasBefore = at(i - di, j - dj, before), hasAfter = at(i + di, j + dj, after);
    if (hasBefore && hasAfter)
    {
      first = 0.5 * (after - before);
      second = after - 2.0 * f0 + before;
      return true;
    }
    if (!hasBefore && !hasAfter)
    {
      return false;
    }
    const int side = hasAfter ? 1 : -1;
    const double near = hasAfter ? after : before;
    second = at(i + 2 * side * di, j + 2 * side * dj, far) ? far - 2.0 * near + f0 : 0.0;
    first = side * (near - f0 - 0.5 * second);
    return true;
  };
  const bool x = alongAxis(1, 0, out.x, out.xx);
  const bool y = alongAxis(0, 1, out.y, out.yy);
  int quadrants = 0;
  out.xy = 0;
  for (const int sx : { -1, 1 })
  {
    for (const int sy : { -1, 1 })
    {
      double fx, fy, fxy;
      if (at(i + sx, j, fx) && at(i, j + sy, fy) && at(i + sx, j + sy, fxy))
      {
        out.xy += sx * sy * (fxy - fx - fy + f0);
        ++quadrants;
      }
    }
  }
  out.xy = quadrants ? out.xy / quadrants : 0.0;
  return x || y;
}

/// Distance in pixels, along the parameter's gradient, to where a parameter now `toBoundary`
/// from a boundary reaches it: the root of its second-order Taylor expansion (the first-order
/// one, toBoundary over the slope, is off by a hundredth of a pixel a pixel away on a patch
/// whose parameter is not affine on the screen). `towardsOne` says the boundary is at 1.
inline double distanceToBoundary(const ParameterDerivatives& f, double toBoundary, bool towardsOne)
{
  const double slope = std::hypot(f.x, f.y);
  if (!(slope > 0))
  {
    return HUGE_VAL;
  }
  const double nx = f.x / slope, ny = f.y / slope;
  const double curvature = nx * nx * f.xx + 2.0 * nx * ny * f.xy + ny * ny * f.yy;
  // t pixels on towards the boundary, toBoundary - slope t - bend t^2 / 2 is left: towards 0
  // the parameter itself, bend the curvature; towards 1 one minus it, bend negated.
  const double bend = towardsOne ? -curvature : curvature;
  const double discriminant = std::max(0.0, slope * slope - 2.0 * bend * toBoundary);
  return 2.0 * toBoundary / (slope + std::sqrt(discriminant));
}

} // namespace detail

/// Per pixel (the G-buffer's order) the coverage in [0, 1] of element edges `lineWidth` pixels
/// wide: 1 - (distance - lineWidth / 2 + 1/2) clamped, from the pixel centre's distance in
/// pixels to the nearest boundary of its first hit's element (the parameter's distance to 0 or
/// 1 over its screen gradient; a surface's two parameters, an isosurface's three). A pixel whose
/// element shows in no neighbour is all edge: the element is smaller than the line.
inline std::vector<float> elementEdgeCoverage(const GBuffer& g, double lineWidth)
{
  std::vector<float> coverage(size_t(g.width) * g.height, 0.0f);
  for (int j = 0; j < g.height; ++j)
  {
    for (int i = 0; i < g.width; ++i)
    {
      const Hit* hit = g.firstHit(i, j);
      if (!hit)
      {
        continue;
      }
      double distance = HUGE_VAL;
      const int parameters = hit->isovalue < 0 ? 2 : 3;
      for (int d = 0; d < parameters; ++d)
      {
        detail::ParameterDerivatives derivatives;
        if (!detail::parameterDerivatives(g, i, j, d, derivatives))
        {
          distance = 0;
          break;
        }
        const bool towardsOne = hit->uvw[d] > 0.5;
        const double toBoundary = std::max(0.0, towardsOne ? 1.0 - hit->uvw[d] : hit->uvw[d]);
        distance =
          std::min(distance, detail::distanceToBoundary(derivatives, toBoundary, towardsOne));
      }
      const double covered = 0.5 * lineWidth + 0.5 - distance;
      coverage[size_t(j) * g.width + i] = float(std::clamp(covered, 0.0, 1.0));
    }
  }
  return coverage;
}

} // namespace sst
} // namespace iga
