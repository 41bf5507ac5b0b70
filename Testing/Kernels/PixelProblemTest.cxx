// The per-tuple exclusion proofs of the SST solution stage against multi-start Newton: a proof
// must never drop a (pixel, node) pair whose ray meets the isosurface inside the node, and the
// sharper proof must drop most pairs whose ray misses it. The directions a node's split halves.
#include "iga/sst/PixelProblem.h"
#include "iga/Camera.h"
#include "iga/Datasets.h"
#include "iga/sst/Tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{

struct ExclusionCounts
{
  int rootPairs = 0;        ///< pairs with a root strictly inside the node
  int missPairs = 0;        ///< pairs where no start converged
  int missesAlongRows = 0;  ///< of those, proved by excludesPixelAlongRows
  int missesByMean = 0;     ///< of those, proved by excludesPixel
  int missesByKrawczyk = 0; ///< of those, proved by the Krawczyk test
  int missesBySlabs = 0;    ///< of those, outside the node's slabs
  int wrongExclusions = 0;  ///< root pairs that some proof dropped
};

/// Window coordinates of a width x width image whose camera frames the patches' control points.
template<int Dim>
glm::dmat4 windowFraming(const std::vector<iga::PatchView<const double, Dim>>& patches, int width)
{
  double bounds[6];
  for (int d = 0; d < 3; ++d)
  {
    bounds[2 * d] = 1e300;
    bounds[2 * d + 1] = -1e300;
  }
  for (const auto& view : patches)
  {
    for (int p = 0; p < view.pointCount(); ++p)
    {
      for (int d = 0; d < 3; ++d)
      {
        const double x = view.point(p)[d] / view.point(p)[iga::kWeightChannel];
        bounds[2 * d] = std::min(bounds[2 * d], x);
        bounds[2 * d + 1] = std::max(bounds[2 * d + 1], x);
      }
    }
  }
  const iga::Camera camera = iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30);
  glm::dmat4 window(1.0);
  window[0][0] = window[3][0] = window[1][1] = window[3][1] = 0.5 * width;
  return window * iga::worldToClip(camera, 1.0);
}

/// Every node of a uniform subdivision of `world` to `depth` that may hold the surface, against
/// every pixel of a width x width image that its box covers.
ExclusionCounts countExclusions(
  const iga::BezierVolume<double>& world, double isovalue, int width, int depth)
{
  const auto view = world.view();
  const glm::dmat4 windowFromWorld = windowFraming<3>({ view }, width);

  const int count = view.pointCount() * iga::sst::kScreenChannels;
  std::vector<double> level(count);
  iga::sst::makeScreenPatch<double>(
    view, windowFromWorld, iga::kFirstAttributeChannel, level.data());
  for (int d = 0; d < depth; ++d)
  {
    std::vector<double> next(level.size() * 8);
    for (size_t n = 0; n < level.size() / count; ++n)
    {
      iga::splitMidpoint<double, 3>(iga::VolumeView<const double>(level.data() + n * count,
                                      view.degree, iga::sst::kScreenChannels),
        next.data() + n * 8 * count);
    }
    level.swap(next);
  }

  ExclusionCounts counts;
  const double tolerance[3] = { 1e-6, 1e-6, 1e-9 };
  for (size_t n = 0; n < level.size() / count; ++n)
  {
    const iga::VolumeView<const double> node(
      level.data() + n * count, view.degree, iga::sst::kScreenChannels);
    const auto info = iga::sst::analyzeNode(node, isovalue);
    if (info.status != iga::ProjectionStatus::InFront || !info.mayContainSurface || !info.hasCentre)
    {
      continue;
    }
    for (int j = std::max(0, int(info.box.lo[1])); j <= std::min(width - 1, int(info.box.hi[1]));
         ++j)
    {
      for (int i = std::max(0, int(info.box.lo[0])); i <= std::min(width - 1, int(info.box.hi[0]));
           ++i)
      {
        if (!iga::sst::boxCoversPixel(info.box, i, j))
        {
          continue;
        }
        bool inside = false, converged = false;
        for (int s = 0; s < 27 && !inside; ++s)
        {
          const double start[3] = { 0.1 + 0.4 * (s % 3), 0.1 + 0.4 * (s / 3 % 3),
            0.1 + 0.4 * (s / 9) };
          double u[3], ndc;
          if (iga::sst::solvePixel<double>(node, i, j, isovalue, tolerance, start, u, ndc,
                iga::sst::ClipPlanes<double>()) != iga::sst::TupleOutcome::Undecided)
          {
            converged = true;
            inside = u[0] > 1e-6 && u[0] < 1 - 1e-6 && u[1] > 1e-6 && u[1] < 1 - 1e-6 &&
                     u[2] > 1e-6 && u[2] < 1 - 1e-6;
          }
        }
        const bool alongRows = iga::sst::excludesPixelAlongRows(node, info, i, j, isovalue, 7);
        const bool byMean = iga::sst::excludesPixel(node, i, j, isovalue);
        const glm::dvec3 residual(
          info.centre[0] - (i + 0.5), info.centre[1] - (j + 0.5), info.centre[2] - isovalue);
        const bool byKrawczyk =
          info.canExclude && iga::krawczykExcludes<double, 3>(info.inverse, info.spread, residual,
                               iga::NewtonSettings<double>().domainSlack);
        const bool bySlabs = !iga::sst::slabsCoverPixel(info.slabs, i, j);
        if (inside)
        {
          ++counts.rootPairs;
          counts.wrongExclusions += alongRows || byMean || byKrawczyk || bySlabs ? 1 : 0;
        }
        else if (!converged)
        {
          ++counts.missPairs;
          counts.missesAlongRows += alongRows ? 1 : 0;
          counts.missesByMean += byMean ? 1 : 0;
          counts.missesByKrawczyk += byKrawczyk ? 1 : 0;
          counts.missesBySlabs += bySlabs ? 1 : 0;
        }
      }
    }
  }
  return counts;
}

