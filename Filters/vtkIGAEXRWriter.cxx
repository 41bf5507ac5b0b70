#include "vtkIGAEXRWriter.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkIGAEXRWriter);

vtkIGAEXRWriter::vtkIGAEXRWriter() = default;

vtkIGAEXRWriter::~vtkIGAEXRWriter()
{
  this->SetFileName(nullptr);
}

void vtkIGAEXRWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

int vtkIGAEXRWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkIGAEXRWriter::WriteData()
{
  this->LastError.clear();
  const std::string file = this->FileName ? this->FileName : "";
  auto fail = [&](const std::string& what)
  {
    this->LastError = file + ": " + what;
    vtkErrorMacro(<< this->LastError);
    this->SetErrorCode(1);
  };
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  if (file.empty())
  {
    fail("no file name given");
    return;
  }
  if (!image)
  {
    fail("no image to write");
    return;
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1 || dims[0] < 1 || dims[1] < 1)
  {
    fail("the image is not 2D (" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
         std::to_string(dims[2]) + ")");
    return;
  }
  const int width = dims[0], height = dims[1];
  const size_t pixels = size_t(width) * height;
  vtkPointData* pd = image->GetPointData();
  std::vector<std::pair<std::string, std::vector<float>>> channels;
  const char* suffix[4] = { ".X", ".Y", ".Z", ".W" };
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (!array || !array->GetName() || array->GetNumberOfTuples() != vtkIdType(pixels))
    {
      continue;
    }
    const int components = array->GetNumberOfComponents();
    if (components > 4)
    {
      continue;
    }
    for (int c = 0; c < components; ++c)
    {
      std::vector<float> values(pixels);
      for (int j = 0; j < height; ++j) // EXR rows run top to bottom
      {
        for (int i = 0; i < width; ++i)
        {
          values[size_t(height - 1 - j) * width + i] =
            static_cast<float>(array->GetComponent(vtkIdType(j) * width + i, c));
        }
      }
      channels.emplace_back(
        std::string(array->GetName()) + (components == 1 ? "" : suffix[c]), std::move(values));
    }
  }
  if (channels.empty())
  {
    fail("the image has no point-data arrays to write");
    return;
  }
  try
  {
    Imf::Header header(width, height);
    Imf::FrameBuffer frame;
    for (auto& channel : channels)
    {
      header.channels().insert(channel.first, Imf::Channel(Imf::FLOAT));
      frame.insert(
        channel.first, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(channel.second.data()),
                         sizeof(float), sizeof(float) * size_t(width)));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
  }
  catch (const std::exception& e)
  {
    fail(std::string("cannot write OpenEXR: ") + e.what());
  }
}
