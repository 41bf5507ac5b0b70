// A named engine scene (patches, camera, settings) and how the engine tests make one: a z-up
// camera at a position looking at a focal point, clipping planes around the data.
#pragma once

#include "iga/Datasets.h"
#include "iga/sst/Engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  std::vector<iga::BezierSurface<double>> surfaces;

  /// What the engine draws: the set's volumes and the surfaces.
  iga::sst::Scene patches() const { return iga::sst::Scene(this->set.patches, this->surfaces); }
};

inline iga::Camera lookAt(const iga::sst::Scene& patches, const glm::dvec3& position,
  const glm::dvec3& focal, double angle, const glm::dvec3& up = { 0, 0, 1 })
{
  iga::Camera camera;
  camera.position = position;
  camera.focalPoint = focal;
  camera.viewUp = up;
  camera.viewAngle = angle;
  double bounds[6];
  iga::sst::patchBounds(patches, bounds);
  iga::fitClippingRange(camera, bounds);
  return camera;
}

inline iga::Camera lookAt(const iga::VolumeSet<double>& set, const glm::dvec3& position,
  const glm::dvec3& focal, double angle, const glm::dvec3& up = { 0, 0, 1 })
{
  return lookAt(iga::sst::Scene(set.patches), position, focal, angle, up);
}

inline Scene scene(const std::string& name, iga::VolumeSet<double> set, const glm::dvec3& position,
  const glm::dvec3& focal, double angle, int width, int height, std::vector<double> isovalues)
{
  Scene s{ name, std::move(set), {}, {}, {} };
  s.camera = lookAt(s.set.patches, position, focal, angle);
  s.settings.width = width;
  s.settings.height = height;
  s.settings.isovalues = std::move(isovalues);
  return s;
}

/// Whether two G-buffers hold the same hits bit for bit (field by field: Hit has padding).
inline ::testing::AssertionResult identicalGBuffers(
  const iga::sst::GBuffer& one, const iga::sst::GBuffer& two)
{
  if (one.offsets != two.offsets)
    return ::testing::AssertionFailure() << "the pixels' hit counts differ";
  for (size_t h = 0; h < one.hits.size(); ++h)
  {
    const iga::sst::Hit &a = one.hits[h], &b = two.hits[h];
    if (a.ndcDepth != b.ndcDepth || a.eyeDepth != b.eyeDepth || a.patch != b.patch ||
        a.isovalue != b.isovalue || a.entersBelow != b.entersBelow || a.position != b.position ||
        a.normal != b.normal || a.uvw != b.uvw ||
        !(a.color == b.color || (a.color != a.color && b.color != b.color)))
      return ::testing::AssertionFailure() << "hit " << h << " differs";
  }
  return ::testing::AssertionSuccess();
}

/// Largest depth difference between two G-buffers' first hits and the pixels covered by one only.
inline void expectSameFirstHits(const iga::sst::GBuffer& a, const iga::sst::GBuffer& b,
  int allowedCoverageDifferences, double depthTolerance)
{
  int differ = 0, both = 0;
  double maxDepth = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i)
    {
      const auto *ha = a.firstHit(i, j), *hb = b.firstHit(i, j);
      if ((ha != nullptr) != (hb != nullptr))
      {
        ++differ;
        continue;
      }
      if (ha)
      {
        ++both;
        maxDepth = std::max(maxDepth, std::abs(ha->eyeDepth - hb->eyeDepth));
      }
    }
  EXPECT_LE(differ, allowedCoverageDifferences);
  EXPECT_GT(both, 100);
  EXPECT_LT(maxDepth, depthTolerance);
}

/// Brute force (multi-start Newton in uniform leaves, all-hits mode) finds no root the trees
/// (all-hits mode) miss, and misses few of theirs; at least `atLeast` roots in common. Roots
/// count as the same within `depthTolerance` in eye depth (grazing rays' roots are the least
/// accurate along the ray).
inline void expectBruteForceWithinTrees(const iga::sst::GBuffer& sst,
  const iga::sst::GBuffer& brute, int atLeast, double depthTolerance = 1e-6)
{
  int found = 0, missing = 0;
  for (size_t p = 0; p + 1 < sst.offsets.size(); ++p)
  {
    for (uint32_t b = brute.offsets[p]; b < brute.offsets[p + 1]; ++b)
    {
      bool present = false;
      for (uint32_t s = sst.offsets[p]; s < sst.offsets[p + 1]; ++s)
        present =
          present || std::abs(sst.hits[s].eyeDepth - brute.hits[b].eyeDepth) < depthTolerance;
      EXPECT_TRUE(present) << "pixel " << p << " depth " << brute.hits[b].eyeDepth;
      found += present;
    }
    missing +=
      int(sst.offsets[p + 1] - sst.offsets[p]) - int(brute.offsets[p + 1] - brute.offsets[p]);
  }
  EXPECT_GT(found, atLeast);
  EXPECT_LE(missing, int(sst.hits.size() / 50));
}

} // namespace igatest
