// The root finders of univariate Bernstein polynomials against roots known by construction and
// polished in long double on the very coefficients the finders see (so that the reference is
// the rounded polynomial's root, not the one it was built from): random products of real roots
// in [0, 1], roots outside it and complex pairs, degrees 1 to 16, with double roots, roots at
// t = 0 and 1, and polynomials that come close to zero without reaching it.
#include "iga/BernsteinRoots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace
{

using Poly = std::vector<long double>; // Bernstein coefficients of degree size() - 1

long double binomial(int n, int k)
{
  long double b = 1;
  for (int i = 1; i <= k; ++i)
  {
    b = b * (n - k + i) / i;
  }
  return b;
}

/// The product in the Bernstein basis of degree m + n.
Poly multiply(const Poly& f, const Poly& g)
{
  const int m = int(f.size()) - 1, n = int(g.size()) - 1;
  Poly h(size_t(m + n + 1), 0.0L);
  for (int i = 0; i <= m; ++i)
  {
    for (int j = 0; j <= n; ++j)
    {
      h[size_t(i + j)] +=
        binomial(m, i) * binomial(n, j) / binomial(m + n, i + j) * f[size_t(i)] * g[size_t(j)];
    }
  }
  return h;
}

Poly linear(long double root) // t - root
{
  return { -root, 1 - root };
}

Poly complexPair(long double a, long double b) // (t - a)^2 + b^2
{
  return { a * a + b * b, a * a + b * b - a, (1 - a) * (1 - a) + b * b };
}

/// Value and derivative of a double-coefficient polynomial, in long double.
void evaluate(const std::vector<double>& c, long double t, long double& value, long double& slope)
{
  const int d = int(c.size()) - 1;
  std::vector<long double> w(c.begin(), c.end());
  for (int r = 1; r < d; ++r)
  {
    for (int i = 0; i <= d - r; ++i)
    {
      w[size_t(i)] = (1 - t) * w[size_t(i)] + t * w[size_t(i + 1)];
    }
  }
  value = d > 0 ? (1 - t) * w[0] + t * w[1] : w[0];
  slope = d > 0 ? d * (w[1] - w[0]) : 0;
}

std::vector<double> derivative(const std::vector<double>& c)
{
  std::vector<double> d;
  for (size_t i = 0; i + 1 < c.size(); ++i)
  {
    d.push_back(double((c.size() - 1) * (long double)(c[i + 1] - c[i])));
  }
  return d;
}

/// Newton in long double on the rounded polynomial (on its derivative for a double root).
long double polish(const std::vector<double>& c, long double t)
{
  for (int k = 0; k < 60; ++k)
  {
    long double v, s;
    evaluate(c, t, v, s);
    if (s == 0)
    {
      break;
    }
    t -= v / s;
  }
  return t;
}

struct Case
{
  std::vector<double> coefficients;
  std::vector<double> roots; ///< reference, sorted
  std::string what;
};

/// A random polynomial of degree `degree` with `real` simple roots in [0, 1] (separated by at
/// least 0.05), `doubled` double roots there, the rest complex pairs or real roots outside.
Case randomCase(std::mt19937& rng, int degree, int real, int doubled)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<long double> inside;
  while (int(inside.size()) < real + doubled)
  {
    const long double r = 0.02 + 0.96 * unit(rng);
    bool apart = true;
    for (long double other : inside)
      apart = apart && std::fabs(double(other - r)) >= 0.05;
    if (apart)
      inside.push_back(r);
  }
  Poly f = { 1.0L };
  for (int k = 0; k < real; ++k)
    f = multiply(f, linear(inside[size_t(k)]));
  for (int k = real; k < real + doubled; ++k)
    f = multiply(f, multiply(linear(inside[size_t(k)]), linear(inside[size_t(k)])));
  while (int(f.size()) - 1 < degree)
  {
    if (int(f.size()) - 1 + 2 <= degree && unit(rng) < 0.5)
      f = multiply(f, complexPair(unit(rng), 0.1 + unit(rng)));
    else
      f = multiply(f, linear(unit(rng) < 0.5 ? -0.1 - 2 * unit(rng) : 1.1 + 2 * unit(rng)));
  }
  const long double scale = std::pow(10.0L, 6 * unit(rng) - 3) * (unit(rng) < 0.5 ? -1 : 1);
  Case c;
  for (long double v : f)
    c.coefficients.push_back(double(scale * v));
  const std::vector<double> slope = derivative(c.coefficients);
  for (int k = 0; k < real + doubled; ++k)
  {
    const long double r = inside[size_t(k)];
    c.roots.push_back(double(k < real ? polish(c.coefficients, r) : polish(slope, r)));
  }
  std::sort(c.roots.begin(), c.roots.end());
  c.what = "degree " + std::to_string(degree) + ", " + std::to_string(real) + " simple and " +
           std::to_string(doubled) + " double roots";
  return c;
}

