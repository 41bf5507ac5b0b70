// The engine does not depend on units: engine scenes scaled by 1e-6 .. 1e6 (data, camera and
// clipping planes together), or with their attribute scaled, give the unscaled image, and data
// beyond what double precision frames gets one clear error.
#include "EngineScenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{

using iga::sst::GBuffer;
using iga::sst::Method;

using igatest::Scene;

std::vector<Scene> scenes()
{
  using igatest::scene;
  std::vector<Scene> all;
  all.push_back(scene("sphere p3", iga::makeMarsdenSphere<double>(3), { 1.2, -3.5, 2.1 },
    { 0.1, 0, 0 }, 40, 64, 48, { 0.0 }));
  all.push_back(scene("twisted tube, two isovalues", iga::makeTwistedTube<double>(0.7),
    { 3, -3.5, 3 }, { 0.2, 0, 1 }, 35, 64, 48, { 0.3, 0.6 }));
  all.push_back(scene("tube with a collapsed axis", iga::makeTube<double>(0.0, 0.0),
    { 1.9, -2.4, 3.6 }, { 0, 0, 1 }, 38, 64, 48, { 0.4 }));
  all.back().settings.surfaceAttribute = 1;
  all.push_back(scene("teardrop, all hits", iga::makeTeardrop<double>(1.2), { -0.2, -1.6, 0.9 },
    { -0.5, 0, 0 }, 40, 64, 48, { 0.0 }));
  all.back().settings.firstHitOnly = false;
  all.push_back(scene("sphere, clipping planes", iga::makeMarsdenSphere<double>(3),
    { 0.6, -4, 1.1 }, { 0, 0, 0 }, 35, 64, 48, { 0.0 }));
  all.back().settings.clipPlanes = { { 1, 0.2, 0, -0.1 }, { 0, 0, -2, 1 } };
  // A far camera with a narrow view: the distance is 1e5 times the data's size.
  all.push_back(scene("sphere p2 from afar", iga::makeMarsdenSphere<double>(2),
    { 1.2e5, -3.5e5, 2.1e5 }, { 0, 0, 0 }, 0.0006, 64, 48, { 0.0 }));
  return all;
}

/// The scene with its coordinates, camera and clipping planes times `s`.
Scene scaled(Scene scene, double s)
{
  for (auto& patch : scene.set.patches)
  {
    auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      for (int d = 0; d < 3; ++d)
        view.point(p)[d] *= s;
  }
  scene.camera.position *= s;
  scene.camera.focalPoint *= s;
  scene.camera.clippingRange[0] *= s;
  scene.camera.clippingRange[1] *= s;
  for (auto& plane : scene.settings.clipPlanes)
    plane[3] *= s;
  return scene;
}

/// The scene with its surface attribute (and isovalues) times `a`.
Scene attributeScaled(Scene scene, double a)
{
  const int channel = iga::kFirstAttributeChannel + scene.settings.surfaceAttribute;
  for (auto& patch : scene.set.patches)
  {
    auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      view.point(p)[channel] *= a;
  }
  for (double& iso : scene.settings.isovalues)
    iso *= a;
  return scene;
}

GBuffer render(const Scene& scene, iga::sst::FrameReport& report)
{
  GBuffer gbuffer;
  report = iga::sst::render(
    scene.set.patches, scene.camera, scene.settings, Method::SharedSubdivisionTree, gbuffer);
  return gbuffer;
}

/// Whether a pixel lies on the reference's silhouette: a neighbour's hit count differs.
bool onSilhouette(const GBuffer& g, int i, int j)
{
  for (const auto& [di, dj] :
    { std::pair{ 1, 0 }, std::pair{ -1, 0 }, std::pair{ 0, 1 }, std::pair{ 0, -1 } })
  {
    const int ni = i + di, nj = j + dj;
    if (ni >= 0 && nj >= 0 && ni < g.width && nj < g.height &&
        g.hitCount(ni, nj) != g.hitCount(i, j))
      return true;
  }
  return false;
}

/// Compares a frame of the scene at `s` (coordinates times s) with the unscaled one.
void expectSameFrame(const Scene& scene, const Scene& other, double s)
{
  iga::sst::FrameReport refReport, report;
  const GBuffer reference = render(scene, refReport);
  const GBuffer frame = render(other, report);
  ASSERT_EQ(refReport.unresolvedPixels, 0u);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  double bounds[6];
  iga::sst::patchBounds(scene.set.patches, bounds);
  const double size =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  int silhouetteMismatches = 0;
  double worstPosition = 0, worstNormal = 0;
  for (int j = 0; j < reference.height; ++j)
    for (int i = 0; i < reference.width; ++i)
    {
      if (frame.hitCount(i, j) != reference.hitCount(i, j))
      {
        EXPECT_TRUE(onSilhouette(reference, i, j)) << "pixel " << i << "," << j;
        ++silhouetteMismatches;
        continue;
      }
      for (int h = 0; h < reference.hitCount(i, j); ++h)
      {
        const auto& a = reference.firstHit(i, j)[h];
        const auto& b = frame.firstHit(i, j)[h];
        for (int d = 0; d < 3; ++d)
          worstPosition = std::max(worstPosition, std::abs(b.position[d] / s - a.position[d]));
        worstNormal = std::max(worstNormal, 1 - glm::dot(a.normal, b.normal));
        EXPECT_EQ(a.entersBelow, b.entersBelow);
      }
    }
  EXPECT_GT(reference.coveredPixels(), 200u);
  EXPECT_LE(silhouetteMismatches, 4);
  // Newton stops within 1e-6 pixel of the ray; a pixel is about a fiftieth of the data's size.
  EXPECT_LT(worstPosition, 1e-7 * size);
  EXPECT_LT(worstNormal, 1e-9);
}

class Scaled : public ::testing::TestWithParam<double>
{
};

TEST_P(Scaled, GivesTheUnscaledFrame)
{
  for (const Scene& scene : scenes())
  {
    SCOPED_TRACE(scene.name);
    expectSameFrame(scene, scaled(scene, GetParam()), GetParam());
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, Scaled, ::testing::Values(1e-6, 1e-3, 1e3, 1e6));

class AttributeScaled : public ::testing::TestWithParam<double>
{
};

TEST_P(AttributeScaled, GivesTheUnscaledFrame)
{
  for (const Scene& scene : scenes())
  {
    SCOPED_TRACE(scene.name);
    expectSameFrame(scene, attributeScaled(scene, GetParam()), 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, AttributeScaled, ::testing::Values(1e-12, 1e-6, 1e6, 1e12));

/// Expects the scene's frame to be refused with `message`.
void expectRefused(const Scene& scene, const std::string& message)
{
  GBuffer gbuffer;
  try
  {
    iga::sst::render(
      scene.set.patches, scene.camera, scene.settings, Method::SharedSubdivisionTree, gbuffer);
    ADD_FAILURE() << "accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(Scale, DataBeyondDoublePrecisionFramingIsRefused)
{
  const Scene scene = scenes().front();
  expectRefused(
    scaled(scene, 1e120), "lies beyond 1e+100, farther than double precision can frame");
  expectRefused(scaled(scene, 1e-200), "the view's world-to-clip matrix is singular or not finite");
}

} // namespace
