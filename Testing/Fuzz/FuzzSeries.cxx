// libFuzzer target: arbitrary bytes as a .pvd collection (vtkIGABezierSeriesReader), in a
// directory holding one good step, `step.vtu` (a bundled sphere), which the seeds name.
#include "FuzzReader.h"
#include "vtkIGABezierSeriesReader.h"

#include <sys/stat.h>

#include <cstdio>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string directory = []
  {
    const std::string d = "/dev/shm/igaview-fuzz-series-" + std::to_string(getpid());
    mkdir(d.c_str(), 0700);
    const std::string step = d + "/step.vtu";
    std::remove(step.c_str());
    if (symlink(IGAVIEW_DATA_DIR "/marsden_sphere_p2.vtu", step.c_str()) != 0)
    {
      __builtin_trap();
    }
    return d;
  }();
  vtkNew<vtkIGABezierSeriesReader> reader;
  return fuzzReader(reader.Get(), data, size, directory + "/collection.pvd");
}
