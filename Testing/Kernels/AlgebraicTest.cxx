// Polynomial expressions (values against the formulas they spell, precedence, errors with their
// positions) and the algebraic gallery, whose equations are checked by their nodes: the Cayley
// cubic's 4, the Kummer surface's 16 and the Dervish's 31, counted by Newton's method on the
// gradient from a grid of starts.
#include "iga/AbsField.h"
#include "iga/AlgebraicGallery.h"
#include "iga/PolynomialExpression.h"
#include "iga/RayComposition.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace
{

double valueOf(const std::string& text, double x, double y, double z)
{
  return iga::parsePolynomial(text).evaluate(x, y, z);
}

TEST(PolynomialExpression, ValuesMatchTheFormulas)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(-2, 2);
  for (int trial = 0; trial < 20; ++trial)
  {
    const double x = coordinate(rng), y = coordinate(rng), z = coordinate(rng);
    const double heart = std::pow(x * x + 2.25 * y * y + z * z - 1, 3) - x * x * z * z * z -
                         9.0 / 80 * y * y * z * z * z;
    EXPECT_NEAR(valueOf("(x^2 + 9/4*y^2 + z^2 - 1)^3 - x^2*z^3 - 9/80*y^2*z^3", x, y, z), heart,
      1e-12 * std::max(1.0, std::fabs(heart)));
    EXPECT_NEAR(valueOf("-x^2 + 2^3*y - -z", x, y, z), -x * x + 8 * y + z, 1e-12);
    EXPECT_NEAR(valueOf(" x*y/4 - (z) ", x, y, z), x * y / 4 - z, 1e-12);
    EXPECT_NEAR(valueOf("x^16 + .5e1", x, y, z), std::pow(x, 16) + 5, 1e-9 * std::pow(2, 16));
  }
  const auto p = iga::parsePolynomial("x^3*y + z^2");
  EXPECT_EQ(p.degree[0], 3);
  EXPECT_EQ(p.degree[1], 1);
  EXPECT_EQ(p.degree[2], 2);
  EXPECT_EQ(iga::detail::totalDegree(p), 4);
}

void expectError(const std::string& text, const std::string& message)
{
  try
  {
    iga::parsePolynomial(text);
    ADD_FAILURE() << "'" << text << "' was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_EQ(std::string(e.what()), message) << "for '" << text << "'";
  }
}

TEST(PolynomialExpression, ErrorsNameTheirPosition)
{
  expectError("x + * y", "expression, position 5: unexpected '*'");
  expectError("x + w^2", "expression, position 5: unknown variable 'w' (x, y and z are known)");
  expectError("2*(x + y", "expression, position 9: '(' at position 3 is not closed");
  expectError("x + y)", "expression, position 6: unbalanced ')'");
  expectError("x y", "expression, position 3: expected an operator");
  expectError("x^2^3", "expression, position 4: expected an operator");
  expectError("x^", "expression, position 3: expected a whole exponent after '^'");
  expectError("x^17", "expression, position 3: degree above 16");
  expectError("x^99999999999", "expression, position 3: degree above 16");
  expectError("(x^9)*(x^8)", "expression, position 6: degree above 16");
  expectError("x^8*y^9", "expression: total degree 17 above 16");
  expectError("x/y", "expression, position 3: division only by a nonzero constant");
  expectError("x/(1 - 1)", "expression, position 3: division only by a nonzero constant");
  expectError("1e400*x", "expression, position 1: bad number");
  expectError("", "expression, position 1: unexpected end of the expression");
  expectError("x + ", "expression, position 5: unexpected end of the expression");
  // Nesting is bounded where it passes the limit (a fuzzer's 2 000 parentheses overflowed the
  // stack): 64 levels are read, the 65th is refused.
  const std::string within = std::string(64, '(') + "x" + std::string(64, ')');
  EXPECT_EQ(iga::parsePolynomial(within).degree[0], 1);
  expectError(std::string(100000, '(') + "x",
    "expression, position 65: parentheses and signs nested deeper than 64");
  expectError("1 + " + std::string(70, '-') + "x",
    "expression, position 69: parentheses and signs nested deeper than 64");
}

