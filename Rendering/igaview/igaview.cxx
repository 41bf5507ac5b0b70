// igaview: the command-line front end. `igaview render` draws isosurfaces of rational Bézier
// volumes, or the surfaces of a geometry (volumes' boundaries, surface patches), through
// vtkIGAIsosurfaceMapper in an offscreen VTK render window and writes a PNG and, on request, the
// engine's OpenEXR G-buffer of the same frame. `igaview view` shows them in an interactive
// window (trackball camera, keys for the isovalue and time, frame-time readout).
#include "vtkIGAAlgebraicSource.h"
#include "vtkIGABezierFileReading.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGABezierSeriesReader.h"
#include "vtkIGADeepEXR.h"
#include "vtkIGADefaultVolumeSource.h"
#include "vtkIGAEXRWriter.h"
#include "vtkIGAGBufferImage.h"
#include "vtkIGAGeoPDEsReader.h"
#include "vtkIGAGismoReader.h"
#include "vtkIGAMFEMReader.h"

#include "vtkIGAIsosurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTrivialProducer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include "iga/AlgebraicGallery.h"
#include "iga/AttributeRange.h"
#include "iga/BernsteinRoots.h"
#include "iga/Bounds.h"
#include "iga/Csg.h"
#include "iga/NurbsSet.h"
#include "iga/sst/Engine.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

const char* const kUsage = R"(usage: igaview render [INPUT] [options]
       igaview view [INPUT] [options]

render: draws isosurfaces of rational Bezier volumes, or the surfaces of a geometry (the
boundary of its volumes and its surface patches), pixel-exactly (Shared Subdivision Trees; ray
composition for patches with affine geometry) to a PNG image and optionally an OpenEXR
G-buffer; or an algebraic surface f(x, y, z) = 0 (--algebraic, --gallery).
view: shows them in an interactive window: drag to rotate (trackball), right-drag or wheel to
zoom, middle-drag to pan; Up/Down raise/lower the isovalue by 2% of the attribute's range,
Right/Left step the time (inputs with time steps: the default dataset, a .pvd series), r resets
the camera,
q quits. The corner shows the isovalue, the time, the last frame's engine and frame time, and
the hit under the cursor (its cell, position, parameter and attributes, exact).
With no INPUT both use the bundled default dataset (a twisted rational tube of 8 tri-quadratic
patches, deforming over the time steps 0..1).

