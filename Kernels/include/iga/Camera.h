// A camera with VTK's semantics (vtkCamera) and the matrices VTK derives from it, so the engine
// sees what VTK's own props see. Vectors and matrices are GLM's (matrices indexed [column][row],
// acting on column vectors); clip space depth runs from -1 (near plane) to 1 (far plane).
#pragma once

#include "iga/Bounds.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace iga
{

struct Camera
{
  glm::dvec3 position{ 0, 0, 1 };
  glm::dvec3 focalPoint{ 0, 0, 0 };
  glm::dvec3 viewUp{ 0, 1, 0 };
  double viewAngle = 30; ///< vertical, degrees
  bool parallelProjection = false;
  double parallelScale = 1; ///< half the viewport height in world units
  double clippingRange[2] = { 0.01, 1000.01 };
};

/// The unit vector along v, or v itself where it has no length (glm::normalize gives NaN).
IGA_HD inline glm::dvec3 normalizedOrZero(const glm::dvec3& v)
{
  const double length = glm::length(v);
  return length > 0 ? v / length : v;
}

/// Unit vector from the position to the focal point.
inline glm::dvec3 viewDirection(const Camera& camera)
{
  return normalizedOrZero(camera.focalPoint - camera.position);
}

/// World to eye coordinates (vtkCamera::GetViewTransformMatrix, gluLookAt).
inline glm::dmat4 viewMatrix(const Camera& camera)
{
  return glm::lookAt(camera.position, camera.focalPoint, camera.viewUp);
}

/// Eye to clip coordinates for a viewport of the given width/height aspect
/// (vtkCamera::GetProjectionTransformMatrix(aspect, -1, 1)).
inline glm::dmat4 projectionMatrix(const Camera& camera, double aspect)
{
  const double n = camera.clippingRange[0], f = camera.clippingRange[1];
  if (camera.parallelProjection)
  {
    const double h = camera.parallelScale, w = h * aspect;
    return glm::ortho(-w, w, -h, h, n, f);
  }
  const double h = std::tan(camera.viewAngle * 3.14159265358979323846 / 360.0) * n;
  const double w = h * aspect;
  return glm::frustum(-w, w, -h, h, n, f);
}

/// World to clip coordinates.
inline glm::dmat4 worldToClip(const Camera& camera, double aspect)
{
  return projectionMatrix(camera, aspect) * viewMatrix(camera);
}

/// The coefficients q of the plane p . x = 0 in the coordinates `m` maps to: q . (m x) = p . x for
/// every homogeneous x, i.e. m^T q = p. False when m is singular.
inline bool transformPlane(const glm::dmat4& m, const glm::dvec4& p, glm::dvec4& q)
{
  if (glm::determinant(m) == 0)
  {
    return false;
  }
  q = glm::inverse(glm::transpose(m)) * p;
  return true;
}

/// Points the camera at the centre of `bounds` (xmin, xmax, ymin, ymax, zmin, zmax) from
/// `direction` (towards the data) at the distance where the bounding sphere fills the view, as
/// vtkRenderer::ResetCamera does, and sets the clipping range around it.
inline Camera frameBounds(
  const double* bounds, const glm::dvec3& direction, const glm::dvec3& viewUp, double viewAngle)
{
  Camera camera;
  const glm::dvec3 dir = normalizedOrZero(direction);
  glm::dvec3 extent;
  for (int d = 0; d < 3; ++d)
  {
    camera.focalPoint[d] = 0.5 * bounds[2 * d] + 0.5 * bounds[2 * d + 1];
    extent[d] = bounds[2 * d + 1] - bounds[2 * d];
  }
  // Half the diagonal, its squares taken at unit scale (1e-200 squared would be 0).
  const double largest = std::max({ extent[0], extent[1], extent[2] });
  double radius = largest > 0 ? 0.5 * largest * glm::length(extent / largest) : 0;
  if (radius == 0)
  {
    radius = 0.5;
  }
  const double distance = radius / std::sin(viewAngle * 3.14159265358979323846 / 360.0);
  camera.position = camera.focalPoint - distance * dir;
  camera.viewUp = viewUp;
  camera.viewAngle = viewAngle;
  camera.parallelScale = radius;
  camera.clippingRange[0] = std::max(distance - 1.01 * radius, 1e-3 * (distance + radius));
  camera.clippingRange[1] = distance + 1.01 * radius;
  return camera;
}

/// Moves the camera along its view direction, its focal point at the box's centre, so that the
/// box's corners just fit a viewport of the given width/height aspect with `margin` (a fraction
/// of its half-size, e.g. 0.05) left free on the tighter side: tighter than frameBounds'
/// enclosing sphere. A parallel camera gets the scale that fits instead.
inline void fitBounds(Camera& camera, const double* bounds, double aspect, double margin)
{
  const glm::dvec3 forward = viewDirection(camera);
  const glm::dvec3 right = normalizedOrZero(glm::cross(forward, camera.viewUp));
  const glm::dvec3 up = glm::cross(right, forward);
  glm::dvec3 centre;
  for (int d = 0; d < 3; ++d)
    centre[d] = 0.5 * bounds[2 * d] + 0.5 * bounds[2 * d + 1];
  const double tanY = std::tan(camera.viewAngle * 3.14159265358979323846 / 360.0) * (1 - margin);
  const double tanX = tanY * aspect;
  double distance = 0, halfHeight = 0;
  for (int corner = 0; corner < 8; ++corner)
  {
    glm::dvec3 offset;
    for (int d = 0; d < 3; ++d)
      offset[d] = bounds[2 * d + ((corner >> d) & 1)] - centre[d];
    const double x = std::abs(glm::dot(offset, right)), y = std::abs(glm::dot(offset, up));
    const double towardsEye = -glm::dot(offset, forward);
    distance = std::max({ distance, towardsEye + x / tanX, towardsEye + y / tanY });
    halfHeight = std::max({ halfHeight, x / aspect, y });
  }
  if (!(distance > 0))
    distance = 1;
  camera.focalPoint = centre;
  camera.position = centre - distance * forward;
  camera.parallelScale = halfHeight > 0 ? halfHeight / (1 - margin) : 1;
}

/// Tight near/far planes around `bounds` seen from the camera (vtkRenderer's
/// ResetCameraClippingRange, simplified to the box's corners).
inline void fitClippingRange(Camera& camera, const double* bounds)
{
  const glm::dvec3 forward = viewDirection(camera);
  double lo = 1e300, hi = -1e300;
  for (int corner = 0; corner < 8; ++corner)
  {
    double depth = 0;
    for (int d = 0; d < 3; ++d)
    {
      depth += (bounds[2 * d + ((corner >> d) & 1)] - camera.position[d]) * forward[d];
    }
    lo = std::min(lo, depth);
    hi = std::max(hi, depth);
  }
  // Margins and floors relative to the depths, whatever the data's units.
  const double margin = 0.01 * (hi - lo) + 1e-9 * std::max(std::abs(lo), std::abs(hi));
  camera.clippingRange[1] = hi + margin > 0 ? hi + margin : std::max(hi - lo, 1e-300);
  camera.clippingRange[0] = std::max(lo - margin, 1e-3 * camera.clippingRange[1]);
}

} // namespace iga
