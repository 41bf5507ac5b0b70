// Ray composition for patches whose geometry is affine (algebraic surfaces over a box, ABS
// patches): along a ray the attribute is a univariate polynomial of the patch's total degree,
// whose Bernstein coefficients on the ray's segment inside the patch come from its values at
// Chebyshev points (Reimers and Seland; Wei and Feng) through a precomputed inverse collocation
// matrix. Its roots are the ray's hits (BernsteinRoots.h).
#pragma once

#include "iga/BernsteinRoots.h"
#include "iga/BezierPatch.h"
#include "iga/PowerForm.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <vector>

namespace iga
{

/// Channels a patch may have for ray composition.
constexpr int kMaxChannels = 16;

/// A patch's affine geometry x(u) = origin + axes u (axes' columns: the images of the unit
/// directions), its attribute divided by the common weight (one value a control point), and the
/// ray polynomial's degree.
struct AffinePatch
{
  glm::dvec3 origin;
  glm::dmat3 axes, inverse;
  int degree[3] = {};
  std::vector<double> field;
  int rayDegree = 0;
  /// The field's sparse power form (PowerForm.h) where its blossom composes a ray for less than
  /// the field at d + 1 points; empty otherwise.
  std::vector<PowerTerm> terms;
};

/// How far a power form may stand from its field, a fraction of the field's largest Bernstein
/// coefficient: the rounding of the conversions, which drop nothing above it.
constexpr double kPowerFormTolerance = 1e-12;

/// The products of the patch's field at a point: one a coefficient.
inline double fieldProducts(const AffinePatch& patch)
{
  return double(patch.degree[0] + 1) * (patch.degree[1] + 1) * (patch.degree[2] + 1);
}

// The ways to compose a ray are priced in about nanoseconds on the project's machines, fitted to
// each way's measured time on gallery and ABS patches of degree 2 to 16 (docs/benchmarks.md):
// only their ratios decide.

/// A ray's cost when composed directly: the field at d + 1 points, their Bernstein bases, and a
/// fixed part.
inline double directRayCost(const AffinePatch& patch)
{
  const double points = patch.rayDegree + 1;
  double bases = 0;
  for (int d = 0; d < 3; ++d)
  {
    bases += 0.5 * patch.degree[d] * (patch.degree[d] + 1);
  }
  return 0.45 * points * fieldProducts(patch) + 3 * points * bases + 100;
}

namespace detail
{
inline glm::dvec3 euclideanPoint(const VolumeView<const double>& patch, int p)
{
  const double* cp = patch.point(p);
  return glm::dvec3(cp[0], cp[1], cp[2]) / cp[kWeightChannel];
}

} // namespace detail

/// Whether the patch's geometry is affine (equal weights, control points on the affine map of
/// their Greville points), its attribute's degree along rays at most kMaxDegree and its channels
/// at most kMaxChannels; fills `affine` if so.
inline bool affineGeometry(
  const VolumeView<const double>& patch, int attributeChannel, AffinePatch& affine)
{
  if (patch.channels > kMaxChannels || attributeChannel >= patch.channels)
  {
    return false;
  }
  const int n[3] = { patch.degree[0], patch.degree[1], patch.degree[2] };
  const double w = patch.point(0)[kWeightChannel];
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    if (!(std::fabs(patch.point(p)[kWeightChannel] - w) <= 1e-14 * std::fabs(w)))
    {
      return false;
    }
  }
  affine.origin = detail::euclideanPoint(patch, 0);
  const int corner[3] = { n[0], (n[0] + 1) * n[1], (n[0] + 1) * (n[1] + 1) * n[2] };
  double size = 0;
  for (int d = 0; d < 3; ++d)
  {
    affine.axes[d] = detail::euclideanPoint(patch, corner[d]) - affine.origin;
    size = std::max(size, glm::length(affine.axes[d]));
  }
  if (!(std::fabs(glm::determinant(affine.axes)) > 1e-12 * size * size * size))
  {
    return false;
  }
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    int i[3];
    tensorIndices(size_t(p), n, i);
    const glm::dvec3 greville(double(i[0]) / n[0], double(i[1]) / n[1], double(i[2]) / n[2]);
    if (!(glm::length(detail::euclideanPoint(patch, p) -
                      (affine.origin + affine.axes * greville)) <= 1e-12 * size))
    {
      return false;
    }
  }
  affine.inverse = glm::inverse(affine.axes);
  std::copy(n, n + 3, affine.degree);
  affine.field.resize(size_t(patch.pointCount()));
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    affine.field[size_t(p)] = patch.point(p)[attributeChannel] / patch.point(p)[kWeightChannel];
  }
  // The degree along rays is the field's total degree: the largest a + b + c of its power form
  // (in s = 2 u - 1, as in u) above the conversion's rounding.
  std::vector<double> power, bound;
  centredPowerForm(affine.field, n, power, bound);
  affine.rayDegree = 0;
  for (size_t p = 0; p < power.size(); ++p)
  {
    if (significantPower(power[p], bound[p], n))
    {
      int a[3];
      tensorIndices(p, n, a);
      affine.rayDegree = std::max(affine.rayDegree, a[0] + a[1] + a[2]);
    }
  }
  if (affine.rayDegree > kMaxDegree)
  {
    return false;
  }
  // Its blossom where that costs a ray less than direct composition.
  const double direct = directRayCost(affine);
  sparsePowerForm(affine.field, n, power, bound, size_t(direct / kLeastTermCost) + 1,
    kPowerFormTolerance, affine.terms);
  if (!(blossomRayCost(affine.terms, affine.rayDegree) < direct))
  {
    affine.terms.clear();
  }
  return true;
}

