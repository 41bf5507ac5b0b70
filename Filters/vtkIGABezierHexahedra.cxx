#include "vtkIGABezierHexahedra.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkHigherOrderHexahedron.h"
#include "vtkHigherOrderQuadrilateral.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Orientation.h"
#include "iga/Validation.h"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
const char* const kWeightsName = "RationalWeights";
const char* const kDegreesName = "HigherOrderDegrees";

/// A number as a user wrote it (2.9, 1e+30), not std::to_string's fixed six decimals.
std::string formatNumber(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

/// An array's name, empty when it has none (or there is no array).
std::string arrayName(vtkDataArray* array)
{
  return array && array->GetName() ? array->GetName() : "";
}

/// Consecutive point arrays NAME_0, NAME_1, NAME_2 (a vector field's components, as the readers
/// name them) also as one 3-component array NAME, which filters taking vectors take (e.g.
/// vtkIGADisplaceControlPoints' displacement); the components stay the attributes drawn.
void addVectorArrays(vtkPointData* data)
{
  const int count = data->GetNumberOfArrays();
  for (int a = 0; a + 2 < count; ++a)
  {
    const std::string name = data->GetArrayName(a) ? data->GetArrayName(a) : "";
    if (name.size() < 3 || name.compare(name.size() - 2, 2, "_0") != 0)
      continue;
    const std::string stem = name.substr(0, name.size() - 2);
    vtkDataArray* parts[3] = { data->GetArray(a), data->GetArray(a + 1), data->GetArray(a + 2) };
    if (arrayName(parts[1]) != stem + "_1" || arrayName(parts[2]) != stem + "_2" ||
        data->GetArray(stem.c_str()))
      continue;
    vtkNew<vtkDoubleArray> vector;
    vector->SetName(stem.c_str());
    vector->SetNumberOfComponents(3);
    vector->SetNumberOfTuples(parts[0]->GetNumberOfTuples());
    for (vtkIdType t = 0; t < vector->GetNumberOfTuples(); ++t)
      for (int c = 0; c < 3; ++c)
        vector->SetComponent(t, c, parts[c]->GetComponent(t, 0));
    data->AddArray(vector);
  }
}

/// What is wrong with a point that iga::firstInvalidPoint refused, in the file's terms: its id,
/// and the array or coordinate by name.
std::string pointProblem(vtkUnstructuredGrid* grid, vtkIdType id, vtkDataArray* weights,
  const std::vector<vtkDataArray*>& attributes)
{
  const std::string point = "point " + std::to_string(id);
  const std::string weightName = "rational weight ('" + arrayName(weights) + "')";
  double x[3];
  grid->GetPoint(id, x);
  const double w = weights ? weights->GetComponent(id, 0) : 1.0;
  for (int d = 0; d < 3; ++d)
  {
    if (!std::isfinite(x[d]))
    {
      return point + ": its " + "xyz"[d] + " coordinate is " + formatNumber(x[d]);
    }
  }
  if (!(w > 0) || !std::isfinite(w))
  {
    return point + ": its " + weightName + " is " + formatNumber(w) +
           ", weights must be positive and finite";
  }
  for (vtkDataArray* array : attributes)
  {
    const double value = array->GetComponent(id, 0);
    if (!std::isfinite(value))
    {
      return point + ": its value of '" + array->GetName() + "' is " + formatNumber(value);
    }
  }
  const std::string at =
    " at (" + formatNumber(x[0]) + ", " + formatNumber(x[1]) + ", " + formatNumber(x[2]) + ")";
  if (std::abs(x[0]) > iga::kMaxCoordinate || std::abs(x[1]) > iga::kMaxCoordinate ||
      std::abs(x[2]) > iga::kMaxCoordinate)
  {
    return point + at + " lies beyond 1e+100, farther than double precision can frame";
  }
  return point + at + ": its values times its " + weightName + ", " + formatNumber(w) +
         ", pass what double precision holds";
}

/// Calls fn(linear Kernels index, VTK point index within the cell) for every control point of a
/// hexahedron (Dim 3) or quadrilateral (Dim 2) of the given degrees; `mirrored` puts point
/// (i, j, k) where (degree - i, j, k) goes, which turns a left-handed patch into a right-handed
/// cell of the same volume.
template<int Dim = 3, class Fn>
void forEachControlPoint(const int* degree, bool mirrored, Fn fn)
{
  int linear = 0;
  for (int k = 0; k <= (Dim == 3 ? degree[2] : 0); ++k)
  {
    for (int j = 0; j <= degree[1]; ++j)
    {
      for (int i = 0; i <= degree[0]; ++i, ++linear)
      {
        const int first = mirrored ? degree[0] - i : i;
        fn(linear, Dim == 3 ? vtkHigherOrderHexahedron::PointIndexFromIJK(first, j, k, degree)
                            : vtkHigherOrderQuadrilateral::PointIndexFromIJK(first, j, degree));
      }
    }
  }
}

/// The grid's arrays the conversion reads.
struct GridArrays
{
  vtkDataArray* weights = nullptr;
  vtkDataArray* degrees = nullptr;
  std::vector<vtkDataArray*> attributes; ///< one-component point arrays, in order
};

/// "SUBJECT N UNIT for M WHAT" when an array's size does not match the grid, else "".
std::string sizeProblem(
  const std::string& subject, vtkIdType count, const char* unit, vtkIdType expected, const char* of)
{
  return count == expected ? std::string()
                           : subject + " " + std::to_string(count) + " " + unit + " for " +
                               std::to_string(expected) + " " + of;
}

/// Finds the weights (active, or by their usual name with a warning), the degrees (likewise)
/// and the attributes, and checks their shapes against the grid; returns "" or the problem.
std::string findArrays(
  vtkUnstructuredGrid* grid, GridArrays& arrays, std::vector<std::string>& warnings)
{
  vtkPointData* pd = grid->GetPointData();
  vtkDataArray*& weights = arrays.weights;
  weights = pd->GetRationalWeights();
  if (!weights && (weights = pd->GetArray(kWeightsName)))
  {
    warnings.push_back(
      std::string("point array '") + kWeightsName +
      "' is not flagged as the active rational weights; VTK ignores it, IGAView uses it");
  }
  if (!weights)
  {
    warnings.push_back("no rational weights: all weights are taken as 1 (polynomial cells)");
  }
  vtkDataArray*& degrees = arrays.degrees;
  degrees = grid->GetCellData()->GetHigherOrderDegrees();
  if (!degrees && (degrees = grid->GetCellData()->GetArray(kDegreesName)))
  {
    warnings.push_back(
      std::string("cell array '") + kDegreesName +
      "' is not flagged as the active higher-order degrees; VTK ignores it, IGAView uses it");
  }
  if (degrees && degrees->GetNumberOfComponents() != 3)
  {
    return std::string("cell array '") + kDegreesName + "' has " +
           std::to_string(degrees->GetNumberOfComponents()) + " components, expected 3";
  }
  if (weights && weights->GetNumberOfComponents() != 1)
  {
    return "rational weights '" + arrayName(weights) + "' have " +
           std::to_string(weights->GetNumberOfComponents()) + " components, expected 1";
  }
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (array && array != weights && array->GetNumberOfComponents() == 1 && array->GetName())
    {
      arrays.attributes.push_back(array);
    }
  }
  const vtkIdType points = grid->GetNumberOfPoints();
  std::string problem;
  for (vtkDataArray* array : arrays.attributes)
  {
    problem = sizeProblem(std::string("point array '") + array->GetName() + "' has",
      array->GetNumberOfTuples(), "values", points, "points");
    if (!problem.empty())
    {
      return problem;
    }
  }
  if (weights)
  {
    problem = sizeProblem(
      "rational weights have", weights->GetNumberOfTuples(), "values", points, "points");
  }
  if (problem.empty() && degrees)
  {
    problem = sizeProblem(std::string("cell array '") + kDegreesName + "' has",
      degrees->GetNumberOfTuples(), "tuples", grid->GetNumberOfCells(), "cells");
  }
  return problem;
}

