// The isosurface engine against analytic surfaces (spheres, exact rational cylinders, planes
// across a collapsed axis), the three methods against each other, and its failure modes.
#include "AnalyticTruth.h"
#include "EngineScenes.h"
#include "iga/Newton.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <thread>

namespace
{

using iga::sst::GBuffer;
using iga::sst::Method;
using iga::sst::Settings;
using namespace igatest::truth;

GBuffer renderSet(const iga::VolumeSet<double>& set, const iga::Camera& camera, Settings settings,
  Method method = Method::SharedSubdivisionTree, iga::sst::FrameReport* report = nullptr)
{
  GBuffer gbuffer;
  const auto r = iga::sst::render(set.patches, camera, settings, method, gbuffer);
  if (report)
    *report = r;
  return gbuffer;
}

class MarsdenSphere : public ::testing::TestWithParam<int>
{
};

TEST_P(MarsdenSphere, MatchesTheAnalyticSphere)
{
  const auto set = iga::makeMarsdenSphere<double>(GetParam());
  const double bounds[6] = { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 };
  const glm::dvec3 position{ 1.2, -3.5, 2.1 }, focal{ 0.1, 0, 0 }, up{ 0, 0, 1 };
  const auto camera = makeCamera(position, focal, up, 40, bounds);
  Settings settings;
  settings.width = 80;
  settings.height = 64;
  settings.isovalues = { 0.0 };
  iga::sst::FrameReport report;
  const GBuffer gbuffer = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  expectTheUnitSphere(gbuffer, camera, report.unresolvedPixels);
  // Depths agree with the hit's own projection.
  const auto* hit = gbuffer.firstHit(40, 32);
  ASSERT_NE(hit, nullptr);
  EXPECT_NEAR(
    hit->eyeDepth, glm::dot(hit->position - camera.position, iga::viewDirection(camera)), 1e-12);
  const glm::dvec4 clip = iga::worldToClip(camera, 80.0 / 64.0) * glm::dvec4(hit->position, 1);
  EXPECT_NEAR(hit->ndcDepth, clip[2] / clip[3], 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Degrees2To5, MarsdenSphere, ::testing::Values(2, 3, 4, 5));

/// The Marsden sphere of a degree seen from `position` towards the origin (z up, 35 degrees) on
/// a size x size image, isovalue 0.
struct SphereView
{
  iga::VolumeSet<double> set;
  iga::Camera camera;
  Settings settings;
};

SphereView sphereView(int degree, const glm::dvec3& position, int size)
{
  const double bounds[6] = { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 };
  const glm::dvec3 focal{ 0, 0, 0 }, up{ 0, 0, 1 };
  SphereView view{ iga::makeMarsdenSphere<double>(degree),
    makeCamera(position, focal, up, 35, bounds), {} };
  view.settings.width = view.settings.height = size;
  view.settings.isovalues = { 0.0 };
  return view;
}

TEST(Engine, AllHitsModeFindsFrontAndBackOfTheSphere)
{
  const glm::dvec3 position{ 0, -4, 0.5 };
  auto [set, camera, settings] = sphereView(2, position, 48);
  settings.firstHitOnly = false;
  const BothSides sides = unitSphereBothSides(renderSet(set, camera, settings), camera);
  EXPECT_GT(sides.crossing, 500);
  EXPECT_EQ(sides.twoHits, sides.crossing);
}

/// Per-pixel far depths: all hits of the sphere in front of each pixel's front hit are that
/// hit alone; a pixel below -1 is skipped; in first-hit mode a far depth in front of the front
/// hit leaves the pixel empty. A wrong count of them, or NaN, is refused.
TEST(Engine, FarDepthsStopEachPixelsWork)
{
  auto [set, camera, settings] = sphereView(2, { 0, -4, 0.5 }, 48);
  settings.firstHitOnly = false;
  const GBuffer all = renderSet(set, camera, settings);
  const size_t pixels = size_t(settings.width) * size_t(settings.height);
  settings.farDepths.assign(pixels, -2.0);
  size_t covered = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    if (all.offsets[p + 1] - all.offsets[p] == 2 && p % 3 != 0) // every third pixel skipped
    {
      settings.farDepths[p] = all.hits[all.offsets[p]].ndcDepth;
      ++covered;
    }
  }
  ASSERT_GT(covered, 300u);
  const GBuffer front = renderSet(set, camera, settings);
  EXPECT_EQ(front.hits.size(), covered);
  for (size_t p = 0; p < pixels; ++p)
  {
    const size_t count = front.offsets[p + 1] - front.offsets[p];
    ASSERT_EQ(count, settings.farDepths[p] > -2 ? 1u : 0u) << "pixel " << p;
    if (count == 1)
    {
      EXPECT_EQ(front.hits[front.offsets[p]].position, all.hits[all.offsets[p]].position);
    }
  }
  settings.firstHitOnly = true;
  for (double& far : settings.farDepths)
    far = far > -2 ? far - 1e-9 : far;
  EXPECT_EQ(renderSet(set, camera, settings).hits.size(), 0u);
  settings.farDepths.pop_back();
  EXPECT_THROW(renderSet(set, camera, settings), std::invalid_argument);
  settings.farDepths.push_back(std::nan(""));
  EXPECT_THROW(renderSet(set, camera, settings), std::invalid_argument);
}

/// Every hit says whether the ray enters the region below the isovalue there: the sphere's
/// inside (x^2 + y^2 + z^2 - 1 < 0) is entered at the front and left at the back, whatever the
/// orientation of the parametrisation (mirrored: det J < 0); with the attribute negated the
/// outside is below and the order flips.
TEST(Engine, HitsSayWhetherTheRayEntersTheRegionBelowTheIsovalue)
{
  const glm::dvec3 position{ 0.3, -4, 0.5 };
  for (const char* variant : { "as made", "mirrored", "negated" })
  {
    SCOPED_TRACE(variant);
    auto [set, camera, settings] = sphereView(3, position, 40);
    settings.firstHitOnly = false;
    const auto view = set.patches[0].view();
    const int order = view.order(0), rest = view.pointCount() / order;
    if (std::string(variant) == "mirrored") // reverse the first parameter direction
    {
      for (int r = 0; r < rest; ++r)
        for (int i = 0; i < order / 2; ++i)
          for (int c = 0; c < view.channels; ++c)
            std::swap(view.point(r * order + i)[c], view.point(r * order + order - 1 - i)[c]);
    }
    if (std::string(variant) == "negated")
    {
      for (int p = 0; p < view.pointCount(); ++p)
        view.point(p)[iga::kFirstAttributeChannel] *= -1;
    }
    const bool frontEnters = std::string(variant) != "negated";
    const GBuffer gbuffer = renderSet(set, camera, settings);
    int checked = 0;
    for (int p = 0; p < 40 * 40; ++p)
    {
      if (gbuffer.hitCount(p % 40, p / 40) != 2)
        continue;
      const auto* hits = gbuffer.firstHit(p % 40, p / 40);
      EXPECT_EQ(hits[0].entersBelow, frontEnters) << "pixel " << p;
      EXPECT_EQ(hits[1].entersBelow, !frontEnters) << "pixel " << p;
      ++checked;
    }
    EXPECT_GT(checked, 300);
  }
}

/// Clipping planes cut the surface exactly: the first hit is the nearest sphere point on the
/// kept side of both planes, so where the front cap is cut away the ray hits the sphere's inside.
TEST(Engine, ClippingPlanesCutTheSurfaceExactly)
{
  const glm::dvec3 position{ 0.6, -4, 1.1 };
  auto [set, camera, settings] = sphereView(3, position, 64);
  settings.clipPlanes = sphereCuts();
  for (Method method : { Method::SharedSubdivisionTree, Method::BasicScheme })
  {
    iga::sst::FrameReport report;
    const GBuffer gbuffer = renderSet(set, camera, settings, method, &report);
    const Comparison c = compare(gbuffer, camera, clippedSphereTruth, sphereNormal);
    EXPECT_EQ(report.unresolvedPixels, 0u) << iga::sst::methodName(method);
    EXPECT_GT(c.covered, 600) << iga::sst::methodName(method);
    EXPECT_EQ(c.mismatched, 0) << iga::sst::methodName(method);
    EXPECT_LT(c.maxPositionError, 1e-6) << iga::sst::methodName(method);
    EXPECT_LT(c.maxNormalError, 1e-9) << iga::sst::methodName(method);
  }
  // Brute force's multi-start Newton may miss a root near the silhouette, but every root it
  // keeps lies on the sphere's kept part.
  settings.firstHitOnly = false;
  const GBuffer brute = renderSet(set, camera, settings, Method::BruteForce);
  settings.firstHitOnly = true;
  ASSERT_GT(brute.hits.size(), 600u);
  for (const auto& hit : brute.hits)
  {
    EXPECT_NEAR(glm::dot(hit.position, hit.position), 1.0, 1e-6);
    EXPECT_TRUE(keptBySphereCuts(hit.position))
      << hit.position[0] << " " << hit.position[1] << " " << hit.position[2];
  }
  // The cut is visible: some pixels see the back of the sphere through the cut.
  const GBuffer clipped = renderSet(set, camera, settings);
  settings.clipPlanes.clear();
  const GBuffer whole = renderSet(set, camera, settings);
  int deeper = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
    {
      const auto *a = clipped.firstHit(i, j), *b = whole.firstHit(i, j);
      deeper += a && b && a->eyeDepth > b->eyeDepth + 0.1 ? 1 : 0;
    }
  EXPECT_GT(deeper, 100);
}

TEST(Engine, RejectsBadClippingPlanes)
{
  const glm::dvec3 position{ 0, -4, 0.5 };
  auto [set, camera, settings] = sphereView(2, position, 8);
  GBuffer gbuffer;
  settings.clipPlanes = { { 0, 0, 0, 1 } };
  EXPECT_THROW(
    iga::sst::render(set.patches, camera, settings, Method::SharedSubdivisionTree, gbuffer),
    std::invalid_argument);
  settings.clipPlanes.assign(7, { 1, 0, 0, 0 });
  EXPECT_THROW(
    iga::sst::render(set.patches, camera, settings, Method::SharedSubdivisionTree, gbuffer),
    std::invalid_argument);
}

TEST(Engine, ExactRationalCylinderInTheTube)
{
  const auto set = iga::makeTube<double>(0.5, 0.0);
  const glm::dvec3 position{ 2.6, -3.1, 3.4 }, focal{ 0, 0, 1 };
  const auto camera = igatest::lookAt(set, position, focal, 35);
  Settings settings;
  settings.width = 72;
  settings.height = 64;
  settings.isovalues = { 0.75 };
  settings.surfaceAttribute = 1; // radius
  settings.colorAttribute = 2;   // height
  const GBuffer gbuffer = renderSet(set, camera, settings);
  const Comparison c = compare(
    gbuffer, camera,
    [](const glm::dvec3& o, const glm::dvec3& d) { return cylinderTruth(o, d, 0.75, 0, 2); },
    cylinderNormal);
  EXPECT_GT(c.covered, 800);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6); // Newton stops 1e-6 pixel from the ray
  EXPECT_LT(c.maxNormalError, 1e-9);
  // The colour attribute is the height, exactly.
  const auto* hit = gbuffer.firstHit(36, 32);
  ASSERT_NE(hit, nullptr);
  EXPECT_NEAR(hit->color, hit->position[2], 1e-12);
}

