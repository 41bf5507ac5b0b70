#include "vtkIGAIsosurfaceImage.h"

#include "vtkIGAIsosurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"

#include "iga/sst/GBuffer.h"

#include <algorithm>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkIGAIsosurfaceImage);

vtkIGAIsosurfaceImage::vtkIGAIsosurfaceImage()
{
  this->Actor->SetMapper(this->Mapper);
}

vtkIGAIsosurfaceImage::~vtkIGAIsosurfaceImage()
{
  this->SetCamera(nullptr);
}

void vtkIGAIsosurfaceImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "Layers: " << this->Layers << "\n";
  os << indent << "Camera: " << (this->Camera ? "set" : "(framing the input)") << "\n";
  os << indent << "Mapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

vtkIGAIsosurfaceMapper* vtkIGAIsosurfaceImage::GetMapper()
{
  return this->Mapper;
}

vtkProperty* vtkIGAIsosurfaceImage::GetProperty()
{
  return this->Actor->GetProperty();
}

void vtkIGAIsosurfaceImage::SetCamera(vtkCamera* camera)
{
  if (camera == this->Camera)
  {
    return;
  }
  if (this->Camera)
  {
    this->Camera->UnRegister(this);
  }
  this->Camera = camera;
  if (camera)
  {
    camera->Register(this);
  }
  this->Modified();
}

vtkMTimeType vtkIGAIsosurfaceImage::GetMTime()
{
  vtkMTimeType time = std::max(this->Superclass::GetMTime(), this->Mapper->GetMTime());
  time = std::max(time, this->Actor->GetProperty()->GetMTime());
  return this->Camera ? std::max(time, this->Camera->GetMTime()) : time;
}

int vtkIGAIsosurfaceImage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkIGAIsosurfaceImage::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (this->ImageSize[0] < 1 || this->ImageSize[1] < 1)
  {
    vtkErrorMacro(<< "ImageSize " << this->ImageSize[0] << " x " << this->ImageSize[1]
                  << " has no pixels");
    return 0;
  }
  const int extent[6] = { 0, this->ImageSize[0] - 1, 0, this->ImageSize[1] - 1, 0, 0 };
  vtkInformation* out = outputVector->GetInformationObject(0);
  out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(out, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

namespace
{
/// A point array of `components` components named `name`, NaN (or `fill`) everywhere.
template<class Array, class Value>
vtkSmartPointer<Array> pixelArray(
  vtkPointData* data, const char* name, int components, vtkIdType pixels, Value fill)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(pixels);
  std::fill_n(array->GetPointer(0), pixels * components, fill);
  data->AddArray(array);
  return array;
}
} // namespace

int vtkIGAIsosurfaceImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  image->SetDimensions(this->ImageSize[0], this->ImageSize[1], 1);
  const bool computed = this->ComputeFrame(input);
  if (!computed && this->Mapper->GetLastRefusal()[0] != '\0')
  {
    vtkErrorMacro(<< this->Mapper->GetLastRefusal());
    return 0;
  }
  this->WritePixels(image, vtkCompositeDataSet::SafeDownCast(input) != nullptr, computed);
  return 1;
}

bool vtkIGAIsosurfaceImage::ComputeFrame(vtkDataObject* input)
{
  // The input as the mapper's own data (its pipeline stays this filter's).
  vtkSmartPointer<vtkDataObject> copy;
  copy.TakeReference(input->NewInstance());
  copy->ShallowCopy(input);
  this->Mapper->SetInputData(copy);
  vtkNew<vtkRenderer> renderer;
  if (this->Camera)
  {
    renderer->SetActiveCamera(this->Camera);
  }
  else
  {
    renderer->ResetCamera(this->Mapper->GetBounds());
  }
  renderer->CreateLight();
  renderer->UpdateLightsGeometryToFollowCamera();
  const bool computed =
    this->Mapper->ComputeImage(renderer, this->Actor, this->ImageSize[0], this->ImageSize[1]);
  this->Mapper->SetInputData(nullptr);
  return computed;
}

