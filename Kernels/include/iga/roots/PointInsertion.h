// Bézier point insertion (Wei and Feng 2014, Algorithm 1 and 2): de Casteljau subdivision at the
// first zero of the control polygon, the left part first. The split point converges
// quadratically to a simple root (it is Mørken and Reimers' knot insertion with the knot
// inserted d times), and the value there reaching zero ends the search for that root.
#pragma once

#include "iga/roots/SplitSearch.h"

namespace iga
{
namespace roots
{

struct PolygonZeroCut
{
  IGA_HD Cut operator()(const Piece& piece, const RootContext& context, RootCost&) const
  {
    // Strictly inside, so that both parts are smaller than the piece.
    const double s = firstPolygonZero(piece, context.zero);
    return Cut{ false, minValue(maxValue(s, 1e-12), 1 - 1e-12), 0.0 };
  }
};

} // namespace roots
} // namespace iga
