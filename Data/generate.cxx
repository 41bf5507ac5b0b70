// Writes the bundled sample datasets (VTK XML unstructured grids of rational Bézier hexahedra):
//   igaview-generate-data OUTPUT_DIRECTORY
#include "vtkIGABezierHexahedra.h"

#include "vtkNew.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include "iga/Datasets.h"

#include <cstdio>
#include <string>

namespace
{
bool write(const iga::VolumeSet<double>& set, const std::string& file)
{
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(set));
  writer->SetFileName(file.c_str());
  writer->SetCompressorTypeToZLib();
  writer->SetDataModeToBinary();
  if (!writer->Write())
  {
    std::fprintf(stderr, "igaview-generate-data: cannot write %s\n", file.c_str());
    return false;
  }
  std::printf("wrote %s (%zu patches)\n", file.c_str(), set.patches.size());
  return true;
}
}

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: igaview-generate-data OUTPUT_DIRECTORY\n");
    return 1;
  }
  const std::string dir = std::string(argv[1]) + "/";
  bool ok = write(iga::makeTwistedTube<double>(0.5), dir + "twisted_tube.vtu");
  ok = write(iga::makeTube<double>(0.0, 0.0), dir + "collapsed_axis_cylinder.vtu") && ok;
  ok = write(iga::makeTeardrop<double>(1.2), dir + "twisted_teardrop.vtu") && ok;
  for (int degree = 2; degree <= 5; ++degree)
  {
    ok = write(iga::makeMarsdenSphere<double>(degree),
           dir + "marsden_sphere_p" + std::to_string(degree) + ".vtu") &&
         ok;
  }
  return ok ? 0 : 1;
}