INPUT                    VTK XML unstructured grid (.vtu) of VTK_BEZIER_HEXAHEDRON and
                         VTK_BEZIER_QUADRILATERAL cells with RationalWeights (and
                         HigherOrderDegrees where a cell's degrees differ), a .pvd collection of
                         such files (a time series: one file a time step), a G+Smo XML or
                         GeoPDEs text geometry, or an MFEM NURBS mesh (.mesh), each format known
                         by its content: drawn as surfaces, or isosurfaces of the first solution
                         field (G+Smo MultiPatches after the geometry's, MFEM --field)
  --field FILE           an MFEM GridFunction (.gf) on the MFEM mesh given as INPUT, an attribute
                         named after the file (repeatable); isosurfaces of the first are drawn
                         unless --surface or --surface-by says otherwise
  --exact-parameters     a G+Smo, GeoPDEs or MFEM file's parameter_u/v/w exact where weights
                         vary (those patches' cells one degree higher); else Greville abscissae,
                         exact on polynomial patches only
  --algebraic EXPR       instead of INPUT, the algebraic surface EXPR = 0: a polynomial in x, y,
                         z (+ - * ^ by whole exponents, / by constants, parentheses, decimal
                         constants; total degree up to 16) over --box, as the exact Bernstein
                         volume of attribute f (isovalue 0 unless --iso says otherwise)
  --box x0,x1,y0,y1,z0,z1
                         the box --algebraic draws over (default -1.2,1.2,-1.2,1.2,-1.2,1.2)
  --gallery NAME         instead of INPUT, a surface of the papers' gallery over its own box:
                         sphere, cayley, clebsch, kummer, dervish, kiss, heart, klein,
                         linked-tori, tangle, barth-decic, super-sphere
  --abs-cells N          with --algebraic or --gallery: an algebraic B-spline (ABS) field instead,
                         the surface's f fitted on N x N x N elements (1..64), the elements it
                         crosses kept (Wei and Feng's scenes)
  --abs-degree P         the ABS field's degree per direction, 1..3 (default 3)
  --method M             auto (default: patches with affine geometry by ray composition, the
                         others by the SST), sst, or ray-composition (every patch; curved ones
                         are refused)
  --root-finder NAME     ray composition's root finder: subdivision, knot-insertion,
                         bezier-clipping, point-insertion (default) or polar-newton
  --frame-coherency      ray composition: each frame's roots seeded by the frame before's hits
                         (view: camera moves and time steps draw faster; the image is unchanged)
  --antialias            silhouette anti-aliasing: pixels whose colour differs from a
                         neighbour's drawn again with four rays on a rotated grid, averaged
  --surface              draw the surfaces (volumes' boundaries, surface patches), not
                         isosurfaces; the default for geometry files and for input without volumes
  --edges                draw the element edges (every knot line of NURBS input) over the surface
  --csg EXPR             draw the solid EXPR of the volumes: NAME<VALUE, NAME>VALUE (an
                         attribute's solid), domain (the volumes), plane(a,b,c,d) (the half-space
                         a x + b y + c z + d >= 0), joined by | (union), & (intersection, binds
                         tighter), - (difference), grouped by ( ); e.g. "cube<0 - pips<0". Where
                         the solid meets the volumes' boundary, the boundary closes it
  --slice a,b,c,d        draw the section a x + b y + c z + d = 0 of the volumes (repeatable),
                         alone or with --csg
  --clip a,b,c,d         keep the part a x + b y + c z + d >= 0, its cut face drawn (repeatable):
                         the volumes, or the --csg solid, intersected with the half-space, and
                         the slices cut by it
  --iso V                isovalue (repeatable; default: the middle of the range the attribute
                         takes, found by subdivision to 1e-5 of its spread)
  --surface-by NAME      attribute that defines the surface (default: the first one)
  --color-by NAME        attribute that colours the surface (default: a plain colour), or
                         curvature_mean / curvature_gauss: the isosurface's mean or Gaussian
                         curvature at each pixel (the map spans its 2nd to 98th percentile)
  --size WxH             image size in pixels (default 800x600)
  --time T               the time drawn: the default dataset's deformation time, 0..1, or
                         the time step nearest T of a .pvd series (default 0.5)
  --series               render: draw every time step (the default dataset's 11, a .pvd's) to
                         -o, --exr and --deep-exr numbered _000, _001, ... before the extension,
                         with one camera framing all steps and the isovalue and colour range of
                         the --time step
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
                         N.X N.Y N.Z, u v w, patch, and the colour attribute by name (render);
                         with --csg, --slice or --clip also operand (the surface's operand, the
                         slices numbered after the operands)
  --deep-exr FILE        also write every layer (every hit of every pixel, front to back) as a
                         deep OpenEXR image: Z, P, N, u v w, patch, operand, entering (render)
  --probe X,Y            print the first hit at pixel (X, Y) (from the lower left), exactly:
                         its cell, world position, parameter in the cell and every attribute
                         there (repeatable; view shows the same under the cursor)
  --no-annotations       without the title and colour bar a run with no INPUT draws (the default
                         dataset coloured by radius, framed from above)
  --keys K1,K2,...       view: press these keys (Up, Down, Left, Right, r), print the state after
                         each, write -o if given, and exit without opening a window (scripts, tests)
  -h, --help             this text
)";

struct Options
{
  bool view = false;   ///< `igaview view`
  bool series = false; ///< --series
  bool surface = false, edges = false;
  bool noAnnotations = false; ///< --no-annotations
  std::string csg;            ///< --csg as typed
  std::vector<std::array<double, 4>> slices, clips;
  std::vector<std::string> keys;
  std::vector<std::array<int, 2>> probes; ///< --probe pixels
  std::vector<std::string> fields;        ///< --field files
  bool exactParameters = false;           ///< --exact-parameters
  bool hasOutput = false;
  std::string input;
  std::vector<double> isovalues;
  std::string surfaceBy, colorBy, output = "igaview.png", exr, deepExr;
  int size[2] = { 800, 600 };
  int threads = 0;
  int memoryBudgetMB = 4096;
  double deadline = -1; ///< seconds; -1: the command's default
  iga::sst::Backend backend = iga::sst::Backend::Automatic;
  std::string algebraic, gallery; ///< --algebraic, --gallery
  bool hasBox = false;
  int absCells = 0, absDegree = 3; ///< --abs-cells, --abs-degree
  double box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  int method = vtkIGAIsosurfaceMapper::METHOD_AUTOMATIC;
  iga::RootFinder rootFinder = iga::RootFinder::PointInsertion;
  bool frameCoherency = false;
  bool antialias = false;
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

/// `count` comma-separated numbers (`names` says which, for the message) into `out`.
void parseNumbers(
  const std::string& text, const std::string& option, int count, const char* names, double* out)
{
  const std::string expected = option + " expects " + std::to_string(count) +
                               " comma-separated numbers " + names + ", got '" + text + "'";
  std::stringstream stream(text);
  std::string part;
  int n = 0;
  while (std::getline(stream, part, ','))
  {
    if (n == count)
    {
      fail(expected);
    }
    out[n++] = parseNumber(part, option);
  }
  if (n != count)
  {
    fail(expected);
  }
}

void parseTriple(const std::string& text, const std::string& option, double* out)
{
  parseNumbers(text, option, 3, "x,y,z", out);
}

/// A plane a,b,c,d with a normal (a, b, c).
std::array<double, 4> parsePlane(const std::string& text, const std::string& option)
{
  std::array<double, 4> plane;
  parseNumbers(text, option, 4, "a,b,c,d", plane.data());
  if (plane[0] == 0 && plane[1] == 0 && plane[2] == 0)
  {
    fail(option + " " + text + ": the normal (a, b, c) is zero");
  }
  return plane;
}

/// Fails with the expression's error, the expression marked at its position by ">>>".
[[noreturn]] void failExpression(const std::string& text, const iga::csg::ExpressionError& error)
{
  const size_t at = std::min(error.position(), text.size());
  fail("--csg: " + std::string(error.what()) + ": \"" + text.substr(0, at) + " >>> " +
       text.substr(at) + "\"");
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

/// Refuses an output that cannot be written before anything is read or drawn: a directory, or a
/// file in a directory that does not exist or is not writable.
void checkOutputPath(const std::string& option, const std::string& path)
{
  struct stat status;
  if (stat(path.c_str(), &status) == 0 && S_ISDIR(status.st_mode))
    fail(option + " '" + path + "' is a directory");
  const size_t slash = path.find_last_of('/');
  const std::string directory = slash == std::string::npos ? "."
                                : slash == 0               ? "/"
                                                           : path.substr(0, slash);
  if (access(directory.c_str(), W_OK) != 0)
    fail(option + " '" + path + "': the directory '" + directory + "' " +
         (errno == ENOENT || errno == ENOTDIR ? "does not exist" : "cannot be written to"));
}

/// The outputs the run will write, checked (checkOutputPath).
void checkOutputs(const Options& options)
{
  if (!options.view || options.hasOutput)
    checkOutputPath("-o", options.output);
  if (!options.exr.empty())
    checkOutputPath("--exr", options.exr);
  if (!options.deepExr.empty())
    checkOutputPath("--deep-exr", options.deepExr);
}

/// --method's value as the mapper's MethodType.
int parseMethodOption(const std::string& name)
{
  const char* names[] = { "auto", "sst", "ray-composition" };
  for (int m = 0; m < 3; ++m)
  {
    if (name == names[m])
      return m; // the mapper's METHOD_ order
  }
  fail("--method: '" + name + "' is none of auto, sst, ray-composition");
}

/// --algebraic, --gallery and --box stand instead of an input, one of them, the box with the
/// expression; a gallery name must be known.
void checkAlgebraic(const Options& options)
{
  const bool algebraic = !options.algebraic.empty(), gallery = !options.gallery.empty();
  if (algebraic && gallery)
    fail("--algebraic and --gallery each give the surface: take one");
  if ((algebraic || gallery) && !options.input.empty())
    fail(std::string(algebraic ? "--algebraic" : "--gallery") + " stands instead of an input, '" +
         options.input + "' given too");
  if (options.absCells > 0 && !algebraic && !gallery)
    fail("--abs-cells fits --algebraic's or --gallery's surface: give one");
  if (options.hasBox && !algebraic)
    fail("--box is the box of --algebraic's expression (gallery surfaces bring their own)");
  if (gallery && !iga::findAlgebraicSurface(options.gallery))
  {
    std::string names;
    for (int k = 0; k < vtkIGAAlgebraicSource::GetNumberOfGallerySurfaces(); ++k)
      names += std::string(k ? ", " : "") + vtkIGAAlgebraicSource::GetGallerySurfaceName(k);
    fail("--gallery: no surface '" + options.gallery + "' (have: " + names + ")");
  }
}

/// The next argument, the value of the option before it.
using OptionValue = std::function<std::string()>;

/// What and how to draw, and where to write it. Each parse*Option says whether `arg` was its own.
bool parseDrawingOption(const std::string& arg, const OptionValue& value, Options& options)
{
  if (arg == "--iso")
    options.isovalues.push_back(parseNumber(value(), arg));
  else if (arg == "--surface")
    options.surface = true;
  else if (arg == "--no-annotations")
    options.noAnnotations = true;
  else if (arg == "--edges")
    options.edges = true;
  else if (arg == "--csg")
  {
    options.csg = value();
    try
    {
      iga::csg::parseExpression(options.csg);
    }
    catch (const iga::csg::ExpressionError& e)
    {
      failExpression(options.csg, e);
    }
  }
  else if (arg == "--slice")
    options.slices.push_back(parsePlane(value(), arg));
  else if (arg == "--clip")
    options.clips.push_back(parsePlane(value(), arg));
  else if (arg == "--surface-by")
    options.surfaceBy = value();
  else if (arg == "--color-by")
    options.colorBy = value();
  else if (arg == "--field")
    options.fields.push_back(value());
  else if (arg == "--exact-parameters")
    options.exactParameters = true;
  else if (arg == "--time")
    options.time = parseNumber(value(), arg);
  else if (arg == "--series" && !options.view)
    options.series = true;
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
  else if (arg == "--deep-exr")
    options.deepExr = value();
  else
    return false;
  return true;
}

/// The engine's settings.
bool parseEngineOption(const std::string& arg, const OptionValue& value, Options& options)
{
  if (arg == "--threads")
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
  else if (arg == "--method")
    options.method = parseMethodOption(value());
  else if (arg == "--frame-coherency")
    options.frameCoherency = true;
  else if (arg == "--antialias")
    options.antialias = true;
  else if (arg == "--root-finder")
  {
    try
    {
      options.rootFinder = iga::parseRootFinder(value());
    }
    catch (const std::invalid_argument& e)
    {
      fail(std::string("--root-finder: ") + e.what());
    }
  }
  else
    return false;
  return true;
}

/// An algebraic surface instead of an input.
bool parseAlgebraicOption(const std::string& arg, const OptionValue& value, Options& options)
{
  if (arg == "--algebraic")
    options.algebraic = value();
  else if (arg == "--box")
    parseNumbers(value(), arg, 6, "x0,x1,y0,y1,z0,z1", options.box), options.hasBox = true;
  else if (arg == "--gallery")
    options.gallery = value();
  else if (arg == "--abs-cells" || arg == "--abs-degree")
  {
    const std::string text = value();
    const double number = parseNumber(text, arg);
    const bool cells = arg == "--abs-cells";
    if (!(number == std::floor(number) && number >= 1 && number <= (cells ? 64 : 3)))
      fail(arg + " expects a whole number in 1.." + (cells ? "64" : "3") + ", got '" + text + "'");
    (cells ? options.absCells : options.absDegree) = int(number);
  }
  else
    return false;
  return true;
}

/// The image's size and the camera.
bool parseViewOption(const std::string& arg, const OptionValue& value, Options& options)
{
  if (arg == "--size")
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
  else if (arg == "--probe")
  {
    const std::string text = value();
    double pixel[2];
    parseNumbers(text, arg, 2, "X,Y", pixel);
    if (pixel[0] != std::floor(pixel[0]) || pixel[1] != std::floor(pixel[1]) || pixel[0] < 0 ||
        pixel[1] < 0 || pixel[0] > 16383 || pixel[1] > 16383)
      fail("--probe expects a pixel X,Y of whole numbers in 0..16383, got '" + text + "'");
    options.probes.push_back({ int(pixel[0]), int(pixel[1]) });
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
  else
    return false;
  return true;
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
    const OptionValue value = [&]() -> std::string
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
    const bool parsed =
      parseDrawingOption(arg, value, options) || parseEngineOption(arg, value, options) ||
      parseAlgebraicOption(arg, value, options) || parseViewOption(arg, value, options);
    if (parsed)
      continue;
    if (!arg.empty() && arg[0] == '-')
      fail("unknown option '" + arg + "' (try: igaview --help)");
    else if (options.input.empty())
      options.input = arg;
    else
      fail("more than one input given: '" + options.input + "' and '" + arg + "'");
  }
  checkAlgebraic(options);
  checkImageBudget(options);
  checkOutputs(options);
  for (const auto& pixel : options.probes)
    if (pixel[0] >= options.size[0] || pixel[1] >= options.size[1])
      fail("--probe " + std::to_string(pixel[0]) + "," + std::to_string(pixel[1]) +
           " lies outside the " + std::to_string(options.size[0]) + "x" +
           std::to_string(options.size[1]) + " image");
  return options;
}

/// The input: its producer, updated, and its patches; `geometry` says whether it came from a
/// geometry-only file (G+Smo or MFEM without fields, GeoPDEs), whose attributes are the readers'
/// coordinates.
struct Input
{
  vtkSmartPointer<vtkAlgorithm> producer;
  vtkIGABezierHexahedra::Patches patches;
  bool geometry = false;
  std::string field;      ///< a NURBS file's first field (solution, GridFunction): drawn by default
  bool algebraic = false; ///< an algebraic surface: attribute f, drawn at 0
  bool demo = false;      ///< the default dataset: coloured by radius, seen from above, annotated
  std::string name;       ///< what the title calls it
};

/// Runs `request` (a pipeline update returning whether it succeeded), failing with the first
/// message VTK gave, on one line.
template<class Request>
void requestOrFail(const std::string& name, Request request)
{
  std::string message;
  if (!vtkIGABezierFileReading::RunQuietly(request, message))
    fail(message.empty() ? name + ": the pipeline update failed" : message);
  if (!message.empty())
    std::fprintf(stderr, "igaview: warning: %s\n", message.c_str());
}

/// The time steps the producer advertises (none for a static input).
std::vector<double> timeSteps(vtkAlgorithm* producer)
{
  producer->UpdateInformation();
  vtkInformation* info = producer->GetOutputInformation(0);
  if (!info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
    return {};
  const double* steps = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  return { steps, steps + info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) };
}

/// The index of the step nearest `time` (0 for none).
size_t nearestStep(const std::vector<double>& steps, double time)
{
  size_t nearest = 0;
  for (size_t k = 0; k < steps.size(); ++k)
  {
    if (std::abs(steps[k] - time) < std::abs(steps[nearest] - time))
      nearest = k;
  }
  return nearest;
}

/// The patches of the producer's output, read like the mapper takes them.
void convertOutput(vtkAlgorithm* producer, const std::string& name,
  vtkIGABezierHexahedra::Patches& patches, std::vector<std::string>& warnings)
{
  std::string error;
  if (!vtkIGABezierHexahedra::FromUnstructuredGrid(
        vtkUnstructuredGrid::SafeDownCast(producer->GetOutputDataObject(0)), patches, error,
        warnings))
  {
    fail(name + ": " + error);
  }
}

/// A NURBS reader's output read like the mapper takes it, failing with the reader's message.
void readGeometry(vtkIGANurbsReader* reader, const Options& options, Input& input,
  std::vector<std::string>& warnings)
{
  const std::string& file = options.input;
  reader->SetFileName(file.c_str());
  reader->SetExactParameters(options.exactParameters);
  requestOrFail("'" + file + "'", [&] { return reader->Update(0, nullptr) != 0; });
  input.producer = reader;
  convertOutput(reader, "'" + file + "'", input.patches, warnings);
  // A field besides the reader's coordinates (a solution, a GridFunction) is what is drawn.
  const auto geometryNames = iga::geometryAttributeNames();
  for (const auto& name : input.patches.volumes.attributeNames)
    if (input.field.empty() &&
        std::find(geometryNames.begin(), geometryNames.end(), name) == geometryNames.end())
      input.field = name;
  input.geometry = input.field.empty();
}

/// A .pvd series at its time step nearest --time.
void readSeries(const Options& options, Input& input, std::vector<std::string>& warnings)
{
  auto reader = vtkSmartPointer<vtkIGABezierSeriesReader>::New();
  reader->SetFileName(options.input.c_str());
  std::vector<double> steps;
  const std::string name = "'" + options.input + "'";
  requestOrFail(name,
    [&]
    {
      const bool ok = reader->GetExecutive()->UpdateInformation() != 0;
      steps = timeSteps(reader);
      return ok && !steps.empty();
    });
  const double time = steps[nearestStep(steps, options.time)];
  requestOrFail(name, [&] { return reader->UpdateTimeStep(time) != 0; });
  std::printf("igaview: %s: %zu time steps, time %g\n", options.input.c_str(), steps.size(), time);
  input.producer = reader;
  convertOutput(reader, "'" + options.input + "'", input.patches, warnings);
}

/// The default dataset's source, a G+Smo or GeoPDEs geometry's reader, or the grid of a .vtu
/// read as the mapper would take it.
Input loadInput(const Options& options)
{
  std::vector<std::string> warnings;
  Input input;
  std::string name = options.input;
  vtkNew<vtkIGAGismoReader> gismo;
  vtkNew<vtkIGAGeoPDEsReader> geopdes;
  vtkNew<vtkIGAMFEMReader> mfem;
  if (!options.fields.empty() && !mfem->CanReadFile(options.input.c_str()))
    fail("--field reads MFEM GridFunctions on an MFEM NURBS mesh, and '" + options.input +
         "' is none");
  if (!options.algebraic.empty() || !options.gallery.empty())
  {
    auto source = vtkSmartPointer<vtkIGAAlgebraicSource>::New();
    source->SetExpression(options.algebraic.c_str());
    source->SetBox(options.box);
    if (!options.gallery.empty())
      source->SetGallerySurfaceByName(options.gallery.c_str());
    source->SetSplineCells(options.absCells);
    source->SetSplineDegree(options.absDegree);
    name = options.gallery.empty() ? "--algebraic" : "--gallery " + options.gallery;
    requestOrFail(
      name, [&] { return source->GetExecutive()->Update() != 0 && source->GetErrorCode() == 0; });
    input.producer = source;
    input.algebraic = true;
    convertOutput(source, name, input.patches, warnings);
  }
  else if (options.input.empty())
  {
    if (!(options.time >= 0 && options.time <= 1))
      fail("--time must lie in 0..1 for the default dataset");
    auto source = vtkSmartPointer<vtkIGADefaultVolumeSource>::New();
    source->SetTime(options.time);
    source->Update();
    input.producer = source;
    input.demo = true;
    name = "default dataset";
    std::printf("igaview: no input given, rendering the default dataset (twisted rational tube, "
                "8 tri-quadratic patches, time %g)\n",
      options.time);
    convertOutput(source, name, input.patches, warnings);
  }
  else if (gismo->CanReadFile(options.input.c_str()))
  {
    readGeometry(gismo, options, input, warnings);
  }
  else if (geopdes->CanReadFile(options.input.c_str()))
  {
    readGeometry(geopdes, options, input, warnings);
  }
  else if (mfem->CanReadFile(options.input.c_str()))
  {
    for (const auto& field : options.fields)
      mfem->AddGridFunctionFileName(field.c_str());
    readGeometry(mfem, options, input, warnings);
  }
  else if (vtkIGABezierSeriesReader::CanReadFile(options.input.c_str()))
  {
    readSeries(options, input, warnings);
  }
  else
  {
    std::string error;
    const auto grid =
      vtkIGABezierFileReading::Read(options.input, nullptr, input.patches, error, warnings);
    if (!grid)
    {
      fail(error);
    }
    auto trivial = vtkSmartPointer<vtkTrivialProducer>::New();
    trivial->SetOutput(grid);
    input.producer = trivial;
  }
  for (const auto& warning : warnings)
  {
    std::fprintf(stderr, "igaview: warning: %s: %s\n", name.c_str(), warning.c_str());
  }
  input.name = options.input.empty() ? name : vtksys::SystemTools::GetFilenameName(options.input);
  return input;
}

int attributeIndex(const Input& input, const std::string& name, const char* option)
{
  const auto& names = input.patches.volumes.attributeNames;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
  {
    std::string known;
    for (const auto& n : names)
      known += (known.empty() ? "" : ", ") + n;
    fail(std::string(option) + ": no attribute named '" + name + "' (have: " + known + ")");
  }
  return int(it - names.begin());
}

/// The scene of the input's patches, volumes and surfaces.
iga::sst::Scene sceneOf(const Input& input)
{
  return iga::sst::Scene(input.patches.volumes.patches, input.patches.surfaces);
}

/// The range an attribute takes over the volumes, and the surfaces with `surfaces`, to 1e-5 of its
/// spread (iga::attributeExtremes); empty (lo above hi) without patches. Control values may pass
/// the field by far: the Marsden sphere's f = r^2 - 1 over [-1.5, 1.5]^3 takes -1 .. 5.75, its
/// control values -7.75 .. 5.75, whose middle, the minimum -1, is a single point.
void attributeRange(const Input& input, int attribute, bool surfaces, double* range)
{
  const iga::sst::Scene scene = sceneOf(input);
  const long count = long(surfaces ? scene.size() : scene.volumeCount());
  const auto extremes = iga::attributeExtremes<double, 3>(
    count, [&](long p) { return scene[size_t(p)]; }, iga::kFirstAttributeChannel + attribute);
  if (!extremes.complete)
    std::fprintf(stderr,
      "igaview: warning: the range of '%s' is the values found; its subdivision budget ran out "
      "before 1e-5 of the spread\n",
      input.patches.volumes.attributeNames[size_t(attribute)].c_str());
  range[0] = extremes.empty() ? INFINITY : extremes.min.value;
  range[1] = extremes.empty() ? -INFINITY : extremes.max.value;
}

/// The bounds of the input's patches; with --series, of every time step's.
/// What a run draws: isosurfaces of an attribute at isovalues, or the surfaces; the colouring
/// attribute (-1: none) and its range.
struct Drawing
{
  bool surfaces = false;
  bool csg = false;       ///< --csg, --slice or --clip: the mapper's DRAW_CSG
  std::string expression; ///< the solid drawn: --csg intersected with the --clip half-spaces
  int surface = 0;
  std::vector<double> isovalues;
  double surfaceRange[2] = { 0, 1 };
  int colour = -1;        ///< the attribute coloured by, -1 for none (or a curvature)
  std::string colourName; ///< the attribute's name or a curvature's, empty for none
  bool curvature = false; ///< coloured by curvature_mean or curvature_gauss
  double colourRange[2] = { 0, 1 };
};

/// Bounds of what a step draws: where its isosurfaces may lie when it draws only isosurfaces of
/// volumes (pieces of the patches after a few halvings: the view frames the surface, not the
/// volume holding it), else its patches'.
void drawnBounds(const Input& input, const Drawing& drawing, double* bounds)
{
  iga::sst::patchBounds(sceneOf(input), bounds);
  const auto& volumes = input.patches.volumes.patches;
  if (drawing.surfaces || drawing.csg || !input.patches.surfaces.empty() || volumes.empty())
    return;
  // Five halvings for a few patches (pieces 1/32 of theirs on a side), fewer for more.
  const int depth = volumes.size() > 256 ? 1 : volumes.size() > 32 ? 3 : 5;
  constexpr double kHuge = std::numeric_limits<double>::max();
  iga::Box3<double> box{ { kHuge, kHuge, kHuge }, { -kHuge, -kHuge, -kHuge } };
  bool found = false;
  for (const auto& patch : volumes)
    found = iga::growByIsosurfaces(patch.view(), iga::kFirstAttributeChannel + drawing.surface,
              drawing.isovalues, depth, box) ||
            found;
  for (int a = 0; found && a < 3; ++a)
  {
    bounds[2 * a] = std::max(bounds[2 * a], box.lo[a]);
    bounds[2 * a + 1] = std::min(bounds[2 * a + 1], box.hi[a]);
  }
}

/// What is drawn's bounds; with --series, over every step.
void inputBounds(const Options& options, const Input& input, const Drawing& drawing, double* bounds)
{
  drawnBounds(input, drawing, bounds);
  if (!options.series)
    return;
  for (double time : timeSteps(input.producer))
  {
    requestOrFail(
      "time " + std::to_string(time), [&] { return input.producer->UpdateTimeStep(time) != 0; });
    Input step;
    std::vector<std::string> warnings; // said when the step was read first
    convertOutput(input.producer, "time " + std::to_string(time), step.patches, warnings);
    double stepBounds[6];
    drawnBounds(step, drawing, stepBounds);
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], stepBounds[2 * a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], stepBounds[2 * a + 1]);
    }
  }
}

iga::Camera chooseCamera(const Options& options, const Input& input, const Drawing& drawing)
{
  double bounds[6];
  inputBounds(options, input, drawing, bounds);
  // Default view: from the front right and above (the default dataset's sheet, across its tube,
  // from higher up), z up, the box of what is drawn just fitting the image (5% margin).
  const glm::dvec3 direction =
    input.demo ? glm::dvec3(-0.2, 0.25, -0.95) : glm::dvec3(-0.55, 0.65, -0.5);
  iga::Camera camera = iga::frameBounds(bounds, direction, { 0, 0, 1 }, options.viewAngle);
  iga::fitBounds(camera, bounds, double(options.size[0]) / options.size[1], 0.05);
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
/// The first hit at pixel (x, y) of the mapper's last frame, exactly (ProbePixel), on one line.
std::string probeText(vtkIGAIsosurfaceMapper* mapper, int x, int y)
{
  double position[3], uvw[3];
  vtkNew<vtkFieldData> attributes;
  const vtkIdType cell = mapper->ProbePixel(x, y, position, uvw, attributes);
  char text[256];
  std::snprintf(text, sizeof(text), "pixel %d,%d: ", x, y);
  if (cell < 0)
    return text + std::string("no hit");
  std::string line = text;
  std::snprintf(text, sizeof(text),
    "cell %lld, position (%.9g, %.9g, %.9g), uvw (%.9g, %.9g, %.9g)", static_cast<long long>(cell),
    position[0], position[1], position[2], uvw[0], uvw[1], uvw[2]);
  line += text;
  for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
  {
    std::snprintf(text, sizeof(text), ", %s = %.9g", attributes->GetArrayName(a),
      attributes->GetArray(a)->GetComponent(0, 0));
    line += text;
  }
  return line;
}

struct Viewer
{
  vtkAlgorithm* producer;
  vtkIGAIsosurfaceMapper* mapper;
  vtkRenderer* renderer;
  vtkTextActor* readout;
  /// What is drawn: the isosurfaces' attribute, "surfaces", "solid EXPRESSION" and/or "N slices".
  std::string drawn;
  std::vector<double> isovalues;
  double isoStep;
  std::vector<double> times;
  size_t timeIndex = 0;
  std::string probe; ///< the hit under the cursor, as probeText says it

  /// Reads the step; a bad one is said on one line and leaves nothing drawn, the viewer open.
  void setTime()
  {
    const double time = this->times[this->timeIndex];
    std::string message;
    if (!vtkIGABezierFileReading::RunQuietly(
          [&] { return this->producer->UpdateTimeStep(time) != 0; }, message))
      std::fprintf(stderr, "igaview: time %g: %s\n", time,
        message.empty() ? "the pipeline update failed" : message.c_str());
  }

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
    std::string text = this->isovalues.empty() ? this->drawn : this->drawn + " =";
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

  /// What the last frame drew: pixels covered and engine and whole-frame milliseconds, or why
  /// it drew nothing.
  std::string outcome() const
  {
    const std::string refusal = this->mapper->GetLastRefusal();
    if (!refusal.empty())
    {
      return "nothing drawn: " + refusal;
    }
    char text[128];
    std::snprintf(text, sizeof(text), "%zu pixels covered, engine %.1f ms, frame %.1f ms",
      this->mapper->GetLastGBuffer().coveredPixels(), this->mapper->GetLastEngineTime(),
      1000 * this->renderer->GetLastRenderTimeInSeconds());
    return text;
  }

  /// The corner text, after a frame: the state, then the outcome.
  void updateReadout()
  {
    const std::string probe = this->probe.empty() ? "" : "\n" + this->probe;
    this->readout->SetInput((this->state() + "\n" + this->outcome() + probe).c_str());
  }
};

/// The viewer: an interactive window, or with --keys the same key handling offscreen (the
/// caller then writes the last frame like `render` does).
void runViewer(const Options& options, Viewer& viewer, vtkRenderWindow* window)
{
  viewer.times = timeSteps(viewer.producer);
  if (!viewer.times.empty())
  {
    viewer.timeIndex = nearestStep(viewer.times, options.time);
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
      std::printf(
        "igaview: key %s: %s, %s\n", key.c_str(), viewer.state().c_str(), viewer.outcome().c_str());
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
  // The hit under the cursor; the frame is the mapper's last, so only the readout is redrawn.
  vtkNew<vtkCallbackCommand> onMove;
  onMove->SetClientData(&viewer);
  onMove->SetCallback(
    [](vtkObject* caller, unsigned long, void* data, void*)
    {
      auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
      auto* viewer = static_cast<Viewer*>(data);
      const int* at = interactor->GetEventPosition();
      viewer->probe = probeText(viewer->mapper, at[0], at[1]);
      interactor->Render();
    });
  interactor->AddObserver(vtkCommand::MouseMoveEvent, onMove);
  vtkNew<vtkCallbackCommand> onFrame;
  onFrame->SetClientData(&viewer);
  onFrame->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<Viewer*>(data)->updateReadout(); });
  window->AddObserver(vtkCommand::EndEvent, onFrame);
  interactor->Initialize();
  window->Render();
  interactor->Start();
}

/// Isosurfaces when asked for (--iso, --surface-by) or when the input holds volumes of a field;
/// the surfaces when asked for (--surface), for geometry files and for input without volumes.
/// The solid of --csg and --clip, its attributes checked against the input's.
std::string csgExpression(const Options& options, const Input& input)
{
  const std::string expression = iga::csg::cutByHalfSpaces(options.csg, options.clips);
  try
  {
    if (!expression.empty()) // --clip may pass the limits on operands and nesting
      iga::csg::parseExpression(expression);
  }
  catch (const iga::csg::ExpressionError& e)
  {
    failExpression(expression, e);
  }
  if (!options.csg.empty())
  {
    for (const auto& operand : iga::csg::parseExpression(options.csg).operands)
    {
      const auto& names = input.patches.volumes.attributeNames;
      if (!operand.attribute.empty() &&
          std::find(names.begin(), names.end(), operand.attribute) == names.end())
      {
        std::string known;
        for (const auto& n : names)
          known += (known.empty() ? "" : ", ") + n;
        failExpression(
          options.csg, iga::csg::ExpressionError(
                         "no attribute named '" + operand.attribute + "' (have: " + known + ")",
                         operand.position));
      }
    }
  }
  return expression;
}

Drawing chooseDrawing(const Options& options, const Input& input)
{
  Drawing drawing;
  const auto& names = input.patches.volumes.attributeNames;
  drawing.csg = !options.csg.empty() || !options.slices.empty() || !options.clips.empty();
  if (drawing.csg && (options.surface || !options.isovalues.empty() || !options.surfaceBy.empty()))
    fail("--csg, --slice and --clip draw solids and sections: they take no --surface, --iso or "
         "--surface-by");
  if (drawing.csg && input.patches.volumes.patches.empty())
    fail("'" + options.input + "' holds no volumes to draw --csg, --slice or --clip of");
  const bool isosurfaces = !options.isovalues.empty() || !options.surfaceBy.empty();
  drawing.surfaces =
    options.surface || (!isosurfaces && (input.geometry || input.patches.volumes.patches.empty()));
  if (drawing.csg)
    drawing.expression = csgExpression(options, input);
  if (!drawing.surfaces && !drawing.csg && input.patches.volumes.patches.empty())
    fail("'" + options.input + "' holds no volumes to take an isosurface of: --surface draws it");
  if (!drawing.surfaces && !drawing.csg && names.empty())
    fail("'" + options.input +
         "': no scalar point attribute to take an isosurface of: --surface "
         "draws its shape");
  if (!drawing.surfaces && !drawing.csg)
  {
    const std::string& surfaceBy = options.surfaceBy.empty() ? input.field : options.surfaceBy;
    drawing.surface = surfaceBy.empty() ? 0 : attributeIndex(input, surfaceBy, "--surface-by");
    // The range (a subdivision over every patch) serves the default isovalue and the viewer's
    // isovalue keys alone.
    if ((options.isovalues.empty() && !input.algebraic) || options.view)
      attributeRange(input, drawing.surface, false, drawing.surfaceRange);
    drawing.isovalues = options.isovalues;
    if (drawing.isovalues.empty() && input.algebraic)
      drawing.isovalues.push_back(0.0);
    if (drawing.isovalues.empty())
      drawing.isovalues.push_back(0.5 * (drawing.surfaceRange[0] + drawing.surfaceRange[1]));
  }
  // The default dataset shows its radius unless told otherwise.
  const std::string colorBy = options.colorBy.empty() && input.demo ? "radius" : options.colorBy;
  drawing.curvature = colorBy == "curvature_mean" || colorBy == "curvature_gauss";
  if (drawing.curvature && (drawing.surfaces || drawing.csg))
    fail("--color-by " + colorBy + ": the curvature of isosurfaces only");
  drawing.colour =
    colorBy.empty() || drawing.curvature ? -1 : attributeIndex(input, colorBy, "--color-by");
  drawing.colourName = colorBy;
  if (drawing.colour >= 0)
  {
    attributeRange(input, drawing.colour, true, drawing.colourRange);
    if (!(drawing.colourRange[1] > drawing.colourRange[0]))
      drawing.colourRange[1] = drawing.colourRange[0] + 1;
  }
  return drawing;
}

/// The mapper for the options and the drawing, ParaView's cool-to-warm map for a colouring.
void configureMapper(const Options& options, const Input& input, const Drawing& drawing,
  vtkIGAIsosurfaceMapper* mapper, vtkColorTransferFunction* coolToWarm)
{
  const auto& names = input.patches.volumes.attributeNames;
  mapper->SetInputConnection(input.producer->GetOutputPort());
  mapper->SetDrawMode(drawing.csg        ? vtkIGAIsosurfaceMapper::DRAW_CSG
                      : drawing.surfaces ? vtkIGAIsosurfaceMapper::DRAW_SURFACES
                                         : vtkIGAIsosurfaceMapper::DRAW_ISOSURFACES);
  if (!drawing.surfaces && !drawing.csg)
    mapper->SetSurfaceArrayName(names[drawing.surface].c_str());
  mapper->SetCsgExpression(options.csg.c_str());
  mapper->SetAllLayers(!options.deepExr.empty());
  for (size_t k = 0; k < options.slices.size(); ++k)
  {
    const auto& plane = options.slices[k];
    mapper->SetSlice(int(k), plane[0], plane[1], plane[2], plane[3]);
  }
  for (size_t k = 0; k < options.clips.size(); ++k)
  {
    const auto& clip = options.clips[k];
    mapper->SetCappedClip(int(k), clip[0], clip[1], clip[2], clip[3]);
  }
  mapper->SetNumberOfThreads(options.threads);
  mapper->SetMemoryBudgetMB(options.memoryBudgetMB);
  // An interactive window answers within two seconds unless told otherwise.
  mapper->SetFrameDeadline(options.deadline >= 0 ? options.deadline : options.view ? 2.0 : 0.0);
  // The mapper's BackendType follows the engine's Backend order (auto, CPU, CUDA).
  mapper->SetBackend(int(options.backend));
  mapper->SetMethod(options.method);
  mapper->SetRootFinder(int(options.rootFinder)); // RootFinderType follows iga::RootFinder
  mapper->SetFrameCoherency(options.frameCoherency);
  mapper->SetAntialiasing(options.antialias);
  for (size_t k = 0; k < drawing.isovalues.size(); ++k)
    mapper->SetIsovalue(int(k), drawing.isovalues[k]);
  mapper->ScalarVisibilityOff();
  if (!drawing.colourName.empty())
  {
    coolToWarm->SetColorSpaceToDiverging();
    coolToWarm->AddRGBPoint(drawing.colourRange[0], 0.231, 0.298, 0.753);
    coolToWarm->AddRGBPoint(drawing.colourRange[1], 0.706, 0.016, 0.150);
    mapper->SetLookupTable(coolToWarm);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(drawing.colourName.c_str());
    mapper->SetScalarRange(drawing.colourRange);
    mapper->ScalarVisibilityOn();
  }
}

/// --color-by curvature_*: the colour map spans the curvature's values at the first frame's
/// hits (2nd to 98th percentile, so that a few points of high curvature do not wash it out).
void frameTheHitsOnce(vtkRenderWindow* window, vtkRenderer* renderer,
  vtkIGAIsosurfaceMapper* mapper, double width, double fill)
{
  window->Render();
  const iga::sst::GBuffer& gbuffer = mapper->GetLastGBuffer();
  int lo[2] = { gbuffer.width, gbuffer.height }, hi[2] = { -1, -1 };
  for (int j = 0; j < gbuffer.height; ++j)
    for (int i = 0; i < gbuffer.width; ++i)
      if (gbuffer.hitCount(i, j) > 0)
      {
        lo[0] = std::min(lo[0], i), hi[0] = std::max(hi[0], i);
        lo[1] = std::min(lo[1], j), hi[1] = std::max(hi[1], j);
      }
  if (hi[0] < 0)
    return;
  vtkCamera* camera = renderer->GetActiveCamera();
  glm::dvec3 position, focal, up, forward;
  camera->GetPosition(glm::value_ptr(position));
  camera->GetFocalPoint(glm::value_ptr(focal));
  camera->GetViewUp(glm::value_ptr(up));
  forward = glm::normalize(focal - position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  up = glm::cross(right, forward);
  // World units a pixel spans in the focal plane; the covered box's centre moved to the image's.
  const double pixel = 2 * glm::length(focal - position) *
                       std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2) /
                       gbuffer.height;
  const double centre[2] = { 0.5 * width * gbuffer.width, 0.5 * gbuffer.height };
  const glm::dvec3 shift = pixel * ((0.5 * (lo[0] + hi[0] + 1) - centre[0]) * right +
                                     (0.5 * (lo[1] + hi[1] + 1) - centre[1]) * up);
  camera->SetPosition(glm::value_ptr(position + shift));
  camera->SetFocalPoint(glm::value_ptr(focal + shift));
  camera->Dolly(fill * std::min(width * gbuffer.width / (hi[0] - lo[0] + 1),
                         double(gbuffer.height) / (hi[1] - lo[1] + 1)));
  renderer->ResetCameraClippingRange();
}

/// Centres the pixels a frame covers in the part of the image left of the colour bar and fills
/// `fill` of it with them, by panning and moving the camera along its view direction: what is
/// seen is framed, not a box around it. Twice: a move changes the perspective a little.
void frameTheHits(vtkRenderWindow* window, vtkRenderer* renderer, vtkIGAIsosurfaceMapper* mapper)
{
  for (int pass = 0; pass < 2; ++pass)
    frameTheHitsOnce(window, renderer, mapper, 0.85, 0.85);
}

void fitCurvatureRange(vtkRenderWindow* window, vtkIGAIsosurfaceMapper* mapper,
  vtkColorTransferFunction* coolToWarm, Drawing& drawing)
{
  window->Render();
  std::vector<double> values;
  for (const auto& hit : mapper->GetLastGBuffer().hits)
    if (std::isfinite(hit.color))
      values.push_back(hit.color);
  if (values.empty())
    return;
  std::sort(values.begin(), values.end());
  drawing.colourRange[0] = values[values.size() / 50];
  drawing.colourRange[1] = values[values.size() - 1 - values.size() / 50];
  if (!(drawing.colourRange[1] > drawing.colourRange[0]))
    drawing.colourRange[1] =
      drawing.colourRange[0] + 1e-9 * (1 + std::fabs(drawing.colourRange[0]));
  coolToWarm->RemoveAllPoints();
  coolToWarm->AddRGBPoint(drawing.colourRange[0], 0.231, 0.298, 0.753);
  coolToWarm->AddRGBPoint(drawing.colourRange[1], 0.706, 0.016, 0.150);
  mapper->SetScalarRange(drawing.colourRange);
  std::printf("igaview: %s from %g to %g\n", drawing.colourName.c_str(), drawing.colourRange[0],
    drawing.colourRange[1]);
}

/// The actor's look, with the element edges for --edges.
void configureActor(const Options& options, vtkActor* actor)
{
  vtkProperty* property = actor->GetProperty();
  property->SetColor(0.9, 0.75, 0.45);
  property->SetAmbient(0.1);
  property->SetDiffuse(0.9);
  property->SetSpecular(0.35);
  property->SetSpecularPower(40);
  property->SetEdgeVisibility(options.edges);
  property->SetEdgeColor(0.15, 0.15, 0.2);
}

/// The renderer with its gradient background and the chosen camera.
void configureRenderer(const iga::Camera& view, vtkRenderer* renderer)
{
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->SetBackground2(0.32, 0.36, 0.42);
  renderer->GradientBackgroundOn();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(glm::value_ptr(view.position));
  camera->SetFocalPoint(glm::value_ptr(view.focalPoint));
  camera->SetViewUp(glm::value_ptr(view.viewUp));
  camera->SetViewAngle(view.viewAngle);
  camera->SetClippingRange(view.clippingRange);
}

/// One line saying what is drawn.
void describe(const Options& options, const Input& input, const Drawing& drawing)
{
  const auto& names = input.patches.volumes.attributeNames;
  if (drawing.csg)
  {
    std::printf("igaview: %zu patches, %s%s%zu slices, %dx%d pixels\n",
      input.patches.volumes.patches.size(), drawing.expression.empty() ? "" : "solid ",
      drawing.expression.empty() ? "" : (drawing.expression + " and ").c_str(),
      options.slices.size(), options.size[0], options.size[1]);
    return;
  }
  if (drawing.surfaces)
  {
    std::printf("igaview: surfaces of %zu volumes (their boundary) and %zu surface patches, "
                "%dx%d pixels\n",
      input.patches.volumes.patches.size(), input.patches.surfaces.size(), options.size[0],
      options.size[1]);
    return;
  }
  std::string isoText;
  for (double iso : drawing.isovalues)
    isoText += (isoText.empty() ? "" : ", ") + std::to_string(iso);
  std::printf("igaview: %zu patches, isosurface %s = %s, %dx%d pixels\n",
    input.patches.volumes.patches.size(), names[drawing.surface].c_str(), isoText.c_str(),
    options.size[0], options.size[1]);
}

/// The mapper's first error message, on one line without VTK's "ERROR: In FILE ... (ADDRESS): "
/// (set by the observer watchErrors installs, which also keeps VTK from printing it).
std::string mapperError;

vtkSmartPointer<vtkCallbackCommand> watchErrors(vtkIGAIsosurfaceMapper* mapper)
{
  auto onError = vtkSmartPointer<vtkCallbackCommand>::New();
  onError->SetCallback(
    [](vtkObject*, unsigned long, void*, void* text)
    {
      std::string message = static_cast<const char*>(text);
      const size_t at = message.find("): ");
      message = message.substr(at == std::string::npos ? 0 : at + 3);
      if (mapperError.empty())
        mapperError = message.substr(0, message.find_last_not_of('\n') + 1);
    });
  mapper->AddObserver(vtkCommand::ErrorEvent, onError);
  return onError;
}

/// The paths the last frame's patches took: "SST engine", "ray composition (FINDER)", or both
/// with their patch counts.
std::string enginePaths(vtkIGAIsosurfaceMapper* mapper)
{
  const std::string composition = std::string("ray composition (") +
                                  iga::rootFinderName(iga::RootFinder(mapper->GetRootFinder())) +
                                  ")";
  const vtkIdType composed = mapper->GetLastRayCompositionPatches();
  const vtkIdType tree = mapper->GetLastSstPatches();
  if (composed == 0)
    return "SST engine";
  if (tree == 0)
    return composition;
  return "SST engine for " + std::to_string(tree) + " patches, " + composition + " for " +
         std::to_string(composed);
}

/// The PNG of the window and, for --exr, the G-buffer.
void writeOutputs(const Options& options, const Drawing& drawing, vtkRenderWindow* window,
  vtkIGAIsosurfaceMapper* mapper)
{
  const std::string refusal = mapper->GetLastRefusal();
  if (!refusal.empty())
    fail(refusal);
  // Other errors of the mapper surface as VTK errors; make them fatal and on one line.
  const iga::sst::GBuffer& gbuffer = mapper->GetLastGBuffer();
  if (gbuffer.width != options.size[0] || gbuffer.height != options.size[1])
  {
    fail(mapperError.empty() ? "the isosurface could not be rendered" : mapperError);
  }
  std::printf("igaview: %zu pixels covered in %.1f ms (%s, %s)\n", gbuffer.coveredPixels(),
    mapper->GetLastEngineTime(), enginePaths(mapper).c_str(), mapper->GetLastBackend());
  if (options.antialias)
    std::printf("igaview: %lld pixels antialiased\n",
      static_cast<long long>(mapper->GetLastAntialiasedPixels()));
  for (const auto& pixel : options.probes)
    std::printf("igaview: probe %s\n", probeText(mapper, pixel[0], pixel[1]).c_str());
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
      gbuffer, mapper->GetLastColours().data(), drawing.colourName, drawing.csg));
    writer->SetFileName(options.exr.c_str());
    writer->Write();
    if (writer->GetErrorCode() != 0)
      fail(writer->GetLastError());
    std::printf("igaview: wrote %s\n", options.exr.c_str());
  }
  if (!options.deepExr.empty())
  {
    std::string error;
    if (!vtkIGADeepEXR::Write(gbuffer, options.deepExr, error))
      fail(error);
    std::printf("igaview: wrote %s (%zu samples)\n", options.deepExr.c_str(), gbuffer.hits.size());
  }
}

