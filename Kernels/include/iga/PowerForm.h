// A patch field's sparse power form and its blossom along rays. In the centred parameter
// s = 2 u - 1 in [-1, 1]^3 every monomial is at most 1 in size, and a polynomial written with few
// terms (x^16 + y^16 + z^16 - 0.0001) keeps few: a ray's Bernstein coefficients are then the
// polynomial's blossom at the segment's two ends (Seland and Dokken), here from products of
// the linear forms s(sigma) = s0 (1 - sigma) + s1 sigma, a few products a term, where direct
// composition evaluates every coefficient of the patch at d + 1 points. The form is kept only
// where the Bernstein coefficients of its difference to the field prove it within rounding.
#pragma once

#include "iga/Portability.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace iga
{

/// coefficient * s0^power[0] * s1^power[1] * s2^power[2].
struct PowerTerm
{
  double coefficient;
  int8_t power[3];

  IGA_HD int degree() const { return power[0] + power[1] + power[2]; }
};

/// The indices (i, j, k) of entry p of a (n0+1)(n1+1)(n2+1) tensor, p = i + (n0 + 1)(j + (n1 + 1)
/// k): a patch's control points, and the powers of its power form.
inline void tensorIndices(size_t p, const int* n, int* index)
{
  index[0] = int(p % size_t(n[0] + 1));
  index[1] = int(p / size_t(n[0] + 1) % size_t(n[1] + 1));
  index[2] = int(p / size_t((n[0] + 1) * (n[1] + 1)));
}

/// A ray's blossom (blossomAlongRay), priced as directRayCost (RayComposition.h), fitted to
/// its measured 36-730 ns (within 20 %) on patches of degree 2 to 6 with 4 to 35 terms: a term of
/// degree q takes q linear factors, about q (q + 1) products; the sum's elevations and the
/// binomials (d + 1)^2 / 2.
inline double blossomRayCost(const std::vector<PowerTerm>& terms, int rayDegree)
{
  double products = 0;
  for (const PowerTerm& term : terms)
  {
    products += term.degree() * (term.degree() + 1);
  }
  return 0.8 * products + 0.5 * (rayDegree + 1) * (rayDegree + 1) + 20;
}

/// The least a term adds to blossomRayCost (one of degree 1).
constexpr double kLeastTermCost = 1.6;

namespace detail
{
/// The coefficient of s^a in (1 + s)^i (1 - s)^(n - i), an integer.
inline double expansionCoefficient(int n, int i, int a)
{
  double sum = 0;
  for (int j = std::max(0, a - (n - i)); j <= std::min(i, a); ++j)
    sum += ((a - j) % 2 ? -1.0 : 1.0) * binomial(i, j) * binomial(n - i, a - j);
  return sum;
}

/// Row i of B_i^n((1 + s) / 2) = sum_a m[i][a] s^a: C(n, i) 2^-n (1 + s)^i (1 - s)^(n - i),
/// exact in double (integers below 2^53 over a power of two).
inline void bernsteinToCentredPower(int n, double (&m)[kMaxOrder][kMaxOrder])
{
  for (int i = 0; i <= n; ++i)
    for (int a = 0; a <= n; ++a)
      m[i][a] = binomial(n, i) * expansionCoefficient(n, i, a) / std::ldexp(1.0, n);
}

/// Row a of s^a = sum_i p[a][i] B_i^n(u), s = 2 u - 1: the blossom of s^a (as degree n) at i
/// ones and n - i minus ones, the same expansion's coefficient over C(n, a).
inline void centredPowerToBernstein(int n, double (&p)[kMaxOrder][kMaxOrder])
{
  for (int a = 0; a <= n; ++a)
    for (int i = 0; i <= n; ++i)
      p[a][i] = expansionCoefficient(n, i, a) / binomial(n, a);
}

/// Applies rows[d] (one matrix a direction) along each direction of a (n0+1)(n1+1)(n2+1) tensor
/// (index i + (n0 + 1) (j + (n1 + 1) k)), with the same sums of magnitudes for `bound`.
inline void transformTensor(const int* n, const double (&rows)[3][kMaxOrder][kMaxOrder],
  std::vector<double>& value, std::vector<double>& bound)
{
  const size_t count = value.size();
  size_t stride = 1;
  for (int d = 0; d < 3; ++d)
  {
    std::vector<double> nextValue(count, 0.0), nextBound(count, 0.0);
    for (size_t p = 0; p < count; ++p)
    {
      const int i = int(p / stride) % (n[d] + 1);
      const size_t base = p - size_t(i) * stride;
      for (int a = 0; a <= n[d]; ++a)
      {
        nextValue[base + size_t(a) * stride] += rows[d][i][a] * value[p];
        nextBound[base + size_t(a) * stride] += std::fabs(rows[d][i][a]) * bound[p];
      }
    }
    value.swap(nextValue);
    bound.swap(nextBound);
    stride *= size_t(n[d] + 1);
  }
}
} // namespace detail

/// The power form in s = 2 u - 1 of a field given by its Bernstein coefficients (degree n per
/// direction, index i + (n0 + 1) (j + (n1 + 1) k), and the powers' indices the same): `value`
/// its coefficients, `bound` the sums of magnitudes that bound their rounding.
inline void centredPowerForm(const std::vector<double>& field, const int* n,
  std::vector<double>& value, std::vector<double>& bound)
{
  double toPower[3][kMaxOrder][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    detail::bernsteinToCentredPower(n[d], toPower[d]);
  }
  value = field;
  bound.resize(field.size());
  for (size_t p = 0; p < field.size(); ++p)
  {
    bound[p] = std::fabs(field[p]);
  }
  detail::transformTensor(n, toPower, value, bound);
}

/// Whether a coefficient of centredPowerForm stands above its rounding.
inline bool significantPower(double value, double bound, const int* n)
{
  return std::fabs(value) > 16.0 * (n[0] + n[1] + n[2] + 3) * Epsilon<double>::value * bound;
}

/// The terms of the power form (centredPowerForm's `value` and `bound`) that stand above their
/// rounding, when there are at most `maxTerms` of them and the Bernstein coefficients of their
/// sum differ from the field's by at most `tolerance` times the largest (which bounds the
/// difference everywhere in the patch); false, and no terms, otherwise. Nothing above rounding
/// is dropped: near its isosurface a field may be far smaller than its largest coefficient.
inline bool sparsePowerForm(const std::vector<double>& field, const int* n,
  const std::vector<double>& value, const std::vector<double>& bound, size_t maxTerms,
  double tolerance, std::vector<PowerTerm>& terms)
{
  terms.clear();
  for (size_t p = 0; p < value.size(); ++p)
  {
    if (significantPower(value[p], bound[p], n))
    {
      if (terms.size() == maxTerms)
      {
        terms.clear();
        return false;
      }
      int a[3];
      tensorIndices(p, n, a);
      terms.push_back({ value[p], { int8_t(a[0]), int8_t(a[1]), int8_t(a[2]) } });
    }
  }
  // By total degree, as blossomAlongRay sums them.
  std::stable_sort(terms.begin(), terms.end(),
    [](const PowerTerm& a, const PowerTerm& b) { return a.degree() < b.degree(); });
  // The certificate: the kept terms back in Bernstein form against the field.
  double toBernstein[3][kMaxOrder][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    detail::centredPowerToBernstein(n[d], toBernstein[d]);
  }
  double largest = 0, difference = 0;
  for (size_t p = 0; p < field.size(); ++p)
  {
    int i[3];
    tensorIndices(p, n, i);
    double back = 0;
    for (const PowerTerm& term : terms)
    {
      back += term.coefficient * toBernstein[0][term.power[0]][i[0]] *
              toBernstein[1][term.power[1]][i[1]] * toBernstein[2][term.power[2]][i[2]];
    }
    largest = std::max(largest, std::fabs(field[p]));
    difference = std::max(difference, std::fabs(back - field[p]));
  }
  if (!(difference <= tolerance * largest))
  {
    terms.clear();
    return false;
  }
  return true;
}

namespace detail
{
/// Degree elevation of scaled Bernstein coefficients (coefficient i times C(order - 1, i)):
/// times lambda + mu, `order` coefficients to order + 1.
IGA_HD inline void elevateScaled(double* c, int order)
{
  c[order] = c[order - 1];
  for (int k = order - 1; k > 0; --k)
  {
    c[k] += c[k - 1];
  }
}
} // namespace detail

/// The Bernstein coefficients, degree `degree` (at least each term's total degree) on sigma in
/// [0, 1], of the form minus `isovalue` along s(sigma) = s0 (1 - sigma) + s1 sigma: its blossom
/// at (s0, ..., s0, s1, ..., s1), i times s1 for coefficient i. Each term is a product of the
/// linear forms s0 lambda + s1 mu in homogeneous (lambda, mu) = (1 - sigma, sigma); coefficient i
/// of the sum, elevated by (lambda + mu) to `degree`, over C(degree, i). The terms' products are
/// summed as their degrees rise and the sum elevated on the way, once a degree (sparsePowerForm
/// sorts the terms so), not each term to the full degree.
IGA_HD inline void blossomAlongRay(const PowerTerm* terms, int count, int degree,
  const glm::dvec3& s0, const glm::dvec3& s1, double isovalue, double* coefficients)
{
  double sum[kMaxOrder] = { 0.0 };
  int sumOrder = 1; // coefficients in `sum`
  for (int t = 0; t < count; ++t)
  {
    const PowerTerm& term = terms[t];
    double product[kMaxOrder];
    product[0] = term.coefficient;
    int order = 1; // coefficients in `product`
    for (int d = 0; d < 3; ++d)
    {
      for (int e = 0; e < term.power[d]; ++e, ++order) // times s0[d] lambda + s1[d] mu
      {
        product[order] = product[order - 1] * s1[d];
        for (int k = order - 1; k > 0; --k)
        {
          product[k] = product[k] * s0[d] + product[k - 1] * s1[d];
        }
        product[0] *= s0[d];
      }
    }
    for (; sumOrder < order; ++sumOrder)
    {
      detail::elevateScaled(sum, sumOrder);
    }
    for (; order < sumOrder; ++order) // a term out of degree order
    {
      detail::elevateScaled(product, order);
    }
    for (int k = 0; k < order; ++k)
    {
      sum[k] += product[k];
    }
  }
  for (; sumOrder <= degree; ++sumOrder)
  {
    detail::elevateScaled(sum, sumOrder);
  }
  double choose = 1; // C(degree, k), exact
  for (int k = 0; k <= degree; ++k)
  {
    coefficients[k] = sum[k] / choose - isovalue;
    choose = choose * (degree - k) / (k + 1);
  }
}

/// The form's gradient in s at s.
IGA_HD inline glm::dvec3 powerGradient(const PowerTerm* terms, int count, const glm::dvec3& s)
{
  double powers[3][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    powers[d][0] = 1;
    for (int k = 1; k < kMaxOrder; ++k)
    {
      powers[d][k] = powers[d][k - 1] * s[d];
    }
  }
  glm::dvec3 gradient(0.0);
  for (int t = 0; t < count; ++t)
  {
    const int8_t* p = terms[t].power;
    for (int d = 0; d < 3; ++d)
    {
      if (p[d] > 0)
      {
        const int e = (d + 1) % 3, f = (d + 2) % 3;
        gradient[d] +=
          terms[t].coefficient * p[d] * powers[d][p[d] - 1] * powers[e][p[e]] * powers[f][p[f]];
      }
    }
  }
  return gradient;
}

} // namespace iga
