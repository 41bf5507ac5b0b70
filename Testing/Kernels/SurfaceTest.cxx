// The engine's surfaces (the paper's 2D SST): exact rational spheres and cylinders against their
// analytic intersections, the teapot against a dense tessellation and its own patches, the three
// methods against each other, surfaces and isosurfaces in one frame, and bad surfaces.
#include "AnalyticTruth.h"
#include "EngineScenes.h"

#include "TestPatches.h"

#include "iga/Boundary.h"
#include "iga/sst/ElementEdges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace
{

using iga::BezierSurface;
using iga::BezierVolume;
using iga::sst::FrameReport;
using iga::sst::GBuffer;
using iga::sst::Method;
using iga::sst::Settings;
using namespace igatest::truth;

const std::vector<BezierVolume<double>> kNoVolumes;

GBuffer renderSurfaces(const std::vector<BezierSurface<double>>& surfaces,
  const iga::Camera& camera, const Settings& settings,
  Method method = Method::SharedSubdivisionTree, FrameReport* report = nullptr)
{
  GBuffer gbuffer;
  const FrameReport r =
    iga::sst::render(iga::sst::Scene(kNoVolumes, surfaces), camera, settings, method, gbuffer);
  if (report)
    *report = r;
  return gbuffer;
}

Settings imageOf(int width, int height)
{
  Settings settings;
  settings.width = width;
  settings.height = height;
  return settings;
}

/// Bounds (xmin, xmax, ...) of surfaces' control points.
void surfaceBounds(const std::vector<BezierSurface<double>>& surfaces, double* bounds)
{
  iga::sst::patchBounds(iga::sst::Scene(kNoVolumes, surfaces), bounds);
}

/// The largest distance of a hit from the unit sphere about the origin, over all hits.
double sphereDistance(const GBuffer& gbuffer)
{
  double worst = 0;
  for (const auto& hit : gbuffer.hits)
    worst = std::max(worst, std::abs(glm::length(hit.position) - 1));
  return worst;
}

/// The unit sphere's 8 rational patches seen from `eye` towards `focal` (z up, 40 degrees).
struct SphereSurfaces
{
  std::vector<BezierSurface<double>> patches;
  iga::Camera camera;
};

SphereSurfaces unitSphereFrom(const glm::dvec3& eye, const glm::dvec3& focal)
{
  const double centre[3] = { 0, 0, 0 };
  SphereSurfaces view{ iga::makeSphereSurfaces<double>(1.0, centre).patches, {} };
  double bounds[6];
  surfaceBounds(view.patches, bounds);
  view.camera = makeCamera(eye, focal, { 0, 0, 1 }, 40, bounds);
  return view;
}

TEST(Surfaces, ExactRationalSphereMatchesTheAnalyticSphere)
{
  const auto [patches, camera] = unitSphereFrom({ 1.2, -3.5, 2.1 }, { 0.1, 0, 0 });
  Settings settings = imageOf(80, 64);
  settings.colorAttribute = 0; // height
  FrameReport report;
  const GBuffer gbuffer =
    renderSurfaces(patches, camera, settings, Method::SharedSubdivisionTree, &report);
  expectTheUnitSphere(gbuffer, camera, report.unresolvedPixels);
  EXPECT_LT(sphereDistance(gbuffer), 1e-9) << "a hit off the sphere";
  const GBuffer clipped = renderSurfaces(patches, camera, settings, Method::BezierClipping);
  const Comparison byClipping = compare(clipped, camera, sphereTruth, sphereNormal);
  EXPECT_EQ(byClipping.mismatched, 0) << "Bézier clipping";
  EXPECT_LT(byClipping.maxPositionError, 1e-6);
  EXPECT_LT(sphereDistance(clipped), 1e-9);
  for (const auto& hit : gbuffer.hits)
  {
    EXPECT_EQ(hit.isovalue, -1) << "a surface's hit";
    EXPECT_NEAR(hit.color, hit.position[2], 1e-9) << "the height attribute sampled at the hit";
    // x_u x x_v points outwards on the northern patches (u from the pole), inwards on the
    // southern ones: seen from outside, the ray enters the northern ones' negative side.
    if (std::abs(hit.position[2]) > 1e-6)
    {
      EXPECT_EQ(hit.entersBelow, hit.position[2] > 0) << "the side the ray enters";
    }
  }
}

TEST(Surfaces, ClippingPlanesCutTheSphereExactly)
{
  const auto [patches, camera] = unitSphereFrom({ 0.6, -4, 1.1 }, { 0, 0, 0 });
  Settings settings = imageOf(64, 64);
  settings.clipPlanes = sphereCuts(); // the inside shows where they cut the sphere open
  for (Method method :
    { Method::SharedSubdivisionTree, Method::BasicScheme, Method::BezierClipping })
  {
    FrameReport report;
    const GBuffer gbuffer = renderSurfaces(patches, camera, settings, method, &report);
    const Comparison c = compare(gbuffer, camera, clippedSphereTruth, sphereNormal);
    EXPECT_EQ(report.unresolvedPixels, 0u) << iga::sst::methodName(method);
    EXPECT_GT(c.covered, 500) << iga::sst::methodName(method);
    EXPECT_EQ(c.mismatched, 0) << iga::sst::methodName(method);
    EXPECT_LT(c.maxPositionError, 1e-6) << iga::sst::methodName(method);
  }
}

TEST(Surfaces, AllHitsModeFindsBothSidesOfTheSphere)
{
  const auto [patches, camera] = unitSphereFrom({ 0.4, -3.6, 1.1 }, { 0, 0, 0 });
  Settings settings = imageOf(64, 48);
  settings.firstHitOnly = false;
  const BothSides sides = unitSphereBothSides(renderSurfaces(patches, camera, settings), camera);
  EXPECT_GT(sides.crossing, 500);
  EXPECT_EQ(sides.twoHits, sides.crossing);
}

/// The tube's outer wall (radius 1, z in [0, 2]) as surfaces: its boundary faces across the
/// radius at parameter 1.
std::vector<BezierSurface<double>> outerWall(const iga::VolumeSet<double>& tube)
{
  std::vector<BezierSurface<double>> wall;
  for (const auto& patch : tube.patches)
    wall.push_back(iga::faceSurface(patch, 1, 1));
  return wall;
}

TEST(Surfaces, ExactRationalCylinderFromTheTubesOuterFaces)
{
  const auto tube = iga::makeTube<double>(0.5, 0.0);
  const auto wall = outerWall(tube);
  const auto camera = igatest::lookAt(tube, { 2.6, -3.1, 3.4 }, { 0, 0, 1 }, 35);
  Settings settings = imageOf(72, 64);
  settings.colorAttribute = 2; // height
  FrameReport report;
  const GBuffer gbuffer =
    renderSurfaces(wall, camera, settings, Method::SharedSubdivisionTree, &report);
  const Comparison c = compare(
    gbuffer, camera,
    [](const glm::dvec3& o, const glm::dvec3& d) { return cylinderTruth(o, d, 1.0, 0.0, 2.0); },
    cylinderNormal);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  EXPECT_GT(c.covered, 1000);
  EXPECT_EQ(c.mismatched, 0);
  EXPECT_LT(c.maxPositionError, 1e-6);
  EXPECT_LT(c.maxNormalError, 1e-9);
  for (const auto& hit : gbuffer.hits)
  {
    EXPECT_NEAR(std::hypot(hit.position[0], hit.position[1]), 1.0, 1e-9);
    EXPECT_NEAR(hit.color, hit.position[2], 1e-9);
  }
}

/// The teapot seen from above and in front, 32 bicubic patches.
struct TeapotView
{
  std::vector<BezierSurface<double>> patches;
  iga::Camera camera;
};

TeapotView teapotView()
{
  TeapotView view;
  for (int p = 0; p < 32; ++p)
    view.patches.push_back(iga::makeTeapotSurface<double>(p));
  double bounds[6];
  surfaceBounds(view.patches, bounds);
  view.camera = makeCamera({ 4.5, -7.5, 5.0 }, { 0, 0, 1.4 }, { 0, 0, 1 }, 35, bounds);
  return view;
}

/// Where a world point lands in the image (window coordinates in pixels).
glm::dvec2 windowOf(const iga::Camera& camera, int width, int height, const glm::dvec3& x)
{
  const glm::dvec4 clip = iga::worldToClip(camera, double(width) / height) * glm::dvec4(x, 1.0);
  return { (clip[0] / clip[3] + 1) * 0.5 * width, (clip[1] / clip[3] + 1) * 0.5 * height };
}

TEST(Surfaces, TeapotHitsLieOnTheirPatchesAtThePixelCentres)
{
  const TeapotView view = teapotView();
  const Settings settings = imageOf(96, 72);
  FrameReport report;
  const GBuffer gbuffer =
    renderSurfaces(view.patches, view.camera, settings, Method::SharedSubdivisionTree, &report);
  EXPECT_EQ(report.unresolvedPixels, 0u);
  EXPECT_GT(gbuffer.coveredPixels(), 1500u);
  double worstPixel = 0, worstPoint = 0;
  for (int j = 0; j < settings.height; ++j)
    for (int i = 0; i < settings.width; ++i)
      if (const auto* hit = gbuffer.firstHit(i, j))
      {
        // The patch evaluated independently at the hit's parameter.
        const auto euclidean =
          igatest::evaluateEuclidean(view.patches[size_t(hit->patch)].view(), &hit->uvw[0]);
        const glm::dvec3 x{ double(euclidean[0]), double(euclidean[1]), double(euclidean[2]) };
        worstPoint = std::max(worstPoint, glm::length(x - hit->position));
        const glm::dvec2 w = windowOf(view.camera, settings.width, settings.height, x);
        worstPixel =
          std::max(worstPixel, std::max(std::abs(w[0] - (i + 0.5)), std::abs(w[1] - (j + 0.5))));
      }
  EXPECT_LT(worstPoint, 1e-9 * 3.5) << "the hit's position is its patch's point (teapot ~3.5 wide)";
  EXPECT_LT(worstPixel, 1e-5) << "the hit lies on the pixel's ray";
}

} // namespace