/// A ray's cost without a frustum form: its blossom's where the patch has a power form, else
/// direct composition's.
inline double composedRayCost(const AffinePatch& patch)
{
  return patch.terms.empty() ? directRayCost(patch) : blossomRayCost(patch.terms, patch.rayDegree);
}

/// Chebyshev points on [0, 1] and, per degree, the inverse of the Bernstein collocation matrix
/// there: coefficient i = sum_k inverse[i][k] value_k.
struct ChebyshevInterpolation
{
  int degree = 0;
  double point[kMaxOrder] = {};
  double inverse[kMaxOrder][kMaxOrder] = {};
};

inline ChebyshevInterpolation chebyshevInterpolation(int degree)
{
  ChebyshevInterpolation c;
  c.degree = degree;
  const int n = degree + 1;
  double m[kMaxOrder][2 * kMaxOrder] = {};
  for (int k = 0; k < n; ++k)
  {
    c.point[k] = 0.5 * (1 - std::cos((k + 0.5) / n * M_PI));
    double basis[kMaxOrder], unused[kMaxOrder];
    bernsteinBasis(degree, c.point[k], basis, unused);
    for (int i = 0; i < n; ++i)
    {
      m[k][i] = basis[i];
      m[k][n + i] = i == k ? 1 : 0;
    }
  }
  for (int col = 0; col < n; ++col) // Gauss-Jordan with partial pivoting
  {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
    {
      pivot = std::fabs(m[r][col]) > std::fabs(m[pivot][col]) ? r : pivot;
    }
    for (int k = 0; k < 2 * n; ++k)
    {
      std::swap(m[col][k], m[pivot][k]);
    }
    const double scale = m[col][col];
    for (int k = 0; k < 2 * n; ++k)
    {
      m[col][k] /= scale;
    }
    for (int r = 0; r < n; ++r)
    {
      const double factor = r == col ? 0 : m[r][col];
      for (int k = 0; k < 2 * n && factor != 0; ++k)
      {
        m[r][k] -= factor * m[col][k];
      }
    }
  }
  for (int i = 0; i < n; ++i)
  {
    for (int k = 0; k < n; ++k)
    {
      c.inverse[i][k] = m[i][n + k];
    }
  }
  return c;
}

