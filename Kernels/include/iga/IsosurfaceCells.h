// The cells of an affine patch's parameter cube that may hold its isosurface: an octree of the
// field's Bernstein coefficients, halved where they straddle the isovalue, the rest dropped (a
// cell's field lies within the hull of its coefficients). Ray composition composes only the rays
// that the cells' window boxes cover: the others would find no root.
#pragma once

#include "iga/RayComposition.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace iga
{

/// A cube [lo, lo + size]^3 of the parameter cube.
struct ParameterCell
{
  glm::dvec3 lo;
  double size;
};

namespace detail
{
/// Halves a (n0+1)(n1+1)(n2+1) Bernstein tensor (index i + (n0 + 1)(j + (n1 + 1) k)) along
/// `axis` at 1/2 into `left` and `right`: de Casteljau on whole rows of the lines along `axis`
/// (the indices below it run contiguously), in place in `right`. splitMidpoint (BezierPatch.h),
/// a line at a time, takes three times as long on a one-channel tensor (measured).
inline void halveTensor(const double* c, const int* n, int axis, double* left, double* right)
{
  const size_t size[3] = { size_t(n[0] + 1), size_t(n[1] + 1), size_t(n[2] + 1) };
  const size_t row = axis == 0 ? 1 : axis == 1 ? size[0] : size[0] * size[1];
  const size_t block = row * size[axis], count = size[0] * size[1] * size[2];
  const int d = n[axis];
  std::copy(c, c + count, right);
  for (size_t base = 0; base < count; base += block)
  {
    double* work = right + base;
    std::copy(work, work + row, left + base);
    for (int r = 1; r <= d; ++r)
    {
      for (size_t q = 0; q < size_t(d - r + 1) * row; ++q)
      {
        work[q] = 0.5 * work[q] + 0.5 * work[q + row];
      }
      std::copy(work, work + row, left + base + size_t(r) * row);
    }
  }
}

/// Appends the cells of `cell` (coefficients `c`, `count` of them) down to `levels` more
/// halvings whose coefficients reach within `margin` of the isovalue. `work` holds 14 tensors
/// a level below: the halves, quarters and eighths of a split.
inline void addIsosurfaceCells(const double* c, size_t count, const int* n, ParameterCell cell,
  double isovalue, double margin, int levels, double* work, std::vector<ParameterCell>& cells)
{
  const auto range = std::minmax_element(c, c + count);
  if (*range.first > isovalue + margin || *range.second < isovalue - margin)
  {
    return;
  }
  if (levels == 0)
  {
    cells.push_back(cell);
    return;
  }
  // Halves along x (work 0, 1), quarters along y (2..5), eighths along z (6..13): eighth k has
  // bit d of k set for the upper half along d.
  const auto part = [&](int k) { return work + size_t(k) * count; };
  halveTensor(c, n, 0, part(0), part(1));
  for (int k = 0; k < 2; ++k)
  {
    halveTensor(part(k), n, 1, part(2 + k), part(4 + k));
  }
  for (int k = 0; k < 4; ++k)
  {
    halveTensor(part(2 + k), n, 2, part(6 + k), part(10 + k));
  }
  const double half = 0.5 * cell.size;
  for (int k = 0; k < 8; ++k)
  {
    const ParameterCell child{
      cell.lo + half * glm::dvec3(double(k & 1), double(k >> 1 & 1), double(k >> 2 & 1)), half
    };
    addIsosurfaceCells(
      part(6 + k), count, n, child, isovalue, margin, levels - 1, work + 14 * count, cells);
  }
}
} // namespace detail

/// How far a cell's coefficients may stand from the isovalue and still be kept, a fraction of
/// the field's largest distance from it: far above the subdivision's rounding, far below what
/// a ray's root finder could take for a root.
constexpr double kCellMargin = 1e-9;

/// The cubes of side 2^-levels of the patch's parameter cube that may hold the isosurface at
/// `isovalue` (its field's coefficients on them reach within kCellMargin of it), in octant
/// `octant` of the cube (bit d: the upper half along d), levels >= 1: the octants can be
/// worked on side by side.
inline std::vector<ParameterCell> isosurfaceCells(
  const AffinePatch& patch, double isovalue, int levels, int octant)
{
  double largest = 0;
  for (double v : patch.field)
  {
    largest = std::max(largest, std::fabs(v - isovalue));
  }
  const size_t count = patch.field.size();
  std::vector<double> work(14 * size_t(levels) * count), part(2 * count);
  // The octant's coefficients: a half along each direction.
  std::vector<double> octantField = patch.field;
  for (int d = 0; d < 3; ++d)
  {
    detail::halveTensor(octantField.data(), patch.degree, d, part.data(), part.data() + count);
    std::copy_n(part.data() + (octant >> d & 1) * count, count, octantField.data());
  }
  const ParameterCell cell{
    0.5 * glm::dvec3(double(octant & 1), double(octant >> 1 & 1), double(octant >> 2 & 1)), 0.5
  };
  std::vector<ParameterCell> cells;
  detail::addIsosurfaceCells(octantField.data(), count, patch.degree, cell, isovalue,
    kCellMargin * largest, levels - 1, work.data(), cells);
  return cells;
}

} // namespace iga
