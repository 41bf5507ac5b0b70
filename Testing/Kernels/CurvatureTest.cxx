// Isosurface curvature at the engine's hits against analytic surfaces: an algebraic sphere
// (affine geometry: the field's second derivatives only) and the tube's radius = 0.75 cylinder
// on its rational patches at rest (exact circles: the geometry's second derivatives enter).
// Beneath them, the jets of a patch's channels against evaluation and central differences.
#include "TestPatches.h"

#include "iga/Curvature.h"
#include "iga/Datasets.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Engine.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{

/// The first hits of the isovalue's surface of attribute `attribute`, seen from `camera`.
iga::sst::GBuffer hitsOf(const std::vector<iga::BezierVolume<double>>& patches, int attribute,
  double isovalue, const iga::Camera& camera)
{
  iga::sst::Settings settings;
  settings.width = settings.height = 48;
  settings.isovalues = { isovalue };
  settings.surfaceAttribute = attribute;
  settings.threads = 2;
  settings.isoTolerance = 1e-12;
  iga::sst::GBuffer out;
  iga::sst::render(iga::sst::Scene(patches), camera, settings, iga::sst::Method::Automatic, out);
  return out;
}

/// channelJets on a random rational patch: values and gradients equal to evaluateHomogeneous's,
/// Hessians equal to central differences of its gradients.
template<int Dim>
void expectJetsOfRandomPatch(const int* degree)
{
  std::mt19937 rng(31 + Dim);
  const auto patch = igatest::randomPatch<double, Dim>(rng, degree);
  const int channels[5] = { 0, 1, 2, iga::kWeightChannel, iga::kFirstAttributeChannel };
  const double u[3] = { 0.3, 0.65, 0.45 };
  iga::Jet<double> jets[5];
  iga::channelJets<double, Dim>(patch.view(), u, channels, 5, jets);
  const int C = patch.channels();
  auto evaluate = [&](const double* at, double* values, double* derivatives)
  { iga::evaluateHomogeneous<double, Dim>(patch.view(), at, values, derivatives); };
  std::vector<double> values(C), derivatives(Dim * C), plus(Dim * C), minus(Dim * C), scratch(C);
  evaluate(u, values.data(), derivatives.data());
  const double h = 1e-5;
  for (int k = 0; k < 5; ++k)
  {
    const int c = channels[k];
    EXPECT_NEAR(jets[k].value, values[size_t(c)], 1e-13 * std::abs(values[size_t(c)]) + 1e-14);
    for (int s = 0; s < Dim; ++s)
    {
      EXPECT_NEAR(jets[k].gradient[s], derivatives[size_t(s * C + c)], 1e-12);
      double above[3] = { u[0], u[1], u[2] }, below[3] = { u[0], u[1], u[2] };
      above[s] += h;
      below[s] -= h;
      evaluate(above, scratch.data(), plus.data());
      evaluate(below, scratch.data(), minus.data());
      for (int r = 0; r < Dim; ++r)
      {
        const double difference = (plus[size_t(r * C + c)] - minus[size_t(r * C + c)]) / (2 * h);
        EXPECT_NEAR(jets[k].hessian[r][s], difference, 1e-6 * (1 + std::abs(difference)))
          << "channel " << c << " derivative " << r << s;
      }
    }
    for (int r = Dim; r < 3; ++r)
    {
      EXPECT_EQ(jets[k].gradient[r], 0.0) << "a surface has no third direction";
    }
  }
}

TEST(Curvature, JetsMatchEvaluationAndCentralDifferences)
{
  const int cubic[3] = { 3, 2, 3 };
  expectJetsOfRandomPatch<2>(cubic);
  expectJetsOfRandomPatch<3>(cubic);
}

TEST(Curvature, SphereOfRadiusTwoHasMeanOneHalfAndGaussOneQuarter)
{
  const double box[6] = { -2.5, 2.5, -2.5, 2.5, -2.5, 2.5 };
  const std::vector<iga::BezierVolume<double>> patches = { iga::makeAlgebraicVolume(
    iga::parsePolynomial("x^2 + y^2 + z^2 - 4"), box) };
  double bounds[6];
  iga::sst::patchBounds(iga::sst::Scene(patches), bounds);
  const auto gbuffer =
    hitsOf(patches, 0, 0.0, iga::frameBounds(bounds, { -0.5, 0.7, -0.4 }, { 0, 0, 1 }, 30));
  ASSERT_GT(gbuffer.hits.size(), 300u);
  for (const auto& hit : gbuffer.hits)
  {
    const auto c = iga::isosurfaceCurvature(
      patches[size_t(hit.patch)].view(), iga::kFirstAttributeChannel, &hit.uvw[0]);
    EXPECT_NEAR(c.mean, 0.5, 1e-9);
    EXPECT_NEAR(c.gauss, 0.25, 1e-9);
  }
}

TEST(Curvature, TheTubesRadiusLevelIsACylinderOnRationalPatches)
{
  // "radius" (attribute 1) is exactly the distance from the axis at time 0: radius 0.75 is a
  // cylinder, mean 1 / 1.5, Gaussian 0; the patches' geometry is rational and curved.
  const auto tube = iga::makeTwistedTube<double>(0.0);
  iga::Camera camera;
  camera.position = { 3.0, -2.5, 2.2 };
  camera.focalPoint = { 0, 0, 1 };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngle = 35;
  camera.clippingRange[0] = 0.1;
  camera.clippingRange[1] = 20;
  const auto gbuffer = hitsOf(tube.patches, 1, 0.75, camera);
  ASSERT_GT(gbuffer.hits.size(), 300u);
  for (const auto& hit : gbuffer.hits)
  {
    const auto c = iga::isosurfaceCurvature(
      tube.patches[size_t(hit.patch)].view(), iga::kFirstAttributeChannel + 1, &hit.uvw[0]);
    EXPECT_NEAR(c.mean, 1 / 1.5, 1e-9);
    EXPECT_NEAR(c.gauss, 0.0, 1e-9);
  }
}

TEST(Curvature, AVanishingGradientHasNone)
{
  const double box[6] = { -1, 1, -1, 1, -1, 1 };
  const auto volume = iga::makeAlgebraicVolume(iga::parsePolynomial("x^2 + y^2 + z^2"), box);
  const double centre[3] = { 0.5, 0.5, 0.5 };
  const auto c = iga::isosurfaceCurvature(volume.view(), iga::kFirstAttributeChannel, centre);
  EXPECT_TRUE(std::isnan(c.mean));
  EXPECT_TRUE(std::isnan(c.gauss));
}

} // namespace