namespace
{

/// Per pixel whether a dense tessellation of the surfaces (n x n quads a patch, two triangles
/// each, vertices on the patches) covers its centre.
std::vector<char> tessellatedCoverage(const std::vector<BezierSurface<double>>& surfaces,
  const iga::Camera& camera, int width, int height, int n)
{
  std::vector<char> covered(size_t(width) * height, 0);
  for (const auto& surface : surfaces)
  {
    std::vector<glm::dvec2> grid;
    for (int b = 0; b <= n; ++b)
      for (int a = 0; a <= n; ++a)
      {
        const double u[2] = { double(a) / n, double(b) / n };
        const auto e = igatest::evaluateEuclidean(surface.view(), u);
        grid.push_back(
          windowOf(camera, width, height, glm::dvec3{ double(e[0]), double(e[1]), double(e[2]) }));
      }
    auto fill = [&](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r)
    {
      const double area = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
      if (area == 0)
        return;
      const int i0 = std::max(0, int(std::floor(std::min({ p.x, q.x, r.x }))));
      const int i1 = std::min(width - 1, int(std::ceil(std::max({ p.x, q.x, r.x }))));
      const int j0 = std::max(0, int(std::floor(std::min({ p.y, q.y, r.y }))));
      const int j1 = std::min(height - 1, int(std::ceil(std::max({ p.y, q.y, r.y }))));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
        {
          const glm::dvec2 c{ i + 0.5, j + 0.5 };
          auto edge = [&](glm::dvec2 a, glm::dvec2 b)
          { return ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / area; };
          if (edge(p, q) >= 0 && edge(q, r) >= 0 && edge(r, p) >= 0)
            covered[size_t(j) * width + i] = 1;
        }
    };
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a)
      {
        const size_t k = size_t(b) * (n + 1) + a;
        fill(grid[k], grid[k + 1], grid[k + n + 2]);
        fill(grid[k], grid[k + n + 2], grid[k + n + 1]);
      }
  }
  return covered;
}

