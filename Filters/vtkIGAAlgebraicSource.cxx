#include "vtkIGAAlgebraicSource.h"

#include "vtkErrorCode.h"
#include "vtkIGAAttributeRanges.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include "iga/AbsField.h"
#include "iga/AlgebraicGallery.h"
#include "iga/Datasets.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Engine.h"

#include <stdexcept>
#include <string>

vtkStandardNewMacro(vtkIGAAlgebraicSource);

vtkIGAAlgebraicSource::vtkIGAAlgebraicSource()
{
  this->SetNumberOfInputPorts(0);
}

void vtkIGAAlgebraicSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Expression: " << this->Expression << "\n";
  os << indent << "Box: " << this->Box[0] << " " << this->Box[1] << " " << this->Box[2] << " "
     << this->Box[3] << " " << this->Box[4] << " " << this->Box[5] << "\n";
  os << indent << "GallerySurface: " << this->GallerySurface << "\n";
  os << indent << "SplineCells: " << this->SplineCells << "\n";
  os << indent << "SplineDegree: " << this->SplineDegree << "\n";
}

void vtkIGAAlgebraicSource::SetExpression(const char* expression)
{
  const std::string text = expression ? expression : "";
  if (text != this->Expression)
  {
    this->Expression = text;
    this->Modified();
  }
}

int vtkIGAAlgebraicSource::GetNumberOfGallerySurfaces()
{
  int count = 0;
  iga::algebraicGallery(count);
  return count;
}

const char* vtkIGAAlgebraicSource::GetGallerySurfaceName(int index)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  return index >= 0 && index < count ? gallery[index].name : nullptr;
}

void vtkIGAAlgebraicSource::SetGallerySurfaceByName(const char* name)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name ? name : "");
  if (!surface)
  {
    std::string names;
    for (int k = 0; k < count; ++k)
    {
      names += std::string(k ? ", " : "") + gallery[k].name;
    }
    vtkErrorMacro(<< "no gallery surface '" << (name ? name : "") << "' (have: " << names << ")");
    return;
  }
  this->SetGallerySurface(int(surface - gallery));
}

int vtkIGAAlgebraicSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkIGAAlgebraicSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  iga::VolumeSet<double> set;
  set.attributeNames = { "f" };
  this->SetErrorCode(vtkErrorCode::NoError);
  try
  {
    if (this->GallerySurface >= count)
    {
      throw std::invalid_argument("GallerySurface " + std::to_string(this->GallerySurface) +
                                  " is not below the gallery's " + std::to_string(count) +
                                  " surfaces");
    }
    const bool fromGallery = this->GallerySurface >= 0;
    const auto field = iga::parsePolynomial(
      fromGallery ? gallery[this->GallerySurface].expression : this->Expression);
    const double* box = fromGallery ? gallery[this->GallerySurface].box : this->Box;
    if (this->SplineCells > 0)
    {
      const int cells[3] = { this->SplineCells, this->SplineCells, this->SplineCells };
      set = iga::makeAbsField([&](double x, double y, double z) { return field.evaluate(x, y, z); },
        box, this->SplineDegree, cells)
              .set;
    }
    else
    {
      set.patches.push_back(iga::makeAlgebraicVolume(field, box));
    }
    // Piece p of n keeps the elements [p N / n, (p + 1) N / n).
    const int piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
    const int pieces = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
    if (pieces > 1 && piece >= 0 && piece < pieces)
    {
      const size_t count = set.patches.size();
      set.patches = decltype(set.patches)(set.patches.begin() + count * piece / pieces,
        set.patches.begin() + count * (piece + 1) / pieces);
    }
  }
  catch (const std::invalid_argument& e)
  {
    // Said once, with an empty output: the pipeline stays sound, so the next good setting
    // draws again (a failed request would leave ParaView's views on the last good frame). The
    // error code tells callers that stop at an error, as a reader's does.
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::UserError);
  }
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(set);
  vtkIGAAttributeRanges::Attach(grid, iga::sst::Scene(set.patches), set.attributeNames);
  vtkUnstructuredGrid::GetData(outInfo)->ShallowCopy(grid);
  return 1;
}
