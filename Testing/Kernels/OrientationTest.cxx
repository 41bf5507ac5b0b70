// Signed volumes and reversed directions of Bézier and B-spline volumes, against affine maps,
// a brute-force midpoint sum of finite-difference Jacobians and direct evaluation.
#include "NurbsReference.h"
#include "TestPatches.h"

#include "iga/Datasets.h"
#include "iga/Orientation.h"

using namespace igatest;

namespace
{

/// A polynomial patch of the given degrees whose control points lie on x = A u + b, so that the
/// map is that affine map.
iga::BezierVolume<double> affinePatch(const int* degree, const double (&a)[3][3])
{
  iga::BezierVolume<double> patch(degree, iga::kFirstAttributeChannel);
  const auto view = patch.view();
  int linear = 0;
  for (int k = 0; k <= degree[2]; ++k)
    for (int j = 0; j <= degree[1]; ++j)
      for (int i = 0; i <= degree[0]; ++i, ++linear)
      {
        const double u[3] = { double(i) / degree[0], double(j) / degree[1], double(k) / degree[2] };
        double* cp = view.point(linear);
        for (int r = 0; r < 3; ++r)
          cp[r] = a[r][0] * u[0] + a[r][1] * u[1] + a[r][2] * u[2] + 0.5 * r;
        cp[iga::kWeightChannel] = 1;
      }
  return patch;
}

/// Volume by the midpoint rule on n^3 cells with the Jacobian from central differences of
/// positions evaluated by the explicit Bernstein formula.
double bruteForceVolume(const iga::PatchView<const double, 3>& patch, int n)
{
  const double h = 1.0 / n, delta = 1e-5;
  double sum = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        glm::dmat3 jacobian; // column d: derivative along direction d
        for (int d = 0; d < 3; ++d)
        {
          double lo[3] = { (i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h }, hi[3];
          std::copy(lo, lo + 3, hi);
          lo[d] -= delta;
          hi[d] += delta;
          const auto a = evaluateEuclidean(patch, lo), b = evaluateEuclidean(patch, hi);
          for (int e = 0; e < 3; ++e)
            jacobian[d][e] = double(b[e] - a[e]) / (2 * delta);
        }
        sum += glm::determinant(jacobian);
      }
  return sum * h * h * h;
}

TEST(Orientation, AffinePatchVolumeIsTheDeterminant)
{
  const int degree[3] = { 2, 1, 3 };
  const double right[3][3] = { { 2, 0.3, 0 }, { 0, 1.5, -0.2 }, { 0.1, 0, 0.5 } };
  const double det = 2 * (1.5 * 0.5 - 0) - 0.3 * (0 * 0.5 + 0.2 * 0.1) + 0;
  EXPECT_NEAR(iga::signedVolume<double>(affinePatch(degree, right).view()), det, 1e-12);
  const double left[3][3] = { { -2, 0.3, 0 }, { 0, 1.5, -0.2 }, { -0.1, 0, 0.5 } };
  EXPECT_NEAR(iga::signedVolume<double>(affinePatch(degree, left).view()), -det, 1e-12);
}

TEST(Orientation, CurvedPatchVolumeMatchesBruteForce)
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3; ++trial)
  {
    // Gauss quadrature is only close for curved rational maps; the sign is what callers use.
    const auto patch = nearAffinePatch<double>(rng, 0.1);
    const double reference = bruteForceVolume(patch.view(), 12);
    ASSERT_GT(std::abs(reference), 1e-3);
    EXPECT_NEAR(iga::signedVolume<double>(patch.view()), reference, 0.05 * std::abs(reference));
  }
}

TEST(Orientation, ReversedBezierPatchIsTheSameVolume)
{
  std::mt19937 rng(5);
  const int degree[3] = { 3, 2, 1 };
  for (int dir = 0; dir < 3; ++dir)
  {
    const auto original = randomPatch<double, 3>(rng, degree, 2);
    auto reversed = original;
    iga::reverseDirection(reversed.view(), dir);
    for (double s : { 0.0, 0.3, 0.71, 1.0 })
    {
      double u[3] = { 0.2, 0.55, 0.9 }, mirrored[3];
      u[dir] = s;
      std::copy(u, u + 3, mirrored);
      mirrored[dir] = 1 - s;
      const auto a = evaluateEuclidean(original.view(), u);
      const auto b = evaluateEuclidean(reversed.view(), mirrored);
      for (size_t c = 0; c < a.size(); ++c)
        EXPECT_NEAR(double(a[c]), double(b[c]), 1e-12) << "dir " << dir << " channel " << c;
    }
    EXPECT_NEAR(iga::signedVolume<double>(reversed.view()),
      -iga::signedVolume<double>(original.view()), 1e-12);
    iga::reverseDirection(reversed.view(), dir);
    EXPECT_EQ(reversed.coeffs(), original.coeffs());
  }
}

TEST(Orientation, ReversedBSplinePatchIsTheSameVolume)
{
  const auto ball = iga::makeNurbsBall<double>(3, -1.0); // x mirrored: left-handed
  const iga::BezierExtraction<double, 3> extraction(ball.knots, ball.degree, ball.netSize);
  const double volume = iga::signedVolume(extraction, ball.net, ball.channels);
  // Close to the mirrored box [-1.2, 1.2]^3 the control points span.
  EXPECT_NEAR(volume, -2.4 * 2.4 * 2.4, 0.05 * 2.4 * 2.4 * 2.4);
  for (int dir = 0; dir < 3; ++dir)
  {
    auto reversed = ball;
    iga::reverseDirection(reversed, dir);
    const iga::BezierExtraction<double, 3> mirroredExtraction(
      reversed.knots, reversed.degree, reversed.netSize);
    EXPECT_NEAR(
      iga::signedVolume(mirroredExtraction, reversed.net, reversed.channels), -volume, 1e-9);
    for (double s : { 0.0, 0.15, 0.5, 0.8, 1.0 })
    {
      double u[3] = { 0.3, 0.6, 0.45 }, mirrored[3];
      u[dir] = s;
      std::copy(u, u + 3, mirrored);
      mirrored[dir] = 1 - s; // knots span [0, 1]
      const auto a = evaluateNurbs(ball, u), b = evaluateNurbs(reversed, mirrored);
      for (size_t c = 0; c < a.size(); ++c)
        EXPECT_NEAR(a[c], b[c], 1e-12) << "dir " << dir << " s " << s << " channel " << c;
    }
  }
}

} // namespace