/// The parameters where the ray origin + t direction is inside the unit cube of u = inverse
/// (x - origin): [t0, t1] within [lo, hi], false if empty.
inline bool rayInPatch(const AffinePatch& affine, const glm::dvec3& origin,
  const glm::dvec3& direction, double lo, double hi, double& t0, double& t1)
{
  const glm::dvec3 u0 = affine.inverse * (origin - affine.origin);
  const glm::dvec3 du = affine.inverse * direction;
  t0 = lo;
  t1 = hi;
  for (int d = 0; d < 3; ++d)
  {
    if (du[d] == 0)
    {
      if (u0[d] < 0 || u0[d] > 1)
      {
        return false;
      }
      continue;
    }
    const double a = (0 - u0[d]) / du[d], b = (1 - u0[d]) / du[d];
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  return t0 < t1;
}

/// The patch's field at the n <= kMaxOrder points u0 + s_k du (s_k = points[k], clamped to the
/// unit cube), values only: the coefficients contracted one direction at a time for all points
/// at once, so that each coefficient is read once and the points' sums run side by side.
inline void fieldAlongRay(const AffinePatch& patch, const glm::dvec3& u0, const glm::dvec3& du,
  const double* points, int n, double* values)
{
  const int n0 = patch.degree[0] + 1, n1 = patch.degree[1] + 1, n2 = patch.degree[2] + 1;
  double basis[3][kMaxOrder][kMaxOrder]; // [direction][index][point]
  for (int k = 0; k < n; ++k)
  {
    const glm::dvec3 u = u0 + points[k] * du;
    for (int d = 0; d < 3; ++d)
    {
      double b[kMaxOrder];
      bernsteinBasis(
        patch.degree[d], std::min(std::max(u[d], 0.0), 1.0), b, static_cast<double*>(nullptr));
      for (int i = 0; i <= patch.degree[d]; ++i)
      {
        basis[d][i][k] = b[i];
      }
    }
  }
  const double* c = patch.field.data();
  std::fill(values, values + n, 0.0);
  for (int w = 0; w < n2; ++w)
  {
    double plane[kMaxOrder] = {};
    for (int v = 0; v < n1; ++v, c += n0)
    {
      double line[kMaxOrder] = {};
      for (int i = 0; i < n0; ++i)
      {
        for (int k = 0; k < n; ++k)
        {
          line[k] += basis[0][i][k] * c[i];
        }
      }
      for (int k = 0; k < n; ++k)
      {
        plane[k] += basis[1][v][k] * line[k];
      }
    }
    for (int k = 0; k < n; ++k)
    {
      values[k] += basis[2][w][k] * plane[k];
    }
  }
}

/// The Bernstein coefficients of the polynomial with these values at the interpolation's points.
inline void bernsteinFromValues(
  const ChebyshevInterpolation& interpolation, const double* values, double* coefficients)
{
  const int n = interpolation.degree + 1;
  for (int i = 0; i < n; ++i)
  {
    double sum = 0;
    for (int k = 0; k < n; ++k)
    {
      sum += interpolation.inverse[i][k] * values[k];
    }
    coefficients[i] = sum;
  }
}

/// The Bernstein coefficients (degree interpolation.degree) on s in [0, 1] of the field minus
/// `isovalue` along u(s) = u0 + s du.
inline void composeRay(const AffinePatch& patch, double isovalue, const glm::dvec3& u0,
  const glm::dvec3& du, const ChebyshevInterpolation& interpolation, double* coefficients)
{
  const int n = interpolation.degree + 1;
  double values[kMaxOrder];
  fieldAlongRay(patch, u0, du, interpolation.point, n, values);
  for (int k = 0; k < n; ++k)
  {
    values[k] -= isovalue;
  }
  bernsteinFromValues(interpolation, values, coefficients);
}

} // namespace iga
