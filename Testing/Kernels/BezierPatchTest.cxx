// Evaluation, derivatives, subdivision and degree elevation of rational Bézier patches, checked
// against explicit Bernstein sums in long double and central differences.
#include "TestPatches.h"

#include "iga/BezierPatch.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace igatest;

namespace
{

template<class T>
class BezierPatchTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(BezierPatchTest, ScalarTypes);

/// Largest difference between the Euclidean values of `a` at ua and `b` at ub, relative to the
/// values' magnitude.
template<class A, class B, int Dim>
double euclideanDifference(const iga::PatchView<A, Dim>& a, const double* ua,
  const iga::PatchView<B, Dim>& b, const double* ub)
{
  const auto va = evaluateEuclidean(a, ua);
  const auto vb = evaluateEuclidean(b, ub);
  double diff = 0;
  for (size_t c = 0; c < va.size(); ++c)
  {
    diff = std::max(diff, double(std::fabs(va[c] - vb[c])));
  }
  return diff / std::max(1.0, maxAbs(va));
}

template<class T, int Dim>
void checkEvaluation(std::mt19937& rng)
{
  std::uniform_real_distribution<double> param(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial)
  {
    int degree[Dim];
    randomDegrees<Dim>(rng, degree, 6);
    const auto patch = randomPatch<T, Dim>(rng, degree, 2);
    const auto view = patch.view();
    double u[Dim];
    T uT[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      u[d] = param(rng);
      uT[d] = T(u[d]);
      u[d] = double(uT[d]); // evaluate the reference at exactly the same parameter
    }
    std::vector<T> values(view.channels);
    iga::evaluateHomogeneous<T, Dim>(view, uT, values.data(), nullptr);
    const auto reference = evaluateDirect(view, u);
    for (int c = 0; c < view.channels; ++c)
    {
      EXPECT_NEAR(double(values[c]), double(reference[c]),
        Tolerance<T>::relative * std::max(1.0, maxAbs(reference)))
        << "channel " << c << " trial " << trial;
    }
  }
}

TYPED_TEST(BezierPatchTest, EvaluationMatchesExplicitBernsteinSum)
{
  std::mt19937 rng(1);
  checkEvaluation<TypeParam, 3>(rng);
  checkEvaluation<TypeParam, 2>(rng);
}

template<class T, int Dim>
void checkDerivatives(std::mt19937& rng)
{
  std::uniform_real_distribution<double> param(0.05, 0.95);
  for (int trial = 0; trial < 50; ++trial)
  {
    int degree[Dim];
    randomDegrees<Dim>(rng, degree);
    const auto patch = randomPatch<T, Dim>(rng, degree, 1);
    const auto reference = toDouble(patch);
    const auto view = patch.view();
    T uT[Dim];
    double u[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      uT[d] = T(param(rng));
      u[d] = double(uT[d]);
    }
    std::vector<T> values(view.channels), derivatives(Dim * view.channels);
    iga::evaluateHomogeneous<T, Dim>(view, uT, values.data(), derivatives.data());
    const double h = 1e-5;
    for (int c = 0; c < view.channels; ++c)
    {
      if (c == iga::kWeightChannel)
        continue;
      T gradient[Dim];
      iga::rationalValue<T, Dim>(
        values.data(), derivatives.data(), view.channels, c, iga::kWeightChannel, gradient);
      for (int d = 0; d < Dim; ++d)
      {
        double up[Dim], down[Dim];
        for (int e = 0; e < Dim; ++e)
        {
          up[e] = down[e] = u[e];
        }
        up[d] += h;
        down[d] -= h;
        const double central = double(evaluateEuclidean(reference.view(), up)[c] -
                                      evaluateEuclidean(reference.view(), down)[c]) /
                               (2 * h);
        EXPECT_NEAR(double(gradient[d]), central,
          Tolerance<T>::derivative * std::max(1.0, std::fabs(central)))
          << "channel " << c << " direction " << d << " trial " << trial;
      }
    }
  }
}

TYPED_TEST(BezierPatchTest, RationalDerivativesMatchCentralDifferences)
{
  std::mt19937 rng(2);
  checkDerivatives<TypeParam, 3>(rng);
  checkDerivatives<TypeParam, 2>(rng);
}

/// Asked for the leading channels only, the evaluation gives them as the full one does and
/// leaves the others alone: what Newton on a surface (X, Y, Z, W of six) relies on.
template<class T, int Dim>
void checkLeadingChannels(std::mt19937& rng, const int* degree)
{
  constexpr int kLeading = 4;
  const T untouched = T(-12345);
  const auto patch = randomPatch<T, Dim>(rng, degree, 2);
  const auto view = patch.view();
  const T u[3] = { T(0.3), T(0.7), T(0.45) };
  std::vector<T> values(view.channels), derivatives(Dim * view.channels);
  std::vector<T> leading(view.channels, untouched),
    leadingDerivatives(Dim * view.channels, untouched);
  iga::evaluateHomogeneous<T, Dim>(view, u, values.data(), derivatives.data());
  iga::evaluateHomogeneous<T, Dim>(view, u, leading.data(), leadingDerivatives.data(), kLeading);
  for (int c = 0; c < view.channels; ++c)
  {
    const bool asked = c < kLeading;
    EXPECT_EQ(leading[c], asked ? values[c] : untouched) << "channel " << c;
    for (int d = 0; d < Dim; ++d)
    {
      const size_t k = size_t(d * view.channels + c);
      EXPECT_EQ(leadingDerivatives[k], asked ? derivatives[k] : untouched)
        << "channel " << c << " direction " << d;
    }
  }
}

TYPED_TEST(BezierPatchTest, EvaluatesOnlyTheLeadingChannelsAsked)
{
  std::mt19937 rng(5);
  // Equal degrees (the unrolled shapes), unequal ones, and orders past the factorised scratch.
  for (const int p : { 1, 3, 5, 7 })
  {
    const int equal[3] = { p, p, p }, unequal[3] = { p, p + 1, 2 };
    checkLeadingChannels<TypeParam, 2>(rng, equal);
    checkLeadingChannels<TypeParam, 3>(rng, equal);
    checkLeadingChannels<TypeParam, 2>(rng, unequal);
    checkLeadingChannels<TypeParam, 3>(rng, unequal);
  }
  const int high[3] = { 16, 16, 16 };
  checkLeadingChannels<TypeParam, 3>(rng, high);
}

/// Value and gradient of one channel as the sum over every control point of its basis product.
template<class T>
void pointByPoint(const iga::VolumeView<const T>& patch, const double* u, int c, double* out)
{
  double basis[3][iga::kMaxOrder], dbasis[3][iga::kMaxOrder];
  for (int d = 0; d < 3; ++d)
    iga::bernsteinBasis(patch.degree[d], u[d], basis[d], dbasis[d]);
  std::fill(out, out + 4, 0.0);
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    const int index[3] = { p % patch.order(0), p / patch.order(0) % patch.order(1),
      p / (patch.order(0) * patch.order(1)) };
    const double value = double(patch.point(p)[c]);
    out[0] += basis[0][index[0]] * basis[1][index[1]] * basis[2][index[2]] * value;
    for (int d = 0; d < 3; ++d)
    {
      double product = value;
      for (int e = 0; e < 3; ++e)
        product *= e == d ? dbasis[e][index[e]] : basis[e][index[e]];
      out[1 + d] += product;
    }
  }
}

