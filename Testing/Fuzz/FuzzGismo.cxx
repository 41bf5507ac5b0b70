// libFuzzer target: arbitrary bytes as a G+Smo XML file (vtkIGAGismoReader).
#include "FuzzReader.h"
#include "vtkIGAGismoReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  return fuzzNurbsReader<vtkIGAGismoReader>(data, size, ".xml");
}
