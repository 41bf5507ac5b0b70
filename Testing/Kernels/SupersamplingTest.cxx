// Silhouette supersampling: the moved view shifts every depth's point by the offset; the
// contrast test marks both sides of an edge and nothing else; the samples are the moved frames'
// hits at the marked pixels alone, on the ray-composition, tree and CSG paths; and the samples'
// coverage of a sphere's silhouette is the exact area of its disc in each pixel, far closer
// than a pixel centre's. The frustum form pays for the pixels a masked frame draws alone.
#include "iga/sst/Supersampling.h"
#include "iga/Camera.h"
#include "iga/FrustumForm.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Csg.h"
#include "iga/sst/Engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{

using iga::sst::GBuffer;

std::vector<iga::BezierVolume<double>> unitSphere()
{
  const double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  return { iga::makeAlgebraicVolume(iga::parsePolynomial("x^2 + y^2 + z^2 - 1"), box) };
}

/// Looking at the origin down -y, z up: the unit sphere's disc, of `radius` pixels for a
/// parallel camera, in a size x size image.
iga::Camera sphereCamera(bool parallel, int size, double radius)
{
  iga::Camera camera;
  camera.position = { 0.3, -4, 0.2 };
  camera.focalPoint = { 0, 0, 0 };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngle = 40;
  camera.parallelProjection = parallel;
  camera.parallelScale = 0.5 * size / radius;
  camera.clippingRange[0] = 1;
  camera.clippingRange[1] = 10;
  return camera;
}

iga::sst::Settings frameSettings(int size)
{
  iga::sst::Settings settings;
  settings.width = settings.height = size;
  settings.isovalues = { 0.0 };
  settings.threads = 2;
  return settings;
}

/// An opaque white pixel where the frame has a hit, a transparent one where it has none.
std::vector<float> coverageImage(const GBuffer& frame)
{
  std::vector<float> rgba(4 * size_t(frame.width) * size_t(frame.height), 0.0f);
  for (size_t p = 0; p + 1 < frame.offsets.size(); ++p)
  {
    if (frame.offsets[p] < frame.offsets[p + 1])
      std::fill(&rgba[4 * p], &rgba[4 * p + 4], 1.0f);
  }
  return rgba;
}

TEST(Supersampling, TheMovedViewShiftsEveryDepthByTheOffset)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (const bool parallel : { false, true })
  {
    const iga::sst::View view = iga::sst::makeView(sphereCamera(parallel, 80, 30), 80, 60);
    const iga::sst::View moved = iga::sst::offsetView(view, 80, 60, 0.375, -0.125);
    const glm::dmat4 before = iga::sst::windowFromWorld(view, 80, 60);
    const glm::dmat4 after = iga::sst::windowFromWorld(moved, 80, 60);
    for (int k = 0; k < 20; ++k)
    {
      const glm::dvec4 x(coordinate(random), 3 * coordinate(random), coordinate(random), 1);
      const glm::dvec4 a = before * x, b = after * x;
      // What lay at (x + 0.375, y - 0.125) lies at (x, y): a pixel samples its centre moved so.
      EXPECT_NEAR(b.x / b.w - a.x / a.w, -0.375, 1e-9);
      EXPECT_NEAR(b.y / b.w - a.y / a.w, 0.125, 1e-9);
      EXPECT_NEAR(b.z / b.w, a.z / a.w, 1e-12);
    }
    EXPECT_EQ(moved.eye, view.eye);
    EXPECT_EQ(moved.pixelFootprint, view.pixelFootprint);
  }
}

