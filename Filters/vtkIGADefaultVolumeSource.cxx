#include "vtkIGADefaultVolumeSource.h"

#include "vtkIGAAttributeRanges.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Datasets.h"
#include "iga/sst/Engine.h"

#include <algorithm>

vtkStandardNewMacro(vtkIGADefaultVolumeSource);

vtkIGADefaultVolumeSource::vtkIGADefaultVolumeSource()
{
  this->SetNumberOfInputPorts(0);
}

void vtkIGADefaultVolumeSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Time: " << this->Time << "\n";
}

int vtkIGADefaultVolumeSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Eleven steps over the deformation's range, so animation tools have something to step.
  double steps[11];
  for (int i = 0; i < 11; ++i)
  {
    steps[i] = 0.1 * i;
  }
  const double range[2] = { 0.0, 1.0 };
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps, 11);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  outInfo->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkIGADefaultVolumeSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  double time = this->Time;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    time = std::clamp(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()), 0.0, 1.0);
  }
  auto set = iga::makeTwistedTube<double>(time);
  // Piece p of n keeps the patches [p N / n, (p + 1) N / n): whole patches, so that MPI ranks
  // draw disjoint parts of the tube.
  const int piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  const int pieces = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  if (pieces > 1 && piece >= 0 && piece < pieces)
  {
    const size_t count = set.patches.size();
    decltype(set.patches) mine(set.patches.begin() + count * piece / pieces,
      set.patches.begin() + count * (piece + 1) / pieces);
    set.patches = std::move(mine);
  }
  auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(set);
  vtkIGAAttributeRanges::Attach(grid, iga::sst::Scene(set.patches), set.attributeNames);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outInfo);
  output->ShallowCopy(grid);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);
  return 1;
}
