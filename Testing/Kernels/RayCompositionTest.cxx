// Ray composition against the shared subdivision tree on the same volumes: the unit sphere (hits
// on it to 1e-9), and the gallery's algebraic surfaces over their boxes, every root finder, hits
// within 1e-6 of the SST's and |f(hit)| / K (Reimers and Seland's error metric) below their
// Table 1; the frustum form and the power form's blossom against direct composition; patches
// without affine geometry refused, and drawn by the tree in the automatic method's frames.
#include "iga/AbsField.h"
#include "iga/AlgebraicGallery.h"
#include "iga/Camera.h"
#include "iga/Deformation.h"
#include "iga/FrustumForm.h"
#include "iga/IsosurfaceCells.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Engine.h"

#include "RayCompositionPass.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>

namespace
{

using iga::sst::GBuffer;
using iga::sst::Method;

struct Volume
{
  iga::Polynomial3<double> field;
  std::vector<iga::BezierVolume<double>> patches;
};

/// The surface's polynomial as one Bézier volume over its box.
Volume algebraicVolume(const std::string& expression, const double* box)
{
  Volume v;
  v.field = iga::parsePolynomial(expression);
  v.patches.push_back(iga::makeAlgebraicVolume(v.field, box));
  return v;
}

iga::Camera cameraOf(const Volume& v)
{
  double bounds[6];
  iga::sst::patchBounds(iga::sst::Scene(v.patches), bounds);
  return iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30);
}

GBuffer draw(const Volume& v, int size, Method method,
  iga::RootFinder finder = iga::RootFinder::PointInsertion, iga::sst::FrameReport* report = nullptr)
{
  const iga::Camera camera = cameraOf(v);
  iga::sst::Settings settings;
  settings.width = settings.height = size;
  settings.isovalues = { 0.0 };
  settings.threads = 2;
  settings.rootFinder = finder;
  settings.isoTolerance = 1e-12; // the tree's Newton to double precision, as ray composition's
  GBuffer out;
  const auto r = iga::sst::render(iga::sst::Scene(v.patches), camera, settings, method, out);
  if (report)
    *report = r;
  return out;
}

/// The surface's largest Bernstein coefficient K (Reimers and Seland's scale).
double largestCoefficient(const Volume& v)
{
  double largest = 0;
  for (int p = 0; p < v.patches[0].view().pointCount(); ++p)
    largest =
      std::max(largest, std::fabs(v.patches[0].view().point(p)[iga::kFirstAttributeChannel]));
  return largest;
}

/// Whether a hit at x, seen from `eye`, is trusted to 1e-6: rounding's 1e-13 K moves the root
/// along the ray by less than 1e-7 there (not at nodes, self-intersections, flat roots or grazing
/// rays, where no method does better).
bool wellConditioned(const Volume& v, double size, const glm::dvec3& eye, const glm::dvec3& x)
{
  const double h = 1e-6 * size;
  const glm::dvec3 ray = glm::normalize(x - eye);
  const glm::dvec3 up = x + h * ray, down = x - h * ray;
  const double slope =
    (v.field.evaluate(up.x, up.y, up.z) - v.field.evaluate(down.x, down.y, down.z)) / (2 * h);
  return 1e-13 * largestCoefficient(v) <= 1e-7 * std::fabs(slope);
}

/// How two G-buffers' first hits compare: pixels covered by one only; the largest distance
/// between hits where `trusted(position)` (the surface there is well conditioned); pixels where
/// `a` is nearer by more than that (a hit `b` missed).
struct Comparison
{
  size_t onlyInA = 0, onlyInB = 0, untrusted = 0, nearerInA = 0;
  double farthest = 0;
};

template<class Trusted>
Comparison compare(const GBuffer& a, const GBuffer& b, Trusted trusted)
{
  Comparison c;
  for (int j = 0; j < a.height; ++j)
  {
    for (int i = 0; i < a.width; ++i)
    {
      const auto* ha = a.firstHit(i, j);
      const auto* hb = b.firstHit(i, j);
      if (!ha || !hb)
      {
        c.onlyInA += ha && !hb ? 1 : 0;
        c.onlyInB += hb && !ha ? 1 : 0;
      }
      else if (!trusted(*ha))
      {
        ++c.untrusted;
      }
      else if (glm::length(ha->position - hb->position) > 1e-6 && ha->ndcDepth < hb->ndcDepth)
      {
        ++c.nearerInA;
      }
      else
      {
        c.farthest = std::max(c.farthest, glm::length(ha->position - hb->position));
      }
    }
  }
  return c;
}

TEST(RayComposition, SphereHitsLieOnTheSphere)
{
  const double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  const Volume sphere = algebraicVolume("x^2 + y^2 + z^2 - 1", box);
  iga::sst::FrameReport report;
  const GBuffer composed =
    draw(sphere, 96, Method::RayComposition, iga::RootFinder::PointInsertion, &report);
  EXPECT_EQ(report.method, "ray-composition");
  // Its four terms' blossom costs a ray less than a frustum form: composed and shaded by it.
  EXPECT_EQ(report.frustumPatches, 0u);
  EXPECT_EQ(report.blossomPatches, 1u);
  EXPECT_GT(report.composedRays, 0u);
  EXPECT_EQ(report.cappedRays, 0u);
  ASSERT_GT(composed.coveredPixels(), 1000u);
  for (const auto& hit : composed.hits)
  {
    EXPECT_NEAR(glm::length(hit.position), 1.0, 1e-9);
    EXPECT_NEAR(std::fabs(glm::dot(hit.normal, hit.position)), 1.0, 1e-9);
  }
  const Comparison c = compare(composed, draw(sphere, 96, Method::SharedSubdivisionTree),
    [](const iga::sst::Hit&) { return true; });
  EXPECT_EQ(c.onlyInA + c.onlyInB, 0u);
  EXPECT_EQ(c.nearerInA, 0u);
  EXPECT_LT(c.farthest, 1e-6);
}

