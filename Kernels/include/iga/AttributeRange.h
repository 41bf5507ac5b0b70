// The range a rational attribute takes over patches, and where its extremes lie: values the field
// takes (corners of pieces) narrowed against Bernstein bounds by midpoint subdivision. The
// control points' range alone may pass the field's by far (the Marsden sphere's f = r^2 - 1
// takes -1 .. 5.75, its control values reach -7.75). Host only.
#pragma once

#include "iga/Bounds.h"

#include <limits>
#include <vector>

namespace iga
{

/// A value the attribute takes: at parameter u of patch `patch` (-1 while none was seen).
template<class T>
struct AttributeExtreme
{
  T value = T(0);
  long patch = -1;
  T u[3] = {};

  template<int Dim>
  void set(T at, long where, const T* parameter)
  {
    this->value = at;
    this->patch = where;
    for (int d = 0; d < 3; ++d)
    {
      this->u[d] = d < Dim ? parameter[d] : T(0);
    }
  }
};

/// The least and greatest values found so far, and whether every patch narrowed them to its
/// tolerance (false where a patch's piece budget ran out first: the values are still values the
/// field takes, so the true range contains them, but may pass them by more than the tolerance).
template<class T>
struct AttributeExtremes
{
  AttributeExtreme<T> min, max;
  bool complete = true;

