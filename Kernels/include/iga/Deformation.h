// Synthetic deformations of control nets (host only, VTK-free): twist, bend, wave and a
// free-form deformation (FFD) lattice, each scaled by a time parameter so that time 0 is the
// identity and a sequence of times gives an animation.
//
// A map D applied to the control points P_i of a rational Bézier volume sum_i w_i B_i P_i / sum_i
// w_i B_i gives the volume sum_i w_i B_i D(P_i) / sum_i w_i B_i: again a spline of the same degrees
// and weights, which is what solvers and animation systems produce (they move control points).
// It is the composition D o V only where D is affine (e.g. the rotation of a twist restricted to
// one cross-section is not); attributes stay on the material, as they do in the SST paper's
// deforming datasets. The FFD lattice is applied the same way (to the control points, not
// composed exactly: the exact composition of a degree-(l,m,n) lattice with a degree-p volume
// would have degree (l+m+n) p per direction).
#pragma once

#include "iga/BezierPatch.h"

#include <cmath>
#include <string>
#include <vector>

namespace iga
{

enum class DeformationKind
{
  Twist,  ///< rotation about the axis by time * amount * a radians
  Bend,   ///< x[direction] += time * amount * a^2
  Wave,   ///< x[direction] += time * amount * sin(2 pi (a / wavelength - time))
  Lattice ///< (1 - time) x + time L(x), L the trivariate Bernstein lattice map
};

/// Sederberg-Parry FFD lattice: L(x) = sum_ijk B_i(s_0) B_j(s_1) B_k(s_2) P_ijk with
/// s = (x - lo) / (hi - lo); points holds 3 values per lattice point, first direction fastest.
struct DeformationLattice
{
  int degree[3] = { 1, 1, 1 };
  double lo[3] = { 0, 0, 0 };
  double hi[3] = { 1, 1, 1 };
  std::vector<double> points;