/// Every gallery surface's rays through its frustum form against the same rays composed
/// directly, for a perspective and a parallel view: Bernstein coefficients within 1e-11 of K
/// (the largest coefficient of the patch). The super-sphere's x^16 grows a million-fold in the
/// frustum's box beyond the patch, where rounding would reach every ray's coefficients: it has
/// no form, and its rays are composed directly.
TEST(RayComposition, FrustumFormComposesTheRaysComposeRayDoes)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int g = 0; g < count; ++g)
  {
    const Volume v = algebraicVolume(gallery[g].expression, gallery[g].box);
    iga::AffinePatch patch;
    ASSERT_TRUE(iga::affineGeometry(v.patches[0].view(), iga::kFirstAttributeChannel, patch));
    patch.terms.clear(); // the form against direct composition, whatever a blossom would cost
    const iga::ChebyshevInterpolation interpolation = iga::chebyshevInterpolation(patch.rayDegree);
    double largest = 0;
    for (double c : patch.field)
      largest = std::max(largest, std::fabs(c));
    for (bool parallel : { false, true })
    {
      iga::Camera camera = cameraOf(v);
      camera.parallelProjection = parallel;
      const iga::sst::View view = iga::sst::makeView(camera, 256, 256);
      const glm::dmat4 clipToWorld = glm::inverse(view.worldToClip);
      iga::FrustumForm form;
      const auto serial = [](size_t n, const auto& fn) { fn(size_t(0), n); };
      const bool made = iga::makeFrustumForm(
        patch, view.worldToClip, clipToWorld, iga::DrawnPixels(256, 256), INFINITY, form, serial);
      ASSERT_EQ(made, g != count - 1) << gallery[g].name;
      if (!made)
        continue;
      int composed = 0;
      for (int trial = 0; trial < 400 && composed < 40; ++trial)
      {
        const double x = form.a[0] + form.a[1] * (2 * unit(rng) - 1);
        const double y = form.b[0] + form.b[1] * (2 * unit(rng) - 1);
        const glm::dvec4 nearPoint = clipToWorld * glm::dvec4(x, y, -1, 1);
        const glm::dvec4 farPoint = clipToWorld * glm::dvec4(x, y, 1, 1);
        const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
        const glm::dvec3 direction = glm::dvec3(farPoint) / farPoint.w - origin;
        double t0, t1;
        if (!iga::rayInPatch(patch, origin, direction, 0, 1, t0, t1))
          continue;
        ++composed;
        const glm::dvec3 u0 = patch.inverse * (origin + t0 * direction - patch.origin);
        const glm::dvec3 du = patch.inverse * ((t1 - t0) * direction);
        double direct[iga::kMaxOrder], frustum[iga::kMaxOrder];
        iga::composeRay(patch, 0.25, u0, du, interpolation, direct);
        iga::composeFrustumRay(form, 0.25, x, y, t0, t1, interpolation, frustum);
        for (int k = 0; k <= patch.rayDegree; ++k)
          EXPECT_NEAR(frustum[k], direct[k], 1e-11 * largest)
            << gallery[g].name << (parallel ? " parallel" : " perspective") << " coefficient " << k;
      }
      EXPECT_EQ(composed, 40) << gallery[g].name;
    }
  }
}