void expectSoundAndSharp(const ExclusionCounts& c)
{
  EXPECT_GT(c.rootPairs, 200) << "the scene should have many pairs with a root";
  EXPECT_GT(c.missPairs, 200) << "the scene should have many pairs without one";
  EXPECT_EQ(c.wrongExclusions, 0) << "a proof dropped a pair whose ray meets the surface";
  // The rows of J(centre)^-1 are the sharper directions: most misses are proved.
  EXPECT_GT(c.missesAlongRows, c.missPairs / 2);
  EXPECT_GT(c.missesAlongRows, c.missesByMean);
  std::printf("root pairs %d, miss pairs %d: proved along rows %d, by the mean %d, by Krawczyk "
              "%d, outside the slabs %d\n",
    c.rootPairs, c.missPairs, c.missesAlongRows, c.missesByMean, c.missesByKrawczyk,
    c.missesBySlabs);
}

TEST(PixelProblem, ExclusionsAreSoundOnTheSphere)
{
  const auto sphere = iga::makeMarsdenSphere<double>(2);
  expectSoundAndSharp(countExclusions(sphere.patches[0], 0.0, 96, 3));
}

TEST(PixelProblem, ExclusionsAreSoundOnTheTwistedTeardrop)
{
  const auto teardrop = iga::makeTeardrop<double>(1.2);
  expectSoundAndSharp(countExclusions(teardrop.patches[0], 0.0, 96, 3));
}

/// fn(node) for every screen node of the teapot framed in a width-wide image, each patch split
/// `depth` times in u and v.
template<class Fn>
void forEachTeapotNode(int width, int depth, Fn fn)
{
  const auto teapot = iga::makeTeapot<double>();
  std::vector<iga::PatchView<const double, 2>> views;
  for (const auto& patch : teapot.patches)
  {
    views.push_back(patch.view());
  }
  const glm::dmat4 windowFromWorld = windowFraming<2>(views, width);
  for (const auto& surface : views)
  {
    const auto world = iga::flatVolume(surface);
    const int count = world.pointCount() * iga::sst::kScreenChannels;
    std::vector<double> level(count);
    iga::sst::makeScreenPatch<double>(world, windowFromWorld, iga::kWeightChannel, level.data());
    for (int d = 0; d < depth; ++d)
    {
      std::vector<double> next(level.size() * 4);
      for (size_t n = 0; n < level.size() / count; ++n)
      {
        iga::sst::splitNode(iga::VolumeView<const double>(
                              level.data() + n * count, world.degree, iga::sst::kScreenChannels),
          0b011, next.data() + n * 4 * count);
      }
      level.swap(next);
    }
    for (size_t n = 0; n < level.size() / count; ++n)
    {
      fn(iga::VolumeView<const double>(
        level.data() + n * count, world.degree, iga::sst::kScreenChannels));
    }
  }
}

