// Generators for built-in datasets (host only, VTK-free, so the CUDA benchmarks can use them).
#pragma once

#include "iga/BezierPatch.h"
#include "iga/Deformation.h"
#include "iga/NurbsSet.h"
#include "iga/Polynomial.h"
#include "iga/TeapotPatches.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
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
  // The control net is twisted about the axis, then bent along x.
  Deformation twist, bend;
  twist.amount = 0.6;
  bend.kind = DeformationKind::Bend;
  bend.amount = 0.2;
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
            const double z = segment + 0.5 * k;
            double x[3] = { r * scale * std::cos(theta), r * scale * std::sin(theta), z };
            const double attributes[3] = { (z - 1.0) + 0.35 * std::cos(3 * theta) * r / 0.75, r,
              z };
            deformPoint(twist, time, x, x);
            deformPoint(bend, time, x, x);
            T* cp = view.point(p);
            for (int d = 0; d < 3; ++d)
            {
              cp[d] = T(w * x[d]);
            }
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
  Deformation deformation;
  deformation.axis = 0;
  deformation.origin[0] = -1.1;
  deformation.amount = twist;
  deformControlPoints(deformation, 1.0, set.patches[0].view());
  return set;
}

/// Moves the control points of every patch (see Deformation.h).
template<class T>
void deform(VolumeSet<T>& set, const Deformation& deformation, double time)
{
  for (auto& patch : set.patches)
  {
    deformControlPoints(deformation, time, patch.view());
  }
}

/// Bounds of the Euclidean control points; they contain the volume (convex hull property).
template<class T>
void controlPointBounds(const VolumeSet<T>& set, double* lo, double* hi)
{
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = HUGE_VAL;
    hi[d] = -HUGE_VAL;
  }
  for (const auto& patch : set.patches)
  {
    const auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
    {
      const T* cp = view.point(p);
      for (int d = 0; d < 3; ++d)
      {
        const double x = double(cp[d]) / double(cp[kWeightChannel]);
        lo[d] = std::min(lo[d], x);
        hi[d] = std::max(hi[d], x);
      }
    }
  }
}

/// |x - centre|^2 - radius^2: negative inside the sphere.
template<class T>
Polynomial3<T> sphereField(const double* centre, double radius)
{
  Polynomial3<T> f(2, 2, 2);
  double constant = -radius * radius;
  for (int d = 0; d < 3; ++d)
  {
    int power[3] = { 0, 0, 0 };
    power[d] = 2;
    f.at(power[0], power[1], power[2]) = T(1);
    power[d] = 1;
    f.at(power[0], power[1], power[2]) = T(-2 * centre[d]);
    constant += centre[d] * centre[d];
  }
  f.at(0, 0, 0) = T(constant);
  return f;
}

/// sum_d ((x_d - centre_d) / half_d)^4 - 1: a box with rounded edges and corners (a
/// superellipsoid touching the box's face centres), negative inside.
template<class T>
Polynomial3<T> roundedBoxField(const double* centre, const double* half)
{
  Polynomial3<T> f(4, 4, 4);
  double constant = -1;
  for (int d = 0; d < 3; ++d)
  {
    // ((x - c) / h)^4 = sum_k C(4, k) x^k (-c)^(4-k) / h^4
    for (int k = 1; k <= 4; ++k)
    {
      int power[3] = { 0, 0, 0 };
      power[d] = k;
      f.at(power[0], power[1], power[2]) =
        T(binomial(4, k) * std::pow(-centre[d], 4 - k) / std::pow(half[d], 4));
    }
    constant += std::pow(centre[d] / half[d], 4);
  }
  f.at(0, 0, 0) = T(constant);
  return f;
}

struct Sphere
{
  double centre[3];
  double radius;
};

