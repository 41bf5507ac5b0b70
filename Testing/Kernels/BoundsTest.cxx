// Projected boxes, attribute ranges and the unique-root certificate, checked against dense
// sampling and multi-start Newton.
#include "TestPatches.h"

#include "iga/Bounds.h"
#include "iga/Camera.h"
#include "iga/Datasets.h"

#include "iga/Newton.h"
#include <limits>

using namespace igatest;

namespace
{

template<class T>
class BoundsTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(BoundsTest, ScalarTypes);

/// Perspective projection (OpenGL convention, 40 degree field of view, near 0.5, far 50) after a
/// rotation about the y axis and a translation along -z by `distance`.
template<class T>
glm::mat<4, 4, T> viewProjection(double angle, double distance)
{
  const double f = 1.0 / std::tan(20.0 * M_PI / 180.0), n = 0.5, fa = 50.0;
  const double P[4][4] = { { f, 0, 0, 0 }, { 0, f, 0, 0 },
    { 0, 0, (fa + n) / (n - fa), 2 * fa * n / (n - fa) }, { 0, 0, -1, 0 } };
  const double c = std::cos(angle), s = std::sin(angle);
  const double V[4][4] = { { c, 0, s, 0 }, { 0, 1, 0, 0 }, { -s, 0, c, -distance },
    { 0, 0, 0, 1 } };
  glm::mat<4, 4, T> M;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
    {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
        sum += P[i][k] * V[k][j];
      M[j][i] = T(sum);
    }
  return M;
}

TYPED_TEST(BoundsTest, ProjectedBoxContainsDenseSamples)
{
  using T = TypeParam;
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  for (int trial = 0; trial < 20; ++trial)
  {
    int degree[3];
    randomDegrees<3>(rng, degree);
    const auto patch = randomPatch<T, 3>(rng, degree);
    const auto M = viewProjection<T>(angle(rng), 6.0);
    iga::Box3<T> box;
    ASSERT_EQ((iga::projectedBounds<T, 3>(patch.view(), M, box)), iga::ProjectionStatus::InFront);
    const int n = 12;
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
        {
          const double u[3] = { double(i) / n, double(j) / n, double(k) / n };
          const auto v = evaluateEuclidean(patch.view(), u);
          const glm::vec<4, T> clip = M * glm::vec<4, T>(T(v[0]), T(v[1]), T(v[2]), T(1));
          for (int d = 0; d < 3; ++d)
          {
            const double ndc = double(clip[d]) / double(clip[3]);
            const double slack = Tolerance<T>::relative * 10;
            EXPECT_GE(ndc, double(box.lo[d]) - slack);
            EXPECT_LE(ndc, double(box.hi[d]) + slack);
          }
        }
  }
}

TYPED_TEST(BoundsTest, PatchesAtOrBehindTheEyeAreFlagged)
{
  using T = TypeParam;
  std::mt19937 rng(11);
  const int degree[3] = { 2, 2, 2 };
  const auto patch = randomPatch<T, 3>(rng, degree); // inside [-1,1]^3
  iga::Box3<T> box;
  // Eye at the patch's centre: projected weights of both signs.
  EXPECT_EQ((iga::projectedBounds<T, 3>(patch.view(), viewProjection<T>(0, 0.0), box)),
    iga::ProjectionStatus::StraddlesEyePlane);
  // Patch 6 units behind the eye.
  EXPECT_EQ((iga::projectedBounds<T, 3>(patch.view(), viewProjection<T>(0, -6.0), box)),
    iga::ProjectionStatus::BehindEye);
}

TYPED_TEST(BoundsTest, AttributeRangeContainsSamplesAndDecidesSignChange)
{
  using T = TypeParam;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> param(0, 1), iso(-1.2, 1.2);
  int excluded = 0;
  for (int trial = 0; trial < 50; ++trial)
  {
    int degree[3];
    randomDegrees<3>(rng, degree);
    const auto patch = randomPatch<T, 3>(rng, degree);
    T lo = T(0), hi = T(0);
    ASSERT_TRUE((iga::rationalRange<T, 3>(
      patch.view(), iga::kFirstAttributeChannel, iga::kWeightChannel, lo, hi)));
    const T isovalue = T(iso(rng));
    const bool may =
      iga::mayContainIsovalue<T, 3>(patch.view(), iga::kFirstAttributeChannel, isovalue);
    excluded += may ? 0 : 1;
    int below = 0, above = 0;
    for (int s = 0; s < 200; ++s)
    {
      const double u[3] = { param(rng), param(rng), param(rng) };
      const double a = double(evaluateEuclidean(patch.view(), u)[iga::kFirstAttributeChannel]);
      EXPECT_GE(a, double(lo) - Tolerance<T>::relative);
      EXPECT_LE(a, double(hi) + Tolerance<T>::relative);
      (a < double(isovalue) ? below : above)++;
    }
    if (!may)
    {
      EXPECT_TRUE(below == 0 || above == 0) << "a sign change was sampled in an excluded patch";
    }
  }
  EXPECT_GT(excluded, 0) << "the test should exercise excluded patches";
}

TYPED_TEST(BoundsTest, CertifiedPatchesHaveOneRootForMultiStartNewton)
{
  using T = TypeParam;
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> param(0.05, 0.95);
  int certified = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    const auto patch = nearAffinePatch<T>(rng, 0.03);
    if (!iga::certifyUniqueRoot<T, 3>(patch.view(), kPixelRows))
      continue;
    ++certified;
    const double u[3] = { param(rng), param(rng), param(rng) };
    const auto v = evaluateEuclidean(patch.view(), u);
    const T target[3] = { T(v[0]), T(v[1]), T(v[4]) };
    const T tolerance[3] = { T(1e-4), T(1e-4), T(1e-4) };
    for (int start = 0; start < 27; ++start)
    {
      const T u0[3] = { T(0.1 + 0.4 * (start % 3)), T(0.1 + 0.4 * (start / 3 % 3)),
        T(0.1 + 0.4 * (start / 9)) };
      const auto result = iga::solveNewton<T, 3>(patch.view(), kPixelRows, target, tolerance, u0);
      if (result.status == iga::NewtonStatus::Converged)
      {
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(double(result.u[d]), u[d], 1e-2) << "a second root in a certified patch";
      }
    }
  }
  EXPECT_GE(certified, 20) << "mildly curved patches should mostly be certified";
}