constexpr iga::RootFinder kFinders[] = { iga::RootFinder::Subdivision,
  iga::RootFinder::KnotInsertion, iga::RootFinder::BezierClipping, iga::RootFinder::PointInsertion,
  iga::RootFinder::PolarNewton };

void expectRoots(const Case& c, iga::RootFinder finder, double accuracy = 1e-9)
{
  const iga::BernsteinRoots found =
    iga::findBernsteinRoots(c.coefficients.data(), int(c.coefficients.size()) - 1, finder);
  std::string list; // the roots found and the coefficients, for a failure's message
  for (int k = 0; k < found.count; ++k)
    list += " " + std::to_string(found.t[k]);
  list += " of";
  for (double v : c.coefficients)
  {
    char text[32];
    std::snprintf(text, sizeof(text), " %.17g", v);
    list += text;
  }
  ASSERT_FALSE(found.invalid);
  EXPECT_FALSE(found.cost.capped) << iga::rootFinderName(finder) << ", " << c.what;
  ASSERT_EQ(size_t(found.count), c.roots.size())
    << iga::rootFinderName(finder) << ", " << c.what << ": found" << list;
  for (int k = 0; k < found.count; ++k)
  {
    EXPECT_NEAR(found.t[k], c.roots[size_t(k)], accuracy)
      << iga::rootFinderName(finder) << ", " << c.what << ", root " << k;
    if (k > 0)
    {
      EXPECT_LT(found.t[k - 1], found.t[k]);
    }
  }
}

TEST(BernsteinRoots, EveryFinderFindsTheSimpleRootsOfRandomPolynomials)
{
  std::mt19937 rng(11);
  for (int degree = 1; degree <= 16; ++degree)
  {
    for (int trial = 0; trial < 12; ++trial)
    {
      const int real = std::uniform_int_distribution<int>(0, std::min(degree, 6))(rng);
      const Case c = randomCase(rng, degree, real, 0);
      for (iga::RootFinder finder : kFinders)
        expectRoots(c, finder);
    }
  }
}

TEST(BernsteinRoots, EveryFinderFindsDoubleRootsOnce)
{
  std::mt19937 rng(12);
  for (int degree = 2; degree <= 16; ++degree)
  {
    for (int trial = 0; trial < 6; ++trial)
    {
      const int doubled = std::uniform_int_distribution<int>(1, std::min(degree / 2, 2))(rng);
      const int real =
        std::uniform_int_distribution<int>(0, std::min(degree - 2 * doubled, 3))(rng);
      const Case c = randomCase(rng, degree, real, doubled);
      for (iga::RootFinder finder : kFinders)
        expectRoots(c, finder);
    }
  }
}

/// The search for even roots (the derivative's roots where the polynomial touches zero) runs
/// only where the odd roots' search cannot rule them out: for simple roots it is skipped (the
/// same steps as without it) in most cases, for the first root as for all, with the same roots;
/// double roots are still found.
TEST(BernsteinRoots, TheEvenRootSearchRunsOnlyWhereTheOddSearchCannotRuleItOut)
{
  std::mt19937 rng(14);
  for (const int wanted : { 1, iga::roots::kMaxRoots })
  {
    int skipped = 0, cases = 0;
    for (int degree = 2; degree <= 16; ++degree)
    {
      for (int trial = 0; trial < 12; ++trial)
      {
        const int real = std::uniform_int_distribution<int>(1, std::min(degree, 6))(rng);
        const Case c = randomCase(rng, degree, real, 0);
        for (iga::RootFinder finder : kFinders)
        {
          if (finder == iga::RootFinder::PolarNewton) // isolates critical points itself
            continue;
          iga::RootSettings settings, oddOnly;
          settings.maxRoots = oddOnly.maxRoots = wanted;
          oddOnly.evenRoots = false;
          const auto all = iga::findBernsteinRoots(c.coefficients.data(), degree, finder, settings);
          const auto odd = iga::findBernsteinRoots(c.coefficients.data(), degree, finder, oddOnly);
          ASSERT_EQ(all.count, odd.count) << c.what;
          for (int k = 0; k < all.count; ++k)
            EXPECT_EQ(all.t[k], odd.t[k]) << c.what;
          ++cases;
          skipped += all.cost.insertions == odd.cost.insertions &&
                     all.cost.evaluations == odd.cost.evaluations;
        }
      }
    }
    EXPECT_GT(skipped, cases / 2) << "of " << cases << " searches for " << wanted;
  }
  // A near touch within rounding (minimum 1e-14 at t = 0.88064019577) beside the rounding's own
  // sign change: Bézier clipping's clipped-off margins must not hide it.
  const double touch[3] = { 0.77552715441517506, -0.10511304136012856, 0.01424676286456783 };
  for (iga::RootFinder finder : kFinders)
  {
    const auto found = iga::findBernsteinRoots(touch, 2, finder);
    bool seen = false;
    for (int k = 0; k < found.count; ++k)
      seen = seen || std::fabs(found.t[k] - 0.88064019577) < 1e-8;
    EXPECT_TRUE(seen) << iga::rootFinderName(finder) << ": " << found.count << " roots";
  }
  // Double roots: found, whether the odd search's rounding saw them or the even search did.
  for (int trial = 0; trial < 20; ++trial)
  {
    const Case doubled = randomCase(rng, 8, 2, 1);
    for (iga::RootFinder finder : kFinders)
      expectRoots(doubled, finder);
  }
}

