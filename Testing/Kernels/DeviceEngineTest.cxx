// The device driver of the shared-subdivision-tree engine against the CPU driver, scene by scene
// (the CPU engine's test scenes: spheres of degrees 2..5, the teardrop in all-hits mode, the
// tube with two isovalues and a colour attribute, the exact rational cylinder drawn from its
// second attribute, the collapsed cylinder axis, a camera inside the patch, clipping planes, a
// folded volume, the depth and memory caps).
//
// Built twice from this source:
// - igaDeviceLogicTests (IGAVIEW_DEVICE_LOGIC): the driver compiled by g++ for Thrust's host
//   system. Same functions on the same processor, so the G-buffers must be identical; this
//   checks the driver's logic on machines without a GPU.
// - igaCudaEngineTests: frames through iga::sst::render with the CUDA backend. Without a usable
//   device every test reports SKIPPED. GPU arithmetic (fused multiply-adds) may move a root by
//   rounding, so positions are compared to the CPU tests' tolerance and a few silhouette pixels
//   may differ.
#include "EngineScenes.h"

#include "CsgFrame.h"
#include "iga/sst/Csg.h"

#ifdef IGAVIEW_DEVICE_LOGIC
#include "DeviceDriver.h"
#else
#include "CudaEngine.h"
#endif

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{

using iga::sst::FrameReport;
using iga::sst::GBuffer;
using iga::sst::Settings;

using igatest::lookAt;
using igatest::Scene;
using igatest::scene;

/// The twisted tube coloured by its second attribute, drawn by several tests.
Scene colouredTube(const std::string& name)
{
  const glm::dvec3 position{ 3, -3.5, 3 }, focal{ 0.2, 0, 1 };
  Scene s = scene(name, iga::makeTwistedTube<double>(0.7), position, focal, 35, 64, 64, { 0.0 });
  s.settings.colorAttribute = 1;
  return s;
}

std::vector<Scene> scenes()
{
  std::vector<Scene> all;
  const glm::dvec3 origin{ 0, 0, 0 };
  for (int degree = 2; degree <= 5; ++degree)
  {
    const glm::dvec3 position{ 1.2, -3.5, 2.1 }, focal{ 0.1, 0, 0 };
    all.push_back(scene("sphere p" + std::to_string(degree), iga::makeMarsdenSphere<double>(degree),
      position, focal, 40, 80, 64, { 0.0 }));
  }
  {
    const glm::dvec3 position{ -0.2, -1.6, 0.9 }, focal{ -0.5, 0, 0 };
    all.push_back(scene(
      "teardrop, all hits", iga::makeTeardrop<double>(1.2), position, focal, 40, 48, 40, { 0.0 }));
    all.back().settings.firstHitOnly = false;
  }
  all.push_back(colouredTube("twisted tube, two isovalues, colour"));
  all.back().settings.isovalues.push_back(0.3);
  {
    const glm::dvec3 position{ 2.6, -3.1, 3.4 }, focal{ 0, 0, 1 };
    all.push_back(scene("exact rational cylinder, radius attribute, height colour",
      iga::makeTube<double>(0.5, 0.0), position, focal, 35, 72, 64, { 0.75 }));
    all.back().settings.surfaceAttribute = 1;
    all.back().settings.colorAttribute = 2;
  }
  {
    const glm::dvec3 position{ 1.9, -2.4, 3.6 }, focal{ 0, 0, 1 };
    all.push_back(scene("tube with a collapsed axis", iga::makeTube<double>(0.0, 0.0), position,
      focal, 38, 64, 64, { 1.0 }));
  }
  {
    const glm::dvec3 position{ 0.1, 0.2, -0.1 }, focal{ 1, 0.3, 0 };
    all.push_back(scene("camera inside the sphere", iga::makeMarsdenSphere<double>(3), position,
      focal, 60, 40, 40, { 0.0 }));
  }
  {
    const glm::dvec3 position{ 0.6, -4, 1.1 };
    all.push_back(scene(
      "clipping planes", iga::makeMarsdenSphere<double>(3), position, origin, 35, 64, 64, { 0.0 }));
    all.back().settings.clipPlanes = { { 1, 0.2, 0, -0.1 }, { 0, 0, -2, 1 } };
  }
  {
    auto set = iga::makeMarsdenSphere<double>(3);
    const auto view = set.patches[0].view();
    const double fold[4] = { -1.5, 3.0, -3.0, 1.5 };
    for (int p = 0; p < view.pointCount(); ++p)
    {
      view.point(p)[0] = fold[p % 4];
    }
    const glm::dvec3 position{ 0.8, -4.2, 1.6 };
    all.push_back(
      scene("folded volume, all hits", std::move(set), position, origin, 40, 40, 40, { 0.0 }));
    all.back().settings.firstHitOnly = false;
  }
  {
    Scene teapot{ "teapot surfaces, all hits", {}, {}, {}, {} };
    for (int p = 0; p < 32; ++p)
      teapot.surfaces.push_back(iga::makeTeapotSurface<double>(p));
    teapot.camera = lookAt(teapot.patches(), { 4.5, -7.5, 5.0 }, { 0, 0, 1.4 }, 35);
    teapot.settings.width = 72;
    teapot.settings.height = 56;
    teapot.settings.firstHitOnly = false;
    all.push_back(std::move(teapot));
  }
  {
    // A sphere surface (coloured by its height) through the unit sphere's isosurface.
    const double centre[3] = { 0.6, 0, 0 };
    all.push_back(scene("sphere surface and isosurface, colour", iga::makeMarsdenSphere<double>(2),
      { 1.2, -3.5, 2.1 }, { 0.1, 0, 0 }, 40, 64, 56, { 0.0 }));
    all.back().surfaces = iga::makeSphereSurfaces<double>(0.8, centre).patches;
    all.back().settings.colorAttribute = 0;
  }
  {
    const glm::dvec3 position{ 0, -4, 0 };
    all.push_back(
      scene("depth cap", iga::makeMarsdenSphere<double>(4), position, origin, 35, 32, 32, { 0.0 }));
    all.back().settings.maxSubdivisionDepth = 3;
  }
  return all;
}

#ifdef IGAVIEW_DEVICE_LOGIC
/// The driver of every logic-test frame: it persists across frames and serves both entry points
/// (patches and NURBS volumes), as the CUDA engine does.
iga::sst::device::Driver& logicDriver()
{
  static iga::sst::device::Driver driver;
  return driver;
}
#endif

bool deviceRender(const Scene& s, GBuffer& out, FrameReport& report, std::string& skipped)
{
  const iga::sst::View view = iga::sst::makeView(s.camera, s.settings.width, s.settings.height);
#ifdef IGAVIEW_DEVICE_LOGIC
  (void)skipped;
  report = FrameReport();
  logicDriver().render(s.patches(), view, s.settings, out, report);
  return true;
#else
  if (!iga::sst::cuda::usable(skipped))
  {
    return false;
  }
  Settings settings = s.settings;
  settings.backend = iga::sst::Backend::Cuda;
  report =
    iga::sst::render(s.patches(), view, settings, iga::sst::Method::SharedSubdivisionTree, out);
  EXPECT_EQ(report.backend, "cuda") << report.notice;
  return true;
#endif
}

/// Runs a device frame (a call that returns false, saying why in `why`, where no GPU is usable)
/// or skips the test, visibly (GTEST_SKIP returns from the function it is written in).
#define FRAME_OR_SKIP(frame, why)                                                                  \
  do                                                                                               \
  {                                                                                                \
    if (!(frame))                                                                                  \
    {                                                                                              \
      GTEST_SKIP() << (why);                                                                       \
    }                                                                                              \
  } while (false)

/// The rational B-spline ball of iga::makeNurbsBall on 3 x 3 x 3 elements.
struct NurbsBall
{
  iga::BSplinePatch<double, 3> patch;
  iga::BezierExtraction<double, 3> extraction;

  explicit NurbsBall(double stretch)
    : patch(iga::makeNurbsBall<double>(3, stretch))
    , extraction(patch.knots, patch.degree, patch.netSize)
  {
  }

  iga::sst::NurbsVolumes volumes(uint64_t version) const
  {
    iga::sst::NurbsVolumes v;
    v.extractions = { &extraction };
    v.nets = { &patch.net };
    v.channels = iga::kFirstAttributeChannel + 1;
    v.extractionVersion = version;
    return v;
  }
};

bool deviceRenderNurbs(const iga::sst::NurbsVolumes& volumes, const iga::Camera& camera,
  const Settings& settings, GBuffer& out, FrameReport& report, std::string& skipped)
{
  const iga::sst::View view = iga::sst::makeView(camera, settings.width, settings.height);
#ifdef IGAVIEW_DEVICE_LOGIC
  (void)skipped;
  report = FrameReport();
  logicDriver().renderNurbs(volumes, view, settings, out, report);
  return true;
#else
  if (!iga::sst::cuda::usable(skipped))
  {
    return false;
  }
  Settings cuda = settings;
  cuda.backend = iga::sst::Backend::Cuda;
  report = iga::sst::render(volumes, view, cuda, iga::sst::Method::SharedSubdivisionTree, out);
  EXPECT_EQ(report.backend, "cuda") << report.notice;
  return true;
#endif
}

#ifdef IGAVIEW_DEVICE_LOGIC
constexpr int kCoverageSlack = 0;
constexpr double kPositionTolerance = 1e-12;
#else
constexpr int kCoverageSlack = 3;
constexpr double kPositionTolerance = 1e-6;
#endif

class DeviceEngine : public ::testing::TestWithParam<int>
{
};

#ifdef IGAVIEW_DEVICE_LOGIC
/// On Thrust's host system the device driver makes the CPU driver's decisions, step for step
/// (on a GPU, rounding may move a silhouette pixel or a cut).
void expectSameSteps(const FrameReport& device, const FrameReport& cpu)
{
  EXPECT_EQ(device.iterations, cpu.iterations);
  EXPECT_EQ(device.newtonSolves, cpu.newtonSolves);
  EXPECT_EQ(device.newtonRuns, cpu.newtonRuns);
  EXPECT_EQ(device.newtonEvaluations, cpu.newtonEvaluations);
  EXPECT_EQ(device.subdividedPatches, cpu.subdividedPatches);
  EXPECT_EQ(device.maxPatches, cpu.maxPatches);
  EXPECT_EQ(device.maxTuples, cpu.maxTuples);
  EXPECT_EQ(device.unresolvedPixels, cpu.unresolvedPixels);
  EXPECT_EQ(device.unresolvedAtDepthCap, cpu.unresolvedAtDepthCap);
  EXPECT_EQ(device.unresolvedAtBudget, cpu.unresolvedAtBudget);
}
#endif

/// Compares a device frame with the CPU driver's frame of the same scene.
void expectMatchesTheCpuDriver(
  const Scene& s, const GBuffer& device, const FrameReport& deviceReport)
{
  Settings settings = s.settings;
  settings.backend = iga::sst::Backend::Cpu;
  GBuffer cpu;
  const FrameReport cpuReport =
    iga::sst::render(s.patches(), s.camera, settings, iga::sst::Method::SharedSubdivisionTree, cpu);
  ASSERT_EQ(device.width, cpu.width);
  ASSERT_EQ(device.height, cpu.height);
  ASSERT_EQ(device.offsets.size(), cpu.offsets.size());
  int coverageDifferences = 0, compared = 0;
  double maxPosition = 0, maxNormal = 0, maxDepth = 0, maxColor = 0;
  for (int j = 0; j < cpu.height; ++j)
  {
    for (int i = 0; i < cpu.width; ++i)
    {
      if (device.hitCount(i, j) != cpu.hitCount(i, j))
      {
        ++coverageDifferences;
        continue;
      }
      for (int h = 0; h < cpu.hitCount(i, j); ++h)
      {
        const auto& a = device.firstHit(i, j)[h];
        const auto& b = cpu.firstHit(i, j)[h];
        ++compared;
        EXPECT_EQ(a.patch, b.patch) << "pixel " << i << "," << j;
        EXPECT_EQ(a.isovalue, b.isovalue) << "pixel " << i << "," << j;
        for (int d = 0; d < 3; ++d)
        {
          maxPosition = std::max(maxPosition, std::abs(a.position[d] - b.position[d]));
          maxNormal = std::max(maxNormal, std::abs(a.normal[d] - b.normal[d]));
        }
        maxDepth = std::max(maxDepth, std::abs(a.ndcDepth - b.ndcDepth));
        if (s.settings.colorAttribute >= 0)
        {
          maxColor = std::max(maxColor, std::abs(a.color - b.color));
        }
        else
        {
          EXPECT_TRUE(std::isnan(a.color));
        }
      }
    }
  }
  EXPECT_LE(coverageDifferences, kCoverageSlack);
  EXPECT_GT(compared, 100);
  EXPECT_LT(maxPosition, kPositionTolerance);
  EXPECT_LT(maxNormal, 1e3 * kPositionTolerance);
  EXPECT_LT(maxDepth, kPositionTolerance);
  EXPECT_LT(maxColor, kPositionTolerance);
  EXPECT_EQ(deviceReport.unresolvedPixels > 0, cpuReport.unresolvedPixels > 0);
  EXPECT_EQ(cpuReport.unresolvedPixels > 0, s.name == "depth cap");
  EXPECT_GT(deviceReport.uploadedBytes, 0u);
  // Offsets of every pixel, or of the covered ones (pixel and offset) when under half the image.
  const size_t pixels = size_t(device.width) * device.height, covered = device.coveredPixels();
  const size_t offsetBytes =
    (2 * covered < pixels ? 2 * covered + 1 : pixels + 1) * sizeof(uint32_t);
  EXPECT_EQ(deviceReport.downloadedBytes, offsetBytes + device.hits.size() * sizeof(iga::sst::Hit));
  EXPECT_EQ(cpuReport.downloadedBytes, 0u);
#ifdef IGAVIEW_DEVICE_LOGIC
  expectSameSteps(deviceReport, cpuReport);
#endif
}

TEST_P(DeviceEngine, MatchesTheCpuDriver)
{
  static const std::vector<Scene> all = scenes();
  const Scene& s = all[GetParam()];
  SCOPED_TRACE(s.name);
  GBuffer device;
  FrameReport deviceReport;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, device, deviceReport, why), why);
  expectMatchesTheCpuDriver(s, device, deviceReport);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DeviceEngine, ::testing::Range(0, int(scenes().size())));