/// The gallery's power forms: the expression's terms in the centred parameter (the
/// super-sphere's four, 0.7^16 s^16 for x^16 over [-0.7, 0.7]), certified; random rays through
/// each patch composed by the blossom as directly (within its rounding) and as the expression
/// gives along the ray; the certificate refuses what it cannot prove.
TEST(PowerForm, GalleryBlossomsComposeTheRaysComposeRayDoes)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int g = 0; g < count; ++g)
  {
    SCOPED_TRACE(gallery[g].name);
    const Volume v = algebraicVolume(gallery[g].expression, gallery[g].box);
    iga::AffinePatch patch;
    ASSERT_TRUE(iga::affineGeometry(v.patches[0].view(), iga::kFirstAttributeChannel, patch));
    ASSERT_FALSE(patch.terms.empty());
    double largest = 0;
    for (double c : patch.field)
      largest = std::max(largest, std::fabs(c));
    const iga::ChebyshevInterpolation interpolation = iga::chebyshevInterpolation(patch.rayDegree);
    for (int trial = 0; trial < 40; ++trial)
    {
      const glm::dvec3 u0(unit(rng), unit(rng), unit(rng)), u1(unit(rng), unit(rng), unit(rng));
      double direct[iga::kMaxOrder], blossom[iga::kMaxOrder];
      iga::composeRay(patch, 0.25, u0, u1 - u0, interpolation, direct);
      iga::blossomAlongRay(patch.terms.data(), int(patch.terms.size()), patch.rayDegree,
        2.0 * u0 - 1.0, 2.0 * u1 - 1.0, 0.25, blossom);
      // Against direct composition, within its rounding (its degree-16 collocation: 1e-10 K)...
      for (int k = 0; k <= patch.rayDegree; ++k)
        ASSERT_NEAR(blossom[k], direct[k], 1e-9 * largest) << k;
      // ... and against the expression itself along the segment, within 1e-13 K.
      const double* box = gallery[g].box;
      for (double sigma : { 0.0, 0.3, 0.7, 1.0 })
      {
        double x[3];
        for (int d = 0; d < 3; ++d)
          x[d] = box[2 * d] + (box[2 * d + 1] - box[2 * d]) * (u0[d] + sigma * (u1[d] - u0[d]));
        double basis[iga::kMaxOrder], unused[iga::kMaxOrder], value = 0;
        iga::bernsteinBasis(patch.rayDegree, sigma, basis, unused);
        for (int k = 0; k <= patch.rayDegree; ++k)
          value += basis[k] * blossom[k];
        EXPECT_NEAR(value, v.field.evaluate(x[0], x[1], x[2]) - 0.25, 1e-13 * largest) << sigma;
      }
      // The gradient in s against central differences of the blossom's values.
      const glm::dvec3 s = 2.0 * u0 - 1.0;
      const glm::dvec3 gradient =
        iga::powerGradient(patch.terms.data(), int(patch.terms.size()), s);
      for (int d = 0; d < 3; ++d)
      {
        glm::dvec3 step(0.0);
        step[d] = 1e-5;
        double ends[2][iga::kMaxOrder];
        iga::blossomAlongRay(patch.terms.data(), int(patch.terms.size()), patch.rayDegree, s - step,
          s + step, 0.0, ends[0]);
        // The segment's end values are its first and last coefficients.
        const double slope = (ends[0][patch.rayDegree] - ends[0][0]) / 2e-5;
        EXPECT_NEAR(gradient[d], slope, 1e-6 * (1 + std::fabs(slope))) << d;
      }
    }
  }
  const Volume superSphere = algebraicVolume("x^16 + y^16 + z^16 - 0.0001", gallery[count - 1].box);
  iga::AffinePatch patch;
  ASSERT_TRUE(
    iga::affineGeometry(superSphere.patches[0].view(), iga::kFirstAttributeChannel, patch));
  ASSERT_EQ(patch.terms.size(), 4u);
  for (const iga::PowerTerm& term : patch.terms)
  {
    const int degree = term.power[0] + term.power[1] + term.power[2];
    EXPECT_TRUE(
      degree == 16 ? std::max({ term.power[0], term.power[1], term.power[2] }) == 16 : degree == 0);
    // To rounding: the source's blossom conversion and the power form's are exact but for it.
    EXPECT_NEAR(term.coefficient, degree == 16 ? std::pow(0.7, 16) : -1e-4, 1e-17);
  }
  // A constant a hundred million times below K is a term like the others: the surface hangs on
  // it.
  const Volume flat = algebraicVolume("x^16 + y^16 + z^16 - 1e-9", gallery[count - 1].box);
  iga::AffinePatch flatPatch;
  ASSERT_TRUE(iga::affineGeometry(flat.patches[0].view(), iga::kFirstAttributeChannel, flatPatch));
  ASSERT_EQ(flatPatch.terms.size(), 4u);
  EXPECT_EQ(std::count_if(flatPatch.terms.begin(), flatPatch.terms.end(),
              [](const iga::PowerTerm& t) {
                return t.power[0] + t.power[1] + t.power[2] == 0 &&
                       std::fabs(t.coefficient + 1e-9) < 1e-17;
              }),
    1);
  // The certificate holds for the four terms; it refuses fewer than the field needs, and a form
  // one of whose terms is off by a millionth.
  std::vector<double> power, bound;
  iga::centredPowerForm(patch.field, patch.degree, power, bound);
  std::vector<iga::PowerTerm> terms;
  EXPECT_TRUE(iga::sparsePowerForm(
    patch.field, patch.degree, power, bound, 4, iga::kPowerFormTolerance, terms));
  EXPECT_FALSE(iga::sparsePowerForm(
    patch.field, patch.degree, power, bound, 3, iga::kPowerFormTolerance, terms));
  std::vector<double> altered = power;
  *std::max_element(altered.begin(), altered.end()) *= 1 + 1e-6;
  EXPECT_FALSE(iga::sparsePowerForm(
    patch.field, patch.degree, altered, bound, 1000, iga::kPowerFormTolerance, terms));
  EXPECT_TRUE(terms.empty());
}

/// A field of random Bernstein coefficients has a dense power form: no blossom where it would
/// cost more than composing the ray directly, and where allowed every term is kept and proved.
TEST(PowerForm, DenseFieldsKeepEveryTerm)
{
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> coefficient(-1, 1);
  const int n[3] = { 3, 2, 4 };
  std::vector<double> field(size_t(4 * 3 * 5));
  for (double& c : field)
    c = coefficient(rng);
  std::vector<double> power, bound;
  iga::centredPowerForm(field, n, power, bound);
  std::vector<iga::PowerTerm> terms;
  ASSERT_TRUE(iga::sparsePowerForm(field, n, power, bound, field.size(), 1e-12, terms));
  EXPECT_EQ(terms.size(), field.size());
  EXPECT_FALSE(iga::sparsePowerForm(field, n, power, bound, field.size() - 1, 1e-12, terms));
}

