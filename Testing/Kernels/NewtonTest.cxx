// Newton's method on the pixel problem: convergence to known roots, and clear failure statuses
// on constructed singular and out-of-domain cases.
#include "TestPatches.h"

#include "iga/Newton.h"

using namespace igatest;

namespace
{

template<class T>
class NewtonTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(NewtonTest, ScalarTypes);

TYPED_TEST(NewtonTest, ConvergesToKnownRootsOfCurvedRationalVolumes)
{
  using T = TypeParam;
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> param(0.05, 0.95);
  for (int trial = 0; trial < 50; ++trial)
  {
    const auto patch = nearAffinePatch<T>(rng, 0.1);
    const double u[3] = { param(rng), param(rng), param(rng) };
    const auto v = evaluateEuclidean(patch.view(), u);
    const T target[3] = { T(v[0]), T(v[1]), T(v[4]) };
    const T tolerance[3] = { T(1e-3), T(1e-3), T(1e-5) };
    const T u0[3] = { T(0.5), T(0.5), T(0.5) };
    const auto result = iga::solveNewton<T, 3>(patch.view(), kPixelRows, target, tolerance, u0);
    ASSERT_EQ(result.status, iga::NewtonStatus::Converged) << "trial " << trial;
    EXPECT_LE(result.iterations, 8);
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(double(result.u[d]), u[d], Tolerance<T>::parameter * 10) << "trial " << trial;
      EXPECT_LE(std::fabs(double(result.residual[d])), double(tolerance[d]));
    }
  }
}

TYPED_TEST(NewtonTest, SurfaceVariantFindsPixelPoint)
{
  using T = TypeParam;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> param(0.1, 0.9);
  for (int trial = 0; trial < 30; ++trial)
  {
    // A gently curved rational surface over the xy plane: x, y near u, v; z and weights random.
    const int degree[2] = { 3, 3 };
    auto surface = randomPatch<T, 2>(rng, degree, 0);
    const auto view = surface.view();
    for (int p = 0; p < view.pointCount(); ++p)
    {
      const double w = double(view.point(p)[3]) / 4.0 + 0.8; // weights in [0.85, 2.05]
      view.point(p)[0] = T(w * ((p % 4) / 3.0 + 0.05 * std::sin(p)));
      view.point(p)[1] = T(w * ((p / 4) / 3.0 + 0.05 * std::cos(p)));
      view.point(p)[2] = T(w * double(view.point(p)[2]) / double(view.point(p)[3]));
      view.point(p)[3] = T(w);
    }
    const double u[2] = { param(rng), param(rng) };
    const auto v = evaluateEuclidean(surface.view(), u);
    const iga::RationalRow rows[2] = { { 0, 3 }, { 1, 3 } };
    const T target[2] = { T(v[0]), T(v[1]) };
    const T tolerance[2] = { T(1e-4), T(1e-4) };
    const T u0[2] = { T(0.5), T(0.5) };
    const auto result = iga::solveNewton<T, 2>(surface.view(), rows, target, tolerance, u0);
    ASSERT_EQ(result.status, iga::NewtonStatus::Converged) << "trial " << trial;
    EXPECT_NEAR(double(result.u[0]), u[0], Tolerance<T>::parameter * 10);
    EXPECT_NEAR(double(result.u[1]), u[1], Tolerance<T>::parameter * 10);
  }
}