  int pointCount() const { return (degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1); }
  double* point(int i, int j, int k)
  {
    return points.data() + 3 * (i + (degree[0] + 1) * (j + (degree[1] + 1) * k));
  }
};

/// One deformation. The axial coordinate is a = x[axis] - origin[axis]; a twist turns about the
/// line through `origin` along `axis`.
struct Deformation
{
  DeformationKind kind = DeformationKind::Twist;
  int axis = 2;
  int direction = 0; ///< displaced coordinate of Bend and Wave (not the axis)
  double origin[3] = { 0, 0, 0 };
  double amount = 0;     ///< twist: radians per unit length; bend: curvature k; wave: amplitude
  double wavelength = 1; ///< Wave only
  DeformationLattice lattice; ///< Lattice only: the lattice reached at time 1
};

/// The lattice whose map is the identity: P_ijk on the regular grid of the box (Bernstein
/// polynomials reproduce linear functions).
inline DeformationLattice identityLattice(const double* lo, const double* hi, const int* degree)
{
  DeformationLattice lattice;
  for (int d = 0; d < 3; ++d)
  {
    lattice.degree[d] = degree[d];
    lattice.lo[d] = lo[d];
    lattice.hi[d] = hi[d];
  }
  lattice.points.resize(3 * static_cast<size_t>(lattice.pointCount()));
  for (int k = 0; k <= degree[2]; ++k)
  {
    for (int j = 0; j <= degree[1]; ++j)
    {
      for (int i = 0; i <= degree[0]; ++i)
      {
        const int ijk[3] = { i, j, k };
        double* p = lattice.point(i, j, k);
        for (int d = 0; d < 3; ++d)
        {
          p[d] = lo[d] + (hi[d] - lo[d]) * ijk[d] / degree[d];
        }
      }
    }
  }
  return lattice;
}

/// Empty when the deformation is usable, else one sentence naming the problem.
inline std::string checkDeformation(const Deformation& deformation)
{
  const auto finite = [](double v) { return std::isfinite(v); };
  if (deformation.axis < 0 || deformation.axis > 2)
  {
    return "deformation axis " + std::to_string(deformation.axis) + " is not 0, 1 or 2";
  }
  if (!finite(deformation.amount) || !finite(deformation.origin[0]) ||
      !finite(deformation.origin[1]) || !finite(deformation.origin[2]))
  {
    return "deformation amount or origin is not finite";
  }
  const bool displaces =
    deformation.kind == DeformationKind::Bend || deformation.kind == DeformationKind::Wave;
  if (displaces && (deformation.direction < 0 || deformation.direction > 2 ||
                     deformation.direction == deformation.axis))
  {
    return "displacement direction " + std::to_string(deformation.direction) +
           " must be 0, 1 or 2 and differ from the axis " + std::to_string(deformation.axis);
  }
  if (deformation.kind == DeformationKind::Wave &&
      !(deformation.wavelength > 0 && finite(deformation.wavelength)))
  {
    return "wavelength " + std::to_string(deformation.wavelength) + " is not positive";
  }
  if (deformation.kind == DeformationKind::Lattice)
  {
    const DeformationLattice& lattice = deformation.lattice;
    for (int d = 0; d < 3; ++d)
    {
      if (lattice.degree[d] < 1 || lattice.degree[d] > kMaxDegree)
      {
        return "lattice degree " + std::to_string(lattice.degree[d]) + " in direction " +
               std::to_string(d) + " is outside 1.." + std::to_string(kMaxDegree);
      }
      if (!(lattice.lo[d] < lattice.hi[d]) || !finite(lattice.lo[d]) || !finite(lattice.hi[d]))
      {
        return "lattice box is empty or not finite in direction " + std::to_string(d);
      }
    }
    if (lattice.points.size() != 3 * static_cast<size_t>(lattice.pointCount()))
    {
      return "lattice has " + std::to_string(lattice.points.size()) + " coordinates, degrees " +
             std::to_string(lattice.degree[0]) + "x" + std::to_string(lattice.degree[1]) + "x" +
             std::to_string(lattice.degree[2]) + " need " +
             std::to_string(3 * lattice.pointCount());
    }
    for (size_t i = 0; i < lattice.points.size(); ++i)
    {
      if (!finite(lattice.points[i]))
      {
        return "lattice point " + std::to_string(i / 3) + " is not finite";
      }
    }
  }
  return std::string();
}

/// L(x) of the lattice (a polynomial, so points outside the box are extrapolated).
inline void evaluateLattice(const DeformationLattice& lattice, const double* x, double* out)
{
  double basis[3][kMaxOrder];
  for (int d = 0; d < 3; ++d)
  {
    const double s = (x[d] - lattice.lo[d]) / (lattice.hi[d] - lattice.lo[d]);
    bernsteinBasis(lattice.degree[d], s, basis[d], static_cast<double*>(nullptr));
  }
  out[0] = out[1] = out[2] = 0;
  const double* p = lattice.points.data();
  for (int k = 0; k <= lattice.degree[2]; ++k)
  {
    for (int j = 0; j <= lattice.degree[1]; ++j)
    {
      for (int i = 0; i <= lattice.degree[0]; ++i, p += 3)
      {
        const double b = basis[0][i] * basis[1][j] * basis[2][k];
        for (int d = 0; d < 3; ++d)
        {
          out[d] += b * p[d];
        }
      }
    }
  }
}

/// The deformed position of the Euclidean point x at `time` (checkDeformation must pass).
/// `out` may alias `x`.
inline void deformPoint(const Deformation& deformation, double time, const double* x, double* out)
{
  const double a = x[deformation.axis] - deformation.origin[deformation.axis];
  double y[3] = { x[0], x[1], x[2] };
  switch (deformation.kind)
  {
    case DeformationKind::Twist:
    {
      const int p = (deformation.axis + 1) % 3, q = (deformation.axis + 2) % 3;
      const double angle = time * deformation.amount * a;
      const double c = std::cos(angle), s = std::sin(angle);
      const double u = x[p] - deformation.origin[p], v = x[q] - deformation.origin[q];
      y[p] = deformation.origin[p] + c * u - s * v;
      y[q] = deformation.origin[q] + s * u + c * v;
      break;
    }
    case DeformationKind::Bend:
      y[deformation.direction] += time * deformation.amount * a * a;
      break;
    case DeformationKind::Wave:
    {
      const double kTwoPi = 6.283185307179586;
      y[deformation.direction] +=
        time * deformation.amount * std::sin(kTwoPi * (a / deformation.wavelength - time));
      break;
    }
    case DeformationKind::Lattice:
    {
      double lattice[3];
      evaluateLattice(deformation.lattice, x, lattice);
      for (int d = 0; d < 3; ++d)
      {
        y[d] = (1 - time) * x[d] + time * lattice[d];
      }
      break;
    }
  }
  for (int d = 0; d < 3; ++d)
  {
    out[d] = y[d];
  }
}

/// Moves the control points of a patch in the standard homogeneous layout: the Euclidean point
/// (w x, w) becomes (w D(x), w); weights and attributes are unchanged.
template<class T>
void deformControlPoints(const Deformation& deformation, double time, const VolumeView<T>& patch)
{
  for (int p = 0; p < patch.pointCount(); ++p)
  {
    T* cp = patch.point(p);
    const double w = double(cp[kWeightChannel]);
    double x[3] = { cp[0] / w, cp[1] / w, cp[2] / w };
    deformPoint(deformation, time, x, x);
    for (int d = 0; d < 3; ++d)
    {
      cp[d] = T(w * x[d]);
    }
  }
}

/// A deformation sized to the box [lo, hi] (e.g. a dataset's bounds), as the synthetic
/// deformation filter and the generator's time series use it. The axial coordinate runs from
/// lo[axis]; over its length L, at time 1:
///  - Twist: the far end turns by `amount` radians about the box's central line;
///  - Bend: the far end moves by amount * L along direction (axis + 1) % 3 (parabolic);
///  - Wave: amplitude amount * L along (axis + 1) % 3, wavelength `wavelength` * L, travelling;
///  - Lattice: a bulge: the lattice has degree 2 along the axis and 1 across, and its middle
///    layer is scaled about the central line by 1 + amount, so
///    x_perp -> x_perp + time * amount * 2 s (1 - s) (x_perp - centre_perp), s = a / L.
/// A zero extent along the axis (or across it, for the lattice) leaves an invalid deformation
/// that checkDeformation reports.
inline Deformation boxDeformation(DeformationKind kind, int axis, const double* lo,
  const double* hi, double amount, double wavelength)
{
  Deformation deformation;
  deformation.kind = kind;
  deformation.axis = axis;
  deformation.direction = (axis + 1) % 3;
  if (axis < 0 || axis > 2)
  {
    return deformation;
  }
  for (int d = 0; d < 3; ++d)
  {
    deformation.origin[d] = d == axis ? lo[d] : 0.5 * (lo[d] + hi[d]);
  }
  const double length = hi[axis] - lo[axis];
  switch (kind)
  {
    case DeformationKind::Twist:
    case DeformationKind::Bend:
      deformation.amount = amount / length;
      break;
    case DeformationKind::Wave:
      deformation.amount = amount * length;
      deformation.wavelength = wavelength * length;
      break;
    case DeformationKind::Lattice:
    {
      int degree[3] = { 1, 1, 1 };
      degree[axis] = 2;
      deformation.lattice = identityLattice(lo, hi, degree);
      for (int k = 0; k < 2; ++k)
      {
        for (int j = 0; j < 2; ++j)
        {
          int index[3];
          index[axis] = 1; // the middle layer

          index[(axis + 1) % 3] = k;
          index[(axis + 2) % 3] = j;
          double* p = deformation.lattice.point(index[0], index[1], index[2]);
          for (int d = 0; d < 3; ++d)
          {
            if (d != axis)
            {
              p[d] = deformation.origin[d] + (1 + amount) * (p[d] - deformation.origin[d]);
            }
          }
        }
      }
      break;
    }
  }
  return deformation;
}

} // namespace iga