  bool empty() const { return this->min.patch < 0; }
  /// Takes `value`, seen at u of `patch`, where it extends the range.
  template<int Dim>
  void see(T value, long patch, const T* u)
  {
    const bool first = this->empty();
    if (first || value < this->min.value)
    {
      this->min.template set<Dim>(value, patch, u);
    }
    if (first || value > this->max.value)
    {
      this->max.template set<Dim>(value, patch, u);
    }
  }
};

namespace detail
{

/// One piece of a patch: its coefficients (numerator, weight), the box of the patch's parameters
/// it covers and how often it was halved.
template<class T, int Dim>
struct RangePiece
{
  std::vector<T> coeffs;
  T origin[Dim];
  T extent[Dim];
  int depth;
};

/// Offers the attribute (channel `numerator` over channel `denominator`) at the patch's corners
/// to `extremes` (exact: a Bézier patch interpolates its corner control points); the patch covers
/// the box of parameters from `origin` spanning `extent`.
template<class T, int Dim>
void seeCorners(const PatchView<const T, Dim>& patch, int numerator, int denominator,
  const T* origin, const T* extent, long patchIndex, AttributeExtremes<T>& extremes)
{
  for (int corner = 0; corner < (1 << Dim); ++corner)
  {
    int index = 0, step = 1;
    T u[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      const int bit = (corner >> d) & 1;
      index += bit * patch.degree[d] * step;
      step *= patch.order(d);
      u[d] = origin[d] + T(bit) * extent[d];
    }
    const T* point = patch.point(index);
    extremes.template see<Dim>(point[numerator] / point[denominator], patchIndex, u);
  }
}

} // namespace detail

/// Offers the attribute (channel `numerator` over channel `denominator`, positive weights) at the
/// patch's corners and centre to `extremes`: values the field takes, to start from.
template<class T, int Dim>
void sampleExtremes(const PatchView<const T, Dim>& patch, int numerator, int denominator,
  long patchIndex, AttributeExtremes<T>& extremes)
{
  T origin[Dim], extent[Dim], centre[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    origin[d] = T(0);
    extent[d] = T(1);
    centre[d] = T(0.5);
  }
  detail::seeCorners(patch, numerator, denominator, origin, extent, patchIndex, extremes);
  std::vector<T> values(size_t(patch.channels));
  evaluateHomogeneous<T, Dim>(patch, centre, values.data(), nullptr);
  extremes.template see<Dim>(
    values[size_t(numerator)] / values[size_t(denominator)], patchIndex, centre);
}

/// Narrows `extremes` to within `tolerance` of the attribute's extremes over the patch (those
/// of the other patches it holds prune this one's search): a piece whose Bernstein bounds cannot
/// pass the values found by more than the tolerance is dropped; the others are halved, the
/// directions in turn, and their corners offered. At most `maxPieces` pieces are examined; a
/// patch left open then clears `extremes.complete`. Weights must be positive (a piece with a
/// non-positive weight coefficient is dropped and clears `complete`).
template<class T, int Dim>
void narrowExtremes(const PatchView<const T, Dim>& patch, int numerator, int denominator,
  long patchIndex, T tolerance, int maxPieces, AttributeExtremes<T>& extremes)
{
  using Piece = detail::RangePiece<T, Dim>;
  // Only the two channels read are split.
  Piece root;
  root.coeffs.resize(size_t(patch.pointCount()) * 2);
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    root.coeffs[size_t(2 * p)] = patch.point(p)[numerator];
    root.coeffs[size_t(2 * p + 1)] = patch.point(p)[denominator];
  }
  for (int d = 0; d < Dim; ++d)
  {
    root.origin[d] = T(0);
    root.extent[d] = T(1);
  }
  root.depth = 0;
  std::vector<Piece> stack{ std::move(root) };
  int examined = 0;
  while (!stack.empty())
  {
    Piece piece = std::move(stack.back());
    stack.pop_back();
    const PatchView<const T, Dim> view(piece.coeffs.data(), patch.degree, 2);
    T lo, hi;
    if (!rationalRange(view, 0, 1, lo, hi))
    {
      extremes.complete = false;
      continue;
    }
    const bool lower = !(lo >= extremes.min.value - tolerance);
    const bool upper = !(hi <= extremes.max.value + tolerance);
    if (!lower && !upper)
    {
      continue;
    }
    if (++examined > maxPieces)
    {
      extremes.complete = false;
      return;
    }
    detail::seeCorners(view, 0, 1, piece.origin, piece.extent, patchIndex, extremes);
    // Halving each direction in turn keeps the pieces cubes of the parameter domain.
    const int dir = piece.depth % Dim;
    Piece upperHalf = piece;
    const PatchView<T, Dim> left(piece.coeffs.data(), patch.degree, 2);
    const PatchView<T, Dim> right(upperHalf.coeffs.data(), patch.degree, 2);
    split<T, Dim>(view, dir, T(0.5), left, right);
    piece.extent[dir] /= 2;
    upperHalf.extent[dir] = piece.extent[dir];
    upperHalf.origin[dir] += piece.extent[dir];
    piece.depth = upperHalf.depth = piece.depth + 1;
    stack.push_back(std::move(upperHalf));
    stack.push_back(std::move(piece));
  }
}

/// The extremes of attribute channel `channel` (weight in kWeightChannel) over the patches
/// patchAt(0) ... patchAt(count - 1), each within `relative` times the range's spread (rounding
/// aside) of the field's, unless a patch's `maxPieces` ran out (see narrowExtremes).
template<class T, int Dim, class PatchAt>
AttributeExtremes<T> attributeExtremes(
  long count, const PatchAt& patchAt, int channel, T relative = T(1e-5), int maxPieces = 4096)
{
  AttributeExtremes<T> extremes;
  for (long p = 0; p < count; ++p)
  {
    sampleExtremes<T, Dim>(patchAt(p), channel, kWeightChannel, p, extremes);
  }
  if (extremes.empty())
  {
    return extremes;
  }
  const T scale = maxValue(absValue(extremes.min.value), absValue(extremes.max.value));
  const T tolerance = maxValue(relative * (extremes.max.value - extremes.min.value),
    maxValue(T(64) * std::numeric_limits<T>::epsilon() * scale, std::numeric_limits<T>::min()));
  for (long p = 0; p < count; ++p)
  {
    narrowExtremes<T, Dim>(patchAt(p), channel, kWeightChannel, p, tolerance, maxPieces, extremes);
  }
  return extremes;
}

} // namespace iga