/// A budget far below the frame's needs (64 KiB besides the image's) leaves pixels unresolved
/// and bounds the working set.
TEST(DeviceEngineCaps, MemoryBudgetIsReportedNotExceeded)
{
  const glm::dvec3 position{ 0, -4, 0 }, origin{ 0, 0, 0 };
  Scene s =
    scene("budget", iga::makeMarsdenSphere<double>(4), position, origin, 35, 32, 32, { 0.0 });
  s.settings.memoryBudgetBytes = iga::sst::imageBytes(s.settings) + 64 * 1024;
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
  EXPECT_GT(report.unresolvedAtBudget, 0u);
  EXPECT_GT(report.unresolvedPixels, 0u);
  EXPECT_LE(report.peakBytes, size_t(1) << 20);
}

/// The budget less the image's share caps the working set it names
/// (FrameReport::peakBudgetedBytes) in both drivers, which give up the same work under it:
/// every scene at a half, a quarter and an eighth of what it takes without a cap, pixels left
/// unresolved each time.
TEST(DeviceEngineCaps, BudgetCapsTheWorkingSet)
{
  std::string why;
  for (Scene s : scenes())
  {
    SCOPED_TRACE(s.name);
    Settings cpu = s.settings;
    cpu.backend = iga::sst::Backend::Cpu;
    GBuffer out;
    const size_t unbounded =
      iga::sst::render(s.patches(), s.camera, cpu, iga::sst::Method::SharedSubdivisionTree, out)
        .peakBudgetedBytes;
    for (size_t fraction : { 2, 4, 8 })
    {
      SCOPED_TRACE(fraction);
      const size_t loopBudget = unbounded / fraction;
      cpu.memoryBudgetBytes = s.settings.memoryBudgetBytes = iga::sst::imageBytes(cpu) + loopBudget;
      const FrameReport cpuReport =
        iga::sst::render(s.patches(), s.camera, cpu, iga::sst::Method::SharedSubdivisionTree, out);
      EXPECT_LE(cpuReport.peakBudgetedBytes, loopBudget);
      EXPECT_GT(cpuReport.unresolvedAtBudget, 0u);
      GBuffer device;
      FrameReport deviceReport;
      if (!deviceRender(s, device, deviceReport, why))
      {
        continue; // no GPU: the CPU driver is checked, then the test says it skipped the GPU
      }
      EXPECT_LE(deviceReport.peakBudgetedBytes, loopBudget);
      EXPECT_GT(deviceReport.unresolvedAtBudget, 0u);
#ifdef IGAVIEW_DEVICE_LOGIC
      expectSameSteps(deviceReport, cpuReport);
      EXPECT_EQ(device.offsets, out.offsets);
#endif
    }
  }
  if (!why.empty())
  {
    GTEST_SKIP() << "the CPU driver passed; " << why;
  }
}

