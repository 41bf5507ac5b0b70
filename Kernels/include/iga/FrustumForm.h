// Reimers and Seland's frustum form, with Chebyshev interpolation: for one view, an affine
// patch's field along every pixel ray through its screen box as one trivariate Chebyshev series
// in (a, b, w) on [-1, 1]^3, where (a, b) span the box in NDC and w the patch's range of the ray
// parameter t (0 on the near plane, 1 on the far plane). The rays of a perspective or parallel
// view are x = N(a, b) + t (F(a, b) - N(a, b)) with N and F affine in (a, b), so the field is a
// polynomial of degree d (its degree along rays) in each of a, b and w, and of degree d in
// (a, b) together per power of w: per pixel, the d + 1 coefficients of the ray's series in w
// cost (d + 1)(d + 1)(d + 2) / 2 products, against (d + 1) evaluations of the whole patch when
// the ray is composed directly (composeRay).
#pragma once

#include "iga/RayComposition.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace iga
{

/// The pixels a frame draws, to count those in an NDC box: all of a width x height image, or
/// those its far depths leave (Settings::farDepths: below -1 skips a pixel), by a summed-area
/// table.
class DrawnPixels
{
public:
  DrawnPixels(int width, int height)
    : Width(width)
    , Height(height)
  {
  }
  DrawnPixels(int width, int height, const std::vector<double>& farDepths)
    : DrawnPixels(width, height)
  {
    if (farDepths.empty())
      return;
    const size_t w = size_t(width) + 1;
    Table.assign(w * (size_t(height) + 1), 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i)
        Table[(j + 1) * w + i + 1] = Table[(j + 1) * w + i] + Table[j * w + i + 1] -
                                     Table[j * w + i] +
                                     (farDepths[size_t(j) * width + i] >= -1 ? 1 : 0);
  }
  /// Pixels drawn in the box [lo, hi] of NDC x and y (within [-1, 1]).
  double in(const double* lo, const double* hi) const
  {
    if (Table.empty())
      return 0.25 * (hi[0] - lo[0]) * Width * (hi[1] - lo[1]) * Height;
    const auto index = [](double ndc, int size, bool up)
    {
      const double x = 0.5 * (ndc + 1) * size;
      return size_t(std::min(std::max(up ? std::ceil(x) : std::floor(x), 0.0), double(size)));
    };
    const size_t i0 = index(lo[0], Width, false), i1 = index(hi[0], Width, true);
    const size_t j0 = index(lo[1], Height, false), j1 = index(hi[1], Height, true);
    const size_t w = size_t(Width) + 1;
    return double(
      Table[j1 * w + i1] + Table[j0 * w + i0] - Table[j0 * w + i1] - Table[j1 * w + i0]);
  }

private:
  int Width, Height;
  std::vector<uint32_t> Table; ///< empty: every pixel is drawn
};

struct FrustumForm
{
  int degree = -1;             ///< d; -1: no form (the patch's rays are composed directly)
  double a[2] = {}, b[2] = {}; ///< the box's NDC midpoint and half width in x and y
  double t[2] = {};            ///< midpoint and half range of t over the patch
  std::vector<double> series;  ///< G[m][i][j], i + j <= d, m slowest, then i, then j
};

namespace detail
{
/// T_0(x) .. T_d(x).
inline void chebyshevValues(int d, double x, double* values)
{
  values[0] = 1;
  if (d > 0)
  {
    values[1] = x;
  }
  for (int k = 2; k <= d; ++k)
  {
    values[k] = 2 * x * values[k - 1] - values[k - 2];
  }
}

/// Sum_k c_k T_k(x), by Clenshaw's recurrence.
inline double chebyshevSum(const double* c, int d, double x)
{
  double next = 0, after = 0;
  for (int k = d; k >= 1; --k)
  {
    const double current = 2 * x * next - after + c[k];
    after = next;
    next = current;
  }
  return x * next - after + c[0];
}

/// Entries (i, j) with i + j <= d.
inline int triangleSize(int d)
{
  return (d + 1) * (d + 2) / 2;
}

/// The values at the n Chebyshev nodes cos(pi (k + 1/2) / n) to the coefficients of their
/// interpolant (DCT-II): coefficient j = sum_k transform[j][k] value_k.
inline void chebyshevTransform(
  int n, double (&node)[kMaxOrder], double (&transform)[kMaxOrder][kMaxOrder])
{
  for (int k = 0; k < n; ++k)
  {
    node[k] = std::cos(M_PI * (k + 0.5) / n);
  }
  for (int j = 0; j < n; ++j)
  {
    for (int k = 0; k < n; ++k)
    {
      transform[j][k] = (j == 0 ? 1.0 : 2.0) / n * std::cos(M_PI * j * (k + 0.5) / n);
    }
  }
}

/// Applies `matrix` (rows: outputs) along `axis` of the n0 x n1 x n2 array v (first index
/// fastest... slowest: v[(i0 n1 + i1) n2 + i2]), in place.
inline void transformAxis(
  std::vector<double>& v, const int (&n)[3], int axis, const double (&matrix)[kMaxOrder][kMaxOrder])
{
  const size_t stride[3] = { size_t(n[1]) * n[2], size_t(n[2]), 1 };
  const int others[2] = { axis == 0 ? 1 : 0, axis == 2 ? 1 : 2 };
  for (int a = 0; a < n[others[0]]; ++a)
  {
    for (int b = 0; b < n[others[1]]; ++b)
    {
      const size_t start = size_t(a) * stride[others[0]] + size_t(b) * stride[others[1]];
      double in[kMaxOrder];
      for (int k = 0; k < n[axis]; ++k)
      {
        in[k] = v[start + size_t(k) * stride[axis]];
      }
      for (int j = 0; j < n[axis]; ++j)
      {
        double sum = 0;
        for (int k = 0; k < n[axis]; ++k)
        {
          sum += matrix[j][k] * in[k];
        }
        v[start + size_t(j) * stride[axis]] = sum;
      }
    }
  }
}

/// The patch's field as a tensor Chebyshev series in s = 2 u - 1 (index (i0 n1 + i1) n2 + i2,
/// i_d the degree in direction d): its values beyond the unit cube, which a frustum form
/// samples, without the cancellation of the Bernstein sums there.
inline std::vector<double> chebyshevField(const AffinePatch& patch)
{
  const int n[3] = { patch.degree[0] + 1, patch.degree[1] + 1, patch.degree[2] + 1 };
  std::vector<double> v(size_t(n[0]) * n[1] * n[2]);
  for (int i0 = 0; i0 < n[0]; ++i0) // the Bernstein coefficients, reordered
  {
    for (int i1 = 0; i1 < n[1]; ++i1)
    {
      for (int i2 = 0; i2 < n[2]; ++i2)
      {
        v[(size_t(i0) * n[1] + i1) * n[2] + i2] = patch.field[(size_t(i2) * n[1] + i1) * n[0] + i0];
      }
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    // Row k of `toChebyshev`, column i: the Chebyshev coefficient k of B_i.
    double node[kMaxOrder], transform[kMaxOrder][kMaxOrder], toChebyshev[kMaxOrder][kMaxOrder];
    chebyshevTransform(n[axis], node, transform);
    double basis[kMaxOrder][kMaxOrder]; // basis[j][i] = B_i at node j
    for (int j = 0; j < n[axis]; ++j)
    {
      bernsteinBasis(n[axis] - 1, 0.5 * (node[j] + 1), basis[j], static_cast<double*>(nullptr));
    }
    for (int k = 0; k < n[axis]; ++k)
    {
      for (int i = 0; i < n[axis]; ++i)
      {
        double sum = 0;
        for (int j = 0; j < n[axis]; ++j)
        {
          sum += transform[k][j] * basis[j][i];
        }
        toChebyshev[k][i] = sum;
      }
    }
    transformAxis(v, n, axis, toChebyshev);
  }
  return v;
}

/// The Chebyshev field (chebyshevField) at u.
inline double chebyshevFieldAt(const std::vector<double>& c, const int (&n)[3], const glm::dvec3& u)
{
  double t[3][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    chebyshevValues(n[d] - 1, 2 * u[d] - 1, t[d]);
  }
  double sum = 0;
  const double* p = c.data();
  for (int i0 = 0; i0 < n[0]; ++i0)
  {
    double plane = 0;
    for (int i1 = 0; i1 < n[1]; ++i1, p += n[2])
    {
      double line = 0;
      for (int i2 = 0; i2 < n[2]; ++i2)
      {
        line += t[2][i2] * p[i2];
      }
      plane += t[1][i1] * line;
    }
    sum += t[0][i0] * plane;
  }
  return sum;
}

inline glm::dvec3 unproject(const glm::dmat4& clipToWorld, double x, double y, double z)
{
  const glm::dvec4 p = clipToWorld * glm::dvec4(x, y, z, 1);
  return glm::dvec3(p) / p.w;
}
} // namespace detail

/// A pixel's ray through a frustum form of degree d (priced as directRayCost, fitted to its
/// measured 51-560 ns at degrees 2 to 10): its series' (d + 1) triangles of products, its values
/// and their Bernstein coefficients, and a fixed part.
inline double frustumRayCost(int d)
{
  return 0.6 * (double(d + 1) * detail::triangleSize(d) + 2.0 * (d + 1) * (d + 1)) + 25;
}

/// Whether a frustum form costs less than composing `rays` rays without it (composedRayCost):
/// the patch's field at its (d + 1)^3 samples (measured at 0.55-0.8 ns a coefficient), and the
/// rays through it.
inline bool frustumFormPays(const AffinePatch& patch, double rays)
{
  const double samples = std::pow(double(patch.rayDegree + 1), 3);
  return 0.7 * samples * fieldProducts(patch) + rays * frustumRayCost(patch.rayDegree) <
         rays * composedRayCost(patch);
}

/// The patch's frustum form for the view (worldToClip, its inverse clipToWorld) of an image
/// whose `drawn` pixels are drawn; false, and no form, where it does not pay for the drawn
/// pixels of the patch's screen box, at most `maxRays` (frustumFormPays), the view's unprojection
/// is not affine in (a, b) at fixed depth, a corner lies behind the eye, the patch covers no part
/// of the screen and of t in [0, 1], or the field grows in the frustum's box past 1000 times its
/// largest coefficient. `forEach(count, fn)` runs fn(begin, end) over [0, count) (on threads).
template<class ForEach>
bool makeFrustumForm(const AffinePatch& patch, const glm::dmat4& worldToClip,
  const glm::dmat4& clipToWorld, const DrawnPixels& drawn, double maxRays, FrustumForm& form,
  ForEach forEach)
{
  form = FrustumForm();
  const int d = patch.rayDegree, n = d + 1;
  const double wScale = std::fabs(clipToWorld[3][3]) + std::fabs(clipToWorld[2][3]);
  if (d < 0 || std::fabs(clipToWorld[0][3]) > 1e-14 * wScale ||
      std::fabs(clipToWorld[1][3]) > 1e-14 * wScale)
  {
    return false;
  }
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 u(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::dvec3 x = patch.origin + patch.axes * u;
    const glm::dvec4 clip = worldToClip * glm::dvec4(x, 1);
    if (!(clip.w > 0))
    {
      return false;
    }
    const double ndc[2] = { clip.x / clip.w, clip.y / clip.w };
    const glm::dvec3 nearPoint = detail::unproject(clipToWorld, ndc[0], ndc[1], -1);
    const glm::dvec3 ray = detail::unproject(clipToWorld, ndc[0], ndc[1], 1) - nearPoint;
    const double t = glm::dot(x - nearPoint, ray) / glm::dot(ray, ray);
    const double at[3] = { ndc[0], ndc[1], t };
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], at[k]);
      hi[k] = std::max(hi[k], at[k]);
    }
  }
  // Only the screen and t in [0, 1] are drawn.
  lo[0] = std::max(lo[0], -1.0), hi[0] = std::min(hi[0], 1.0);
  lo[1] = std::max(lo[1], -1.0), hi[1] = std::min(hi[1], 1.0);
  lo[2] = std::max(lo[2], 0.0), hi[2] = std::min(hi[2], 1.0);
  if (!(lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2]) ||
      !frustumFormPays(patch, std::min(maxRays, drawn.in(lo, hi))))
  {
    return false;
  }
  form.degree = d;
  double* mid[3] = { form.a, form.b, form.t };
  for (int k = 0; k < 3; ++k)
  {
    mid[k][0] = 0.5 * (lo[k] + hi[k]);
    mid[k][1] = 0.5 * (hi[k] - lo[k]);
  }
  double node[kMaxOrder], transform[kMaxOrder][kMaxOrder];
  detail::chebyshevTransform(n, node, transform);
  const std::vector<double> field = detail::chebyshevField(patch);
  const int orders[3] = { patch.degree[0] + 1, patch.degree[1] + 1, patch.degree[2] + 1 };
  // Samples on the node grid, V[ia][ib][iw], then the transform along each direction in place.
  std::vector<double> v(size_t(n) * n * n);
  forEach(size_t(n) * n,
    [&](size_t begin, size_t end)
    {
      for (size_t ab = begin; ab < end; ++ab)
      {
        const double x = form.a[0] + form.a[1] * node[ab / n];
        const double y = form.b[0] + form.b[1] * node[ab % n];
        const glm::dvec3 nearPoint = detail::unproject(clipToWorld, x, y, -1);
        const glm::dvec3 ray = detail::unproject(clipToWorld, x, y, 1) - nearPoint;
        for (int iw = 0; iw < n; ++iw)
        {
          const glm::dvec3 point = nearPoint + (form.t[0] + form.t[1] * node[iw]) * ray;
          v[ab * n + size_t(iw)] =
            detail::chebyshevFieldAt(field, orders, patch.inverse * (point - patch.origin));
        }
      }
    });
  // Rounding where the field is large in the box reaches every ray's coefficients: a field that
  // grows past 1000 times its largest coefficient there (x^16 beyond the patch) is composed
  // directly instead.
  double largest = 0, sampled = 0;
  for (double c : patch.field)
  {
    largest = std::max(largest, std::fabs(c));
  }
  for (double value : v)
  {
    sampled = std::max(sampled, std::fabs(value));
  }
  if (!(sampled <= 1e3 * largest))
  {
    form = FrustumForm();
    return false;
  }
  const int sizes[3] = { n, n, n };
  const size_t stride[3] = { size_t(n) * n, size_t(n), 1 };
  for (int axis = 0; axis < 3; ++axis)
  {
    detail::transformAxis(v, sizes, axis, transform);
  }
  form.series.reserve(size_t(n) * size_t(detail::triangleSize(d)));
  for (int m = 0; m < n; ++m)
  {
    for (int i = 0; i < n; ++i)
    {
      for (int j = 0; i + j <= d; ++j)
      {
        form.series.push_back(v[size_t(i) * stride[0] + size_t(j) * stride[1] + size_t(m)]);
      }
    }
  }
  return true;
}