/// CSG primitives embedded in Bézier volumes, as in the SST paper's dice and cheese: the box
/// cut at `breaks` (per direction, increasing) into patches of degree 4 with two attributes:
///  - names[0]: the `box` polynomial (degree <= 4), the same in every patch;
///  - names[1]: in each patch the sphereField of the sphere inside it, or where there is none, of
///    the nearest sphere. Every sphere must lie strictly inside one patch and no patch may hold
///    two, so the zero set of names[1] is exactly the union of the spheres (negative inside).
/// Their Boolean combinations are drawn exactly by CSG frames (iga/sst/Csg.h), e.g.
/// "cube<0 - pips<0".
template<class T>
VolumeSet<T> makeSpheresInBox(const std::vector<double> (&breaks)[3], const Polynomial3<T>& box,
  const std::vector<Sphere>& spheres, const std::string (&names)[2])
{
  const int count[3] = { int(breaks[0].size()) - 1, int(breaks[1].size()) - 1,
    int(breaks[2].size()) - 1 };
  const auto cellOf = [&](const Sphere& s, int* cell)
  {
    for (int d = 0; d < 3; ++d)
    {
      cell[d] = -1;
      for (int c = 0; c < count[d]; ++c)
      {
        if (s.centre[d] - s.radius > breaks[d][c] && s.centre[d] + s.radius < breaks[d][c + 1])
        {
          cell[d] = c;
        }
      }
      if (cell[d] < 0)
      {
        return false;
      }
    }
    return true;
  };
  if (spheres.empty())
  {
    throw std::invalid_argument("no spheres to embed");
  }
  std::vector<int> owner(static_cast<size_t>(count[0]) * count[1] * count[2], -1);
  for (size_t s = 0; s < spheres.size(); ++s)
  {
    int cell[3];
    if (!cellOf(spheres[s], cell))
    {
      throw std::invalid_argument(
        "sphere " + std::to_string(s) + " does not lie strictly inside one patch");
    }
    int& slot = owner[cell[0] + count[0] * (cell[1] + count[1] * cell[2])];
    if (slot >= 0)
    {
      throw std::invalid_argument(
        "spheres " + std::to_string(slot) + " and " + std::to_string(s) + " share a patch");
    }
    slot = int(s);
  }
  const int degree[3] = { 4, 4, 4 };
  VolumeSet<T> set;
  set.attributeNames = { names[0], names[1] };
  for (int k = 0; k < count[2]; ++k)
  {
    for (int j = 0; j < count[1]; ++j)
    {
      for (int i = 0; i < count[0]; ++i)
      {
        const T lo[3] = { T(breaks[0][i]), T(breaks[1][j]), T(breaks[2][k]) };
        const T hi[3] = { T(breaks[0][i + 1]), T(breaks[1][j + 1]), T(breaks[2][k + 1]) };
        int nearest = owner[i + count[0] * (j + count[1] * k)];
        double best = HUGE_VAL;
        for (size_t s = 0; nearest < 0 && s < spheres.size(); ++s)
        {
          double distance = 0;
          for (int d = 0; d < 3; ++d)
          {
            const double centre = 0.5 * (double(lo[d]) + double(hi[d]));
            distance += (centre - spheres[s].centre[d]) * (centre - spheres[s].centre[d]);
          }
          if (distance < best)
          {
            best = distance;
            nearest = int(s);
          }
        }
        BezierVolume<T> patch = makePolynomialVolume(box, lo, hi, degree);
        const BezierVolume<T> sphere = makePolynomialVolume(
          sphereField<T>(spheres[nearest].centre, spheres[nearest].radius), lo, hi, degree);
        BezierVolume<T> both(degree, kFirstAttributeChannel + 2);
        const auto out = both.view();
        for (int p = 0; p < out.pointCount(); ++p)
        {
          std::copy(patch.view().point(p), patch.view().point(p) + kFirstAttributeChannel + 1,
            out.point(p));
          out.point(p)[kFirstAttributeChannel + 1] = sphere.view().point(p)[kFirstAttributeChannel];
        }
        set.patches.push_back(std::move(both));
      }
    }
  }
  return set;
}

