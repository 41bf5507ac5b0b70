// Trivariate polynomials in power form and their exact conversion to tensor Bernstein form over a
// box, for algebraic surfaces and for volumes whose attribute is a polynomial of position (the
// SST paper's sphere x^2 + y^2 + z^2 - 1 as a tri-quadratic volume, elevated to higher degrees).
#pragma once

#include "iga/BezierPatch.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace iga
{

/// p(x, y, z) = sum c[a + (da+1) * (b + (db+1) * c)] x^a y^b z^c.
template<class T>
struct Polynomial3
{
  int degree[3] = {};
  std::vector<T> coeffs;

  Polynomial3() = default;
  Polynomial3(int dx, int dy, int dz)
    : degree{ dx, dy, dz }
    , coeffs(static_cast<size_t>(dx + 1) * (dy + 1) * (dz + 1), T(0))
  {
  }
  T& at(int a, int b, int c) { return coeffs[a + (degree[0] + 1) * (b + (degree[1] + 1) * c)]; }
  T at(int a, int b, int c) const
  {
    return coeffs[a + (degree[0] + 1) * (b + (degree[1] + 1) * c)];
  }
  /// Horner evaluation in double, the reference for tests.
  double evaluate(double x, double y, double z) const
  {
    double result = 0;
    for (int c = degree[2]; c >= 0; --c)
    {
      double inY = 0;
      for (int b = degree[1]; b >= 0; --b)
      {
        double inX = 0;
        for (int a = degree[0]; a >= 0; --a)
        {
          inX = inX * x + double(at(a, b, c));
        }
        inY = inY * y + inX;
      }
      result = result * z + inY;
    }
    return result;
  }
};

/// Bernstein coefficients (degree n) on [lo, hi] of the monomials x^a, a = 0..maxPower:
/// result[a * (n+1) + j]. Coefficient j is the blossom of x^a (as degree n) at j copies of hi and
/// n - j of lo: sum_k C(j, k) C(n - j, a - k) hi^k lo^(a-k) / C(n, a). Products of the ends
/// without the cancellation of expanding (lo + (hi - lo) s)^a: x^16 over [-0.7, 0.7] is
/// hi^j lo^(16-j), to the last bit.
inline std::vector<double> monomialToBernstein(int maxPower, int n, double lo, double hi)
{
  std::vector<double> result(static_cast<size_t>(maxPower + 1) * (n + 1), 0.0);
  for (int a = 0; a <= maxPower; ++a)
  {
    for (int j = 0; j <= n; ++j)
    {
      double sum = 0;
      for (int k = maxValue(0, a - (n - j)); k <= minValue(a, j); ++k)
      {
        double term = binomial(j, k) * binomial(n - j, a - k);
        for (int i = 0; i < k; ++i)
        {
          term *= hi;
        }
        for (int i = 0; i < a - k; ++i)
        {
          term *= lo;
        }
        sum += term;
      }
      result[a * (n + 1) + j] = sum / binomial(n, a);
    }
  }
  return result;
}

/// A rational Bézier volume (all weights 1) whose geometry is the box [lo, hi] (the identity map
/// scaled) and whose single attribute is the polynomial, exactly, at the given degrees (each at
/// least the polynomial's degree in that variable and at least 1).
template<class T>
BezierVolume<T> makePolynomialVolume(
  const Polynomial3<T>& poly, const T* lo, const T* hi, const int* degree)
{
  for (int d = 0; d < 3; ++d)
  {
    if (degree[d] < maxValue(1, poly.degree[d]) || degree[d] > kMaxDegree)
    {
      throw std::invalid_argument("volume degree " + std::to_string(degree[d]) + " in direction " +
                                  std::to_string(d) + " cannot represent polynomial degree " +
                                  std::to_string(poly.degree[d]) + " (allowed up to " +
                                  std::to_string(kMaxDegree) + ")");
    }
    if (!(lo[d] < hi[d]))
    {
      throw std::invalid_argument("box is empty in direction " + std::to_string(d));
    }
  }
  std::vector<double> M[3];
  for (int d = 0; d < 3; ++d)
  {
    M[d] = monomialToBernstein(poly.degree[d], degree[d], double(lo[d]), double(hi[d]));
  }
  BezierVolume<T> volume(degree, kFirstAttributeChannel + 1);
  const VolumeView<T> view = volume.view();
  int point = 0;
  for (int k = 0; k <= degree[2]; ++k)
  {
    for (int j = 0; j <= degree[1]; ++j)
    {
      for (int i = 0; i <= degree[0]; ++i, ++point)
      {
        const int ijk[3] = { i, j, k };
        T* cp = view.point(point);
        for (int d = 0; d < 3; ++d)
        {
          cp[d] = lo[d] + (hi[d] - lo[d]) * T(ijk[d]) / T(degree[d]);
        }
        cp[kWeightChannel] = T(1);
        double value = 0;
        for (int c = 0; c <= poly.degree[2]; ++c)
        {
          for (int b = 0; b <= poly.degree[1]; ++b)
          {
            for (int a = 0; a <= poly.degree[0]; ++a)
            {
              value += double(poly.at(a, b, c)) * M[0][a * (degree[0] + 1) + i] *
                       M[1][b * (degree[1] + 1) + j] * M[2][c * (degree[2] + 1) + k];
            }
          }
        }
        cp[kFirstAttributeChannel] = T(value);
      }
    }
  }
  return volume;
}

} // namespace iga