TEST(RayComposition, AnEyeInsideThePatchHasNoFrustumForm)
{
  // A corner behind the eye leaves no screen box: no frustum form, the same surface.
  const double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  const Volume sphere = algebraicVolume("x^2 + y^2 + z^2 - 1", box);
  iga::Camera camera;
  camera.position = { 0.1, -0.2, 0.05 };
  camera.focalPoint = { 0.1, 1, 0.05 };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngle = 60;
  camera.clippingRange[0] = 0.01;
  camera.clippingRange[1] = 10;
  iga::sst::Settings settings;
  settings.width = settings.height = 64;
  settings.isovalues = { 0.0 };
  settings.threads = 2;
  GBuffer out;
  const auto report = iga::sst::render(
    iga::sst::Scene(sphere.patches), camera, settings, Method::RayComposition, out);
  EXPECT_EQ(report.frustumPatches, 0u);
  EXPECT_EQ(out.coveredPixels(), 64u * 64u);
  for (const auto& hit : out.hits)
    EXPECT_NEAR(glm::length(hit.position), 1.0, 1e-9);
}

TEST(RayComposition, GallerySurfacesAgreeWithTheTreeForEveryFinder)
{
  // Reimers and Seland's Table 1 (mean, max of |f(hit)| / K) where they list the surface; ours
  // in double precision must be lower. Elsewhere 1e-9 and 1e-7. Near the super-sphere's sharp
  // edges (degree 16) the tree keeps a farther hit or none in 122 of 1 300 pixels at 64x64 (it
  // reports such pixels unresolved: 9 277 at 256x256), where ray composition finds the nearer
  // hit, on the surface; there only ray composition's own misses are counted.
  const std::pair<const char*, std::array<double, 2>> table[] = { { "sphere", { 1e-9, 1e-7 } },
    { "cayley", { 1.2e-7, 1.5e-6 } }, { "clebsch", { 2.3e-7, 4.7e-6 } },
    { "kummer", { 1e-9, 1e-7 } }, { "dervish", { 1e-9, 1e-7 } }, { "kiss", { 2.7e-7, 1.2e-5 } },
    { "heart", { 4.3e-9, 5.6e-8 } }, { "klein", { 2.4e-6, 1.9e-5 } },
    { "linked-tori", { 3.4e-8, 2.9e-7 } }, { "tangle", { 2.3e-7, 4.7e-6 } },
    { "barth-decic", { 3.5e-9, 7.3e-7 } }, { "super-sphere", { 7.2e-9, 2.9e-7 } } };
  for (const auto& [name, paper] : table)
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    const GBuffer tree = draw(v, 64, Method::SharedSubdivisionTree);
    const double largest = largestCoefficient(v);
    const glm::dvec3 eye = cameraOf(v).position;
    const auto trusted = [&](const iga::sst::Hit& hit)
    { return wellConditioned(v, surface->box[1] - surface->box[0], eye, hit.position); };
    for (int f = 0; f < iga::kRootFinderCount; ++f)
    {
      const auto finder = iga::RootFinder(f);
      iga::sst::FrameReport report;
      const GBuffer composed = draw(v, 64, Method::RayComposition, finder, &report);
      const Comparison c = compare(composed, tree, trusted);
      const std::string what = std::string(name) + " " + iga::rootFinderName(finder);
      EXPECT_LE(c.onlyInB, composed.coveredPixels() / 200) << what;
      EXPECT_LE(c.untrusted, composed.coveredPixels() / 20) << what;
      if (name != std::string("super-sphere")) // where the tree misses hits (see above)
      {
        EXPECT_LE(c.onlyInA, composed.coveredPixels() / 200) << what;
        EXPECT_EQ(c.nearerInA, 0u) << what;
      }
      EXPECT_LT(c.farthest, 1e-6) << what;
      EXPECT_EQ(report.cappedRays, 0u) << name << " " << iga::rootFinderName(finder);
      double sum = 0, worst = 0;
      for (const auto& hit : composed.hits)
      {
        const double error =
          std::fabs(v.field.evaluate(hit.position.x, hit.position.y, hit.position.z)) / largest;
        sum += error;
        worst = std::max(worst, error);
      }
      ASSERT_GT(composed.hits.size(), 100u) << name;
      EXPECT_LT(sum / composed.hits.size(), paper[0]) << name << " " << iga::rootFinderName(finder);
      EXPECT_LT(worst, paper[1]) << name << " " << iga::rootFinderName(finder);
    }
  }
}

/// The G-buffers' hits pixel by pixel: counts equal, positions within 1e-6, same patch.
void expectSameHits(const GBuffer& a, const GBuffer& b)
{
  ASSERT_EQ(a.offsets, b.offsets);
  for (size_t h = 0; h < a.hits.size(); ++h)
  {
    EXPECT_LT(glm::length(a.hits[h].position - b.hits[h].position), 1e-6) << "hit " << h;
    EXPECT_EQ(a.hits[h].patch, b.hits[h].patch) << "hit " << h;
  }
}

