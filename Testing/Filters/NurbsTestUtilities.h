// Independent references for the NURBS tests: Cox-de Boor evaluation of B-spline patches
// (NurbsReference.h, shared with the Kernels tests) and VTK's own evaluation of the Bézier cells
// that vtkIGANurbsData puts out.
#pragma once

#include "../Kernels/NurbsReference.h"
#include "iga/NurbsSet.h"

#include "vtkCellData.h"
#include "vtkCellValidator.h"
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
/// the largest difference. Volume v with reversed[v] is expected with its first direction
/// reversed (vtkIGANurbsData turns left-handed volumes so): parameter u of `set` is then found
/// at the mirrored knot span and cell coordinate.
inline double compareWithCoxDeBoor(const iga::NurbsSet<double>& set, vtkUnstructuredGrid* grid,
  std::mt19937& rng, int samples, const std::vector<bool>& reversed = {})
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
      if (index < int(reversed.size()) && reversed[index])
      {
        element[0] = int(spans[0].size()) - 1 - element[0];
        pcoords[0] = 1 - pcoords[0];
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

/// vtkCellValidator's verdict on every cell of `grid`, as 0 (valid) or its state bits.
inline std::vector<int> validatorStates(vtkUnstructuredGrid* grid)
{
  std::vector<int> states;
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    grid->GetCell(c, cell);
    grid->SetCellOrderAndRationalWeights(c, cell);
    states.push_back(static_cast<int>(vtkCellValidator::Check(cell, 1e-9)));
  }
  return states;
}

} // namespace igatest