/// With a data version the device keeps its copy of the patches (and its shading patches): a
/// camera move uploads only the isovalues, a new colour attribute or a new version (the tube
/// twisted further) uploads the patches again but not their shapes, and every frame matches the
/// CPU driver.
TEST(DeviceEngineCaps, CameraMoveReusesTheDeviceCopy)
{
  Scene s = colouredTube("tube, version 1");
  s.settings.dataVersion = 1;
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
  size_t patchBytes = 0;
  for (const auto& patch : s.set.patches)
  {
    patchBytes += patch.view().valueCount() * sizeof(double);
  }
  EXPECT_GE(report.uploadedBytes, patchBytes);
  expectMatchesTheCpuDriver(s, out, report);

  const glm::dvec3 moved{ -2.5, -3.8, 2.2 };
  s.camera = lookAt(s.set, moved, s.camera.focalPoint, 35);
  ASSERT_TRUE(deviceRender(s, out, report, why));
  EXPECT_EQ(report.uploadedBytes, sizeof(double)); // the one isovalue
  expectMatchesTheCpuDriver(s, out, report);

  s.settings.colorAttribute = 0;
  ASSERT_TRUE(deviceRender(s, out, report, why));
  EXPECT_EQ(report.uploadedBytes, patchBytes + sizeof(double)); // the shapes stay
  expectMatchesTheCpuDriver(s, out, report);

  s.set = iga::makeTwistedTube<double>(0.9);
  s.settings.dataVersion = 2;
  ASSERT_TRUE(deviceRender(s, out, report, why));
  EXPECT_EQ(report.uploadedBytes, patchBytes + sizeof(double));
  expectMatchesTheCpuDriver(s, out, report);
}

