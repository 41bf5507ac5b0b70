// igaview: the command-line front end.
//
// Until the SST engine lands, `render` draws VTK's tessellated contour of the Bézier cells (an
// approximation, and said so on the console); the data path (default dataset or .vtu, checks,
// camera framing, PNG output) is the one the engine will use.
#include "vtkIGABezierHexahedra.h"
#include "vtkIGADefaultVolumeSource.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkContourFilter.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

const char* const kUsage = R"(usage: igaview render [INPUT] [options]

Renders the isosurface of a rational Bezier volume dataset to a PNG image.
With no INPUT it renders the bundled default dataset (a twisted rational tube).

INPUT                    VTK XML unstructured grid (.vtu) of VTK_BEZIER_HEXAHEDRON cells
                         with RationalWeights and HigherOrderDegrees
  --iso V                isovalue (repeatable; default: the middle of the attribute's range)
  --surface-by NAME      attribute that defines the surface (default: the first one)
  --color-by NAME        attribute that colours the surface (default: none)
  --size WxH             image size in pixels (default 800x600)
  --time T               deformation time of the default dataset, 0..1 (default 0.5)
  --camera-position x,y,z
  --focal-point x,y,z
  --view-up x,y,z
  --view-angle DEG       a camera that is not given is chosen to frame the data
  -o FILE                output PNG (default igaview.png)
  -h, --help             this text
)";

struct Options
{
  std::string input;
  std::vector<double> isovalues;
  std::string surfaceBy, colorBy, output = "igaview.png";
  int size[2] = { 800, 600 };
  double time = 0.5;
  bool hasPosition = false, hasFocal = false, hasViewUp = false, hasAngle = false;
  double position[3], focal[3], viewUp[3], viewAngle = 30;
};

[[noreturn]] void fail(const std::string& message)
{
  std::fprintf(stderr, "igaview: %s\n", message.c_str());
  std::exit(1);
}

double parseNumber(const std::string& text, const std::string& option)
{
  try
  {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size())
    {
      return value;
    }
  }
  catch (const std::exception&)
  {
  }
  fail(option + " expects a number, got '" + text + "'");
}

void parseTriple(const std::string& text, const std::string& option, double* out)
{
  std::stringstream stream(text);
  std::string part;
  int n = 0;
  while (std::getline(stream, part, ','))
  {
    if (n == 3)
    {
      break;
    }
    out[n++] = parseNumber(part, option);
  }
  if (n != 3 || stream.rdbuf()->in_avail() > 0)
  {
    fail(option + " expects three comma-separated numbers x,y,z, got '" + text + "'");
  }
}