/// The parametric dimension of a cell type IGAView reads: 3 for hexahedra, 2 for
/// quadrilaterals, 0 for any other.
int cellDimension(int type)
{
  return type == VTK_HEXAHEDRON || type == VTK_BEZIER_HEXAHEDRON ? 3
         : type == VTK_QUAD || type == VTK_BEZIER_QUADRILATERAL  ? 2
                                                                 : 0;
}

/// The degrees of cell c of dimension `dim`: from the degrees array, or VTK's fallback (equal
/// degrees from the point count) without one; 1 for a linear cell. Returns "" or the problem.
std::string cellDegrees(vtkUnstructuredGrid* grid, vtkIdType c, vtkDataArray* degrees,
  vtkIdType npts, int dim, int* degree)
{
  const int type = grid->GetCellType(c);
  if (type == VTK_HEXAHEDRON || type == VTK_QUAD)
  {
    return std::string();
  }
  if (!degrees)
  {
    const double root = dim == 3 ? std::cbrt(double(npts)) : std::sqrt(double(npts));
    const int order = static_cast<int>(std::lround(root));
    if (order < 2 || (dim == 3 ? order * order * order : order * order) != npts)
    {
      return std::to_string(npts) + " points are no " + (dim == 3 ? "cube" : "square") +
             " of an order and there is no HigherOrderDegrees array";
    }
    std::fill_n(degree, dim, order - 1);
    return std::string();
  }
  for (int d = 0; d < dim; ++d)
  {
    const double value = degrees->GetComponent(c, d);
    if (!(value >= 1 && value <= iga::kMaxDegree && value == std::floor(value)))
    {
      return "degree " + formatNumber(value) + " in direction " + std::to_string(d) +
             " is not a whole number in 1.." + std::to_string(iga::kMaxDegree);
    }
    degree[d] = static_cast<int>(value);
  }
  return std::string();
}