TEST(RayComposition, AutomaticMethodComposesAffinePatchesWithTheTreesOthersInOneFrame)
{
  // Two overlapping spheres, one affine and one curved (a control point moved, then shifted):
  // each occludes the other somewhere, so the paths' hits meet in the same pixels.
  const double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  Volume v = algebraicVolume("x^2 + y^2 + z^2 - 1", box);
  v.patches.push_back(v.patches[0]);
  auto curved = v.patches[1].view();
  curved.point(13)[1] += 0.3;
  for (int p = 0; p < curved.pointCount(); ++p)
    curved.point(p)[0] += 0.9 * curved.point(p)[iga::kWeightChannel];
  for (bool firstHitOnly : { true, false })
  {
    SCOPED_TRACE(firstHitOnly ? "first hit" : "all hits");
    const iga::Camera camera = cameraOf(v);
    iga::sst::Settings settings;
    settings.width = settings.height = 80;
    settings.isovalues = { 0.0 };
    settings.threads = 2;
    settings.isoTolerance = 1e-12;
    settings.firstHitOnly = firstHitOnly;
    GBuffer automatic, tree;
    const auto report =
      iga::sst::render(iga::sst::Scene(v.patches), camera, settings, Method::Automatic, automatic);
    const auto treeReport = iga::sst::render(
      iga::sst::Scene(v.patches), camera, settings, Method::SharedSubdivisionTree, tree);
    EXPECT_EQ(report.method, "auto");
    EXPECT_EQ(report.rayCompositionPatches, 1u);
    EXPECT_EQ(report.sstPatches, 1u);
    EXPECT_EQ(treeReport.sstPatches, 2u);
    EXPECT_GT(report.composedRays, 0u);
    EXPECT_GT(report.newtonSolves, 0u);
    EXPECT_LT(report.newtonSolves, treeReport.newtonSolves);
    EXPECT_EQ(report.unresolvedPixels + treeReport.unresolvedPixels, 0u);
    size_t fromEach[2] = { 0, 0 };
    for (const auto& hit : automatic.hits)
      ++fromEach[hit.patch];
    EXPECT_GT(fromEach[0], 300u);
    EXPECT_GT(fromEach[1], 300u);
    expectSameHits(automatic, tree);
  }
}

/// A first-hit frame looks for each ray's nearest root alone: its hits are the all-hits frame's
/// nearest, bit for bit, with fewer root-finder steps (the linked tori: two or four roots on
/// most rays). Under a clipping plane the nearest root may be cut away, and every root is found.
TEST(RayComposition, FirstHitFramesFindTheNearestRootAlone)
{
  const iga::AlgebraicSurface* tori = iga::findAlgebraicSurface("linked-tori");
  ASSERT_NE(tori, nullptr);
  const Volume v = algebraicVolume(tori->expression, tori->box);
  const iga::Camera camera = cameraOf(v);
  for (iga::RootFinder finder : { iga::RootFinder::PointInsertion, iga::RootFinder::PolarNewton })
  {
    for (bool clipped : { false, true })
    {
      SCOPED_TRACE(std::string(iga::rootFinderName(finder)) + (clipped ? ", clipped" : ""));
      iga::sst::Settings settings;
      settings.width = settings.height = 96;
      settings.isovalues = { 0.0 };
      settings.threads = 2;
      settings.rootFinder = finder;
      if (clipped)
        settings.clipPlanes.push_back({ 0.3, -1.0, 0.2, 0.1 });
      GBuffer first, all;
      const auto firstReport = iga::sst::render(
        iga::sst::Scene(v.patches), camera, settings, Method::RayComposition, first);
      settings.firstHitOnly = false;
      const auto allReport =
        iga::sst::render(iga::sst::Scene(v.patches), camera, settings, Method::RayComposition, all);
      ASSERT_GT(first.coveredPixels(), 400u);
      ASSERT_EQ(first.coveredPixels(), all.coveredPixels());
      EXPECT_GT(all.hits.size(), first.hits.size() * 3 / 2) << "rays with several roots";
      for (int j = 0; j < first.height; ++j)
      {
        for (int i = 0; i < first.width; ++i)
        {
          const auto* a = first.firstHit(i, j);
          const auto* b = all.firstHit(i, j);
          ASSERT_EQ(a == nullptr, b == nullptr);
          if (a)
          {
            EXPECT_EQ(a->position, b->position) << i << ", " << j;
          }
        }
      }
      EXPECT_EQ(firstReport.composedRays, allReport.composedRays);
      if (clipped)
        EXPECT_EQ(firstReport.rootFinderSteps, allReport.rootFinderSteps);
      else
        EXPECT_LT(firstReport.rootFinderSteps, allReport.rootFinderSteps);
    }
  }
}

/// Frame coherency: a frame seeded by the previous one (the camera turned by 1 degree) has the
/// cold frame's hits (positions within 1e-9), settles most rays from their seeds and takes fewer
/// root-finder steps; a seed frame of another size is ignored.
TEST(RayComposition, SeededFramesEqualColdFrames)
{
  for (const char* name : { "kummer", "heart", "linked-tori" })
  {
    SCOPED_TRACE(name);
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    const iga::Camera before = cameraOf(v);
    iga::Camera after = before;
    const glm::dvec3 arm = before.position - before.focalPoint;
    const double angle = 1.0 * M_PI / 180;
    const glm::dvec3 axis = glm::normalize(before.viewUp);
    after.position = before.focalPoint + arm * std::cos(angle) +
                     glm::cross(axis, arm) * std::sin(angle) +
                     axis * glm::dot(axis, arm) * (1 - std::cos(angle));
    iga::sst::Settings settings;
    settings.width = settings.height = 96;
    settings.isovalues = { 0.0 };
    settings.threads = 2;
    const iga::sst::Scene scene(v.patches);
    GBuffer previous, cold, seeded, ignored;
    iga::sst::render(scene, before, settings, Method::RayComposition, previous);
    const auto coldReport = iga::sst::render(scene, after, settings, Method::RayComposition, cold);
    settings.seedFrame = &previous;
    const auto seededReport =
      iga::sst::render(scene, after, settings, Method::RayComposition, seeded);
    ASSERT_GT(cold.coveredPixels(), 500u);
    ASSERT_EQ(seeded.offsets, cold.offsets);
    for (size_t h = 0; h < cold.hits.size(); ++h)
    {
      ASSERT_LT(glm::length(seeded.hits[h].position - cold.hits[h].position), 1e-9) << "hit " << h;
    }
    EXPECT_EQ(coldReport.seededRays, 0u);
    EXPECT_GT(seededReport.seededRays, cold.coveredPixels() / 2);
    EXPECT_LT(seededReport.rootFinderSteps, coldReport.rootFinderSteps);
    GBuffer small;
    settings.seedFrame = nullptr;
    settings.width = settings.height = 48;
    iga::sst::render(scene, before, settings, Method::RayComposition, small);
    settings.width = settings.height = 96;
    settings.seedFrame = &small;
    EXPECT_EQ(
      iga::sst::render(scene, after, settings, Method::RayComposition, ignored).seededRays, 0u);
  }
}

