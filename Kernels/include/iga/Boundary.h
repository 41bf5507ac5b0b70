// The boundary of a set of rational Bézier volumes as rational Bézier surfaces: a face of a
// patch is a slice of its control net (exact, every channel: geometry, weight and attributes),
// and a face is on the boundary unless another patch has the same face (conforming multi-patch
// blocks) or it is collapsed onto a curve or a point (a cylinder's axis).
#pragma once

#include "iga/BezierPatch.h"
#include "iga/Orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace iga
{

/// Face `side` (0: parameter 0, 1: parameter 1) across parametric direction `direction` of a
/// volume patch.
struct PatchFace
{
  int patch;
  int direction;
  int side;
};

/// The two directions of the volume that parametrise face across `direction`, in increasing
/// order: the surface's (s, t).
inline void faceDirections(int direction, int& s, int& t)
{
  s = direction == 0 ? 1 : 0;
  t = direction == 2 ? 1 : 2;
}

/// The face's control net as a surface of the volume's channels: surface point (i, j) is the
/// volume's point with index i along faceDirections' s, j along t, and 0 or the degree across.
template<class T>
BezierSurface<T> faceSurface(const BezierVolume<T>& volume, int direction, int side)
{
  int s, t;
  faceDirections(direction, s, t);
  const auto view = volume.view();
  const int degree[2] = { volume.degree(s), volume.degree(t) };
  BezierSurface<T> surface(degree, volume.channels());
  const auto out = surface.view();
  const int across = side ? volume.degree(direction) : 0;
  for (int j = 0; j <= degree[1]; ++j)
  {
    for (int i = 0; i <= degree[0]; ++i)
    {
      int index[3];
      index[direction] = across;
      index[s] = i;
      index[t] = j;
      const T* from = view.coeffs + index[0] * view.stride(0) + index[1] * view.stride(1) +
                      index[2] * view.stride(2);
      std::copy(from, from + volume.channels(), out.point(i + out.order(0) * j));
    }
  }
  return surface;
}

/// Whether faceSurface's normal x_s x x_t points into the volume at this face: across
/// direction d the volume lies on the side of increasing u_d at side 0, so (x_s, x_t, x_d) being
/// right-handed or not, with the patch's handedness (signedVolume's sign), decides.
inline bool faceNormalPointsInward(const PatchFace& face, bool leftHanded)
{
  // det(x_s, x_t, x_d) is +det J for d = 0 and 2 and -det J for d = 1 (faceDirections' order).
  const bool rightHandedTriple = (face.direction == 1) == leftHanded;
  return rightHandedTriple == (face.side == 0);
}

/// The face as faceSurface gives it, its t direction reversed where that is needed for x_s x x_t
/// to point out of the volume: an oriented piece of the volumes' boundary, which a ray enters
/// where that normal faces it.
template<class T>
BezierSurface<T> outwardFaceSurface(
  const BezierVolume<T>& volume, const PatchFace& face, bool leftHanded)
{
  BezierSurface<T> surface = faceSurface(volume, face.direction, face.side);
  if (faceNormalPointsInward(face, leftHanded))
  {
    reverseDirection(surface.view(), 1);
  }
  return surface;
}

/// The volume parameter of point (s, t) of outwardFaceSurface.
inline void faceParameterInVolume(
  const PatchFace& face, bool reversed, double s, double t, double* uvw)
{
  int ds, dt;
  faceDirections(face.direction, ds, dt);
  uvw[face.direction] = face.side ? 1.0 : 0.0;
  uvw[ds] = s;
  uvw[dt] = reversed ? 1.0 - t : t;
}

namespace detail
{

/// A face's control points in Euclidean coordinates with their weights over the face's largest
/// (a rational surface is unchanged by scaling its weights), sorted: the same for the same face
/// of two patches whatever their parametrisations' orientations.
template<class T>
std::vector<std::array<double, 4>> faceKey(const BezierSurface<T>& face)
{
  const auto view = face.view();
  double largest = 0;
  for (int p = 0; p < view.pointCount(); ++p)
    largest = std::max(largest, std::abs(double(view.point(p)[kWeightChannel])));
  std::vector<std::array<double, 4>> key;
  for (int p = 0; p < view.pointCount(); ++p)
  {
    const T* point = view.point(p);
    const double w = double(point[kWeightChannel]);
    key.push_back({ double(point[0]) / w, double(point[1]) / w, double(point[2]) / w,
      largest > 0 ? w / largest : 0 });
  }
  std::sort(key.begin(), key.end());
  return key;
}

/// Whether two sorted keys hold the same points within `tolerance` (weights within 1e-9).
inline bool sameKey(const std::vector<std::array<double, 4>>& a,
  const std::vector<std::array<double, 4>>& b, double tolerance)
{
  if (a.size() != b.size())
    return false;
  // Each point of `a` pairs with the first unused point of `b` within the tolerance.
  std::vector<bool> used(b.size(), false);
  for (const auto& p : a)
  {
    bool found = false;
    for (size_t k = 0; k < b.size() && !found; ++k)
    {
      const auto& q = b[k];
      found = !used[k] && std::abs(p[0] - q[0]) <= tolerance &&
              std::abs(p[1] - q[1]) <= tolerance && std::abs(p[2] - q[2]) <= tolerance &&
              std::abs(p[3] - q[3]) <= 1e-9;
      if (found)
        used[k] = true;
    }
    if (!found)
      return false;
  }
  return true;
}

/// Whether a face's net is collapsed along one of its directions (every line of control
/// points along it a single point, within `tolerance`): a curve or a point, no area.
template<class T>
bool collapsedFace(const BezierSurface<T>& face, double tolerance)
{
  const auto view = face.view();
  for (int along = 0; along < 2; ++along)
  {
    bool collapsed = true;
    const int lines = view.order(1 - along), length = view.order(along);
    for (int line = 0; line < lines && collapsed; ++line)
    {
      auto at = [&](int k)
      {
        const int i = along == 0 ? k : line, j = along == 0 ? line : k;
        return view.point(i + view.order(0) * j);
      };
      const T* first = at(0);
      for (int k = 1; k < length && collapsed; ++k)
      {
        const T* other = at(k);
        for (int d = 0; d < 3 && collapsed; ++d)
          collapsed = std::abs(double(other[d]) / double(other[kWeightChannel]) -
                               double(first[d]) / double(first[kWeightChannel])) <= tolerance;
      }
    }
    if (collapsed)
      return true;
  }
  return false;
}

} // namespace detail

/// The faces of `patches` (positive, finite weights: checkPatch) on the boundary of their union,
/// in patch, direction, side order: every face but those matched by another patch's face (the
/// same control points, in any order, within 1e-9 of the patches' largest extent along x, y or
/// z; points closer than that within one face may fail to pair up) and those collapsed onto a
/// curve or a point.
template<class T>
std::vector<PatchFace> boundaryFaces(const std::vector<BezierVolume<T>>& patches)
{
  struct Candidate
  {
    PatchFace face;
    std::vector<std::array<double, 4>> key;
  };
  std::vector<Candidate> faces;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (int p = 0; p < int(patches.size()); ++p)
  {
    for (int direction = 0; direction < 3; ++direction)
    {
      for (int side = 0; side < 2; ++side)
      {
        auto key = detail::faceKey(faceSurface(patches[size_t(p)], direction, side));
        for (const auto& point : key)
          for (int d = 0; d < 3; ++d)
          {
            lo[d] = std::min(lo[d], point[d]);
            hi[d] = std::max(hi[d], point[d]);
          }
        faces.push_back({ { p, direction, side }, std::move(key) });
      }
    }
  }
  const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300 });
  const double tolerance = 1e-9 * extent;
  // Matching faces start with the same smallest point: sorted by it, a face's partners follow
  // it within the tolerance in x.
  std::vector<size_t> order(faces.size());
  for (size_t f = 0; f < order.size(); ++f)
    order[f] = f;
  std::sort(order.begin(), order.end(),
    [&](size_t a, size_t b) { return faces[a].key[0][0] < faces[b].key[0][0]; });
  std::vector<bool> inner(faces.size(), false);
  for (size_t a = 0; a < order.size(); ++a)
  {
    for (size_t b = a + 1;
         b < order.size() && faces[order[b]].key[0][0] - faces[order[a]].key[0][0] <= tolerance;
         ++b)
    {
      if (faces[order[a]].face.patch != faces[order[b]].face.patch &&
          detail::sameKey(faces[order[a]].key, faces[order[b]].key, tolerance))
      {
        inner[order[a]] = inner[order[b]] = true;
      }
    }
  }
  std::vector<PatchFace> boundary;
  for (size_t f = 0; f < faces.size(); ++f)
  {
    const PatchFace& face = faces[f].face;
    if (!inner[f] &&
        !detail::collapsedFace(
          faceSurface(patches[size_t(face.patch)], face.direction, face.side), tolerance))
    {
      boundary.push_back(face);
    }
  }
  return boundary;
}

} // namespace iga
