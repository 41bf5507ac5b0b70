// A named engine scene (patches, camera, settings) and how the engine tests make one: a z-up
// camera at a position looking at a focal point, clipping planes around the data.
#pragma once

#include "iga/Datasets.h"
#include "iga/sst/Engine.h"

#include <string>
#include <utility>
#include <vector>

namespace igatest
{

struct Scene
{
  std::string name;
  iga::VolumeSet<double> set;
  iga::Camera camera;
  iga::sst::Settings settings;
};

inline iga::Camera lookAt(const iga::VolumeSet<double>& set, const glm::dvec3& position,
  const glm::dvec3& focal, double angle)
{
  iga::Camera camera;
  camera.position = position;
  camera.focalPoint = focal;
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngle = angle;
  double bounds[6];
  iga::sst::patchBounds(set.patches, bounds);
  iga::fitClippingRange(camera, bounds);
  return camera;
}

inline Scene scene(const std::string& name, iga::VolumeSet<double> set, const glm::dvec3& position,
  const glm::dvec3& focal, double angle, int width, int height, std::vector<double> isovalues)
{
  Scene s{ name, std::move(set), {}, {} };
  s.camera = lookAt(s.set, position, focal, angle);
  s.settings.width = width;
  s.settings.height = height;
  s.settings.isovalues = std::move(isovalues);
  return s;
}

} // namespace igatest
