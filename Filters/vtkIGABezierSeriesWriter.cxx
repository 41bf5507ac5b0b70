#include "vtkIGABezierSeriesWriter.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridWriter.h"
#include "vtksys/SystemTools.hxx"

#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkIGABezierSeriesWriter);

vtkIGABezierSeriesWriter::~vtkIGABezierSeriesWriter()
{
  this->SetFileName(nullptr);
}

void vtkIGABezierSeriesWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

void vtkIGABezierSeriesWriter::SetInputConnection(vtkAlgorithmOutput* input)
{
  this->Input = input;
  this->Modified();
}

int vtkIGABezierSeriesWriter::Write()
{
  vtkAlgorithm* producer = this->Input ? this->Input->GetProducer() : nullptr;
  if (!this->FileName || !producer)
  {
    vtkErrorMacro(<< "set FileName and an input connection before writing");
    return 0;
  }
  const int port = this->Input->GetIndex();
  const std::string pvd = this->FileName;
  const std::string directory = vtksys::SystemTools::GetFilenamePath(pvd);
  const std::string stem = vtksys::SystemTools::GetFilenameWithoutLastExtension(pvd);

  producer->UpdateInformation();
  vtkInformation* info = producer->GetOutputInformation(port);
  std::vector<double> times;
  if (info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    const double* steps = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    times.assign(steps, steps + info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  }
  const bool timed = !times.empty();
  if (!timed)
  {
    times.push_back(0.0);
  }

  std::ostringstream collection;
  collection << std::setprecision(std::numeric_limits<double>::max_digits10);
  collection << "<?xml version=\"1.0\"?>\n"
             << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             << "  <Collection>\n";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  for (size_t i = 0; i < times.size(); ++i)
  {
    if (timed)
    {
      info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), times[i]);
    }
    auto* executive = vtkStreamingDemandDrivenPipeline::SafeDownCast(producer->GetExecutive());
    if (!executive || !executive->Update(port))
    {
      vtkErrorMacro(<< pvd << ": the input failed to produce time step " << i);
      return 0;
    }
    auto* grid = vtkUnstructuredGrid::SafeDownCast(producer->GetOutputDataObject(port));
    if (!grid)
    {
      vtkErrorMacro(<< pvd << ": the input does not produce a vtkUnstructuredGrid");
      return 0;
    }
    const std::string name = stem + "_" + std::to_string(i) + ".vtu";
    const std::string path = directory.empty() ? name : directory + "/" + name;
    writer->SetFileName(path.c_str());
    writer->SetInputData(grid);
    if (!writer->Write())
    {
      vtkErrorMacro(<< path << ": cannot write time step " << i);
      return 0;
    }
    collection << "    <DataSet timestep=\"" << times[i] << "\" part=\"0\" file=\"" << name
               << "\"/>\n";
  }
  collection << "  </Collection>\n</VTKFile>\n";
  std::ofstream out(pvd, std::ios::binary);
  if (!(out << collection.str()))
  {
    vtkErrorMacro(<< pvd << ": cannot write the collection file");
    return 0;
  }
  return 1;
}