TEST(BernsteinRoots, RootsAtTheEndsAreExact)
{
  // t (1 - t)^2 (t - 0.3) (t - 0.7): a simple root at 0, a double one at 1.
  Poly f = multiply(
    multiply(linear(0), multiply(linear(1), linear(1))), multiply(linear(0.3L), linear(0.7L)));
  Case c;
  for (long double v : f)
    c.coefficients.push_back(double(v));
  c.roots = { 0.0, double(polish(c.coefficients, 0.3L)), double(polish(c.coefficients, 0.7L)),
    1.0 };
  c.what = "roots at 0 and 1";
  for (iga::RootFinder finder : kFinders)
    expectRoots(c, finder);
}

/// A search for the first k roots returns the full search's first k (simple, double and end
/// roots), and stops early: for the first root alone, under half the steps over all the cases
/// (measured: 27-43%) by the finders that search left first, fewer by the polar Newton (90%).
TEST(BernsteinRoots, TheNearestRootsAloneAreTheFullSearchsFirst)
{
  std::mt19937 rng(14);
  std::vector<Case> cases;
  for (int degree = 2; degree <= 16; ++degree)
  {
    for (int trial = 0; trial < 6; ++trial)
    {
      const int doubled = std::uniform_int_distribution<int>(0, std::min((degree - 1) / 2, 2))(rng);
      const int real =
        std::uniform_int_distribution<int>(1, std::min(degree - 2 * doubled, 4))(rng);
      cases.push_back(randomCase(rng, degree, real, doubled));
    }
  }
  Poly ends = multiply(multiply(linear(0), linear(0.4L)), multiply(linear(1), linear(1)));
  cases.push_back({});
  for (long double v : ends)
    cases.back().coefficients.push_back(double(v));
  for (iga::RootFinder finder : kFinders)
  {
    long fullSteps = 0, firstSteps = 0;
    for (const Case& c : cases)
    {
      const int degree = int(c.coefficients.size()) - 1;
      const iga::BernsteinRoots full =
        iga::findBernsteinRoots(c.coefficients.data(), degree, finder);
      ASSERT_GT(full.count, 0);
      fullSteps += full.cost.insertions + full.cost.evaluations;
      for (int wanted = 1; wanted <= 3; ++wanted)
      {
        iga::RootSettings settings;
        settings.maxRoots = wanted;
        const iga::BernsteinRoots first =
          iga::findBernsteinRoots(c.coefficients.data(), degree, finder, settings);
        ASSERT_EQ(first.count, std::min(wanted, full.count))
          << iga::rootFinderName(finder) << ", " << c.what << ", " << wanted << " wanted";
        for (int k = 0; k < first.count; ++k)
        {
          EXPECT_NEAR(first.t[k], full.t[k], 1e-12)
            << iga::rootFinderName(finder) << ", " << c.what << ", root " << k;
        }
        firstSteps += wanted == 1 ? first.cost.insertions + first.cost.evaluations : 0;
      }
    }
    // The polar Newton still finds every critical point: its last level alone stops early.
    const double most = finder == iga::RootFinder::PolarNewton ? 0.95 : 0.5;
    EXPECT_LT(double(firstSteps), most * double(fullSteps)) << iga::rootFinderName(finder);
  }
}