/// Pixels whose coverage differs from the reference's, leaving out the reference's silhouette
/// pixels (those with a neighbour of the other coverage).
int coverageMismatches(const GBuffer& gbuffer, const std::vector<char>& reference)
{
  const int w = gbuffer.width, h = gbuffer.height;
  int mismatched = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const char mine = gbuffer.firstHit(i, j) != nullptr, theirs = reference[size_t(j) * w + i];
      bool silhouette = false;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
        {
          const int a = std::clamp(i + di, 0, w - 1), b = std::clamp(j + dj, 0, h - 1);
          silhouette = silhouette || reference[size_t(b) * w + a] != theirs;
        }
      mismatched += mine != theirs && !silhouette ? 1 : 0;
    }
  return mismatched;
}

TEST(Surfaces, TeapotCoverageMatchesADenseTessellation)
{
  const TeapotView view = teapotView();
  const Settings settings = imageOf(160, 120);
  const GBuffer gbuffer = renderSurfaces(view.patches, view.camera, settings);
  const auto reference =
    tessellatedCoverage(view.patches, view.camera, settings.width, settings.height, 64);
  EXPECT_GT(gbuffer.coveredPixels(), 5000u);
  EXPECT_EQ(coverageMismatches(gbuffer, reference), 0);
}

TEST(Surfaces, SharedTreesAndTheThreeReferencesAgreeOnTheTeapot)
{
  const TeapotView view = teapotView();
  const Settings settings = imageOf(96, 72);
  FrameReport sst, basic;
  const GBuffer a =
    renderSurfaces(view.patches, view.camera, settings, Method::SharedSubdivisionTree, &sst);
  const GBuffer b =
    renderSurfaces(view.patches, view.camera, settings, Method::BasicScheme, &basic);
  FrameReport clippingReport;
  const GBuffer clipped =
    renderSurfaces(view.patches, view.camera, settings, Method::BezierClipping, &clippingReport);
  Settings allHits = settings;
  allHits.firstHitOnly = false;
  const GBuffer c = renderSurfaces(view.patches, view.camera, allHits, Method::BruteForce);
  igatest::expectSameFirstHits(a, b, 0, 1e-6);
  // Clipping stops where a region's window box is 1e-7 pixel wide, Newton 1e-6 pixel from the
  // ray: on the spout's grazing rays that is up to 1e-6 of the teapot's distance (about 8).
  igatest::expectSameFirstHits(a, clipped, 0, 1e-5);
  EXPECT_EQ(clippingReport.unresolvedPixels, 0u);
  // Depths within 1e-6 of the teapot's distance (about 8): the spout's grazing rays.
  igatest::expectBruteForceWithinTrees(
    renderSurfaces(view.patches, view.camera, allHits), c, 2000, 1e-5);
  EXPECT_EQ(sst.unresolvedPixels + basic.unresolvedPixels, 0u);
  EXPECT_LT(sst.subdividedPatches, basic.subdividedPatches) << "pixels share the tree";
  Settings oneThread = settings;
  oneThread.threads = 1;
  const GBuffer single = renderSurfaces(view.patches, view.camera, oneThread);
  EXPECT_TRUE(igatest::identicalGBuffers(single, a)) << "bit-identical for any thread count";
}

