#include "vtkIGABoundarySurface.h"

#include "vtkIGABezierHexahedra.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Boundary.h"

#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkIGABoundarySurface);

namespace
{

/// A named array of `components` components added to `data`.
template<class Array>
Array* addArray(vtkDataSetAttributes* data, const char* name, int components = 1)
{
  vtkNew<Array> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  data->AddArray(array);
  return array;
}

} // namespace

int vtkIGABoundarySurface::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  iga::VolumeSet<double> set;
  std::string error;
  std::vector<std::string> warnings;
  if (!vtkIGABezierHexahedra::FromUnstructuredGrid(input, set, error, warnings))
  {
    vtkErrorMacro("cannot take the boundary of the input: " << error);
    return 0;
  }
  const std::vector<iga::PatchFace> faces = iga::boundaryFaces(set.patches);

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  output->SetPoints(points);
  output->AllocateExact(vtkIdType(faces.size()), 9 * vtkIdType(faces.size()));
  vtkPointData* pd = output->GetPointData();
  vtkCellData* cd = output->GetCellData();
  pd->SetRationalWeights(addArray<vtkDoubleArray>(pd, "RationalWeights"));
  cd->SetHigherOrderDegrees(addArray<vtkIntArray>(cd, "HigherOrderDegrees", 3));
  std::vector<vtkDataArray*> attributes;
  for (const auto& name : set.attributeNames)
  {
    attributes.push_back(addArray<vtkDoubleArray>(pd, name.c_str()));
  }
  if (!attributes.empty())
  {
    pd->SetActiveScalars(attributes.front()->GetName());
  }
  vtkIntArray* fromCell = addArray<vtkIntArray>(cd, "BoundaryCell");
  vtkIntArray* fromFace = addArray<vtkIntArray>(cd, "BoundaryFace");
  for (const iga::PatchFace& face : faces)
  {
    const auto surface =
      iga::faceSurface(set.patches[size_t(face.patch)], face.direction, face.side);
    vtkIGABezierHexahedra::AppendQuadrilateral(output, surface.view(), attributes);
    fromCell->InsertNextValue(face.patch);
    fromFace->InsertNextValue(2 * face.direction + face.side);
  }
  return 1;
}
