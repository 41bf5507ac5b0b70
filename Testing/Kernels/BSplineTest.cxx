// Bézier extraction of B-spline / NURBS patches against direct Cox-de Boor evaluation.
#include "TestPatches.h"

#include "iga/BSpline.h"

#include <algorithm>

using namespace igatest;

namespace
{

template<class T>
class BSplineTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(BSplineTest, ScalarTypes);

/// Cox-de Boor recursion for N_{i,p}(t), with 0/0 = 0 and the last non-empty span closed on the
/// right: the textbook definition, independent of the blossom-based extraction.
double coxDeBoor(const std::vector<double>& U, int i, int p, double t, int lastSpan)
{
  if (p == 0)
  {
    if (i == lastSpan)
      return U[i] <= t && t <= U[i + 1] ? 1.0 : 0.0;
    return U[i] <= t && t < U[i + 1] ? 1.0 : 0.0;
  }
  double value = 0;
  if (U[i + p] > U[i])
    value += (t - U[i]) / (U[i + p] - U[i]) * coxDeBoor(U, i, p - 1, t, lastSpan);
  if (U[i + p + 1] > U[i + 1])
    value +=
      (U[i + p + 1] - t) / (U[i + p + 1] - U[i + 1]) * coxDeBoor(U, i + 1, p - 1, t, lastSpan);
  return value;
}

std::vector<double> randomKnotsMaybeEmpty(
  std::mt19937& rng, int degree, int controlPoints, bool open)
{
  std::uniform_real_distribution<double> step(0.2, 1.0), coin(0, 1);
  const int count = controlPoints + degree + 1;
  std::vector<double> knots;
  double t = 0;
  while (int(knots.size()) < count)
  {
    const bool end = int(knots.size()) < degree + 1 || int(knots.size()) >= count - degree - 1;
    int repeat = 1;
    if (open && end)
      repeat = degree + 1;
    else if (coin(rng) < 0.3)
      repeat = 1 + int(coin(rng) * degree); // up to multiplicity p
    for (int r = 0; r < repeat && int(knots.size()) < count; ++r)
      knots.push_back(t);
    t += step(rng);
  }
  return knots;
}

/// Random knot vector: open (clamped) or unclamped, with some repeated interior knots and a
/// non-empty domain.
std::vector<double> randomKnots(std::mt19937& rng, int degree, int controlPoints, bool open)
{
  for (;;)
  {
    auto knots = randomKnotsMaybeEmpty(rng, degree, controlPoints, open);
    if (knots[degree] < knots[controlPoints])
      return knots;
  }
}

int lastNonEmptySpan(const std::vector<double>& U, int controlPoints)
{
  int span = controlPoints - 1;
  while (U[span] == U[span + 1])
    --span;
  return span;
}

template<class T, int Dim>
void checkExtraction(std::mt19937& rng, bool open)
{
  std::uniform_int_distribution<int> pickDegree(1, 3), extra(0, 4);
  std::uniform_real_distribution<double> coord(-1, 1), weight(0.2, 5), unit(0, 1);
  iga::BSplinePatch<T, Dim> spline;
  std::vector<double> knots[Dim];
  int points = 1;
  for (int d = 0; d < Dim; ++d)
  {
    spline.degree[d] = pickDegree(rng);
    spline.netSize[d] = spline.degree[d] + 1 + extra(rng);
    knots[d] = randomKnots(rng, spline.degree[d], spline.netSize[d], open);
    spline.knots[d].assign(knots[d].begin(), knots[d].end());
    points *= spline.netSize[d];
  }
  spline.channels = 5;
  std::vector<double> euclidean(points * 5);
  for (int p = 0; p < points; ++p)
  {
    const double w = weight(rng);
    for (int c = 0; c < 5; ++c)
    {
      euclidean[p * 5 + c] = c == 3 ? w : coord(rng);
      spline.net.push_back(T(c == 3 ? w : w * euclidean[p * 5 + c]));
    }
  }
  const iga::BezierExtraction<T, Dim> extraction(spline.knots, spline.degree, spline.netSize);
  const auto patches = extraction.apply(spline.net, spline.channels);
  ASSERT_EQ(int(patches.size()), extraction.elementCount());
  for (int sample = 0; sample < 40; ++sample)
  {
    // Pick an element and a parameter in it, then evaluate both ways.
    const int element = std::uniform_int_distribution<int>(0, extraction.elementCount() - 1)(rng);
    int perDirection[Dim];
    extraction.elementIndex(element, perDirection);
    double local[Dim], t[Dim];
    std::vector<double> basis[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      const auto& op = extraction.direction(d);
      local[d] = unit(rng);
      const double a = double(op.spanStart[perDirection[d]]),
                   b = double(op.spanEnd[perDirection[d]]);
      t[d] = a + (b - a) * local[d];
      const int last = lastNonEmptySpan(knots[d], spline.netSize[d]);
      for (int i = 0; i < spline.netSize[d]; ++i)
        basis[d].push_back(coxDeBoor(knots[d], i, spline.degree[d], t[d], last));
    }
    double numerator[5] = {}, denominator = 0;
    for (int p = 0; p < points; ++p)
    {
      double b = 1;
      int rest = p;
      for (int d = 0; d < Dim; ++d)
      {
        b *= basis[d][rest % spline.netSize[d]];
        rest /= spline.netSize[d];
      }
      const double w = euclidean[p * 5 + 3];
      denominator += b * w;
      for (int c = 0; c < 5; ++c)
        numerator[c] += b * w * euclidean[p * 5 + c];
    }
    const auto bezier = evaluateEuclidean(patches[element].view(), local);
    for (int c = 0; c < 5; ++c)
    {
      if (c == 3)
        continue;
      EXPECT_NEAR(double(bezier[c]), numerator[c] / denominator, Tolerance<T>::relative * 10)
        << "channel " << c << " element " << element;
    }
  }
}

TYPED_TEST(BSplineTest, ExtractionMatchesCoxDeBoorEvaluation)
{
  std::mt19937 rng(30);
  for (int trial = 0; trial < 15; ++trial)
  {
    checkExtraction<TypeParam, 3>(rng, true);
    checkExtraction<TypeParam, 3>(rng, false);
    checkExtraction<TypeParam, 2>(rng, true);
    checkExtraction<TypeParam, 2>(rng, false);
  }
}

TYPED_TEST(BSplineTest, ReextractionOfAMovedNetMatchesFreshExtraction)
{
  using T = TypeParam;
  iga::BSplinePatch<T, 3> spline;
  const std::vector<T> knots = { 0, 0, 0, 0.5, 1, 1, 1 };
  for (int d = 0; d < 3; ++d)
  {
    spline.degree[d] = 2;
    spline.netSize[d] = 4;
    spline.knots[d] = knots;
  }
  spline.channels = 4;
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> coord(-1, 1);
  for (int p = 0; p < 64; ++p)
    for (int c = 0; c < 4; ++c)
      spline.net.push_back(c == 3 ? T(1) : T(coord(rng)));
  const iga::BezierExtraction<T, 3> extraction(spline.knots, spline.degree, spline.netSize);
  for (auto& v : spline.net)
    v = v * T(1.5) + T(0.25); // a "time step": every coordinate and weight moves
  const auto reused = extraction.apply(spline.net, spline.channels);
  const auto fresh = iga::extractBezier(spline);
  ASSERT_EQ(reused.size(), 8u);
  for (size_t e = 0; e < reused.size(); ++e)
    EXPECT_EQ(reused[e].coeffs(), fresh[e].coeffs());
}

TEST(BSplineValidation, RejectsMalformedKnotVectorsWithClearMessages)
{
  auto message = [](const std::vector<double>& knots, int degree, int points)
  {
    try
    {
      iga::validateKnotVector(knots, degree, points);
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({ 0, 0, 0, 1, 1, 1 }, 2, 3), "");
  EXPECT_NE(message({ 0, 0, 0, 1, 1 }, 2, 3).find("expected 6"), std::string::npos);
  EXPECT_NE(message({ 0, 0, 0.6, 0.5, 1, 1 }, 2, 3).find("not non-decreasing at index 3"),
    std::string::npos);
  EXPECT_NE(message({ 0, 0, NAN, 1, 1, 1 }, 2, 3).find("knot 2 is not finite"), std::string::npos);
  EXPECT_NE(message({ 0, 0, 0, 0, 1, 1, 1 }, 2, 4).find("multiplicity"), std::string::npos);
  EXPECT_NE(message({ 0, 0, 1, 1 }, 17, 2).find("outside 1..16"), std::string::npos);
  EXPECT_NE(message({ 0, 1, 1, 2 }, 1, 2).find("empty"), std::string::npos);
  std::vector<double> knots[3] = { { 0, 0, 1, 1 }, { 0, 0, 1, 1 }, { 0, 1, 0, 1 } };
  const int degree[3] = { 1, 1, 1 }, size[3] = { 2, 2, 2 };
  try
  {
    iga::BezierExtraction<double, 3> extraction(knots, degree, size);
    ADD_FAILURE() << "non-monotone knots in direction 2 were accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("direction 2"), std::string::npos) << e.what();
  }
}

} // namespace
