// A zoo of degenerate patches, each with its expected behaviour, and the G-buffer of every
// drawable one identical for 1, 2 and 8 threads: collapsed face, edge and whole patch,
// inverted, zero / negative / NaN / widely ranging weights, a constant field, degree 16.
#include "EngineScenes.h"

#include "iga/Orientation.h"

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

/// The Marsden sphere x^2 + y^2 + z^2 = 1 in one patch of the given degree, changed by `edit`.
iga::VolumeSet<double> sphere(
  int degree, const std::function<void(iga::PatchView<double, 3>)>& edit)
{
  auto set = iga::makeMarsdenSphere<double>(degree);
  edit(set.patches[0].view());
  return set;
}

/// Control point (i, j, k) of a patch.
double* at(const iga::PatchView<double, 3>& patch, int i, int j, int k)
{
  return patch.point(i + patch.order(0) * (j + patch.order(1) * k));
}

/// Which isosurface a zoo scene draws.
struct Surface
{
  int attribute = 0;
  double isovalue = 0;
};

/// Draws `set` at 48x40 with `threads` threads; the report into `report` when given.
GBuffer draw(const iga::VolumeSet<double>& set, int threads,
  iga::sst::FrameReport* report = nullptr, Surface surface = {})
{
  const auto camera = igatest::lookAt(set, { 3.2, -4.1, 2.7 }, { 0, 0, 0 }, 40);
  Settings settings;
  settings.width = 48;
  settings.height = 40;
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
GBuffer drawOnThreads(
  const iga::VolumeSet<double>& set, const std::string& name, Surface surface = {})
{
  const GBuffer one = draw(set, 1, nullptr, surface);
  for (int threads : { 2, 8 })
  {
    const GBuffer other = draw(set, threads, nullptr, surface);
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
  const iga::VolumeSet<double>& set, const std::string& name, size_t covered)
{
  const GBuffer gbuffer = drawOnThreads(set, name);
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
  const GBuffer gbuffer = drawOnThreads(sphere(2, [](auto) {}), "sphere");
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
  const auto set = sphere(2,
    [](iga::PatchView<double, 3> patch)
    {
      for (int i = 0; i < 3; ++i)
        for (int d = 0; d < 3; ++d)
          at(patch, i, 0, 0)[d] = at(patch, 1, 0, 0)[d];
    });
  expectDrawnOnItsZeroSet(set, "collapsed edge", 100);
}

TEST(Zoo, PatchCollapsedToAPointDrawsNothingAndEnds)
{
  const auto set = sphere(2,
    [](iga::PatchView<double, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
        for (int d = 0; d < 3; ++d)
          patch.point(p)[d] = 0.25 * patch.point(p)[iga::kWeightChannel];
    });
  iga::sst::FrameReport report;
  const GBuffer gbuffer = draw(set, 1, &report);
  EXPECT_LE(gbuffer.coveredPixels(), 1u) << "a point covers at most one pixel";
  EXPECT_EQ(report.unresolvedPixels, 0u);
  drawOnThreads(set, "point");
}

TEST(Zoo, InvertedPatchDrawsTheSameSphere)
{
  const auto set =
    sphere(3, [](iga::PatchView<double, 3> patch) { iga::reverseDirection(patch, 1); });
  ASSERT_LT(iga::signedVolume<double>(std::as_const(set.patches[0]).view()), 0);
  const GBuffer inverted = drawOnThreads(set, "inverted");
  const GBuffer regular = draw(sphere(3, [](auto) {}), 1);
  EXPECT_NEAR(double(inverted.coveredPixels()), double(regular.coveredPixels()), 2);
  EXPECT_LT(sphereError(inverted), 1e-6);
}

TEST(Zoo, BadWeightsAreRefusedByName)
{
  for (double bad : { 0.0, -0.5, std::nan("") })
  {
    const auto set = sphere(
      2, [bad](iga::PatchView<double, 3> patch) { patch.point(13)[iga::kWeightChannel] = bad; });
    const std::string message = refusal(set);
    EXPECT_NE(message.find("patch 0"), std::string::npos) << message;
    EXPECT_NE(message.find("weight"), std::string::npos) << bad << ": " << message;
  }
}

TEST(Zoo, WidelyRangingWeightsAreDrawn)
{
  // Weights 1e-3 .. 1e3 (a ratio of 1e6) times the sphere's control values: another rational
  // map and field, drawn with finite hits and alike on all threads.
  const auto set = sphere(2,
    [](iga::PatchView<double, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
      {
        const double w = std::pow(10.0, 3 * std::sin(7.0 * p));
        for (int c = 0; c < patch.channels; ++c)
          patch.point(p)[c] *= w;
      }
    });
  expectDrawnOnItsZeroSet(set, "weights 1e-3 .. 1e3", 50);
}

TEST(Zoo, ConstantFieldIsCountedNotDrawn)
{
  const auto set = sphere(2,
    [](iga::PatchView<double, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
        patch.point(p)[iga::kFirstAttributeChannel] = 0;
    });
  iga::sst::FrameReport report;
  const GBuffer gbuffer = draw(set, 1, &report);
  EXPECT_EQ(report.constantAttributeRoots, 1u);
  EXPECT_EQ(gbuffer.coveredPixels(), 0u);
  EXPECT_EQ(report.unresolvedPixels, 0u);
}

TEST(Zoo, DegreeSixteenDrawsTheSphere)
{
  const GBuffer gbuffer = drawOnThreads(sphere(iga::kMaxDegree, [](auto) {}), "degree 16");
  const GBuffer reference = draw(sphere(2, [](auto) {}), 1);
  EXPECT_NEAR(double(gbuffer.coveredPixels()), double(reference.coveredPixels()), 2);
  EXPECT_LT(sphereError(gbuffer), 1e-6);
}

} // namespace
