// Checks of patch data before it reaches the numeric kernels. The messages are host strings; the
// tests of control point values and of the weights' range also run on the device
// (firstInvalidPoint, weightsTooSkewed).
#pragma once

#include "iga/BezierPatch.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace iga
{

/// Largest coordinate magnitude the engine frames: squares of coordinates and of the camera's
/// distances must stay finite in double precision.
constexpr double kMaxCoordinate = 1e100;

/// Largest ratio of a patch's largest to its smallest weight that is drawn. Its rational functions
/// change over parameter intervals of about the inverse ratio, which midpoint subdivision must
/// reach: against a ratio of 1e4, the zoo's sphere costs 10x at 1e6, 25x at 3e6, 200x at 1e7,
/// and at 3e7 (2400x) a quarter of its pixels are left at the depth cap.
constexpr double kMaxWeightRatio = 1e6;

/// The smallest and largest of a patch's weights.
template<class T, int Dim>
IGA_HD void weightRange(const PatchView<const T, Dim>& patch, T& lo, T& hi)
{
  lo = hi = patch.point(0)[kWeightChannel];
  for (int p = 1; p < patch.pointCount(); ++p)
  {
    const T w = patch.point(p)[kWeightChannel];
    lo = w < lo ? w : lo;
    hi = w > hi ? w : hi;
  }
}

/// Whether a patch's positive weights range over more than kMaxWeightRatio.
template<class T, int Dim>
IGA_HD bool weightsTooSkewed(const PatchView<const T, Dim>& patch)
{
  T lo, hi;
  weightRange(patch, lo, hi);
  return hi > T(kMaxWeightRatio) * lo;
}

/// Whether a control point's Euclidean coordinate (weighted value / weight) is too large.
template<class T>
IGA_HD bool beyondFraming(const T* point, int d)
{
  return absValue(point[d]) > T(kMaxCoordinate) * point[kWeightChannel];
}

/// The first control point with a non-finite value, a non-positive weight or a coordinate
/// beyond kMaxCoordinate, or -1.
template<class T, int Dim>
IGA_HD int firstInvalidPoint(const PatchView<const T, Dim>& patch)
{
  const int count = patch.pointCount();
  for (int p = 0; p < count; ++p)
  {
    const T* point = patch.point(p);
    for (int c = 0; c < patch.channels; ++c)
    {
      if (!isFinite(point[c]))
      {
        return p;
      }
    }
    if (!(point[kWeightChannel] > T(0)) || beyondFraming(point, 0) || beyondFraming(point, 1) ||
        beyondFraming(point, 2))
    {
      return p;
    }
  }
  return -1;
}

/// What firstInvalidPoint found wrong with a control point of `channels` values, after its name
/// ("control point 7"): a non-finite value, a non-positive weight or a coordinate beyond
/// kMaxCoordinate.
template<class T>
std::string invalidPointProblem(const T* point, int channels)
{
  for (int c = 0; c < channels; ++c)
  {
    if (!isFinite(point[c]))
    {
      const std::string channel =
        c < kWeightChannel
          ? std::string("weighted ") + "xyz"[c] + " coordinate (channel " + std::to_string(c) + ")"
        : c == kWeightChannel ? "weight (channel " + std::to_string(c) + ")"
                              : "attribute " + std::to_string(c - kFirstAttributeChannel) +
                                  " (channel " + std::to_string(c) + ")";
      return " has a non-finite " + channel + ": " + std::to_string(double(point[c]));
    }
  }
  if (!(point[kWeightChannel] > T(0)))
  {
    return " has non-positive weight " + std::to_string(point[kWeightChannel]);
  }
  char coordinates[128];
  std::snprintf(coordinates, sizeof coordinates, "(%.3g, %.3g, %.3g)",
    double(point[0] / point[kWeightChannel]), double(point[1] / point[kWeightChannel]),
    double(point[2] / point[kWeightChannel]));
  return std::string(" at ") + coordinates +
         " lies beyond 1e+100, farther than double precision can frame";
}

/// Weights from lo to hi, more than kMaxWeightRatio apart, in words.
inline std::string weightRatioProblem(double lo, double hi)
{
  // The ratio with as many digits as show it above the limit (1.0004e+06, not 1e+06).
  char ratio[32];
  for (int digits = 3; digits <= 17; ++digits)
  {
    std::snprintf(ratio, sizeof ratio, "%.*g", digits, hi / lo);
    if (std::strtod(ratio, nullptr) > kMaxWeightRatio)
    {
      break;
    }
  }
  char text[192];
  std::snprintf(text, sizeof text,
    "weights range over %.3g .. %.3g, a ratio of %s: more than the %.0e that subdivision "
    "resolves",
    lo, hi, ratio, kMaxWeightRatio);
  return text;
}

/// What weightsTooSkewed found: the weights' range and ratio against kMaxWeightRatio.
template<class T, int Dim>
std::string weightRangeProblem(const PatchView<const T, Dim>& patch)
{
  T lo, hi;
  weightRange(patch, lo, hi);
  return weightRatioProblem(double(lo), double(hi));
}

/// Empty when the patch (standard layout) is usable; otherwise one sentence naming the first
/// problem: degree outside 1..kMaxDegree, too few channels, a non-finite value, a non-positive
/// weight or a coordinate beyond kMaxCoordinate (with the control point's index), or weights
/// ranging over more than kMaxWeightRatio.
template<class T, int Dim>
std::string checkPatch(const PatchView<const T, Dim>& patch)
{
  for (int d = 0; d < Dim; ++d)
  {
    if (patch.degree[d] < 1 || patch.degree[d] > kMaxDegree)
    {
      return "degree " + std::to_string(patch.degree[d]) + " in direction " + std::to_string(d) +
             " is outside 1.." + std::to_string(kMaxDegree);
    }
  }
  if (patch.channels < kFirstAttributeChannel)
  {
    return "control points have " + std::to_string(patch.channels) +
           " values, need at least 4 (w*x, w*y, w*z, w)";
  }
  const int p = firstInvalidPoint(patch);
  if (p >= 0)
  {
    return "control point " + std::to_string(p) +
           invalidPointProblem(patch.point(p), patch.channels);
  }
  return weightsTooSkewed(patch) ? weightRangeProblem(patch) : std::string();
}

} // namespace iga
