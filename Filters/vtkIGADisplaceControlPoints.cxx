#include "vtkIGADisplaceControlPoints.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkIGADisplaceControlPoints);

vtkIGADisplaceControlPoints::vtkIGADisplaceControlPoints()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::VECTORS);
}

void vtkIGADisplaceControlPoints::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleFactor: " << this->ScaleFactor << "\n";
}

int vtkIGADisplaceControlPoints::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  if (!std::isfinite(this->ScaleFactor))
  {
    vtkErrorMacro("scale factor " << this->ScaleFactor << " is not finite");
    return 0;
  }
  if (!input->GetPoints())
  {
    output->ShallowCopy(input);
    return 1;
  }
  int association = -1;
  vtkDataArray* displacement = this->GetInputArrayToProcess(0, inputVector, association);
  if (!displacement)
  {
    vtkInformation* selection = this->GetInputArrayInformation(0);
    if (selection->Has(vtkDataObject::FIELD_NAME()))
    {
      vtkErrorMacro("no displacement: the input has no point array '"
                    << selection->Get(vtkDataObject::FIELD_NAME()) << "'");
    }
    else
    {
      vtkErrorMacro("no displacement: the input has no active vectors; select a 3-component "
                    "point array");
    }
    return 0;
  }
  const std::string name = displacement->GetName() ? displacement->GetName() : "(unnamed)";
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS)
  {
    vtkErrorMacro("displacement array '" << name << "' is not a point array: solvers' "
                                         << "displacements live on the control points");
    return 0;
  }
  if (displacement->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("displacement array '" << name << "' has "
                                         << displacement->GetNumberOfComponents()
                                         << " components, expected 3");
    return 0;
  }
  const vtkIdType count = input->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    double x[3], d[3];
    input->GetPoint(i, x);
    displacement->GetTuple(i, d);
    for (int c = 0; c < 3; ++c)
    {
      if (!std::isfinite(d[c]))
      {
        vtkErrorMacro("displacement array '" << name << "' has a non-finite value at point " << i
                                             << ", component " << c);
        return 0;
      }
      x[c] += this->ScaleFactor * d[c];
    }
    points->SetPoint(i, x);
  }
  output->ShallowCopy(input);
  output->SetPoints(points);
  return 1;
}