/// A loose tolerance stops the iteration early; the final step, taken without evaluating, still
/// ends at the root far below the residual tested, and the values at the root follow it.
TEST(NewtonFinalStep, TakesTheRootFarBeyondTheResidualTested)
{
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> param(0.1, 0.9);
  int stepped = 0;
  for (int trial = 0; trial < 30; ++trial)
  {
    const auto patch = nearAffinePatch<double>(rng, 0.1);
    const double u[3] = { param(rng), param(rng), param(rng) };
    const auto v = evaluateEuclidean(patch.view(), u);
    const double target[3] = { double(v[0]), double(v[1]), double(v[4]) };
    const double tolerance[3] = { 0.05, 0.05, 0.05 };
    const double u0[3] = { 0.5, 0.5, 0.5 };
    double atRoot[8];
    const auto result =
      iga::solveNewton<double, 3>(patch.view(), kPixelRows, target, tolerance, u0, {}, atRoot);
    ASSERT_EQ(result.status, iga::NewtonStatus::Converged) << "trial " << trial;
    double values[8];
    iga::evaluateHomogeneous<double, 3>(patch.view(), result.u, values, nullptr);
    double tested = 0, after = 0;
    for (int r = 0; r < 3; ++r)
    {
      const double f = values[kPixelRows[r].numerator] / values[kPixelRows[r].denominator];
      tested = std::max(tested, std::fabs(result.residual[r]));
      after = std::max(after, std::fabs(f - target[r]));
    }
    stepped += tested > 1e-8 ? 1 : 0;
    EXPECT_LE(after, 1e-3 * tested + 1e-13) << "trial " << trial;
    for (int c = 0; c < 5; ++c) // the channels the rows read, up to the attribute
    {
      // First order in a step of the order of the residual tested.
      EXPECT_NEAR(atRoot[c], values[c], 10 * tested * tested + 1e-13) << "channel " << c;
    }
  }
  EXPECT_GT(stepped, 10) << "trials stopped with a residual the final step had to remove";
}

TYPED_TEST(NewtonTest, ReportsSingularJacobianWhenAParameterHasNoEffect)
{
  using T = TypeParam;
  std::mt19937 rng(22);
  auto patch = nearAffinePatch<T>(rng, 0.1);
  const auto view = patch.view();
  // Copy the w = 0 layer to every layer: nothing depends on the third parameter.
  const int layer = view.order(0) * view.order(1) * view.channels;
  for (int k = 1; k < view.order(2); ++k)
    for (int v = 0; v < layer; ++v)
      view.coeffs[k * layer + v] = view.coeffs[v];
  const double u[3] = { 0.3, 0.6, 0.5 };
  const auto v = evaluateEuclidean(patch.view(), u);
  const T target[3] = { T(v[0]) + T(0.01), T(v[1]), T(v[4]) };
  const T tolerance[3] = { T(1e-4), T(1e-4), T(1e-5) };
  const T u0[3] = { T(0.5), T(0.5), T(0.5) };
  const auto result = iga::solveNewton<T, 3>(patch.view(), kPixelRows, target, tolerance, u0);
  EXPECT_EQ(result.status, iga::NewtonStatus::SingularJacobian);
}

TYPED_TEST(NewtonTest, ReportsLeavingTheDomainForARootOutsideThePatch)
{
  using T = TypeParam;
  std::mt19937 rng(23);
  const auto patch = nearAffinePatch<T>(rng, 0.0); // exactly affine: extrapolation is exact
  const double outside[3] = { 1.6, 0.5, 0.5 };
  const auto b = evaluateEuclidean(patch.view(), outside);
  const T target[3] = { T(b[0]), T(b[1]), T(b[4]) };
  const T tolerance[3] = { T(1e-4), T(1e-4), T(1e-5) };
  const T u0[3] = { T(0.5), T(0.5), T(0.5) };
  const auto result = iga::solveNewton<T, 3>(patch.view(), kPixelRows, target, tolerance, u0);
  EXPECT_EQ(result.status, iga::NewtonStatus::LeftDomain);
}

TYPED_TEST(NewtonTest, ReportsNoConvergenceWithinTheIterationLimit)
{
  using T = TypeParam;
  std::mt19937 rng(24);
  const auto patch = nearAffinePatch<T>(rng, 0.3);
  const double u[3] = { 0.9, 0.1, 0.85 };
  const auto v = evaluateEuclidean(patch.view(), u);
  const T target[3] = { T(v[0]), T(v[1]), T(v[4]) };
  const T tolerance[3] = { T(1e-6), T(1e-6), T(1e-6) };
  const T u0[3] = { T(0.1), T(0.9), T(0.1) };
  iga::NewtonSettings<T> settings;
  settings.maxIterations = 1;
  const auto result =
    iga::solveNewton<T, 3>(patch.view(), kPixelRows, target, tolerance, u0, settings);
  EXPECT_EQ(result.status, iga::NewtonStatus::NoConvergence);
}

} // namespace
