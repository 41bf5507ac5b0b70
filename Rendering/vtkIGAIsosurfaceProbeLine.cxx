#include "vtkIGAIsosurfaceProbeLine.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkIGAIsosurfaceImage.h"
#include "vtkIGAIsosurfaceMapper.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkIGAIsosurfaceProbeLine);

vtkIGAIsosurfaceProbeLine::vtkIGAIsosurfaceProbeLine()
{
  this->Image->SetImageSize(1, 1);
}

vtkIGAIsosurfaceProbeLine::~vtkIGAIsosurfaceProbeLine() = default;

void vtkIGAIsosurfaceProbeLine::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Point1: " << this->Point1[0] << ", " << this->Point1[1] << ", "
     << this->Point1[2] << "\n";
  os << indent << "Point2: " << this->Point2[0] << ", " << this->Point2[1] << ", "
     << this->Point2[2] << "\n";
  os << indent << "MaximumHits: " << this->MaximumHits << "\n";
}

vtkIGAIsosurfaceMapper* vtkIGAIsosurfaceProbeLine::GetMapper()
{
  return this->Image->GetMapper();
}

void vtkIGAIsosurfaceProbeLine::SetSurfaceArrayName(const char* name)
{
  this->GetMapper()->SetSurfaceArrayName(name);
}

void vtkIGAIsosurfaceProbeLine::SetSurfaceArray(int, int, int, int, const char* name)
{
  this->SetSurfaceArrayName(name);
}

void vtkIGAIsosurfaceProbeLine::SetIsovalue(double value)
{
  this->GetMapper()->SetNumberOfIsovalues(1);
  this->GetMapper()->SetIsovalue(0, value);
}

vtkMTimeType vtkIGAIsosurfaceProbeLine::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Image->GetMTime());
}

int vtkIGAIsosurfaceProbeLine::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

namespace
{
/// The names the image gives a hit's arrays (its first layer's), less those read apart: each
/// name whose layers 1 .. layers - 1 are all there as NAME_k.
std::vector<std::string> layerNames(vtkPointData* data, int layers)
{
  std::vector<std::string> names;
  for (int a = 0; a < data->GetNumberOfArrays(); ++a)
  {
    const std::string name = data->GetArrayName(a) ? data->GetArrayName(a) : "";
    bool layered = name != "HitCount" && name != "RGBA" && name != "Position";
    for (int k = 1; layered && k < layers; ++k)
    {
      layered = data->GetArray((name + "_" + std::to_string(k)).c_str()) != nullptr;
    }
    if (layered)
    {
      names.push_back(name);
    }
  }
  return names;
}
} // namespace

int vtkIGAIsosurfaceProbeLine::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  double direction[3];
  vtkMath::Subtract(this->Point2, this->Point1, direction);
  const double length = vtkMath::Norm(direction);
  if (!(length > 0) || !std::isfinite(length))
  {
    vtkErrorMacro(<< "Point1 and Point2 must be distinct finite points: no segment to probe");
    return 0;
  }
  // A parallel view whose middle ray runs from Point1 to Point2, one pixel across.
  double up[3], side[3];
  vtkMath::Perpendiculars(direction, up, side, 0);
  vtkNew<vtkCamera> camera;
  camera->ParallelProjectionOn();
  camera->SetPosition(this->Point1);
  camera->SetFocalPoint(this->Point2);
  camera->SetViewUp(up);
  camera->SetParallelScale(1e-3 * length);
  camera->SetClippingRange(1e-9 * length, length);
  this->Image->SetCamera(camera);
  this->Image->SetLayers(this->MaximumHits);
  this->GetMapper()->SetAllLayers(this->MaximumHits > 1);
  this->Image->SetInputData(input);
  this->Image->Update();
  this->Image->SetInputData(nullptr);
  vtkPointData* pixel = this->Image->GetOutput()->GetPointData();
  if (!pixel->GetArray("Position"))
  {
    return 0; // the image filter said why
  }
  const std::vector<std::string> names = layerNames(pixel, this->MaximumHits);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  std::vector<vtkSmartPointer<vtkDataArray>> columns;
  for (const std::string& name : names)
  {
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(pixel->GetArray(name.c_str())->NewInstance());
    array->SetName(name == "Depth" ? "Distance" : name.c_str());
    array->SetNumberOfComponents(pixel->GetArray(name.c_str())->GetNumberOfComponents());
    columns.push_back(array);
  }
  for (int layer = 0; layer < this->MaximumHits; ++layer)
  {
    const std::string suffix = layer ? "_" + std::to_string(layer) : "";
    vtkDataArray* cell = pixel->GetArray(("Cell" + suffix).c_str());
    if (!cell || cell->GetComponent(0, 0) < 0)
    {
      break; // the hits come nearest first
    }
    points->InsertNextPoint(pixel->GetArray(("Position" + suffix).c_str())->GetTuple3(0));
    for (size_t a = 0; a < names.size(); ++a)
    {
      columns[a]->InsertNextTuple(pixel->GetArray((names[a] + suffix).c_str())->GetTuple(0));
    }
  }
  // An attribute named as a fixed array (Distance, Normal, ...) yields to it, which comes first.
  for (const auto& column : columns)
  {
    if (!output->GetPointData()->HasArray(column->GetName()))
    {
      output->GetPointData()->AddArray(column);
    }
  }
  output->SetPoints(points);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    vertices->InsertNextCell(1, &p);
  }
  output->SetVerts(vertices);
  return 1;
}