TYPED_TEST(BoundsTest, FoldedPatchIsNotCertifiedButItsUnfoldedPartsAre)
{
  using T = TypeParam;
  // Attribute (u - 0.5)^2 on a unit cube: the isosurface a = 0.01 meets every pixel ray twice.
  const int degree[3] = { 2, 1, 1 };
  iga::BezierVolume<T> patch(degree, 5);
  const auto view = patch.view();
  const double attribute[3] = { 0.25, -0.25, 0.25 }; // Bernstein form of (u - 0.5)^2
  for (int p = 0; p < view.pointCount(); ++p)
  {
    const int i = p % 3, j = p / 3 % 2, k = p / 6;
    T* cp = view.point(p);
    cp[0] = T(0.5 * i);
    cp[1] = T(j);
    cp[2] = T(k);
    cp[3] = T(1);
    cp[4] = T(attribute[i]);
  }
  const iga::RationalRow rows[3] = { { 1, 3 }, { 2, 3 }, { 4, 3 } }; // (y, z, a): rays along x
  EXPECT_FALSE((iga::certifyUniqueRoot<T, 3>(view, rows)));
  // The fold is at u = 0.5: parts that avoid it are certified, parts that contain it are not
  // (the derivative of the attribute vanishes there).
  auto left = patch, right = patch;
  iga::split<T, 3>(view, 0, T(0.4), left.view(), right.view());
  EXPECT_TRUE((iga::certifyUniqueRoot<T, 3>(left.view(), rows)));
  EXPECT_FALSE((iga::certifyUniqueRoot<T, 3>(right.view(), rows)));
  iga::split<T, 3>(view, 0, T(0.6), left.view(), right.view());
  EXPECT_FALSE((iga::certifyUniqueRoot<T, 3>(left.view(), rows)));
  EXPECT_TRUE((iga::certifyUniqueRoot<T, 3>(right.view(), rows)));
}