/// Fills `patch` (its degrees set) from the cell's points `pts` and checks them; returns "" or
/// the problem.
template<int Dim>
std::string readCell(vtkUnstructuredGrid* grid, vtkIdType npts, const vtkIdType* pts,
  const GridArrays& arrays, iga::BezierPatch<double, Dim>& patch)
{
  const auto view = patch.view();
  const int* degree = view.degree;
  if (npts != view.pointCount())
  {
    std::string degrees = std::to_string(degree[0]);
    for (int d = 1; d < Dim; ++d)
    {
      degrees += "x" + std::to_string(degree[d]);
    }
    return "has " + std::to_string(npts) + " points, degrees " + degrees + " need " +
           std::to_string(view.pointCount());
  }
  const vtkIdType pointCount = grid->GetNumberOfPoints();
  bool badId = false;
  std::vector<vtkIdType> ids(static_cast<size_t>(view.pointCount()));
  forEachControlPoint<Dim>(degree, false,
    [&](int linear, int vtkIndex)
    {
      const vtkIdType id = ids[linear] = pts[vtkIndex];
      if (id < 0 || id >= pointCount)
      {
        badId = true;
        return;
      }
      double x[3];
      grid->GetPoint(id, x);
      const double w = arrays.weights ? arrays.weights->GetComponent(id, 0) : 1.0;
      double* cp = view.point(linear);
      for (int d = 0; d < 3; ++d)
      {
        cp[d] = w * x[d];
      }
      cp[iga::kWeightChannel] = w;
      for (size_t a = 0; a < arrays.attributes.size(); ++a)
      {
        cp[iga::kFirstAttributeChannel + a] = w * arrays.attributes[a]->GetComponent(id, 0);
      }
    });
  if (badId)
  {
    return "refers to a point outside 0.." + std::to_string(pointCount - 1);
  }
  const int bad = iga::firstInvalidPoint<double, Dim>(view);
  if (bad >= 0)
  {
    return pointProblem(grid, ids[bad], arrays.weights, arrays.attributes);
  }
  return iga::weightsTooSkewed<double, Dim>(view)
           ? "its " + iga::weightRangeProblem<double, Dim>(view) + " (array '" +
               arrayName(arrays.weights) + "')"
           : std::string();
}

