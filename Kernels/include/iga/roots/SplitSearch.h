// The search that de Casteljau subdivision, Bézier point insertion and Bézier clipping share:
// pieces on a stack, the left one first so that roots come out sorted; a piece whose nonzero
// coefficients keep one sign holds no root of odd multiplicity and is dropped; one narrower than
// the tolerance holds one, at its control polygon's zero. What differs is where a piece is cut:
// the finder's `choose(piece, context, cost)` says split at a local parameter or clip to a local
// interval.
#pragma once

#include "iga/roots/RootTools.h"

namespace iga
{
namespace roots
{

/// How a finder cuts a piece: split at local `a`, or (clip) keep only local [a, b], which holds
/// every root of the piece; an empty clip (a > b) means none.
struct Cut
{
  bool clip;
  double a, b;
};

namespace detail
{
/// A stack entry: a piece, or (degree < 0) a root met at a split point, kept until the roots to
/// its left are out.
IGA_HD inline Piece rootMarker(double t)
{
  Piece marker;
  marker.degree = -1;
  marker.lo = marker.hi = t;
  return marker;
}
} // namespace detail

/// Appends the roots of odd multiplicity inside `whole` (whose end coefficients are nonzero) to
/// `roots`, sorted, up to context.limit of them and none beyond context.until; see the header
/// comment.
template<class Choose>
IGA_HD void splitSearch(
  const Piece& whole, const RootContext& context, Choose choose, RootList& roots)
{
  constexpr int kStackSize = 96;
  Piece stack[kStackSize];
  int top = 0;
  copyPiece(whole, stack[top++]);
  const int d = whole.degree;
  long splits = 0;
  while (top > 0 && roots.count < context.limit)
  {
    // The top piece is worked on in place: a split writes its right part over it and the left
    // one above (copying whole pieces just written stalls, see copyPiece).
    Piece& piece = stack[top - 1];
    if (piece.lo > context.until)
    {
      --top;
      continue;
    }
    if (piece.degree < 0)
    {
      roots.add(piece.lo, context.merge);
      --top;
      continue;
    }
    if (!changesSign(piece, context.zero))
    {
      roots.touched = roots.touched || !holdsNoEvenRoot(piece, context.zero);
      --top;
      continue;
    }
    if (piece.hi - piece.lo <= context.tolerance || splits >= context.maxSplits ||
        top + 2 > kStackSize)
    {
      roots.cost.capped = roots.cost.capped || piece.hi - piece.lo > context.tolerance;
      const double zero = firstPolygonZero(piece, context.zero);
      roots.add(globalOf(piece, zero < 0 ? 0.5 : zero), context.merge);
      --top;
      continue;
    }
    const Cut cut = choose(piece, context, roots.cost);
    ++splits;
    if (cut.clip && !roots.touched && !holdsNoEvenRoot(piece, context.zero))
    {
      // A clip drops the piece outside [a, b]: it holds no odd root, but may touch zero.
      roots.touched = cut.a > cut.b ||
                      (cut.a > 0 && !holdsNoEvenRoot(clipPiece(piece, 0, cut.a), context.zero)) ||
                      (cut.b < 1 && !holdsNoEvenRoot(clipPiece(piece, cut.b, 1), context.zero));
    }
    if (cut.clip && (cut.b - cut.a) * (piece.hi - piece.lo) <= context.tolerance)
    {
      if (cut.a <= cut.b)
      {
        roots.add(globalOf(piece, 0.5 * (cut.a + cut.b)), context.merge);
      }
      --top;
      continue;
    }
    if (cut.clip)
    {
      // A clip may end on a root: its value there is zero to rounding.
      const Piece middle = clipPiece(piece, cut.a, cut.b);
      --top;
      roots.cost.insertions += 2 * d;
      if (signOf(middle.c[d], context.zero) == 0)
      {
        stack[top++] = detail::rootMarker(middle.hi);
      }
      stack[top++] = middle;
      if (signOf(middle.c[0], context.zero) == 0)
      {
        stack[top++] = detail::rootMarker(middle.lo);
      }
      continue;
    }
    splitPiece(piece, cut.a, stack[top], piece);
    roots.cost.insertions += d;
    if (signOf(piece.c[0], context.zero) == 0)
    {
      // A root at the split point, kept between the two parts.
      copyPiece(stack[top], stack[top + 1]);
      stack[top++] = detail::rootMarker(piece.lo);
    }
    ++top;
  }
}

} // namespace roots
} // namespace iga
