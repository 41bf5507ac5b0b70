// Generators for built-in datasets (host only, VTK-free, so the CUDA benchmarks can use them).
#pragma once

#include "iga/BezierPatch.h"
#include "iga/Polynomial.h"

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

/// A thick-walled tube (inner radius `inner`, outer radius 1, height 2) of 8 tri-quadratic
/// rational patches: 4 quadrants (exact circles through weights sqrt(2)/2) times 2 axial
/// segments, parametrised (angle, radius, height). `inner` = 0 collapses the inner face onto the
/// axis. The control net is twisted and bent with an amplitude growing with `time` in [0, 1].
/// Attributes live on the material (computed at rest, moving with the deformation):
///  - "temperature" = (z - 1) + 0.35 cos(3 theta) r / 0.75: its zero set is a wavy sheet;
///  - "radius" = r, exactly the distance from the axis at time 0 (level sets are cylinders);
///  - "height" = z, exactly the height at every time (level sets are planar disks).
template<class T>
VolumeSet<T> makeTube(double inner, double time)
{
  const double kOuter = 1.0, kHalfPi = 1.5707963267948966;
  const int degree[3] = { 2, 2, 2 };
  VolumeSet<T> set;
  set.attributeNames = { "temperature", "radius", "height" };
  for (int segment = 0; segment < 2; ++segment)
  {
    for (int quadrant = 0; quadrant < 4; ++quadrant)
    {
      BezierVolume<T> patch(degree, kFirstAttributeChannel + 3);
      const auto view = patch.view();
      int p = 0;
      for (int k = 0; k <= 2; ++k)
      {
        for (int j = 0; j <= 2; ++j)
        {
          for (int i = 0; i <= 2; ++i, ++p)
          {
            const double theta = (quadrant + 0.5 * i) * kHalfPi;
            const double r = inner + 0.5 * j * (kOuter - inner);
            // The middle angular control point sits at the corner of the quadrant's square.
            const double scale = i == 1 ? std::sqrt(2.0) : 1.0;
            const double w = i == 1 ? std::sqrt(0.5) : 1.0;
            double x = r * scale * std::cos(theta), y = r * scale * std::sin(theta);
            const double z = segment + 0.5 * k;
            const double attributes[3] = { (z - 1.0) + 0.35 * std::cos(3 * theta) * r / 0.75, r,
              z };
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
            for (int a = 0; a < 3; ++a)
            {
              cp[kFirstAttributeChannel + a] = T(w * attributes[a]);
            }
          }
        }
      }
      set.patches.push_back(std::move(patch));
    }
  }
  return set;
}

/// The default dataset: the tube with inner radius 0.5, deformed at `time`.
template<class T>
VolumeSet<T> makeTwistedTube(double time)
{
  return makeTube<T>(0.5, time);
}

/// The SST paper's degree study: f = x^2 + y^2 + z^2 - 1 over [-1.5, 1.5]^3 as one Bézier volume
/// of the given degree (2..5 in the paper) per direction, attribute "sphere".
template<class T>
VolumeSet<T> makeMarsdenSphere(int degree)
{
  Polynomial3<T> sphere(2, 2, 2);
  sphere.at(0, 0, 0) = T(-1);
  sphere.at(2, 0, 0) = sphere.at(0, 2, 0) = sphere.at(0, 0, 2) = T(1);
  const T lo[3] = { T(-1.5), T(-1.5), T(-1.5) }, hi[3] = { T(1.5), T(1.5), T(1.5) };
  const int degrees[3] = { degree, degree, degree };
  VolumeSet<T> set;
  set.attributeNames = { "sphere" };
  set.patches.push_back(makePolynomialVolume(sphere, lo, hi, degrees));
  return set;
}

/// The teardrop 0.5 x^5 + 0.5 x^4 - y^2 - z^2 = 0 (x in [-1, 0]) in a degree (5, 2, 2) volume
/// over [-1.1, 0.1] x [-0.45, 0.45]^2 whose control net is twisted about the x axis by `twist`
/// radians per unit length: a nonlinear deformation of the embedded surface.
template<class T>
VolumeSet<T> makeTeardrop(double twist)
{
  Polynomial3<T> teardrop(5, 2, 2);
  teardrop.at(5, 0, 0) = T(0.5);
  teardrop.at(4, 0, 0) = T(0.5);
  teardrop.at(0, 2, 0) = T(-1);
  teardrop.at(0, 0, 2) = T(-1);
  const T lo[3] = { T(-1.1), T(-0.45), T(-0.45) }, hi[3] = { T(0.1), T(0.45), T(0.45) };
  const int degrees[3] = { 5, 2, 2 };
  VolumeSet<T> set;
  set.attributeNames = { "teardrop" };
  set.patches.push_back(makePolynomialVolume(teardrop, lo, hi, degrees));
  const auto view = set.patches[0].view();
  for (int p = 0; p < view.pointCount(); ++p)
  {
    T* cp = view.point(p);
    const double angle = twist * (double(cp[0]) + 1.1);
    const double y = cp[1], z = cp[2];
    cp[1] = T(std::cos(angle) * y - std::sin(angle) * z);
    cp[2] = T(std::sin(angle) * y + std::cos(angle) * z);
  }
  return set;
}

} // namespace iga