TEST(Engine, CollapsedAxisDiskAndCylinder)
{
  const auto set = iga::makeTube<double>(0.0, 0.0); // inner face collapsed onto the axis
  const glm::dvec3 position{ 1.9, -2.4, 3.6 }, focal{ 0, 0, 1 };
  const auto camera = igatest::lookAt(set, position, focal, 38);
  Settings settings;
  settings.width = settings.height = 64;
  // The plane z = 1 crosses the collapsed axis: a disk of radius 1.
  settings.isovalues = { 1.0 };
  settings.surfaceAttribute = 2;
  iga::sst::FrameReport report;
  GBuffer gbuffer = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  Comparison c = compare(
    gbuffer, camera,
    [](const glm::dvec3& o, const glm::dvec3& d)
    {
      const double t = (1 - o[2]) / d[2];
      const double x = o[0] + t * d[0], y = o[1] + t * d[1];
      const double r = std::hypot(x, y);
      return Truth{ t > 0 && r <= 1 ? t : INFINITY, std::abs(r - 1) < 1e-6 };
    },
    [](const glm::dvec3&) { return glm::dvec3(0, 0, 1); });
  EXPECT_GT(c.covered, 600);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6); // Newton stops 1e-6 pixel from the ray
  EXPECT_LT(c.maxNormalError, 1e-9);

  // A cylinder of radius 0.4 around the collapsed axis.
  settings.isovalues = { 0.4 };
  settings.surfaceAttribute = 1;
  gbuffer = renderSet(set, camera, settings);
  c = compare(
    gbuffer, camera,
    [](const glm::dvec3& o, const glm::dvec3& d) { return cylinderTruth(o, d, 0.4, 0, 2); },
    cylinderNormal);
  EXPECT_GT(c.covered, 300);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6); // Newton stops 1e-6 pixel from the ray
}

