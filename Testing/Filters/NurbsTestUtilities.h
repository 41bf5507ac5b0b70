// Independent references for the NURBS tests: Cox-de Boor evaluation of B-spline patches and VTK's
// own evaluation of the Bézier cells that vtkIGANurbsData puts out.
#pragma once

#include "iga/NurbsSet.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace igatest
{

/// All B-splines N_{i,p}(u), i = 0..count-1, by the Cox-de Boor recursion (0/0 = 0); at the end
/// of the domain the last non-empty span is used.
inline std::vector<double> coxDeBoor(const std::vector<double>& t, int p, int count, double u)
{
  const double end = t[count];
  std::vector<double> N(t.size() - 1, 0.0);
  for (size_t i = 0; i + 1 < t.size(); ++i)
  {
    const bool inside = t[i] <= u && u < t[i + 1];
    const bool atEnd = u == end && t[i] < t[i + 1] && t[i + 1] == end;
    N[i] = inside || atEnd ? 1.0 : 0.0;
  }
  for (int k = 1; k <= p; ++k)
  {
    for (size_t i = 0; i + k + 1 < t.size(); ++i)
    {
      double value = 0;
      if (t[i + k] > t[i])
        value += (u - t[i]) / (t[i + k] - t[i]) * N[i];
      if (t[i + k + 1] > t[i + 1])
        value += (t[i + k + 1] - u) / (t[i + k + 1] - t[i + 1]) * N[i + 1];
      N[i] = value;
    }
  }
  N.resize(count);
  return N;
}

/// Euclidean values (x, y, z, attributes...) of a patch at global parameter u (Dim values).
template<int Dim>
std::vector<double> evaluateNurbs(const iga::BSplinePatch<double, Dim>& patch, const double* u)
{
  std::vector<double> basis[Dim];
  for (int d = 0; d < Dim; ++d)
    basis[d] = coxDeBoor(patch.knots[d], patch.degree[d], patch.netSize[d], u[d]);
  std::vector<double> h(patch.channels, 0.0);
  const size_t points = iga::controlPointCount(patch);
  for (size_t p = 0; p < points; ++p)
  {
    double b = 1;
    size_t rest = p;
    for (int d = 0; d < Dim; ++d)
    {
      b *= basis[d][rest % patch.netSize[d]];
      rest /= patch.netSize[d];
    }
    for (int c = 0; c < patch.channels; ++c)
      h[c] += b * patch.net[p * patch.channels + c];
  }
  std::vector<double> result;
  for (int c = 0; c < patch.channels; ++c)
    if (c != iga::kWeightChannel)
      result.push_back(h[c] / h[iga::kWeightChannel]);
  return result;
}

/// The non-empty knot spans [a, b] of a knot vector, in order.
inline std::vector<std::pair<double, double>> knotSpans(const std::vector<double>& knots)
{
  std::vector<std::pair<double, double>> spans;
  for (size_t i = 0; i + 1 < knots.size(); ++i)
    if (knots[i] < knots[i + 1])
      spans.emplace_back(knots[i], knots[i + 1]);
  return spans;
}

/// VTK's evaluation of a Bézier cell at pcoords: x, y, z, then every named point array.
inline std::vector<double> evaluateCell(vtkUnstructuredGrid* grid, vtkIdType cellId,
  const double* pcoords, const std::vector<std::string>& arrays)
{
  vtkNew<vtkGenericCell> cell;
  grid->GetCell(cellId, cell);
  std::vector<double> weights(cell->GetNumberOfPoints());
  double x[3];
  int subId = 0;
  double pc[3] = { pcoords[0], pcoords[1], pcoords[2] };
  cell->EvaluateLocation(subId, pc, x, weights.data());
  std::vector<double> result(x, x + 3);
  for (const auto& name : arrays)
  {
    vtkDataArray* array = grid->GetPointData()->GetArray(name.c_str());
    double value = 0;
    for (vtkIdType p = 0; p < cell->GetNumberOfPoints(); ++p)
      value += weights[p] * array->GetComponent(cell->GetPointId(p), 0);
    result.push_back(value);
  }
  return result;
}

/// Cell id per (patch, span along each direction) from the grid's cell data.
inline std::map<std::tuple<int, int, int, int>, vtkIdType> cellsBySpan(vtkUnstructuredGrid* grid)
{
  std::map<std::tuple<int, int, int, int>, vtkIdType> cells;
  vtkDataArray* patch = grid->GetCellData()->GetArray("NurbsPatch");
  vtkDataArray* span = grid->GetCellData()->GetArray("NurbsKnotSpan");
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    cells[{ int(patch->GetComponent(c, 0)), int(span->GetComponent(c, 0)),
      int(span->GetComponent(c, 1)), int(span->GetComponent(c, 2)) }] = c;
  return cells;
}

/// Checks that the grid's Bézier cells reproduce the Cox-de Boor evaluation of every patch of
/// `set` (patch indices: volumes, then surfaces) at `samples` random parameters each; returns
/// the largest difference.
inline double compareWithCoxDeBoor(
  const iga::NurbsSet<double>& set, vtkUnstructuredGrid* grid, std::mt19937& rng, int samples)
{
  const auto cells = cellsBySpan(grid);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst = 0;
  auto check = [&](const auto& patch, int index, int dim)
  {
    std::vector<std::pair<double, double>> spans[3];
    for (int d = 0; d < dim; ++d)
      spans[d] = knotSpans(patch.knots[d]);
    for (int s = 0; s < samples; ++s)
    {
      int element[3] = { 0, 0, 0 };
      double u[3] = { 0, 0, 0 }, pcoords[3] = { 0, 0, 0 };
      for (int d = 0; d < dim; ++d)
      {
        element[d] = std::uniform_int_distribution<int>(0, int(spans[d].size()) - 1)(rng);
        pcoords[d] = unit(rng);
        const auto [a, b] = spans[d][element[d]];
        u[d] = a + pcoords[d] * (b - a);
      }
      const auto found = cells.find({ index, element[0], element[1], element[2] });
      EXPECT_NE(found, cells.end()) << "patch " << index;
      if (found == cells.end())
        return;
      const auto reference = evaluateNurbs(patch, u);
      const auto value = evaluateCell(grid, found->second, pcoords, set.attributeNames);
      for (size_t c = 0; c < reference.size(); ++c)
      {
        const double difference = std::abs(value[c] - reference[c]);
        worst = std::max(worst, difference);
        EXPECT_NEAR(value[c], reference[c], 1e-9 * (1 + std::abs(reference[c])))
          << "patch " << index << " value " << c << " at u = " << u[0] << ", " << u[1] << ", "
          << u[2];
      }
    }
  };
  int index = 0;
  for (const auto& volume : set.volumes)
    check(volume, index++, 3);
  for (const auto& surface : set.surfaces)
    check(surface, index++, 2);
  return worst;
}

} // namespace igatest