/// A guess near the nearest root settles it (the same root as the search's, to 1e-12); a guess
/// near a later root, near a double root or off [0, 1] is dropped for the finder's search, which
/// still returns the nearest root.
TEST(BernsteinRoots, AGuessIsTakenWhereItIsProved)
{
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  int seeded = 0, cases = 0;
  for (int degree = 2; degree <= 16; ++degree)
  {
    for (int trial = 0; trial < 6; ++trial)
    {
      const int real = std::uniform_int_distribution<int>(2, std::min(degree, 4))(rng);
      const Case c = randomCase(rng, degree, real, 0);
      for (iga::RootFinder finder : kFinders)
      {
        SCOPED_TRACE(std::string(iga::rootFinderName(finder)) + ", " + c.what);
        bool taken = false;
        const auto nearest = [&](double guess)
        {
          return iga::findNearestRoot(
            c.coefficients.data(), int(c.coefficients.size()) - 1, guess, 0.02, finder, {}, taken);
        };
        iga::BernsteinRoots found = nearest(c.roots[0] + jitter(rng));
        ASSERT_EQ(found.count, 1);
        EXPECT_NEAR(found.t[0], c.roots[0], 1e-12);
        seeded += taken ? 1 : 0;
        ++cases;
        for (double guess : { c.roots[1], -0.5, 1.5 })
        {
          found = nearest(guess);
          EXPECT_FALSE(taken) << "guess " << guess;
          ASSERT_EQ(found.count, 1);
          EXPECT_NEAR(found.t[0], c.roots[0], 1e-9);
        }
      }
    }
  }
  EXPECT_GT(seeded, cases * 9 / 10);
  // (t - 0.4)^2 (t - 0.8) (t - 1.2): the nearest root is the double one at 0.4, which changes no
  // sign: a bracket about it is refused, and the search finds it.
  Poly f = multiply(multiply(linear(0.4L), linear(0.4L)), multiply(linear(0.8L), linear(1.2L)));
  std::vector<double> c;
  for (long double v : f)
    c.push_back(double(v));
  bool taken = true;
  const iga::BernsteinRoots nearDouble =
    iga::findNearestRoot(c.data(), 4, 0.4, 0.05, iga::RootFinder::PointInsertion, {}, taken);
  EXPECT_FALSE(taken);
  ASSERT_EQ(nearDouble.count, 1);
  EXPECT_NEAR(nearDouble.t[0], 0.4, 1e-6);
}

TEST(BernsteinRoots, PolynomialsThatOnlyComeCloseHaveNoRoots)
{
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int degree = 2; degree <= 16; degree += 2)
  {
    // ((t - a)^2 + 1e-6) times positive factors: a minimum of about 1e-6 of the scale.
    Poly f = complexPair(0.1L + 0.8L * unit(rng), 1e-3L);
    while (int(f.size()) - 1 < degree)
      f = multiply(f, complexPair(unit(rng), 0.2 + unit(rng)));
    Case c;
    for (long double v : f)
      c.coefficients.push_back(double(v));
    c.what = "degree " + std::to_string(degree) + " without roots";
    for (iga::RootFinder finder : kFinders)
      expectRoots(c, finder);
  }
}

TEST(BernsteinRoots, BadInputIsNamed)
{
  const double c[18] = { 1, -1 };
  EXPECT_TRUE(iga::findBernsteinRoots(c, 17, iga::RootFinder::PointInsertion).invalid);
  EXPECT_TRUE(iga::findBernsteinRoots(c, -1, iga::RootFinder::PointInsertion).invalid);
  const double nan[2] = { 1, std::nan("") };
  EXPECT_TRUE(iga::findBernsteinRoots(nan, 1, iga::RootFinder::PointInsertion).invalid);
  const double zero[3] = { 0, 0, 0 };
  const auto none = iga::findBernsteinRoots(zero, 2, iga::RootFinder::PointInsertion);
  EXPECT_TRUE(none.identicallyZero);
  EXPECT_EQ(none.count, 0);
}

} // namespace

TEST(BernsteinRoots, FinderNamesParseBackAndUnknownNamesAreListed)
{
  for (int f = 0; f < iga::kRootFinderCount; ++f)
    EXPECT_EQ(int(iga::parseRootFinder(iga::rootFinderName(iga::RootFinder(f)))), f);
  try
  {
    iga::parseRootFinder("newton");
    ADD_FAILURE() << "an unknown finder was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("'newton' is none of subdivision, knot-insertion"),
      std::string::npos)
      << e.what();
  }
}
