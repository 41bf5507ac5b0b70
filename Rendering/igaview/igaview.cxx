// igaview: the command-line front end. `igaview render` draws isosurfaces of rational Bézier
// volumes through vtkIGAIsosurfaceMapper in an offscreen VTK render window and writes a PNG and,
// on request, the engine's OpenEXR G-buffer of the same frame. `igaview view` shows them in an
// interactive window (trackball camera, keys for the isovalue and time, frame-time readout).
#include "vtkIGABezierFileReading.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGADefaultVolumeSource.h"
#include "vtkIGAEXRWriter.h"
#include "vtkIGAGBufferImage.h"

#include "vtkIGAIsosurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkInformation.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTrivialProducer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Bounds.h"
#include "iga/sst/Engine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

const char* const kUsage = R"(usage: igaview render [INPUT] [options]
       igaview view [INPUT] [options]

render: draws isosurfaces of rational Bezier volumes pixel-exactly (Shared Subdivision Trees) to
a PNG image and optionally an OpenEXR G-buffer.
view: shows them in an interactive window: drag to rotate (trackball), right-drag or wheel to
zoom, middle-drag to pan; Up/Down raise/lower the isovalue by 2% of the attribute's range,
Right/Left step the time (inputs with time steps, e.g. the default dataset), r resets the camera,
q quits. The corner shows the isovalue, the time and the last frame's engine and frame time.
With no INPUT both use the bundled default dataset (a twisted rational tube of 8 tri-quadratic
patches, deforming over the time steps 0..1).

INPUT                    VTK XML unstructured grid (.vtu) of VTK_BEZIER_HEXAHEDRON cells with
                         RationalWeights (and HigherOrderDegrees where a cell's degrees differ)
  --iso V                isovalue (repeatable; default: the middle of the attribute's range)
  --surface-by NAME      attribute that defines the surface (default: the first one)
  --color-by NAME        attribute that colours the surface (default: a plain colour)
  --size WxH             image size in pixels (default 800x600)
  --time T               deformation time of the default dataset, 0..1 (default 0.5)
  --camera-position x,y,z
  --focal-point x,y,z
  --view-up x,y,z
  --view-angle DEG       a camera that is not given is chosen to frame the data
  --threads N            CPU threads (default: all)
  --memory-budget MB     cap on a frame's memory besides the data's copies, in MiB (default
                         4096): the image takes 365 bytes a pixel of it, the engine the rest
  --deadline S           frame deadline in seconds, 0 for none: a frame still running then stops
                         and shows the hits found (default: none for render, 2 for view)
  --backend B            auto, cpu or cuda (default auto: CUDA where built with it and a GPU is
                         present; the environment variable IGAVIEW_BACKEND sets auto's choice)
  -o FILE                output PNG (default igaview.png)
  --exr FILE             also write the G-buffer as OpenEXR: R G B A, Z (eye depth), P.X P.Y P.Z,
                         N.X N.Y N.Z, u v w, patch, and the colour attribute by name (render)
  --keys K1,K2,...       view: press these keys (Up, Down, Left, Right, r), print the state after
                         each, write -o if given, and exit without opening a window (scripts, tests)
  -h, --help             this text
)";

struct Options
{
  bool view = false; ///< `igaview view`
  std::vector<std::string> keys;
  bool hasOutput = false;
  std::string input;
  std::vector<double> isovalues;
  std::string surfaceBy, colorBy, output = "igaview.png", exr;
  int size[2] = { 800, 600 };
  int threads = 0;
  int memoryBudgetMB = 4096;
  double deadline = -1; ///< seconds; -1: the command's default
  iga::sst::Backend backend = iga::sst::Backend::Automatic;
  double time = 0.5;
  bool hasPosition = false, hasFocal = false, hasViewUp = false;
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
    if (used == text.size() && std::isfinite(value))
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
      fail(option + " expects three comma-separated numbers x,y,z, got '" + text + "'");
    }
    out[n++] = parseNumber(part, option);
  }
  if (n != 3)
  {
    fail(option + " expects three comma-separated numbers x,y,z, got '" + text + "'");
  }
}