Options parseArguments(int argc, char** argv)
{
  if (argc < 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")
  {
    std::fputs(kUsage, stdout);
    std::exit(argc < 2 ? 1 : 0);
  }
  if (std::string(argv[1]) != "render")
  {
    fail("unknown command '" + std::string(argv[1]) + "' (try: igaview render --help)");
  }
  Options options;
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string
    {
      if (i + 1 >= argc)
      {
        fail(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "-h" || arg == "--help")
    {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    else if (arg == "--iso")
      options.isovalues.push_back(parseNumber(value(), arg));
    else if (arg == "--surface-by")
      options.surfaceBy = value();
    else if (arg == "--color-by")
      options.colorBy = value();
    else if (arg == "--time")
      options.time = parseNumber(value(), arg);
    else if (arg == "-o")
      options.output = value();
    else if (arg == "--size")
    {
      const std::string text = value();
      if (std::sscanf(text.c_str(), "%dx%d", &options.size[0], &options.size[1]) != 2 ||
          options.size[0] < 1 || options.size[1] < 1 || options.size[0] > 16384 ||
          options.size[1] > 16384)
      {
        fail("--size expects WxH with 1..16384 pixels each, got '" + text + "'");
      }
    }
    else if (arg == "--camera-position")
      parseTriple(value(), arg, options.position), options.hasPosition = true;
    else if (arg == "--focal-point")
      parseTriple(value(), arg, options.focal), options.hasFocal = true;
    else if (arg == "--view-up")
      parseTriple(value(), arg, options.viewUp), options.hasViewUp = true;
    else if (arg == "--view-angle")
      options.viewAngle = parseNumber(value(), arg), options.hasAngle = true;
    else if (!arg.empty() && arg[0] == '-')
      fail("unknown option '" + arg + "' (try: igaview render --help)");
    else if (options.input.empty())
      options.input = arg;
    else
      fail("more than one input given: '" + options.input + "' and '" + arg + "'");
  }
  if (!(options.time >= 0 && options.time <= 1))
  {
    fail("--time must lie in 0..1");
  }
  return options;
}

vtkSmartPointer<vtkUnstructuredGrid> loadInput(const Options& options)
{
  if (options.input.empty())
  {
    vtkNew<vtkIGADefaultVolumeSource> source;
    source->SetTime(options.time);
    source->Update();
    std::printf("igaview: no input given, rendering the default dataset (twisted rational tube, "
                "8 tri-quadratic patches, time %g)\n",
                options.time);
    return source->GetOutput();
  }
  if (!std::ifstream(options.input))
  {
    fail("cannot open '" + options.input + "'");
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(options.input.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0 || !reader->GetOutput() ||
      reader->GetOutput()->GetNumberOfCells() == 0)
  {
    fail("'" + options.input + "' is not a readable VTK XML unstructured grid with cells");
  }
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  // Check the cells with the converter the engine will use, and report what VTK would ignore.
  iga::VolumeSet<double> set;
  std::string error;
  std::vector<std::string> warnings;
  if (!vtkIGABezierHexahedra::FromUnstructuredGrid(grid, set, error, warnings))
  {
    fail(options.input + ": " + error);
  }
  for (const auto& warning : warnings)
  {
    std::fprintf(stderr, "igaview: warning: %s: %s\n", options.input.c_str(), warning.c_str());
  }
  std::printf("igaview: %s: %zu patches, attributes:", options.input.c_str(), set.patches.size());
  for (const auto& name : set.attributeNames)
  {
    std::printf(" %s", name.c_str());
  }
  std::printf("\n");
  return grid;
}

} // namespace

int main(int argc, char** argv)
{
  const Options options = parseArguments(argc, argv);
  vtkSmartPointer<vtkUnstructuredGrid> grid = loadInput(options);

  vtkPointData* pd = grid->GetPointData();
  vtkDataArray* surfaceArray =
    options.surfaceBy.empty() ? pd->GetScalars() : pd->GetArray(options.surfaceBy.c_str());
  if (!surfaceArray && options.surfaceBy.empty())
  {
    for (int a = 0; a < pd->GetNumberOfArrays() && !surfaceArray; ++a)
    {
      vtkDataArray* array = pd->GetArray(a);
      if (array && array != pd->GetRationalWeights() && array->GetNumberOfComponents() == 1)
        surfaceArray = array;
    }
  }
  if (!surfaceArray)
  {
    fail(options.surfaceBy.empty() ? "the data has no scalar attribute to contour"
                                   : "no point attribute named '" + options.surfaceBy + "'");
  }
  std::vector<double> isovalues = options.isovalues;
  if (isovalues.empty())
  {
    double range[2];
    surfaceArray->GetRange(range);
    isovalues.push_back(0.5 * (range[0] + range[1]));
  }

  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(grid);
  contour->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, surfaceArray->GetName());
  contour->SetNumberOfContours(static_cast<int>(isovalues.size()));
  for (size_t i = 0; i < isovalues.size(); ++i)
  {
    contour->SetValue(static_cast<int>(i), isovalues[i]);
  }
  contour->ComputeScalarsOff();
  contour->Update();
  std::printf("igaview: interim renderer: VTK's tessellated contour of '%s' (the pixel-exact SST "
              "engine replaces it)\n",
              surfaceArray->GetName());

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(contour->GetOutputPort());
  if (!options.colorBy.empty())
  {
    vtkDataArray* colorArray = pd->GetArray(options.colorBy.c_str());
    if (!colorArray)
    {
      fail("no point attribute named '" + options.colorBy + "' to colour by");
    }
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(options.colorBy.c_str());
    mapper->SetScalarRange(colorArray->GetRange());
    mapper->ScalarVisibilityOn();
  }
  else
  {
    mapper->ScalarVisibilityOff();
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.75, 0.45);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(30);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->SetBackground2(0.32, 0.36, 0.42);
  renderer->GradientBackgroundOn();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(3.5, -4.0, 3.0);
  camera->SetFocalPoint(0, 0, 1);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera(grid->GetBounds());
  if (options.hasAngle)
    camera->SetViewAngle(options.viewAngle);
  if (options.hasFocal)
    camera->SetFocalPoint(options.focal);
  if (options.hasPosition)
    camera->SetPosition(options.position);
  if (options.hasViewUp)
    camera->SetViewUp(options.viewUp);
  renderer->ResetCameraClippingRange(grid->GetBounds());

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(options.size[0], options.size[1]);
  window->Render();

  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(capture->GetOutputPort());
  writer->SetFileName(options.output.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    fail("cannot write '" + options.output + "'");
  }
  std::printf("igaview: wrote %s (%dx%d, %lld triangles)\n",
              options.output.c_str(),
              options.size[0],
              options.size[1],
              static_cast<long long>(contour->GetOutput()->GetNumberOfCells()));
  return 0;
}