/// `file` with _NNN (step k) before its extension.
std::string numbered(const std::string& file, size_t k)
{
  char suffix[24];
  std::snprintf(suffix, sizeof(suffix), "_%03zu", k);
  const size_t slash = file.find_last_of('/');
  const size_t dot = file.find_last_of('.');
  const size_t at =
    dot != std::string::npos && (slash == std::string::npos || dot > slash) ? dot : file.size();
  return file.substr(0, at) + suffix + file.substr(at);
}

/// --series: each time step drawn and written, the outputs numbered by step.
void renderSeries(const Options& options, const Input& input, const Drawing& drawing,
  vtkRenderWindow* window, vtkIGAIsosurfaceMapper* mapper)
{
  const std::vector<double> steps = timeSteps(input.producer);
  if (steps.empty())
    fail("--series: '" + options.input +
         "' has no time steps (a .pvd series and the default dataset have)");
  for (size_t k = 0; k < steps.size(); ++k)
  {
    requestOrFail("time " + std::to_string(steps[k]),
      [&] { return input.producer->UpdateTimeStep(steps[k]) != 0; });
    window->Render();
    const std::string refusal = mapper->GetLastRefusal();
    if (!refusal.empty())
      fail("time step " + std::to_string(k + 1) + " of " + std::to_string(steps.size()) + ": " +
           refusal);
    std::printf("igaview: time step %zu of %zu, time %g\n", k + 1, steps.size(), steps[k]);
    Options frame = options;
    frame.output = numbered(options.output, k);
    frame.exr = options.exr.empty() ? "" : numbered(options.exr, k);
    frame.deepExr = options.deepExr.empty() ? "" : numbered(options.deepExr, k);
    writeOutputs(frame, drawing, window, mapper);
  }
}