TEST(PolynomialExpression, AlgebraicVolumesHoldThePolynomialOverTheirBox)
{
  const auto field = iga::parsePolynomial("x^3*y - 2*z^2 + 0.5");
  const double box[6] = { -1, 2, 0.5, 1.5, -3, -1 };
  const iga::BezierVolume<double> volume = iga::makeAlgebraicVolume(field, box);
  EXPECT_EQ(volume.view().degree[0], 3);
  EXPECT_EQ(volume.view().degree[1], 1);
  EXPECT_EQ(volume.view().degree[2], 2);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 20; ++trial)
  {
    const double u[3] = { unit(rng), unit(rng), unit(rng) };
    double values[iga::kFirstAttributeChannel + 1];
    iga::evaluateHomogeneous<double, 3>(volume.view(), u, values, nullptr);
    double x[3];
    for (int d = 0; d < 3; ++d)
    {
      x[d] = box[2 * d] + u[d] * (box[2 * d + 1] - box[2 * d]);
      EXPECT_NEAR(values[d] / values[iga::kWeightChannel], x[d], 1e-13);
    }
    EXPECT_NEAR(values[iga::kFirstAttributeChannel] / values[iga::kWeightChannel],
      field.evaluate(x[0], x[1], x[2]), 1e-12);
  }
  const auto refused =
    [&](const iga::Polynomial3<double>& p, std::array<double, 6> b, const std::string& message)
  {
    try
    {
      iga::makeAlgebraicVolume(p, b.data());
      ADD_FAILURE() << message << " was accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_EQ(std::string(e.what()), message);
    }
  };
  refused(
    field, { -1, 1, 2, 2, -1, 1 }, "box: y from 2.000000 to 2.000000 is not a finite interval");
  refused(field, { -1, 1, -1, 1, std::nan(""), 1 },
    "box: z from nan to 1.000000 is not a finite interval");
  refused(iga::parsePolynomial("(1e300*x)^2"), { -1, 1, -1, 1, -1, 1 },
    "expression: its Bernstein coefficients over the box overflow");
}

/// Partial derivative in direction d, in power form.
iga::Polynomial3<double> partial(const iga::Polynomial3<double>& p, int d)
{
  int degree[3] = { p.degree[0], p.degree[1], p.degree[2] };
  degree[d] = std::max(0, degree[d] - 1);
  iga::Polynomial3<double> q(degree[0], degree[1], degree[2]);
  for (int c = 0; c <= p.degree[2]; ++c)
    for (int b = 0; b <= p.degree[1]; ++b)
      for (int a = 0; a <= p.degree[0]; ++a)
      {
        const int power[3] = { a, b, c };
        if (power[d] == 0)
          continue;
        int lowered[3] = { a, b, c };
        --lowered[d];
        q.at(lowered[0], lowered[1], lowered[2]) += power[d] * p.at(a, b, c);
      }
  return q;
}

/// Singular points (f = 0 and grad f = 0) inside the box: Newton on grad f = 0 from a grid of
/// starts, kept where it converged and f vanishes relative to the size of its terms there.
int countNodes(const iga::AlgebraicSurface& surface, const int (&starts)[3] = { 16, 16, 16 })
{
  const auto f = iga::parsePolynomial(surface.expression);
  std::array<iga::Polynomial3<double>, 3> g;
  std::array<std::array<iga::Polynomial3<double>, 3>, 3> h;
  for (int d = 0; d < 3; ++d)
  {
    g[size_t(d)] = partial(f, d);
    for (int e = 0; e < 3; ++e)
      h[size_t(d)][size_t(e)] = partial(g[size_t(d)], e);
  }
  std::vector<std::array<double, 3>> nodes;
  for (int i = 0; i < starts[0]; ++i)
    for (int j = 0; j < starts[1]; ++j)
      for (int k = 0; k < starts[2]; ++k)
      {
        const int ijk[3] = { i, j, k };
        double x[3];
        for (int d = 0; d < 3; ++d)
          x[d] = surface.box[2 * d] +
                 (surface.box[2 * d + 1] - surface.box[2 * d]) * (ijk[d] + 0.5) / starts[d];
        bool converged = false;
        for (int iteration = 0; iteration < 60; ++iteration)
        {
          double r[3], m[3][3];
          for (int d = 0; d < 3; ++d)
          {
            r[d] = g[size_t(d)].evaluate(x[0], x[1], x[2]);
            for (int e = 0; e < 3; ++e)
              m[d][e] = h[size_t(d)][size_t(e)].evaluate(x[0], x[1], x[2]);
          }
          const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
          if (!(std::fabs(det) > 0))
            break;
          double step[3]; // Cramer's rule
          for (int d = 0; d < 3; ++d)
          {
            double a[3][3];
            for (int row = 0; row < 3; ++row)
              for (int col = 0; col < 3; ++col)
                a[row][col] = col == d ? r[row] : m[row][col];
            step[d] = (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                        a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                        a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])) /
                      det;
          }
          double size = 0;
          for (int d = 0; d < 3; ++d)
          {
            x[d] -= step[d];
            size = std::max(size, std::fabs(step[d]));
          }
          converged = size <= 1e-12;
          if (converged)
            break;
        }
        bool inside = true;
        for (int d = 0; d < 3; ++d)
          inside = inside && x[d] >= surface.box[2 * d] && x[d] <= surface.box[2 * d + 1];
        // |f| against the sum of its terms' magnitudes at x: zero to rounding at a node.
        double magnitude = 0;
        for (int c = 0; c <= f.degree[2]; ++c)
          for (int b = 0; b <= f.degree[1]; ++b)
            for (int a = 0; a <= f.degree[0]; ++a)
              magnitude += std::fabs(
                f.at(a, b, c) * std::pow(x[0], a) * std::pow(x[1], b) * std::pow(x[2], c));
        if (!converged || !inside ||
            !(std::fabs(f.evaluate(x[0], x[1], x[2])) <= 1e-10 * magnitude))
          continue;
        bool known = false;
        for (const auto& node : nodes)
          known = known || std::hypot(node[0] - x[0], node[1] - x[1], node[2] - x[2]) < 1e-6;
        if (!known)
          nodes.push_back({ x[0], x[1], x[2] });
      }
  return int(nodes.size());
}

