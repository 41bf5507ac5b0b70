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

/// The screen gradient of parameter d at pixel (i, j) from its neighbours' first hits on the
/// same patch (central differences, one-sided at a patch's border); false when no neighbour in
/// x or in y lies on the patch.
inline bool parameterGradient(const GBuffer& g, int i, int j, int d, double& gx, double& gy)
{
  const Hit& centre = *g.firstHit(i, j);
  auto at = [&](int a, int b) -> const Hit*
  {
    if (a < 0 || b < 0 || a >= g.width || b >= g.height)
    {
      return nullptr;
    }
    const Hit* hit = g.firstHit(a, b);
    return hit && hit->patch == centre.patch && hit->isovalue == centre.isovalue ? hit : nullptr;
  };
  auto difference = [&](const Hit* before, const Hit* after, double& slope)
  {
    if (before && after)
    {
      slope = 0.5 * (after->uvw[d] - before->uvw[d]);
    }
    else if (before || after)
    {
      slope = after ? after->uvw[d] - centre.uvw[d] : centre.uvw[d] - before->uvw[d];
    }
    return before || after;
  };
  const bool x = difference(at(i - 1, j), at(i + 1, j), gx);
  const bool y = difference(at(i, j - 1), at(i, j + 1), gy);
  gx = x ? gx : 0.0;
  gy = y ? gy : 0.0;
  return x || y;
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
        double gx, gy;
        if (!detail::parameterGradient(g, i, j, d, gx, gy))
        {
          distance = 0;
          break;
        }
        const double toBoundary = std::min(hit->uvw[d], 1.0 - hit->uvw[d]);
        const double slope = std::hypot(gx, gy);
        distance = std::min(distance, slope > 0 ? std::max(0.0, toBoundary) / slope : HUGE_VAL);
      }
      const double covered = 0.5 * lineWidth + 0.5 - distance;
      coverage[size_t(j) * g.width + i] = float(std::clamp(covered, 0.0, 1.0));
    }
  }
  return coverage;
}

} // namespace sst
} // namespace iga
