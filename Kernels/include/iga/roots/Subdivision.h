// De Casteljau subdivision at the midpoint (Lane and Riesenfeld; Schneider's Graphics Gems
// root finder): linear convergence, the reference the others are measured against.
#pragma once

#include "iga/roots/SplitSearch.h"

namespace iga
{
namespace roots
{

struct MidpointCut
{
  IGA_HD Cut operator()(const Piece&, const RootContext&, RootCost&) const
  {
    return Cut{ false, 0.5, 0.0 };
  }
};

} // namespace roots
} // namespace iga
