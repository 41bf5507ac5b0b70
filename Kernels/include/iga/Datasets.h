// Generators for built-in datasets (host only, VTK-free, so the CUDA benchmarks can use them).
#pragma once

#include "iga/BezierPatch.h"

#include <cmath>
#include <string>
#include <vector>

namespace iga
{

/// Patches plus the names of their attributes (channel kFirstAttributeChannel + i is names[i]).
template<class T>
struct VolumeSet
{
  std::vector<BezierVolume<T>> patches;
  std::vector<std::string> attributeNames;
};

/// The default dataset: a thick-walled tube (inner radius 0.5, outer 1, height 2) made of 8
/// tri-quadratic rational patches (4 quadrants, exact circles through weights sqrt(2)/2, times 2
/// axial segments), deformed by a twist and a bend whose amplitude grows with `time` in [0, 1].
/// Attributes live on the material (computed at rest, moving with the deformation):
/// "temperature" = (z - 1) + 0.35 cos(3 theta) r / 0.75, whose zero set is a wavy sheet across the
/// tube, and "radius" = r, for colouring.
template<class T>
VolumeSet<T> makeTwistedTube(double time)
{
  const double kInner = 0.5, kOuter = 1.0, kHalfPi = 1.5707963267948966;
  const int degree[3] = { 2, 2, 2 }; // angular, radial, axial
  VolumeSet<T> set;
  set.attributeNames = { "temperature", "radius" };
  for (int segment = 0; segment < 2; ++segment)
  {
    for (int quadrant = 0; quadrant < 4; ++quadrant)
    {
      BezierVolume<T> patch(degree, kFirstAttributeChannel + 2);
      const auto view = patch.view();
      int p = 0;
      for (int k = 0; k <= 2; ++k)
      {
        for (int j = 0; j <= 2; ++j)
        {
          for (int i = 0; i <= 2; ++i, ++p)
          {
            const double theta = (quadrant + 0.5 * i) * kHalfPi;
            const double r = kInner + 0.5 * j * (kOuter - kInner);
            // The middle angular control point sits at the corner of the quadrant's square.
            const double scale = i == 1 ? std::sqrt(2.0) : 1.0;
            const double w = i == 1 ? std::sqrt(0.5) : 1.0;
            double x = r * scale * std::cos(theta), y = r * scale * std::sin(theta);
            double z = segment + 0.5 * k;
            const double temperature = (z - 1.0) + 0.35 * std::cos(3 * theta) * r / 0.75;
            const double radius = r;
            // Deformation of the control net: twist about the axis, then bend along x.
            const double twist = 0.6 * time * z;
            const double xt = x * std::cos(twist) - y * std::sin(twist);
            const double yt = x * std::sin(twist) + y * std::cos(twist);
            x = xt + 0.2 * time * z * z;
            y = yt;
            T* cp = view.point(p);
            cp[0] = T(w * x);
            cp[1] = T(w * y);
            cp[2] = T(w * z);
            cp[kWeightChannel] = T(w);
            cp[kFirstAttributeChannel] = T(w * temperature);
            cp[kFirstAttributeChannel + 1] = T(w * radius);
          }
        }
      }
      set.patches.push_back(std::move(patch));
    }
  }
  return set;
}

} // namespace iga