TEST(Surfaces, SurfacesAndIsosurfacesShareOneFrame)
{
  // The unit sphere as an isosurface and a sphere surface of radius 0.8 about (0.6, 0, 0): each
  // pixel's first hit is the nearer of the two frames drawn apart.
  const auto volume = iga::makeMarsdenSphere<double>(2);
  const double centre[3] = { 0.6, 0, 0 };
  const auto surface = iga::makeSphereSurfaces<double>(0.8, centre);
  const double bounds[6] = { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 };
  const auto camera = makeCamera({ 1.2, -3.5, 2.1 }, { 0.1, 0, 0 }, { 0, 0, 1 }, 40, bounds);
  Settings settings = imageOf(80, 64);
  settings.isovalues = { 0.0 };
  GBuffer both, isosurface;
  iga::sst::render(iga::sst::Scene(volume.patches, surface.patches), camera, settings,
    Method::SharedSubdivisionTree, both);
  iga::sst::render(volume.patches, camera, settings, Method::SharedSubdivisionTree, isosurface);
  const GBuffer alone = renderSurfaces(surface.patches, camera, settings);
  int fromSurface = 0, fromVolume = 0;
  for (int j = 0; j < settings.height; ++j)
    for (int i = 0; i < settings.width; ++i)
    {
      const auto *x = isosurface.firstHit(i, j), *y = alone.firstHit(i, j);
      const auto* hit = both.firstHit(i, j);
      ASSERT_EQ(hit != nullptr, x || y);
      if (!hit)
        continue;
      const bool surfaceNearer = y && (!x || y->eyeDepth < x->eyeDepth);
      const auto* expected = surfaceNearer ? y : x;
      EXPECT_NEAR(hit->eyeDepth, expected->eyeDepth, 1e-12);
      EXPECT_EQ(hit->patch, surfaceNearer ? int(volume.patches.size()) + y->patch : x->patch);
      EXPECT_EQ(hit->isovalue, surfaceNearer ? -1 : 0);
      (surfaceNearer ? fromSurface : fromVolume) += 1;
    }
  EXPECT_GT(fromSurface, 300);
  EXPECT_GT(fromVolume, 300);
}

