// What every root finder of a univariate Bernstein polynomial shares: the coefficients of a
// piece of [0, 1], de Casteljau splits and evaluation, sign tests with a rounding tolerance, the
// zero of the control polygon, and the sorted list the roots go to.
#pragma once

#include "iga/Portability.h"

namespace iga
{
namespace roots
{

constexpr int kMaxRoots = kMaxDegree;

/// A polynomial of degree `degree` on the piece [lo, hi] of [0, 1], in the Bernstein basis of
/// that piece. The coefficients past the degree are left unset (a search's stack of pieces would
/// otherwise clear kilobytes a ray).
struct Piece
{
  int degree = 0;
  double lo = 0, hi = 1;
  double c[kMaxOrder];
};

/// What a finder needs to know of the problem beyond its piece.
struct RootContext
{
  double zero = 0;       ///< coefficients and values within it count as zero (rounding)
  double tolerance = 0;  ///< parametric width below which a piece holds one root
  double merge = 0;      ///< roots closer than this are one (found from both sides of a cut)
  int maxSplits = 0;     ///< splits (or insertions) allowed for the whole polynomial
  int limit = kMaxRoots; ///< the search stops once it has found this many roots (the nearest)
  double until = 1;      ///< nor does it look for roots beyond this parameter
};

/// Cost of a search, in the units of Reimers and Seland's Table 2: a de Casteljau split of a
/// degree-d piece counts d knot insertions; `evaluations` counts polynomial evaluations
/// (Newton and regula falsi).
struct RootCost
{
  long insertions = 0;
  long evaluations = 0;
  bool capped = false; ///< the split budget ran out: roots may be missing
};

/// The roots found, sorted, and how they were found.
struct RootList
{
  int count = 0;
  double t[kMaxRoots] = {};
  RootCost cost;
  /// A piece the search dropped may hold an even root (holdsNoEvenRoot failed): without that,
  /// the polynomial has none wherever the search looked but within its roots' narrow pieces.
  bool touched = false;