TEST(Engine, CameraInsideThePatchSeesTheSphereAllAround)
{
  // The eye is inside the volume: the patch straddles the eye plane and must be split there.
  const auto set = iga::makeMarsdenSphere<double>(3);
  const glm::dvec3 position{ 0.1, 0.2, -0.1 }, focal{ 1, 0.3, 0 }, up{ 0, 0, 1 };
  iga::Camera camera;
  camera.position = position;
  camera.focalPoint = focal;
  camera.viewUp = up;
  camera.viewAngle = 60;
  camera.clippingRange[0] = 0.05;
  camera.clippingRange[1] = 5;
  Settings settings;
  settings.width = settings.height = 40;
  settings.isovalues = { 0.0 };
  iga::sst::FrameReport report;
  const GBuffer gbuffer = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  const Comparison c = compare(gbuffer, camera, sphereTruth, sphereNormal);
  EXPECT_EQ(c.covered, 40 * 40);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6); // Newton stops 1e-6 pixel from the ray
  EXPECT_EQ(report.unresolvedPixels, 0u);
}

/// The eye on the isosurface, inside the volume, with a near plane 1e-4 from it. The parts
/// straddling the eye plane beyond the view's sides are dropped at once: before, the splitting
/// at the eye plane covered the whole layer of the volume around it down to the near plane's
/// scale (the degenerate zoo seen from (0, 0, 1) at 384x48: 156 s, 20.7 GB, 101 835 parts
/// dropped at its cap).
TEST(Engine, EyeOnTheIsosurfaceNearTheNearPlane)
{
  auto [set, camera, settings] = sphereView(2, { 0, -1, 0 }, 64);
  camera.clippingRange[0] = 1e-4;
  camera.clippingRange[1] = 5;
  iga::sst::FrameReport report;
  const GBuffer gbuffer = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  const Comparison c = compare(gbuffer, camera, sphereTruth, sphereNormal);
  EXPECT_EQ(c.covered, 64 * 64);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  EXPECT_EQ(report.droppedAtEyePlane, 0u);
}

