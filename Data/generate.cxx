// Writes the bundled sample datasets (VTK XML unstructured grids of rational Bézier hexahedra,
// and the teapot's quadrilaterals)
// and, on request, deforming time series and the large wind blade:
//   igaview-generate-data OUTPUT_DIRECTORY [--series STEPS] [--benchmark STEPS] [--blade PATCHES]
//                         [--zoo]
//  --series STEPS     each sample also as NAME_series.pvd + NAME_series/NAME_NNN.vtu, deformed
//                     over time [0, 1] by the same maps as vtkIGASyntheticDeformation
//  --benchmark STEPS  the ~10k patch blade flapping over STEPS time steps (blade_10k_series.pvd)
//  --blade PATCHES    the wind blade with at least PATCHES patches (800000 as in the SST paper) as
//                     wind_blade.pvtu + wind_blade/wind_blade_NNN.vtu pieces of 100k patches
//  --zoo              degenerate_zoo.vtu: the engine tests' degenerate sphere patches in a row
//                     (iga::makeDegenerateZoo)
#include "vtkIGABezierHexahedra.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include "iga/Datasets.h"
#include "iga/DegenerateZoo.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
template<class Set>
bool write(const Set& set, const std::string& file)
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

bool makeDirectory(const std::string& dir)
{
  if (mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
  {
    std::fprintf(stderr, "igaview-generate-data: cannot create %s\n", dir.c_str());
    return false;
  }
  return true;
}

std::string numbered(const std::string& name, int i)
{
  char suffix[16];
  std::snprintf(suffix, sizeof(suffix), "_%03d.vtu", i);
  return name + suffix;
}

/// Writes `make(time)` for `steps` times over [0, 1] as dir/NAME_series/NAME_NNN.vtu and the
/// collection dir/NAME_series.pvd that ParaView reads as one temporal dataset.
template<class Make>
bool writeSeries(const std::string& dir, const std::string& name, int steps, Make make)
{
  const std::string sub = name + "_series";
  if (!makeDirectory(dir + sub))
  {
    return false;
  }
  std::ofstream pvd(dir + sub + ".pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  bool ok = true;
  for (int i = 0; i < steps; ++i)
  {
    const double time = double(i) / (steps - 1);
    const std::string file = sub + "/" + numbered(name, i);
    ok = write(make(time), dir + file) && ok;
    pvd << "  <DataSet timestep=\"" << time << "\" part=\"0\" file=\"" << file << "\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  return ok && pvd.good();
}

/// A static sample deformed like vtkIGASyntheticDeformation does it (sized to its bounds).
bool writeDeformedSeries(const std::string& dir, const std::string& name,
  const iga::VolumeSet<double>& set, iga::DeformationKind kind, int axis, double amount, int steps)
{
  double lo[3], hi[3];
  iga::controlPointBounds(set, lo, hi);
  const iga::Deformation deformation = iga::boxDeformation(kind, axis, lo, hi, amount, 0.5);
  return writeSeries(dir, name, steps,
    [&](double time)
    {
      iga::VolumeSet<double> moved = set;
      iga::deform(moved, deformation, time);
      return moved;
    });
}

const char* xmlType(vtkDataArray* array)
{
  switch (array->GetDataTypeSize())
  {
    case 1:
      return "UInt8";
    case 4:
      return array->GetDataType() == VTK_FLOAT ? "Float32" : "Int32";
    default:
      return array->GetDataType() == VTK_DOUBLE ? "Float64" : "Int64";
  }
}

void describeArrays(std::ofstream& out, vtkDataSetAttributes* data)
{
  for (int a = 0; a < data->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = data->GetArray(a);
    out << "    <PDataArray type=\"" << xmlType(array) << "\" Name=\"" << array->GetName()
        << "\" NumberOfComponents=\"" << array->GetNumberOfComponents() << "\"/>\n";
  }
}

/// The blade in pieces of at most 100k patches (bounded memory) plus a .pvtu that VTK's and
/// ParaView's parallel unstructured grid readers assemble into one grid.
bool writeBlade(const std::string& dir, long patches)
{
  const iga::BladeLayout layout = iga::bladeLayout(patches);
  const long pieceSize = 100000;
  const long pieces = (layout.patchCount() + pieceSize - 1) / pieceSize;
  if (!makeDirectory(dir + "wind_blade"))
  {
    return false;
  }
  std::ofstream pvtu(dir + "wind_blade.pvtu");
  pvtu << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
          "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PUnstructuredGrid "
          "GhostLevel=\"0\">\n";
  bool ok = true;
  for (long p = 0; p < pieces && ok; ++p)
  {
    const auto set = iga::makeBlade<double>(layout, 0.0, p * pieceSize, pieceSize);
    const std::string file = "wind_blade/" + numbered("wind_blade", int(p));
    ok = write(set, dir + file);
    if (p == 0)
    {
      const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(set);
      pvtu << "  <PPointData Scalars=\"" << set.attributeNames[0]
           << "\" RationalWeights=\"RationalWeights\">\n";
      describeArrays(pvtu, grid->GetPointData());
      pvtu << "  </PPointData>\n  <PCellData HigherOrderDegrees=\"HigherOrderDegrees\">\n";
      describeArrays(pvtu, grid->GetCellData());
      pvtu << "  </PCellData>\n  <PPoints>\n    <PDataArray type=\""
           << xmlType(grid->GetPoints()->GetData()) << "\" NumberOfComponents=\"3\"/>\n"
           << "  </PPoints>\n";
    }
    pvtu << "  <Piece Source=\"" << file << "\"/>\n";
  }
  pvtu << "</PUnstructuredGrid>\n</VTKFile>\n";
  std::printf("wrote %swind_blade.pvtu (%ld patches in %ld pieces)\n", dir.c_str(),
    layout.patchCount(), pieces);
  return ok && pvtu.good();
}

} // namespace

int main(int argc, char** argv)
{
  const char* usage = "usage: igaview-generate-data OUTPUT_DIRECTORY [--series STEPS] "
                      "[--benchmark STEPS] [--blade PATCHES] [--zoo]\n";
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
  {
    std::printf("%s", usage);
    return 0;
  }
  if (argc < 2 || argv[1][0] == '-')
  {
    if (argc >= 2)
    {
      std::fprintf(stderr,
        "igaview-generate-data: the first argument must be the output directory, got '%s'\n",
        argv[1]);
    }
    std::fprintf(stderr, "%s", usage);
    return 1;
  }
  long series = 0, benchmark = 0, blade = 0;
  bool zoo = false;
  for (int i = 2; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--zoo")
    {
      zoo = true;
      continue;
    }
    long* target = option == "--series"      ? &series
                   : option == "--benchmark" ? &benchmark
                   : option == "--blade"     ? &blade
                                             : nullptr;
    if (!target)
    {
      std::fprintf(stderr, "igaview-generate-data: unknown option %s\n%s", option.c_str(), usage);
      return 1;
    }
    const long minimum = target == &blade ? 1 : 2;
    char* end = nullptr;
    if (i + 1 >= argc || (*target = std::strtol(argv[++i], &end, 10)) < minimum || *end != '\0' ||
        *target > 100000000)
    {
      std::fprintf(stderr, "igaview-generate-data: %s needs a whole count in %ld..100000000\n%s",
        option.c_str(), minimum, usage);
      return 1;
    }
  }
  const std::string dir = std::string(argv[1]) + "/";
  if (!makeDirectory(argv[1]))
  {
    return 1;
  }
  using Kind = iga::DeformationKind;
  struct Sample
  {
    std::string name;
    iga::VolumeSet<double> set;
    Kind kind; // of the deforming series
    int axis;
    double amount;
  };
  std::vector<Sample> samples = {
    { "twisted_tube", iga::makeTwistedTube<double>(0.5), Kind::Wave, 2, 0.05 },
    { "collapsed_axis_cylinder", iga::makeTube<double>(0.0, 0.0), Kind::Twist, 2, 1.5 },
    { "twisted_teardrop", iga::makeTeardrop<double>(1.2), Kind::Lattice, 0, 0.4 },
    { "dice", iga::makeDice<double>(), Kind::Twist, 2, 1.2 },
    { "cheese", iga::makeCheese<double>(), Kind::Bend, 0, 0.25 },
    { "teapot_shell", iga::makeTeapotShell<double>(0.02), Kind::Wave, 2, 0.04 },
  };
  for (int degree = 2; degree <= 5; ++degree)
  {
    samples.push_back({ "marsden_sphere_p" + std::to_string(degree),
      iga::makeMarsdenSphere<double>(degree), Kind::Lattice, 2, 0.3 });
  }
  bool ok = true;
  for (const Sample& sample : samples)
  {
    ok = write(sample.set, dir + sample.name + ".vtu") && ok;
    if (series)
    {
      ok = writeDeformedSeries(
             dir, sample.name, sample.set, sample.kind, sample.axis, sample.amount, int(series)) &&
           ok;
    }
  }
  if (benchmark)
  {
    const iga::BladeLayout layout = iga::bladeLayout(10000);
    ok = writeSeries(dir, "blade_10k", int(benchmark),
           [&](double time) { return iga::makeBlade<double>(layout, time); }) &&
         ok;
  }
  ok = write(iga::makeTeapot<double>(), dir + "teapot.vtu") && ok;
  if (zoo)
  {
    ok = write(iga::makeDegenerateZoo<double>(), dir + "degenerate_zoo.vtu") && ok;
  }
  if (blade)
  {
    ok = writeBlade(dir, blade) && ok;
  }
  return ok ? 0 : 1;
}
