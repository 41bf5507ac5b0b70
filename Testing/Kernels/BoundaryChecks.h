// Independent checks of a volume set's boundary faces (iga/Boundary.h): that they close up
// (every edge of a boundary face is an edge of exactly one other), and their area.
#pragma once

#include "iga/Boundary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace igatest
{

/// The edges of boundary faces that are not shared by exactly two boundary faces (an edge
/// collapsed to a point is no edge): 0 for the closed boundary of a solid.
template<class T>
size_t openBoundaryEdges(
  const std::vector<iga::BezierVolume<T>>& patches, const std::vector<iga::PatchFace>& faces)
{
  using Point = std::array<double, 3>;
  std::vector<std::vector<Point>> edges;
  double extent = 0;
  for (const auto& f : faces)
  {
    const auto face = iga::faceSurface(patches[size_t(f.patch)], f.direction, f.side);
    const auto view = face.view();
    for (int side = 0; side < 4; ++side)
    {
      const bool alongS = side < 2;
      const int fixed = side % 2 ? view.degree[alongS ? 1 : 0] : 0;
      std::vector<Point> edge;
      for (int k = 0; k < view.order(alongS ? 0 : 1); ++k)
      {
        const T* p = view.point(alongS ? k + view.order(0) * fixed : fixed + view.order(0) * k);
        const double w = double(p[iga::kWeightChannel]);
        edge.push_back({ double(p[0]) / w, double(p[1]) / w, double(p[2]) / w });
        for (int d = 0; d < 3; ++d)
          extent = std::max(extent, std::abs(edge.back()[d]));
      }
      std::sort(edge.begin(), edge.end());
      edges.push_back(edge);
    }
  }
  const double tolerance = 1e-9 * std::max(extent, 1.0);
  auto same = [&](const std::vector<Point>& a, const std::vector<Point>& b)
  {
    if (a.size() != b.size())
      return false;
    for (size_t k = 0; k < a.size(); ++k)
      for (int d = 0; d < 3; ++d)
        if (std::abs(a[k][d] - b[k][d]) > tolerance)
          return false;
    return true;
  };
  size_t open = 0;
  for (size_t e = 0; e < edges.size(); ++e)
  {
    if (same({ edges[e].front() }, { edges[e].back() }))
      continue; // collapsed to a point
    size_t partners = 0;
    for (size_t other = 0; other < edges.size(); ++other)
      partners += other != e && same(edges[e], edges[other]);
    open += partners != 1;
  }
  return open;
}

/// Area of the boundary faces, by 8 x 8 Gauss-Legendre points a face.
template<class T>
double boundaryArea(
  const std::vector<iga::BezierVolume<T>>& patches, const std::vector<iga::PatchFace>& faces)
{
  const double x[4] = { 0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
    0.9602898564975363 };
  const double w[4] = { 0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
    0.1012285362903763 };
  double nodes[8], weights[8];
  for (int k = 0; k < 4; ++k)
  {
    nodes[k] = 0.5 - 0.5 * x[k];
    nodes[7 - k] = 0.5 + 0.5 * x[k];
    weights[k] = weights[7 - k] = 0.5 * w[k];
  }
  double area = 0;
  for (const auto& f : faces)
  {
    const auto face = iga::faceSurface(patches[size_t(f.patch)], f.direction, f.side);
    const int channels = face.channels();
    std::vector<double> values(static_cast<size_t>(channels)),
      derivatives(static_cast<size_t>(2 * channels));
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
      {
        const double st[2] = { nodes[a], nodes[b] };
        iga::evaluateHomogeneous<double, 2>(face.view(), st, values.data(), derivatives.data());
        const double h = values[iga::kWeightChannel];
        double tangent[2][3];
        for (int d = 0; d < 2; ++d)
          for (int c = 0; c < 3; ++c)
            tangent[d][c] =
              (derivatives[size_t(d * channels + c)] * h -
                values[size_t(c)] * derivatives[size_t(d * channels + iga::kWeightChannel)]) /
              (h * h);
        const double n[3] = { tangent[0][1] * tangent[1][2] - tangent[0][2] * tangent[1][1],
          tangent[0][2] * tangent[1][0] - tangent[0][0] * tangent[1][2],
          tangent[0][0] * tangent[1][1] - tangent[0][1] * tangent[1][0] };
        area += weights[a] * weights[b] * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      }
  }
  return area;
}

} // namespace igatest