/// The Kummer surface's f fitted on n^3 cubic elements, those it crosses kept (Wei and Feng's
/// scenes).
iga::AbsField kummerAbsField(int n)
{
  const iga::AlgebraicSurface* kummer = iga::findAlgebraicSurface("kummer");
  const auto f = iga::parsePolynomial(kummer->expression);
  const int cells[3] = { n, n, n };
  return iga::makeAbsField(
    [&](double x, double y, double z) { return f.evaluate(x, y, z); }, kummer->box, 3, cells);
}

/// igaBenchmark's view of an ABS field: its bounds framed from (-0.55, 0.65, -0.5), 30 degrees.
iga::Camera absCamera(const iga::AbsField& field)
{
  double bounds[6];
  iga::sst::patchBounds(iga::sst::Scene(field.set.patches), bounds);
  return iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30);
}

TEST(RayComposition, AbsFieldsAgreeWithTheTree)
{
  // Wei and Feng's scenes: the Kummer surface fitted on 12^3 cubic elements, the elements it
  // crosses kept (hundreds of patches, each seen by few pixels: composed directly).
  const iga::AbsField field = kummerAbsField(12);
  ASSERT_GT(field.set.patches.size(), 300u);
  const iga::Camera camera = absCamera(field);
  iga::sst::Settings settings;
  settings.width = settings.height = 96;
  settings.isovalues = { 0.0 };
  settings.threads = 2;
  settings.isoTolerance = 1e-12;
  GBuffer composed, tree;
  const auto report = iga::sst::render(
    iga::sst::Scene(field.set.patches), camera, settings, Method::Automatic, composed);
  iga::sst::render(
    iga::sst::Scene(field.set.patches), camera, settings, Method::SharedSubdivisionTree, tree);
  EXPECT_EQ(report.rayCompositionPatches, field.set.patches.size());
  EXPECT_EQ(report.unresolvedPixels, 0u);
  ASSERT_GT(composed.coveredPixels(), 1200u);
  size_t differing = 0;
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i)
    {
      const auto* a = composed.firstHit(i, j);
      const auto* b = tree.firstHit(i, j);
      differing += (!a != !b) || (a && b && glm::length(a->position - b->position) > 1e-6);
    }
  EXPECT_LE(differing, composed.coveredPixels() / 100);
  for (const auto& hit : composed.hits)
  {
    double values[iga::kFirstAttributeChannel + 1];
    const iga::VolumeView<const double> patch = field.set.patches[size_t(hit.patch)].view();
    iga::evaluateHomogeneous<double, 3>(patch, &hit.uvw[0], values, nullptr);
    EXPECT_LT(std::fabs(values[iga::kFirstAttributeChannel]), 1e-9);
  }
}

TEST(IsosurfaceCells, HoldEveryRootOfTheFieldAndOnlyCellsThatMay)
{
  // Random segments through the parameter cube, sampled: each sign change of the field (the
  // polynomial itself, not its Bernstein form) bisected to its root, which must lie in a kept
  // cell; and every dropped cell's samples of one sign.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const char* name : { "kiss", "heart", "dervish", "klein", "tangle" })
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    iga::AffinePatch patch;
    ASSERT_TRUE(iga::affineGeometry(v.patches[0].view(), iga::kFirstAttributeChannel, patch));
    const int levels = 3, side = 1 << levels;
    std::vector<char> kept(size_t(side) * side * side, 0);
    for (int octant = 0; octant < 8; ++octant)
    {
      for (const iga::ParameterCell& cell : iga::isosurfaceCells(patch, 0.0, levels, octant))
      {
        ASSERT_DOUBLE_EQ(cell.size, 1.0 / side) << name;
        const glm::ivec3 c = glm::ivec3(glm::round(cell.lo * double(side)));
        kept[size_t((c.z * side + c.y) * side + c.x)] = 1;
      }
    }
    const auto field = [&](const glm::dvec3& u)
    {
      const glm::dvec3 x = patch.origin + patch.axes * u;
      return v.field.evaluate(x.x, x.y, x.z);
    };
    const auto cellOf = [&](const glm::dvec3& u)
    { return glm::min(glm::ivec3(u * double(side)), glm::ivec3(side - 1)); };
    size_t roots = 0;
    for (int segment = 0; segment < 400; ++segment)
    {
      const glm::dvec3 a(unit(random), unit(random), unit(random));
      const glm::dvec3 b(unit(random), unit(random), unit(random));
      double previous = field(a);
      for (int k = 1; k <= 400; ++k)
      {
        const double current = field(a + (k / 400.0) * (b - a));
        if (previous * current < 0)
        {
          double lo = (k - 1) / 400.0, hi = k / 400.0;
          for (int i = 0; i < 60; ++i)
          {
            const double mid = 0.5 * (lo + hi);
            (field(a + mid * (b - a)) * previous > 0 ? lo : hi) = mid;
          }
          const glm::ivec3 c = cellOf(a + lo * (b - a));
          EXPECT_TRUE(kept[size_t((c.z * side + c.y) * side + c.x)])
            << name << " root in a dropped cell";
          ++roots;
        }
        previous = current;
      }
    }
    EXPECT_GT(roots, 100u) << name;
    size_t dropped = 0;
    for (int c = 0; c < side * side * side; ++c)
    {
      if (kept[size_t(c)])
        continue;
      ++dropped;
      const glm::dvec3 lo(c % side, c / side % side, c / (side * side));
      int signs[2] = { 0, 0 };
      for (int q = 0; q < 9 * 9 * 9; ++q)
      {
        const glm::dvec3 u = (lo + glm::dvec3(q % 9, q / 9 % 9, q / 81) / 8.0) / double(side);
        ++signs[field(u) > 0 ? 1 : 0];
      }
      EXPECT_TRUE(signs[0] == 0 || signs[1] == 0) << name << " dropped cell " << c;
    }
    EXPECT_GT(dropped, 0u) << name;
  }
}