/// Transfers larger than the staging buffer go a chunk at a time: with 4 KiB chunks the patches
/// (12 KiB), the ball's net (5 KiB) and the G-buffer (16 KiB of offsets, 45 KiB of hits)
/// cross in several chunks, and the frames still match the CPU driver's. A smaller chunk is
/// refused before anything is copied.
TEST(DeviceEngineCaps, TransfersGoInChunks)
{
  Scene s = colouredTube("tube, 4 KiB chunks");
  s.settings.transferChunkBytes = 4096;
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
  EXPECT_GT(report.uploadedBytes, 2 * s.settings.transferChunkBytes);
  EXPECT_GT(out.hits.size() * sizeof(iga::sst::Hit), 10 * s.settings.transferChunkBytes);
  expectMatchesTheCpuDriver(s, out, report);

  const NurbsBall ball(1.0);
  Scene n{ "NURBS ball, 4 KiB chunks", { iga::sst::extractElements(ball.volumes(0)), { "ball" } },
    {}, s.settings, {} };
  n.camera = lookAt(n.set, s.camera.position, { 0, 0, 0 }, 35);
  n.settings.colorAttribute = -1;
  ASSERT_GT(ball.patch.net.size() * sizeof(double), n.settings.transferChunkBytes);
  ASSERT_TRUE(deviceRenderNurbs(ball.volumes(4), n.camera, n.settings, out, report, why));
  expectMatchesTheCpuDriver(n, out, report);

  s.settings.transferChunkBytes = 4095;
  try
  {
    deviceRender(s, out, report, why);
    ADD_FAILURE() << "a 4095-byte chunk was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "transfer chunk of 4095 bytes is below 4096");
  }
}

/// `count` slabs one behind the other along +y from y = 1, `spacing` apart and half as thick,
/// `halfWidth` wide in x and z, seen by a camera at the origin looking along +y. Each holds the
/// plane through its middle (the isovalue 0 of y minus that middle), facing the camera: every
/// slab covers the whole image, and every pixel's first hit lies on the nearest slab's plane.
Scene slabStack(int count, double spacing, double halfWidth, int width, int height)
{
  const int degrees[3] = { 1, 1, 1 };
  iga::VolumeSet<double> slabs;
  slabs.attributeNames = { "y" };
  for (int k = 0; k < count; ++k)
  {
    const double y = 1 + spacing * k;
    iga::Polynomial3<double> field(0, 1, 0);
    field.at(0, 1, 0) = 1;
    field.at(0, 0, 0) = -(y + 0.25 * spacing);
    const double lo[3] = { -halfWidth, y, -halfWidth };
    const double hi[3] = { halfWidth, y + 0.5 * spacing, halfWidth };
    slabs.patches.push_back(iga::makePolynomialVolume(field, lo, hi, degrees));
  }
  const glm::dvec3 position{ 0, 0, 0 }, focal{ 0, 1, 0 };
  return scene("slabs", std::move(slabs), position, focal, 40, width, height, { 0.0 });
}

/// The 10k-patch blade under a 128 KiB budget (besides the image's): the round's nodes alone fill
/// it, so no tuple fits. The overlap stage lets a band's worth in (a tuple per work item) rather
/// than one node an iteration, which took thousands of iterations (the 800k blade at 2160p under 16
/// MiB: 4 404 iterations, 12.5 s instead of 2.4 s).
TEST(DeviceEngineCaps, RoundOverTheBudgetMovesOnABandAtATime)
{
  auto blade = iga::makeBlade<double>(iga::bladeLayout(10000), 0.0);
  double bounds[6];
  iga::sst::patchBounds(blade.patches, bounds);
  Scene s{ "blade, 128 KiB", std::move(blade),
    iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30), {}, {} };
  s.settings.width = 160;
  s.settings.height = 120;
  s.settings.isovalues = { 0.3 };
  s.settings.memoryBudgetBytes = iga::sst::imageBytes(s.settings) + 128 * 1024;
  Settings cpu = s.settings;
  cpu.backend = iga::sst::Backend::Cpu;
  GBuffer out;
  const FrameReport cpuReport =
    iga::sst::render(s.patches(), s.camera, cpu, iga::sst::Method::SharedSubdivisionTree, out);
  EXPECT_LE(cpuReport.iterations, 4);
  EXPECT_GT(cpuReport.unresolvedAtBudget, 0u);
  EXPECT_GT(out.coveredPixels(), 50u);
  GBuffer device;
  FrameReport deviceReport;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, device, deviceReport, why), why);
  EXPECT_LE(deviceReport.iterations, 4);