/// The dice: a rounded cube x^4 + y^4 + z^4 = 1 ("cube") with 21 pips ("pips", spheres of radius
/// 0.16 centred on the cube's surface, 1 on +z, 6 on -z, 2 on +x, 5 on -x, 3 on +y, 4 on -y) in
/// [-1.25, 1.25]^3 cut at +-0.25 and +-0.75: 125 patches of degree 4, each pip in its own patch.
template<class T>
VolumeSet<T> makeDice()
{
  const double h = 0.5;
  const std::vector<std::vector<std::pair<double, double>>> faces = {
    { { 0, 0 } },
    { { -h, -h }, { h, h } },
    { { -h, -h }, { 0, 0 }, { h, h } },
    { { -h, -h }, { -h, h }, { h, -h }, { h, h } },
    { { -h, -h }, { -h, h }, { 0, 0 }, { h, -h }, { h, h } },
    { { -h, -h }, { -h, 0 }, { -h, h }, { h, -h }, { h, 0 }, { h, h } },
  };
  // (face normal axis, sign) for the faces showing 1..6: opposite faces add up to 7.
  const int axis[6] = { 2, 0, 1, 1, 0, 2 }, sign[6] = { 1, 1, 1, -1, -1, -1 };
  std::vector<Sphere> pips;
  for (int n = 0; n < 6; ++n)
  {
    for (const auto& uv : faces[n])
    {
      Sphere pip;
      pip.radius = 0.16;
      pip.centre[(axis[n] + 1) % 3] = uv.first;
      pip.centre[(axis[n] + 2) % 3] = uv.second;
      pip.centre[axis[n]] =
        sign[n] * std::pow(1 - std::pow(uv.first, 4) - std::pow(uv.second, 4), 0.25);
      pips.push_back(pip);
    }
  }
  const std::vector<double> cuts = { -1.25, -0.75, -0.25, 0.25, 0.75, 1.25 };
  const std::vector<double> breaks[3] = { cuts, cuts, cuts };
  const double centre[3] = { 0, 0, 0 }, half[3] = { 1, 1, 1 };
  return makeSpheresInBox(breaks, roundedBoxField<T>(centre, half), pips, { "cube", "pips" });
}

/// The cheese: a block of cheese, the rounded box [0, 2] x [0, 1.2] x [0, 1] ("cheese"), with 8
/// spherical holes of radii 0.14..0.22 ("holes"), five of them cutting the block's faces, in
/// [-0.1, 2.1] x [-0.1, 1.3] x [-0.1, 1.1] cut into 4 x 2 x 2 patches of degree 4.
template<class T>
VolumeSet<T> makeCheese()
{
  const std::vector<Sphere> holes = {
    { { 0.2, 0.25, 0.95 }, 0.14 },
    { { 0.25, 0.9, 0.3 }, 0.18 },
    { { 0.75, 0.3, 0.25 }, 0.22 },
    { { 0.78, 1.05, 0.8 }, 0.2 },
    { { 1.25, 0.08, 0.7 }, 0.17 },
    { { 1.22, 0.95, 0.2 }, 0.15 },
    { { 1.9, 0.3, 0.3 }, 0.18 },
    { { 1.75, 0.9, 0.85 }, 0.22 },
  };
  const std::vector<double> breaks[3] = { { -0.1, 0.5, 1.0, 1.5, 2.1 }, { -0.1, 0.6, 1.3 },
    { -0.1, 0.5, 1.1 } };
  const double centre[3] = { 1, 0.6, 0.5 }, half[3] = { 1, 0.6, 0.5 };
  return makeSpheresInBox(breaks, roundedBoxField<T>(centre, half), holes, { "cheese", "holes" });
}

/// Surfaces plus the names of their attributes, as VolumeSet.
template<class T>
struct SurfaceSet
{
  std::vector<BezierSurface<T>> patches;
  std::vector<std::string> attributeNames;
};