/// The frames of `patches` with the isosurface cells off ([0]) and on ([1]), at 256^2.
void framesWithAndWithoutCells(const std::vector<iga::BezierVolume<double>>& patches,
  const iga::Camera& camera, bool firstHit, GBuffer (&frames)[2],
  iga::sst::FrameReport (&reports)[2])
{
  for (int culled = 0; culled < 2; ++culled)
  {
    iga::sst::Settings settings;
    settings.width = settings.height = 256;
    settings.isovalues = { 0.0 };
    settings.threads = 2;
    settings.firstHitOnly = firstHit;
    settings.isosurfaceCells = culled == 1;
    reports[culled] = iga::sst::render(
      iga::sst::Scene(patches), camera, settings, Method::Automatic, frames[culled]);
  }
}

/// How two 256^2 frames' hits compare: pixels whose hit counts differ; of the others' hits, those
/// `trusted` (well conditioned) and the largest distance between them.
struct CellFramesCompared
{
  size_t differing = 0, compared = 0;
  double worst = 0;
};
CellFramesCompared compareCellFrames(
  const GBuffer (&frames)[2], const std::function<bool(const glm::dvec3&)>& trusted)
{
  CellFramesCompared result;
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i)
    {
      const size_t p = size_t(j) * 256 + i;
      const int count = frames[0].hitCount(i, j);
      if (count != frames[1].hitCount(i, j))
      {
        ++result.differing;
        continue;
      }
      for (int k = 0; k < count; ++k)
      {
        const auto& a = frames[0].hits[frames[0].offsets[p] + k];
        const auto& b = frames[1].hits[frames[1].offsets[p] + k];
        if (trusted(a.position))
        {
          result.worst = std::max(result.worst, glm::length(a.position - b.position));
          ++result.compared;
        }
      }
    }
  return result;
}

TEST(RayComposition, IsosurfaceCellsSkipRaysWithoutRoots)
{
  // The same frames with and without the cells, first and all hits: fewer rays composed and
  // fewer finder steps (the cells shorten the rays' segments), the same hits at well
  // conditioned roots to rounding. At the heart's flat (triple) roots near z = 0 rounding alone
  // moves a root by 5e-5 or splits it in three: there the frames may differ, in a pixel or two.
  for (const char* name : { "kiss", "heart", "klein" })
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    const double size = surface->box[1] - surface->box[0];
    for (bool firstHit : { true, false })
    {
      GBuffer frames[2];
      iga::sst::FrameReport reports[2];
      framesWithAndWithoutCells(v.patches, cameraOf(v), firstHit, frames, reports);
      const std::string what = std::string(name) + (firstHit ? " first hit" : " all hits");
      EXPECT_EQ(reports[0].isosurfaceCells, 0u) << what;
      EXPECT_GT(reports[1].isosurfaceCells, 0u) << what;
      EXPECT_LT(reports[1].composedRays, reports[0].composedRays * 3 / 4) << what;
      EXPECT_LT(reports[1].rootFinderSteps, reports[0].rootFinderSteps) << what;
      ASSERT_GT(frames[0].hits.size(), 1000u) << what;
      const CellFramesCompared compared = compareCellFrames(frames,
        [&](const glm::dvec3& x) { return wellConditioned(v, size, cameraOf(v).position, x); });
      EXPECT_LT(compared.worst, 1e-9 * size) << what;
      EXPECT_LE(compared.differing, 2u) << what;
      EXPECT_GT(compared.compared, frames[0].hits.size() * 9 / 10) << what;
    }
  }
}

// Many small patches (an ABS field of 16^3 cubic elements, 8-16 pixels each at 256^2): with
// the cells, a patch's nodes take its cells' window box (the sweep pairs them with those pixels
// only) and a pixel's patches come in their cells' depth order. First and all hits equal the
// frame without the cells: the same hits per pixel, positions within 1e-9 of the box.
TEST(RayComposition, IsosurfaceCellsNarrowManyPatchesWithoutChangingHits)
{
  const iga::AbsField field = kummerAbsField(16);
  const iga::Camera camera = absCamera(field);
  const iga::AlgebraicSurface* kummer = iga::findAlgebraicSurface("kummer");
  const double size = kummer->box[1] - kummer->box[0];
  for (bool firstHit : { true, false })
  {
    GBuffer frames[2];
    iga::sst::FrameReport reports[2];
    framesWithAndWithoutCells(field.set.patches, camera, firstHit, frames, reports);
    const std::string what = firstHit ? "first hit" : "all hits";
    EXPECT_GT(reports[1].isosurfaceCells, 0u) << what;
    EXPECT_LT(reports[1].composedRays, reports[0].composedRays * 3 / 4) << what;
    ASSERT_GT(frames[0].hits.size(), 10000u) << what;
    const CellFramesCompared compared =
      compareCellFrames(frames, [](const glm::dvec3&) { return true; });
    EXPECT_LE(compared.differing, 2u) << what;
    EXPECT_LT(compared.worst, 1e-9 * size) << what;
  }
}

