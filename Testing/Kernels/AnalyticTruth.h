// Analytic references for the engine tests: the ray through a pixel from the camera's geometry,
// first hits of quadrics, and the comparison of a G-buffer's first hits with them.
#pragma once

#include "iga/Camera.h"
#include "iga/sst/GBuffer.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace igatest
{
namespace truth
{

using iga::sst::GBuffer;

inline iga::Camera makeCamera(const glm::dvec3& position, const glm::dvec3& focal,
  const glm::dvec3& up, double angle, const double* bounds)
{
  iga::Camera camera;
  camera.position = position;
  camera.focalPoint = focal;
  camera.viewUp = up;
  camera.viewAngle = angle;
  iga::fitClippingRange(camera, bounds);
  return camera;
}

/// The ray through pixel (i, j)'s centre from the camera's geometry (not from its matrices).
inline void pixelRay(const iga::Camera& camera, int width, int height, int i, int j,
  glm::dvec3& origin, glm::dvec3& direction)
{
  const glm::dvec3 forward = iga::viewDirection(camera);
  const glm::dvec3 side = glm::normalize(glm::cross(forward, camera.viewUp));
  const glm::dvec3 up = glm::cross(side, forward);
  const double t = std::tan(camera.viewAngle * M_PI / 360.0);
  const double x = (i + 0.5) / width * 2 - 1, y = (j + 0.5) / height * 2 - 1;
  origin = camera.position;
  direction = forward + x * t * double(width) / height * side + y * t * up;
}

/// An analytic first hit: ray parameter (inf for none) and whether the ray passes so close to the
/// surface's boundary or silhouette that a pixel may go either way.
struct Truth
{
  double t;
  bool ambiguous;
};

struct Comparison
{
  int covered = 0, mismatched = 0, ambiguous = 0;
  double maxPositionError = 0, maxNormalError = 0;
};

/// Compares the first hits with the truth at every pixel; `normalAt` gives the true unit normal
/// at a point (up to sign).
inline Comparison compare(const GBuffer& gbuffer, const iga::Camera& camera,
  std::function<Truth(const glm::dvec3&, const glm::dvec3&)> truth,
  std::function<glm::dvec3(const glm::dvec3&)> normalAt)
{
  Comparison result;
  for (int j = 0; j < gbuffer.height; ++j)
  {
    for (int i = 0; i < gbuffer.width; ++i)
    {
      glm::dvec3 o, dir;
      pixelRay(camera, gbuffer.width, gbuffer.height, i, j, o, dir);
      const Truth expected = truth(o, dir);
      const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
      if (expected.ambiguous)
      {
        ++result.ambiguous;
        continue;
      }
      if ((hit != nullptr) != std::isfinite(expected.t))
      {
        ++result.mismatched;
        continue;
      }
      if (!hit)
        continue;
      ++result.covered;
      const glm::dvec3 p = o + expected.t * dir;
      const glm::dvec3 n = normalAt(p);
      double error = 0;
      for (int d = 0; d < 3; ++d)
        error = std::max(error, std::abs(hit->position[d] - p[d]));
      const double dotn = glm::dot(hit->normal, n);
      result.maxPositionError = std::max(result.maxPositionError, error);
      result.maxNormalError = std::max(result.maxNormalError, 1 - std::abs(dotn));
    }
  }
  return result;
}

/// Nearest t > tMin solving the quadratic a t^2 + b t + c = 0 that passes `accept`.
inline double firstRoot(
  double a, double b, double c, std::function<bool(double)> accept, double& discriminant)
{
  discriminant = b * b - 4 * a * c;
  if (discriminant < 0)
    return INFINITY;
  const double s = std::sqrt(discriminant);
  double roots[2] = { (-b - s) / (2 * a), (-b + s) / (2 * a) };
  for (double t : roots)
    if (t > 0 && accept(t))
      return t;
  return INFINITY;
}

inline Truth sphereTruth(const glm::dvec3& o, const glm::dvec3& d)
{
  const double a = glm::dot(d, d), b = 2 * glm::dot(o, d), c = glm::dot(o, o) - 1;
  double disc;
  const double t = firstRoot(
    a, b, c, [](double) { return true; }, disc);
  // Grazing rays (within 1e-7 of tangency, relative) may fall either way.
  return { t, std::abs(disc) < 1e-6 * b * b };
}

inline glm::dvec3 sphereNormal(const glm::dvec3& p)
{
  return glm::normalize(p);
}

/// First hit on the lateral surface x^2 + y^2 = r^2, z in [z0, z1].
inline Truth cylinderTruth(const glm::dvec3& o, const glm::dvec3& d, double r, double z0, double z1)
{
  const double a = d[0] * d[0] + d[1] * d[1], b = 2 * (o[0] * d[0] + o[1] * d[1]),
               c = o[0] * o[0] + o[1] * o[1] - r * r;
  double disc;
  bool nearRim = false;
  const double t = firstRoot(
    a, b, c,
    [&](double t)
    {
      const double z = o[2] + t * d[2];
      nearRim = nearRim || std::abs(z - z0) < 1e-6 || std::abs(z - z1) < 1e-6;
      return z >= z0 && z <= z1;
    },
    disc);
  return { t, nearRim || std::abs(disc) < 1e-6 * b * b };
}

inline glm::dvec3 cylinderNormal(const glm::dvec3& p)
{
  return glm::normalize(glm::dvec3(p[0], p[1], 0));
}

/// Pixels whose ray clearly crosses the unit sphere about the origin (not grazing) and how many
/// of them hold exactly its two crossings, front then back, within 1e-6 of the analytic points.
struct BothSides
{
  int crossing = 0, twoHits = 0;
};

inline BothSides unitSphereBothSides(const GBuffer& gbuffer, const iga::Camera& camera)
{
  BothSides result;
  for (int j = 0; j < gbuffer.height; ++j)
    for (int i = 0; i < gbuffer.width; ++i)
    {
      glm::dvec3 o, d;
      pixelRay(camera, gbuffer.width, gbuffer.height, i, j, o, d);
      const Truth truth = sphereTruth(o, d);
      if (truth.ambiguous || !std::isfinite(truth.t))
        continue;
      ++result.crossing;
      if (gbuffer.hitCount(i, j) != 2)
        continue;
      const auto* hit = gbuffer.firstHit(i, j);
      const double a = glm::dot(d, d), b = 2 * glm::dot(o, d), c = glm::dot(o, o) - 1;
      const double far = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
      const bool ordered = hit[0].ndcDepth < hit[1].ndcDepth && hit[0].eyeDepth < hit[1].eyeDepth;
      const bool placed = glm::length(hit[0].position - (o + truth.t * d)) < 1e-6 &&
                          glm::length(hit[1].position - (o + far * d)) < 1e-6;
      result.twoHits += ordered && placed ? 1 : 0;
    }
  return result;
}

/// The clipping-plane tests' cuts of the unit sphere: kept where x + 0.2 y >= 0.1 and z <= 0.5.
inline std::vector<std::array<double, 4>> sphereCuts()
{
  return { { 1, 0.2, 0, -0.1 }, { 0, 0, -2, 1 } };
}

inline bool keptBySphereCuts(const glm::dvec3& p)
{
  return p[0] + 0.2 * p[1] - 0.1 >= 0 && p[2] <= 0.5;
}

/// The first hit on the unit sphere's kept part; ambiguous within 1e-5 of a cut or grazing.
inline Truth clippedSphereTruth(const glm::dvec3& o, const glm::dvec3& d)
{
  const double a = glm::dot(d, d), b = 2 * glm::dot(o, d), c = glm::dot(o, o) - 1;
  double disc;
  bool nearCut = false;
  const double t = firstRoot(
    a, b, c,
    [&](double t)
    {
      const glm::dvec3 p = o + t * d;
      nearCut = nearCut || std::abs(p[0] + 0.2 * p[1] - 0.1) < 1e-5 || std::abs(p[2] - 0.5) < 1e-5;
      return keptBySphereCuts(p);
    },
    disc);
  return { t, nearCut || std::abs(disc) < 1e-6 * b * b };
}

/// A frame of the unit sphere about the origin (first hits) against the analytic one: nothing
/// unresolved, coverage equal off grazing rays, hits within 1e-6 (Newton stops 1e-6 pixel from
/// the ray), normals to 1e-9.
inline void expectTheUnitSphere(
  const GBuffer& gbuffer, const iga::Camera& camera, size_t unresolvedPixels)
{
  const Comparison c = compare(gbuffer, camera, sphereTruth, sphereNormal);
  EXPECT_EQ(unresolvedPixels, 0u);
  EXPECT_GT(c.covered, 1000);
  EXPECT_EQ(c.mismatched, 0) << "coverage differs from the analytic silhouette";
  EXPECT_LT(c.maxPositionError, 1e-6);
  EXPECT_LT(c.maxNormalError, 1e-9);
}

} // namespace truth
} // namespace igatest