TYPED_TEST(BoundsTest, SubdivisionEventuallyCertifiesCurvedPatches)
{
  using T = TypeParam;
  std::mt19937 rng(14);
  const auto patch = nearAffinePatch<T>(rng, 0.2);
  std::vector<T> level(patch.coeffs());
  const auto view = patch.view();
  const int size = view.valueCount();
  double fraction = 0;
  for (int depth = 0; depth < 5 && fraction < 1.0; ++depth)
  {
    int ok = 0;
    const int count = int(level.size()) / size;
    for (int c = 0; c < count; ++c)
    {
      ok += iga::certifyUniqueRoot<T, 3>(
        iga::VolumeView<const T>(level.data() + c * size, view.degree, view.channels), kPixelRows);
    }
    fraction = double(ok) / count;
    std::vector<T> next(level.size() * 8);
    for (int c = 0; c < count; ++c)
      iga::splitMidpoint<T, 3>(
        iga::VolumeView<const T>(level.data() + c * size, view.degree, view.channels),
        next.data() + 8 * c * size);
    level.swap(next);
  }
  EXPECT_EQ(fraction, 1.0);
}

/// The sphere x^2 + y^2 + z^2 = 1 inside the Marsden volume [-1.5, 1.5]^3: the bounds of where
/// it may lie contain [-1, 1]^3 and shrink onto it as the depth grows; an isovalue the field
/// never takes has none.
TEST(IsosurfaceBounds, ShrinkOntoTheMarsdenSphere)
{
  const auto sphere = iga::makeMarsdenSphere<double>(2).patches[0];
  const int attribute = iga::kFirstAttributeChannel;
  double previous = 1.5;
  for (int depth = 0; depth <= 5; ++depth)
  {
    constexpr double kHuge = std::numeric_limits<double>::max();
    iga::Box3<double> box{ { kHuge, kHuge, kHuge }, { -kHuge, -kHuge, -kHuge } };
    ASSERT_TRUE(iga::growByIsosurfaces(sphere.view(), attribute, { 0.0 }, depth, box));
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_LE(box.lo[a], -1.0);
      EXPECT_GE(box.hi[a], 1.0);
      EXPECT_LE(box.hi[a], previous + 1e-12);
    }
    previous = box.hi[0];
  }
  EXPECT_LT(previous, 1.1); // pieces of 3/32 on a side at depth 5
  iga::Box3<double> none{ { 7, 7, 7 }, { 7, 7, 7 } };
  EXPECT_FALSE(iga::growByIsosurfaces(sphere.view(), attribute, { 10.0 }, 3, none));
  EXPECT_EQ(none.lo[0], 7.0);
}

/// A fitted camera shows a box's corners inside the viewport, the outermost at its margin.
TEST(FitBounds, CornersReachTheMarginAndNoFurther)
{
  const double bounds[6] = { -1, 3, 0, 0.5, 2, 2.2 };
  for (const double aspect : { 0.5, 1.0, 16.0 / 9.0 })
  {
    iga::Camera camera = iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30);
    iga::fitBounds(camera, bounds, aspect, 0.05);
    iga::fitClippingRange(camera, bounds);
    const glm::dmat4 toClip = iga::worldToClip(camera, aspect);
    double most = 0;
    for (int corner = 0; corner < 8; ++corner)
    {
      const glm::dvec4 clip =
        toClip * glm::dvec4(bounds[(corner & 1)], bounds[2 + ((corner >> 1) & 1)],
                   bounds[4 + ((corner >> 2) & 1)], 1.0);
      most = std::max({ most, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w) });
    }
    EXPECT_NEAR(most, 0.95, 1e-9) << "aspect " << aspect;
  }
}

} // namespace
