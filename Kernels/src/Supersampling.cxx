#include "iga/sst/Supersampling.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace iga
{
namespace sst
{

View offsetView(const View& view, int width, int height, double dx, double dy)
{
  // A translation of normalized device coordinates, applied to clip coordinates before the
  // division by w, so that it moves every depth's point by the same window offset: by -(dx, dy),
  // so that the pixel centres see what lay at +(dx, dy).
  View moved = view;
  const glm::dvec3 shift(-2.0 * dx / width, -2.0 * dy / height, 0.0);
  moved.worldToClip = glm::translate(glm::dmat4(1.0), shift) * view.worldToClip;
  return moved;
}

std::vector<uint8_t> contrastingPixels(
  const std::vector<float>& rgba, int width, int height, float threshold)
{
  const size_t pixels = size_t(width) * size_t(height);
  if (width < 0 || height < 0 || rgba.size() != 4 * pixels)
  {
    throw std::invalid_argument("an RGBA image of " + std::to_string(rgba.size()) +
                                " values is not " + std::to_string(width) + " x " +
                                std::to_string(height) + " pixels");
  }
  std::vector<uint8_t> mask(pixels, 0);
  const auto differ = [&](size_t a, size_t b)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (std::fabs(rgba[4 * a + c] - rgba[4 * b + c]) > threshold)
        return true;
    }
    return false;
  };
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const size_t p = size_t(j) * width + i;
      // Each pair once: the right and the upper neighbour.
      for (const size_t q : { i + 1 < width ? p + 1 : p, j + 1 < height ? p + width : p })
      {
        if (q != p && differ(p, q))
          mask[p] = mask[q] = 1;
      }
    }
  }
  return mask;
}

FrameReport renderRotatedGridSamples(const View& view, const Settings& settings,
  const std::vector<uint8_t>& mask, const FrameRenderer& renderFrame,
  std::array<GBuffer, kRotatedGridSamples>& samples)
{
  const size_t pixels = size_t(settings.width) * size_t(settings.height);
  if (mask.size() != pixels)
  {
    throw std::invalid_argument("a supersampling mask of " + std::to_string(mask.size()) +
                                " pixels for a frame of " + std::to_string(pixels));
  }
  Settings s = settings;
  s.seedFrame = nullptr;
  s.farDepths.resize(pixels, INFINITY);
  for (size_t p = 0; p < pixels; ++p)
  {
    if (!mask[p])
      s.farDepths[p] = -2.0;
  }
  FrameReport report;
  for (int k = 0; k < kRotatedGridSamples; ++k)
  {
    const View moved = offsetView(
      view, settings.width, settings.height, kRotatedGridOffsets[k][0], kRotatedGridOffsets[k][1]);
    addPassReport(report, renderFrame(moved, s, samples[size_t(k)]));
  }
  return report;
}

} // namespace sst
} // namespace iga