/// The default dataset's title (dataset, what is drawn, the colouring) and colour bar.
void annotate(
  const Input& input, const Drawing& drawing, vtkRenderer* renderer, vtkScalarsToColors* colours)
{
  const auto& names = input.patches.volumes.attributeNames;
  std::string title = input.name + ": ";
  if (drawing.surfaces || drawing.csg)
    title += drawing.csg ? "solid " + drawing.expression : "surfaces";
  else
  {
    title += names[size_t(drawing.surface)] + " =";
    for (double iso : drawing.isovalues)
    {
      char value[32];
      std::snprintf(value, sizeof(value), " %g", iso);
      title += value;
    }
  }
  if (!drawing.colourName.empty())
    title += ", coloured by " + drawing.colourName;
  vtkNew<vtkTextActor> text;
  text->SetInput(title.c_str());
  text->GetTextProperty()->SetFontSize(
    std::max(10, renderer->GetRenderWindow()->GetSize()[1] / 30));
  text->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  text->GetTextProperty()->SetVerticalJustificationToTop();
  text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  text->GetPositionCoordinate()->SetValue(0.02, 0.97);
  renderer->AddActor2D(text);
  if (drawing.colourName.empty())
    return;
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(colours);
  bar->SetTitle(drawing.colourName.c_str());
  bar->SetNumberOfLabels(5);
  bar->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  bar->GetPositionCoordinate()->SetValue(0.88, 0.15);
  bar->SetWidth(0.1);
  bar->SetHeight(0.7);
  renderer->AddActor2D(bar);
  std::printf("igaview: colour bar %s from %g to %g\n", drawing.colourName.c_str(),
    drawing.colourRange[0], drawing.colourRange[1]);
}

