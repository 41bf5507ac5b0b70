// The SST paper's datasets (dice, cheese, teapot shell, wind blade) against hand-written
// geometry: the implicit fields vanish on analytic points and nowhere else, the teapot shell's
// isosurface is the teapot, the blade's patch counts and continuity.
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace
{

/// Attribute `a` of the box-shaped patch containing x (the patches' geometry is the identity
/// map of their control point box); NaN when no patch contains x.
double attributeAt(const iga::VolumeSet<double>& set, const double* x, int a)
{
  for (const auto& patch : set.patches)
  {
    const auto view = patch.view();
    const double* first = view.point(0);
    const double* last = view.point(view.pointCount() - 1);
    double u[3];
    bool inside = true;
    for (int d = 0; d < 3; ++d)
    {
      u[d] = (x[d] - first[d]) / (last[d] - first[d]);
      inside = inside && u[d] >= 0 && u[d] <= 1;
    }
    if (inside)
    {
      std::vector<double> values(view.channels);
      iga::evaluateHomogeneous<double, 3>(view, u, values.data(), nullptr);
      return values[iga::kFirstAttributeChannel + a] / values[iga::kWeightChannel];
    }
  }
  return std::nan("");
}

/// Checks that field `a` is zero on the spheres, -r^2 at their centres, and negative only
/// inside them (random samples of the box).
void expectSpheresExactly(const iga::VolumeSet<double>& set, int a,
  const std::vector<iga::Sphere>& spheres, const double* lo, const double* hi)
{
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (const auto& s : spheres)
  {
    EXPECT_NEAR(attributeAt(set, s.centre, a), -s.radius * s.radius, 1e-13);
    for (int k = 0; k < 10; ++k)
    {
      double dir[3] = { normal(rng), normal(rng), normal(rng) };
      const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      const double x[3] = { s.centre[0] + s.radius * dir[0] / n,
        s.centre[1] + s.radius * dir[1] / n, s.centre[2] + s.radius * dir[2] / n };
      EXPECT_NEAR(attributeAt(set, x, a), 0.0, 1e-13);
    }
  }
  std::uniform_real_distribution<double> unit(0, 1);
  int inside = 0;
  for (int k = 0; k < 20000; ++k)
  {
    const double x[3] = { lo[0] + (hi[0] - lo[0]) * unit(rng), lo[1] + (hi[1] - lo[1]) * unit(rng),
      lo[2] + (hi[2] - lo[2]) * unit(rng) };
    double nearest = HUGE_VAL;
    for (const auto& s : spheres)
    {
      nearest = std::min(
        nearest, std::hypot(x[0] - s.centre[0], x[1] - s.centre[1], x[2] - s.centre[2]) - s.radius);
    }
    const double f = attributeAt(set, x, a);
    ASSERT_FALSE(std::isnan(f));
    EXPECT_EQ(f < 0, nearest < 0) << x[0] << " " << x[1] << " " << x[2];
    inside += nearest < 0;
  }
  EXPECT_GT(inside, 0);
}

} // namespace

TEST(Datasets, DiceCubeAndPipsAreExact)
{
  const auto dice = iga::makeDice<double>();
  ASSERT_EQ(dice.patches.size(), 125u);
  ASSERT_EQ(dice.attributeNames, (std::vector<std::string>{ "cube", "pips" }));
  // On the rounded cube x^4 + y^4 + z^4 = 1.
  const auto height = [](double u, double v)
  { return std::pow(1 - u * u * u * u - v * v * v * v, 0.25); };
  for (double u : { -0.9, -0.3, 0.0, 0.45, 0.8 })
  {
    for (double v : { -0.7, 0.1, 0.6 })
    {
      const double x[3] = { u, v, -height(u, v) }, y[3] = { height(u, v), u, v };
      EXPECT_NEAR(attributeAt(dice, x, 0), 0.0, 1e-13);
      EXPECT_NEAR(attributeAt(dice, y, 0), 0.0, 1e-13);
    }
  }
  // A die by hand: 1 on +z, 6 on -z, 2 on +x, 5 on -x, 3 on +y, 4 on -y.
  const double c = height(0.5, 0.5), e = height(0.5, 0);
  const double r = 0.16;
  const std::vector<iga::Sphere> pips = { { { 0, 0, 1 }, r }, { { -0.5, -0.5, -c }, r },
    { { -0.5, 0, -e }, r }, { { -0.5, 0.5, -c }, r }, { { 0.5, -0.5, -c }, r },
    { { 0.5, 0, -e }, r }, { { 0.5, 0.5, -c }, r }, { { c, -0.5, -0.5 }, r },
    { { c, 0.5, 0.5 }, r }, { { -c, -0.5, -0.5 }, r }, { { -c, -0.5, 0.5 }, r },
    { { -1, 0, 0 }, r }, { { -c, 0.5, -0.5 }, r }, { { -c, 0.5, 0.5 }, r },
    { { -0.5, c, -0.5 }, r }, { { 0, 1, 0 }, r }, { { 0.5, c, 0.5 }, r }, { { -0.5, -c, -0.5 }, r },
    { { 0.5, -c, -0.5 }, r }, { { -0.5, -c, 0.5 }, r }, { { 0.5, -c, 0.5 }, r } };
  ASSERT_EQ(pips.size(), 21u);
  const double lo[3] = { -1.25, -1.25, -1.25 }, hi[3] = { 1.25, 1.25, 1.25 };
  expectSpheresExactly(dice, 1, pips, lo, hi);
}