/// A whole number in lo..hi, else fail naming the option and the text as typed.
int parseWholeNumber(const std::string& text, const std::string& option, int lo, int hi)
{
  const double number = parseNumber(text, option);
  if (!(number >= lo && number <= hi && number == std::floor(number)))
    fail(option + " expects a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
         ", got '" + text + "'");
  return int(number);
}

/// The image's share of the memory budget (vtkIGAIsosurfaceMapper::GetImageBytes), refused
/// before anything is read or allocated.
void checkImageBudget(const Options& options)
{
  const double needed = vtkIGAIsosurfaceMapper::GetImageBytes(options.size[0], options.size[1]);
  if (needed > double(options.memoryBudgetMB) * 1048576.0)
  {
    char text[256];
    std::snprintf(text, sizeof text,
      "--size %dx%d needs %.0f MiB for the image (%.0f bytes a pixel), more than the memory "
      "budget of %d MiB: lower --size or raise --memory-budget",
      options.size[0], options.size[1], std::ceil(needed / 1048576.0),
      needed / (double(options.size[0]) * options.size[1]), options.memoryBudgetMB);
    fail(text);
  }
}

Options parseArguments(int argc, char** argv)
{
  if (argc < 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")
  {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    std::exit(argc < 2 ? 1 : 0);
  }
  if (std::string(argv[1]) != "render" && std::string(argv[1]) != "view")
  {
    fail("unknown command '" + std::string(argv[1]) + "' (try: igaview --help)");
  }
  Options options;
  options.view = std::string(argv[1]) == "view";
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
      options.output = value(), options.hasOutput = true;
    else if (arg == "--keys" && options.view)
    {
      std::stringstream keys(value());
      std::string key;
      while (std::getline(keys, key, ','))
      {
        if (key != "Up" && key != "Down" && key != "Left" && key != "Right" && key != "r")
          fail("--keys: unknown key '" + key + "' (Up, Down, Left, Right, r)");
        options.keys.push_back(key);
      }
    }
    else if (arg == "--exr")
      options.exr = value();
    else if (arg == "--threads")
      options.threads = parseWholeNumber(value(), arg, 1, 1024);
    else if (arg == "--memory-budget")
      options.memoryBudgetMB = parseWholeNumber(value(), arg, 16, 1048576);
    else if (arg == "--deadline")
    {
      const std::string text = value();
      options.deadline = parseNumber(text, arg);
      if (!(options.deadline >= 0 && options.deadline <= 1e6))
        fail("--deadline expects seconds in 0..1e6, got '" + text + "'");
    }
    else if (arg == "--backend")
    {
      try
      {
        options.backend = iga::sst::parseBackend(value());
      }
      catch (const std::invalid_argument& e)
      {
        fail(std::string("--backend: ") + e.what());
      }
    }
    else if (arg == "--size")
    {
      const std::string text = value();
      char rest = 0;
      if (std::sscanf(text.c_str(), "%dx%d%c", &options.size[0], &options.size[1], &rest) != 2 ||
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
    {
      options.viewAngle = parseNumber(value(), arg);
      if (!(options.viewAngle > 0 && options.viewAngle < 180))
        fail("--view-angle must lie strictly between 0 and 180 degrees");
    }
    else if (!arg.empty() && arg[0] == '-')
      fail("unknown option '" + arg + "' (try: igaview --help)");
    else if (options.input.empty())
      options.input = arg;
    else
      fail("more than one input given: '" + options.input + "' and '" + arg + "'");
  }
  if (!(options.time >= 0 && options.time <= 1))
  {
    fail("--time must lie in 0..1");
  }
  checkImageBudget(options);
  return options;
}

/// The input's producer (the default dataset's source, or the grid of a .vtu read as the
/// mapper would take it), updated, and its patches.
vtkSmartPointer<vtkAlgorithm> loadInput(const Options& options, iga::VolumeSet<double>& set)
{
  std::string error;
  std::vector<std::string> warnings;
  vtkSmartPointer<vtkAlgorithm> producer;
  std::string name = options.input;
  if (options.input.empty())
  {
    auto source = vtkSmartPointer<vtkIGADefaultVolumeSource>::New();
    source->SetTime(options.time);
    source->Update();
    producer = source;
    name = "default dataset";
    std::printf("igaview: no input given, rendering the default dataset (twisted rational tube, "
                "8 tri-quadratic patches, time %g)\n",
      options.time);
    if (!vtkIGABezierHexahedra::FromUnstructuredGrid(source->GetOutput(), set, error, warnings))
    {
      fail(name + ": " + error);
    }
  }
  else
  {
    const auto grid = vtkIGABezierFileReading::Read(options.input, nullptr, set, error, warnings);
    if (!grid)
    {
      fail(error);
    }
    auto trivial = vtkSmartPointer<vtkTrivialProducer>::New();
    trivial->SetOutput(grid);
    producer = trivial;
  }
  for (const auto& warning : warnings)
  {
    std::fprintf(stderr, "igaview: warning: %s: %s\n", name.c_str(), warning.c_str());
  }
  return producer;
}

int attributeIndex(const iga::VolumeSet<double>& set, const std::string& name, const char* option)
{
  const auto it = std::find(set.attributeNames.begin(), set.attributeNames.end(), name);
  if (it == set.attributeNames.end())
  {
    std::string known;
    for (const auto& n : set.attributeNames)
      known += (known.empty() ? "" : ", ") + n;
    fail(std::string(option) + ": no attribute named '" + name + "' (have: " + known + ")");
  }
  return int(it - set.attributeNames.begin());
}

/// Range of an attribute over all patches (Bernstein coefficients bound the field).
void attributeRange(const iga::VolumeSet<double>& set, int attribute, double* range)
{
  range[0] = INFINITY;
  range[1] = -INFINITY;
  for (const auto& patch : set.patches)
  {
    double lo, hi;
    iga::rationalRange<double, 3>(
      patch.view(), iga::kFirstAttributeChannel + attribute, iga::kWeightChannel, lo, hi);
    range[0] = std::min(range[0], lo);
    range[1] = std::max(range[1], hi);
  }
}

iga::Camera chooseCamera(const Options& options, const iga::VolumeSet<double>& set)
{
  double bounds[6];
  iga::sst::patchBounds(set.patches, bounds);
  // Default view: from the front right and above, z up, framing the data like ResetCamera.
  iga::Camera camera =
    iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, options.viewAngle);
  if (options.hasFocal)
    camera.focalPoint = glm::make_vec3(options.focal);
  if (options.hasPosition)
    camera.position = glm::make_vec3(options.position);
  if (options.hasViewUp)
    camera.viewUp = glm::make_vec3(options.viewUp);
  if (camera.position == camera.focalPoint)
  {
    fail("the camera position is the focal point: there is no view direction");
  }
  if (camera.viewUp == glm::dvec3(0.0))
  {
    fail("--view-up is the zero vector");
  }
  const glm::dvec3 side =
    glm::cross(iga::viewDirection(camera), iga::normalizedOrZero(camera.viewUp));
  if (glm::dot(side, side) < 1e-20)
  {
    fail("the view-up direction is parallel to the view direction");
  }
  iga::fitClippingRange(camera, bounds);
  return camera;
}

/// The interactive viewer's state and keys: isovalues shift by a step, time moves over the
/// input's time steps, and a corner text shows them with the last frame's times.
struct Viewer
{
  vtkAlgorithm* producer;
  vtkIGAIsosurfaceMapper* mapper;
  vtkRenderer* renderer;
  vtkTextActor* readout;
  std::string surfaceName;
  std::vector<double> isovalues;
  double isoStep;
  std::vector<double> times;
  size_t timeIndex = 0;

  void setTime() { this->producer->UpdateTimeStep(this->times[this->timeIndex]); }

  /// Applies a key; false for keys it does not handle.
  bool press(const std::string& key)
  {
    if (key == "Up" || key == "Down")
    {
      for (size_t k = 0; k < this->isovalues.size(); ++k)
      {
        this->isovalues[k] += key == "Up" ? this->isoStep : -this->isoStep;
        this->mapper->SetIsovalue(int(k), this->isovalues[k]);
      }
      return true;
    }
    if ((key == "Right" || key == "Left") && !this->times.empty())
    {
      const size_t n = this->times.size();
      this->timeIndex = (this->timeIndex + (key == "Right" ? 1 : n - 1)) % n;
      this->setTime();
      return true;
    }
    if (key == "r")
    {
      this->renderer->ResetCamera();
      return true;
    }
    return false;
  }

  std::string state() const
  {
    std::string text = this->surfaceName + " =";
    for (double iso : this->isovalues)
    {
      text += " " + std::to_string(iso);
    }
    if (!this->times.empty())
    {
      text += "   time " + std::to_string(this->times[this->timeIndex]);
    }
    return text;
  }

  /// The corner text, after a frame: state, engine and whole-frame milliseconds.
  void updateReadout()
  {
    char times[96];
    std::snprintf(times, sizeof(times), "\nengine %.1f ms   frame %.1f ms",
      this->mapper->GetLastEngineTime(), 1000 * this->renderer->GetLastRenderTimeInSeconds());
    this->readout->SetInput((this->state() + times).c_str());
  }
};

/// The viewer: an interactive window, or with --keys the same key handling offscreen (the
/// caller then writes the last frame like `render` does).
void runViewer(const Options& options, Viewer& viewer, vtkRenderWindow* window)
{
  vtkInformation* info = viewer.producer->GetOutputInformation(0);
  if (info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    const double* steps = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    viewer.times.assign(
      steps, steps + info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
    // Start at the step nearest the requested time.
    for (size_t k = 0; k < viewer.times.size(); ++k)
    {
      if (std::abs(viewer.times[k] - options.time) <
          std::abs(viewer.times[viewer.timeIndex] - options.time))
        viewer.timeIndex = k;
    }
    viewer.setTime();
  }
  viewer.readout->GetTextProperty()->SetFontSize(16);
  viewer.readout->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  viewer.readout->SetPosition(10, 10);
  viewer.renderer->AddActor2D(viewer.readout);
  if (!options.keys.empty())
  {
    window->Render();
    for (const auto& key : options.keys)
    {
      viewer.press(key);
      window->Render();
      viewer.updateReadout();
      std::printf("igaview: key %s: %s, %zu pixels covered, engine %.1f ms, frame %.1f ms\n",
        key.c_str(), viewer.state().c_str(), viewer.mapper->GetLastGBuffer().coveredPixels(),
        viewer.mapper->GetLastEngineTime(), 1000 * viewer.renderer->GetLastRenderTimeInSeconds());
    }
    window->Render();
    return;
  }
  window->SetOffScreenRendering(0);
  window->SetWindowName("igaview");
  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  interactor->SetRenderWindow(window);
  vtkNew<vtkCallbackCommand> onKey;
  onKey->SetClientData(&viewer);
  onKey->SetCallback(
    [](vtkObject* caller, unsigned long, void* data, void*)
    {
      auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
      if (static_cast<Viewer*>(data)->press(interactor->GetKeySym()))
        interactor->Render();
    });
  interactor->AddObserver(vtkCommand::KeyPressEvent, onKey);
  vtkNew<vtkCallbackCommand> onFrame;
  onFrame->SetClientData(&viewer);
  onFrame->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<Viewer*>(data)->updateReadout(); });
  window->AddObserver(vtkCommand::EndEvent, onFrame);
  interactor->Initialize();
  window->Render();
  interactor->Start();
}

} // namespace