TEST(Engine, SharedTreesBasicSchemeAndBruteForceAgreeOnTheTwistedTeardrop)
{
  const auto set = iga::makeTeardrop<double>(1.2);
  const glm::dvec3 position{ -0.2, -1.6, 0.9 }, focal{ -0.5, 0, 0 };
  const auto camera = igatest::lookAt(set, position, focal, 40);
  Settings settings;
  settings.width = settings.height = 40;
  settings.isovalues = { 0.0 };
  settings.firstHitOnly = false;
  const GBuffer sst = renderSet(set, camera, settings, Method::SharedSubdivisionTree);
  const GBuffer basic = renderSet(set, camera, settings, Method::BasicScheme);
  const GBuffer brute = renderSet(set, camera, settings, Method::BruteForce);
  // The two subdivision schemes find the same roots.
  igatest::expectSameFirstHits(sst, basic, 0, 1e-6);
  ASSERT_EQ(sst.offsets, basic.offsets);
  for (size_t h = 0; h < sst.hits.size(); ++h)
    EXPECT_NEAR(sst.hits[h].eyeDepth, basic.hits[h].eyeDepth, 1e-6);
  igatest::expectBruteForceWithinTrees(sst, brute, 200);
}

TEST(Engine, FoldedSelfIntersectingVolumeAgreesWithTheReferences)
{
  // Fold the sphere volume over itself: the control planes x_i of the first direction become
  // non-monotone, so the map's Jacobian changes sign (an inverted, self-intersecting volume).
  auto set = iga::makeMarsdenSphere<double>(3);
  const auto view = set.patches[0].view();
  for (int p = 0; p < view.pointCount(); ++p)
  {
    const int i = p % 4;
    const double fold[4] = { -1.5, 3.0, -3.0, 1.5 };
    view.point(p)[0] = fold[i];
  }
  const glm::dvec3 position{ 0.8, -4.2, 1.6 }, focal{ 0, 0, 0 };
  const auto camera = igatest::lookAt(set, position, focal, 40);
  Settings settings;
  settings.width = settings.height = 40;
  settings.isovalues = { 0.0 };
  settings.firstHitOnly = false;
  iga::sst::FrameReport report;
  const GBuffer sst = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  const GBuffer basic = renderSet(set, camera, settings, Method::BasicScheme);
  settings.bruteForceLevels = 5;
  const GBuffer brute = renderSet(set, camera, settings, Method::BruteForce);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  ASSERT_EQ(sst.offsets, basic.offsets);
  size_t moreThanTwo = 0;
  for (int p = 0; p < 40 * 40; ++p)
  {
    moreThanTwo += sst.offsets[p + 1] - sst.offsets[p] > 2 ? 1 : 0;
    for (uint32_t b = brute.offsets[p]; b < brute.offsets[p + 1]; ++b)
    {
      bool present = false;
      for (uint32_t s = sst.offsets[p]; s < sst.offsets[p + 1]; ++s)
        present = present || std::abs(sst.hits[s].eyeDepth - brute.hits[b].eyeDepth) < 1e-6;
      EXPECT_TRUE(present) << "pixel " << p << " depth " << brute.hits[b].eyeDepth;
    }
  }
  // The fold makes rays cross the surface more than twice.
  EXPECT_GT(moreThanTwo, 20u);
}

