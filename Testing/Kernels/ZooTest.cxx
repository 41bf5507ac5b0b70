// A zoo of degenerate patches, each with its expected behaviour, and the G-buffer of every
// drawable one identical for 1, 2 and 8 threads: collapsed face, edge and whole patch,
// inverted, self-intersecting, zero / negative / NaN weights, weights ranging widely (drawn) and
// beyond kMaxWeightRatio (refused), a constant field,
// degree 16, the sphere members side by side, and 10^6 patches (1 and 2 threads). Coordinates at
// 1e-6 and 1e6: ScaleTest.
#include "EngineScenes.h"

#include "iga/DegenerateZoo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

using iga::sst::GBuffer;
using iga::sst::Settings;

/// Which isosurface a zoo scene draws.
struct Surface
{
  int attribute = 0;
  double isovalue = 0;
};

/// Camera and image size of a zoo scene: by default one patch about the origin.
struct Shot
{
  glm::dvec3 eye{ 3.2, -4.1, 2.7 }, focal{ 0, 0, 0 };
  double viewAngle = 40;
  int width = 48, height = 40;
  glm::dvec3 up{ 0, 0, 1 };
};

/// The members of makeDegenerateZoo in a row across the image, about 19 pixels each.
const Shot kZooRow{ { 14, -9.5, 0 }, { 14, 0, 0 }, 30, 384, 48 };

/// Draws `set` with `threads` threads; the report into `report` when given.
GBuffer draw(const iga::VolumeSet<double>& set, int threads,
  iga::sst::FrameReport* report = nullptr, Surface surface = {}, const Shot& shot = {})
{
  const auto camera = igatest::lookAt(set, shot.eye, shot.focal, shot.viewAngle, shot.up);
  Settings settings;
  settings.width = shot.width;
  settings.height = shot.height;
  settings.isovalues = { surface.isovalue };
  settings.surfaceAttribute = surface.attribute;
  settings.threads = threads;
  GBuffer gbuffer;
  const auto r = iga::sst::render(
    set.patches, camera, settings, iga::sst::Method::SharedSubdivisionTree, gbuffer);
  if (report)
    *report = r;
  return gbuffer;
}

/// Draws with 1, 2 and 8 threads, expects the three G-buffers identical, returns the first.
GBuffer drawOnThreads(const iga::VolumeSet<double>& set, const std::string& name,
  Surface surface = {}, const Shot& shot = {})
{
  const GBuffer one = draw(set, 1, nullptr, surface, shot);
  for (int threads : { 2, 8 })
  {
    const GBuffer other = draw(set, threads, nullptr, surface, shot);
    EXPECT_EQ(one.offsets, other.offsets) << name << ", " << threads << " threads";
    if (one.hits.size() != other.hits.size())
      continue;
    for (size_t h = 0; h < one.hits.size(); ++h)
    {
      EXPECT_EQ(one.hits[h].ndcDepth, other.hits[h].ndcDepth) << name;
      EXPECT_EQ(one.hits[h].position, other.hits[h].position) << name;
      EXPECT_EQ(one.hits[h].normal, other.hits[h].normal) << name;
    }
  }
  return one;
}

/// Largest distance of a hit from the unit sphere.
double sphereError(const GBuffer& gbuffer)
{
  double worst = 0;
  for (const auto& hit : gbuffer.hits)
    worst = std::max(worst, std::abs(glm::length(hit.position) - 1));
  return worst;
}

/// Draws `set` on 1, 2 and 8 threads and expects at least `covered` pixels whose hits lie on
/// their own patch's zero set: the patch evaluated at a hit's parameters gives its position
/// and attribute 0 there (the isovalue).
void expectDrawnOnItsZeroSet(
  const iga::VolumeSet<double>& set, const std::string& name, size_t covered, const Shot& shot = {})
{
  const GBuffer gbuffer = drawOnThreads(set, name, {}, shot);
  EXPECT_GE(gbuffer.coveredPixels(), covered) << name;
  for (const auto& hit : gbuffer.hits)
  {
    const auto patch = set.patches[size_t(hit.patch)].view();
    std::vector<double> values(size_t(patch.channels));
    const double u[3] = { hit.uvw.x, hit.uvw.y, hit.uvw.z };
    iga::evaluateHomogeneous<double, 3>(patch, u, values.data(), nullptr);
    const double w = values[iga::kWeightChannel];
    const glm::dvec3 x(values[0] / w, values[1] / w, values[2] / w);
    EXPECT_LT(glm::length(x - hit.position), 1e-6) << name;
    EXPECT_LT(std::abs(values[iga::kFirstAttributeChannel] / w), 1e-6) << name;
  }
}

