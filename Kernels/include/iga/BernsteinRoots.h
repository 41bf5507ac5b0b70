// All roots in [0, 1] of a univariate Bernstein polynomial of degree up to 16, sorted, by a
// chosen finder: the ray equations of algebraic and ABS surfaces (Reimers and Seland; Wei and
// Feng). Roots at the ends are divided out first; roots of even multiplicity, which change no
// sign, are the critical points (roots of the derivative, found by the same finder) where the
// polynomial is zero to rounding.
#pragma once

#include "iga/roots/BezierClipping.h"
#include "iga/roots/KnotInsertion.h"
#include "iga/roots/PointInsertion.h"
#include "iga/roots/PolarNewton.h"
#include "iga/roots/Subdivision.h"

#include <stdexcept>
#include <string>

namespace iga
{

enum class RootFinder
{
  Subdivision,    ///< de Casteljau at the midpoint (Lane-Riesenfeld, Schneider)
  KnotInsertion,  ///< Mørken-Reimers
  BezierClipping, ///< Nishita-Sederberg-Kakimoto
  PointInsertion, ///< Wei-Feng's Bézier point insertion (BPI)
  PolarNewton,    ///< Wei-Feng's Newton and regula falsi, isolated by the polar surface
};
constexpr int kRootFinderCount = 5;

/// The finder's name on command lines and in benchmarks.
inline const char* rootFinderName(RootFinder finder)
{
  switch (finder)
  {
    case RootFinder::Subdivision:
      return "subdivision";
    case RootFinder::KnotInsertion:
      return "knot-insertion";
    case RootFinder::BezierClipping:
      return "bezier-clipping";
    case RootFinder::PointInsertion:
      return "point-insertion";
    case RootFinder::PolarNewton:
      return "polar-newton";
  }
  return "unknown";
}

/// The finder of that name (rootFinderName's inverse); std::invalid_argument listing the names
/// otherwise.
inline RootFinder parseRootFinder(const std::string& name)
{
  std::string names;
  for (int f = 0; f < kRootFinderCount; ++f)
  {
    if (name == rootFinderName(RootFinder(f)))
    {
      return RootFinder(f);
    }
    names += std::string(f ? ", " : "") + rootFinderName(RootFinder(f));
  }
  throw std::invalid_argument("root finder '" + name + "' is none of " + names);
}

struct RootSettings
{
  double tolerance = 1e-12;        ///< parametric width that ends a root's search
  double merge = 1e-9;             ///< roots closer than this are one
  bool evenRoots = true;           ///< also the roots where the polynomial touches zero
  int maxSplits = 4096;            ///< splits or clips of one search (then the result is capped)
  int maxRoots = roots::kMaxRoots; ///< the nearest roots wanted (one for a first hit): the
                                   ///< search stops once it has them
};

/// Roots found, sorted; `identicallyZero` when every coefficient is zero (every t is a root,
/// none listed); `invalid` when the degree is outside 0..16 or a coefficient is not finite.
struct BernsteinRoots : roots::RootList
{
  bool identicallyZero = false;
  bool invalid = false;
};

namespace detail
{
/// Appends the interior roots of odd multiplicity of `piece` found by `finder`.
IGA_HD inline void oddRoots(const roots::Piece& piece, RootFinder finder,
  const roots::RootContext& context, roots::RootList& out)
{
  switch (finder)
  {
    case RootFinder::Subdivision:
      return roots::splitSearch(piece, context, roots::MidpointCut(), out);
    case RootFinder::KnotInsertion:
      return roots::splitSearch(piece, context, roots::KnotInsertionCut(), out);
    case RootFinder::BezierClipping:
      return roots::splitSearch(piece, context, roots::HullCut(), out);
    case RootFinder::PointInsertion:
      return roots::splitSearch(piece, context, roots::PolygonZeroCut(), out);
    case RootFinder::PolarNewton:
      return roots::polarNewtonRoots(piece, context, false, out);
  }
}

/// Merges even roots into the odd ones, sorted: odd roots within cluster[j] of even root j are
/// the rounding's split of it and give way.
IGA_HD inline void mergeEvenRoots(
  roots::RootList& odd, const roots::RootList& even, const double* cluster, double merge)
{
  roots::RootList merged;
  merged.cost = odd.cost;
  int i = 0, j = 0;
  while (i < odd.count || j < even.count)
  {
    const bool takeEven = j < even.count && (i >= odd.count || even.t[j] <= odd.t[i]);
    if (takeEven)
    {
      while (merged.count > 0 && even.t[j] - merged.t[merged.count - 1] <= cluster[j])
      {
        --merged.count; // odd roots just left of it
      }
      merged.add(even.t[j], merge);
      while (i < odd.count && odd.t[i] - even.t[j] <= cluster[j])
      {
        ++i; // and just right of it
      }
      ++j;
    }
    else
    {
      merged.add(odd.t[i++], merge);
    }
  }
  odd = merged;
}
/// A root found to the finder's tolerance, polished by Newton's method on `piece` while the
/// steps stay within `limit` (beyond that the root is not simple enough to trust it).
IGA_HD inline double polishRoot(
  const roots::Piece& piece, double t, double limit, long& evaluations)
{
  for (int k = 0; k < 4; ++k)
  {
    double f, slope;
    roots::valueAndSlope(piece, t, f, slope);
    ++evaluations;
    const double step = slope != 0 ? f / slope : 0;
    const double next = minValue(maxValue(t - step, 0.0), 1.0);
    if (!(absValue(step) <= limit) || next == t)
    {
      break; // a step that moves nothing would be the same again
    }
    t = next;
  }
  return t;
}

/// Whether the odd roots' search proves that no even root is to be looked for: each piece it
/// dropped stayed beyond rounding from zero or had no critical point (holdsNoEvenRoot), over the
/// whole segment or, where it stopped at its last root, up to that root with the derivative
/// keeping one sign within a cluster (1e-3) on either side of it. A critical point within a
/// root's own narrow piece would lie within the tolerance of that root.
IGA_HD inline bool noEvenRoots(const roots::Piece& piece, const roots::RootList& odd,
  bool truncated, const roots::RootContext& context)
{
  if (odd.touched || odd.cost.capped)
  {
    return false;
  }
  if (!truncated)
  {
    return true;
  }
  const double last = odd.t[odd.count - 1];
  const double a = maxValue(last - 1e-3, 0.0), b = minValue(last + 1e-3, 1.0);
  roots::Piece slope = roots::derivativeOf(piece);
  roots::normalise(slope);
  return roots::keepsOneSign(roots::clipPiece(slope, a, b), context.zero);
}

/// The roots inside (0, 1) of `piece` (end coefficients nonzero), sorted, the first
/// context.limit of them or fewer; `truncated` when the search stopped at its limit, so that
/// more may follow.
IGA_HD inline roots::RootList interiorRoots(const roots::Piece& piece, RootFinder finder,
  bool evenRoots, const roots::RootContext& context, bool& truncated)
{
  roots::RootList inside;
  if (finder == RootFinder::PolarNewton)
  {
    roots::polarNewtonRoots(piece, context, evenRoots, inside);
  }
  else
  {
    oddRoots(piece, finder, context, inside);
  }
  truncated = inside.count >= context.limit;
  for (int k = 0; finder != RootFinder::PolarNewton && k < inside.count; ++k)
  {
    inside.t[k] = polishRoot(piece, inside.t[k], 1e-6, inside.cost.evaluations);
  }
  if (evenRoots && finder != RootFinder::PolarNewton && piece.degree > 1 &&
      !noEvenRoots(piece, inside, truncated, context))
  {
    // Critical points: the derivative's roots of odd multiplicity, inside (0, 1).
    // An even root matters left of the last odd root kept, or within a cluster (below) of it.
    roots::RootList critical, even;
    roots::RootContext criticalContext = context;
    criticalContext.limit = roots::kMaxRoots;
    criticalContext.until = truncated ? inside.t[inside.count - 1] + 1e-3 : 1;
    const roots::Piece slope = roots::normalised(roots::derivativeOf(piece));
    const roots::Piece curvature = roots::derivativeOf(roots::derivativeOf(piece));
    oddRoots(slope, finder, criticalContext, critical);
    double cluster[roots::kMaxRoots];
    for (int k = 0; k < critical.count; ++k)
    {
      const double p = polishRoot(slope, critical.t[k], 1e-6, inside.cost.evaluations);
      if (roots::signOf(roots::evaluatePiece(piece, p), context.zero) == 0 &&
          even.count < roots::kMaxRoots)
      {
        // Where |f| <= zero about p: the rounding may show two roots anywhere in it.
        const double a = 0.5 * absValue(roots::evaluatePiece(curvature, p));
        cluster[even.count] = a > 0 ? minValue(2 * squareRoot(context.zero / a), 1e-3) : 1e-3;
        even.add(p, context.merge);
      }
    }
    inside.cost.insertions += critical.cost.insertions;
    inside.cost.evaluations += critical.cost.evaluations + critical.count;
    inside.cost.capped = inside.cost.capped || critical.cost.capped;
    mergeEvenRoots(inside, even, cluster, context.merge);
  }
  return inside;
}

/// The polynomial as a piece scaled to unit size and the search's context; false where
/// `result` already says all: a bad degree or coefficient, or every coefficient zero.
IGA_HD inline bool rootProblem(const double* c, int degree, const RootSettings& settings,
  BernsteinRoots& result, roots::Piece& piece, roots::RootContext& context)
{
  if (degree < 0 || degree > kMaxDegree)
  {
    result.invalid = true;
    return false;
  }
  piece.degree = degree;
  double largest = 0;
  for (int i = 0; i <= degree; ++i)
  {
    result.invalid = result.invalid || !isFinite(c[i]);
    largest = maxValue(largest, absValue(c[i]));
    piece.c[i] = c[i];
  }
  result.identicallyZero = !result.invalid && largest == 0;
  context.tolerance = settings.tolerance;
  context.merge = settings.merge;
  context.maxSplits = settings.maxSplits;
  context.limit = settings.maxRoots;
  context.zero = 32.0 * (degree + 1) * Epsilon<double>::value;
  roots::normalise(piece);
  return !result.invalid && !result.identicallyZero;
}

/// The roots in [0, 1] of the problem rootProblem prepared (`piece`, `context`), the first
/// context.limit of them, added to `result`; roots at the ends are divided out of `piece`.
IGA_HD inline void rootsOf(roots::Piece& piece, roots::RootContext context, RootFinder finder,
  bool evenRoots, BernsteinRoots& result)
{
  // Coefficients of one sign beyond rounding bound the polynomial away from zero: no root at
  // all (most rays through a patch's box miss its surface).
  if (roots::keepsOneSign(piece, context.zero))
  {
    return;
  }
  // Roots at the ends, divided out: t g(t) has c_{i+1} = g_i (i + 1) / d, (1 - t) h(t) has
  // c_i = h_i (d - i) / d. Each division leaves the polynomial's other roots in place.
  bool atZero = false, atOne = false;
  while (piece.degree > 0 && roots::signOf(piece.c[0], context.zero) == 0)
  {
    atZero = true;
    for (int i = 0; i < piece.degree; ++i)
    {
      piece.c[i] = piece.c[i + 1] * piece.degree / (i + 1);
    }
    --piece.degree;
    roots::normalise(piece);
  }
  while (piece.degree > 0 && roots::signOf(piece.c[piece.degree], context.zero) == 0)
  {
    atOne = true;
    for (int i = 0; i < piece.degree; ++i)
    {
      piece.c[i] = piece.c[i] * piece.degree / (piece.degree - i);
    }
    --piece.degree;
    roots::normalise(piece);
  }
  const int wanted = context.limit;
  if (atZero)
  {
    result.add(0.0, context.merge);
    context.limit -= 1;
  }
  bool truncated = context.limit <= 0; // roots beyond those found may exist
  if (piece.degree > 0 && !truncated)
  {
    roots::RootList inside = interiorRoots(piece, finder, evenRoots, context, truncated);
    if (truncated && inside.count < context.limit)
    {
      // Even roots took the place of odd ones (a double root's two sides): search them all.
      const roots::RootCost spent = inside.cost;
      context.limit = roots::kMaxRoots;
      inside = interiorRoots(piece, finder, evenRoots, context, truncated);
      inside.cost.insertions += spent.insertions;
      inside.cost.evaluations += spent.evaluations;
    }
    for (int k = 0; k < inside.count && result.count < wanted; ++k)
    {
      if (inside.t[k] > 0 && inside.t[k] < 1)
      {
        result.add(inside.t[k], context.merge);
      }
    }
    result.cost.insertions += inside.cost.insertions;
    result.cost.evaluations += inside.cost.evaluations;
    result.cost.capped = inside.cost.capped;
  }
  if (atOne && !truncated)
  {
    result.add(1.0, context.merge);
  }
}
} // namespace detail

/// The roots in [0, 1] of sum c_i B_i^degree(t), the first settings.maxRoots of them.
IGA_HD inline BernsteinRoots findBernsteinRoots(
  const double* c, int degree, RootFinder finder, const RootSettings& settings = {})
{
  BernsteinRoots result;
  roots::Piece piece;
  roots::RootContext context;
  if (detail::rootProblem(c, degree, settings, result, piece, context))
  {
    detail::rootsOf(piece, context, finder, settings.evenRoots, result);
  }
  return result;
}

/// Frame coherency: the nearest root in [0, 1] where a guess of it is at hand (the previous
/// frame's hit near the ray). The guess is taken only where it is proved: on [0, a] the
/// polynomial keeps one sign beyond rounding, on [a, b] it changes sign and its derivative keeps
/// one (a single simple root), a and b the guess -+ halfWidth; that root, by Newton in the
/// bracket, is then the nearest. Elsewhere the finder's search for the nearest root (`seeded`
/// false).
IGA_HD inline BernsteinRoots findNearestRoot(const double* c, int degree, double guess,
  double halfWidth, RootFinder finder, const RootSettings& settings, bool& seeded)
{
  BernsteinRoots result;
  roots::Piece piece, before, rest, middle, after;
  roots::RootContext context;
  const double a = maxValue(guess - halfWidth, 0.0), b = minValue(guess + halfWidth, 1.0);
  seeded = false;
  if (detail::rootProblem(c, degree, settings, result, piece, context) && a < b)
  {
    roots::splitPiece(piece, a, before, rest);
    roots::splitPiece(rest, (b - a) / (1 - a), middle, after);
    result.cost.insertions += 2 * degree;
    const int ends =
      roots::signOf(middle.c[0], context.zero) * roots::signOf(middle.c[degree], context.zero);
    seeded = (a == 0 || roots::keepsOneSign(before, context.zero)) && ends < 0 &&
             roots::slopeKeepsOneSign(middle, context.zero);
  }
  if (!seeded)
  {
    if (!result.invalid && !result.identicallyZero)
    {
      context.limit = 1;
      detail::rootsOf(piece, context, finder, settings.evenRoots, result);
    }
    return result;
  }
  const double s =
    roots::detail::bracketedRoot(middle, 0, 1, middle.c[0], middle.c[degree], context, result.cost);
  result.add(roots::globalOf(middle, s), context.merge);
  return result;
}

} // namespace iga