TYPED_TEST(BezierPatchTest, EvaluationMatchesTheSumOverEveryControlPoint)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  // The unrolled shapes, the scratch-factorised ones and the channel-by-channel ones.
  for (const auto& degree : { std::array<int, 3>{ 3, 3, 3 }, std::array<int, 3>{ 4, 2, 5 },
         std::array<int, 3>{ 7, 8, 2 }, std::array<int, 3>{ 16, 16, 16 } })
  {
    const auto patch = randomPatch<TypeParam, 3>(rng, degree.data(), 2);
    const iga::VolumeView<const TypeParam> view = patch.view();
    for (int sample = 0; sample < 5; ++sample)
    {
      const TypeParam u[3] = { TypeParam(param(rng)), TypeParam(param(rng)),
        TypeParam(param(rng)) };
      const double ud[3] = { double(u[0]), double(u[1]), double(u[2]) };
      std::vector<TypeParam> values(size_t(view.channels)), derivatives(size_t(3 * view.channels));
      iga::evaluateHomogeneous<TypeParam, 3>(view, u, values.data(), derivatives.data());
      for (int c = 0; c < view.channels; ++c)
      {
        double reference[4];
        pointByPoint(view, ud, c, reference);
        const double scale = 1 + std::fabs(reference[0]);
        EXPECT_NEAR(double(values[size_t(c)]), reference[0], Tolerance<TypeParam>::relative * scale)
          << degree[0] << " " << degree[1] << " " << degree[2] << " channel " << c;
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(double(derivatives[size_t(d * view.channels + c)]), reference[1 + d],
            Tolerance<TypeParam>::relative * 20 * scale * (1 + degree[size_t(d)]))
            << degree[0] << " " << degree[1] << " " << degree[2] << " channel " << c;
      }
    }
  }
}

