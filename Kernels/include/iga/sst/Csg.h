// CSG frames: the Boolean combination of attribute solids, domains and half-spaces (iga/Csg.h)
// drawn exactly per pixel. Every operand's surfaces are found by all-hits engine frames (an
// attribute's isosurfaces, the inputs' boundaries, a plane's section of the volumes), merged
// along each ray, and classified: a hit is a surface of the result where the result's inside
// changes.
#pragma once

#include "iga/Boundary.h"
#include "iga/Csg.h"
#include "iga/sst/Engine.h"

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

/// What a CSG frame draws.
struct CsgScene
{
  std::vector<CsgInput> inputs;
  csg::Expression expression;
  /// The attribute sampled at each hit (Hit::color), by name; empty for none. An input
  /// without it gives NaN.
  std::string colorAttribute;
};

/// Draws the scene's result. `settings` as for render, except that its isovalues, surface and
/// colour attributes are the scene's; firstHitOnly keeps the result's nearest surface per
/// pixel, else all of them, front to back. The G-buffer's hits are the result's surfaces:
/// Hit::patch numbers the inputs' volumes in one sequence (input 0's first), Hit::uvw is the
/// parameter in that volume (on its face for a boundary hit), Hit::isovalue is the operand whose
/// solid the result enters or leaves there, Hit::entersBelow whether the ray enters the result.
/// Throws std::invalid_argument for bad input: an attribute no input holds (csg::ExpressionError
/// at the operand's position), and what render throws for the frames' patches.
FrameReport renderCsg(
  const CsgScene& scene, const View& view, const Settings& settings, Method method, GBuffer& out);

} // namespace sst
} // namespace iga
