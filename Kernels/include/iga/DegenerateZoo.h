// Degenerate variants of the Marsden sphere patch (makeMarsdenSphere), for the engine's
// robustness tests (ZooTest) and, side by side in one dataset, for the MPI test and whoever wants
// to look at them (igaview-generate-data --zoo).
#pragma once

#include "iga/Datasets.h"
#include "iga/Orientation.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace iga
{

/// The Marsden sphere x^2 + y^2 + z^2 = 1 in one patch of the given degree, changed by `edit`.
template<class T>
VolumeSet<T> makeEditedSphere(int degree, const std::function<void(PatchView<T, 3>)>& edit)
{
  auto set = makeMarsdenSphere<T>(degree);
  edit(set.patches[0].view());
  return set;
}

/// Control point (i, j, k) of a patch.
template<class T>
T* controlPoint(const PatchView<T, 3>& patch, int i, int j, int k)
{
  return patch.point(i + patch.order(0) * (j + patch.order(1) * k));
}

/// The degree-2 sphere with its net's edge (j, k) = (0, 0) moved onto one point: another map of
/// the same control values.
template<class T>
VolumeSet<T> makeSphereWithCollapsedEdge()
{
  return makeEditedSphere<T>(2,
    [](PatchView<T, 3> patch)
    {
      for (int i = 0; i < 3; ++i)
        for (int d = 0; d < 3; ++d)
          controlPoint(patch, i, 0, 0)[d] = controlPoint(patch, 1, 0, 0)[d];
    });
}

/// The degree-2 sphere's net collapsed onto the point (0.25, 0.25, 0.25).
template<class T>
VolumeSet<T> makeSphereCollapsedToAPoint()
{
  return makeEditedSphere<T>(2,
    [](PatchView<T, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
        for (int d = 0; d < 3; ++d)
          patch.point(p)[d] = T(0.25) * patch.point(p)[kWeightChannel];
    });
}

/// The degree-3 sphere with its second parametric direction reversed: left-handed.
template<class T>
VolumeSet<T> makeInvertedSphere()
{
  return makeEditedSphere<T>(3, [](PatchView<T, 3> patch) { reverseDirection(patch, 1); });
}

/// The degree-2 sphere's control values times weights 10^(decades sin 7p): another rational map
/// and field. By default 1e-3 .. 1e3, a ratio of 9.8e5 (about 10^(2 decades)).
template<class T>
VolumeSet<T> makeSphereWithWideWeights(double decades = 3)
{
  return makeEditedSphere<T>(2,
    [decades](PatchView<T, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
      {
        const T w = T(std::pow(10.0, decades * std::sin(7.0 * p)));
        for (int c = 0; c < patch.channels; ++c)
          patch.point(p)[c] *= w;
      }
    });
}

/// The degree-2 sphere's geometry with the attribute 0 everywhere: constant at the isovalue 0.
template<class T>
VolumeSet<T> makeSphereWithConstantField()
{
  return makeEditedSphere<T>(2,
    [](PatchView<T, 3> patch)
    {
      for (int p = 0; p < patch.pointCount(); ++p)
        patch.point(p)[kFirstAttributeChannel] = 0;
    });
}

/// The degree-2 sphere with its middle layer of control points in u pushed 3 along x, past the
/// last layer: the map folds over itself (its Jacobian changes sign), the patch intersects
/// itself.
template<class T>
VolumeSet<T> makeSelfIntersectingSphere()
{
  return makeEditedSphere<T>(2,
    [](PatchView<T, 3> patch)
    {
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          controlPoint(patch, 1, j, k)[0] += T(3) * controlPoint(patch, 1, j, k)[kWeightChannel];
    });
}

/// Moves a rational patch by `offset` (its homogeneous coordinates by offset times the weight).
template<class T>
void translatePatch(const PatchView<T, 3>& patch, const T* offset)
{
  for (int p = 0; p < patch.pointCount(); ++p)
    for (int d = 0; d < 3; ++d)
      patch.point(p)[d] += offset[d] * patch.point(p)[kWeightChannel];
}

/// The regular degree-2 sphere, the variants above and the degree-16 sphere in a row along x, 4
/// apart (each spans about [-1.5, 1.5]^3 about its centre), attribute "sphere": one dataset of
/// the zoo's members that share the sphere's attribute (patch 7 is the self-intersecting one).
template<class T>
VolumeSet<T> makeDegenerateZoo()
{
  const std::vector<VolumeSet<T>> members = { makeMarsdenSphere<T>(2),
    makeSphereWithCollapsedEdge<T>(), makeSphereCollapsedToAPoint<T>(), makeInvertedSphere<T>(),
    makeSphereWithWideWeights<T>(), makeSphereWithConstantField<T>(),
    makeMarsdenSphere<T>(kMaxDegree), makeSelfIntersectingSphere<T>() };
  VolumeSet<T> zoo;
  zoo.attributeNames = members[0].attributeNames;
  for (const auto& member : members)
  {
    const T offset[3] = { T(4 * zoo.patches.size()), 0, 0 };
    zoo.patches.push_back(member.patches[0]);
    translatePatch(zoo.patches.back().view(), offset);
  }
  return zoo;
}

} // namespace iga