#ifdef IGAVIEW_DEVICE_LOGIC
  expectSameSteps(deviceReport, cpuReport);
  EXPECT_EQ(device.offsets, out.offsets);
#endif
}

/// Chunks of 2 MiB are gathered and emptied on two host threads (one per MiB): the 10k-patch
/// blade's 10 MB of coefficients go up in several chunks; a slab over a whole 1024 x 1024 image
/// (a dense frame: every pixel's offset is sent) brings back 4 MiB of offsets and 104 MiB of
/// hits in several. Both frames still equal the CPU driver's.
TEST(DeviceEngineCaps, LargeChunksAreCopiedOnSeveralThreads)
{
  auto blade = iga::makeBlade<double>(iga::bladeLayout(10000), 0.0);
  double bounds[6];
  iga::sst::patchBounds(blade.patches, bounds);
  Scene s{ "blade, 2 MiB chunks", std::move(blade),
    iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30), {}, {} };
  s.settings.width = 1920;
  s.settings.height = 1080;
  s.settings.isovalues = { 0.3 };
  s.settings.threads = 2;
  s.settings.transferChunkBytes = size_t(2) << 20;
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
  EXPECT_GT(report.uploadedBytes, 4 * s.settings.transferChunkBytes);
  expectMatchesTheCpuDriver(s, out, report);

  Scene slab = slabStack(1, 0.01, 100, 1024, 1024);
  slab.settings.threads = 2;
  slab.settings.transferChunkBytes = size_t(2) << 20;
  ASSERT_TRUE(deviceRender(slab, out, report, why));
  EXPECT_EQ(report.downloadedBytes,
    (1024 * 1024 + 1) * sizeof(uint32_t) + 1024 * 1024 * sizeof(iga::sst::Hit));
  expectMatchesTheCpuDriver(slab, out, report);
}

/// Both drivers refuse the scene's frame with exactly this message.
void expectRefused(const Scene& s, const std::string& expected)
{
  GBuffer out;
  Settings cpu = s.settings;
  cpu.backend = iga::sst::Backend::Cpu;
  try
  {
    iga::sst::render(s.patches(), s.camera, cpu, iga::sst::Method::SharedSubdivisionTree, out);
    ADD_FAILURE() << "the CPU accepted the frame";
  }
  catch (const std::length_error& e)
  {
    EXPECT_EQ(e.what(), expected);
  }
  FrameReport report;
  std::string why;
  try
  {
    FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
    ADD_FAILURE() << "the device accepted the frame";
  }
  catch (const std::length_error& e)
  {
    EXPECT_EQ(e.what(), expected);
  }
}

/// Draws the scene in one pass and, under `loopBudget` besides the image's, in bands of rows, by
/// each CPU method and by the device driver: the G-buffers must be identical (offsets, patches,
/// positions and depths bit for bit), with the same Newton solves, since each pixel is solved in
/// one band. Returns the number of bands, which all of them must agree on.
int expectBandsMatchOnePass(
  Scene s, size_t loopBudget, std::initializer_list<iga::sst::Method> methods)
{
  const size_t budget = iga::sst::imageBytes(s.settings) + loopBudget;
  int bands = 0;
  for (auto method : methods)
  {
    SCOPED_TRACE(iga::sst::methodName(method));
    Settings cpu = s.settings;
    cpu.backend = iga::sst::Backend::Cpu;
    GBuffer whole, banded;
    const FrameReport wholeReport = iga::sst::render(s.patches(), s.camera, cpu, method, whole);
    EXPECT_EQ(wholeReport.bands, 1);
    cpu.memoryBudgetBytes = budget;
    const FrameReport bandedReport = iga::sst::render(s.patches(), s.camera, cpu, method, banded);
    EXPECT_TRUE(bands == 0 || bandedReport.bands == bands);
    bands = bandedReport.bands;
    EXPECT_EQ(bandedReport.newtonSolves, wholeReport.newtonSolves) << "each pixel in one band";
    EXPECT_EQ(bandedReport.newtonEvaluations, wholeReport.newtonEvaluations);
    EXPECT_EQ(bandedReport.unresolvedPixels, 0u);
    EXPECT_EQ(banded.offsets, whole.offsets);
    if (banded.hits.size() != whole.hits.size())
    {
      ADD_FAILURE() << banded.hits.size() << " hits in bands, " << whole.hits.size()
                    << " in one pass";
      continue;
    }
    for (size_t h = 0; h < banded.hits.size(); ++h)
    {
      EXPECT_EQ(banded.hits[h].patch, whole.hits[h].patch);
      EXPECT_EQ(banded.hits[h].ndcDepth, whole.hits[h].ndcDepth);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_EQ(banded.hits[h].position[d], whole.hits[h].position[d]);
      }
    }
  }
  s.settings.memoryBudgetBytes = budget;
  GBuffer device;
  FrameReport deviceReport;
  std::string why;
  if (!deviceRender(s, device, deviceReport, why))
  {
    return bands; // no GPU: the CPU methods were compared
  }
  EXPECT_EQ(deviceReport.bands, bands);
  expectMatchesTheCpuDriver(s, device, deviceReport);
  return bands;
}