/// VTK's X window aborts the process when no X server answers: say so first where none is named.
void checkDisplay(vtkRenderWindow* window)
{
  const char* display = std::getenv("DISPLAY");
  if (window->IsA("vtkXOpenGLRenderWindow") && !(display && *display))
    fail("no X display (DISPLAY is not set): run igaview under xvfb-run -a, or on a desktop");
}

} // namespace

int main(int argc, char** argv)
{
  const Options options = parseArguments(argc, argv);
  vtkNew<vtkRenderWindow> window;
  checkDisplay(window);
  const Input input = loadInput(options);
  Drawing drawing = chooseDrawing(options, input);
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkColorTransferFunction> coolToWarm;
  configureMapper(options, input, drawing, mapper, coolToWarm);
  const auto errorWatch = watchErrors(mapper);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  configureActor(options, actor);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  configureRenderer(chooseCamera(options, input, drawing), renderer);
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(options.size[0], options.size[1]);
  describe(options, input, drawing);
  if (input.demo && !options.noAnnotations)
    annotate(input, drawing, renderer, coolToWarm);
  if (input.demo && !options.hasPosition && !options.hasFocal)
    frameTheHits(window, renderer, mapper);
  if (drawing.curvature)
    fitCurvatureRange(window, mapper, coolToWarm, drawing);
  if (options.series)
  {
    renderSeries(options, input, drawing, window, mapper);
    return 0;
  }
  if (options.view)
  {
    vtkNew<vtkTextActor> readout;
    const auto& names = input.patches.volumes.attributeNames;
    const std::string slices = options.slices.empty()
                                 ? ""
                                 : std::to_string(options.slices.size()) +
                                     (options.slices.size() == 1 ? " slice" : " slices");
    const std::string drawn =
      drawing.csg        ? (drawing.expression.empty()
                               ? slices
                               : "solid " + drawing.expression + (slices.empty() ? "" : " and " + slices))
      : drawing.surfaces ? "surfaces"
                         : names[drawing.surface];
    Viewer viewer{ input.producer, mapper, renderer, readout, drawn, drawing.isovalues,
      0.02 * (drawing.surfaceRange[1] - drawing.surfaceRange[0]), {}, 0, {} };
    runViewer(options, viewer, window);
    if (options.keys.empty() || !options.hasOutput)
      return 0;
  }
  else
  {
    window->Render();
  }
  writeOutputs(options, drawing, window, mapper);
  return 0;
}
