// Random rational patches and precision-dependent tolerances shared by the Kernels tests.
#pragma once

#include "iga/Bounds.h"
#include "iga/Orientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace igatest
{

/// Tolerances per scalar type: the same property must hold at the type's precision.
template<class T>
struct Tolerance;
template<>
struct Tolerance<double>
{
  static constexpr double relative = 1e-9;   // reproduction of a parent by its children etc.
  static constexpr double derivative = 1e-6; // against central differences
  static constexpr double parameter = 1e-6;  // Newton roots (residual 1e-3 x tolerance)
};
template<>
struct Tolerance<float>
{
  static constexpr double relative = 2e-4;
  static constexpr double derivative = 2e-3;
  static constexpr double parameter = 1e-4;
};

using ScalarTypes = ::testing::Types<double, float>;

/// A random rational patch in the standard layout: Euclidean coordinates in [-1,1], weights in
/// [0.2, 5], `attributes` attributes in [-1,1]; stored homogeneous.
template<class T, int Dim>
iga::BezierPatch<T, Dim> randomPatch(std::mt19937& rng, const int* degree, int attributes = 1)
{
  std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(0.2, 5.0);
  iga::BezierPatch<T, Dim> patch(degree, iga::kFirstAttributeChannel + attributes);
  const auto view = patch.view();
  for (int p = 0; p < view.pointCount(); ++p)
  {
    const double w = weight(rng);
    T* cp = view.point(p);
    for (int c = 0; c < view.channels; ++c)
    {
      cp[c] = c == iga::kWeightChannel ? T(w) : T(w * coord(rng));
    }
  }
  return patch;
}

/// Random degrees in [1, maxDegree] per direction.
template<int Dim>
void randomDegrees(std::mt19937& rng, int* degree, int maxDegree = 4)
{
  std::uniform_int_distribution<int> pick(1, maxDegree);
  for (int d = 0; d < Dim; ++d)
  {
    degree[d] = pick(rng);
  }
}

/// The patch as a VTK cell holds it: a left-handed one (negative signed volume) with its first
/// parametric direction reversed.
inline iga::BezierVolume<double> rightHanded(iga::BezierVolume<double> patch)
{
  if (iga::signedVolume<double>(std::as_const(patch).view()) < 0)
  {
    iga::reverseDirection(patch.view(), 0);
  }
  return patch;
}

/// The same patch in double precision, the reference for float tests.
template<class T, int Dim>
iga::BezierPatch<double, Dim> toDouble(const iga::BezierPatch<T, Dim>& patch)
{
  int degree[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    degree[d] = patch.degree(d);
  }
  iga::BezierPatch<double, Dim> result(degree, patch.channels());
  for (size_t i = 0; i < patch.coeffs().size(); ++i)
  {
    result.coeffs()[i] = double(patch.coeffs()[i]);
  }
  return result;
}

/// Direct evaluation of all homogeneous channels by the explicit Bernstein formula
/// C(n,i) t^i (1-t)^(n-i) in long double: independent of the kernels' recurrence.
template<class T, int Dim>
std::vector<long double> evaluateDirect(const iga::PatchView<T, Dim>& patch, const double* u)
{
  std::vector<long double> values(patch.channels, 0.0L);
  int index[Dim] = {};
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    long double weight = 1.0L;
    for (int d = 0; d < Dim; ++d)
    {
      const int n = patch.degree[d], i = index[d];
      weight *= static_cast<long double>(iga::binomial(n, i)) * std::pow((long double)u[d], i) *
                std::pow(1.0L - u[d], n - i);
    }
    for (int c = 0; c < patch.channels; ++c)
    {
      values[c] += weight * patch.point(p)[c];
    }
    for (int d = 0; d < Dim; ++d)
    {
      if (++index[d] < patch.order(d))
        break;
      index[d] = 0;
    }
  }
  return values;
}

/// Euclidean value of every non-weight channel (divided by the weight) at u, in long double.
template<class T, int Dim>
std::vector<long double> evaluateEuclidean(const iga::PatchView<T, Dim>& patch, const double* u)
{
  std::vector<long double> values = evaluateDirect(patch, u);
  const long double w = values[iga::kWeightChannel];
  for (int c = 0; c < patch.channels; ++c)
  {
    if (c != iga::kWeightChannel)
      values[c] /= w;
  }
  return values;
}

inline double maxAbs(const std::vector<long double>& v)
{
  long double m = 0;
  for (long double x : v)
    m = std::max(m, std::fabs(x));
  return double(m);
}

/// The volume pixel problem's rows in the standard layout: (x, y, attribute 0), all over w.
inline const iga::RationalRow kPixelRows[3] = { { 0, 3 }, { 1, 3 }, { 4, 3 } };

/// A patch close to an affine map: control points of a random affine map plus perturbations of
/// relative size `bend`, weights near 1.
template<class T>
iga::BezierVolume<T> nearAffinePatch(std::mt19937& rng, double bend)
{
  std::uniform_real_distribution<double> unit(-1, 1);
  // Rows x, y, z, attribute of a random affine map; the boosts keep (x, y, attribute) a
  // well-conditioned function of (u, v, w).
  double A[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      A[i][j] = unit(rng);
  A[0][0] += 2.5;
  A[1][1] += 2.5;
  A[2][2] += 2.5;
  A[3][2] += 2.5;
  const int degree[3] = { 3, 2, 3 };
  iga::BezierVolume<T> patch(degree, 5);
  const auto view = patch.view();
  int p = 0;
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 3; ++i, ++p)
      {
        const double u[3] = { i / 3.0, j / 2.0, k / 3.0 };
        const double w = 1.0 + 0.5 * bend * unit(rng);
        T* cp = view.point(p);
        // Rows 0..2 of A give x, y, z; row 3 gives the attribute (channel 4).
        for (int row = 0; row < 4; ++row)
        {
          const double value = A[row][0] * u[0] + A[row][1] * u[1] + A[row][2] * u[2] + A[row][3];
          cp[row == 3 ? 4 : row] = T(w * (value + bend * unit(rng)));
        }
        cp[3] = T(w);
      }
  return patch;
}

} // namespace igatest
