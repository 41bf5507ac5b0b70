// Newton and regula falsi with roots isolated by the polar surface (Wei and Feng). Along a ray
// through the eye the polar surface's equation is the derivative of the ray's polynomial, so its
// roots cut [0, 1] into pieces where the polynomial is monotone: one root at most in each, found
// by Newton's method kept inside the bracket by regula falsi (Illinois) steps. The derivative's
// roots come the same way from the second derivative's, down to a linear one. A critical point
// where the polynomial is zero to rounding is a root of even multiplicity, which no sign change
// shows.
#pragma once

#include "iga/roots/RootTools.h"

namespace iga
{
namespace roots
{

namespace detail
{
/// The root in the bracket [a, b] (values fa, fb of opposite signs) of a monotone piece.
IGA_HD inline double bracketedRoot(const Piece& piece, double a, double b, double fa, double fb,
  const RootContext& context, RootCost& cost)
{
  const double step = context.tolerance / (piece.hi - piece.lo);
  double x = a + (b - a) * fa / (fa - fb);
  int side = 0; // Illinois: the end kept twice in a row has its value halved
  for (int iteration = 0; iteration < 200; ++iteration)
  {
    double f, slope;
    valueAndSlope(piece, x, f, slope);
    ++cost.evaluations;
    if (f == 0 || b - a <= step) // bracketed, Newton may go on inside the rounding's band
    {
      return x;
    }
    if ((f < 0) == (fa < 0))
    {
      a = x;
      fa = f;
      fb = side == 1 ? 0.5 * fb : fb;
      side = 1;
    }
    else
    {
      b = x;
      fb = f;
      fa = side == -1 ? 0.5 * fa : fa;
      side = -1;
    }
    const double newton = slope != 0 ? x - f / slope : a - 1;
    const double next = newton > a && newton < b ? newton : a + (b - a) * fa / (fa - fb);
    if (absValue(next - x) <= step)
    {
      return next;
    }
    x = next;
  }
  cost.capped = true;
  return x;
}

/// The first `limit` roots of `piece` in local parameters, sorted, given its critical points
/// (sorted, inside (0, 1)); even-multiplicity roots at critical points unless `evenRoots` is false.
IGA_HD inline int monotoneRoots(const Piece& piece, const double* critical, int criticalCount,
  const RootContext& context, bool evenRoots, int limit, double* out, RootCost& cost)
{
  int count = 0;
  double a = 0, fa = piece.c[0];
  for (int k = 0; k <= criticalCount && count < limit; ++k)
  {
    const double b = k < criticalCount ? critical[k] : 1.0;
    double fb = piece.c[piece.degree], slope = 0;
    if (k < criticalCount)
    {
      valueAndSlope(piece, b, fb, slope);
      ++cost.evaluations;
    }
    if (signOf(fa, context.zero) * signOf(fb, context.zero) < 0 && count < limit)
    {
      out[count++] = bracketedRoot(piece, a, b, fa, fb, context, cost);
    }
    if (k < criticalCount && evenRoots && signOf(fb, context.zero) == 0 && count < limit)
    {
      out[count++] = b;
    }
    a = b;
    fa = fb;
  }
  return count;
}

} // namespace detail

/// Appends the roots inside `whole` (end coefficients nonzero), sorted, the first context.limit
/// of them: the critical points are all found, the last level stops there.
IGA_HD inline void polarNewtonRoots(
  const Piece& whole, const RootContext& context, bool evenRoots, RootList& roots)
{
  // The chain of derivatives, each scaled to unit size so that one zero tolerance fits all.
  Piece chain[kMaxOrder];
  chain[0] = normalised(whole);
  for (int k = 1; k < whole.degree; ++k)
  {
    chain[k] = normalised(derivativeOf(chain[k - 1]));
  }
  double critical[kMaxRoots], found[kMaxRoots];
  int criticalCount = 0;
  for (int k = whole.degree - 1; k >= 0; --k)
  {
    const int count = detail::monotoneRoots(chain[k], critical, criticalCount, context,
      k > 0 || evenRoots, k > 0 ? kMaxRoots : context.limit, found, roots.cost);
    for (int i = 0; i < count; ++i)
    {
      critical[i] = found[i];
    }
    criticalCount = count;
  }
  for (int i = 0; i < criticalCount; ++i)
  {
    roots.add(globalOf(whole, critical[i]), context.merge);
  }
}

} // namespace roots
} // namespace iga