TEST(Surfaces, BadSurfacesAreRejectedWithTheSurfaceNamed)
{
  const auto sphere = unitSphereFrom({ 0, -4, 1 }, { 0, 0, 0 });
  const iga::Camera& camera = sphere.camera;
  auto message = [&](std::vector<BezierSurface<double>> surfaces, Settings settings)
  {
    try
    {
      renderSurfaces(surfaces, camera, settings);
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const Settings settings = imageOf(16, 16);
  auto withPoint = [&](int surface, int channel, double value)
  {
    auto surfaces = sphere.patches;
    surfaces[size_t(surface)].view().point(4)[channel] = value;
    return surfaces;
  };
  EXPECT_EQ(message(withPoint(3, iga::kWeightChannel, NAN), settings),
    "surface 3: control point 4 has a non-finite weight (channel 3): nan");
  EXPECT_EQ(message(withPoint(5, iga::kWeightChannel, -1), settings),
    "surface 5: control point 4 has non-positive weight -1.000000");
  Settings colour = settings;
  colour.colorAttribute = 1;
  EXPECT_EQ(message(sphere.patches, colour), "surface 0 has 1 attributes; the colour 1");
  const int zeroDegree[2] = { 0, 2 };
  EXPECT_EQ(message({ BezierSurface<double>(zeroDegree, 4) }, settings),
    "surface 0: degree 0 in direction 0 is outside 1..16");
  // A scene of surfaces needs no isovalue, one with volumes does.
  EXPECT_EQ(message(sphere.patches, settings), "no error");
  GBuffer gbuffer;
  const auto volume = iga::makeMarsdenSphere<double>(2);
  EXPECT_THROW(iga::sst::render(iga::sst::Scene(volume.patches, sphere.patches), camera, settings,
                 Method::SharedSubdivisionTree, gbuffer),
    std::invalid_argument);
  Settings withIsovalue = settings;
  withIsovalue.isovalues = { 0.0 };
  EXPECT_THROW(iga::sst::render(iga::sst::Scene(volume.patches, sphere.patches), camera,
                 withIsovalue, Method::BezierClipping, gbuffer),
    std::invalid_argument)
    << "Bézier clipping draws surfaces only";
}

} // namespace

namespace
{

/// The plane z = 0 over [0, 4] x [0, 3] as 4 x 3 biquadratic elements whose parameters are not
/// affine in x and y (control points at 0, 1/4 and 1 of each element's width): element
/// boundaries at the whole numbers.
std::vector<BezierSurface<double>> elementGrid()
{
  std::vector<BezierSurface<double>> grid;
  const int degree[2] = { 2, 2 };
  const double along[3] = { 0, 0.25, 1 };
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 4; ++a)
    {
      BezierSurface<double> patch(degree, iga::kFirstAttributeChannel);
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
        {
          double* cp = patch.view().point(3 * j + i);
          cp[0] = a + along[i];
          cp[1] = b + along[j];
          cp[2] = 0;
          cp[iga::kWeightChannel] = 1;
        }
      grid.push_back(std::move(patch));
    }
  return grid;
}

/// Distance in pixels from a pixel centre to the nearest element boundary of elementGrid, the
/// projected segments x = 0..4 and y = 0..3.
double distanceToBoundaries(const iga::Camera& camera, int width, int height, int i, int j)
{
  const glm::dvec2 c{ i + 0.5, j + 0.5 };
  double nearest = HUGE_VAL;
  auto segment = [&](glm::dvec3 a, glm::dvec3 b)
  {
    const glm::dvec2 p = windowOf(camera, width, height, a), q = windowOf(camera, width, height, b);
    const double t = std::clamp(glm::dot(c - p, q - p) / glm::dot(q - p, q - p), 0.0, 1.0);
    nearest = std::min(nearest, glm::length(c - (p + t * (q - p))));
  };
  for (int x = 0; x <= 4; ++x)
    segment({ x, 0, 0 }, { x, 3, 0 });
  for (int y = 0; y <= 3; ++y)
    segment({ 0, y, 0 }, { 4, y, 0 });
  return nearest;
}

TEST(Surfaces, ElementEdgesLieOnTheElementBoundaries)
{
  const auto grid = elementGrid();
  double bounds[6];
  surfaceBounds(grid, bounds);
  for (const glm::dvec3& eye : { glm::dvec3{ 2, 1.5, 6 }, glm::dvec3{ 2.6, -2.5, 4.5 } })
  {
    const auto camera = makeCamera(eye, { 2, 1.5, 0 }, { 0, 1, 0 }, 45, bounds);
    const Settings settings = imageOf(160, 120);
    const GBuffer gbuffer = renderSurfaces(grid, camera, settings);
    const auto coverage = iga::sst::elementEdgeCoverage(gbuffer, 1.0);
    int edges = 0, misplaced = 0, missing = 0;
    double worstDistanceError = 0;
    for (int j = 0; j < settings.height; ++j)
      for (int i = 0; i < settings.width; ++i)
      {
        if (!gbuffer.firstHit(i, j))
          continue;
        const double distance = distanceToBoundaries(camera, settings.width, settings.height, i, j);
        const float covered = coverage[size_t(j) * settings.width + i];
        edges += covered > 0;
        misplaced += covered > 0 && distance > 1.0;
        missing += distance < 0.25 && covered < 0.5;
        // A line one pixel wide covers 1 - distance of a pixel partly on it.
        if (covered > 0 && covered < 1)
          worstDistanceError = std::max(worstDistanceError, std::abs(1 - covered - distance));
      }
    EXPECT_GT(edges, 500) << "eye " << eye.x << ", " << eye.y << ", " << eye.z;
    EXPECT_EQ(misplaced, 0) << "edge pixels more than 1 pixel from a boundary";
    EXPECT_EQ(missing, 0) << "boundary pixels without an edge";
    // The parameters' derivatives come from differences between neighbouring pixels; this
    // grid's parameters change their screen speed by up to a fifth from one pixel to the next.
    EXPECT_LT(worstDistanceError, 0.06) << "distance to the boundary in pixels";
  }
}

} // namespace

