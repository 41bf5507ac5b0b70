// libFuzzer target: arbitrary bytes as an MFEM NURBS mesh (vtkIGAMFEMReader), or, when they
// begin like a GridFunction ("FiniteElementSpace"), as a GridFunction on Data's quarter ring.
#include "FuzzReader.h"
#include "vtkIGAMFEMReader.h"

#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const char kField[] = "FiniteElementSpace";
  if (size < sizeof(kField) - 1 || std::memcmp(data, kField, sizeof(kField) - 1) != 0)
  {
    return fuzzNurbsReader<vtkIGAMFEMReader>(data, size, ".mesh");
  }
  static const std::string field = "/dev/shm/igaview-fuzz-" + std::to_string(getpid()) + ".gf";
  std::ofstream(field, std::ios::binary).write(reinterpret_cast<const char*>(data), long(size));
  vtkNew<vtkIGAMFEMReader> reader;
  reader->SetMemoryLimitMB(64);
  reader->AddGridFunctionFileName(field.c_str());
  static const std::string mesh = std::string(IGAVIEW_DATA_DIR) + "/mfem_quarter_ring.mesh";
  std::ifstream in(mesh, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return fuzzReader(reader.Get(), reinterpret_cast<const uint8_t*>(text.data()), text.size(),
    "/dev/shm/igaview-fuzz-" + std::to_string(getpid()) + "-ring.mesh");
}
