// CSG frames: the Boolean combination of attribute solids, domains and half-spaces (iga/Csg.h)
// drawn exactly per pixel. Every operand's surfaces are found by all-hits engine frames (an
// attribute's isosurfaces, the inputs' boundaries, a plane's section of the volumes), merged
// along each ray, and classified: a hit is a surface of the result where the result's inside
// changes.
#pragma once

#include "iga/Boundary.h"
#include "iga/Csg.h"
#include "iga/sst/Engine.h"

#include <array>
#include <string>
#include <vector>

namespace iga
{
namespace sst
{

/// One input of a CSG frame: volumes (each conforming block closed by its boundary faces) and
/// the names of their attributes, attribute k in channel kFirstAttributeChannel + k. Attributes
/// must be continuous across the patches' shared faces: their signs carry over from patch to
/// patch along a ray.
struct CsgInput
{
  const std::vector<BezierVolume<double>>* volumes = nullptr;
  std::vector<std::string> attributes;
  /// The volumes' boundary faces (boundaryFaces), found from the volumes when null: a caller
  /// drawing a deforming input keeps them, as the topology decides them.
  const std::vector<PatchFace>* boundary = nullptr;
};

/// What a CSG frame draws: the expression's result (none for an empty expression, root -1) and
/// slices.
struct CsgScene
{
  std::vector<CsgInput> inputs;
  csg::Expression expression;
  /// Planes (a, b, c, d): each drawn where a x + b y + c z + d = 0 in the volumes, with the
  /// result, whatever the expression.
  std::vector<std::array<double, 4>> slices;
  /// The attribute sampled at each hit (Hit::color), by name; empty for none. An input
  /// without it gives NaN.
  std::string colorAttribute;
};

/// Draws the scene's result and slices. `settings` as for render, except that its isovalues,
/// surface and colour attributes are the scene's; firstHitOnly keeps the nearest surface per
/// pixel, else all of them, front to back. Clipping planes cut what is drawn, not the operands.
/// The G-buffer's hits: Hit::patch numbers the inputs' volumes in one sequence (input 0's
/// first), Hit::uvw is the parameter in that volume (on its face for a boundary hit);
/// Hit::isovalue is, on the result's surfaces, the operand whose solid the result enters or
/// leaves there, and Hit::entersBelow whether the ray enters the result; on slice s it is the
/// number of operands plus s, and entersBelow whether the ray passes to the plane's positive
/// side. FrameReport::peakBytes is the largest pass's working set plus every pass's G-buffer and
/// derived patches (kept until the classification); Settings::memoryBudgetBytes caps each pass.
/// Throws std::invalid_argument for bad input: an attribute no input holds
/// (csg::ExpressionError at the operand's position), a surface among the volumes, boundary
/// faces naming no face, an unsound expression (csg::checkExpression), a slice or clipping
/// plane that is not a plane, and what render throws for the passes' patches.
FrameReport renderCsg(
  const CsgScene& scene, const View& view, const Settings& settings, Method method, GBuffer& out);

} // namespace sst
} // namespace iga
