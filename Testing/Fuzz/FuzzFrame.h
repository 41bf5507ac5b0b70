// The small frame the engine's fuzz targets draw: 12x10 pixels on one CPU thread, seen from
// (3, -4, 2.5) with the clipping range fitted to the box [-1, 1]^3.
#pragma once

#include "iga/Camera.h"
#include "iga/sst/Engine.h"

#include <cstddef>

inline iga::Camera fuzzBoxCamera()
{
  iga::Camera camera;
  camera.position = { 3, -4, 2.5 };
  camera.viewUp = { 0, 0, 1 };
  const double bounds[6] = { -1, 1, -1, 1, -1, 1 };
  iga::fitClippingRange(camera, bounds);
  return camera;
}

/// First-hit or all hits by the input's size.
inline iga::sst::Settings fuzzFrameSettings(size_t size)
{
  iga::sst::Settings settings;
  settings.width = 12;
  settings.height = 10;
  settings.threads = 1;
  settings.firstHitOnly = size % 2 == 0;
  return settings;
}