/// Reads cell c into `patches` (a volume or a surface); returns "" or the problem.
std::string readAnyCell(vtkUnstructuredGrid* grid, vtkIdType c, const GridArrays& arrays,
  int channels, vtkIGABezierHexahedra::Patches& patches)
{
  const int type = grid->GetCellType(c);
  const int dim = cellDimension(type);
  if (dim == 0)
  {
    return "cell type " + std::to_string(type) +
           " is neither a hexahedron (VTK_BEZIER_HEXAHEDRON = 79, VTK_HEXAHEDRON = 12) nor a "
           "quadrilateral (VTK_BEZIER_QUADRILATERAL = 77, VTK_QUAD = 9)";
  }
  vtkIdType npts;
  const vtkIdType* pts;
  grid->GetCellPoints(c, npts, pts);
  int degree[3] = { 1, 1, 1 };
  std::string problem = cellDegrees(grid, c, arrays.degrees, npts, dim, degree);
  if (!problem.empty())
  {
    return problem;
  }
  if (dim == 3)
  {
    iga::BezierVolume<double> patch(degree, channels);
    problem = readCell<3>(grid, npts, pts, arrays, patch);
    patches.volumes.patches.push_back(std::move(patch));
    patches.volumeCells.push_back(c);
  }
  else
  {
    iga::BezierSurface<double> patch(degree, channels);
    problem = readCell<2>(grid, npts, pts, arrays, patch);
    patches.surfaces.push_back(std::move(patch));
    patches.surfaceCells.push_back(c);
  }
  return problem;
}
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGABezierHexahedra::ToUnstructuredGrid(
  const iga::VolumeSet<double>& set, CellLayout layout)
{
  vtkIdType total = 0;
  for (const auto& patch : set.patches)
  {
    total += patch.view().pointCount();
  }
  return ToUnstructuredGrid(
    vtkIdType(set.patches.size()), total, set.attributeNames,
    [&](vtkIdType c) -> const iga::BezierVolume<double>& { return set.patches[size_t(c)]; },
    layout);
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGABezierHexahedra::ToUnstructuredGrid(vtkIdType cellCount,
  vtkIdType pointCount, const std::vector<std::string>& attributeNames,
  const std::function<const iga::BezierVolume<double>&(vtkIdType)>& cell, CellLayout layout)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(pointCount);
  vtkNew<vtkDoubleArray> weights;
  weights->SetName(kWeightsName);
  weights->SetNumberOfTuples(pointCount);
  std::vector<vtkSmartPointer<vtkDoubleArray>> attributes;
  for (const auto& name : attributeNames)
  {
    attributes.push_back(vtkSmartPointer<vtkDoubleArray>::New());
    attributes.back()->SetName(name.c_str());
    attributes.back()->SetNumberOfTuples(pointCount);
  }
  vtkNew<vtkIntArray> degrees;
  degrees->SetName(kDegreesName);
  degrees->SetNumberOfComponents(3);
  degrees->SetNumberOfTuples(cellCount);
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(cellCount, pointCount);

  bool uniform = true;
  vtkIdType offset = 0;
  std::vector<vtkIdType> ids;
  for (vtkIdType c = 0; c < cellCount; ++c)
  {
    const auto view = cell(c).view();
    const int* degree = view.degree;
    ids.resize(view.pointCount());
    forEachControlPoint(degree, layout == CellLayout::ForVTK && iga::signedVolume<double>(view) < 0,
      [&](int linear, int vtkIndex)
      {
        const double* cp = view.point(linear);
        const double w = cp[iga::kWeightChannel];
        const vtkIdType id = offset + vtkIndex;
        points->SetPoint(id, cp[0] / w, cp[1] / w, cp[2] / w);
        weights->SetValue(id, w);
        for (size_t a = 0; a < attributes.size(); ++a)
        {
          attributes[a]->SetValue(id, cp[iga::kFirstAttributeChannel + a] / w);
        }
        ids[vtkIndex] = id;
      });
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    degrees->SetTypedTuple(c, degree);
    uniform &= degree[0] == degree[1] && degree[1] == degree[2];
    offset += view.pointCount();
  }

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_BEZIER_HEXAHEDRON, cells);
  grid->GetPointData()->SetRationalWeights(weights);
  for (const auto& array : attributes)
  {
    grid->GetPointData()->AddArray(array);
  }
  if (!attributes.empty())
  {
    grid->GetPointData()->SetActiveScalars(attributes.front()->GetName());
  }
  if (!(uniform && layout == CellLayout::ForVTK))
  {
    grid->GetCellData()->SetHigherOrderDegrees(degrees);
  }
  addVectorArrays(grid->GetPointData());
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGABezierHexahedra::ToUnstructuredGrid(
  const iga::SurfaceSet<double>& set)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  grid->SetPoints(points);
  grid->AllocateExact(vtkIdType(set.patches.size()), 16 * vtkIdType(set.patches.size()));
  vtkNew<vtkDoubleArray> weights;
  weights->SetName(kWeightsName);
  grid->GetPointData()->SetRationalWeights(weights);
  vtkNew<vtkIntArray> degrees;
  degrees->SetName(kDegreesName);
  degrees->SetNumberOfComponents(3);
  grid->GetCellData()->SetHigherOrderDegrees(degrees);
  std::vector<vtkDataArray*> attributes;
  for (const std::string& name : set.attributeNames)
  {
    vtkNew<vtkDoubleArray> attribute;
    attribute->SetName(name.c_str());
    grid->GetPointData()->AddArray(attribute);
    attributes.push_back(attribute);
  }
  if (!attributes.empty())
  {
    grid->GetPointData()->SetActiveScalars(attributes.front()->GetName());
  }
  for (const auto& surface : set.patches)
  {
    AppendQuadrilateral(grid, surface.view(), attributes);
  }
  addVectorArrays(grid->GetPointData());
  return grid;
}