/// The Bernstein coefficients (degree form.degree) on s in [0, 1] of the field minus `isovalue`
/// along the ray of the NDC pixel (x, y) for t = t0 + s (t1 - t0), like composeRay's.
inline void composeFrustumRay(const FrustumForm& form, double isovalue, double x, double y,
  double t0, double t1, const ChebyshevInterpolation& interpolation, double* coefficients)
{
  const int d = form.degree, n = d + 1;
  double ta[kMaxOrder], tb[kMaxOrder];
  detail::chebyshevValues(d, (x - form.a[0]) / form.a[1], ta);
  detail::chebyshevValues(d, (y - form.b[0]) / form.b[1], tb);
  double series[kMaxOrder] = {};
  const double* g = form.series.data();
  for (int m = 0; m < n; ++m)
  {
    double sum = 0;
    for (int i = 0; i < n; ++i)
    {
      double row = 0;
      for (int j = 0; i + j <= d; ++j)
      {
        row += g[j] * tb[j];
      }
      g += d - i + 1;
      sum += ta[i] * row;
    }
    series[m] = sum;
  }
  series[0] -= isovalue;
  double values[kMaxOrder];
  for (int k = 0; k < n; ++k)
  {
    const double t = t0 + interpolation.point[k] * (t1 - t0);
    values[k] = detail::chebyshevSum(series, d, (t - form.t[0]) / form.t[1]);
  }
  bernsteinFromValues(interpolation, values, coefficients);
}

} // namespace iga