TEST(Datasets, CheeseBlockAndHolesAreExact)
{
  const auto cheese = iga::makeCheese<double>();
  ASSERT_EQ(cheese.patches.size(), 16u);
  ASSERT_EQ(cheese.attributeNames, (std::vector<std::string>{ "cheese", "holes" }));
  // The rounded block touches its box [0, 2] x [0, 1.2] x [0, 1] at the face centres.
  for (const auto& x : { std::array<double, 3>{ 2, 0.6, 0.5 }, std::array<double, 3>{ 0, 0.6, 0.5 },
         std::array<double, 3>{ 1, 1.2, 0.5 }, std::array<double, 3>{ 1, 0.6, 0 } })
  {
    EXPECT_NEAR(attributeAt(cheese, x.data(), 0), 0.0, 1e-13);
  }
  // ((1.5 - 1) / 1)^4 + ((0.9 - 0.6) / 0.6)^4 + ((0.75 - 0.5) / 0.5)^4 - 1 = 3 / 16 - 1
  const double inside[3] = { 1.5, 0.9, 0.75 };
  EXPECT_NEAR(attributeAt(cheese, inside, 0), -0.8125, 1e-13);
  const std::vector<iga::Sphere> holes = { { { 0.2, 0.25, 0.95 }, 0.14 },
    { { 0.25, 0.9, 0.3 }, 0.18 }, { { 0.75, 0.3, 0.25 }, 0.22 }, { { 0.78, 1.05, 0.8 }, 0.2 },
    { { 1.25, 0.08, 0.7 }, 0.17 }, { { 1.22, 0.95, 0.2 }, 0.15 }, { { 1.9, 0.3, 0.3 }, 0.18 },
    { { 1.75, 0.9, 0.85 }, 0.22 } };
  const double lo[3] = { -0.1, -0.1, -0.1 }, hi[3] = { 2.1, 1.3, 1.1 };
  expectSpheresExactly(cheese, 1, holes, lo, hi);
}

TEST(Datasets, SpheresMustHaveTheirOwnPatch)
{
  const std::vector<double> breaks[3] = { { 0, 1, 2 }, { 0, 1 }, { 0, 1 } };
  const double centre[3] = { 1, 0.5, 0.5 }, half[3] = { 1, 0.5, 0.5 };
  const auto box = iga::roundedBoxField<double>(centre, half);
  const std::string names[2] = { "a", "b" };
  EXPECT_THROW(iga::makeSpheresInBox(breaks, box, { { { 1, 0.5, 0.5 }, 0.1 } }, names),
    std::invalid_argument); // straddles the cut at x = 1
  EXPECT_THROW(iga::makeSpheresInBox(
                 breaks, box, { { { 0.3, 0.5, 0.5 }, 0.1 }, { { 0.7, 0.5, 0.5 }, 0.1 } }, names),
    std::invalid_argument); // two in one patch
  EXPECT_EQ(
    iga::makeSpheresInBox(breaks, box, { { { 0.3, 0.5, 0.5 }, 0.1 } }, names).patches.size(), 2u);
}

