// CSG frames with their passes drawn by a given renderer: the device driver's tests run them on
// the driver they check.
#pragma once

#include "iga/sst/Csg.h"

#include <functional>

namespace iga
{
namespace sst
{

/// Draws one pass of a CSG frame: the scene's patches with the pass's settings.
using CsgPassRenderer =
  std::function<FrameReport(const Scene& scene, const Settings& settings, GBuffer& out)>;

/// renderCsg with every pass drawn by `renderPass`.
FrameReport renderCsg(const CsgScene& scene, const View& view, const Settings& settings,
  const CsgPassRenderer& renderPass, GBuffer& out);

} // namespace sst
} // namespace iga
