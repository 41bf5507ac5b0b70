// Knot insertion (Mørken and Reimers 2007): the polynomial as a spline on a Bernstein knot
// vector, refined by inserting the first zero of its control polygon as a knot (Boehm's
// algorithm) until that zero stops moving. It converges to the smallest root from any start,
// quadratically at a simple one, linearly near a multiple one: after kMaxKnotInsertions the
// piece is split at the zero reached, as Bézier point insertion would, and the search goes on
// in its parts (the shared left-first search keeps the roots sorted).
#pragma once

#include "iga/roots/SplitSearch.h"

namespace iga
{
namespace roots
{

/// Knots inserted into one piece's spline before the piece is split where its zero stands.
constexpr int kMaxKnotInsertions = 64;

namespace detail
{
/// A spline of degree d: `count` coefficients on count + d + 1 knots.
struct KnotSpline
{
  int degree = 0, count = 0;
  double knot[2 * kMaxOrder + kMaxKnotInsertions] = {};
  double c[kMaxOrder + kMaxKnotInsertions] = {};

  IGA_HD double abscissa(int i) const // the knot average of coefficient i
  {
    double sum = 0;
    for (int k = i + 1; k <= i + degree; ++k)
    {
      sum += knot[k];
    }
    return sum / degree;
  }

  /// Boehm's algorithm: x becomes a knot, the spline unchanged.
  IGA_HD void insert(double x)
  {
    int mu = degree;
    while (mu + 1 < count && knot[mu + 1] <= x)
    {
      ++mu;
    }
    for (int i = count; i > mu; --i)
    {
      c[i] = c[i - 1];
    }
    for (int i = mu; i >= mu - degree + 1; --i)
    {
      const double alpha = (x - knot[i]) / (knot[i + degree] - knot[i]);
      c[i] = alpha * c[i] + (1 - alpha) * c[i - 1];
    }
    for (int k = count + degree; k > mu; --k)
    {
      knot[k + 1] = knot[k];
    }
    knot[mu + 1] = x;
    ++count;
  }
};

/// The first zero of the spline's control polygon at a strict sign change; -1 without one.
IGA_HD inline double firstPolygonZero(const KnotSpline& spline, double zero)
{
  int last = -1;
  for (int i = 0; i < spline.count; ++i)
  {
    const int s = signOf(spline.c[i], zero);
    if (s == 0)
    {
      continue;
    }
    if (last >= 0 && s != signOf(spline.c[last], zero))
    {
      const double x0 = spline.abscissa(last), x1 = spline.abscissa(i);
      return x0 + (x1 - x0) * spline.c[last] / (spline.c[last] - spline.c[i]);
    }
    last = i;
  }
  return -1;
}

/// The smallest root of a piece with a sign change, in local parameters, or where the search
/// stood after kMaxKnotInsertions; -1 when the refined polygon shows there is none.
IGA_HD inline double smallestRoot(const Piece& piece, double step, double zero, RootCost& cost)
{
  KnotSpline spline;
  spline.degree = piece.degree;
  spline.count = piece.degree + 1;
  for (int i = 0; i <= piece.degree; ++i)
  {
    spline.c[i] = piece.c[i];
    spline.knot[i] = 0;
    spline.knot[piece.degree + 1 + i] = 1;
  }
  double x = firstPolygonZero(spline, zero);
  for (int inserted = 0; inserted < kMaxKnotInsertions; ++inserted)
  {
    spline.insert(x);
    ++cost.insertions;
    const double next = firstPolygonZero(spline, zero);
    if (next < 0) // no sign change left: a root only where the value at x is zero
    {
      return signOf(evaluatePiece(piece, x), zero) == 0 ? x : -1;
    }
    const bool still = absValue(next - x) <= step;
    x = next;
    if (still)
    {
      return x;
    }
  }
  return x;
}
} // namespace detail

/// Splits a piece where its spline's search for the smallest root stopped; none without one.
struct KnotInsertionCut
{
  IGA_HD Cut operator()(const Piece& piece, const RootContext& context, RootCost& cost) const
  {
    const double s =
      detail::smallestRoot(piece, context.tolerance / (piece.hi - piece.lo), context.zero, cost);
    return s < 0 ? Cut{ true, 1.0, 0.0 }
                 : Cut{ false, minValue(maxValue(s, 1e-12), 1 - 1e-12), 0.0 };
  }
};

} // namespace roots
} // namespace iga