TEST(RayComposition, CellCoverageBoundsEveryHit)
{
  // Every hit of a frame drawn without the cells (all hits, perspective and parallel views) lies
  // in its pixel's mask and within the segment of the ray the mask gives it: what the pass skips
  // and cuts away holds none.
  for (const char* name : { "kiss", "heart", "klein", "dervish" })
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    for (bool parallel : { false, true })
    {
      iga::Camera camera = cameraOf(v);
      camera.parallelProjection = parallel;
      camera.parallelScale = 0.6 * (surface->box[1] - surface->box[0]);
      iga::sst::Settings settings;
      settings.width = settings.height = 256;
      settings.isovalues = { 0.0 };
      settings.threads = 2;
      settings.firstHitOnly = false;
      settings.isosurfaceCells = false;
      GBuffer frame;
      iga::sst::render(iga::sst::Scene(v.patches), camera, settings, Method::RayComposition, frame);
      settings.isosurfaceCells = true;
      iga::sst::FrameReport report;
      const auto affine =
        iga::sst::affineWherePossible(iga::sst::Scene(v.patches), settings, 2, report);
      const iga::sst::View view = iga::sst::makeView(camera, 256, 256);
      const iga::sst::CellCoverage coverage(affine, view, settings, 2);
      const std::string what = std::string(name) + (parallel ? " parallel" : " perspective");
      ASSERT_GT(coverage.cells(), 100u) << what;
      ASSERT_GT(frame.hits.size(), 1000u) << what;
      const glm::dmat4 clipToWorld = glm::inverse(view.worldToClip);
      for (size_t p = 0; p + 1 < frame.offsets.size(); ++p)
      {
        const auto ray = iga::sst::detail::pixelRay(clipToWorld, settings, p);
        for (uint32_t h = frame.offsets[p]; h < frame.offsets[p + 1]; ++h)
        {
          double first, last;
          ASSERT_TRUE(coverage.mayHit(0, 0, p)) << what << " pixel " << p;
          ASSERT_TRUE(coverage.segment(0, 0, p, first, last)) << what;
          const double t = glm::dot(frame.hits[h].position - ray.origin, ray.direction) /
                           glm::dot(ray.direction, ray.direction);
          EXPECT_LE(first, t + 1e-12) << what << " pixel " << p;
          EXPECT_GE(last, t - 1e-12) << what << " pixel " << p;
        }
      }
    }
  }
}

TEST(RayComposition, AffineFormsAreKeptForTheSameDataVersionOnly)
{
  // A camera move under one data version reuses the analysis (and its count of affine patches);
  // another scene, even under a reused version (a caller's mistake the patches' fingerprint
  // catches), gets its own.
  iga::sst::FrameReport report;
  const auto frame = [&report](const char* name, uint64_t version, double turn)
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    const Volume v = algebraicVolume(surface->expression, surface->box);
    iga::Camera camera = cameraOf(v);
    camera.position =
      camera.focalPoint + glm::dvec3(glm::rotate(glm::dmat4(1.0), turn, glm::dvec3(0, 0, 1)) *
                                     glm::dvec4(camera.position - camera.focalPoint, 0));
    iga::sst::Settings settings;
    settings.width = settings.height = 96;
    settings.isovalues = { 0.0 };
    settings.threads = 2;
    settings.dataVersion = version;
    GBuffer out;
    report = iga::sst::render(iga::sst::Scene(v.patches), camera, settings, Method::Automatic, out);
    return out;
  };
  const auto same = [](const GBuffer& a, const GBuffer& b)
  {
    if (a.offsets != b.offsets)
      return false;
    for (size_t h = 0; h < a.hits.size(); ++h)
      if (a.hits[h].position != b.hits[h].position || a.hits[h].normal != b.hits[h].normal)
        return false;
    return true;
  };
  frame("kiss", 9, 0.0);
  EXPECT_TRUE(same(frame("kiss", 9, 0.3), frame("kiss", 0, 0.3)));
  frame("kiss", 9, 0.3);
  EXPECT_EQ(report.rayCompositionPatches, 1u);
  EXPECT_EQ(report.sstPatches, 0u);
  frame("kiss", 9, 0.0);
  const GBuffer heart = frame("heart", 9, 0.0);
  EXPECT_TRUE(same(heart, frame("heart", 0, 0.0)));
  EXPECT_FALSE(same(heart, frame("kiss", 0, 0.0)));
}

TEST(RayComposition, MethodNamesParseBack)
{
  for (Method m : { Method::Automatic, Method::SharedSubdivisionTree, Method::RayComposition,
         Method::BasicScheme, Method::BezierClipping, Method::BruteForce })
    EXPECT_EQ(iga::sst::parseMethod(iga::sst::methodName(m)), m);
  EXPECT_THROW(iga::sst::parseMethod("fast"), std::invalid_argument);
}

TEST(RayComposition, PatchesWithoutAffineGeometryAreRefused)
{
  const double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  Volume v = algebraicVolume("x^2 + y^2 + z^2 - 1", box);
  v.patches[0].view().point(13)[0] += 0.1; // the middle control point moved
  try
  {
    draw(v, 16, Method::RayComposition);
    ADD_FAILURE() << "a curved patch was drawn by ray composition";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("patch 0"), std::string::npos) << e.what();
  }
}

} // namespace