namespace
{

/// Ray parameters where the ray meets the tube's boundary (radii 0.5 and 1, z in [0, 2]): its
/// walls and its end annuli; false when the ray passes within 1e-6 of an edge or a silhouette.
bool tubeBoundaryCrossings(const glm::dvec3& o, const glm::dvec3& d, std::vector<double>& t)
{
  t.clear();
  for (double r : { 0.5, 1.0 })
  {
    const double a = d.x * d.x + d.y * d.y, b = 2 * (o.x * d.x + o.y * d.y),
                 c = o.x * o.x + o.y * o.y - r * r, disc = b * b - 4 * a * c;
    if (disc < 0)
      continue;
    if (disc < 1e-6 * b * b)
      return false;
    for (double s : { -1.0, 1.0 })
    {
      const double root = (-b + s * std::sqrt(disc)) / (2 * a), z = o.z + root * d.z;
      if (std::abs(z) < 1e-6 || std::abs(z - 2) < 1e-6)
        return false;
      if (root > 0 && z > 0 && z < 2)
        t.push_back(root);
    }
  }
  for (double z : { 0.0, 2.0 })
  {
    const double root = (z - o.z) / d.z, r = std::hypot(o.x + root * d.x, o.y + root * d.y);
    if (std::abs(r - 0.5) < 1e-6 || std::abs(r - 1) < 1e-6)
      return false;
    if (root > 0 && r > 0.5 && r < 1)
      t.push_back(root);
  }
  return true;
}

TEST(Surfaces, RaysThroughAMultiPatchBlockHitOnlyItsOuterFaces)
{
  // The tube's 8 patches share 12 inner faces (between quadrants, and across z = 1); its
  // boundary is 24 faces: the walls and the end annuli.
  const auto tube = iga::makeTube<double>(0.5, 0.0);
  std::vector<BezierSurface<double>> boundary;
  for (const iga::PatchFace& face : iga::boundaryFaces(tube.patches))
    boundary.push_back(
      iga::faceSurface(tube.patches[size_t(face.patch)], face.direction, face.side));
  ASSERT_EQ(boundary.size(), 24u);
  const auto camera = igatest::lookAt(tube, { 2.2, -2.9, 3.6 }, { 0, 0, 0.9 }, 40);
  Settings settings = imageOf(96, 80);
  settings.firstHitOnly = false;
  const GBuffer gbuffer = renderSurfaces(boundary, camera, settings);
  int checked = 0, wrong = 0, throughTheHole = 0;
  std::vector<double> crossings;
  for (int j = 0; j < settings.height; ++j)
    for (int i = 0; i < settings.width; ++i)
    {
      glm::dvec3 o, d;
      pixelRay(camera, settings.width, settings.height, i, j, o, d);
      if (!tubeBoundaryCrossings(o, d, crossings))
        continue;
      ++checked;
      throughTheHole += crossings.size() == 4;
      if (gbuffer.hitCount(i, j) != int(crossings.size()))
      {
        ++wrong;
        continue;
      }
      std::sort(crossings.begin(), crossings.end());
      for (size_t k = 0; k < crossings.size(); ++k)
        EXPECT_LT(glm::length(gbuffer.firstHit(i, j)[k].position - (o + crossings[k] * d)), 1e-6);
    }
  EXPECT_GT(checked, 4000);
  EXPECT_GT(throughTheHole, 200) << "rays through both walls on both sides";
  EXPECT_EQ(wrong, 0) << "rays whose hits are not the boundary's crossings";
}

} // namespace
