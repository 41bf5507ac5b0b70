// A camera with VTK's semantics (vtkCamera) and the matrices VTK derives from it, so the engine
// sees exactly what VTK's own props see. Matrices are row-major and act on column vectors; clip
// space depth runs from -1 (near plane) to 1 (far plane).
#pragma once

#include "iga/Bounds.h"

#include <cmath>
#include <utility>

namespace iga
{

struct Camera
{
  double position[3] = { 0, 0, 1 };
  double focalPoint[3] = { 0, 0, 0 };
  double viewUp[3] = { 0, 1, 0 };
  double viewAngle = 30; ///< vertical, degrees
  bool parallelProjection = false;
  double parallelScale = 1; ///< half the viewport height in world units
  double clippingRange[2] = { 0.01, 1000.01 };
};

IGA_HD inline void normalize3(double* v)
{
  const double n = squareRoot(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n > 0)
  {
    v[0] /= n;
    v[1] /= n;
    v[2] /= n;
  }
}

IGA_HD inline void cross3(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

IGA_HD inline double dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Unit vector from the position to the focal point.
inline void viewDirection(const Camera& camera, double* direction)
{
  for (int d = 0; d < 3; ++d)
  {
    direction[d] = camera.focalPoint[d] - camera.position[d];
  }
  normalize3(direction);
}

inline Matrix4<double> multiply(const Matrix4<double>& a, const Matrix4<double>& b)
{
  Matrix4<double> r;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j] +
                  a.m[i][3] * b.m[3][j];
    }
  }
  return r;
}

/// World to eye coordinates (vtkCamera::GetViewTransformMatrix, gluLookAt).
inline Matrix4<double> viewMatrix(const Camera& camera)
{
  double forward[3], side[3], up[3];
  viewDirection(camera, forward);
  cross3(forward, camera.viewUp, side);
  normalize3(side);
  cross3(side, forward, up);
  Matrix4<double> m = Matrix4<double>::identity();
  for (int d = 0; d < 3; ++d)
  {
    m.m[0][d] = side[d];
    m.m[1][d] = up[d];
    m.m[2][d] = -forward[d];
  }
  for (int r = 0; r < 3; ++r)
  {
    m.m[r][3] = -dot3(m.m[r], camera.position);
  }
  return m;
}

/// Eye to clip coordinates for a viewport of the given width/height aspect
/// (vtkCamera::GetProjectionTransformMatrix(aspect, -1, 1)).
inline Matrix4<double> projectionMatrix(const Camera& camera, double aspect)
{
  const double n = camera.clippingRange[0], f = camera.clippingRange[1];
  Matrix4<double> m;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      m.m[i][j] = 0;
    }
  }
  if (camera.parallelProjection)
  {
    const double h = camera.parallelScale, w = h * aspect;
    m.m[0][0] = 1 / w;
    m.m[1][1] = 1 / h;
    m.m[2][2] = -2 / (f - n);
    m.m[2][3] = -(n + f) / (f - n);
    m.m[3][3] = 1;
  }
  else
  {
    const double h = std::tan(camera.viewAngle * 3.14159265358979323846 / 360.0) * n;
    const double w = h * aspect;
    m.m[0][0] = n / w;
    m.m[1][1] = n / h;
    m.m[2][2] = -(n + f) / (f - n);
    m.m[2][3] = -2 * n * f / (f - n);
    m.m[3][2] = -1;
  }
  return m;
}

/// World to clip coordinates.
inline Matrix4<double> worldToClip(const Camera& camera, double aspect)
{
  return multiply(projectionMatrix(camera, aspect), viewMatrix(camera));
}

/// The coefficients q of the plane p . x = 0 in the coordinates `m` maps to: q . (m x) = p . x for
/// every homogeneous x, i.e. m^T q = p (Gaussian elimination with partial pivoting). False when m
/// is singular.
inline bool transformPlane(const Matrix4<double>& m, const double* p, double* q)
{
  double a[4][5];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      a[r][c] = m.m[c][r];
    }
    a[r][4] = p[r];
  }
  for (int c = 0; c < 4; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
    {
      pivot = std::abs(a[r][c]) > std::abs(a[pivot][c]) ? r : pivot;
    }
    if (a[pivot][c] == 0)
    {
      return false;
    }
    for (int k = 0; k < 5; ++k)
    {
      std::swap(a[c][k], a[pivot][k]);
    }
    for (int r = c + 1; r < 4; ++r)
    {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 5; ++k)
      {
        a[r][k] -= f * a[c][k];
      }
    }
  }
  for (int r = 3; r >= 0; --r)
  {
    double v = a[r][4];
    for (int k = r + 1; k < 4; ++k)
    {
      v -= a[r][k] * q[k];
    }
    q[r] = v / a[r][r];
  }
  return true;
}

/// Points the camera at the centre of `bounds` (xmin, xmax, ymin, ymax, zmin, zmax) from
/// `direction` (towards the data) at the distance where the bounding sphere fills the view, as
/// vtkRenderer::ResetCamera does, and sets the clipping range around it.
inline Camera frameBounds(
  const double* bounds, const double* direction, const double* viewUp, double viewAngle)
{
  Camera camera;
  double dir[3] = { direction[0], direction[1], direction[2] };
  normalize3(dir);
  double radius = 0;
  for (int d = 0; d < 3; ++d)
  {
    camera.focalPoint[d] = 0.5 * (bounds[2 * d] + bounds[2 * d + 1]);
    radius += 0.25 * (bounds[2 * d + 1] - bounds[2 * d]) * (bounds[2 * d + 1] - bounds[2 * d]);
  }
  radius = std::sqrt(radius);
  if (radius == 0)
  {
    radius = 0.5;
  }
  const double distance = radius / std::sin(viewAngle * 3.14159265358979323846 / 360.0);
  for (int d = 0; d < 3; ++d)
  {
    camera.position[d] = camera.focalPoint[d] - distance * dir[d];
    camera.viewUp[d] = viewUp[d];
  }
  camera.viewAngle = viewAngle;
  camera.parallelScale = radius;
  camera.clippingRange[0] = std::max(distance - 1.01 * radius, 1e-3 * (distance + radius));
  camera.clippingRange[1] = distance + 1.01 * radius;
  return camera;
}

/// Tight near/far planes around `bounds` seen from the camera (vtkRenderer's
/// ResetCameraClippingRange, simplified to the box's corners).
inline void fitClippingRange(Camera& camera, const double* bounds)
{
  double forward[3];
  viewDirection(camera, forward);
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
  const double margin = 0.01 * (hi - lo) + 1e-9;
  camera.clippingRange[1] = std::max(hi + margin, 1e-3);
  camera.clippingRange[0] = std::max(lo - margin, 1e-3 * camera.clippingRange[1]);
}

} // namespace iga
