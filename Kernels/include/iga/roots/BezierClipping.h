// Bézier clipping (Nishita, Sederberg and Kakimoto 1990) for a function graph: the piece is cut
// down to where the convex hull of its control points (i/d, c_i) meets the axis, which holds all
// its roots; where that removes less than a fifth (several roots, or one of even multiplicity
// nearby) it is split in the middle of that interval instead.
#pragma once

#include "iga/roots/SplitSearch.h"

namespace iga
{
namespace roots
{

/// Where the hull of the control points meets the axis, in local parameters: the span of the
/// axis crossings of all segments between points of opposite sign, and of the points on it.
IGA_HD inline Cut hullCut(const Piece& piece, double zero)
{
  const int d = piece.degree;
  double a = 2, b = -1;
  for (int i = 0; i <= d; ++i)
  {
    const int si = signOf(piece.c[i], zero);
    if (si == 0)
    {
      a = minValue(a, double(i) / d);
      b = maxValue(b, double(i) / d);
      continue;
    }
    for (int j = i + 1; j <= d; ++j)
    {
      if (signOf(piece.c[j], zero) == -si)
      {
        const double x0 = double(i) / d, x1 = double(j) / d;
        const double x = x0 + (x1 - x0) * piece.c[i] / (piece.c[i] - piece.c[j]);
        a = minValue(a, x);
        b = maxValue(b, x);
      }
    }
  }
  return Cut{ true, maxValue(a, 0.0), minValue(b, 1.0) };
}

struct HullCut
{
  IGA_HD Cut operator()(const Piece& piece, const RootContext& context, RootCost&) const
  {
    const Cut hull = hullCut(piece, context.zero);
    return hull.b - hull.a > 0.8 ? Cut{ false, 0.5 * (hull.a + hull.b), 0.0 } : hull;
  }
};

} // namespace roots
} // namespace iga
