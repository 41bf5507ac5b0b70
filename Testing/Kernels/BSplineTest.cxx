// Bézier extraction of B-spline / NURBS patches against direct Cox-de Boor evaluation.
#include "NurbsReference.h"
#include "TestPatches.h"

#include "iga/BSpline.h"
#include "iga/NurbsSet.h"
#include "iga/Validation.h"

#include <algorithm>
#include <utility>

using namespace igatest;

namespace
{

template<class T>
class BSplineTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(BSplineTest, ScalarTypes);

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

template<class T, int Dim>
void checkExtraction(std::mt19937& rng, bool open)
{
  std::uniform_int_distribution<int> pickDegree(1, 3), extra(0, 4);
  std::uniform_real_distribution<double> coord(-1, 1), weight(0.2, 5), unit(0, 1);
  iga::BSplinePatch<T, Dim> spline;
  int points = 1;
  for (int d = 0; d < Dim; ++d)
  {
    spline.degree[d] = pickDegree(rng);
    spline.netSize[d] = spline.degree[d] + 1 + extra(rng);
    const auto knots = randomKnots(rng, spline.degree[d], spline.netSize[d], open);
    spline.knots[d].assign(knots.begin(), knots.end());
    points *= spline.netSize[d];
  }
  spline.channels = 5;
  for (int p = 0; p < points; ++p)
  {
    const double w = weight(rng);
    for (int c = 0; c < 5; ++c)
    {
      spline.net.push_back(T(c == 3 ? w : w * coord(rng)));
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
    for (int d = 0; d < Dim; ++d)
    {
      const auto& op = extraction.direction(d);
      local[d] = unit(rng);
      const double a = double(op.spanStart[perDirection[d]]),
                   b = double(op.spanEnd[perDirection[d]]);
      t[d] = a + (b - a) * local[d];
    }
    const std::vector<double> reference = evaluateNurbs(spline, t); // x, y, z, attribute
    const auto bezier = evaluateEuclidean(patches[element].view(), local);
    for (int c = 0; c < 5; ++c)
    {
      if (c == 3)
        continue;
      EXPECT_NEAR(double(bezier[c]), reference[c < 3 ? c : c - 1], Tolerance<T>::relative * 10)
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

// An element is refused for its Bézier weights, not for its support's: quadratic in u with knots
// 0 0 0 1 2 3 3 3 and the middle control point weighing W, element 0's Bézier weights along u
// are 1, 1 and (1 + W) / 2, while its support in the net ranges over 1 .. W.
TEST(BSplineValidation, ElementsAreRefusedForTheirBezierWeightsRatherThanTheirSupports)
{
  auto patchWithMiddleWeight = [](double w)
  {
    iga::BSplinePatch<double, 3> patch;
    const int degree[3] = { 2, 1, 1 }, size[3] = { 5, 2, 2 };
    patch.knots[0] = { 0, 0, 0, 1, 2, 3, 3, 3 };
    patch.knots[1] = patch.knots[2] = { 0, 0, 1, 1 };
    std::copy(degree, degree + 3, patch.degree);
    std::copy(size, size + 3, patch.netSize);
    patch.channels = iga::kFirstAttributeChannel;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 5; ++i)
        {
          const double weight = i == 2 ? w : 1.0;
          for (double x : { double(i), double(j), double(k) })
            patch.net.push_back(weight * x);
          patch.net.push_back(weight);
        }
    return patch;
  };
  auto problem = [](const iga::BSplinePatch<double, 3>& patch)
  {
    const iga::BezierExtraction<double, 3> extraction(patch.knots, patch.degree, patch.netSize);
    return iga::skewedElementProblem(extraction, patch.net, patch.channels);
  };
  // W = 1.5e6: supports range over 1.5e6, Bézier weights over 7.5e5 at most; accepted, and the
  // engine's own check passes every element.
  const auto accepted = patchWithMiddleWeight(1.5e6);
  EXPECT_EQ(problem(accepted), "");
  for (const auto& element : iga::extractBezier(accepted))
    EXPECT_EQ(iga::checkPatch(element.view()), "");
  // W = 3e6: element 0's Bézier weights range over 1 .. 1.5e6.
  const auto refused = patchWithMiddleWeight(3e6);
  EXPECT_EQ(problem(refused), "element (0, 0, 0): its Bézier weights range over 1 .. 1.5e+06, a "
                              "ratio of 1.5e+06: more than the 1e+06 that subdivision resolves");
  const auto elements = iga::extractBezier(refused);
  EXPECT_NE(iga::checkPatch(elements[0].view()), "");
}

} // namespace

// Exact parameter channels: on random rational elements (volumes and surfaces), the elevated
// element's parameter attributes equal start + s (end - start) at random s to 1e-13, where the
// Greville-style blend of the element's own degree is off, and every other channel keeps its
// rational value (elevation changes no function).
template<int Dim>
void checkExactParameters(int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1), weight(0.3, 3);
  int degree[Dim];
  for (int d = 0; d < Dim; ++d)
    degree[d] = 1 + int(unit(rng) * 3);
  const int channels = iga::kFirstAttributeChannel + 4; // x y z w, a, u, v, w
  iga::BezierPatch<double, Dim> element(degree, channels);
  for (size_t p = 0; p < element.coeffs().size() / size_t(channels); ++p)
  {
    double* cp = element.coeffs().data() + p * channels;
    cp[iga::kWeightChannel] = weight(rng);
    for (int c = 0; c < channels; ++c)
      if (c != iga::kWeightChannel)
        cp[c] = cp[iga::kWeightChannel] * (2 * unit(rng) - 1);
  }
  const int parameterChannel[3] = { 5, Dim > 1 ? 6 : -1, Dim > 2 ? 7 : -1 };
  const double start[3] = { 0.25, 2.0, -1.0 }, end[3] = { 0.75, 1.5, 3.0 };
  const auto exact = iga::withExactParameters(element, parameterChannel, start, end);
  double worstBefore = 0;
  for (int s = 0; s < 50; ++s)
  {
    double u[Dim];
    for (int d = 0; d < Dim; ++d)
      u[d] = unit(rng);
    std::vector<double> before(channels), after(channels);
    iga::evaluateHomogeneous(
      std::as_const(element).view(), u, before.data(), static_cast<double*>(nullptr));
    iga::evaluateHomogeneous(
      std::as_const(exact).view(), u, after.data(), static_cast<double*>(nullptr));
    for (int d = 0; d < Dim; ++d)
    {
      const double expected = start[d] + u[d] * (end[d] - start[d]);
      const int c = parameterChannel[d];
      EXPECT_NEAR(after[c] / after[iga::kWeightChannel], expected, 1e-13);
      worstBefore =
        std::max(worstBefore, std::abs(before[c] / before[iga::kWeightChannel] - expected));
    }
    for (int c : { 0, 1, 2, 4 })
      EXPECT_NEAR(
        after[c] / after[iga::kWeightChannel], before[c] / before[iga::kWeightChannel], 1e-13);
  }
  EXPECT_GT(worstBefore, 1e-3); // random coefficients are no parameter
  for (int d = 0; d < Dim; ++d)
    EXPECT_EQ(exact.degree(d), degree[d] + 1);
}

TEST(ExactParameters, RationalElementsCarryTheirParameterExactly)
{
  for (int seed = 0; seed < 10; ++seed)
  {
    checkExactParameters<3>(seed);
    checkExactParameters<2>(100 + seed);
  }
}