TEST(AlgebraicGallery, EquationsParseAtTheirDegrees)
{
  const std::pair<const char*, int> degrees[] = { { "sphere", 2 }, { "cayley", 3 },
    { "clebsch", 3 }, { "kummer", 4 }, { "dervish", 5 }, { "kiss", 5 }, { "heart", 6 },
    { "klein", 6 }, { "linked-tori", 8 }, { "tangle", 4 }, { "barth-decic", 10 },
    { "super-sphere", 16 } };
  int count = 0;
  iga::algebraicGallery(count);
  EXPECT_EQ(count, int(std::size(degrees)));
  for (const auto& [name, degree] : degrees)
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    ASSERT_NE(surface, nullptr) << name;
    EXPECT_EQ(iga::detail::totalDegree(iga::parsePolynomial(surface->expression)), degree) << name;
  }
  EXPECT_EQ(iga::findAlgebraicSurface("torus"), nullptr);
}

TEST(AlgebraicGallery, TheDervishHas31Nodes)
{
  // 26 inside the gallery's box, and a ring of 5 at radius 8.5, z = -3.52.
  iga::AlgebraicSurface wide = *iga::findAlgebraicSurface("dervish");
  const double box[6] = { -9, 9, -9, 9, -4, 4 };
  std::copy(box, box + 6, wide.box);
  EXPECT_EQ(countNodes(wide, { 36, 36, 16 }), 31);
}

TEST(AlgebraicGallery, SurfacesHaveTheirNodes)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  for (int k = 0; k < count; ++k)
  {
    if (gallery[k].nodes >= 0)
    {
      EXPECT_EQ(countNodes(gallery[k]), gallery[k].nodes) << gallery[k].name;
    }
  }
}

} // namespace

namespace
{

TEST(AbsField, ALinearFieldIsReproducedAndOnlyTheCrossedElementsKept)
{
  const auto f = [](double x, double y, double z) { return x + 2 * y - z - 0.3; };
  const double box[6] = { -1, 1, -1, 1, -1, 1 };
  for (int degree = 1; degree <= 3; ++degree)
  {
    const int cells[3] = { 6, 5, 4 };
    const iga::AbsField field = iga::makeAbsField(f, box, degree, cells);
    EXPECT_EQ(field.elements, 120u);
    // An element holds the plane iff its corners' values straddle zero (f is linear).
    size_t crossed = 0;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 6; ++i)
        {
          double lo = INFINITY, hi = -INFINITY;
          for (int c = 0; c < 8; ++c)
          {
            const double v = f(-1 + 2.0 * (i + (c & 1)) / 6, -1 + 2.0 * (j + (c >> 1 & 1)) / 5,
              -1 + 2.0 * (k + (c >> 2 & 1)) / 4);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
          }
          crossed += lo <= 0 && hi >= 0 ? 1 : 0;
        }
    EXPECT_EQ(field.set.patches.size(), crossed) << "degree " << degree;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> unit(0, 1);
    for (const auto& patch : field.set.patches)
    {
      const iga::VolumeView<const double> view = patch.view();
      iga::AffinePatch affine;
      EXPECT_TRUE(iga::affineGeometry(view, iga::kFirstAttributeChannel, affine));
      const double u[3] = { unit(rng), unit(rng), unit(rng) };
      double values[iga::kFirstAttributeChannel + 1];
      iga::evaluateHomogeneous<double, 3>(view, u, values, nullptr);
      EXPECT_NEAR(values[iga::kFirstAttributeChannel], f(values[0], values[1], values[2]), 1e-12);
    }
  }
}

TEST(AbsField, BadSizesAndValuesAreRefused)
{
  const auto f = [](double x, double, double) { return x; };
  const double box[6] = { -1, 1, -1, 1, -1, 1 };
  const int cells[3] = { 4, 4, 4 }, tooMany[3] = { 4, 65, 4 }, none[3] = { 0, 4, 4 };
  EXPECT_THROW(iga::makeAbsField(f, box, 4, cells), std::invalid_argument);
  EXPECT_THROW(iga::makeAbsField(f, box, 3, tooMany), std::invalid_argument);
  EXPECT_THROW(iga::makeAbsField(f, box, 3, none), std::invalid_argument);
  const double flat[6] = { -1, 1, 1, 1, -1, 1 };
  EXPECT_THROW(iga::makeAbsField(f, flat, 3, cells), std::invalid_argument);
  EXPECT_THROW(
    iga::makeAbsField([](double, double, double) { return std::nan(""); }, box, 3, cells),
    std::invalid_argument);
}

} // namespace