void vtkIGAIsosurfaceImage::WritePixels(vtkImageData* image, bool composite, bool computed)
{
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  const vtkIdType pixels = vtkIdType(width) * height;
  vtkPointData* data = image->GetPointData();
  auto hitCount = pixelArray<vtkIntArray>(data, "HitCount", 1, pixels, 0);
  auto rgba = pixelArray<vtkUnsignedCharArray>(data, "RGBA", 4, pixels, (unsigned char)0);
  data->SetScalars(rgba);
  if (computed)
  {
    const iga::sst::GBuffer& gbuffer = this->Mapper->GetLastGBuffer();
    const std::vector<float>& colours = this->Mapper->GetLastColours();
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      hitCount->SetValue(p, gbuffer.hitCount(int(p % width), int(p / width)));
      for (int c = 0; hitCount->GetValue(p) > 0 && c < 4; ++c)
      {
        const float value = std::clamp(colours[size_t(4 * p + c)], 0.0f, 1.0f);
        rgba->SetValue(4 * p + c, static_cast<unsigned char>(value * 255.0f + 0.5f));
      }
    }
  }
  for (int layer = 0; layer < this->Layers; ++layer)
  {
    this->WriteLayer(
      image, composite, computed ? layer : -1, layer ? "_" + std::to_string(layer) : "");
  }
}

void vtkIGAIsosurfaceImage::WriteLayer(
  vtkImageData* image, bool composite, int layer, const std::string& suffix)
{
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  const vtkIdType pixels = vtkIdType(width) * height;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkPointData* data = image->GetPointData();
  const auto named = [&](const char* name) { return std::string(name) + suffix; };
  auto depth = pixelArray<vtkDoubleArray>(data, named("Depth").c_str(), 1, pixels, nan);
  auto position = pixelArray<vtkDoubleArray>(data, named("Position").c_str(), 3, pixels, nan);
  auto normal = pixelArray<vtkDoubleArray>(data, named("Normal").c_str(), 3, pixels, nan);
  auto uvw = pixelArray<vtkDoubleArray>(data, named("UVW").c_str(), 3, pixels, nan);
  auto cell = pixelArray<vtkIdTypeArray>(data, named("Cell").c_str(), 1, pixels, vtkIdType(-1));
  auto block = composite
                 ? pixelArray<vtkUnsignedIntArray>(data, named("Block").c_str(), 1, pixels, 0u)
                 : nullptr;
  const int attributeCount = layer >= 0 ? this->Mapper->GetNumberOfAttributes() : 0;
  std::vector<vtkSmartPointer<vtkDoubleArray>> attributes;
  for (int a = 0; a < attributeCount; ++a)
  {
    attributes.push_back(pixelArray<vtkDoubleArray>(
      data, named(this->Mapper->GetAttributeName(a)).c_str(), 1, pixels, nan));
  }
  if (layer < 0)
  {
    return; // nothing computed: every pixel empty
  }
  const iga::sst::GBuffer& gbuffer = this->Mapper->GetLastGBuffer();
  std::vector<double> values(static_cast<size_t>(attributeCount));
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    const int i = int(p % width), j = int(p / width);
    if (gbuffer.hitCount(i, j) <= layer)
    {
      continue;
    }
    const iga::sst::Hit* hit = gbuffer.firstHit(i, j) + layer;
    depth->SetValue(p, hit->eyeDepth);
    position->SetTypedTuple(p, &hit->position[0]);
    normal->SetTypedTuple(p, &hit->normal[0]);
    double parameter[3];
    this->Mapper->CellParameter(*hit, parameter);
    uvw->SetTypedTuple(p, parameter);
    vtkIdType cellId = -1;
    unsigned int blockIndex = 0;
    this->Mapper->PatchSource(hit->patch, cellId, blockIndex);
    cell->SetValue(p, cellId);
    if (block)
    {
      block->SetValue(p, blockIndex);
    }
    this->Mapper->HitAttributes(*hit, values.data());
    for (int a = 0; a < attributeCount; ++a)
    {
      attributes[size_t(a)]->SetValue(p, values[size_t(a)]);
    }
  }
}