  /// Appends t unless it lies within `merge` of the last root (a root met at a split point is
  /// seen by both sides).
  IGA_HD void add(double root, double merge)
  {
    if (count > 0 && root - t[count - 1] <= merge)
    {
      return;
    }
    if (count < kMaxRoots)
    {
      t[count++] = root;
    }
  }
};

/// Copies a piece coefficient by coefficient, its degree + 1 of them: copying the whole struct
/// right after its coefficients were stored one by one stalls on store forwarding (a tenth of
/// the search, measured).
IGA_HD inline void copyPiece(const Piece& from, Piece& to)
{
  to.degree = from.degree;
  to.lo = from.lo;
  to.hi = from.hi;
  for (int i = 0; i <= from.degree; ++i)
  {
    to.c[i] = from.c[i];
  }
}

/// One de Casteljau level in place: work[i] = (1 - s) work[i] + s work[i + 1] for i < count.
/// work[i + 1] is read once and carried: loading work[i] and work[i + 1] together right after
/// storing work[i] stalls the store buffer (a third of the finders' time, measured).
IGA_HD inline void deCasteljauLevel(double* work, int count, double s)
{
  double current = work[0];
  for (int i = 0; i < count; ++i)
  {
    const double next = work[i + 1];
    work[i] = (1 - s) * current + s * next;
    current = next;
  }
}

/// The value of the piece's polynomial at local parameter s in [0, 1] (de Casteljau).
IGA_HD inline double evaluatePiece(const Piece& piece, double s)
{
  double work[kMaxOrder];
  for (int i = 0; i <= piece.degree; ++i)
  {
    work[i] = piece.c[i];
  }
  for (int r = 1; r <= piece.degree; ++r)
  {
    deCasteljauLevel(work, piece.degree - r + 1, s);
  }
  return work[0];
}

/// Value and derivative (per unit of local parameter) by de Casteljau.
IGA_HD inline void valueAndSlope(const Piece& piece, double s, double& value, double& slope)
{
  const int d = piece.degree;
  double work[kMaxOrder];
  for (int i = 0; i <= d; ++i)
  {
    work[i] = piece.c[i];
  }
  for (int r = 1; r < d; ++r)
  {
    deCasteljauLevel(work, d - r + 1, s);
  }
  value = d > 0 ? (1 - s) * work[0] + s * work[1] : work[0];
  slope = d > 0 ? d * (work[1] - work[0]) : 0;
}

/// Splits a piece at local parameter s into [lo, x] and [x, hi], x = lo + s (hi - lo). `right`
/// may be the piece itself.
IGA_HD inline void splitPiece(const Piece& piece, double s, Piece& left, Piece& right)
{
  const int d = piece.degree;
  const double lo = piece.lo, hi = piece.hi, x = lo + s * (hi - lo);
  double work[kMaxOrder];
  for (int i = 0; i <= d; ++i)
  {
    work[i] = piece.c[i];
  }
  left.degree = right.degree = d;
  left.lo = lo;
  left.hi = right.lo = x;
  right.hi = hi;
  left.c[0] = work[0];
  right.c[d] = work[d];
  for (int r = 1; r <= d; ++r)
  {
    deCasteljauLevel(work, d - r + 1, s);
    left.c[r] = work[0];
    right.c[d - r] = work[d - r];
  }
}

/// The piece restricted to local [a, b] (two splits).
IGA_HD inline Piece clipPiece(const Piece& piece, double a, double b)
{
  Piece left, middle, rest;
  splitPiece(piece, b, left, rest);
  splitPiece(left, b > 0 ? a / b : 0, rest, middle);
  return middle;
}

/// The sign of a coefficient, 0 within the zero tolerance.
IGA_HD inline int signOf(double v, double zero)
{
  return v > zero ? 1 : (v < -zero ? -1 : 0);
}

/// Whether the nonzero coefficients take both signs: without that the piece holds no root of
/// odd multiplicity inside (variation diminishing).
IGA_HD inline bool changesSign(const Piece& piece, double zero)
{
  bool positive = false, negative = false;
  for (int i = 0; i <= piece.degree; ++i)
  {
    const int s = signOf(piece.c[i], zero);
    positive = positive || s > 0;
    negative = negative || s < 0;
  }
  return positive && negative;
}

/// Whether every coefficient keeps one sign beyond rounding: the polynomial is bounded away
/// from zero on the piece.
IGA_HD inline bool keepsOneSign(const Piece& piece, double zero)
{
  bool positive = true, negative = true;
  for (int i = 0; i <= piece.degree; ++i)
  {
    positive = positive && piece.c[i] > zero;
    negative = negative && piece.c[i] < -zero;
  }
  return positive || negative;
}

/// The smallest zero of the control polygon (points (i/d, c_i)) in local [0, 1] at a strict sign
/// change of the nonzero coefficients; -1 without one.
IGA_HD inline double firstPolygonZero(const Piece& piece, double zero)
{
  const int d = piece.degree;
  int last = -1;
  for (int i = 0; i <= d; ++i)
  {
    if (signOf(piece.c[i], zero) == 0)
    {
      continue;
    }
    if (last >= 0 && signOf(piece.c[i], zero) != signOf(piece.c[last], zero))
    {
      const double x0 = double(last) / d, x1 = double(i) / d;
      return x0 + (x1 - x0) * piece.c[last] / (piece.c[last] - piece.c[i]);
    }
    last = i;
  }
  return -1;
}

/// The derivative's coefficients (degree d - 1, on the same piece, per unit of local parameter).
IGA_HD inline Piece derivativeOf(const Piece& piece)
{
  Piece derivative;
  derivative.degree = piece.degree - 1;
  derivative.lo = piece.lo;
  derivative.hi = piece.hi;
  for (int i = 0; i < piece.degree; ++i)
  {
    derivative.c[i] = piece.degree * (piece.c[i + 1] - piece.c[i]);
  }
  return derivative;
}

/// Scales the piece so that its largest coefficient has magnitude 1 (zero stays zero).
IGA_HD inline void normalise(Piece& piece)
{
  double largest = 0;
  for (int i = 0; i <= piece.degree; ++i)
  {
    largest = maxValue(largest, absValue(piece.c[i]));
  }
  for (int i = 0; largest > 0 && i <= piece.degree; ++i)
  {
    piece.c[i] /= largest;
  }
}

/// The piece scaled as `normalise` scales it.
IGA_HD inline Piece normalised(Piece piece)
{
  normalise(piece);
  return piece;
}

/// Whether the derivative, scaled as `normalised` scales it, keeps one sign beyond rounding
/// (keepsOneSign(normalised(derivativeOf(piece)))), without building those pieces.
IGA_HD inline bool slopeKeepsOneSign(const Piece& piece, double zero)
{
  const int d = piece.degree;
  double slope[kMaxOrder];
  double largest = 0;
  for (int i = 0; i < d; ++i)
  {
    slope[i] = d * (piece.c[i + 1] - piece.c[i]);
    largest = maxValue(largest, absValue(slope[i]));
  }
  bool positive = largest > 0, negative = largest > 0;
  for (int i = 0; i < d && largest > 0; ++i)
  {
    positive = positive && slope[i] / largest > zero;
    negative = negative && slope[i] / largest < -zero;
  }
  return positive || negative;
}

/// Whether the piece provably holds no even root: it stays beyond rounding from zero, or its
/// derivative keeps one sign (no critical point).
IGA_HD inline bool holdsNoEvenRoot(const Piece& piece, double zero)
{
  return keepsOneSign(piece, zero) || (piece.degree > 0 && slopeKeepsOneSign(piece, zero));
}

/// The global parameter of local s.
IGA_HD inline double globalOf(const Piece& piece, double s)
{
  return piece.lo + s * (piece.hi - piece.lo);
}

} // namespace roots
} // namespace iga