vtkIdType vtkIGABezierHexahedra::AppendQuadrilateral(vtkUnstructuredGrid* grid,
  const iga::PatchView<const double, 2>& surface, const std::vector<vtkDataArray*>& attributes)
{
  vtkPoints* points = grid->GetPoints();
  vtkDataArray* weights = grid->GetPointData()->GetRationalWeights();
  std::vector<vtkIdType> ids(static_cast<size_t>(surface.pointCount()));
  for (int j = 0, linear = 0; j <= surface.degree[1]; ++j)
  {
    for (int i = 0; i <= surface.degree[0]; ++i, ++linear)
    {
      const double* cp = surface.point(linear);
      const double w = cp[iga::kWeightChannel];
      const vtkIdType id = points->InsertNextPoint(cp[0] / w, cp[1] / w, cp[2] / w);
      weights->InsertNextTuple1(w);
      for (size_t a = 0; a < attributes.size(); ++a)
      {
        attributes[a]->InsertNextTuple1(cp[iga::kFirstAttributeChannel + a] / w);
      }
      ids[size_t(vtkHigherOrderQuadrilateral::PointIndexFromIJK(i, j, surface.degree))] = id;
    }
  }
  grid->GetCellData()->GetHigherOrderDegrees()->InsertNextTuple3(
    surface.degree[0], surface.degree[1], 0);
  return grid->InsertNextCell(
    VTK_BEZIER_QUADRILATERAL, static_cast<vtkIdType>(ids.size()), ids.data());
}

bool vtkIGABezierHexahedra::FromUnstructuredGrid(vtkUnstructuredGrid* grid, Patches& patches,
  std::string& error, std::vector<std::string>& warnings)
{
  patches = Patches();
  if (!grid || grid->GetNumberOfCells() == 0)
  {
    error = "the grid has no cells";
    return false;
  }
  GridArrays arrays;
  error = findArrays(grid, arrays, warnings);
  if (!error.empty())
  {
    return false;
  }
  for (vtkDataArray* array : arrays.attributes)
  {
    patches.volumes.attributeNames.emplace_back(array->GetName());
  }
  const int channels = iga::kFirstAttributeChannel + static_cast<int>(arrays.attributes.size());
  vtkIdType leftHanded = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const size_t volumes = patches.volumes.patches.size();
    const std::string problem = readAnyCell(grid, c, arrays, channels, patches);
    if (!problem.empty())
    {
      error = "cell " + std::to_string(c) + ": " + problem;
      return false;
    }
    if (patches.volumes.patches.size() > volumes)
    {
      leftHanded +=
        iga::signedVolume<double>(std::as_const(patches.volumes.patches.back()).view()) < 0;
    }
  }
  if (leftHanded > 0)
  {
    warnings.push_back(std::to_string(leftHanded) + " of " +
                       std::to_string(grid->GetNumberOfCells()) +
                       " cells are inside-out for VTK (left-handed: negative Jacobian "
                       "determinant); they are drawn as they are, but VTK's own filters "
                       "(Contour, Clip, Integrate Variables) may fail on them");
  }
  return true;
}

bool vtkIGABezierHexahedra::FromUnstructuredGrid(vtkUnstructuredGrid* grid,
  iga::VolumeSet<double>& set, std::string& error, std::vector<std::string>& warnings)
{
  Patches patches;
  set = iga::VolumeSet<double>();
  if (!FromUnstructuredGrid(grid, patches, error, warnings))
  {
    return false;
  }
  if (!patches.surfaces.empty())
  {
    error = "cell " + std::to_string(patches.surfaceCells.front()) +
            " is a quadrilateral (a surface), where hexahedra are needed";
    return false;
  }
  set = std::move(patches.volumes);
  return true;
}
