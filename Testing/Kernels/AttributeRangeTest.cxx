// Attribute ranges by subdivision: against analytic extremes (a linear function over a rational
// ring, whose control values pass the field's by far), against dense sampling of random rational
// patches, and the budget's and the constant field's behaviour.
#include "TestPatches.h"

#include "iga/AttributeRange.h"
#include "iga/Datasets.h"

using namespace igatest;

namespace
{

/// The tube's quadrant patches at rest with one more attribute channel, x + 2y (homogeneous, so
/// exactly that function of the position).
iga::VolumeSet<double> tubeWithLinearAttribute(double inner)
{
  auto set = iga::makeTube<double>(inner, 0.0);
  for (auto& patch : set.patches)
  {
    const auto view = patch.view();
    iga::BezierVolume<double> wider(view.degree, view.channels + 1);
    for (int p = 0; p < view.pointCount(); ++p)
    {
      const double* from = view.point(p);
      double* to = wider.view().point(p);
      std::copy(from, from + view.channels, to);
      to[view.channels] = from[0] + 2 * from[1];
    }
    patch = std::move(wider);
  }
  return set;
}

double valueAt(const iga::PatchView<const double, 3>& patch, int channel, const double* u)
{
  std::vector<double> values(size_t(patch.channels));
  iga::evaluateHomogeneous<double, 3>(patch, u, values.data(), nullptr);
  return values[size_t(channel)] / values[iga::kWeightChannel];
}

} // namespace

TEST(AttributeRange, LinearFunctionOverRingHasAnalyticExtremes)
{
  // Over the tube (r in [0.5, 1], every angle) x + 2y takes +-sqrt(5) r; its control values
  // reach +-3 (the quadrants' corner points (1, 1)).
  const auto set = tubeWithLinearAttribute(0.5);
  const int channel = set.patches[0].channels() - 1;
  double controlLo, controlHi;
  iga::rationalRange<double, 3>(
    set.patches[0].view(), channel, iga::kWeightChannel, controlLo, controlHi);
  EXPECT_NEAR(controlHi, 3.0, 1e-12);

  const auto extremes = iga::attributeExtremes<double, 3>(
    long(set.patches.size()), [&](long p) { return set.patches[size_t(p)].view(); }, channel);
  EXPECT_TRUE(extremes.complete);
  EXPECT_NEAR(extremes.max.value, std::sqrt(5.0), 1e-5 * 2 * std::sqrt(5.0));
  EXPECT_NEAR(extremes.min.value, -std::sqrt(5.0), 1e-5 * 2 * std::sqrt(5.0));
  EXPECT_LE(extremes.max.value, std::sqrt(5.0) + 1e-12);
  EXPECT_GE(extremes.min.value, -std::sqrt(5.0) - 1e-12);
  // The witnesses are where the field takes those values: on the outer radius, along (1, 2).
  for (const auto* e : { &extremes.min, &extremes.max })
  {
    const auto patch = set.patches[size_t(e->patch)].view();
    EXPECT_DOUBLE_EQ(valueAt(patch, channel, e->u), e->value);
    const double x = valueAt(patch, 0, e->u), y = valueAt(patch, 1, e->u);
    const double sign = e == &extremes.max ? 1.0 : -1.0;
    EXPECT_NEAR(std::hypot(x, y), 1.0, 1e-4);
    EXPECT_NEAR(x, sign / std::sqrt(5.0), 1e-2);
    EXPECT_NEAR(y, 2 * sign / std::sqrt(5.0), 1e-2);
  }
}

TEST(AttributeRange, NoDenseSampleBeatsTheExtremesOfRandomRationalPatches)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial)
  {
    int degree[3];
    randomDegrees<3>(rng, degree, 4);
    std::vector<iga::BezierVolume<double>> patches;
    for (int k = 0; k < 2; ++k)
    {
      patches.push_back(randomPatch<double, 3>(rng, degree));
    }
    const int channel = iga::kFirstAttributeChannel;
    const auto extremes = iga::attributeExtremes<double, 3>(
      2, [&](long p) { return patches[size_t(p)].view(); }, channel, 1e-7, 100000);
    ASSERT_TRUE(extremes.complete) << "trial " << trial;
    const double spread = extremes.max.value - extremes.min.value;
    const int n = 24;
    for (const auto& patch : patches)
    {
      for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
          for (int i = 0; i <= n; ++i)
          {
            const double u[3] = { double(i) / n, double(j) / n, double(k) / n };
            const double v = valueAt(patch.view(), channel, u);
            ASSERT_GE(v, extremes.min.value - 1e-7 * spread - 1e-12) << "trial " << trial;
            ASSERT_LE(v, extremes.max.value + 1e-7 * spread + 1e-12) << "trial " << trial;
          }
    }
    for (const auto* e : { &extremes.min, &extremes.max })
    {
      EXPECT_DOUBLE_EQ(valueAt(patches[size_t(e->patch)].view(), channel, e->u), e->value);
    }
  }
}

TEST(AttributeRange, ConstantFieldEndsAtOnce)
{
  // A constant attribute on a rational patch: its control ratios differ only by rounding, which
  // must not drive the search to its budget.
  auto set = iga::makeTube<double>(0.5, 0.3);
  for (auto& patch : set.patches)
  {
    const auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
    {
      view.point(p)[iga::kFirstAttributeChannel] = 0.1 * view.point(p)[iga::kWeightChannel];
    }
  }
  const auto extremes = iga::attributeExtremes<double, 3>(
    long(set.patches.size()), [&](long p) { return set.patches[size_t(p)].view(); },
    iga::kFirstAttributeChannel, 1e-5, 8);
  EXPECT_TRUE(extremes.complete);
  EXPECT_NEAR(extremes.min.value, 0.1, 1e-15);
  EXPECT_NEAR(extremes.max.value, 0.1, 1e-15);
}

TEST(AttributeRange, BudgetRunOutIsSaidAndValuesStayTaken)
{
  const auto set = tubeWithLinearAttribute(0.5);
  const int channel = set.patches[0].channels() - 1;
  const auto extremes = iga::attributeExtremes<double, 3>(
    long(set.patches.size()), [&](long p) { return set.patches[size_t(p)].view(); }, channel, 1e-12,
    3);
  EXPECT_FALSE(extremes.complete);
  EXPECT_LE(extremes.max.value, std::sqrt(5.0) + 1e-12);
  EXPECT_GE(extremes.min.value, -std::sqrt(5.0) - 1e-12);
}