template<class T, int Dim>
void checkSplit(std::mt19937& rng)
{
  std::uniform_real_distribution<double> param(0.0, 1.0), cut(0.1, 0.9);
  std::uniform_int_distribution<int> pickDir(0, Dim - 1);
  for (int trial = 0; trial < 40; ++trial)
  {
    int degree[Dim];
    randomDegrees<Dim>(rng, degree, 5);
    const auto parent = randomPatch<T, Dim>(rng, degree, 2);
    const int dir = pickDir(rng);
    const T t = T(cut(rng));
    // Left child computed in place in a copy of the parent: the aliasing the kernels allow.
    auto left = parent;
    auto right = parent;
    iga::split<T, Dim>(left.view(), dir, t, left.view(), right.view());
    for (int sample = 0; sample < 10; ++sample)
    {
      double u[Dim], parentLeft[Dim], parentRight[Dim];
      for (int d = 0; d < Dim; ++d)
      {
        u[d] = parentLeft[d] = parentRight[d] = param(rng);
      }
      parentLeft[dir] = double(t) * u[dir];
      parentRight[dir] = double(t) + (1 - double(t)) * u[dir];
      EXPECT_LT(
        euclideanDifference(left.view(), u, parent.view(), parentLeft), Tolerance<T>::relative);
      EXPECT_LT(
        euclideanDifference(right.view(), u, parent.view(), parentRight), Tolerance<T>::relative);
    }
  }
}

TYPED_TEST(BezierPatchTest, SplitChildrenReproduceParent)
{
  std::mt19937 rng(3);
  checkSplit<TypeParam, 3>(rng);
  checkSplit<TypeParam, 2>(rng);
}

/// Splits random patches at the midpoint of every set of directions: each child reproduces its
/// part of the parent, and the child made alone is the same bit for bit.
template<class T, int Dim>
void checkMidpointSplit(std::mt19937& rng)
{
  std::uniform_real_distribution<double> param(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    int degree[Dim];
    randomDegrees<Dim>(rng, degree, 5);
    const auto parent = randomPatch<T, Dim>(rng, degree, 1);
    const auto view = parent.view();
    for (int axes = 1; axes <= iga::kAllAxes<Dim>; ++axes)
    {
      const int children = 1 << iga::axisCount(axes);
      std::vector<T> split(static_cast<size_t>(view.valueCount()) * children);
      iga::splitMidpoint<T, Dim>(view, split.data(), axes);
      for (int child = 0; child < children; ++child)
      {
        const iga::PatchView<const T, Dim> childView(
          split.data() + child * view.valueCount(), view.degree, view.channels);
        for (int sample = 0; sample < 5; ++sample)
        {
          double u[Dim], parentU[Dim];
          for (int d = 0; d < Dim; ++d)
          {
            u[d] = param(rng);
          }
          iga::childToParentParameter<double, Dim>(child, u, parentU, axes);
          EXPECT_LT(euclideanDifference(childView, u, view, parentU), Tolerance<T>::relative)
            << "axes " << axes << ", child " << child;
        }
        // One child alone (the GPU's thread per child) is the same, bit for bit.
        std::vector<T> alone(static_cast<size_t>(view.valueCount()));
        iga::midpointChild<T, Dim>(view, child, alone.data(), axes);
        EXPECT_TRUE(std::equal(alone.begin(), alone.end(), childView.coeffs))
          << "axes " << axes << ", child " << child;
      }
    }
  }
}