TEST(Engine, ImageIsIdenticalForOneAndTwoThreads)
{
  const auto set = iga::makeTwistedTube<double>(0.7);
  const glm::dvec3 position{ 3, -3.5, 3 }, focal{ 0.2, 0, 1 };
  const auto camera = igatest::lookAt(set, position, focal, 35);
  Settings settings;
  settings.width = settings.height = 64;
  settings.isovalues = { 0.0, 0.3 };
  settings.colorAttribute = 1;
  settings.threads = 1;
  const GBuffer one = renderSet(set, camera, settings);
  settings.threads = 2;
  const GBuffer two = renderSet(set, camera, settings);
  ASSERT_GT(one.hits.size(), 500u);
  EXPECT_TRUE(igatest::identicalGBuffers(one, two));
}

// A non-zero data version names the patches (the mapper's, for a camera move or a new isovalue):
// their checks and attribute ranges are kept from the frame before, and the frames equal those
// of a set checked afresh (version 0) whatever changes with the version kept: the camera, the
// isovalues, the threads. What the version does not name is checked again: the attributes used,
// a set of another size, and (a caller's mistake the patches' sampled fingerprint catches) other
// patches under the same version.
TEST(Engine, AFrameOfTheSameDataVersionEqualsAFreshOne)
{
  const auto set = iga::makeTwistedTube<double>(0.7);
  const auto near = igatest::lookAt(set, { 3, -3.5, 3 }, { 0.2, 0, 1 }, 35);
  const auto far = igatest::lookAt(set, { -4, -3, 2 }, { 0, 0, 1 }, 30);
  Settings settings;
  settings.width = settings.height = 64;
  settings.colorAttribute = 1;
  const std::vector<std::vector<double>> isovalues = { { 0.0 }, { 0.3, -0.2 }, { 5.0 } };
  for (int frame = 0; frame < 6; ++frame)
  {
    Settings fresh = settings;
    fresh.isovalues = isovalues[frame % 3];
    fresh.threads = 1 + frame % 2;
    Settings kept = fresh;
    kept.dataVersion = 41;
    const auto& camera = frame < 3 ? near : far;
    const GBuffer expected = renderSet(set, camera, fresh);
    EXPECT_TRUE(igatest::identicalGBuffers(renderSet(set, camera, kept), expected)) << frame;
    EXPECT_EQ(expected.coveredPixels() == 0, frame % 3 == 2) << frame;
  }
  Settings kept = settings;
  kept.isovalues = { 0.0 };
  kept.dataVersion = 41;
  Settings badAttribute = kept;
  badAttribute.surfaceAttribute = 7;
  GBuffer g;
  EXPECT_THROW(iga::sst::render(set.patches, near, badAttribute, Method::SharedSubdivisionTree, g),
    std::invalid_argument);
  auto fewer = set;
  fewer.patches.erase(fewer.patches.begin() + 3, fewer.patches.end());
  Settings fresh = kept;
  fresh.dataVersion = 0;
  const GBuffer expected = renderSet(fewer, near, fresh);
  ASSERT_GT(expected.coveredPixels(), 0u);
  EXPECT_TRUE(igatest::identicalGBuffers(renderSet(fewer, near, kept), expected));
  // The tube at another time: the same shapes, other values, whose attribute ranges differ.
  const auto later = iga::makeTwistedTube<double>(0.1);
  kept.isovalues = fresh.isovalues = { 0.45 };
  renderSet(set, near, kept);
  const GBuffer laterExpected = renderSet(later, near, fresh);
  EXPECT_FALSE(igatest::identicalGBuffers(laterExpected, renderSet(set, near, fresh)));
  EXPECT_TRUE(igatest::identicalGBuffers(renderSet(later, near, kept), laterExpected));
}

