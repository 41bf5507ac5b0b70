// libFuzzer target: arbitrary bytes as a .vtu read the way igaview and the mapper read one
// (vtkIGABezierFileReading: header size checks, VTK's XML reader, the Bézier conversion), with
// a 256 MiB limit on what a header may claim.
#include "vtkIGABezierFileReading.h"

#include "vtkObject.h"
#include "vtkUnstructuredGrid.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  vtkObject::GlobalWarningDisplayOff();
  const std::string text(reinterpret_cast<const char*>(data), size);
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  const auto grid =
    vtkIGABezierFileReading::Read("fuzz.vtu", &text, patches, error, warnings, 256.0 * (1 << 20));
  // Either a grid with its patches or one message; never both, never neither.
  const size_t cells = patches.volumes.patches.size() + patches.surfaces.size();
  if (!grid == error.empty() || (grid && cells != size_t(grid->GetNumberOfCells())))
  {
    __builtin_trap();
  }
  return 0;
}
