// Handedness of volume parametrizations. VTK's hexahedra are right-handed: their parametric
// directions r, s, t form a right-handed frame in space, and filters that integrate, clip or
// contour them assume it. A left-handed patch describes the same volume as the right-handed one
// with one parametric direction reversed.
#pragma once

#include "iga/BSpline.h"
#include "iga/BezierPatch.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <utility>
#include <vector>

namespace iga
{

/// Signed volume of a rational Bézier volume: the integral of det(dx/du) over [0,1]^3 by
/// two-point Gauss-Legendre quadrature per direction. Negative for a left-handed patch; for a
/// patch that folds over itself, the sign of the larger part.
template<class T>
T signedVolume(const PatchView<const T, 3>& patch)
{
  const T offset = T(0.5) / std::sqrt(T(3));
  const T nodes[2] = { T(0.5) - offset, T(0.5) + offset };
  std::vector<T> values(static_cast<size_t>(patch.channels));
  std::vector<T> derivatives(static_cast<size_t>(3 * patch.channels));
  T sum = T(0);
  for (int q = 0; q < 8; ++q)
  {
    const T u[3] = { nodes[q & 1], nodes[(q >> 1) & 1], nodes[(q >> 2) & 1] };
    evaluateHomogeneous<T, 3>(patch, u, values.data(), derivatives.data());
    const T w = values[kWeightChannel];
    glm::mat<3, 3, T> jacobian; // column d: derivative of the position along direction d
    for (int d = 0; d < 3; ++d)
    {
      const T* dv = derivatives.data() + d * patch.channels;
      for (int e = 0; e < 3; ++e)
      {
        jacobian[d][e] = (dv[e] * w - values[e] * dv[kWeightChannel]) / (w * w);
      }
    }
    sum += glm::determinant(jacobian);
  }
  return sum / T(8);
}

/// Signed volume of a B-spline volume with control net `net`: the sum over its Bézier elements.
template<class T>
T signedVolume(const BezierExtraction<T, 3>& extraction, const std::vector<T>& net, int channels)
{
  int order[3];
  size_t elementValues = static_cast<size_t>(channels);
  for (int d = 0; d < 3; ++d)
  {
    order[d] = extraction.direction(d).degree;
    elementValues *= static_cast<size_t>(order[d] + 1);
  }
  std::vector<T> element(elementValues), work(2 * elementValues);
  T sum = T(0);
  for (int e = 0; e < extraction.elementCount(); ++e)
  {
    extraction.extract(e, net.data(), channels, element.data(), work.data());
    sum += signedVolume(PatchView<const T, 3>(element.data(), order, channels));
  }
  return sum;
}

/// Reverses direction `dir` of a net of `sizes` points per direction (first direction fastest,
/// `channels` values per point): point i along `dir` trades places with point sizes[dir]-1-i.
template<class T>
void reverseNetDirection(T* values, const int* sizes, int dimension, int channels, int dir)
{
  size_t below = static_cast<size_t>(channels), above = 1;
  for (int d = 0; d < dir; ++d)
  {
    below *= static_cast<size_t>(sizes[d]);
  }
  for (int d = dir + 1; d < dimension; ++d)
  {
    above *= static_cast<size_t>(sizes[d]);
  }
  const size_t n = static_cast<size_t>(sizes[dir]);
  for (size_t outer = 0; outer < above; ++outer)
  {
    T* block = values + outer * n * below;
    for (size_t i = 0; i < n / 2; ++i)
    {
      for (size_t inner = 0; inner < below; ++inner)
      {
        std::swap(block[i * below + inner], block[(n - 1 - i) * below + inner]);
      }
    }
  }
}

/// The same Bézier patch with direction `dir` reversed (u_dir -> 1 - u_dir).
template<class T, int Dim>
void reverseDirection(const PatchView<T, Dim>& patch, int dir)
{
  int orders[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    orders[d] = patch.order(d);
  }
  reverseNetDirection(patch.coeffs, orders, Dim, patch.channels, dir);
}

/// A knot vector reversed: t -> a + b - t in reverse order (a, b the first and last knot).
template<class T>
std::vector<T> mirroredKnots(const std::vector<T>& knots)
{
  std::vector<T> mirrored(knots.rbegin(), knots.rend());
  for (T& knot : mirrored)
  {
    knot = knots.front() + knots.back() - knot;
  }
  return mirrored;
}

/// The same B-spline patch with direction `dir` reversed: its knots mirrored (mirroredKnots) and
/// the net reversed along `dir`.
template<class T, int Dim>
void reverseDirection(BSplinePatch<T, Dim>& patch, int dir)
{
  patch.knots[dir] = mirroredKnots(patch.knots[dir]);
  reverseNetDirection(patch.net.data(), patch.netSize, Dim, patch.channels, dir);
}

} // namespace iga
