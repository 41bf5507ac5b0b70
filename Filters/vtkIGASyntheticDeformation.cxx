#include "vtkIGASyntheticDeformation.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Deformation.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkIGASyntheticDeformation);

vtkIGASyntheticDeformation::vtkIGASyntheticDeformation() = default;

void vtkIGASyntheticDeformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "Axis: " << this->Axis << "\n";
  os << indent << "Amount: " << this->Amount << "\n";
  os << indent << "Wavelength: " << this->Wavelength << "\n";
  os << indent << "NumberOfTimeSteps: " << this->NumberOfTimeSteps << "\n";
  os << indent << "Time: " << this->Time << "\n";
  os << indent << "GenerateDisplacement: " << this->GenerateDisplacement << "\n";
}

int vtkIGASyntheticDeformation::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  std::vector<double> steps(static_cast<size_t>(this->NumberOfTimeSteps));
  for (int i = 0; i < this->NumberOfTimeSteps; ++i)
  {
    steps[i] = double(i) / (this->NumberOfTimeSteps - 1);
  }
  const double range[2] = { 0.0, 1.0 };
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(), this->NumberOfTimeSteps);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

int vtkIGASyntheticDeformation::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The time is this filter's: the input is taken as static, whatever time it may offer.
  inputVector[0]->GetInformationObject(0)->Remove(
    vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  return 1;
}

int vtkIGASyntheticDeformation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outInfo);
  double time = this->Time;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    time = std::clamp(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()), 0.0, 1.0);
  }
  output->ShallowCopy(input);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);
  vtkPoints* in = input->GetPoints();
  if (!in || in->GetNumberOfPoints() == 0)
  {
    return 1;
  }
  double bounds[6], lo[3], hi[3];
  in->GetBounds(bounds);
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = bounds[2 * d];
    hi[d] = bounds[2 * d + 1];
  }
  const iga::DeformationKind kinds[4] = { iga::DeformationKind::Twist, iga::DeformationKind::Bend,
    iga::DeformationKind::Wave, iga::DeformationKind::Lattice };
  const iga::Deformation deformation =
    iga::boxDeformation(kinds[this->Mode], this->Axis, lo, hi, this->Amount, this->Wavelength);
  const std::string problem = iga::checkDeformation(deformation);
  if (!problem.empty())
  {
    vtkErrorMacro("cannot deform the input (bounds "
                  << bounds[0] << ".." << bounds[1] << ", " << bounds[2] << ".." << bounds[3]
                  << ", " << bounds[4] << ".." << bounds[5] << "): " << problem);
    output->Initialize();
    return 0;
  }
  const vtkIdType count = in->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  vtkNew<vtkDoubleArray> displacement, magnitude;
  if (this->GenerateDisplacement)
  {
    displacement->SetName("Displacement");
    displacement->SetNumberOfComponents(3);
    displacement->SetNumberOfTuples(count);
    magnitude->SetName("DisplacementMagnitude");
    magnitude->SetNumberOfTuples(count);
  }
  for (vtkIdType i = 0; i < count; ++i)
  {
    double x[3], y[3];
    in->GetPoint(i, x);
    iga::deformPoint(deformation, time, x, y);
    points->SetPoint(i, y);
    if (this->GenerateDisplacement)
    {
      const double d[3] = { y[0] - x[0], y[1] - x[1], y[2] - x[2] };
      displacement->SetTypedTuple(i, d);
      magnitude->SetValue(i, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
  }
  output->SetPoints(points);
  if (this->GenerateDisplacement)
  {
    output->GetPointData()->SetVectors(displacement);
    output->GetPointData()->AddArray(magnitude);
  }
  return 1;
}