TEST(Supersampling, TheContrastTestMarksBothSidesOfAnEdgeAndNothingElse)
{
  // 6 x 5 pixels: columns 0-2 one colour, 3-5 another 0.2 brighter in red; a missing pixel at
  // (0, 4).
  const int width = 6, height = 5;
  std::vector<float> rgba(4 * width * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
    {
      float* pixel = &rgba[4 * size_t(j * width + i)];
      pixel[0] = i < 3 ? 0.5f : 0.7f;
      pixel[1] = pixel[2] = 0.4f;
      pixel[3] = 1.0f;
    }
  std::fill(&rgba[4 * size_t(4 * width)], &rgba[4 * size_t(4 * width) + 4], 0.0f);
  const auto mask = iga::sst::contrastingPixels(rgba, width, height, 0.1f);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
    {
      const bool edge = i == 2 || i == 3;
      const bool besideTheMiss = (j == 4 && i <= 1) || (j == 3 && i == 0);
      EXPECT_EQ(mask[size_t(j * width + i)], edge || besideTheMiss ? 1 : 0) << i << ", " << j;
    }
  // Above the colours' difference, only the miss's neighbours (alpha differs by 1).
  const auto coarse = iga::sst::contrastingPixels(rgba, width, height, 0.25f);
  size_t marked = 0;
  for (const uint8_t m : coarse)
    marked += m;
  EXPECT_EQ(marked, 3u);
  EXPECT_THROW(iga::sst::contrastingPixels(rgba, width + 1, height, 0.1f), std::invalid_argument);
}

/// Draws the unit sphere by each path: ray composition, the tree, and CSG (the solid f < 0 cut
/// at z = -0.3, whose cap faces away from the camera: the cap's pass has hits, none first).
struct SpherePaths
{
  std::vector<iga::BezierVolume<double>> volumes = unitSphere();

  GBuffer draw(int path, const iga::sst::View& view, const iga::sst::Settings& settings,
    iga::sst::FrameReport* report = nullptr) const
  {
    GBuffer out;
    iga::sst::FrameReport r;
    if (path == 2)
    {
      iga::sst::CsgScene scene;
      scene.inputs.push_back({ &volumes, { "f" }, nullptr });
      scene.expression = iga::csg::parseExpression("f<0 & plane(0,0,1,0.3)");
      r = iga::sst::renderCsg(scene, view, settings, iga::sst::Method::Automatic, out);
    }
    else
    {
      const auto method =
        path == 0 ? iga::sst::Method::RayComposition : iga::sst::Method::SharedSubdivisionTree;
      r = iga::sst::render(iga::sst::Scene(volumes), view, settings, method, out);
    }
    if (report)
      *report = r;
    return out;
  }
};

TEST(Supersampling, SamplesAreTheMovedFramesAtTheMarkedPixelsAlone)
{
  const int size = 48;
  const iga::sst::View view = iga::sst::makeView(sphereCamera(false, size, 20), size, size);
  const iga::sst::Settings settings = frameSettings(size);
  const SpherePaths sphere;
  for (int path = 0; path < 3; ++path)
  {
    SCOPED_TRACE(path);
    const GBuffer centres = sphere.draw(path, view, settings);
    const auto mask = iga::sst::contrastingPixels(coverageImage(centres), size, size, 0.5f);
    std::array<GBuffer, iga::sst::kRotatedGridSamples> samples;
    const auto report = iga::sst::renderRotatedGridSamples(
      view, settings, mask,
      [&](const iga::sst::View& v, const iga::sst::Settings& s, GBuffer& out)
      {
        iga::sst::FrameReport r;
        out = sphere.draw(path, v, s, &r);
        return r;
      },
      samples);
    EXPECT_EQ(report.unresolvedPixels, 0u);
    // The work of the marked pixels alone, in every pass of a CSG frame too (its passes, the
    // sphere's, the cap's and the box's faces', each at most once a sample).
    const size_t marked = size_t(std::count(mask.begin(), mask.end(), 1));
    EXPECT_LE(report.composedRays, 3 * iga::sst::kRotatedGridSamples * marked);
    EXPECT_LE(report.newtonRuns, 3 * iga::sst::kRotatedGridSamples * marked);
    size_t sampledHits = 0;
    for (int k = 0; k < iga::sst::kRotatedGridSamples; ++k)
    {
      const GBuffer whole = sphere.draw(path,
        iga::sst::offsetView(view, size, size, iga::sst::kRotatedGridOffsets[k][0],
          iga::sst::kRotatedGridOffsets[k][1]),
        settings);
      for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
        {
          const size_t p = size_t(j * size + i);
          const iga::sst::Hit* hit = samples[size_t(k)].firstHit(i, j);
          const iga::sst::Hit* expected = whole.firstHit(i, j);
          if (!mask[p])
          {
            EXPECT_EQ(hit, nullptr) << i << ", " << j;
            continue;
          }
          ASSERT_EQ(hit != nullptr, expected != nullptr) << k << ": " << i << ", " << j;
          if (hit)
          {
            EXPECT_LT(glm::length(hit->position - expected->position), 1e-9);
            EXPECT_NEAR(glm::length(hit->position), 1.0, 1e-9);
            ++sampledHits;
          }
        }
    }
    // The silhouette's ring of pixels, about two a row and column of the disc.
    EXPECT_GT(marked, 40u);
    EXPECT_LT(marked, size_t(size * size) / 4);
    EXPECT_GT(sampledHits, marked);
  }
}

/// The area of the disc of `radius` about `centre` in pixel (i, j), by a 64 x 64 grid.
double discArea(double ci, double cj, double radius, int i, int j)
{
  int inside = 0;
  for (int a = 0; a < 64; ++a)
    for (int b = 0; b < 64; ++b)
    {
      const double x = i + (a + 0.5) / 64 - ci, y = j + (b + 0.5) / 64 - cj;
      inside += x * x + y * y <= radius * radius;
    }
  return inside / 4096.0;
}

TEST(Supersampling, TheSamplesCoverTheSilhouettePixelsAsTheDiscDoes)
{
  // A parallel view of the unit sphere, which lies at the focal point: a disc of 20.3 pixels'
  // radius about the image's centre.
  const int size = 64;
  const double radius = 20.3;
  const iga::Camera camera = sphereCamera(true, size, radius);
  const iga::sst::View view = iga::sst::makeView(camera, size, size);
  const iga::sst::Settings settings = frameSettings(size);
  const SpherePaths sphere;
  const GBuffer centres = sphere.draw(0, view, settings);
  const auto mask = iga::sst::contrastingPixels(coverageImage(centres), size, size, 0.5f);
  std::array<GBuffer, iga::sst::kRotatedGridSamples> samples;
  iga::sst::renderRotatedGridSamples(
    view, settings, mask,
    [&](const iga::sst::View& v, const iga::sst::Settings& s, GBuffer& out)
    {
      iga::sst::FrameReport r;
      out = sphere.draw(0, v, s, &r);
      return r;
    },
    samples);
  const double ci = size / 2.0, cj = size / 2.0;
  double centreError = 0, sampledError = 0, worst = 0, total = 0;
  size_t boundary = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
    {
      const size_t p = size_t(j * size + i);
      const double exact = discArea(ci, cj, radius, i, j);
      double covered = centres.firstHit(i, j) ? 1.0 : 0.0;
      if (mask[p])
      {
        covered = 0;
        for (const GBuffer& sample : samples)
          covered += sample.firstHit(i, j) ? 0.25 : 0.0;
      }
      total += covered;
      if (exact > 0 && exact < 1)
      {
        EXPECT_TRUE(mask[p] || exact < 0.05 || exact > 0.95) << i << ", " << j << ": " << exact;
        ++boundary;
        centreError += std::fabs((centres.firstHit(i, j) ? 1.0 : 0.0) - exact);
        sampledError += std::fabs(covered - exact);
        worst = std::max(worst, std::fabs(covered - exact));
      }
    }
  ASSERT_GT(boundary, 120u);
  centreError /= double(boundary);
  sampledError /= double(boundary);
  // Four samples leave at most about a quarter pixel wrong on a straight edge; a centre, half.
  EXPECT_LT(sampledError, 0.1) << "centre sampling's mean error " << centreError;
  EXPECT_LT(sampledError, 0.5 * centreError);
  EXPECT_LT(worst, 0.3);
  EXPECT_NEAR(total, M_PI * radius * radius, 0.002 * M_PI * radius * radius);
}

TEST(Supersampling, DrawnPixelsCountTheUnskippedPixelsOfABox)
{
  // A 10 x 6 image whose pixels (i + j) % 3 == 0 are drawn; boxes of NDC against a count.
  const int width = 10, height = 6;
  std::vector<double> far(size_t(width * height), -2.0);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      if ((i + j) % 3 == 0)
        far[size_t(j * width + i)] = INFINITY;
  const iga::DrawnPixels drawn(width, height, far);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> ndc(-1.2, 1.2);
  for (int trial = 0; trial < 200; ++trial)
  {
    double lo[2] = { ndc(random), ndc(random) }, hi[2] = { ndc(random), ndc(random) };
    for (int d = 0; d < 2; ++d)
      if (lo[d] > hi[d])
        std::swap(lo[d], hi[d]);
    // The pixels the box touches (pixel i spans NDC [2 i / width - 1, 2 (i + 1) / width - 1]).
    int count = 0;
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i)
      {
        const bool touched = 2.0 * (i + 1) / width - 1 > lo[0] && 2.0 * i / width - 1 < hi[0] &&
                             2.0 * (j + 1) / height - 1 > lo[1] && 2.0 * j / height - 1 < hi[1];
        count += touched && (i + j) % 3 == 0;
      }
    EXPECT_EQ(drawn.in(lo, hi), count) << lo[0] << " " << hi[0] << " " << lo[1] << " " << hi[1];
  }
  // Without far depths every pixel is drawn: the box's area in pixels.
  const double lo[2] = { -0.5, 0 }, hi[2] = { 0.5, 1 };
  EXPECT_DOUBLE_EQ(iga::DrawnPixels(width, height).in(lo, hi), 0.25 * 1 * width * 1 * height);
}

TEST(Supersampling, AMaskOfTheWrongSizeIsRefused)
{
  const iga::sst::Settings settings = frameSettings(8);
  std::array<GBuffer, iga::sst::kRotatedGridSamples> samples;
  EXPECT_THROW(
    iga::sst::renderRotatedGridSamples(
      iga::sst::makeView(sphereCamera(false, 8, 4), 8, 8), settings, std::vector<uint8_t>(63, 1),
      [](const iga::sst::View&, const iga::sst::Settings&, GBuffer&)
      { return iga::sst::FrameReport(); },
      samples),
    std::invalid_argument);
}

} // namespace
