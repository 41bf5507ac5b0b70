// Power form to Bernstein form over a box: the volume reproduces the polynomial exactly.
#include "TestPatches.h"

#include "iga/Polynomial.h"

using namespace igatest;

namespace
{

template<class T>
class PolynomialTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(PolynomialTest, ScalarTypes);

TYPED_TEST(PolynomialTest, BernsteinVolumeReproducesRandomPolynomials)
{
  using T = TypeParam;
  std::mt19937 rng(40);
  std::uniform_real_distribution<double> coeff(-1, 1), corner(-2, 1), size(0.5, 2), unit(0, 1);
  std::uniform_int_distribution<int> pickDegree(0, 4), pickExtra(0, 2);
  for (int trial = 0; trial < 30; ++trial)
  {
    iga::Polynomial3<T> poly(pickDegree(rng), pickDegree(rng), pickDegree(rng));
    for (auto& c : poly.coeffs)
      c = T(coeff(rng));
    T lo[3], hi[3];
    int degree[3];
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = T(corner(rng));
      hi[d] = lo[d] + T(size(rng));
      degree[d] = std::max(1, poly.degree[d]) + pickExtra(rng);
    }
    const auto volume = iga::makePolynomialVolume(poly, lo, hi, degree);
    double scale = 0;
    for (const auto& c : poly.coeffs)
      scale += std::fabs(double(c));
    for (int s = 0; s < 20; ++s)
    {
      const double u[3] = { unit(rng), unit(rng), unit(rng) };
      const auto v = evaluateEuclidean(volume.view(), u);
      double x[3];
      for (int d = 0; d < 3; ++d)
      {
        x[d] = double(lo[d]) + (double(hi[d]) - double(lo[d])) * u[d];
        EXPECT_NEAR(double(v[d]), x[d], Tolerance<T>::relative * 10);
      }
      EXPECT_NEAR(double(v[iga::kFirstAttributeChannel]), poly.evaluate(x[0], x[1], x[2]),
        Tolerance<T>::relative * 100 * std::max(1.0, scale))
        << "trial " << trial;
    }
  }
}

TYPED_TEST(PolynomialTest, MarsdenSphereAtDegreesTwoToFive)
{
  using T = TypeParam;
  iga::Polynomial3<T> sphere(2, 2, 2);
  sphere.at(0, 0, 0) = T(-1);
  sphere.at(2, 0, 0) = sphere.at(0, 2, 0) = sphere.at(0, 0, 2) = T(1);
  const T lo[3] = { T(-1.5), T(-1.5), T(-1.5) }, hi[3] = { T(1.5), T(1.5), T(1.5) };
  const int quadratic[3] = { 2, 2, 2 };
  const auto base = iga::makePolynomialVolume(sphere, lo, hi, quadratic);
  // Known Bernstein coefficients of the tri-quadratic: x^2 on [-1.5,1.5] has (2.25, -2.25, 2.25).
  EXPECT_NEAR(double(base.view().point(0)[4]), 3 * 2.25 - 1, 1e-6);
  EXPECT_NEAR(double(base.view().point(13)[4]), -3 * 2.25 - 1, 1e-6); // centre control point
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int degree = 3; degree <= 5; ++degree)
  {
    auto elevated = base;
    for (int d = 0; d < 3; ++d)
      elevated = iga::elevateDegree(elevated, d, degree - 2);
    const int direct[3] = { degree, degree, degree };
    const auto fromPolynomial = iga::makePolynomialVolume(sphere, lo, hi, direct);
    ASSERT_EQ(elevated.coeffs().size(), fromPolynomial.coeffs().size());
    for (size_t i = 0; i < elevated.coeffs().size(); ++i)
      EXPECT_NEAR(double(elevated.coeffs()[i]), double(fromPolynomial.coeffs()[i]),
        Tolerance<T>::relative * 10);
    for (int s = 0; s < 20; ++s)
    {
      const double u[3] = { unit(rng), unit(rng), unit(rng) };
      const auto v = evaluateEuclidean(elevated.view(), u);
      const double r2 = double(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      EXPECT_NEAR(double(v[4]), r2 - 1, Tolerance<T>::relative * 20);
    }
  }
}

TEST(PolynomialVolume, RejectsDegreesThatCannotHoldThePolynomial)
{
  iga::Polynomial3<double> poly(3, 1, 1);
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const int tooLow[3] = { 2, 1, 1 };
  EXPECT_THROW(iga::makePolynomialVolume(poly, lo, hi, tooLow), std::invalid_argument);
  const int tooHigh[3] = { 17, 1, 1 };
  EXPECT_THROW(iga::makePolynomialVolume(poly, lo, hi, tooHigh), std::invalid_argument);
  const int fine[3] = { 3, 1, 1 };
  const double flat[3] = { 0, 1, 0 };
  EXPECT_THROW(iga::makePolynomialVolume(poly, lo, flat, fine), std::invalid_argument);
}

} // namespace