/// The message render throws for `set`, or "" if it draws.
std::string refusal(const iga::VolumeSet<double>& set)
{
  try
  {
    draw(set, 1);
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  return std::string();
}

TEST(Zoo, RegularSphereIsTheReference)
{
  const GBuffer gbuffer = drawOnThreads(iga::makeMarsdenSphere<double>(2), "sphere");
  EXPECT_GT(gbuffer.coveredPixels(), 250u);
  EXPECT_LT(sphereError(gbuffer), 1e-6);
}

TEST(Zoo, CollapsedFaceOfTheCylinderIsDrawn)
{
  // The inner face collapses onto the axis; the cylinder radius = 0.5 lies inside.
  const auto set = iga::makeTube<double>(0.0, 0.0);
  ASSERT_EQ(set.attributeNames[1], "radius");
  const GBuffer gbuffer = drawOnThreads(set, "collapsed face", { 1, 0.5 });
  EXPECT_GT(gbuffer.coveredPixels(), 100u);
  for (const auto& hit : gbuffer.hits)
    EXPECT_NEAR(std::hypot(hit.position.x, hit.position.y), 0.5, 1e-6);
}

TEST(Zoo, CollapsedEdgeIsDrawnOnTheSphere)
{
  // The edge (j, k) = (0, 0) of the degree-2 net moved onto one point: another map of the same
  // control values, whose hits must lie on its own zero set.
  expectDrawnOnItsZeroSet(iga::makeSphereWithCollapsedEdge<double>(), "collapsed edge", 100);
}

TEST(Zoo, PatchCollapsedToAPointDrawsNothingAndEnds)
{
  const auto set = iga::makeSphereCollapsedToAPoint<double>();
  iga::sst::FrameReport report;
  const GBuffer gbuffer = draw(set, 1, &report);
  EXPECT_LE(gbuffer.coveredPixels(), 1u) << "a point covers at most one pixel";
  EXPECT_EQ(report.unresolvedPixels, 0u);
  drawOnThreads(set, "point");
}

TEST(Zoo, InvertedPatchDrawsTheSameSphere)
{
  const auto set = iga::makeInvertedSphere<double>();
  ASSERT_LT(iga::signedVolume<double>(std::as_const(set.patches[0]).view()), 0);
  const GBuffer inverted = drawOnThreads(set, "inverted");
  const GBuffer regular = draw(iga::makeMarsdenSphere<double>(3), 1);
  EXPECT_NEAR(double(inverted.coveredPixels()), double(regular.coveredPixels()), 2);
  EXPECT_LT(sphereError(inverted), 1e-6);
}

TEST(Zoo, SelfIntersectingPatchIsDrawnOnItsZeroSet)
{
  const auto set = iga::makeSelfIntersectingSphere<double>();
  // x along u at v = w = 1/2 rises, then falls back: the map folds.
  auto x = [&](double u)
  {
    const double at[3] = { u, 0.5, 0.5 };
    std::vector<double> values(size_t(set.patches[0].channels()));
    iga::evaluateHomogeneous<double, 3>(
      std::as_const(set.patches[0]).view(), at, values.data(), nullptr);
    return values[0] / values[iga::kWeightChannel];
  };
  ASSERT_GT(x(0.1), x(0.0));
  ASSERT_LT(x(1.0), x(0.9));
  expectDrawnOnItsZeroSet(set, "self-intersecting", 100);
}

TEST(Zoo, BadWeightsAreRefusedByName)
{
  for (double bad : { 0.0, -0.5, std::nan("") })
  {
    const auto set = iga::makeEditedSphere<double>(
      2, [bad](iga::PatchView<double, 3> patch) { patch.point(13)[iga::kWeightChannel] = bad; });
    const std::string message = refusal(set);
    EXPECT_NE(message.find("patch 0"), std::string::npos) << message;
    EXPECT_NE(message.find("weight"), std::string::npos) << bad << ": " << message;
  }
}

TEST(Zoo, WidelyRangingWeightsAreDrawn)
{
  // Drawn with finite hits and alike on all threads.
  expectDrawnOnItsZeroSet(iga::makeSphereWithWideWeights<double>(), "weights 1e-3 .. 1e3", 50);
}

TEST(Zoo, WidelyRangingWeightsAreDrawnFromParaViewsFirstCamera)
{
  // ParaView's first view of the zoo's row (384x48, eye 6.69 above the row's first member),
  // centred on this member. The isosurface runs across thin layers of the parameter cube: nodes
  // halved in all three directions multiplied along the layers, 48 s and 70 million tuples,
  // 1 131 pixels given up at the depth cap; halved across the layers alone (splitAxes), a few
  // thousand splits.
  const auto set = iga::makeSphereWithWideWeights<double>();
  const Shot shot{ { 0, 0, 6.69 }, { 0, 0, 0 }, 30, 384, 48, { 0, 1, 0 } };
  iga::sst::FrameReport report;
  draw(set, 2, &report, {}, shot);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  EXPECT_LT(report.subdividedPatches, 10000u);
  expectDrawnOnItsZeroSet(set, "weights 1e-3 .. 1e3, ParaView's camera", 200, shot);
}

TEST(Zoo, WeightsRangingOverMoreThanSubdivisionResolvesAreRefused)
{
  // A ratio of 3.1e6 leaves pixels at the depth cap from ParaView's camera above.
  const std::string message = refusal(iga::makeSphereWithWideWeights<double>(3.25));
  EXPECT_EQ(message, "patch 0: weights range over 0.000574 .. 1.77e+03, a ratio of 3.08e+06: more "
                     "than the 1e+06 that subdivision resolves");
}

TEST(Zoo, ConstantFieldIsCountedNotDrawn)
{
  const auto set = iga::makeSphereWithConstantField<double>();
  iga::sst::FrameReport report;
  const GBuffer gbuffer = draw(set, 1, &report);
  EXPECT_EQ(report.constantAttributeRoots, 1u);
  EXPECT_EQ(gbuffer.coveredPixels(), 0u);
  EXPECT_EQ(report.unresolvedPixels, 0u);
}

TEST(Zoo, DegreeSixteenDrawsTheSphere)
{
  const GBuffer gbuffer =
    drawOnThreads(iga::makeMarsdenSphere<double>(iga::kMaxDegree), "degree 16");
  const GBuffer reference = draw(iga::makeMarsdenSphere<double>(2), 1);
  EXPECT_NEAR(double(gbuffer.coveredPixels()), double(reference.coveredPixels()), 2);
  EXPECT_LT(sphereError(gbuffer), 1e-6);
}

/// The zoo's sphere members side by side in one dataset (igaview-generate-data --zoo, the MPI
/// test's): alike on all threads, every hit on its own patch's zero set, none on the constant
/// field (member 5), the drawable members all seen.
TEST(Zoo, MembersSideBySideAreDrawnAlike)
{
  const auto zoo = iga::makeDegenerateZoo<double>();
  ASSERT_EQ(zoo.patches.size(), 8u);
  expectDrawnOnItsZeroSet(zoo, "zoo", 1000, kZooRow);
  std::vector<size_t> perPatch(zoo.patches.size());
  for (const auto& hit : draw(zoo, 2, nullptr, {}, kZooRow).hits)
    ++perPatch[size_t(hit.patch)];
  EXPECT_EQ(perPatch[5], 0u) << "constant field";
  EXPECT_LE(perPatch[2], 1u) << "collapsed to a point";
  for (size_t member : { 0, 1, 3, 4, 6, 7 })
    EXPECT_GT(perPatch[member], 150u) << member;
}

/// 10^6 patches (the wind blade's layout, degree (2, 1, 2)) in one small frame: drawn, alike
/// on 1 and 2 threads, within the memory budget, every hit on the blade's span.
TEST(Zoo, MillionPatchesAreDrawnAlike)
{
  const auto blade = iga::makeBlade<double>(iga::bladeLayout(1000000), 0.0);
  ASSERT_GE(blade.patches.size(), 1000000u);
  const Shot whole{ { 0.3, -0.4, 14 }, { 0, 0, 5 }, 6, 64, 48 }; // from above
  const Surface span{ 1, 0.5 }; // the plane z = 5 through the blade
  iga::sst::FrameReport report;
  const GBuffer one = draw(blade, 1, &report, span, whole);
  const GBuffer two = draw(blade, 2, nullptr, span, whole);
  EXPECT_GT(one.coveredPixels(), 50u); // the wall's ring in the plane, seen from above
  EXPECT_EQ(report.unresolvedPixels, 0u);
  EXPECT_LE(report.peakBudgetedBytes, Settings().memoryBudgetBytes);
  EXPECT_EQ(one.offsets, two.offsets);
  ASSERT_EQ(one.hits.size(), two.hits.size());
  for (size_t h = 0; h < one.hits.size(); ++h)
  {
    EXPECT_EQ(one.hits[h].position, two.hits[h].position);
    EXPECT_NEAR(one.hits[h].position.z, 5, 1e-6);
  }
}

} // namespace