// The floor of igaBenchmark rests on these counts: every hit is a Newton root, Newton runs only
// on certified tuples, each run evaluates at least once and at most its iteration limit plus
// one, and a pixel's work does not depend on the threads sharing the image.
TEST(Engine, NewtonWorkIsCountedPerFrame)
{
  SphereView view = sphereView(2, { 1.2, -3.5, 2.1 }, 64);
  iga::sst::FrameReport one, two;
  view.settings.threads = 1;
  const GBuffer gbuffer =
    renderSet(view.set, view.camera, view.settings, Method::SharedSubdivisionTree, &one);
  view.settings.threads = 2;
  renderSet(view.set, view.camera, view.settings, Method::SharedSubdivisionTree, &two);
  ASSERT_GT(gbuffer.coveredPixels(), 1000u);
  EXPECT_GE(one.newtonRuns, gbuffer.coveredPixels());
  EXPECT_LE(one.newtonRuns, one.newtonSolves);
  EXPECT_GE(one.newtonEvaluations, one.newtonRuns);
  EXPECT_LE(one.newtonEvaluations,
    size_t(iga::NewtonSettings<double>().maxIterations + 1) * one.newtonRuns);
  EXPECT_EQ(two.newtonRuns, one.newtonRuns);
  EXPECT_EQ(two.newtonEvaluations, one.newtonEvaluations);
}

TEST(Engine, DepthCapIsReportedNotLooped)
{
  const glm::dvec3 position{ 0, -4, 0 };
  auto [set, camera, settings] = sphereView(4, position, 32);
  settings.maxSubdivisionDepth = 1;
  iga::sst::FrameReport report;
  renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_GT(report.unresolvedPixels, 0u);
  EXPECT_GT(report.unresolvedAtDepthCap, 0u);
  settings.maxSubdivisionDepth = 22;
  // Room for the image, the root and little else.
  settings.memoryBudgetBytes = iga::sst::imageBytes(settings) + 64 * 1024;
  renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_GT(report.unresolvedAtBudget, 0u);
  EXPECT_LE(report.peakBytes, size_t(1) << 20);
}

