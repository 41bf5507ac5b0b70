// Bad patch data is named before it reaches the numeric kernels.
#include "TestPatches.h"

#include "iga/Validation.h"

using namespace igatest;

namespace
{

TEST(PatchValidation, AcceptsGoodPatchesAndNamesEachProblem)
{
  std::mt19937 rng(50);
  const int degree[3] = { 2, 3, 1 };
  auto patch = randomPatch<double, 3>(rng, degree);
  const iga::VolumeView<const double> view = patch.view();
  EXPECT_EQ(iga::checkPatch(view), "");

  auto negative = patch;
  negative.view().point(7)[iga::kWeightChannel] = -0.5;
  EXPECT_NE(
    (iga::checkPatch<double, 3>(negative.view())).find("control point 7 has non-positive weight"),
    std::string::npos);

  auto zero = patch;
  zero.view().point(0)[iga::kWeightChannel] = 0.0;
  EXPECT_NE(
    (iga::checkPatch<double, 3>(zero.view())).find("control point 0 has non-positive weight"),
    std::string::npos);

  auto nan = patch;
  nan.view().point(5)[1] = NAN;
  EXPECT_NE((iga::checkPatch<double, 3>(nan.view()))
              .find("control point 5 has a non-finite weighted y coordinate (channel 1)"),
    std::string::npos);

  auto inf = patch;
  inf.view().point(2)[4] = INFINITY;
  EXPECT_NE((iga::checkPatch<double, 3>(inf.view())).find("non-finite"), std::string::npos);

  iga::VolumeView<const double> absurd = view;
  absurd.degree[1] = 40;
  EXPECT_NE(
    iga::checkPatch(absurd).find("degree 40 in direction 1 is outside 1..16"), std::string::npos);

  iga::VolumeView<const double> narrow = view;
  narrow.channels = 3;
  EXPECT_NE(iga::checkPatch(narrow).find("need at least 4"), std::string::npos);
}

/// Rescales a control point's homogeneous values so that its weight becomes w.
template<int Dim>
void setWeight(const iga::PatchView<double, Dim>& patch, int point, double w)
{
  double* values = patch.point(point);
  const double factor = w / values[iga::kWeightChannel];
  for (int c = 0; c < patch.channels; ++c)
    values[c] *= factor;
}

/// Weights may range over kMaxWeightRatio, not more: beyond it subdivision does not resolve the
/// patch (the engine fuzzer's slowest inputs had one weight of 1e300 among weights near 1).
TEST(PatchValidation, NamesWeightsRangingOverMoreThanSubdivisionResolves)
{
  std::mt19937 rng(51);
  const int degree[3] = { 1, 2, 1 };
  auto volume = randomPatch<double, 3>(rng, degree);
  for (int p = 0; p < volume.view().pointCount(); ++p)
    setWeight(volume.view(), p, 1.0);
  setWeight(volume.view(), 3, 0.99 * iga::kMaxWeightRatio);
  EXPECT_EQ((iga::checkPatch<double, 3>(volume.view())), "");
  setWeight(volume.view(), 3, 1.01 * iga::kMaxWeightRatio);
  EXPECT_EQ((iga::checkPatch<double, 3>(volume.view())),
    "weights range over 1 .. 1.01e+06, a ratio of 1.01e+06: more than the 1e+06 that "
    "subdivision resolves");

  setWeight(volume.view(), 3, 1.0004 * iga::kMaxWeightRatio);
  EXPECT_NE((iga::checkPatch<double, 3>(volume.view())).find("a ratio of 1.0004e+06: more"),
    std::string::npos);

  const int surfaceDegree[2] = { 2, 1 };
  auto surface = randomPatch<double, 2>(rng, surfaceDegree);
  setWeight(surface.view(), 4, 1e300);
  EXPECT_NE((iga::checkPatch<double, 2>(surface.view())).find("a ratio of"), std::string::npos);
}

} // namespace