/// The sphere of `radius` about `centre` exactly, as 8 biquadratic rational patches: per octant
/// a quarter meridian (pole to equator, u) swept about the z axis by a quarter circle (v), both
/// rational quadratic arcs with middle weight sqrt(2)/2. Each patch's pole edge is collapsed.
/// Attribute "height" = z - centre z, exact (its control values are the points' z).
template<class T>
SurfaceSet<T> makeSphereSurfaces(double radius, const double* centre)
{
  const double h = std::sqrt(0.5);
  // Quarter meridian in the (r, z) plane from the north pole, and a quarter circle in (x, y).
  const double meridian[3][3] = { { 0, 1, 1 }, { 1, 1, h }, { 1, 0, 1 } }; // r, z, weight
  const double arc[3][3] = { { 1, 0, 1 }, { 1, 1, h }, { 0, 1, 1 } };      // x, y, weight
  SurfaceSet<T> set;
  set.attributeNames = { "height" };
  const int degree[2] = { 2, 2 };
  for (int octant = 0; octant < 8; ++octant)
  {
    const double quarter = (octant % 4) * 1.5707963267948966, c = std::cos(quarter),
                 sn = std::sin(quarter), zSign = octant < 4 ? 1.0 : -1.0;
    BezierSurface<T> patch(degree, kFirstAttributeChannel + 1);
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        const double x = arc[j][0] * c - arc[j][1] * sn, y = arc[j][0] * sn + arc[j][1] * c;
        const double r = meridian[i][0], z = zSign * meridian[i][1];
        const double w = meridian[i][2] * arc[j][2];
        T* cp = patch.view().point(j * 3 + i);
        cp[0] = T(w * (centre[0] + radius * r * x));
        cp[1] = T(w * (centre[1] + radius * r * y));
        cp[2] = T(w * (centre[2] + radius * z));
        cp[kWeightChannel] = T(w);
        cp[kFirstAttributeChannel] = T(w * radius * z);
      }
    }
    set.patches.push_back(std::move(patch));
  }
  return set;
}

/// One of the 32 bicubic Bézier patches of the Utah teapot (standard layout, weights 1).
template<class T>
BezierSurface<T> makeTeapotSurface(int index)
{
  const int degree[2] = { 3, 3 };
  BezierSurface<T> surface(degree, kFirstAttributeChannel);
  for (int p = 0; p < 16; ++p)
  {
    T* cp = surface.view().point(p);
    for (int d = 0; d < 3; ++d)
    {
      cp[d] = T(kTeapotControlPoints[index][p][d]);
    }
    cp[kWeightChannel] = T(1);
  }
  return surface;
}

/// The Utah teapot: its 32 bicubic Bézier patches (polynomial), attribute "height" = z exactly.
template<class T>
SurfaceSet<T> makeTeapot()
{
  SurfaceSet<T> set;
  set.attributeNames = { "height" };
  const int degree[2] = { 3, 3 };
  for (int index = 0; index < 32; ++index)
  {
    const BezierSurface<T> geometry = makeTeapotSurface<T>(index);
    BezierSurface<T> patch(degree, kFirstAttributeChannel + 1);
    for (int p = 0; p < 16; ++p)
    {
      const T* from = geometry.view().point(p);
      T* to = patch.view().point(p);
      std::copy(from, from + kFirstAttributeChannel, to);
      to[kFirstAttributeChannel] = from[2];
    }
    set.patches.push_back(std::move(patch));
  }
  return set;
}

