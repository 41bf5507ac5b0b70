// De Casteljau subdivision at the midpoint (Lane and Riesenfeld; Schneider's Graphics Gems
// root finder): linear convergence, the reference the others are measured against.
#pragma once

#include "iga/roots/SplitSearch.h"

namespace iga
{
namespace roots
{

IGA_HD inline void subdivisionRoots(const Piece& whole, const RootContext& context, RootList& roots)
{
  splitSearch(
    whole, context,
    [](const Piece&) {
      return Cut{ false, 0.5, 0.0 };
    },
    roots);
}

} // namespace roots
} // namespace iga
