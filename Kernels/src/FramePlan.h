// A frame's host-side preparation, shared by the CPU and CUDA drivers: input and settings
// checked, screen and shading patches made, and the subdivision-tree roots found.
#pragma once

#include "iga/sst/Engine.h"
#include "iga/sst/Tree.h"

#include <vector>

namespace iga
{
namespace sst
{

struct FramePlan
{
  FrameConstants frame{}; ///< its isovalues point into the settings
  Matrix4<double> windowFromWorld;
  int threads = 1;
  /// Roots (one per patch and isovalue with a possible sign change, in front of the eye) and
  /// their screen coefficients.
  std::vector<Node> initialNodes;
  std::vector<double> initialPool;
  /// Shading patches of the input patches, kShadeChannels per control point.
  std::vector<double> shadingPool;
  std::vector<size_t> shadingOffsets;
};

/// Throws std::invalid_argument naming the patch and the problem for bad input or settings.
/// Counts roots it cannot place in front of the eye in report.droppedAtEyePlane.
FramePlan planFrame(const std::vector<BezierVolume<double>>& patches, const View& view,
  const Settings& settings, FrameReport& report);

} // namespace sst
} // namespace iga