/// The image's per-pixel arrays and G-buffer count against the budget: a size whose image alone
/// passes it is refused before anything is drawn, naming what it needs; one that just fits
/// leaves the loop no room past the one row and round it takes to move on, so pixels are left
/// unresolved at the budget.
TEST(Engine, ImageBeyondTheMemoryBudgetIsRefused)
{
  auto [set, camera, settings] = sphereView(2, { 0, -4, 0 }, 16384);
  // 16384^2 pixels at 8 + 1 + 8 * 4 bytes of arrays and a hit of 48 + 2 * 112 + 12 bytes.
  EXPECT_EQ(iga::sst::imageBytes(settings), size_t(87241523200));
  auto refusal = [&]() -> std::string
  {
    try
    {
      renderSet(set, camera, settings);
    }
    catch (const std::length_error& e)
    {
      return e.what();
    }
    return "drawn";
  };
  EXPECT_EQ(refusal(), "a 16384x16384 image needs 83200 MiB (325 bytes a pixel), more than the "
                       "memory budget of 4096 MiB: lower the resolution or raise the budget");
  settings.width = settings.height = 32;
  settings.memoryBudgetBytes = iga::sst::imageBytes(settings) - 1;
  EXPECT_EQ(refusal(), "a 32x32 image needs 0.4 MiB (325 bytes a pixel), more than the memory "
                       "budget of 0.3 MiB: lower the resolution or raise the budget");
  settings.memoryBudgetBytes += 1;
  iga::sst::FrameReport report;
  renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_GT(report.unresolvedAtBudget, 0u);
  EXPECT_GT(report.unresolvedPixels, 0u);
  EXPECT_LT(report.peakBudgetedBytes, 64u * 1024) << "the one row and round it takes to move on";
}

/// Pixels whose first hit differs between two G-buffers of one size (or is missing in one).
size_t differingPixels(const GBuffer& a, const GBuffer& b)
{
  size_t differ = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i)
    {
      const iga::sst::Hit *x = a.firstHit(i, j), *y = b.firstHit(i, j);
      differ += (x == nullptr) != (y == nullptr) || (x && x->ndcDepth != y->ndcDepth);
    }
  return differ;
}

TEST(Engine, AFrameStopsAtItsDeadlineKeepingWhatIsCertain)
{
  const auto set = iga::makeTwistedTube<double>(0.7);
  const auto camera = igatest::lookAt(set, { 3, -3.5, 3 }, { 0.2, 0, 1 }, 35);
  Settings settings;
  settings.width = settings.height = 96;
  settings.isovalues = { 0.0 };
  iga::sst::FrameReport full;
  const GBuffer whole = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &full);
  ASSERT_GT(full.iterations, 6);
  EXPECT_EQ(full.unresolvedAtDeadline, 0u);

  // Iterations slowed down to 40 ms each: a 100 ms deadline stops the frame after a few.
  settings.deadlineMs = 100;
  settings.progress = [](int, size_t)
  { std::this_thread::sleep_for(std::chrono::milliseconds(40)); };
  iga::sst::FrameReport cut;
  const GBuffer part = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &cut);
  EXPECT_GE(cut.iterations, 1);
  EXPECT_LE(cut.iterations, 4);
  EXPECT_GT(cut.unresolvedAtDeadline, 0u);
  EXPECT_EQ(cut.unresolvedPixels, cut.unresolvedAtDeadline);
  EXPECT_LT(part.coveredPixels(), whole.coveredPixels());
  // Every pixel not given up is the full frame's.
  EXPECT_LE(differingPixels(part, whole), cut.unresolvedAtDeadline);

  // A deadline already passed when the loop starts gives up every pixel with work.
  settings.deadlineMs = 1e-9;
  settings.progress = nullptr;
  iga::sst::FrameReport none;
  const GBuffer empty = renderSet(set, camera, settings, Method::SharedSubdivisionTree, &none);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_EQ(empty.coveredPixels(), 0u);
  EXPECT_GE(none.unresolvedAtDeadline, whole.coveredPixels());

  settings.deadlineMs = -1;
  EXPECT_THROW(renderSet(set, camera, settings), std::invalid_argument);
}

