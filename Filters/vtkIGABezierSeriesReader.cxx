#include "vtkIGABezierSeriesReader.h"

#include "IGAFileHead.h"
#include "IGAXMLDocument.h"
#include "vtkIGAAttributeRanges.h"
#include "vtkIGABezierFileReading.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLDataElement.h"
#include "vtksys/SystemTools.hxx"

#include "iga/sst/Engine.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numeric>
#include <sstream>

vtkStandardNewMacro(vtkIGABezierSeriesReader);

namespace
{

/// A collection lists files; one this large is not one.
constexpr unsigned long kMaximumCollectionBytes = 64ul << 20;

/// The finite number `text` spells, whole; false otherwise.
bool parseTime(const char* text, double& time)
{
  char* end = nullptr;
  time = text ? std::strtod(text, &end) : 0;
  return text && end != text && *end == '\0' && std::isfinite(time);
}

} // namespace

vtkIGABezierSeriesReader::vtkIGABezierSeriesReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkIGABezierSeriesReader::~vtkIGABezierSeriesReader()
{
  this->SetFileName(nullptr);
}

void vtkIGABezierSeriesReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "TimeSteps: " << this->Times.size() << "\n";
}

int vtkIGABezierSeriesReader::CanReadFile(const char* name)
{
  const std::string head = igaFileHead(name ? name : "", 1024);
  const size_t root = head.find("<VTKFile");
  const size_t end = head.find('>', root);
  return root != std::string::npos && (head.find("type=\"Collection\"", root) < end ||
                                        head.find("type='Collection'", root) < end)
           ? 1
           : 0;
}

bool vtkIGABezierSeriesReader::ParseCollection(std::string& error)
{
  this->Times.clear();
  this->Files.clear();
  const std::string pvd = this->FileName ? this->FileName : "";
  const std::string name = "'" + pvd + "'";
  std::ifstream in;
  if (pvd.empty() || !(error = igaOpenRegularFile(pvd, in)).empty())
  {
    error = pvd.empty() ? "no FileName set" : error;
    return false;
  }
  if (vtksys::SystemTools::FileLength(pvd) > kMaximumCollectionBytes)
  {
    error = name + ": larger than 64 MiB, not a collection of files";
    return false;
  }
  const std::string text{ std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
  std::string parseError;
  const auto parser = igaParseXML(text, parseError);
  if (!parser)
  {
    error = name + ":" + (std::isdigit(static_cast<unsigned char>(parseError[0])) ? "" : " ") +
            parseError;
    return false;
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  const char* type = root->GetAttribute("type");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (std::string(root->GetName()) != "VTKFile" || !type || std::string(type) != "Collection" ||
      !collection)
  {
    error = name + ": not a VTK collection (<VTKFile type=\"Collection\"><Collection>)";
    return false;
  }
  const std::string directory = vtksys::SystemTools::GetFilenamePath(pvd);
  std::vector<double> times;
  std::vector<std::string> files;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* dataSet = collection->GetNestedElement(i);
    if (std::string(dataSet->GetName()) != "DataSet")
      continue;
    const std::string which = name + ": DataSet " + std::to_string(times.size());
    double time;
    if (!parseTime(dataSet->GetAttribute("timestep"), time))
    {
      error = which + " has no finite timestep";
      return false;
    }
    const char* file = dataSet->GetAttribute("file");
    if (!file || !*file)
    {
      error = which + " names no file";
      return false;
    }
    times.push_back(time);
    files.push_back(vtksys::SystemTools::FileIsFullPath(file)
                      ? std::string(file)
                      : vtksys::SystemTools::CollapseFullPath(file, directory));
  }
  if (times.empty())
  {
    error = name + ": the collection lists no DataSet";
    return false;
  }
  std::vector<size_t> order(times.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&](size_t a, size_t b) { return times[a] < times[b]; });
  for (size_t k = 0; k < order.size(); ++k)
  {
    if (k > 0 && times[order[k]] == this->Times.back())
    {
      this->Times.clear();
      this->Files.clear();
      std::ostringstream text;
      text << name << ": several parts at time " << times[order[k]]
           << " (each time step must be one file)";
      error = text.str();
      return false;
    }
    this->Times.push_back(times[order[k]]);
    this->Files.push_back(files[order[k]]);
  }
  return true;
}

int vtkIGABezierSeriesReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  std::string error;
  if (!this->ParseCollection(error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const double range[2] = { this->Times.front(), this->Times.back() };
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), this->Times.data(), int(this->Times.size()));
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

int vtkIGABezierSeriesReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (this->Times.empty())
  {
    return 0; // RequestInformation reported why
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  size_t step = 0;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    const double time = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    const auto after = std::upper_bound(this->Times.begin(), this->Times.end(), time);
    step = after == this->Times.begin() ? 0 : size_t(after - this->Times.begin()) - 1;
  }
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  const auto grid =
    vtkIGABezierFileReading::Read(this->Files[step], nullptr, patches, error, warnings);
  for (const auto& warning : warnings)
  {
    vtkWarningMacro(<< this->Files[step] << ": " << warning);
  }
  if (!grid)
  {
    vtkErrorMacro(<< "time step " << this->Times[step] << " of '" << this->FileName
                  << "': " << error);
    return 0;
  }
  vtkIGAAttributeRanges::Attach(grid, iga::sst::Scene(patches.volumes.patches, patches.surfaces),
    patches.volumes.attributeNames);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outInfo);
  output->ShallowCopy(grid);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), this->Times[step]);
  return 1;
}
