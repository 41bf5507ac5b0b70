// Mean and Gaussian curvature of an isosurface of a rational Bézier volume's attribute, in world
// coordinates: the attribute F(x) = f(u(x)) through the geometry's inverse, its world gradient
// G = J^-T grad_u f and Hessian H = J^-T (H_u f - sum_k G_k H_u x_k) J^-1 (the geometry's
// second derivatives enter where it is not affine), then Goldman's formulas for the level set
// ("Curvature formulas for implicit curves and surfaces", 2005).
#pragma once

#include "iga/BezierPatch.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <limits>

namespace iga
{

/// Curvatures with respect to the normal -G / |G| (towards lower values of the attribute):
/// a sphere of radius r around a minimum has mean 1/r and Gaussian 1/r^2. NaN where the
/// gradient or the Jacobian vanish.
struct IsosurfaceCurvature
{
  double mean = std::numeric_limits<double>::quiet_NaN();
  double gauss = std::numeric_limits<double>::quiet_NaN();
};

namespace detail
{
/// Bernstein basis of degree n at t with first and second derivatives.
inline void bernsteinWithSecond(int n, double t, double* b, double* d1, double* d2)
{
  bernsteinBasis(n, t, b, d1);
  for (int i = 0; i <= n; ++i)
  {
    d2[i] = 0;
  }
  if (n < 2)
  {
    return;
  }
  double lower[kMaxOrder];
  bernsteinBasis(n - 2, t, lower, static_cast<double*>(nullptr));
  for (int i = 0; i <= n; ++i)
  {
    const double a = i >= 2 ? lower[i - 2] : 0, b1 = i >= 1 && i - 1 <= n - 2 ? lower[i - 1] : 0,
                 c = i <= n - 2 ? lower[i] : 0;
    d2[i] = n * (n - 1) * (a - 2 * b1 + c);
  }
}

/// Value, gradient and Hessian in u of one homogeneous channel.
struct Jet
{
  double value = 0;
  glm::dvec3 gradient{ 0.0 };
  glm::dmat3 hessian{ 0.0 };
};

/// The rational function numerator / denominator's jet (quotient rule to second order).
inline Jet rationalJet(const Jet& n, const Jet& d)
{
  Jet q;
  q.value = n.value / d.value;
  q.gradient = (n.gradient - q.value * d.gradient) / d.value;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      q.hessian[i][j] = (n.hessian[i][j] - q.gradient[i] * d.gradient[j] -
                          q.gradient[j] * d.gradient[i] - q.value * d.hessian[i][j]) /
                        d.value;
    }
  }
  return q;
}
} // namespace detail

/// The curvatures at u of the isosurface of `attributeChannel` through the point.
inline IsosurfaceCurvature isosurfaceCurvature(
  const VolumeView<const double>& patch, int attributeChannel, const double* u)
{
  double b[3][kMaxOrder], d1[3][kMaxOrder], d2[3][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    detail::bernsteinWithSecond(patch.degree[d], u[d], b[d], d1[d], d2[d]);
  }
  const int channels[5] = { 0, 1, 2, kWeightChannel, attributeChannel };
  detail::Jet jets[5];
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    const int i[3] = { p % patch.order(0), p / patch.order(0) % patch.order(1),
      p / (patch.order(0) * patch.order(1)) };
    const double value = b[0][i[0]] * b[1][i[1]] * b[2][i[2]];
    glm::dvec3 gradient;
    glm::dmat3 hessian;
    for (int r = 0; r < 3; ++r)
    {
      gradient[r] = 1;
      for (int e = 0; e < 3; ++e)
      {
        gradient[r] *= e == r ? d1[e][i[e]] : b[e][i[e]];
      }
      for (int s = 0; s < 3; ++s)
      {
        double product = 1;
        for (int e = 0; e < 3; ++e)
        {
          const int order = (e == r) + (e == s);
          product *= order == 2 ? d2[e][i[e]] : order == 1 ? d1[e][i[e]] : b[e][i[e]];
        }
        hessian[r][s] = product;
      }
    }
    for (int c = 0; c < 5; ++c)
    {
      const double coefficient = patch.point(p)[channels[c]];
      jets[c].value += value * coefficient;
      jets[c].gradient += gradient * coefficient;
      jets[c].hessian += hessian * coefficient;
    }
  }
  detail::Jet x[3], f = detail::rationalJet(jets[4], jets[3]);
  glm::dmat3 J; // J[i][k] = d x_k / d u_i (glm: column i)
  for (int k = 0; k < 3; ++k)
  {
    x[k] = detail::rationalJet(jets[k], jets[3]);
    for (int i = 0; i < 3; ++i)
    {
      J[i][k] = x[k].gradient[i];
    }
  }
  IsosurfaceCurvature curvature;
  if (!(std::fabs(glm::determinant(J)) > 0))
  {
    return curvature;
  }
  const glm::dmat3 M = glm::inverse(J); // d u / d x
  const glm::dvec3 G = glm::transpose(M) * f.gradient;
  glm::dmat3 inner = f.hessian;
  for (int k = 0; k < 3; ++k)
  {
    inner -= G[k] * x[k].hessian;
  }
  const glm::dmat3 H = glm::transpose(M) * inner * M;
  const double g2 = glm::dot(G, G);
  if (!(g2 > 0))
  {
    return curvature;
  }
  // adj(H) = det(H) H^-1, written out so that a singular H has one too.
  glm::dmat3 adjugate;
  for (int r = 0; r < 3; ++r)
  {
    for (int s = 0; s < 3; ++s)
    {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, s1 = (s + 1) % 3, s2 = (s + 2) % 3;
      adjugate[r][s] = H[s1][r1] * H[s2][r2] - H[s1][r2] * H[s2][r1];
    }
  }
  const double trace = H[0][0] + H[1][1] + H[2][2];
  curvature.gauss = glm::dot(G, adjugate * G) / (g2 * g2);
  curvature.mean = (g2 * trace - glm::dot(G, H * G)) / (2 * g2 * std::sqrt(g2));
  return curvature;
}

} // namespace iga