TEST(Engine, BadInputIsRejectedWithTheProblemNamed)
{
  auto set = iga::makeTwistedTube<double>(0.0);
  const double bounds[6] = { -1, 1, -1, 1, 0, 2 };
  const glm::dvec3 position{ 0, -4, 1 }, focal{ 0, 0, 1 }, up{ 0, 0, 1 };
  const auto camera = makeCamera(position, focal, up, 35, bounds);
  Settings settings;
  settings.width = settings.height = 8;
  settings.isovalues = { 0.0 };
  auto message = [&](const iga::VolumeSet<double>& s, const Settings& st)
  {
    GBuffer g;
    try
    {
      iga::sst::render(s.patches, camera, st, Method::SharedSubdivisionTree, g);
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(set, settings), "");
  auto negative = set;
  negative.patches[3].view().point(4)[iga::kWeightChannel] = -0.5;
  EXPECT_NE(message(negative, settings).find("patch 3: control point 4 has non-positive weight"),
    std::string::npos);
  auto nan = set;
  nan.patches[5].view().point(0)[1] = NAN;
  EXPECT_NE(
    message(nan, settings)
      .find("patch 5: control point 0 has a non-finite weighted y coordinate (channel 1): nan"),
    std::string::npos);
  // Checked in parts on several threads: the first bad patch is named, whichever part finishes
  // first.
  auto twoBad = nan;
  twoBad.patches[7].view().point(2)[iga::kWeightChannel] = 0.0;
  for (int threads : { 1, 2, 8 })
  {
    Settings parallel = settings;
    parallel.threads = threads;
    EXPECT_EQ(
      message(twoBad, parallel).rfind("patch 5: control point 0 has a non-finite weighted y", 0),
      0u);
  }
  Settings noIso = settings;
  noIso.isovalues.clear();
  EXPECT_NE(message(set, noIso).find("no isovalue"), std::string::npos);
  Settings badAttribute = settings;
  badAttribute.surfaceAttribute = 7;
  EXPECT_NE(message(set, badAttribute).find("has 3 attributes"), std::string::npos);
  Settings badSize = settings;
  badSize.width = 0;
  EXPECT_NE(message(set, badSize).find("image size"), std::string::npos);
}

/// A constant attribute equal to the isovalue has no isosurface (its level set is a region):
/// its patches are recognised and counted, not subdivided to the depth cap, on one thread and
/// on two; a constant away from the isovalue is simply empty.
TEST(Engine, ConstantAttributeAtTheIsovalueIsCountedNotSubdivided)
{
  auto set = iga::makeTwistedTube<double>(0.5);
  for (auto& patch : set.patches)
  {
    auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      view.point(p)[iga::kFirstAttributeChannel] = 0.3 * view.point(p)[iga::kWeightChannel];
  }
  const auto camera = igatest::lookAt(set, { 3, -3.5, 3 }, { 0.2, 0, 1 }, 35);
  Settings settings;
  settings.width = settings.height = 64;
  settings.isovalues = { 0.3 };
  for (int threads : { 1, 2 })
  {
    settings.threads = threads;
    iga::sst::FrameReport report;
    const GBuffer gbuffer =
      renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
    EXPECT_EQ(report.constantAttributeRoots, set.patches.size());
    EXPECT_EQ(report.unresolvedPixels, 0u);
    EXPECT_EQ(report.subdividedPatches, 0u);
    EXPECT_EQ(gbuffer.coveredPixels(), 0u);
  }
  // Two isovalues, one at the constant: counted once per patch; none at it: nothing counted.
  settings.isovalues = { 0.1, 0.3 };
  iga::sst::FrameReport report;
  renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_EQ(report.constantAttributeRoots, set.patches.size());
  settings.isovalues = { 0.31 };
  renderSet(set, camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_EQ(report.constantAttributeRoots, 0u);
  EXPECT_EQ(report.unresolvedPixels, 0u);
}

} // namespace