TEST(Datasets, TeapotShellIsosurfaceIsTheTeapot)
{
  const double thickness = 0.03;
  const auto shell = iga::makeTeapotShell<double>(thickness);
  ASSERT_EQ(shell.patches.size(), 32u);
  ASSERT_EQ(shell.attributeNames, (std::vector<std::string>{ "shell", "height" }));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto bernstein = [](int i, double t)
  {
    const double binomial[4] = { 1, 3, 3, 1 };
    return binomial[i] * std::pow(t, i) * std::pow(1 - t, 3 - i);
  };
  for (int s = 0; s < 32; ++s)
  {
    EXPECT_EQ(shell.patches[s].degree(0), 3);
    EXPECT_EQ(shell.patches[s].degree(2), 1);
    for (int k = 0; k < 10; ++k)
    {
      const double u[3] = { unit(rng), unit(rng), 0.5 };
      double surface[3] = { 0, 0, 0 }; // the bicubic Bézier patch, summed directly
      for (int j = 0; j < 4; ++j)
      {
        for (int i = 0; i < 4; ++i)
        {
          for (int d = 0; d < 3; ++d)
          {
            surface[d] +=
              bernstein(i, u[0]) * bernstein(j, u[1]) * iga::kTeapotControlPoints[s][i + 4 * j][d];
          }
        }
      }
      double values[6];
      iga::evaluateHomogeneous<double, 3>(shell.patches[s].view(), u, values, nullptr);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(values[d] / values[3], surface[d], 1e-13) << "patch " << s;
      }
      EXPECT_NEAR(values[4] / values[3], 0.0, 1e-16);
      EXPECT_NEAR(values[5] / values[3], surface[2], 1e-13);
      // Off the mid surface the field is the offset: +-thickness/2 on the faces.
      const double outer[3] = { u[0], u[1], 1.0 };
      iga::evaluateHomogeneous<double, 3>(shell.patches[s].view(), outer, values, nullptr);
      EXPECT_NEAR(values[4] / values[3], thickness / 2, 1e-16);
    }
  }
}

TEST(Datasets, TeapotControlPointsMatchGismoFile)
{
  std::ifstream file(IGAVIEW_SHARED_DATA_DIR "/gismo/teapot.xml");
  if (!file)
  {
    GTEST_SKIP() << "shared data not found: " IGAVIEW_SHARED_DATA_DIR "/gismo/teapot.xml";
  }
  std::stringstream text;
  text << file.rdbuf();
  const std::string xml = text.str();
  size_t at = 0;
  int patch = 0;
  for (; (at = xml.find("<coefs geoDim=\"3\">", at)) != std::string::npos; ++patch)
  {
    at += 18;
    std::istringstream coefs(xml.substr(at, xml.find("</coefs>", at) - at));
    ASSERT_LT(patch, 32);
    for (int p = 0; p < 16; ++p)
    {
      for (int d = 0; d < 3; ++d)
      {
        double value;
        ASSERT_TRUE(coefs >> value);
        EXPECT_EQ(value, iga::kTeapotControlPoints[patch][p][d]) << patch << " " << p;
      }
    }
  }
  EXPECT_EQ(patch, 32);
}

TEST(Datasets, BladeLayoutsAndContinuity)
{
  const auto big = iga::bladeLayout(800000);
  EXPECT_EQ(big.around, 320);
  EXPECT_EQ(big.patchCount(), 800000);
  const auto bench = iga::bladeLayout(10000);
  EXPECT_GE(bench.patchCount(), 10000);
  EXPECT_LT(bench.patchCount(), 10100);
  const auto layout = iga::bladeLayout(500);
  const auto blade = iga::makeBlade<double>(layout, 0.0);
  ASSERT_EQ(long(blade.patches.size()), layout.patchCount());
  ASSERT_EQ(blade.attributeNames, (std::vector<std::string>{ "strain", "span" }));
  // Neighbours around the section (including the wrap-around) share their boundary points
  // bit for bit; so do neighbours along the span.
  for (long a = 0; a < layout.around; ++a)
  {
    const auto left = blade.patches[a].view();
    const auto right = blade.patches[(a + 1) % layout.around].view();
    const auto above = blade.patches[a + layout.around * layout.through].view();
    for (int k = 0; k <= 2; ++k)
    {
      for (int j = 0; j <= 1; ++j)
      {
        for (int c = 0; c < 6; ++c)
        {
          const int i = 3 * (j + 2 * k);
          EXPECT_EQ(left.point(i + 2)[c], right.point(i)[c]);
        }
      }
    }
    for (int p = 0; p < 6; ++p)
    {
      for (int c = 0; c < 6; ++c)
      {
        EXPECT_EQ(blade.patches[a].view().point(12 + p)[c], above.point(p)[c]);
      }
    }
  }
  // A range is the same patches; the flap moves the tip by 1.5 along y at time 1, the root not.
  const long first = 3 * layout.around * layout.through; // a layer along the span
  const auto part = iga::makeBlade<double>(layout, 0.0, first, 5);
  ASSERT_EQ(part.patches.size(), 5u);
  EXPECT_EQ(part.patches[2].coeffs(), blade.patches[first + 2].coeffs());
  const auto flapped = iga::makeBlade<double>(layout, 1.0);
  const auto& tipRest = blade.patches.back().view();
  const auto& tipMoved = flapped.patches.back().view();
  EXPECT_NEAR(tipMoved.point(17)[1] - tipRest.point(17)[1], 1.5, 1e-12);
  EXPECT_EQ(tipMoved.point(17)[0], tipRest.point(17)[0]);
  EXPECT_EQ(flapped.patches[0].view().point(0)[1], blade.patches[0].view().point(0)[1]);
}