/// 48 slabs over a 160 x 120 image make 7 680 (pixel, patch) pairs a row. A memory budget of
/// 2 MiB (66 bytes a pair: its work item and a tuple) takes 4 rows a pass: 30 bands. Every pixel's
/// first hit lies on the nearest slab's middle plane, y = 1.0025.
TEST(DeviceEngineCaps, ManyPairsAreDrawnInBands)
{
  const Scene s = slabStack(48, 0.01, 100, 160, 120);
  EXPECT_EQ(expectBandsMatchOnePass(s, size_t(2) << 20,
              { iga::sst::Method::BasicScheme, iga::sst::Method::SharedSubdivisionTree }),
    30);
  GBuffer out;
  iga::sst::render(s.patches(), s.camera, s.settings, iga::sst::Method::SharedSubdivisionTree, out);
  ASSERT_EQ(out.hits.size(), size_t(160 * 120)) << "one hit a pixel";
  for (const iga::sst::Hit& hit : out.hits)
  {
    EXPECT_EQ(hit.patch, 0);
    EXPECT_NEAR(hit.position[1], 1.0025, 1e-9);
  }
}

/// A row needing more pairs than the budget allows is drawn as a band of its own (rows are not
/// split): a 64 KiB budget takes 992 pairs, the slabs' rows have 7 680 each, so 120 bands.
TEST(DeviceEngineCaps, RowOverTheBudgetIsABandOfItsOwn)
{
  EXPECT_EQ(expectBandsMatchOnePass(slabStack(48, 0.01, 100, 160, 120), 64 * 1024,
              { iga::sst::Method::SharedSubdivisionTree }),
    120);
}

/// Band edges across patch boxes: 40 slabs, the far ones narrower than the view, so their boxes
/// end inside the image, in all-hits mode; a budget of 300 000 bytes (4 545 pairs a band at
/// 66 bytes a pair) cuts the 37 rows into 10 bands and still leaves the loop room for every
/// tuple, for every CPU method and the device.
TEST(DeviceEngineCaps, BandEdgesAcrossBoxesInAllHitsMode)
{
  Scene s = slabStack(40, 0.04, 0.5, 40, 37);
  s.settings.firstHitOnly = false;
  s.settings.bruteForceLevels = 2;
  EXPECT_EQ(expectBandsMatchOnePass(s, 300000,
              { iga::sst::Method::BasicScheme, iga::sst::Method::SharedSubdivisionTree,
                iga::sst::Method::BruteForce }),
    10);
}

/// Pairs have 32-bit indices in both drivers, whatever the budget: 262 144 slabs over a row of
/// 16 384 pixels make 2^32 pairs, one too many, and a row is never split. Refused before the
/// pairs are allocated, where a wrapped count would have indexed out of bounds.
TEST(DeviceEngineCaps, RowBeyond32BitIndicesIsRefused)
{
  Scene s = slabStack(262144, 1e-5, 1e5, 16384, 1);
  s.settings.memoryBudgetBytes = size_t(1) << 40;
  expectRefused(s, "the frame needs 4294967296 (pixel, patch) pairs in image row 0, more than the "
                   "engine's 32-bit indices allow (4294967295): lower the resolution or draw "
                   "fewer patches");
}

#ifdef IGAVIEW_DEVICE_LOGIC
/// The memory model's cuts with numbers worked by hand (the scenes above do not reach every
/// branch: the compaction's cap, for one, binds only when a failed tuple moves to more than
/// six children, which the subdivision's charge of one tuple each does not cover).
TEST(DeviceEngineCaps, MemoryModelCuts)
{
  using namespace iga::sst;
  const uint64_t running[] = { 0, 3, 3, 10, 12 }; // through element k
  auto through = [&](size_t k) { return running[k]; };
  EXPECT_EQ(prefixWithin(5, 2, through), 1u); // only the 0
  EXPECT_EQ(prefixWithin(5, 9, through), 3u);
  EXPECT_EQ(prefixWithin(5, 12, through), 5u);
  // Tuples fit past what is held: room for 10 tuples takes the first four nodes.
  const uint64_t held = 1000, budget = held + 10 * kBytesPerTuple;
  EXPECT_EQ(admittedNodes(5, budget, held, 0, false, through), 4u);
  // None fits and tuples are in flight: all wait but the ones without tuples.
  EXPECT_EQ(admittedNodes(5, held, held, 100, false, through), 1u);
  // None fits and none in flight: a band's worth (11 work items) comes in, or at least the
  // first node with tuples (1 work item).
  EXPECT_EQ(admittedNodes(5, held, held, 11, true, through), 4u);
  EXPECT_EQ(admittedNodes(5, held, held, 1, true, through), 3u);
  // Handed-on tuples: 8 bytes each now, kBytesPerTuple each next to the work items and the kept
  // children later; the smaller room wins, and none past the budget.
  EXPECT_EQ(nextTupleRoom(1000, 920, 0, 0), 10u);
  EXPECT_EQ(nextTupleRoom(1000, 0, 0, 1000 - 3 * kBytesPerTuple), 3u);
  EXPECT_EQ(nextTupleRoom(1000, 0, 1000 / kBytesPerWorkItem + 1, 0), 0u);
  EXPECT_EQ(nextTupleRoom(1000, 1001, 0, 0), 0u);
  // Splitting: the children, their copy and one tuple per failed one; a surface's four
  // children take eight slots.
  EXPECT_EQ(
    splitBytes(10, 8, 3), 2 * (8 * kBytesPerNode + 80 * sizeof(double)) + 3 * kBytesPerTuple);
  EXPECT_EQ(
    splitBytes(10, 4, 3), 2 * (8 * kBytesPerNode + 40 * sizeof(double)) + 3 * kBytesPerTuple);
}

