#include "vtkIGANurbsReader.h"

#include "IGAFileHead.h"

#include "vtkIGANurbsData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtksys/SystemTools.hxx"

#include <cstdio>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

vtkIGANurbsReader::vtkIGANurbsReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkIGANurbsReader::~vtkIGANurbsReader()
{
  this->SetFileName(nullptr);
}

void vtkIGANurbsReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "MemoryLimitMB: " << this->MemoryLimitMB << "\n";
  os << indent << "ExactParameters: " << this->ExactParameters << "\n";
  os << indent << "Patches: " << this->Data->GetNumberOfPatches() << "\n";
}

int vtkIGANurbsReader::CanReadFile(const char* name)
{
  const std::string head = igaFileHead(name ? name : "", 64 * 1024);
  return !head.empty() && this->IsOwnFormat(head) ? 1 : 0;
}

vtkIGANurbsData* vtkIGANurbsReader::GetNurbsData()
{
  return this->Data;
}

int vtkIGANurbsReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Errors wait for RequestData, so that a bad file gives one message, not one per pass.
  const std::string file = this->FileName ? this->FileName : "";
  this->Data->SetExactParameters(this->ExactParameters);
  const std::string stamp = file + "\n" +
                            std::to_string(vtksys::SystemTools::ModifiedTime(file.c_str())) + "\n" +
                            std::to_string(this->MemoryLimitMB) + "\n" +
                            std::to_string(this->ExactParameters) + "\n" + this->InputStamp();
  if (stamp != this->ParsedFile)
  {
    this->ParsedFile = stamp;
    this->Data->SetPatches(iga::NurbsSet<double>());
    std::ifstream in;
    const std::string openProblem = file.empty() ? "no FileName set" : igaOpenRegularFile(file, in);
    if (!openProblem.empty())
    {
      this->Error = openProblem;
    }
    else
    {
      std::string problem = this->FileSizeProblem(file);
      if (problem.empty())
      {
        problem = this->ReadGuarded(in);
      }
      if (problem.empty())
      {
        problem = this->MemoryProblem();
      }
      this->Error.clear();
      if (!problem.empty())
      {
        // "FILE:LINE: problem" when the subclass names a line, "FILE: problem" otherwise.
        const bool hasLine = problem[0] >= '0' && problem[0] <= '9';
        this->Error = file + (hasLine ? ":" : ": ") + problem;
        this->Data->SetPatches(iga::NurbsSet<double>());
      }
    }
  }
  this->Data->FillTimeInformation(outputVector->GetInformationObject(0));
  return 1;
}

std::string vtkIGANurbsReader::ReadGuarded(std::istream& in)
{
  // Whatever a parser or an allocation throws becomes the file's error: a reader inside
  // ParaView must not take the application down.
  try
  {
    // Read at its length, not grown: the text is held once, within MemoryLimitMB.
    in.seekg(0, std::ios::end);
    std::string text(size_t(std::max<std::streamoff>(in.tellg(), 0)), '\0');
    in.seekg(0);
    in.read(&text[0], std::streamsize(text.size()));
    text.resize(size_t(in.gcount()));
    return this->ReadNurbs(text, this->Data);
  }
  catch (const std::bad_alloc&)
  {
    return "not enough memory to read the file (the sizes it gives are too large)";
  }
  catch (const std::exception& e)
  {
    return std::string("cannot be read: ") + e.what();
  }
}

double vtkIGANurbsReader::MemoryLimitBytes() const
{
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  return this->MemoryLimitMB > 0     ? this->MemoryLimitMB * 1048576.0
         : pages > 0 && pageSize > 0 ? 0.5 * double(pages) * double(pageSize)
                                     : VTK_DOUBLE_MAX;
}

std::string vtkIGANurbsReader::FileSizeProblem(const std::string& file) const
{
  const double size = double(vtksys::SystemTools::FileLength(file));
  const double limit = this->MemoryLimitBytes();
  if (size <= limit)
  {
    return std::string();
  }
  char text[192];
  std::snprintf(text, sizeof text,
    "the file holds %.3g GB, more than the reader's memory limit of %.3g GB (MemoryLimitMB)",
    size / 1e9, limit / 1e9);
  return text;
}

std::string vtkIGANurbsReader::MemoryProblem() const
{
  const double limit = this->MemoryLimitBytes();
  const double needed = this->Data->GetBezierCellBytes();
  if (needed <= limit)
  {
    return std::string();
  }
  char text[256];
  std::snprintf(text, sizeof text,
    "its %lld Bézier cells would need %.3g GB to build, more than the reader's memory limit of "
    "%.3g GB (MemoryLimitMB)",
    static_cast<long long>(this->Data->GetNumberOfBezierCells()), needed / 1e9, limit / 1e9);
  return text;
}

int vtkIGANurbsReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Error.empty())
  {
    vtkErrorMacro(<< this->Error);
    return 0;
  }
  this->Data->FillOutput(outputVector->GetInformationObject(0));
  return 1;
}
