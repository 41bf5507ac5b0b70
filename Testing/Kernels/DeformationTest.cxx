// Deformation maps on control points against hand-computed values and closed forms.
#include "iga/Deformation.h"
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace
{

iga::Deformation lattice(int i, int j, int k)
{
  const double lo[3] = { -1, 0, 2 }, hi[3] = { 1, 3, 2.5 };
  const int degree[3] = { i, j, k };
  iga::Deformation deformation;
  deformation.kind = iga::DeformationKind::Lattice;
  deformation.lattice = iga::identityLattice(lo, hi, degree);
  return deformation;
}

} // namespace

TEST(Deformation, IdentityAtTimeZero)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-3, 3);
  iga::Deformation twist, bend, wave;
  twist.amount = 0.9;
  bend.kind = iga::DeformationKind::Bend;
  bend.amount = 0.4;
  wave.kind = iga::DeformationKind::Wave;
  wave.amount = 0.3;
  iga::Deformation ffd = lattice(2, 3, 1);
  ffd.lattice.points[5] += 1.0; // not the identity at time 1
  for (const iga::Deformation* deformation : { &twist, &bend, &wave, &ffd })
  {
    ASSERT_EQ(iga::checkDeformation(*deformation), "");
    for (int s = 0; s < 20; ++s)
    {
      const double x[3] = { coordinate(rng), coordinate(rng), coordinate(rng) };
      double y[3];
      iga::deformPoint(*deformation, 0.0, x, y);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(y[d], x[d], 1e-15 * 3);
      }
    }
  }
}

TEST(Deformation, AnalyticDisplacementOfSpecificPoints)
{
  // Twist about the z line through (1, 2): the point (2, 2, 3) turns by 0.8 * 0.5 * 3 = 1.2 rad.
  iga::Deformation twist;
  twist.origin[0] = 1;
  twist.origin[1] = 2;
  twist.amount = 0.5;
  const double p[3] = { 2, 2, 3 };
  double y[3];
  iga::deformPoint(twist, 0.8, p, y);
  EXPECT_NEAR(y[0], 1 + 0.3623577544766736, 1e-15); // cos 1.2
  EXPECT_NEAR(y[1], 2 + 0.9320390859672263, 1e-15); // sin 1.2
  EXPECT_EQ(y[2], 3);
  // Bend along z over the x axis from x = 1: (3, 1, 1) at time 0.5 moves by 0.5 * 0.3 * 2^2.
  iga::Deformation bend;
  bend.kind = iga::DeformationKind::Bend;
  bend.axis = 0;
  bend.direction = 2;
  bend.origin[0] = 1;
  bend.amount = 0.3;
  const double q[3] = { 3, 1, 1 };
  iga::deformPoint(bend, 0.5, q, y);
  EXPECT_EQ(y[0], 3);
  EXPECT_EQ(y[1], 1);
  EXPECT_NEAR(y[2], 1.6, 1e-15);
  // Wave along x over y, wavelength 2, at time 0.25: a node at y = 0.5, a crest at y = 1.
  iga::Deformation wave;
  wave.kind = iga::DeformationKind::Wave;
  wave.axis = 1;
  wave.direction = 0;
  wave.amount = 0.2;
  wave.wavelength = 2;
  const double node[3] = { 0, 0.5, 0 }, crest[3] = { 0, 1, 0 };
  iga::deformPoint(wave, 0.25, node, y);
  EXPECT_NEAR(y[0], 0, 1e-16);
  iga::deformPoint(wave, 0.25, crest, y);
  EXPECT_NEAR(y[0], 0.25 * 0.2, 1e-16);
  EXPECT_EQ(y[1], 1);
}