/// Host arrays read as one sequence: every range of the parts' concatenation, across empty
/// parts and part boundaries.
TEST(DeviceEngineCaps, HostSequenceCopiesAnyRange)
{
  const std::vector<std::vector<double>> parts = { { 1, 2, 3 }, {}, { 4, 5, 6, 7, 8 }, { 9 }, {} };
  iga::sst::device::HostSequence sequence;
  for (const auto& part : parts)
  {
    sequence.append(part.data(), part.size());
  }
  ASSERT_EQ(sequence.size(), 9u);
  for (size_t first = 0; first <= 9; ++first)
  {
    for (size_t last = first; last <= 9; ++last)
    {
      std::vector<double> copied(last - first, -1);
      sequence.copy(first, last, copied.data());
      for (size_t k = first; k < last; ++k)
      {
        EXPECT_EQ(copied[k - first], double(k + 1)) << first << ".." << last;
      }
    }
  }
}
#endif

/// The ball's host-extracted elements as a scene, for the CPU driver's reference frames.
Scene ballScene(const NurbsBall& ball, uint64_t dataVersion)
{
  Scene s{ "NURBS ball", { iga::sst::extractElements(ball.volumes(0)), { "ball" } }, {}, {}, {} };
  const glm::dvec3 position{ 2.8, -3.6, 2.2 }, origin{ 0, 0, 0 };
  s.camera = lookAt(s.set, position, origin, 35);
  s.settings.width = 72;
  s.settings.height = 64;
  s.settings.isovalues = { 0.0 };
  s.settings.dataVersion = dataVersion;
  return s;
}

/// NURBS volumes extracted on the device draw what their host-extracted elements draw; a moved
/// net (new data version, same extraction version) is all a deforming frame sends, and a camera
/// move sends only the isovalues.
TEST(DeviceEngineCaps, NurbsVolumesExtractedOnTheDevice)
{
  const NurbsBall ball(1.0), stretched(1.15);
  Scene s = ballScene(ball, 7);
  ASSERT_EQ(s.set.patches.size(), 27u);
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRenderNurbs(ball.volumes(3), s.camera, s.settings, out, report, why), why);
  expectMatchesTheCpuDriver(s, out, report);
  const size_t netBytes = ball.patch.net.size() * sizeof(double);
  EXPECT_GT(report.uploadedBytes, netBytes); // extraction operators too

  // The volume deforms: only the net moves.
  s.set.patches = iga::sst::extractElements(stretched.volumes(0));
  s.settings.dataVersion = 8;
  ASSERT_TRUE(deviceRenderNurbs(stretched.volumes(3), s.camera, s.settings, out, report, why));
  EXPECT_EQ(report.uploadedBytes, netBytes + sizeof(double));
  expectMatchesTheCpuDriver(s, out, report);

  // The camera moves: nothing but the isovalue.
  const glm::dvec3 moved{ -3.0, -2.9, 1.4 }, origin{ 0, 0, 0 };
  s.camera = lookAt(s.set, moved, origin, 35);
  ASSERT_TRUE(deviceRenderNurbs(stretched.volumes(3), s.camera, s.settings, out, report, why));
  EXPECT_EQ(report.uploadedBytes, sizeof(double));
  expectMatchesTheCpuDriver(s, out, report);
}