/// The teapot as a thin shell volume for isosurface rendering: per patch, degree (3, 3, 1), the
/// control points P_ij -+ thickness/2 n_ij at w = 0 / 1, n_ij the unit surface normal at the
/// parameter (i/3, j/3) (taken slightly inside where the patch is degenerate). Attributes:
///  - "shell" = (w - 1/2) thickness: zero exactly on the teapot surface V(u, v, 1/2) = S(u, v);
///    its sign follows each patch's orientation;
///  - "height" = z, exactly (the attribute's control values are the control points' z).
template<class T>
VolumeSet<T> makeTeapotShell(double thickness)
{
  const int degree[3] = { 3, 3, 1 };
  VolumeSet<T> set;
  set.attributeNames = { "shell", "height" };
  for (int s = 0; s < kTeapotPatchCount; ++s)
  {
    const BezierSurface<double> surface = makeTeapotSurface<double>(s);
    BezierVolume<T> patch(degree, kFirstAttributeChannel + 2);
    for (int j = 0; j <= 3; ++j)
    {
      for (int i = 0; i <= 3; ++i)
      {
        double normal[3] = { 0, 0, 0 }, length = 0;
        for (double shrink = 1; length < 1e-9 && shrink > 0.9; shrink -= 0.01)
        {
          const double u[2] = { 0.5 + shrink * (i / 3.0 - 0.5), 0.5 + shrink * (j / 3.0 - 0.5) };
          // Sized for the 6 channels evaluation's compile-time shapes write: GCC cannot tell that
          // they are not taken for these 4 and warns of writes past the arrays.
          double values[6] = {}, derivatives[2 * 6] = {};
          evaluateHomogeneous<double, 2>(surface.view(), u, values, derivatives);
          const double* du = derivatives;
          const double* dv = derivatives + kFirstAttributeChannel;
          normal[0] = du[1] * dv[2] - du[2] * dv[1];
          normal[1] = du[2] * dv[0] - du[0] * dv[2];
          normal[2] = du[0] * dv[1] - du[1] * dv[0];
          length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        }
        const double* point = surface.view().point(i + 4 * j);
        for (int k = 0; k <= 1; ++k)
        {
          const double offset = (k - 0.5) * thickness;
          T* cp = patch.view().point(i + 4 * j + 16 * k);
          for (int d = 0; d < 3; ++d)
          {
            cp[d] = T(point[d] + offset * normal[d] / length);
          }
          cp[kWeightChannel] = T(1);
          cp[kFirstAttributeChannel] = T(offset);
          cp[kFirstAttributeChannel + 1] = cp[2];
        }
      }
    }
    set.patches.push_back(std::move(patch));
  }
  return set;
}

/// Patch counts of the wind-blade-like volume: around the airfoil x through the wall (2) x
/// along the span, at least the requested total, `around` a multiple of 4 near sqrt(total / 8).
struct BladeLayout
{
  long around = 8;
  long through = 2;
  long along = 1;
  long patchCount() const { return around * through * along; }
};

inline BladeLayout bladeLayout(long minPatches)
{
  BladeLayout layout;
  layout.around = std::max(8L, 4 * long(std::ceil(std::sqrt(minPatches / 8.0) / 4)));
  layout.along = std::max(1L, (minPatches + 2 * layout.around - 1) / (2 * layout.around));
  return layout;
}

/// The blade at parameters phi (around, periodic), rho (wall: 0 inside, 1 outside) and s (span):
/// length 10 along z, chord 1.2 -> 0.4, thickness 40% -> 12% of the chord, an asymmetric
/// elliptic section pre-twisted by 0.4 (1 - s) radians. `strain` gets the normalised thickness
/// coordinate times (1 - s)^2 (a bending-strain-like field in [-1, 1]).
inline void bladePoint(double phi, double rho, double s, double* x, double* strain)
{
  const double kTwoPi = 6.283185307179586;
  const double chord = 1.2 - 0.8 * s, ratio = 0.4 - 0.28 * s, wall = 0.85 + 0.15 * rho;
  const double theta = kTwoPi * phi;
  const double across = std::sin(theta) * (0.75 + 0.25 * std::cos(theta));
  const double u = wall * 0.5 * chord * std::cos(theta);
  const double v = wall * 0.5 * chord * ratio * across;
  const double twist = 0.4 * (1 - s);
  x[0] = std::cos(twist) * u - std::sin(twist) * v;
  x[1] = std::sin(twist) * u + std::cos(twist) * v;
  x[2] = 10 * s;
  *strain = (1 - s) * (1 - s) * wall * across;
}

