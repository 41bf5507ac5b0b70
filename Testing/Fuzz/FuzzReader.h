// The body of the reader fuzz targets: the bytes as a file read by a reader; the output is
// either cells or one error, never a crash.
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

/// Writes the bytes to `file`, reads it with `reader` (configured otherwise) and traps when
/// cells and an error come together.
template<class Reader>
int fuzzReader(Reader* reader, const uint8_t* data, size_t size, const std::string& file)
{
  vtkObject::GlobalWarningDisplayOff();
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), long(size));
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(file.c_str());
  reader->Update();
  if (errors->Errors > 0 && reader->GetOutput()->GetNumberOfCells() > 0)
  {
    __builtin_trap();
  }
  return 0;
}

/// A NURBS reader with a 64 MiB memory limit.
template<class Reader>
int fuzzNurbsReader(const uint8_t* data, size_t size, const char* extension)
{
  static const std::string file = "/dev/shm/igaview-fuzz-" + std::to_string(getpid()) + extension;
  vtkNew<Reader> reader;
  reader->SetMemoryLimitMB(64);
  return fuzzReader(reader.Get(), data, size, file);
}
