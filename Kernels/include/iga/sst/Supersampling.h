// Silhouette anti-aliasing by rotated-grid supersampling (Wei and Feng's RGSS, four samples a
// pixel): the pixels whose shaded colour differs from a neighbour's (Reimers and Seland's test)
// are drawn again at four offsets within the pixel, on every path of the engine, and their
// colour becomes the mean of the samples' (a sample that misses adds nothing: coverage).
#pragma once

#include "iga/sst/Engine.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace iga
{
namespace sst
{

constexpr int kRotatedGridSamples = 4;

/// The samples' offsets from a pixel's centre, in pixels: one in each row and each column of a
/// 4 x 4 grid, so that a near-horizontal or near-vertical edge crossing the pixel meets them
/// at four heights (a 2 x 2 grid would give two).
constexpr double kRotatedGridOffsets[kRotatedGridSamples][2] = { { 0.125, 0.375 },
  { 0.375, -0.125 }, { -0.125, -0.375 }, { -0.375, 0.125 } };

/// The view moved by (dx, dy) pixels in the image plane of a width x height image: its pixel
/// (i, j) samples the ray through the point (i + 0.5 + dx, j + 0.5 + dy) of the window.
View offsetView(const View& view, int width, int height, double dx, double dy);

/// Per pixel of a width x height premultiplied RGBA image, 1 where its colour differs from one
/// of its four neighbours' by more than `threshold` in some channel, for both pixels of such a
/// pair: a silhouette, a boundary or a colour edge passes between them. A hit beside a miss
/// always differs (in alpha).
std::vector<uint8_t> contrastingPixels(
  const std::vector<float>& rgba, int width, int height, float threshold);

/// Draws one frame of `settings` for a view into a G-buffer: how a caller renders its scene
/// (plain, NURBS or CSG).
using FrameRenderer = std::function<FrameReport(const View&, const Settings&, GBuffer&)>;

/// The rotated-grid samples of the pixels where `mask` is non-zero: sample k is the frame drawn
/// again through `renderFrame` with the view moved by kRotatedGridOffsets[k], every other pixel
/// skipped (its far depth below -1) and no seed frame. Returns the passes' report.
FrameReport renderRotatedGridSamples(const View& view, const Settings& settings,
  const std::vector<uint8_t>& mask, const FrameRenderer& renderFrame,
  std::array<GBuffer, kRotatedGridSamples>& samples);

} // namespace sst
} // namespace iga