/// Patches [first, first + count) of the blade (count < 0: to the end), degree (2, 1, 2)
/// non-rational, control points sampled from bladePoint on the patches' parameter grids so
/// neighbours share their boundary points exactly. Attributes "strain" and "span" (= s). The
/// blade flaps with `time`: a Bend along y of 1.5 (15% of the length) at the tip at time 1.
template<class T>
VolumeSet<T> makeBlade(const BladeLayout& layout, double time, long first = 0, long count = -1)
{
  const long total = layout.patchCount();
  const long last = count < 0 ? total : std::min(total, first + count);
  Deformation flap;
  flap.kind = DeformationKind::Bend;
  flap.axis = 2;
  flap.direction = 1;
  flap.amount = 0.015;
  const int degree[3] = { 2, 1, 2 };
  VolumeSet<T> set;
  set.attributeNames = { "strain", "span" };
  for (long index = first; index < last; ++index)
  {
    const long a = index % layout.around;
    const long t = (index / layout.around) % layout.through;
    const long l = index / (layout.around * layout.through);
    BezierVolume<T> patch(degree, kFirstAttributeChannel + 2);
    const auto view = patch.view();
    int p = 0;
    for (int k = 0; k <= 2; ++k)
    {
      for (int j = 0; j <= 1; ++j)
      {
        for (int i = 0; i <= 2; ++i, ++p)
        {
          // Integer numerators (phi wrapped to 0 at the seam): neighbours compute bit-identical
          // shared points.
          const double phi = double((2 * a + i) % (2 * layout.around)) / double(2 * layout.around);
          const double rho = double(t + j) / double(layout.through);
          const double s = double(2 * l + k) / double(2 * layout.along);
          double x[3], strain;
          bladePoint(phi, rho, s, x, &strain);
          deformPoint(flap, time, x, x);
          T* cp = view.point(p);
          for (int d = 0; d < 3; ++d)
          {
            cp[d] = T(x[d]);
          }
          cp[kWeightChannel] = T(1);
          cp[kFirstAttributeChannel] = T(strain);
          cp[kFirstAttributeChannel + 1] = T(s);
        }
      }
    }
    set.patches.push_back(std::move(patch));
  }
  return set;
}

/// A rational B-spline ball: degree 2 in each direction on spans^3 elements (open uniform
/// knots), control points at the Greville abscissae of [-1.2, 1.2]^3 stretched along x by
/// `stretch`, weights 1 + 0.15 sin(3x + 2y - z), and the attribute |x|^2 - 1 sampled at the
/// control points (one channel). Only the net depends on `stretch`: a deforming volume whose
/// knots, and so whose extraction operators, stay.
template<class T>
BSplinePatch<T, 3> makeNurbsBall(int spans, double stretch)
{
  BSplinePatch<T, 3> ball;
  for (int d = 0; d < 3; ++d)
  {
    ball.degree[d] = 2;
    ball.netSize[d] = spans + 2;
    ball.knots[d] = { T(0), T(0) };
    for (int s = 0; s <= spans; ++s)
    {
      ball.knots[d].push_back(T(s) / T(spans));
    }
    ball.knots[d].insert(ball.knots[d].end(), { T(1), T(1) });
  }
  const std::vector<T> greville = grevilleAbscissae(ball.knots[0], 2, spans + 2);
  ball.channels = kFirstAttributeChannel + 1;
  for (int k = 0; k < spans + 2; ++k)
    for (int j = 0; j < spans + 2; ++j)
      for (int i = 0; i < spans + 2; ++i)
      {
        const double x = stretch * (2.4 * double(greville[i]) - 1.2),
                     y = 2.4 * double(greville[j]) - 1.2, z = 2.4 * double(greville[k]) - 1.2;
        const double w = 1 + 0.15 * std::sin(3 * x + 2 * y - z);
        const double a = x * x + y * y + z * z - 1;
        for (double v : { w * x, w * y, w * z, w, w * a })
        {
          ball.net.push_back(T(v));
        }
      }
  return ball;
}

} // namespace iga
