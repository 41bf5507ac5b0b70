// Mean and Gaussian curvature of an isosurface of a rational Bézier volume's attribute, in world
// coordinates: the attribute F(x) = f(u(x)) through the geometry's inverse, its world gradient
// G = J^-T grad_u f and Hessian H = J^-T (H_u f - sum_k G_k H_u x_k) J^-1 (the geometry's
// second derivatives enter where it is not affine), then Goldman's formulas for the level set
// ("Curvature formulas for implicit curves and surfaces", 2005).
#pragma once

#include "iga/Jet.h"

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

/// The curvatures at u of the isosurface of `attributeChannel` through the point.
inline IsosurfaceCurvature isosurfaceCurvature(
  const VolumeView<const double>& patch, int attributeChannel, const double* u)
{
  const int channels[5] = { 0, 1, 2, kWeightChannel, attributeChannel };
  Jet<double> jets[5];
  channelJets<double, 3>(patch, u, channels, 5, jets);
  Jet<double> x[3];
  const Jet<double> f = rationalJet(jets[4], jets[3]);
  glm::dmat3 J; // J[i][k] = d x_k / d u_i (glm: column i)
  for (int k = 0; k < 3; ++k)
  {
    x[k] = rationalJet(jets[k], jets[3]);
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