/// Patches that fail the device's check after they replaced a NURBS volume's elements there
/// leave no stale copy: the same NURBS versions afterwards are extracted again, not read with
/// the patches' shapes.
TEST(DeviceEngineCaps, RejectedPatchesReplaceTheNurbsCopy)
{
  const NurbsBall ball(1.0);
  const Scene s = ballScene(ball, 11);
  GBuffer out;
  FrameReport report;
  std::string why;
  FRAME_OR_SKIP(deviceRenderNurbs(ball.volumes(12), s.camera, s.settings, out, report, why), why);
  expectMatchesTheCpuDriver(s, out, report);

  Scene bad = colouredTube("tube with a NaN");
  bad.set.patches[6].view().point(3)[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(deviceRender(bad, out, report, why), std::invalid_argument);

  ASSERT_TRUE(deviceRenderNurbs(ball.volumes(12), s.camera, s.settings, out, report, why));
  EXPECT_GT(report.uploadedBytes, ball.patch.net.size() * sizeof(double)) << "extracted again";
  expectMatchesTheCpuDriver(s, out, report);
}

/// The message both backends refuse the ball's frame with ("" when one draws it).
std::vector<std::string> refusalsOnBothBackends(const NurbsBall& ball)
{
  iga::Camera camera;
  Settings settings;
  settings.width = settings.height = 16;
  settings.isovalues = { 0.0 };
  GBuffer out;
  std::vector<std::string> messages;
  for (auto backend : { iga::sst::Backend::Cpu, iga::sst::Backend::Cuda })
  {
    settings.backend = backend;
    messages.emplace_back();
    try
    {
      iga::sst::render(ball.volumes(0), iga::sst::makeView(camera, 16, 16), settings,
        iga::sst::Method::SharedSubdivisionTree, out);
    }
    catch (const std::invalid_argument& e)
    {
      messages.back() = e.what();
    }
  }
  return messages;
}

/// A malformed NURBS net is reported with its volume and point, whatever the backend.
TEST(DeviceEngineCaps, BadNurbsNetIsRejected)
{
  NurbsBall ball(1.0);
  ball.patch.net[5 * 7 + iga::kWeightChannel] = -1;
  for (const std::string& message : refusalsOnBothBackends(ball))
    EXPECT_EQ(message, "volume 0: control point (2, 1, 0) has non-positive weight -1.000000");
  // A corner weight 1e7 times the others': of the 3x3x3 elements only (2, 0, 0) has control
  // point (4, 0, 0), as its corner.
  ball.patch.net[5 * 7 + iga::kWeightChannel] =
    NurbsBall(1.0).patch.net[5 * 7 + iga::kWeightChannel];
  for (int c = 0; c < 5; ++c)
    ball.patch.net[5 * 4 + c] *= 1e7;
  for (const std::string& message : refusalsOnBothBackends(ball))
  {
    EXPECT_EQ(message.rfind("volume 0: element (2, 0, 0): its Bézier weights range over ", 0), 0u)
      << message;
    EXPECT_NE(message.find(": more than the 1e+06 that subdivision resolves"), std::string::npos)
      << message;
  }
  ball.patch.net.pop_back();
  try
  {
    iga::sst::extractElements(ball.volumes(0));
    ADD_FAILURE() << "a short net was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "volume 0: control net has 624 values, expected 625");
  }
}

/// Bad input gets the CPU path's message, naming the first bad patch (the device tests control
/// point values, the host the rest), and leaves the device ready for the next good frame.
TEST(DeviceEngineCaps, BadInputIsRejected)
{
  const glm::dvec3 position{ 3, -3.5, 3 }, focal{ 0.2, 0, 1 };
  const Scene good =
    scene("bad", iga::makeTwistedTube<double>(0.7), position, focal, 35, 48, 48, { 0.0 });
  ASSERT_EQ(good.set.patches.size(), 8u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::pair<std::string, std::function<void(Scene&)>>> breakages = {
    { "negative weight",
      [](Scene& s) { s.set.patches[2].view().point(5)[iga::kWeightChannel] = -1; } },
    { "NaN after a zero weight",
      [=](Scene& s)
      {
        s.set.patches[4].view().point(0)[0] = nan;
        s.set.patches[1].view().point(7)[iga::kWeightChannel] = 0;
      } },
    { "NaN attribute",
      [=](Scene& s) { s.set.patches[3].view().point(2)[iga::kFirstAttributeChannel] = nan; } },
    { "weights ranging over more than kMaxWeightRatio",
      [](Scene& s)
      {
        double* point = s.set.patches[6].view().point(4);
        for (int c = 0; c < s.set.patches[6].channels(); ++c)
          point[c] *= 2 * iga::kMaxWeightRatio;
      } },
    { "missing colour attribute", [](Scene& s) { s.settings.colorAttribute = 4; } },
  };
  GBuffer out;
  FrameReport report;
  std::string why;
  for (const auto& breakage : breakages)
  {
    SCOPED_TRACE(breakage.first);
    Scene s = good;
    s.settings.dataVersion = 5;
    breakage.second(s);
    std::string cpuMessage;
    try
    {
      iga::sst::render(s.patches(),
        iga::sst::makeView(s.camera, s.settings.width, s.settings.height), s.settings,
        iga::sst::Method::SharedSubdivisionTree, out);
    }
    catch (const std::invalid_argument& e)
    {
      cpuMessage = e.what();
    }
    ASSERT_NE(cpuMessage, "") << "the CPU path accepted the input";
    try
    {
      FRAME_OR_SKIP(deviceRender(s, out, report, why), why);
      ADD_FAILURE() << "accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_EQ(std::string(e.what()), cpuMessage);
    }
  }
  // The same data version, now with good data: drawn as the CPU draws it.
  Scene s = good;
  s.settings.dataVersion = 5;
  ASSERT_TRUE(deviceRender(s, out, report, why));
  expectMatchesTheCpuDriver(s, out, report);
}

void cheeseCutOpenMatchesTheCpuDriver(bool opaque)
{
  const auto cheese = iga::makeCheese<double>();
  iga::sst::CsgScene csg;
  csg.inputs.push_back({ &cheese.patches, cheese.attributeNames, nullptr });
  csg.expression = iga::csg::parseExpression("(cheese<0 - holes<0) & plane(0, 1, 0, -0.45)");
  csg.slices = { { 1, 0, 0, -1.3 } };
  csg.colorAttribute = "cheese";
  const iga::Camera camera = lookAt(cheese, { 3.5, -3.0, 2.5 }, { 1, 0.6, 0.5 }, 35);
  Settings settings;
  settings.width = settings.height = 64;
  settings.firstHitOnly = opaque;
  const iga::sst::View view = iga::sst::makeView(camera, 64, 64);
  GBuffer cpu, device;
  iga::sst::renderCsg(csg, view, settings, iga::sst::Method::SharedSubdivisionTree, cpu);
  ASSERT_GT(cpu.coveredPixels(), 800u);
#ifdef IGAVIEW_DEVICE_LOGIC
  iga::sst::renderCsg(
    csg, view, settings,
    [&](const iga::sst::Scene& pass, const Settings& passSettings, GBuffer& out)
    {
      FrameReport report;
      logicDriver().render(pass, view, passSettings, out, report);
      return report;
    },
    device);
  EXPECT_TRUE(igatest::identicalGBuffers(cpu, device));
#else
  std::string why;
  if (!iga::sst::cuda::usable(why))
  {
    GTEST_SKIP() << why;
  }
  settings.backend = iga::sst::Backend::Cuda;
  const auto report =
    iga::sst::renderCsg(csg, view, settings, iga::sst::Method::SharedSubdivisionTree, device);
  EXPECT_EQ(report.backend, "cuda") << report.notice;
  igatest::expectSameFirstHits(cpu, device, 8, kPositionTolerance);
#endif
}

/// A CSG frame, the cheese cut open with a slice, its passes drawn on the device: the same
/// result as on CPU threads (the classification runs on the host for both), every layer and
/// opaque (its passes bounded by per-pixel far depths).
TEST(DeviceEngineCsg, CheeseCutOpenWithASliceMatchesTheCpuDriver)
{
  for (const bool opaque : { false, true })
  {
    SCOPED_TRACE(opaque ? "opaque" : "every layer");
    cheeseCutOpenMatchesTheCpuDriver(opaque);
  }
}

} // namespace