TEST(Deformation, IdentityLatticeReproducesInputExactly)
{
  std::mt19937 rng(11);
  // Inside the box and a little outside (far out, the Bernstein sums cancel catastrophically).
  std::uniform_real_distribution<double> s(-0.1, 1.1);
  for (const auto& degree :
    { std::array<int, 3>{ 1, 1, 1 }, std::array<int, 3>{ 2, 3, 4 }, std::array<int, 3>{ 5, 1, 3 } })
  {
    const iga::Deformation ffd = lattice(degree[0], degree[1], degree[2]);
    ASSERT_EQ(iga::checkDeformation(ffd), "");
    for (int sample = 0; sample < 50; ++sample)
    {
      double x[3];
      for (int d = 0; d < 3; ++d)
      {
        x[d] = ffd.lattice.lo[d] + s(rng) * (ffd.lattice.hi[d] - ffd.lattice.lo[d]);
      }
      double y[3];
      iga::deformPoint(ffd, 1.0, x, y);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(y[d], x[d], 4e-15) << "degrees " << degree[0] << degree[1] << degree[2];
      }
    }
  }
}

TEST(Deformation, TrilinearLatticeWithOneMovedCorner)
{
  // Moving the corner (1, 1, 1) of a trilinear lattice by delta adds delta s0 s1 s2.
  iga::Deformation ffd = lattice(1, 1, 1);
  const double delta[3] = { 0.3, -0.2, 0.7 };
  for (int d = 0; d < 3; ++d)
  {
    ffd.lattice.point(1, 1, 1)[d] += delta[d];
  }
  const double x[3] = { 0.5, 1.5, 2.1 }; // s = (0.75, 0.5, 0.2)
  double y[3];
  iga::deformPoint(ffd, 0.6, x, y);
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(y[d], x[d] + 0.6 * delta[d] * 0.75 * 0.5 * 0.2, 1e-15);
  }
}

TEST(Deformation, BoxDeformationsMatchTheirDefinitions)
{
  const double lo[3] = { -1, -2, 0 }, hi[3] = { 1, 2, 4 }; // centre line x = y = 0, length 4
  // Twist by 0.7 rad over the length: the far end at time 0.5 turns by 0.35.
  auto twist = iga::boxDeformation(iga::DeformationKind::Twist, 2, lo, hi, 0.7, 0);
  const double end[3] = { 1, 0, 4 };
  double y[3];
  iga::deformPoint(twist, 0.5, end, y);
  EXPECT_NEAR(y[0], std::cos(0.35), 1e-15);
  EXPECT_NEAR(y[1], std::sin(0.35), 1e-15);
  // Bend: the far end moves by amount * length along x.
  auto bend = iga::boxDeformation(iga::DeformationKind::Bend, 2, lo, hi, 0.25, 0);
  iga::deformPoint(bend, 1.0, end, y);
  EXPECT_NEAR(y[0], 1 + 0.25 * 4, 1e-14);
  // Lattice bulge: x_perp grows by time * amount * 2 s (1 - s).
  auto bulge = iga::boxDeformation(iga::DeformationKind::Lattice, 2, lo, hi, 0.5, 0);
  ASSERT_EQ(iga::checkDeformation(bulge), "");
  const double side[3] = { 0.8, -1.2, 1 }; // s = 0.25
  iga::deformPoint(bulge, 0.6, side, y);
  const double factor = 1 + 0.6 * 0.5 * 2 * 0.25 * 0.75;
  EXPECT_NEAR(y[0], 0.8 * factor, 1e-14);
  EXPECT_NEAR(y[1], -1.2 * factor, 1e-14);
  EXPECT_NEAR(y[2], 1, 1e-14);
}