TYPED_TEST(BezierPatchTest, MidpointSplitChildrenReproduceParent)
{
  std::mt19937 rng(4);
  checkMidpointSplit<TypeParam, 3>(rng);
  checkMidpointSplit<TypeParam, 2>(rng);
}

template<class T, int Dim>
void checkElevation(std::mt19937& rng)
{
  std::uniform_real_distribution<double> param(0.0, 1.0);
  std::uniform_int_distribution<int> pickDir(0, Dim - 1), pickTimes(1, 3);
  for (int trial = 0; trial < 30; ++trial)
  {
    int degree[Dim];
    randomDegrees<Dim>(rng, degree, 4);
    const auto patch = randomPatch<T, Dim>(rng, degree, 2);
    const int dir = pickDir(rng);
    const int times = pickTimes(rng);
    const auto elevated = iga::elevateDegree(patch, dir, times);
    ASSERT_EQ(elevated.degree(dir), degree[dir] + times);
    for (int sample = 0; sample < 10; ++sample)
    {
      double u[Dim];
      for (int d = 0; d < Dim; ++d)
      {
        u[d] = param(rng);
      }
      EXPECT_LT(euclideanDifference(elevated.view(), u, patch.view(), u), Tolerance<T>::relative);
    }
  }
}

TYPED_TEST(BezierPatchTest, DegreeElevationIsExact)
{
  std::mt19937 rng(5);
  checkElevation<TypeParam, 3>(rng);
  checkElevation<TypeParam, 2>(rng);
}

TYPED_TEST(BezierPatchTest, HighestDegreeEvaluatesAndSplits)
{
  using T = TypeParam;
  std::mt19937 rng(6);
  const int degree[3] = { iga::kMaxDegree, 2, iga::kMaxDegree };
  const auto patch = randomPatch<T, 3>(rng, degree, 1);
  auto left = patch, right = patch;
  iga::split<T, 3>(patch.view(), 0, T(0.5), left.view(), right.view());
  const double u[3] = { 0.3, 0.7, 0.55 }, parentU[3] = { 0.15, 0.7, 0.55 };
  EXPECT_LT(euclideanDifference(left.view(), u, patch.view(), parentU), Tolerance<T>::relative);
  const T uT[3] = { T(0.3), T(0.7), T(0.55) };
  std::vector<T> values(patch.channels());
  iga::evaluateHomogeneous<T, 3>(patch.view(), uT, values.data(), nullptr);
  const double uExact[3] = { double(uT[0]), double(uT[1]), double(uT[2]) };
  const auto reference = evaluateDirect(patch.view(), uExact);
  EXPECT_NEAR(double(values[0]), double(reference[0]), Tolerance<T>::relative * maxAbs(reference));
}

TEST(Portability, InversePowerOfTwoIsLdexpsExactly)
{
  for (int e = -3; e <= 1100; ++e) // the bit-built range and both sides of it
  {
    EXPECT_EQ(iga::inversePowerOfTwo(e), std::ldexp(1.0, -e)) << "e = " << e;
  }
}

TEST(BernsteinBasis, PartitionOfUnityAndDerivativeSum)
{
  for (int n = 0; n <= iga::kMaxDegree; ++n)
  {
    double basis[iga::kMaxOrder], derivative[iga::kMaxOrder];
    iga::bernsteinBasis(n, 0.37, basis, derivative);
    double sum = 0, dsum = 0;
    for (int i = 0; i <= n; ++i)
    {
      sum += basis[i];
      dsum += derivative[i];
      const double exact = iga::binomial(n, i) * std::pow(0.37, i) * std::pow(0.63, n - i);
      EXPECT_NEAR(basis[i], exact, 1e-14) << "n " << n << " i " << i;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(dsum, 0.0, 1e-12);
  }
}

} // namespace
