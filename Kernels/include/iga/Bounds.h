// Conservative bounds of rational Bézier patches: boxes after a projective transform, attribute
// ranges, and a test that certifies at most one root of the pixel problem in a patch.
#pragma once

#include "iga/BezierPatch.h"

#include <glm/common.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat2x2.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <vector>

namespace iga
{

template<class T>
struct Box3
{
  T lo[3];
  T hi[3];
};

enum class ProjectionStatus
{
  InFront,           ///< every projected weight is positive: the box is a valid bound
  StraddlesEyePlane, ///< some projected weights are <= 0: no finite bound exists
  BehindEye,         ///< every projected weight is <= 0: the patch cannot be visible
};

namespace detail
{
/// Box of the control points `point(p)` maps to homogeneous (x, y, z, w), after the perspective
/// division, and where the patch lies relative to the plane w = 0.
template<class T, int Dim, class Map>
IGA_HD ProjectionStatus projectedBounds(const PatchView<const T, Dim>& patch, Map map, Box3<T>& box)
{
  int positive = 0;
  const int count = patch.pointCount();
  for (int d = 0; d < 3; ++d)
  {
    box.lo[d] = T(0);
    box.hi[d] = T(0);
  }
  for (int p = 0; p < count; ++p)
  {
    const glm::vec<4, T> clip = map(patch.point(p));
    if (!(clip[3] > T(0)))
    {
      continue;
    }
    for (int d = 0; d < 3; ++d)
    {
      const T v = clip[d] / clip[3];
      box.lo[d] = positive == 0 ? v : minValue(box.lo[d], v);
      box.hi[d] = positive == 0 ? v : maxValue(box.hi[d], v);
    }
    ++positive;
  }
  if (positive == count)
  {
    return ProjectionStatus::InFront;
  }
  return positive == 0 ? ProjectionStatus::BehindEye : ProjectionStatus::StraddlesEyePlane;
}
} // namespace detail

/// Box of the patch's control points after the projective map M (e.g. world to clip space)
/// followed by the perspective division. Uses channels 0..3 of the standard layout. Because the
/// projected patch is a rational Bézier patch whose weights are the projected w's, the box bounds
/// the patch exactly when all of them are positive; otherwise the status says why it does not.
template<class T, int Dim>
IGA_HD ProjectionStatus projectedBounds(
  const PatchView<const T, Dim>& patch, const glm::mat<4, 4, T>& M, Box3<T>& box)
{
  return detail::projectedBounds(
    patch, [&](const T* point) { return M * glm::make_vec4(point); }, box);
}

/// The same for channels 0..3 already in the projected space (M the identity).
template<class T, int Dim>
IGA_HD ProjectionStatus projectedBounds(const PatchView<const T, Dim>& patch, Box3<T>& box)
{
  return detail::projectedBounds(
    patch, [](const T* point) { return glm::make_vec4(point); }, box);
}

/// Range [lo, hi] of the rational function numerator/denominator over the patch, valid when every
/// denominator coefficient is positive (returns false otherwise): the function is a convex
/// combination of the coefficient ratios.
template<class T, int Dim>
IGA_HD bool rationalRange(
  const PatchView<const T, Dim>& patch, int numerator, int denominator, T& lo, T& hi)
{
  lo = hi = T(0);
  const int count = patch.pointCount();
  for (int p = 0; p < count; ++p)
  {
    const T* point = patch.point(p);
    if (!(point[denominator] > T(0)))
    {
      return false;
    }
    const T v = point[numerator] / point[denominator];
    lo = p == 0 ? v : minValue(lo, v);
    hi = p == 0 ? v : maxValue(hi, v);
  }
  return true;
}

/// The "no sign change, no surface" test: false when attribute channel `attribute` (standard
/// layout, weight in kWeightChannel) stays strictly on one side of `isovalue` over the patch.
template<class T, int Dim>
IGA_HD bool mayContainIsovalue(const PatchView<const T, Dim>& patch, int attribute, T isovalue)
{
  T lo = T(0), hi = T(0);
  if (!rationalRange(patch, attribute, kWeightChannel, lo, hi))
  {
    return true;
  }
  return lo <= isovalue && isovalue <= hi;
}

/// Where the isosurfaces attribute = isovalue (any of `isovalues`) of a volume lie: the union of
/// the control-point boxes of its pieces after `depth` midpoint halvings along every direction,
/// pieces that cannot hold one (mayContainIsovalue) dropped as soon as they appear, so the box
/// shrinks onto the surfaces as depth grows. Grows `box` by it (start from an empty box, lo
/// above hi) and returns true; returns false (box untouched) when no piece may hold one. Host
/// only.
template<class T>
bool growByIsosurfaces(const PatchView<const T, 3>& patch, int attribute,
  const std::vector<T>& isovalues, int depth, Box3<T>& box)
{
  const int size = patch.valueCount();
  std::vector<std::vector<T>> pieces{ std::vector<T>(patch.coeffs, patch.coeffs + size) };
  bool found = false;
  for (int level = 0; level <= depth && !pieces.empty(); ++level)
  {
    std::vector<std::vector<T>> next;
    for (const auto& piece : pieces)
    {
      const PatchView<const T, 3> view(piece.data(), patch.degree, patch.channels);
      const bool holds = std::any_of(isovalues.begin(), isovalues.end(),
        [&](T isovalue) { return mayContainIsovalue(view, attribute, isovalue); });
      if (!holds)
        continue;
      if (level < depth)
      {
        std::vector<T> children(size_t(8 * size));
        splitMidpoint(view, children.data());
        for (int c = 0; c < 8; ++c)
          next.emplace_back(children.begin() + c * size, children.begin() + (c + 1) * size);
        continue;
      }
      Box3<T> part;
      if (projectedBounds(view, part) != ProjectionStatus::InFront)
        continue;
      for (int a = 0; a < 3; ++a)
      {
        box.lo[a] = std::min(box.lo[a], part.lo[a]);
        box.hi[a] = std::max(box.hi[a], part.hi[a]);
      }
      found = true;
    }
    pieces = std::move(next);
  }
  return found;
}

/// One equation of a pixel problem: the rational function numerator/denominator of two channels.
struct RationalRow
{
  int numerator;
  int denominator;
};

/// The leading channels that `Dim` rows read: one past the highest channel among them.
template<int Dim>
IGA_HD int leadingChannelsOf(const RationalRow* rows)
{
  int leading = 0;
  for (int r = 0; r < Dim; ++r)
  {
    leading = maxValue(leading, 1 + maxValue(rows[r].numerator, rows[r].denominator));
  }
  return leading;
}

/// Closed interval.
template<class T>
struct Interval
{
  T lo;
  T hi;
  IGA_HD T mid() const { return T(0.5) * (lo + hi); }
  IGA_HD T radius() const { return T(0.5) * (hi - lo); }
};

template<class T>
IGA_HD Interval<T> operator*(Interval<T> a, Interval<T> b)
{
  const T p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  return { minValue(minValue(p0, p1), minValue(p2, p3)),
    maxValue(maxValue(p0, p1), maxValue(p2, p3)) };
}

template<class T>
IGA_HD Interval<T> operator-(Interval<T> a, Interval<T> b)
{
  return { a.lo - b.hi, a.hi - b.lo };
}

/// Inverse of a Dim x Dim matrix (Dim 2 or 3); false when the determinant is zero relative to
/// the product of the rows' largest entries, a measure that scaling a row leaves alone: the
/// pixel problem's rows are in pixels and in attribute units, and the homogeneous ones scale
/// with the distance to the eye.
template<class T, int Dim>
IGA_HD bool invertMatrix(const glm::mat<Dim, Dim, T>& a, glm::mat<Dim, Dim, T>& inverse)
{
  T rowScales = T(1);
  for (int r = 0; r < Dim; ++r)
  {
    T largest = T(0);
    for (int c = 0; c < Dim; ++c)
    {
      largest = maxValue(largest, absValue(a[c][r]));
    }
    rowScales *= largest;
  }
  if (!(absValue(glm::determinant(a)) > T(64) * Epsilon<T>::value * rowScales))
  {
    return false;
  }
  inverse = glm::inverse(a);
  return true;
}

/// Interval hulls over a patch of the rows of F(u) = (N_r(u) / D_r(u))_r, r < Dim:
/// `scaled` bounds G_r = D_r dN_r - N_r dD_r (row r of the Jacobian times D_r^2 > 0) and
/// `jacobian` the Jacobian itself. Bounds come from Bernstein coefficient ranges; each numerator
/// is first shifted by its mean ratio (N - c D has the same quotient derivative) so the product
/// terms stay tight. False when a denominator coefficient is not positive.
template<class T, int Dim>
IGA_HD bool rationalJacobianHull(const PatchView<const T, Dim>& patch, const RationalRow* rows,
  Interval<T> (&scaled)[Dim][Dim], Interval<T> (&jacobian)[Dim][Dim])
{
  const int count = patch.pointCount();
  for (int r = 0; r < Dim; ++r)
  {
    const int num = rows[r].numerator;
    const int den = rows[r].denominator;
    T ratioLo = T(0), ratioHi = T(0);
    if (!rationalRange(patch, num, den, ratioLo, ratioHi))
    {
      return false;
    }
    const T shift = T(0.5) * (ratioLo + ratioHi);
    Interval<T> N = { T(0), T(0) }, D = { T(0), T(0) };
    Interval<T> dN[Dim], dD[Dim];
    for (int p = 0; p < count; ++p)
    {
      const T* point = patch.point(p);
      const T n = point[num] - shift * point[den];
      N = p == 0 ? Interval<T>{ n, n } : Interval<T>{ minValue(N.lo, n), maxValue(N.hi, n) };
      D = p == 0 ? Interval<T>{ point[den], point[den] }
                 : Interval<T>{ minValue(D.lo, point[den]), maxValue(D.hi, point[den]) };
    }
    for (int d = 0; d < Dim; ++d)
    {
      // Derivative coefficients along d: degree * (P_{i+1} - P_i).
      const int stride = patch.stride(d) / patch.channels;
      const T degree = T(patch.degree[d]);
      bool first = true;
      int index[Dim] = {};
      for (int p = 0; p < count; ++p)
      {
        if (index[d] < patch.degree[d])
        {
          const T* a = patch.point(p);
          const T* b = patch.point(p + stride);
          const T dn = degree * ((b[num] - shift * b[den]) - (a[num] - shift * a[den]));
          const T dd = degree * (b[den] - a[den]);
          dN[d] = first ? Interval<T>{ dn, dn }
                        : Interval<T>{ minValue(dN[d].lo, dn), maxValue(dN[d].hi, dn) };
          dD[d] = first ? Interval<T>{ dd, dd }
                        : Interval<T>{ minValue(dD[d].lo, dd), maxValue(dD[d].hi, dd) };
          first = false;
        }
        for (int e = 0; e < Dim; ++e)
        {
          if (++index[e] < patch.order(e))
          {
            break;
          }
          index[e] = 0;
        }
      }
      if (first) // degree 0 in this direction: the row does not depend on u_d
      {
        dN[d] = { T(0), T(0) };
        dD[d] = { T(0), T(0) };
      }
      scaled[r][d] = D * dN[d] - N * dD[d];
      const Interval<T> inverseSquare = { T(1) / (D.hi * D.hi), T(1) / (D.lo * D.lo) };
      jacobian[r][d] = scaled[r][d] * inverseSquare;
    }
  }
  return true;
}

/// Midpoint inverse of an interval matrix and |mid^-1| rad: the ingredients of Beeck's
/// regularity test and of the Krawczyk operator. False when the midpoint is singular. The
/// interval matrix is indexed [row][column], the GLM ones [column][row].
template<class T, int Dim>
IGA_HD bool preconditioner(
  const Interval<T> (&M)[Dim][Dim], glm::mat<Dim, Dim, T>& inverse, glm::mat<Dim, Dim, T>& spread)
{
  glm::mat<Dim, Dim, T> mid, radius;
  for (int r = 0; r < Dim; ++r)
  {
    for (int c = 0; c < Dim; ++c)
    {
      mid[c][r] = M[r][c].mid();
      radius[c][r] = M[r][c].radius();
    }
  }
  if (!invertMatrix<T, Dim>(mid, inverse))
  {
    return false;
  }
  glm::mat<Dim, Dim, T> magnitude;
  for (int c = 0; c < Dim; ++c)
  {
    magnitude[c] = glm::abs(inverse[c]);
  }
  spread = magnitude * radius;
  return true;
}

/// Certifies that F is injective on the patch, so that F(u) = target has at most one solution in
/// it for every target (and Newton's root, when found, is the only one).
///
/// Why it holds: for two parameters a, b the mean value theorem gives F(a) - F(b) = J' (a - b),
/// where row r of J' is a positive multiple (1 / D_r^2 > 0) of a convex combination of values of
/// G_r on the segment, hence lies in the interval hull [G_r]. If every matrix of the interval
/// matrix [G] is regular, J' is regular and F(a) != F(b). Regularity is checked with Beeck's
/// sufficient condition ||mid([G])^-1| rad([G])|_inf < 1.
template<class T, int Dim>
IGA_HD bool certifyUniqueRoot(const Interval<T> (&scaled)[Dim][Dim])
{
  glm::mat<Dim, Dim, T> inverse, spread;
  if (!preconditioner<T, Dim>(scaled, inverse, spread))
  {
    return false;
  }
  // Row sums; a margin below 1 absorbs the rounding of the bounds themselves.
  const glm::vec<Dim, T> rowSums = spread * glm::vec<Dim, T>(T(1));
  for (int r = 0; r < Dim; ++r)
  {
    if (!(rowSums[r] < T(0.9)))
    {
      return false;
    }
  }
  return true;
}

template<class T, int Dim>
IGA_HD bool certifyUniqueRoot(const PatchView<const T, Dim>& patch, const RationalRow* rows)
{
  Interval<T> scaled[Dim][Dim], jacobian[Dim][Dim];
  return rationalJacobianHull(patch, rows, scaled, jacobian) && certifyUniqueRoot<T, Dim>(scaled);
}

/// The Krawczyk operator's exclusion test on the box [0,1]^Dim widened by `slack`: every root of
/// F(u) = target in the box lies in K = c - Y r + (I - Y [J]) (X - c), with c the centre,
/// r = F(c) - target and Y = mid([J])^-1. When K misses the box in some direction there is no
/// root. `inverse` and `spread` come from preconditioner([J]). Proves the misses that would
/// otherwise fail Newton and force subdivision (rays grazing a surface piece, say).
template<class T, int Dim>
IGA_HD bool krawczykExcludes(const glm::mat<Dim, Dim, T>& inverse,
  const glm::mat<Dim, Dim, T>& spread, const glm::vec<Dim, T>& residualAtCentre, T slack)
{
  const T half = T(0.5) + slack;
  const glm::vec<Dim, T> step = inverse * residualAtCentre;
  const glm::vec<Dim, T> radius = spread * glm::vec<Dim, T>(half);
  for (int i = 0; i < Dim; ++i)
  {
    if (absValue(step[i]) > radius[i] + half)
    {
      return true;
    }
  }
  return false;
}

} // namespace iga