TEST(Deformation, ControlPointsMoveAndEverythingElseStays)
{
  // A rational patch: the deformed patch interpolates the deformed corner control points.
  auto set = iga::makeTube<double>(0.5, 0.0);
  const auto rest = set;
  auto wave = iga::boxDeformation(iga::DeformationKind::Wave, 2,
    std::array<double, 3>{ -1, -1, 0 }.data(), std::array<double, 3>{ 1, 1, 2 }.data(), 0.1, 0.5);
  iga::deform(set, wave, 0.7);
  for (size_t c = 0; c < set.patches.size(); ++c)
  {
    const auto before = rest.patches[c].view();
    const auto after = set.patches[c].view();
    for (int p = 0; p < after.pointCount(); ++p)
    {
      const double w = before.point(p)[iga::kWeightChannel];
      EXPECT_EQ(after.point(p)[iga::kWeightChannel], w);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(after.point(p)[iga::kFirstAttributeChannel + a],
          before.point(p)[iga::kFirstAttributeChannel + a]);
      }
      const double x[3] = { before.point(p)[0] / w, before.point(p)[1] / w,
        before.point(p)[2] / w };
      // Hand formula: x += 0.7 * 0.2 sin(2 pi (z / 1 - 0.7)).
      const double expected = x[0] + 0.7 * 0.2 * std::sin(6.283185307179586 * (x[2] - 0.7));
      EXPECT_NEAR(after.point(p)[0] / w, expected, 1e-14);
      EXPECT_NEAR(after.point(p)[1] / w, x[1], 1e-14);
    }
  }
}

TEST(Deformation, TwistedTubeKeepsItsClosedForm)
{
  // The default dataset's deformation, written out: twist by 0.6 t z, then x += 0.2 t z^2.
  const auto rest = iga::makeTube<double>(0.5, 0.0);
  const auto moved = iga::makeTube<double>(0.5, 1.0);
  for (size_t c = 0; c < rest.patches.size(); ++c)
  {
    for (int p = 0; p < 27; ++p)
    {
      const double* r = rest.patches[c].view().point(p);
      const double* m = moved.patches[c].view().point(p);
      const double w = r[iga::kWeightChannel];
      const double x = r[0] / w, y = r[1] / w, z = r[2] / w;
      EXPECT_NEAR(m[0] / w, x * std::cos(0.6 * z) - y * std::sin(0.6 * z) + 0.2 * z * z, 1e-14);
      EXPECT_NEAR(m[1] / w, x * std::sin(0.6 * z) + y * std::cos(0.6 * z), 1e-14);
      EXPECT_NEAR(m[2] / w, z, 1e-15);
    }
  }
}

TEST(Deformation, BadInputRejected)
{
  iga::Deformation d;
  d.axis = 3;
  EXPECT_NE(iga::checkDeformation(d).find("axis 3"), std::string::npos);
  d = iga::Deformation();
  d.kind = iga::DeformationKind::Bend;
  d.direction = 2; // the axis
  EXPECT_NE(iga::checkDeformation(d).find("differ from the axis"), std::string::npos);
  d = iga::Deformation();
  d.kind = iga::DeformationKind::Wave;
  d.direction = 0;
  d.wavelength = 0;
  EXPECT_NE(iga::checkDeformation(d).find("wavelength"), std::string::npos);
  d.wavelength = 1;
  d.amount = std::nan("");
  EXPECT_NE(iga::checkDeformation(d).find("not finite"), std::string::npos);
  d = lattice(2, 2, 2);
  d.lattice.points.pop_back();
  EXPECT_NE(iga::checkDeformation(d).find("need 81"), std::string::npos);
  d = lattice(2, 2, 2);
  d.lattice.points[4] = HUGE_VAL;
  EXPECT_NE(iga::checkDeformation(d).find("lattice point 1"), std::string::npos);
  d = lattice(2, 2, 2);
  d.lattice.degree[1] = 0;
  EXPECT_NE(iga::checkDeformation(d).find("degree 0"), std::string::npos);
  // Flat input: no length along the axis, or no extent across it for the lattice.
  const double lo[3] = { 0, 0, 1 }, hi[3] = { 1, 1, 1 };
  EXPECT_NE(
    iga::checkDeformation(iga::boxDeformation(iga::DeformationKind::Twist, 2, lo, hi, 1, 0)), "");
  EXPECT_NE(
    iga::checkDeformation(iga::boxDeformation(iga::DeformationKind::Wave, 2, lo, hi, 1, 0.5)), "");
  EXPECT_NE(
    iga::checkDeformation(iga::boxDeformation(iga::DeformationKind::Lattice, 0, lo, hi, 1, 0)), "");
}