/// Every point of the teapot's surfaces, in nodes of a uniform subdivision three levels deep,
/// lies in its node's slabs (sampled on 9 x 9 parameters a node), and the slabs hold a good part
/// of the box's pixels fewer.
TEST(PixelProblem, SlabsHoldEveryPointOfTheirNodeOnTheTeapot)
{
  const int width = 256;
  int outside = 0, boxPixels = 0, slabPixels = 0;
  forEachTeapotNode(width, 3,
    [&](const iga::VolumeView<const double>& node)
    {
      iga::sst::NodeInfo<double> info;
      iga::sst::analyzeNodeBounds(node, 0.0, iga::sst::ClipPlanes<double>(), info);
      ASSERT_EQ(info.status, iga::ProjectionStatus::InFront);
      for (int s = 0; s < 81; ++s)
      {
        const double u[2] = { (s % 9) / 8.0, (s / 9) / 8.0 };
        double values[iga::sst::kScreenChannels];
        iga::evaluateHomogeneous<double, 2>(iga::surfaceOf(node), u, values, nullptr);
        const double x = values[iga::sst::kScreenX] / values[iga::sst::kScreenW];
        const double y = values[iga::sst::kScreenY] / values[iga::sst::kScreenW];
        outside += iga::sst::slabsHold(info.slabs, x, y) ? 0 : 1;
      }
      for (int j = std::max(0, int(info.box.lo[1])); j <= std::min(width - 1, int(info.box.hi[1]));
           ++j)
      {
        for (int i = std::max(0, int(info.box.lo[0]));
             i <= std::min(width - 1, int(info.box.hi[0])); ++i)
        {
          boxPixels += iga::sst::boxCoversPixel(info.box, i, j) ? 1 : 0;
          slabPixels += iga::sst::nodeCoversPixel(info, i, j) ? 1 : 0;
        }
      }
    });
  EXPECT_EQ(outside, 0) << "points of a node outside its slabs";
  EXPECT_GT(boxPixels, 1000);
  EXPECT_LT(slabPixels, boxPixels * 0.9) << "the slabs should drop a good part of the box";
  std::printf("pixels in the boxes %d, in boxes and slabs %d\n", boxPixels, slabPixels);
}

/// Newton's start from a node's quadratic model lands much nearer the root than the linear one,
/// on the teapot's nodes two splits deep (tens of pixels wide) that the engine would solve
/// (certified), for points all over them.
TEST(PixelProblem, QuadraticStartLandsNearerTheRootThanTheLinearOne)
{
  double linearError = 0, quadraticError = 0;
  int samples = 0, worse = 0;
  forEachTeapotNode(512, 2,
    [&](const iga::VolumeView<const double>& node)
    {
      const auto info = iga::sst::analyzeNode(node, 0.0);
      if (!info.hasCentre || !info.certified)
      {
        return;
      }
      for (int s = 0; s < 25; ++s)
      {
        const double root[2] = { 0.1 + 0.2 * (s % 5), 0.1 + 0.2 * (s / 5) };
        double values[iga::sst::kScreenChannels];
        iga::evaluateHomogeneous<double, 2>(iga::surfaceOf(node), root, values, nullptr);
        const glm::dvec2 residual(
          info.centre[0] - values[iga::sst::kScreenX] / values[iga::sst::kScreenW],
          info.centre[1] - values[iga::sst::kScreenY] / values[iga::sst::kScreenW]);
        const glm::dvec2 linear = glm::dvec2(0.5) - glm::dmat2(info.centreInverse) * residual;
        const glm::dvec2 quadratic = iga::sst::detail::quadraticStart<double, 2>(info, residual);
        const double errors[2] = { glm::length(linear - glm::dvec2(root[0], root[1])),
          glm::length(quadratic - glm::dvec2(root[0], root[1])) };
        linearError += errors[0];
        quadraticError += errors[1];
        worse += errors[1] > errors[0] ? 1 : 0;
        ++samples;
      }
    });
  ASSERT_GT(samples, 2000);
  std::printf("certified nodes' mean parametric error of the start: linear %.3g, quadratic %.3g; "
              "worse in %d of %d\n",
    linearError / samples, quadraticError / samples, worse, samples);
  EXPECT_LT(quadraticError, 0.25 * linearError);
  EXPECT_LT(worse, samples / 20);
}