int main(int argc, char** argv)
{
  const Options options = parseArguments(argc, argv);
  iga::VolumeSet<double> set;
  const vtkSmartPointer<vtkAlgorithm> producer = loadInput(options, set);

  const int surface =
    options.surfaceBy.empty() ? 0 : attributeIndex(set, options.surfaceBy, "--surface-by");
  const int colour =
    options.colorBy.empty() ? -1 : attributeIndex(set, options.colorBy, "--color-by");
  double surfaceRange[2], colourRange[2] = { 0, 1 };
  attributeRange(set, surface, surfaceRange);
  std::vector<double> isovalues = options.isovalues;
  if (isovalues.empty())
    isovalues.push_back(0.5 * (surfaceRange[0] + surfaceRange[1]));
  const iga::Camera view = chooseCamera(options, set);

  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  mapper->SetInputConnection(producer->GetOutputPort());
  mapper->SetSurfaceArrayName(set.attributeNames[surface].c_str());
  mapper->SetNumberOfThreads(options.threads);
  mapper->SetMemoryBudgetMB(options.memoryBudgetMB);
  // An interactive window answers within two seconds unless told otherwise.
  mapper->SetFrameDeadline(options.deadline >= 0 ? options.deadline : options.view ? 2.0 : 0.0);
  // The mapper's BackendType follows the engine's Backend order (auto, CPU, CUDA).
  mapper->SetBackend(int(options.backend));
  for (size_t k = 0; k < isovalues.size(); ++k)
    mapper->SetIsovalue(int(k), isovalues[k]);
  vtkNew<vtkColorTransferFunction> coolToWarm; // ParaView's default map
  if (colour >= 0)
  {
    attributeRange(set, colour, colourRange);
    if (!(colourRange[1] > colourRange[0]))
      colourRange[1] = colourRange[0] + 1;
    coolToWarm->SetColorSpaceToDiverging();
    coolToWarm->AddRGBPoint(colourRange[0], 0.231, 0.298, 0.753);
    coolToWarm->AddRGBPoint(colourRange[1], 0.706, 0.016, 0.150);
    mapper->SetLookupTable(coolToWarm);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(set.attributeNames[colour].c_str());
    mapper->SetScalarRange(colourRange);
    mapper->ScalarVisibilityOn();
  }
  else
  {
    mapper->ScalarVisibilityOff();
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.75, 0.45);
  actor->GetProperty()->SetAmbient(0.1);
  actor->GetProperty()->SetDiffuse(0.9);
  actor->GetProperty()->SetSpecular(0.35);
  actor->GetProperty()->SetSpecularPower(40);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->SetBackground2(0.32, 0.36, 0.42);
  renderer->GradientBackgroundOn();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(glm::value_ptr(view.position));
  camera->SetFocalPoint(glm::value_ptr(view.focalPoint));
  camera->SetViewUp(glm::value_ptr(view.viewUp));
  camera->SetViewAngle(view.viewAngle);
  camera->SetClippingRange(view.clippingRange);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(options.size[0], options.size[1]);

  std::string isoText;
  for (double iso : isovalues)
    isoText += (isoText.empty() ? "" : ", ") + std::to_string(iso);
  std::printf("igaview: %zu patches, isosurface %s = %s, %dx%d pixels\n", set.patches.size(),
    set.attributeNames[surface].c_str(), isoText.c_str(), options.size[0], options.size[1]);
  if (options.view)
  {
    vtkNew<vtkTextActor> readout;
    Viewer viewer{ producer, mapper, renderer, readout, set.attributeNames[surface], isovalues,
      0.02 * (surfaceRange[1] - surfaceRange[0]), {}, 0 };
    runViewer(options, viewer, window);
    if (options.keys.empty() || !options.hasOutput)
      return 0;
  }
  else
  {
    window->Render();
  }
  // Errors of the engine surface as VTK errors; make them fatal and on one line.
  const iga::sst::GBuffer& gbuffer = mapper->GetLastGBuffer();
  if (gbuffer.width != options.size[0] || gbuffer.height != options.size[1])
  {
    fail("the isosurface could not be rendered (see the message above)");
  }
  std::printf("igaview: %zu pixels covered in %.1f ms (SST engine, %s)\n", gbuffer.coveredPixels(),
    mapper->GetLastEngineTime(), mapper->GetLastBackend());

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  png->SetFileName(options.output.c_str());
  png->Write();
  if (png->GetErrorCode() != 0)
    fail("cannot write '" + options.output + "'");
  std::printf("igaview: wrote %s\n", options.output.c_str());
  if (!options.exr.empty())
  {
    vtkNew<vtkIGAEXRWriter> writer;
    writer->SetInputData(vtkIGAGBufferImage::Convert(
      gbuffer, mapper->GetLastColours().data(), colour >= 0 ? set.attributeNames[colour] : ""));
    writer->SetFileName(options.exr.c_str());
    writer->Write();
    if (writer->GetErrorCode() != 0)
      fail(writer->GetLastError());
    std::printf("igaview: wrote %s\n", options.exr.c_str());
  }
  return 0;
}
