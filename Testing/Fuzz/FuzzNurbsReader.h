// The body of the NURBS reader fuzz targets: the bytes as a file read by `Reader` with a
// 64 MiB memory limit; the output is either Bézier cells or one error, never a crash.
#pragma once

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkUnstructuredGrid.h"

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <unistd.h>

/// Counts the reader's errors.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Errors; }
  int Errors = 0;
};

template<class Reader>
int fuzzNurbsReader(const uint8_t* data, size_t size, const char* extension)
{
  vtkObject::GlobalWarningDisplayOff();
  static const std::string file = "/dev/shm/igaview-fuzz-" + std::to_string(getpid()) + extension;
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), long(size));
  vtkNew<Reader> reader;
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(file.c_str());
  reader->SetMemoryLimitMB(64);
  reader->Update();
  // Cells and an error never come together.
  if (errors->Errors > 0 && reader->GetOutput()->GetNumberOfCells() > 0)
  {
    __builtin_trap();
  }
  return 0;
}
