#include "vtkIGABezierFileReading.h"

#include "IGAFileHead.h"
#include "IGAXMLArrays.h"

#include "vtkIGABezierHexahedra.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkStringOutputWindow.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>
#include <stdexcept>
#include <unistd.h>

namespace
{

/// "" or why the header's pieces claim more points or cells than `memory` bytes hold.
std::string claimedSizesProblem(const std::string& name, const std::string& head, double memory)
{
  // Bytes each point or cell needs at least: three coordinates; a connectivity entry, an
  // offset and a type.
  for (const auto& [key, bytes] : { std::pair<std::string, double>{ "NumberOfPoints=\"", 24.0 },
         std::pair<std::string, double>{ "NumberOfCells=\"", 17.0 } })
  {
    double claimed = 0;
    for (size_t at = head.find(key); at != std::string::npos; at = head.find(key, at + 1))
    {
      // strtod stops at the closing quote; the head ends in a NUL, so an open one stops too.
      claimed += std::strtod(head.c_str() + at + key.size(), nullptr);
    }
    if (!(claimed * bytes < memory))
    {
      char text[256];
      std::snprintf(text, sizeof text,
        "'%s' claims %.4g %s, which need at least %.3g GB, more than this machine's %.3g GB",
        name.c_str(), claimed, key[8] == 'P' ? "points" : "cells", claimed * bytes / 1e9,
        memory / 1e9);
      return text;
    }
  }
  return std::string();
}

/// The first megabyte of the input.
std::string headOf(const std::string& name, const std::string* text)
{
  return text ? text->substr(0, 1 << 20) : igaFileHead(name, 1 << 20);
}

} // namespace

bool vtkIGABezierFileReading::RunQuietly(const std::function<bool()>& request, std::string& message)
{
  const vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkNew<vtkStringOutputWindow> collected;
  vtkOutputWindow::SetInstance(collected);
  const vtkLogger::Verbosity verbosity = vtkLogger::GetCurrentVerbosityCutoff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // VTK's log repeats each message
  bool ok = false;
  message.clear();
  try
  {
    ok = request();
  }
  catch (const std::bad_alloc&)
  {
    message = "not enough memory to read it (the sizes it gives are too large)";
  }
  catch (const std::exception& e)
  {
    message = std::string("cannot be read: ") + e.what();
  }
  vtkLogger::SetStderrVerbosity(verbosity);
  vtkOutputWindow::SetInstance(previous);
  if (!message.empty())
  {
    return false;
  }
  // VTK writes "ERROR: In FILE, line N\nCLASS (ADDRESS): TEXT\n\n".
  const std::string text = collected->GetOutput();
  const size_t open = text.find("(0x");
  const size_t start = open == std::string::npos ? open : text.find("): ", open);
  if (start != std::string::npos)
  {
    message = text.substr(start + 3, text.find('\n', start) - (start + 3));
  }
  return ok;
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGABezierFileReading::Read(const std::string& name,
  const std::string* text, vtkIGABezierHexahedra::Patches& patches, std::string& error,
  std::vector<std::string>& warnings, double memoryLimitBytes)
{
  patches = vtkIGABezierHexahedra::Patches();
  std::ifstream file;
  if (!text && !(error = igaOpenRegularFile(name, file)).empty())
  {
    return nullptr;
  }
  const double memory = memoryLimitBytes > 0
                          ? memoryLimitBytes
                          : double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  const std::string head = headOf(name, text);
  error = claimedSizesProblem(name, head, memory);
  if (error.empty())
  {
    error = igaXMLArrayProblem(name, text, text ? *text : head, memory);
  }
  if (!error.empty())
  {
    return nullptr;
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  if (text)
  {
    reader->ReadFromInputStringOn();
    reader->SetInputString(*text);
  }
  else
  {
    reader->SetFileName(name.c_str());
  }
  std::string readerMessage;
  const bool read = RunQuietly(
    [&]
    {
      reader->Update();
      return reader->GetErrorCode() == 0;
    },
    readerMessage);
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->ShallowCopy(reader->GetOutput());
  if (!read || grid->GetNumberOfCells() == 0)
  {
    error = "'" + name + "' is not a readable VTK XML unstructured grid with cells" +
            (readerMessage.empty() ? "" : " (" + readerMessage + ")");
    return nullptr;
  }
  if (!readerMessage.empty())
  {
    warnings.push_back(readerMessage);
  }
  if (!vtkIGABezierHexahedra::FromUnstructuredGrid(grid, patches, error, warnings))
  {
    error = "'" + name + "': " + error;
    return nullptr;
  }
  return grid;
}
