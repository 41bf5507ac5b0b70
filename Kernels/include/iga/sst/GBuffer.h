// What the isosurface engine gives back: per pixel its hits, sorted front to back. A header of
// its own so that code which only reads or writes G-buffers needs nothing of the engine.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace iga
{
namespace sst
{

/// One ray/isosurface intersection.
struct Hit
{
  double ndcDepth;     ///< NDC depth in [-1, 1]; window depth is (ndcDepth + 1) / 2
  double eyeDepth;     ///< distance from the eye along the view direction
  glm::dvec3 position; ///< world position
  glm::dvec3 normal;   ///< unit world normal of the isosurface, facing the viewer
  glm::dvec3 uvw;      ///< parameter in the input patch
  int patch;           ///< input patch index
  int isovalue;        ///< index into Settings::isovalues
  /// Whether the ray enters the region below the isovalue here (the attribute decreases along
  /// the ray), else it leaves it: what CSG and transparency classify hits by.
  bool entersBelow;
  double color; ///< colour attribute at the hit (NaN without one)
};

/// Per pixel, all hits sorted front to back. Pixel (i, j) has index j * width + i, row 0 at the
/// bottom (OpenGL and VTK convention), and samples the ray through the pixel's centre.
struct GBuffer
{
  int width = 0;
  int height = 0;
  std::vector<uint32_t> offsets; ///< width * height + 1 entries into hits
  std::vector<Hit> hits;

  const Hit* firstHit(int i, int j) const
  {
    const size_t p = size_t(j) * width + i;
    return offsets[p] < offsets[p + 1] ? &hits[offsets[p]] : nullptr;
  }
  int hitCount(int i, int j) const
  {
    const size_t p = size_t(j) * width + i;
    return int(offsets[p + 1] - offsets[p]);
  }
  size_t coveredPixels() const
  {
    size_t covered = 0;
    for (size_t p = 0; p + 1 < offsets.size(); ++p)
    {
      covered += offsets[p + 1] > offsets[p] ? 1 : 0;
    }
    return covered;
  }
};

} // namespace sst
} // namespace iga