/// A degree-1 screen node (u, v, w in 0, 1 at its corners): window position X/W, Y/W and
/// attribute A/V from `corner`, each corner's homogeneous values scaled by `weight` (which leaves
/// the quotients alone), W scaled by `wSign` at corner 0. `surface`: the corners w = 0 alone.
template<class Corner>
std::vector<double> linearNode(Corner corner, bool surface, double wSign = 1)
{
  std::vector<double> values;
  for (int p = 0; p < (surface ? 4 : 8); ++p)
  {
    const glm::dvec3 u(p & 1, (p >> 1) & 1, (p >> 2) & 1);
    const glm::dvec3 v = corner(u); // X/W, Y/W, A/V
    const double weight = 1 + 3 * p, w = p == 0 ? wSign : 1;
    const double point[iga::sst::kScreenChannels] = { v.x * w, v.y * w, 0.5 * w, w, v.z, 1 };
    for (double x : point)
    {
      values.push_back(weight * x);
    }
  }
  return values;
}

int axesOf(const std::vector<double>& values, bool surface)
{
  const int degree[3] = { 1, 1, surface ? 0 : 1 };
  return iga::sst::splitAxes(
    iga::VolumeView<const double>(values.data(), degree, iga::sst::kScreenChannels));
}

TEST(PixelProblem, SplitAxesFollowWhatVaries)
{
  // 100 pixels along u, 2 along v: u for the window; the attribute along w: w.
  const auto stretched = [](const glm::dvec3& u)
  { return glm::dvec3(100 * u.x + 5, 2 * u.y + 5, u.z - 0.5); };
  EXPECT_EQ(axesOf(linearNode(stretched, false), false), 0b101);
  EXPECT_EQ(axesOf(linearNode(stretched, true), true), 0b01); // a surface has no attribute row
  // Within a quarter of the most: halved.
  const auto even = [](const glm::dvec3& u)
  { return glm::dvec3(10 * u.x + 3 * u.y, 10 * u.y - 3 * u.x, u.x + u.y + u.z); };
  EXPECT_EQ(axesOf(linearNode(even, false), false), 0b111);
  EXPECT_EQ(axesOf(linearNode(even, true), true), 0b11);
  // Nothing varies: all; a corner behind the eye plane (no window position): all.
  const auto still = [](const glm::dvec3&) { return glm::dvec3(5, 5, 0); };
  EXPECT_EQ(axesOf(linearNode(still, false), false), 0b111);
  EXPECT_EQ(axesOf(linearNode(stretched, false, -1), false), 0b111);
  EXPECT_EQ(axesOf(linearNode(stretched, true, 0), true), 0b11);
}

TEST(PixelProblem, ChildrenKeepTheirPlacePerDirection)
{
  using iga::sst::Node;
  const Node root = iga::sst::rootNode(0, 0);
  const Node a = iga::sst::childOf(root, 0b001, 1); // upper half along u
  EXPECT_EQ(a.level, 1);
  EXPECT_EQ(glm::ivec3(a.depth[0], a.depth[1], a.depth[2]), glm::ivec3(1, 0, 0));
  const Node b = iga::sst::childOf(a, 0b110, 2); // lower along v, upper along w
  EXPECT_EQ(b.level, 1);
  EXPECT_EQ(glm::ivec3(b.offset[0], b.offset[1], b.offset[2]), glm::ivec3(1, 0, 1));
  const Node c = iga::sst::childOf(b, 0b011, 3); // upper along u and v
  EXPECT_EQ(c.level, 2);
  EXPECT_EQ(glm::ivec3(c.depth[0], c.depth[1], c.depth[2]), glm::ivec3(2, 2, 1));
  EXPECT_EQ(glm::ivec3(c.offset[0], c.offset[1], c.offset[2]), glm::ivec3(3, 1, 1));
  // u in [0.75, 1], v in [0.25, 0.5], w in [0.5, 1].
  const double centre[3] = { 0.5, 0.5, 0.5 };
  EXPECT_EQ(iga::sst::patchParameter(c, centre, 0), 0.875);
  EXPECT_EQ(iga::sst::patchParameter(c, centre, 1), 0.375);
  EXPECT_EQ(iga::sst::patchParameter(c, centre, 2), 0.75);
  EXPECT_EQ(iga::sst::axesAtDepthCap(c, 2), 0b011);
  EXPECT_EQ(iga::sst::axesAtDepthCap(c, 1), 0b111);
  EXPECT_EQ(iga::sst::axesAtDepthCap(c, 3), 0);
}

} // namespace
