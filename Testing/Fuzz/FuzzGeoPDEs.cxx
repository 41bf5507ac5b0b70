// libFuzzer target: arbitrary bytes as a GeoPDEs text file (vtkIGAGeoPDEsReader).
#include "FuzzReader.h"
#include "vtkIGAGeoPDEsReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  return fuzzNurbsReader<vtkIGAGeoPDEsReader>(data, size, ".txt");
}
