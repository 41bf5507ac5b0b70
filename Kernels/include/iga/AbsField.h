// Algebraic B-spline (ABS) fields, the scenes of Wei and Feng: a trivariate B-spline scalar field
// over a box (uniform open knots, degree p per direction, cells[d] elements) fitted to an implicit
// shape, its zero set the surface. Its elements have affine geometry (the net's points at the
// Greville abscissae reproduce the box's coordinates), so ray composition draws them; elements
// whose coefficients share a sign hold no surface (convex hull) and are dropped.
#pragma once

#include "iga/BSpline.h"
#include "iga/Datasets.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace iga
{

/// Most elements an ABS field may have along a direction.
constexpr int kMaxAbsCells = 64;

struct AbsField
{
  VolumeSet<double> set; ///< the elements kept, attribute "f"
  size_t elements = 0;   ///< elements before the dropping
};

/// The ABS field of degree `degree` (1..3) with cells[d] (1..kMaxAbsCells) uniform elements per
/// direction over the box (x0, x1, y0, y1, z0, z1) whose coefficients are f's values at the
/// Greville points (Schoenberg's variation-diminishing spline: it follows f's sign pattern, and
/// reproduces f where f is of degree at most 1). std::invalid_argument for degrees, cells or a
/// box out of range, and for values of f that are not finite.
template<class Field>
AbsField makeAbsField(Field f, const double* box, int degree, const int* cells)
{
  if (degree < 1 || degree > 3)
  {
    throw std::invalid_argument("ABS degree " + std::to_string(degree) + " is not 1, 2 or 3");
  }
  BSplinePatch<double, 3> spline;
  spline.channels = kFirstAttributeChannel + 1;
  for (int d = 0; d < 3; ++d)
  {
    if (cells[d] < 1 || cells[d] > kMaxAbsCells)
    {
      throw std::invalid_argument("ABS cells " + std::to_string(cells[d]) + " in direction " +
                                  std::to_string(d) + " are not in 1.." +
                                  std::to_string(kMaxAbsCells));
    }
    if (!(box[2 * d] < box[2 * d + 1]) || !std::isfinite(box[2 * d]) ||
        !std::isfinite(box[2 * d + 1]))
    {
      throw std::invalid_argument(
        "box: direction " + std::to_string(d) + " is not a finite interval");
    }
    spline.degree[d] = degree;
    spline.netSize[d] = cells[d] + degree;
    auto& knots = spline.knots[d];
    knots.assign(size_t(degree), 0.0);
    for (int k = 0; k <= cells[d]; ++k)
    {
      knots.push_back(double(k) / cells[d]);
    }
    knots.insert(knots.end(), size_t(degree), 1.0);
  }
  const int n0 = spline.netSize[0], n1 = spline.netSize[1], n2 = spline.netSize[2];
  spline.net.resize(size_t(n0) * n1 * n2 * size_t(spline.channels));
  for (int k = 0; k < n2; ++k)
  {
    for (int j = 0; j < n1; ++j)
    {
      for (int i = 0; i < n0; ++i)
      {
        const int index[3] = { i, j, k };
        double x[3];
        for (int d = 0; d < 3; ++d)
        {
          double greville = 0;
          for (int r = 1; r <= degree; ++r)
          {
            greville += spline.knots[d][size_t(index[d] + r)];
          }
          greville /= degree;
          x[d] = box[2 * d] + greville * (box[2 * d + 1] - box[2 * d]);
        }
        const double value = f(x[0], x[1], x[2]);
        if (!std::isfinite(value))
        {
          throw std::invalid_argument("the field is not finite at (" + std::to_string(x[0]) + ", " +
                                      std::to_string(x[1]) + ", " + std::to_string(x[2]) + ")");
        }
        double* point = &spline.net[((size_t(k) * n1 + j) * n0 + i) * size_t(spline.channels)];
        point[0] = x[0];
        point[1] = x[1];
        point[2] = x[2];
        point[kWeightChannel] = 1;
        point[kFirstAttributeChannel] = value;
      }
    }
  }
  AbsField field;
  field.set.attributeNames = { "f" };
  auto elements = extractBezier(spline);
  field.elements = elements.size();
  for (auto& element : elements)
  {
    const auto view = element.view();
    bool below = false, above = false;
    for (int p = 0; p < view.pointCount(); ++p)
    {
      below = below || view.point(p)[kFirstAttributeChannel] <= 0;
      above = above || view.point(p)[kFirstAttributeChannel] >= 0;
    }
    if (below && above)
    {
      field.set.patches.push_back(std::move(element));
    }
  }
  return field;
}

} // namespace iga
