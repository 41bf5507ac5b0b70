// igaBenchmark: speed and memory of the CPU isosurface engine, VTK-free so it also runs on
// machines without VTK. Prints a table on stderr and one JSON document on stdout (or --json FILE).
//
//   igaBenchmark [--quick] [--json FILE]
//   igaBenchmark --csg [--quick] [--json FILE]
//   igaBenchmark --algebraic [--quick] [--json FILE]
//   igaBenchmark --screen-filling [--quick] [--json FILE]
//   igaBenchmark --surfaces [--quick] [--json FILE]
//   igaBenchmark --gpu [--quick] [--only NAME] [--json FILE]
//
// Studies (the SST paper's figures): SST vs basic scheme over degrees 2..5 (fig. 13); time and
// peak memory over resolutions 256^2..2048^2 (fig. 11); 1 vs 2 threads; the 512^2 tri-quadratic
// sphere frame; the default dataset; the deforming 10k-patch blade at 1080p; surfaces (the
// paper's surface study): the teapot's 32 bicubic patches and the deforming blade's boundary
// (over 10 000 biquadratic faces) at 512^2 and 1080p, SST against the basic scheme and per-pixel
// Bézier clipping; CSG: the dice (cube<0 - pips<0, 125 patches of degree 4) at 512^2 and 1080p
// against the cube's isosurface alone in first-hit mode (--csg: this study alone). Ratios
// compare runs of the same process.
//
// --surfaces: the surface study alone, and the paper's pre-subdivision study (fig. 12): the
// teapot's patches split 0..5 times at 512^2, SST against the per-pixel schemes as patches
// shrink towards a pixel.
//
// --algebraic: the gallery's algebraic surfaces (AlgebraicGallery.h), each one polynomial volume
// over its box, SST against ray composition with each root finder at 512^2 (256^2 quick), with
// the finders' knot insertions and evaluations per composed ray; the cost of silhouette
// anti-aliasing (the frame with the rotated-grid samples of its edge pixels); the frame without
// isosurface cells (every ray through the boxes composed whole); and an orbit of a degree a frame
// drawn cold and with frame coherency (each frame seeded by the one before).
//
// --screen-filling: scenes framed as users frame them, covering a third of a 1920x1080 image or
// more (the sphere p2 close up, the teapot, the deforming blade's boundary, the dice's CSG solid).
// On the CPU each frame is set against its floor: every covered pixel solved once by the engine's
// own Newton (iga::sst::solvePixel), at the frame's mean evaluations a solve and one evaluation's
// cost measured on the scene's first patch, over the threads. --quick times one (cold) frame a
// scene, else the median of five.
//
// --gpu: the CUDA engine in first-hit mode at 1920x1080 and 3840x2160 on the teardrop, the tube
// with a collapsed axis, the spheres of degrees 2..5, a deforming 10k-patch blade (a new net
// every frame), the screen-filling scenes at 1080p, a deforming NURBS ball, and the 800k-patch
// blade (camera moves, and at 1080p deforming), with stage times and peak device memory, next to
// the CPU engine at 1080p. Without a usable device it says why and measures nothing. --only NAME
// keeps the datasets whose names contain NAME (a profiler's run: one dataset, not the whole study).
#include "iga/AbsField.h"
#include "iga/AlgebraicGallery.h"
#include "iga/Boundary.h"
#include "iga/Csg.h"
#include "iga/Datasets.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Csg.h"
#include "iga/sst/Engine.h"
#include "iga/sst/PixelProblem.h"
#include "iga/sst/Supersampling.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{

struct Measurement
{
  std::string study, dataset, method, backend;
  int degree = 0, width = 0, height = 0, threads = 0;
  double ms = 0; ///< median over the repetitions
  double peakMB = 0;
  size_t covered = 0, newtonSolves = 0, subdivided = 0, unresolved = 0;
  iga::sst::FrameReport report; ///< of the median run
  /// The frame's floor (screen-filling scenes on the CPU): every covered pixel solved once by
  /// Newton, at the frame's mean evaluations a solve, each at its measured cost, on all threads.
  double floorMs = 0;
};

iga::Camera frame(const iga::sst::Scene& scene)
{
  double bounds[6];
  iga::sst::patchBounds(scene, bounds);
  return iga::frameBounds(bounds, { -0.55, 0.65, -0.5 }, { 0, 0, 1 }, 30);
}

/// The camera zoomed by `factor` as vtkCamera::Zoom does: the view angle's tangent divided.
iga::Camera zoomed(iga::Camera camera, double factor)
{
  const double degrees = 180 / 3.14159265358979323846;
  camera.viewAngle = 2 * degrees * std::atan(std::tan(camera.viewAngle / (2 * degrees)) / factor);
  return camera;
}

/// A camera made from the one framing the scene whole (for a close-up).
using Reframe = std::function<iga::Camera(const iga::Camera&)>;

/// Renders frame r of a measurement with the settings given (data version set) into a G-buffer.
using RenderFrame = std::function<iga::sst::FrameReport(
  int r, const iga::sst::Settings&, const iga::sst::Method, iga::sst::GBuffer&)>;

/// Frames drawn by `render`, the median time reported. Data versions as the VTK mapper sets
/// them: one for static data (after the first frame a GPU keeps its copy, as for a camera move),
/// a new one for every frame of `deforming` data.
Measurement measureFrames(const std::string& study, const std::string& dataset, double isovalue,
  int degree, int width, int height, int threads, iga::sst::Method method, int repetitions,
  iga::sst::Backend backend, bool deforming, const RenderFrame& render)
{
  iga::sst::Settings settings;
  settings.width = width;
  settings.height = height;
  settings.threads = threads;
  settings.isovalues = { isovalue };
  settings.backend = backend;
  std::vector<std::pair<double, iga::sst::FrameReport>> runs;
  iga::sst::GBuffer gbuffer;
  static uint64_t versions = 0;
  const uint64_t version = ++versions << 20;
  for (int r = 0; r < repetitions; ++r)
  {
    settings.dataVersion = deforming ? version + uint64_t(r) : version;
    const auto report = render(r, settings, method, gbuffer);
    runs.emplace_back(report.msTotal, report);
  }
  std::sort(
    runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Measurement m;
  m.study = study;
  m.dataset = dataset;
  m.method = iga::sst::methodName(method);
  m.degree = degree;
  m.width = width;
  m.height = height;
  m.threads = threads;
  m.report = runs[runs.size() / 2].second;
  m.ms = runs[runs.size() / 2].first;
  m.backend = m.report.backend;
  m.peakMB = m.report.peakBytes / 1048576.0;
  m.covered = gbuffer.coveredPixels();
  m.newtonSolves = m.report.newtonSolves;
  m.subdivided = m.report.subdividedPatches;
  m.unresolved = m.report.unresolvedPixels;
  std::fprintf(stderr,
    "%-11s %-16s %-6s %-4s p=%d %5dx%-5d %d thr %10.1f ms %8.1f MB  covered %zu\n", study.c_str(),
    dataset.c_str(), m.method.c_str(), m.backend.c_str(), degree, width, height, threads, m.ms,
    m.peakMB, m.covered);
  return m;
}

/// Frames of `set` (or of the sets `frames` returns for repetition r, for deforming data).
Measurement measure(const std::string& study, const std::string& dataset,
  const iga::VolumeSet<double>& set, double isovalue, int degree, int width, int height,
  int threads, iga::sst::Method method, int repetitions,
  iga::sst::Backend backend = iga::sst::Backend::Cpu,
  const std::function<iga::VolumeSet<double>(int)>& frames = {})
{
  const iga::Camera camera = frame(set.patches);
  return measureFrames(study, dataset, isovalue, degree, width, height, threads, method,
    repetitions, backend, bool(frames),
    [&](int r, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
    {
      return frames ? iga::sst::render(frames(r).patches, camera, settings, m, out)
                    : iga::sst::render(set.patches, camera, settings, m, out);
    });
}

/// Frames of surfaces (of the ones `frames` returns for repetition r, for deforming data), seen
/// by `reframe` of the camera framing them whole, or by that.
/// The camera framing surfaces whole, as measureSurfaces frames them.
iga::Camera frameSurfaces(const std::vector<iga::BezierSurface<double>>& surfaces)
{
  static const std::vector<iga::BezierVolume<double>> noVolumes;
  return frame(iga::sst::Scene(noVolumes, surfaces));
}

Measurement measureSurfaces(const std::string& dataset,
  const std::vector<iga::BezierSurface<double>>& surfaces, int width, int height, int threads,
  iga::sst::Method method, int repetitions,
  const std::function<std::vector<iga::BezierSurface<double>>(int)>& frames = {},
  iga::sst::Backend backend = iga::sst::Backend::Cpu, const std::string& study = "surfaces",
  const Reframe& reframe = {})
{
  static const std::vector<iga::BezierVolume<double>> noVolumes;
  const iga::Camera whole = frameSurfaces(surfaces);
  const iga::Camera camera = reframe ? reframe(whole) : whole;
  return measureFrames(study, dataset, 0, 0, width, height, threads, method, repetitions, backend,
    bool(frames),
    [&](int r, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
    {
      return iga::sst::render(
        iga::sst::Scene(noVolumes, frames ? frames(r) : surfaces), camera, settings, m, out);
    });
}

/// The deforming blade's boundary: its faces found once for the topology, sliced from each
/// frame's net (frame r at the flap's time 0.1 (r % 10)).
struct DeformingBladeBoundary
{
  iga::BladeLayout layout;
  std::vector<iga::PatchFace> faces;

  explicit DeformingBladeBoundary(const iga::BladeLayout& bladeLayout)
    : layout(bladeLayout)
    , faces(iga::boundaryFaces(iga::makeBlade<double>(layout, 0.0).patches))
  {
  }
  std::string name() const
  {
    return "blade-boundary-" + std::to_string(faces.size()) + "-deforming";
  }
  std::vector<iga::BezierSurface<double>> operator()(int r) const
  {
    const auto blade = iga::makeBlade<double>(layout, 0.1 * (r % 10));
    std::vector<iga::BezierSurface<double>> surfaces;
    for (const iga::PatchFace& face : faces)
      surfaces.push_back(
        iga::faceSurface(blade.patches[size_t(face.patch)], face.direction, face.side));
    return surfaces;
  }
};

/// The surface study: per dataset and size, SST against the better of the basic scheme and
/// Bézier clipping (ratio `referenceOverSst_...`).
void surfaceStudy(bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  using iga::sst::Method;
  const auto teapot = iga::makeTeapot<double>().patches;
  const auto boundary = DeformingBladeBoundary(iga::bladeLayout(quick ? 1000 : 10000));
  const std::string bladeName = boundary.name();
  struct Size
  {
    int width, height;
  };
  for (const Size size : { Size{ 512, 512 }, Size{ 1920, 1080 } })
  {
    const std::string tag = std::to_string(size.width) + "x" + std::to_string(size.height);
    for (const bool blade : { false, true })
    {
      auto run = [&](Method method, int repetitions)
      {
        return blade ? measureSurfaces(bladeName, boundary(0), size.width, size.height, threads,
                         method, repetitions, boundary)
                     : measureSurfaces(
                         "teapot", teapot, size.width, size.height, threads, method, repetitions);
      };
      // The deforming blade's references draw the same frames as SST (a few milliseconds
      // each), the teapot's one frame (seconds at 1080p).
      const int referenceReps = blade ? reps : 1;
      const auto sst = run(Method::SharedSubdivisionTree, reps);
      const auto basic = run(Method::BasicScheme, referenceReps);
      const auto clipping = run(Method::BezierClipping, referenceReps);
      all.insert(all.end(), { sst, basic, clipping });
      const std::string name = (blade ? "bladeBoundary_" : "teapot_") + tag;
      ratios.emplace_back("basicOverSst_" + name, basic.ms / sst.ms);
      ratios.emplace_back("clippingOverSst_" + name, clipping.ms / sst.ms);
      ratios.emplace_back("referenceOverSst_" + name, std::min(basic.ms, clipping.ms) / sst.ms);
    }
  }
}

/// Each surface split at its parametric midpoints `levels` times in both directions (4^levels
/// pieces, the same shape): the SST paper's pre-subdivision (its fig. 12).
std::vector<iga::BezierSurface<double>> preSubdivided(
  std::vector<iga::BezierSurface<double>> surfaces, int levels)
{
  for (int level = 0; level < levels; ++level)
  {
    std::vector<iga::BezierSurface<double>> pieces;
    for (const auto& surface : surfaces)
    {
      const int degree[2] = { surface.degree(0), surface.degree(1) };
      const size_t size = surface.coeffs().size();
      std::vector<double> children(4 * size);
      iga::splitMidpoint<double, 2>(surface.view(), children.data());
      for (int child = 0; child < 4; ++child)
      {
        pieces.emplace_back(degree, surface.channels());
        std::copy_n(
          children.begin() + std::ptrdiff_t(child * size), size, pieces.back().coeffs().begin());
      }
    }
    surfaces = std::move(pieces);
  }
  return surfaces;
}

/// The paper's pre-subdivision study at 512x512: the teapot's patches split 0..5 times (32 to
/// 32 768 patches), SST against the better reference (ratio `referenceOverSst_teapotSplitK`).
/// As patches shrink to a pixel or two the per-pixel schemes' trees have little left to split,
/// and the paper finds them converging towards SST.
void preSubdivisionStudy(bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  using iga::sst::Method;
  const auto teapot = iga::makeTeapot<double>().patches;
  // One camera for every level (the pieces' control points bound the teapot more tightly), so
  // that each level draws the same pixels.
  const iga::Camera camera = frameSurfaces(teapot);
  const Reframe sameCamera = [&](const iga::Camera&) { return camera; };
  for (int levels = 0; levels <= (quick ? 2 : 5); ++levels)
  {
    const auto surfaces = preSubdivided(teapot, levels);
    const std::string name =
      "teapot-split" + std::to_string(levels) + "-" + std::to_string(surfaces.size());
    auto run = [&](Method method, int repetitions)
    {
      return measureSurfaces(name, surfaces, 512, 512, threads, method, repetitions, {},
        iga::sst::Backend::Cpu, "presubdivision", sameCamera);
    };
    const auto sst = run(Method::SharedSubdivisionTree, reps);
    const auto basic = run(Method::BasicScheme, 1);
    const auto clipping = run(Method::BezierClipping, 1);
    all.insert(all.end(), { sst, basic, clipping });
    const std::string tag = "teapotSplit" + std::to_string(levels) + "_512x512";
    ratios.emplace_back("coveredPerPatch_" + tag, double(sst.covered) / double(surfaces.size()));
    ratios.emplace_back("referenceOverSst_" + tag, std::min(basic.ms, clipping.ms) / sst.ms);
  }
}

/// Frames of the dice's solid, cube<0 - pips<0: its nearest surface, or all its layers (as a
/// translucent actor draws them); seen by `reframe` of the camera framing it whole, or by that.
Measurement measureDiceSolid(const std::string& study, const std::string& dataset, int width,
  int height, int threads, int repetitions, iga::sst::Backend backend, bool allLayers,
  const Reframe& reframe = {})
{
  const auto dice = iga::makeDice<double>();
  const auto faces = iga::boundaryFaces(dice.patches);
  iga::sst::CsgScene scene;
  scene.inputs.push_back({ &dice.patches, dice.attributeNames, &faces });
  scene.expression = iga::csg::parseExpression("cube<0 - pips<0");
  const iga::Camera whole = frame(dice.patches);
  const iga::Camera camera = reframe ? reframe(whole) : whole;
  return measureFrames(study, dataset, 0, 4, width, height, threads,
    iga::sst::Method::SharedSubdivisionTree, repetitions, backend, false,
    [&](int, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
    {
      iga::sst::Settings s = settings;
      s.firstHitOnly = !allLayers;
      return iga::sst::renderCsg(scene, iga::sst::makeView(camera, s.width, s.height), s, m, out);
    });
}

/// The CSG study: the dice's solid against the cube's isosurface alone (first hit), per size.
void csgStudy(bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  using iga::sst::Method;
  const auto dice = iga::makeDice<double>();
  const int sizes[2][2] = { { quick ? 256 : 512, quick ? 256 : 512 }, { 1920, 1080 } };
  for (const auto& size : sizes)
  {
    const std::string tag = std::to_string(size[0]) + "x" + std::to_string(size[1]);
    // The solid's nearest surface, then all its layers (as a translucent actor draws them).
    const auto csg = measureDiceSolid("csg", "dice-cube-minus-pips", size[0], size[1], threads,
      reps, iga::sst::Backend::Cpu, false);
    const auto layers = measureDiceSolid("csg", "dice-cube-minus-pips-all-layers", size[0], size[1],
      threads, reps, iga::sst::Backend::Cpu, true);
    const auto cube = measure("csg", "dice-cube-isosurface", dice, 0.0, 4, size[0], size[1],
      threads, Method::SharedSubdivisionTree, reps);
    all.insert(all.end(), { csg, layers, cube });
    ratios.emplace_back("csgOverIsosurface_dice_" + tag, csg.ms / cube.ms);
    ratios.emplace_back("allLayersOverFirst_diceCsg_" + tag, layers.ms / csg.ms);
    if (quick)
    {
      break;
    }
  }
}

std::string json(
  const std::vector<Measurement>& all, const std::vector<std::pair<std::string, double>>& ratios)
{
  std::ostringstream out;
  out << "{\n  \"hardwareThreads\": " << std::thread::hardware_concurrency()
      << ",\n  \"measurements\": [\n";
  for (size_t k = 0; k < all.size(); ++k)
  {
    const auto& m = all[k];
    const auto& r = m.report;
    out << "    {\"study\": \"" << m.study << "\", \"dataset\": \"" << m.dataset
        << "\", \"method\": \"" << m.method << "\", \"backend\": \"" << m.backend
        << "\", \"degree\": " << m.degree << ", \"width\": " << m.width
        << ", \"height\": " << m.height << ", \"threads\": " << m.threads << ", \"ms\": " << m.ms
        << ", \"peakMB\": " << m.peakMB
        << ", \"peakBudgetedMB\": " << r.peakBudgetedBytes / 1048576.0
        << ", \"coveredPixels\": " << m.covered << ", \"newtonSolves\": " << m.newtonSolves
        << ", \"newtonRuns\": " << r.newtonRuns
        << ", \"newtonEvaluations\": " << r.newtonEvaluations << ", \"floorMs\": " << m.floorMs
        << ", \"subdividedPatches\": " << m.subdivided << ", \"unresolvedPixels\": " << m.unresolved
        << ", \"bands\": " << r.bands << ", \"uploadedMB\": " << r.uploadedBytes / 1048576.0
        << ", \"downloadedMB\": " << r.downloadedBytes / 1048576.0
        << ", \"composedRays\": " << r.composedRays << ", \"rootFinderStepsPerRay\": "
        << (r.composedRays ? double(r.rootFinderSteps) / double(r.composedRays) : 0.0)
        << ", \"seededRays\": " << r.seededRays << ", \"isosurfaceCells\": " << r.isosurfaceCells
        << ", \"stagesMs\": {\"setup\": " << r.msSetup << ", \"input\": " << r.msInput
        << ", \"sweepAndGroup\": " << r.msSweepAndGroup << ", \"solution\": " << r.msSolution
        << ", \"overlap\": " << r.msOverlap << ", \"subdivision\": " << r.msSubdivision
        << ", \"compaction\": " << r.msCompaction << ", \"gbuffer\": " << r.msGBuffer << "}}"
        << (k + 1 < all.size() ? "," : "") << "\n";
  }
  out << "  ],\n  \"ratios\": {\n";
  for (size_t k = 0; k < ratios.size(); ++k)
  {
    out << "    \"" << ratios[k].first << "\": " << ratios[k].second
        << (k + 1 < ratios.size() ? "," : "") << "\n";
  }
  out << "  }\n}\n";
  return out.str();
}

/// The camera turned by `degrees` about its view-up axis through the focal point.
iga::Camera orbited(iga::Camera camera, double degrees)
{
  const glm::dvec3 arm = camera.position - camera.focalPoint;
  const glm::dvec3 axis = glm::normalize(camera.viewUp);
  const double a = degrees * 3.14159265358979323846 / 180;
  camera.position = camera.focalPoint + arm * std::cos(a) + glm::cross(axis, arm) * std::sin(a) +
                    axis * glm::dot(axis, arm) * (1 - std::cos(a));
  return camera;
}

/// Frame coherency: ray composition (point insertion) over an orbit of a degree a frame, each
/// frame cold, and each seeded by the frame before (Settings::seedFrame).
void orbitWithCoherency(const std::string& name, const iga::VolumeSet<double>& set, int degree,
  int size, int threads, int frames, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  double ms[2] = { 0, 0 };
  for (int seeded = 0; seeded < 2; ++seeded)
  {
    iga::sst::GBuffer previous; // the orbit's start, before the frames measured
    iga::sst::Settings start;
    start.width = start.height = size;
    start.threads = threads;
    start.isovalues = { 0.0 };
    iga::sst::render(
      set.patches, frame(set.patches), start, iga::sst::Method::RayComposition, previous);
    auto orbit = measureFrames("algebraic", name + (seeded ? "/orbit-seeded" : "/orbit-cold"), 0.0,
      degree, size, size, threads, iga::sst::Method::RayComposition, frames, iga::sst::Backend::Cpu,
      false,
      [&](int r, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
      {
        iga::sst::Settings coherent = settings;
        coherent.seedFrame = seeded ? &previous : nullptr;
        const auto report =
          iga::sst::render(set.patches, orbited(frame(set.patches), r + 1), coherent, m, out);
        previous = out;
        return report;
      });
    ms[seeded] = orbit.ms;
    all.push_back(std::move(orbit));
  }
  ratios.emplace_back("coldOverSeeded_" + name, ms[0] / ms[1]);
}

/// Silhouette anti-aliasing's cost: ray composition (point insertion) with and without the
/// rotated-grid samples of the pixels whose grey (a headlight's Lambert term, as the mapper's
/// shading marks edges) contrasts with a neighbour's by more than 0.1; ratio
/// `antialiasedOverPlain_NAME`.
void supersampledSilhouettes(const std::string& name, const iga::VolumeSet<double>& set, int degree,
  int size, int threads, int reps, const Measurement& plain, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  const iga::Camera camera = frame(set.patches);
  const iga::sst::View view = iga::sst::makeView(camera, size, size);
  size_t marked = 0;
  auto smoothed = measureFrames("algebraic", name + "/antialiased", 0.0, degree, size, size,
    threads, iga::sst::Method::RayComposition, reps, iga::sst::Backend::Cpu, false,
    [&](int, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
    {
      const auto start = std::chrono::steady_clock::now();
      const auto renderFrame =
        [&](const iga::sst::View& v, const iga::sst::Settings& s, iga::sst::GBuffer& g)
      { return iga::sst::render(iga::sst::Scene(set.patches), v, s, m, g); };
      iga::sst::FrameReport report = renderFrame(view, settings, out);
      std::vector<float> grey(4 * size_t(size) * size_t(size), 0.0f);
      for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
          if (const iga::sst::Hit* hit = out.firstHit(i, j))
          {
            const float lambert =
              float(std::fabs(glm::dot(hit->normal, glm::normalize(view.eye - hit->position))));
            float* rgba = &grey[4 * size_t(j * size + i)];
            std::fill(rgba, rgba + 3, lambert);
            rgba[3] = 1.0f;
          }
      const auto mask = iga::sst::contrastingPixels(grey, size, size, 0.1f);
      marked = size_t(std::count(mask.begin(), mask.end(), 1));
      std::array<iga::sst::GBuffer, iga::sst::kRotatedGridSamples> samples;
      iga::sst::addPassReport(
        report, iga::sst::renderRotatedGridSamples(view, settings, mask, renderFrame, samples));
      report.msTotal =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      return report;
    });
  std::fprintf(stderr, "%-11s %-28s %zu pixels supersampled\n", "", name.c_str(), marked);
  ratios.emplace_back("antialiasedOverPlain_" + name, smoothed.ms / plain.ms);
  ratios.emplace_back("antialiasedPixels_" + name, double(marked));
  all.push_back(std::move(smoothed));
}

/// The scene's ray composition without isosurface cells (every ray through the patches' boxes
/// composed over its whole segment), against `withCells`: ratio `uncelledOverCelled_NAME`.
void withoutCells(const std::string& name, const iga::VolumeSet<double>& set,
  const iga::Camera& camera, int degree, int size, int threads, int reps,
  const Measurement& withCells, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  auto uncelled = measureFrames("algebraic", name + "/without-cells", 0.0, degree, size, size,
    threads, iga::sst::Method::RayComposition, reps, iga::sst::Backend::Cpu, false,
    [&](int, const iga::sst::Settings& settings, iga::sst::Method m, iga::sst::GBuffer& out)
    {
      iga::sst::Settings uncelledSettings = settings;
      uncelledSettings.isosurfaceCells = false;
      return iga::sst::render(set.patches, camera, uncelledSettings, m, out);
    });
  ratios.emplace_back("uncelledOverCelled_" + name, uncelled.ms / withCells.ms);
  all.push_back(std::move(uncelled));
}

/// One algebraic scene: the SST against ray composition with each root finder (ratio
/// `sstOverComposition_NAME_FINDER`), its orbit with and without frame coherency, and the cost
/// of anti-aliasing it.
void compareWithComposition(const std::string& name, const iga::VolumeSet<double>& set, int degree,
  bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  using iga::sst::Method;
  const int size = quick ? 256 : 512;
  const auto sst = measure("algebraic", name, set, 0.0, degree, size, size, threads,
    Method::SharedSubdivisionTree, quick ? 1 : reps);
  all.push_back(sst);
  const iga::Camera camera = frame(set.patches);
  for (int f = 0; f < iga::kRootFinderCount; ++f)
  {
    const auto finder = iga::RootFinder(f);
    auto composed = measureFrames("algebraic", name + "/" + iga::rootFinderName(finder), 0.0,
      degree, size, size, threads, Method::RayComposition, reps, iga::sst::Backend::Cpu, false,
      [&](int, const iga::sst::Settings& settings, Method m, iga::sst::GBuffer& out)
      {
        iga::sst::Settings withFinder = settings;
        withFinder.rootFinder = finder;
        return iga::sst::render(set.patches, camera, withFinder, m, out);
      });
    ratios.emplace_back(
      "sstOverComposition_" + name + "_" + iga::rootFinderName(finder), sst.ms / composed.ms);
    if (finder == iga::RootFinder::PointInsertion)
    {
      supersampledSilhouettes(name, set, degree, size, threads, reps, composed, all, ratios);
      withoutCells(name, set, camera, degree, size, threads, reps, composed, all, ratios);
    }
    all.push_back(std::move(composed));
  }
  orbitWithCoherency(name, set, degree, size, threads, std::max(reps, 5), all, ratios);
}

/// The algebraic study: each gallery surface over its box as one polynomial volume, then ABS
/// fields (iga/AbsField.h) fitted to gallery surfaces, named SURFACE-abs-CELLS-pDEGREE.
void algebraicStudy(bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  int count = 0;
  const iga::AlgebraicSurface* gallery = iga::algebraicGallery(count);
  for (int s = 0; s < count; ++s)
  {
    const auto field = iga::parsePolynomial(gallery[s].expression);
    iga::VolumeSet<double> set;
    set.patches.push_back(iga::makeAlgebraicVolume(field, gallery[s].box));
    compareWithComposition(
      gallery[s].name, set, iga::detail::totalDegree(field), quick, threads, reps, all, ratios);
  }
  const struct
  {
    const char* surface;
    int cells, degree;
  } models[] = { { "kummer", 16, 3 }, { "kummer", 37, 3 }, { "heart", 32, 2 },
    { "dervish", 32, 3 } };
  for (const auto& model : models)
  {
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(model.surface);
    const auto f = iga::parsePolynomial(surface->expression);
    const int cells[3] = { model.cells, model.cells, model.cells };
    const iga::AbsField field =
      iga::makeAbsField([&](double x, double y, double z) { return f.evaluate(x, y, z); },
        surface->box, model.degree, cells);
    const std::string name = std::string(model.surface) + "-abs-" + std::to_string(model.cells) +
                             "-p" + std::to_string(model.degree);
    std::printf(
      "%s: %zu of %zu elements kept\n", name.c_str(), field.set.patches.size(), field.elements);
    compareWithComposition(name, field.set, 3 * model.degree, quick, threads, reps, all, ratios);
  }
}

/// Milliseconds one evaluation of the engine's Newton takes on one core: the solution stage's
/// own solver (iga::sst::solvePixel) on the screen patch of `world` (a volume's first attribute,
/// or a surface) as `camera` frames it at width x height, for pixels next to random points of
/// the patch, the isovalue the attribute there.
double newtonEvaluationMs(
  const iga::VolumeView<const double>& world, const iga::Camera& camera, int width, int height)
{
  const int attribute = world.degree[2] == 0 ? iga::kWeightChannel : iga::kFirstAttributeChannel;
  const auto window =
    iga::sst::windowFromWorld(iga::sst::makeView(camera, width, height), width, height);
  std::vector<double> screen(size_t(world.pointCount()) * iga::sst::kScreenChannels);
  iga::sst::makeScreenPatch(world, window, attribute, screen.data());
  const iga::VolumeView<const double> patch(screen.data(), world.degree, iga::sst::kScreenChannels);
  const int unknowns = iga::sst::unknownsOf(patch);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> inside(0.2, 0.8);
  iga::sst::NewtonWork work;
  const double tolerance[3] = { 1e-3, 1e-3, 1e-9 };
  const iga::sst::ClipPlanes<double> noClip{};
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 20000; ++k)
  {
    double u[3] = { inside(rng), inside(rng), unknowns == 3 ? inside(rng) : 0.0 }, values[8];
    iga::evaluateHomogeneous(patch, u, values, static_cast<double*>(nullptr));
    const int i = int(std::floor(values[iga::sst::kScreenX] / values[iga::sst::kScreenW]));
    const int j = int(std::floor(values[iga::sst::kScreenY] / values[iga::sst::kScreenW]));
    const double iso = values[iga::sst::kScreenAttribute] / values[iga::sst::kScreenWeight];
    double root[3], ndc;
    iga::sst::solvePixel(patch, i, j, iso, tolerance, u, root, ndc, noClip, &work);
  }
  const double ms =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return work.evaluations > 0 ? ms / work.evaluations : 0.0;
}

/// The measurement with its floor (Measurement::floorMs) for an evaluation costing `evaluationMs`.
Measurement withFloor(Measurement m, double evaluationMs)
{
  const auto& r = m.report;
  const double perSolve = r.newtonRuns > 0 ? double(r.newtonEvaluations) / r.newtonRuns : 0.0;
  m.floorMs = double(m.covered) * perSolve * evaluationMs / std::max(1, r.threads);
  std::fprintf(stderr,
    "%-11s %-16s floor %.1f ms (%.2f evaluations a solve, %.0f ns each): "
    "frame / floor %.1f\n",
    m.study.c_str(), m.dataset.c_str(), m.floorMs, perSolve, 1e6 * evaluationMs,
    m.floorMs > 0 ? m.ms / m.floorMs : 0.0);
  return m;
}

/// Scenes that fill the screen as users frame them (issue 23), at 1920x1080 on `backend`, for
/// the datasets `wanted` keeps, each framed whole and zoomed to cover a third of the image or
/// more (33-39%): the Marsden sphere p2, the teapot's 32 bicubic surfaces, the deforming 10k
/// blade's boundary (a middle part, its span across the image) and the dice's solid (CSG, first
/// hit). Coverage is reported beside each figure.
std::vector<Measurement> screenFillingStudy(const std::string& study, iga::sst::Backend backend,
  int threads, int reps, const std::function<bool(const std::string&)>& wanted)
{
  using iga::sst::Method;
  const int width = 1920, height = 1080;
  std::vector<Measurement> all;
  // On the CPU each frame is set against its floor, Newton's evaluations costed on its first patch.
  auto measured =
    [&](const Measurement& m, const iga::VolumeView<const double>& patch, const iga::Camera& camera)
  {
    all.push_back(backend == iga::sst::Backend::Cpu
                    ? withFloor(m, newtonEvaluationMs(patch, camera, width, height))
                    : m);
  };
  // A tri-quadratic volume's isosurface at 0, framed whole and zoomed by `zoom`.
  auto volumeCloseUp = [&](const std::string& name, const iga::VolumeSet<double>& set, double zoom)
  {
    if (!wanted(name))
    {
      return;
    }
    const iga::Camera camera = zoomed(frame(set.patches), zoom);
    measured(measureFrames(study, name, 0.0, 2, width, height, threads,
               Method::SharedSubdivisionTree, reps, backend, false,
               [&](int, const iga::sst::Settings& settings, Method m, iga::sst::GBuffer& out)
               { return iga::sst::render(set.patches, camera, settings, m, out); }),
      set.patches[0].view(), camera);
  };
  volumeCloseUp("marsden-sphere-p2-close", iga::makeMarsdenSphere<double>(2), 2.5);
  const auto teapot = iga::makeTeapot<double>().patches;
  const auto teapotCloseUp = [](const iga::Camera& whole) { return zoomed(whole, 2.0); };
  if (wanted("teapot-close"))
  {
    measured(measureSurfaces("teapot-close", teapot, width, height, threads,
               Method::SharedSubdivisionTree, reps, {}, backend, study, teapotCloseUp),
      iga::flatVolume(teapot[0].view()), teapotCloseUp(frameSurfaces(teapot)));
  }
  const DeformingBladeBoundary boundary(iga::bladeLayout(10000));
  if (wanted(boundary.name() + "-close"))
  {
    // Its span across the image, as a long blade is seen on a wide screen.
    auto alongTheWidth = [](const iga::Camera& whole)
    {
      iga::Camera camera = zoomed(whole, 4.5);
      camera.viewUp = { 1, 0, 0 };
      return camera;
    };
    const auto faces = boundary(0);
    measured(measureSurfaces(boundary.name() + "-close", faces, width, height, threads,
               Method::SharedSubdivisionTree, reps, boundary, backend, study, alongTheWidth),
      iga::flatVolume(faces[0].view()), alongTheWidth(frameSurfaces(faces)));
  }
  volumeCloseUp("twisted-tube-close", iga::makeTwistedTube<double>(0.5), 3.5);
  if (wanted("dice-cube-minus-pips-close"))
  {
    const auto dice = iga::makeDice<double>();
    const auto diceCloseUp = [](const iga::Camera& whole) { return zoomed(whole, 1.7); };
    measured(measureDiceSolid(study, "dice-cube-minus-pips-close", width, height, threads, reps,
               backend, false, diceCloseUp),
      dice.patches[0].view(), diceCloseUp(frame(dice.patches)));
  }
  return all;
}

/// The SST paper's large-data setting: the 800k-patch blade at 512x512, its strain's isosurface
/// at each isovalue of a sweep, the set kept throughout (one data version, as the mapper keeps a
/// static input's while the isovalue changes), on the CPU with each frame's floor. The first
/// isovalue's frames start with the set's one-off preparation.
std::vector<Measurement> bladeIsovalueSweep(int threads, int reps)
{
  const int size = 512;
  const auto blade = iga::makeBlade<double>(iga::bladeLayout(800000), 0.5);
  const iga::Camera camera = frame(blade.patches);
  const double evaluationMs = newtonEvaluationMs(blade.patches[0].view(), camera, size, size);
  uint64_t keptVersion = 0;
  std::vector<Measurement> sweep;
  for (const double isovalue : { 0.1, 0.2, 0.3, 0.4, 0.5 })
  {
    char name[64];
    std::snprintf(name, sizeof name, "blade-%zu-strain-%.1f", blade.patches.size(), isovalue);
    sweep.push_back(withFloor(
      measureFrames("screen-filling", name, isovalue, 2, size, size, threads,
        iga::sst::Method::SharedSubdivisionTree, reps, iga::sst::Backend::Cpu, false,
        [&](int, iga::sst::Settings settings, iga::sst::Method method, iga::sst::GBuffer& out)
        {
          keptVersion = keptVersion ? keptVersion : settings.dataVersion;
          settings.dataVersion = keptVersion;
          return iga::sst::render(blade.patches, camera, settings, method, out);
        }),
      evaluationMs));
  }
  return sweep;
}

/// The CUDA engine's study (see the header). Returns false, with the reason, without a GPU.
bool gpuStudy(bool quick, const std::string& only, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios, std::string& why)
{
  auto wanted = [&](const std::string& dataset) { return dataset.find(only) != std::string::npos; };
  using iga::sst::Backend;
  using iga::sst::Method;
  const auto probe = iga::makeMarsdenSphere<double>(2);
  const Measurement warmUp = measure("warm-up", "marsden-sphere", probe, 0.0, 2, 256, 256, 0,
    Method::SharedSubdivisionTree, 1, Backend::Cuda);
  if (warmUp.backend != "cuda")
  {
    why = warmUp.report.notice;
    return false;
  }
  const int reps = quick ? 2 : 5;
  struct Case
  {
    std::string name;
    iga::VolumeSet<double> set;
    double isovalue;
    int degree;
  };
  std::vector<Case> cases;
  cases.push_back({ "teardrop", iga::makeTeardrop<double>(1.2), 0.0, 2 });
  cases.push_back({ "collapsed-tube", iga::makeTube<double>(0.0, 0.0), 1.0, 2 });
  for (int degree = 2; degree <= 5; ++degree)
  {
    cases.push_back({ "marsden-sphere-p" + std::to_string(degree),
      iga::makeMarsdenSphere<double>(degree), 0.0, degree });
  }
  const std::vector<std::pair<int, int>> sizes = { { 1920, 1080 }, { 3840, 2160 } };
  for (const auto& c : cases)
  {
    if (!wanted(c.name))
    {
      continue;
    }
    for (const auto& size : sizes)
    {
      all.push_back(measure("gpu", c.name, c.set, c.isovalue, c.degree, size.first, size.second, 0,
        Method::SharedSubdivisionTree, reps, Backend::Cuda));
    }
  }
  // The deforming blade: every frame a new control net (the flap's time steps).
  const iga::BladeLayout small = iga::bladeLayout(quick ? 1000 : 10000);
  auto flapping = [&](int r) { return iga::makeBlade<double>(small, 0.1 * (r % 10)); };
  const auto blade = flapping(0);
  const std::string smallName = "blade-" + std::to_string(small.patchCount()) + "-deforming";
  if (wanted(smallName))
  {
    for (const auto& size : sizes)
    {
      all.push_back(measure("gpu", smallName, blade, 0.3, 2, size.first, size.second, 0,
        Method::SharedSubdivisionTree, reps, Backend::Cuda, flapping));
    }
    const Measurement gpu1080 = all[all.size() - 2];
    const Measurement cpu1080 = measure("gpu", smallName, blade, 0.3, 2, 1920, 1080, 0,
      Method::SharedSubdivisionTree, 1, Backend::Cpu, flapping);
    all.push_back(cpu1080);
    ratios.emplace_back("cpuOverGpu_" + smallName + "_1080p", cpu1080.ms / gpu1080.ms);
  }
  // A deforming NURBS volume of about 10k tri-quadratic elements, handed over as its nets (each
  // frame uploads only the moved net; the GPU extracts the elements, as for the VTK mapper's
  // NURBS input) and as its elements (uploaded whole every frame).
  const int spans = quick ? 10 : 22;
  const std::string ballName = "nurbs-ball-" + std::to_string(spans * spans * spans) + "-deforming";
  const iga::BSplinePatch<double, 3> ball = iga::makeNurbsBall<double>(spans, 1.0);
  const iga::BezierExtraction<double, 3> ballExtraction(ball.knots, ball.degree, ball.netSize);
  std::vector<std::vector<double>> ballNets;
  for (int r = 0; r < 10; ++r)
  {
    ballNets.push_back(iga::makeNurbsBall<double>(spans, 1.0 + 0.03 * r).net);
  }
  auto ballVolumes = [&](int r)
  {
    iga::sst::NurbsVolumes volumes;
    volumes.extractions = { &ballExtraction };
    volumes.nets = { &ballNets[r % 10] };
    volumes.channels = ball.channels;
    volumes.extractionVersion = 1;
    return volumes;
  };
  iga::VolumeSet<double> ballElements;
  ballElements.patches = iga::sst::extractElements(ballVolumes(0));
  const iga::Camera ballCamera = frame(ballElements.patches);
  for (bool nets : { true, false })
  {
    const std::string name = ballName + (nets ? "-nets" : "-elements");
    if (!wanted(name))
    {
      continue;
    }
    all.push_back(measureFrames("gpu", name, 0.0, 2, 1920, 1080, 0, Method::SharedSubdivisionTree,
      reps, Backend::Cuda, true,
      [&](int r, const iga::sst::Settings& settings, Method m, iga::sst::GBuffer& out)
      {
        const iga::sst::View view = iga::sst::makeView(ballCamera, 1920, 1080);
        return nets ? iga::sst::render(ballVolumes(r), view, settings, m, out)
                    : iga::sst::render(
                        iga::sst::extractElements(ballVolumes(r)), view, settings, m, out);
      }));
  }
  // The screen-filling scenes, against one CPU frame each on all the host's threads.
  const auto filling = screenFillingStudy("gpu", Backend::Cuda, 0, reps, wanted);
  const auto fillingOnCpu = screenFillingStudy("gpu", Backend::Cpu, 0, 1, wanted);
  for (size_t k = 0; k < filling.size(); ++k)
  {
    all.insert(all.end(), { filling[k], fillingOnCpu[k] });
    ratios.emplace_back(
      "cpuOverGpu_" + filling[k].dataset + "_1080p", fillingOnCpu[k].ms / filling[k].ms);
  }
  const iga::BladeLayout large = iga::bladeLayout(800000);
  const std::string largeName = "blade-" + std::to_string(large.patchCount());
  if (!quick && wanted(largeName))
  {
    const auto big = iga::makeBlade<double>(large, 0.5);
    for (const auto& size : sizes)
    {
      all.push_back(measure("gpu", largeName, big, 0.3, 2, size.first, size.second, 0,
        Method::SharedSubdivisionTree, 3, Backend::Cuda));
    }
    // The same set deforming: two time steps in turn, a new data version every frame (the
    // whole set is checked and sent again).
    const auto flapped = iga::makeBlade<double>(large, 0.6);
    const iga::Camera camera = frame(big.patches);
    all.push_back(measureFrames("gpu", largeName + "-deforming", 0.3, 2, 1920, 1080, 0,
      Method::SharedSubdivisionTree, 3, Backend::Cuda, true,
      [&](int r, const iga::sst::Settings& settings, Method m, iga::sst::GBuffer& out)
      { return iga::sst::render((r % 2 ? flapped : big).patches, camera, settings, m, out); }));
  }
  return true;
}

} // namespace

/// The engine's own studies (the paper's figures): SST against one tree per pixel over the
/// sphere's degree (fig. 13), resolution doubling (fig. 11), threads and the 512^2 sphere frame,
/// the default dataset, and the deforming blade's many patches at 1080p.
void engineStudy(bool quick, int threads, int reps, std::vector<Measurement>& all,
  std::vector<std::pair<std::string, double>>& ratios)
{
  using iga::sst::Method;
  // Fig. 13: SST against one tree per pixel over the sphere's degree.
  const int degreeResolution = quick ? 128 : 256;
  for (int degree = 2; degree <= 5; ++degree)
  {
    const auto sphere = iga::makeMarsdenSphere<double>(degree);
    auto run = [&](Method method, int repetitions)
    {
      return measure("degree", "marsden-sphere", sphere, 0.0, degree, degreeResolution,
        degreeResolution, threads, method, repetitions);
    };
    const auto sst = run(Method::SharedSubdivisionTree, reps);
    const auto basic = run(Method::BasicScheme, 1);
    all.push_back(sst);
    all.push_back(basic);
    ratios.emplace_back("basicOverSst_p" + std::to_string(degree), basic.ms / sst.ms);
  }

  // Fig. 11: resolution doubling, time and memory.
  const auto sphere2 = iga::makeMarsdenSphere<double>(2);
  const std::vector<int> resolutions =
    quick ? std::vector<int>{ 128, 256, 512 } : std::vector<int>{ 256, 512, 1024, 2048 };
  std::vector<Measurement> scaling;
  for (int resolution : resolutions)
  {
    scaling.push_back(measure("resolution", "marsden-sphere", sphere2, 0.0, 2, resolution,
      resolution, threads, Method::SharedSubdivisionTree, resolution >= 1024 ? 1 : reps));
    all.push_back(scaling.back());
  }
  for (size_t k = 1; k < scaling.size(); ++k)
  {
    const std::string step =
      std::to_string(scaling[k - 1].width) + "to" + std::to_string(scaling[k].width);
    ratios.emplace_back("timeGrowth_" + step, scaling[k].ms / scaling[k - 1].ms);
    ratios.emplace_back("memoryGrowth_" + step, scaling[k].peakMB / scaling[k - 1].peakMB);
  }

  // Threads, and the 512^2 tri-quadratic sphere frame.
  const int frameResolution = quick ? 256 : 512;
  const auto one = measure("threads", "marsden-sphere", sphere2, 0.0, 2, frameResolution,
    frameResolution, 1, Method::SharedSubdivisionTree, reps);
  const auto many = measure("threads", "marsden-sphere", sphere2, 0.0, 2, frameResolution,
    frameResolution, threads, Method::SharedSubdivisionTree, reps);
  all.push_back(one);
  all.push_back(many);
  ratios.emplace_back("speedupThreads", one.ms / many.ms);

  // The default dataset at the command's default size.
  const auto tube = iga::makeTwistedTube<double>(0.5);
  all.push_back(measure("default", "twisted-tube", tube, 0.0, 2, 800, 600, threads,
    Method::SharedSubdivisionTree, reps));

  // Many patches on CPU threads: the deforming blade (a new control net every frame) at 1080p,
  // where the frame's preparation over all patches weighs.
  const iga::BladeLayout bladeLayout = iga::bladeLayout(quick ? 1000 : 10000);
  auto flapping = [&](int r) { return iga::makeBlade<double>(bladeLayout, 0.1 * (r % 10)); };
  all.push_back(measure("patches",
    "blade-" + std::to_string(bladeLayout.patchCount()) + "-deforming", flapping(0), 0.3, 2, 1920,
    1080, threads, Method::SharedSubdivisionTree, reps, iga::sst::Backend::Cpu, flapping));
}

int main(int argc, char** argv)
{
  bool quick = false, gpu = false, csgOnly = false, algebraicOnly = false, fillingOnly = false,
       surfacesOnly = false;
  std::string jsonFile, only;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--csg"))
      csgOnly = true;
    else if (!std::strcmp(argv[i], "--algebraic"))
      algebraicOnly = true;
    else if (!std::strcmp(argv[i], "--screen-filling"))
      fillingOnly = true;
    else if (!std::strcmp(argv[i], "--surfaces"))
      surfacesOnly = true;
    else if (!std::strcmp(argv[i], "--gpu"))
      gpu = true;
    else if (!std::strcmp(argv[i], "--json") && i + 1 < argc)
      jsonFile = argv[++i];
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
      only = argv[++i];
    else
    {
      std::fprintf(stderr,
        "usage: igaBenchmark [--gpu [--only NAME] | --csg | --algebraic | --screen-filling | "
        "--surfaces] [--quick] [--json FILE]\n");
      return 1;
    }
  }
  if (!only.empty() && !gpu)
  {
    std::fprintf(stderr, "igaBenchmark: --only selects datasets of the GPU study; add --gpu\n");
    return 1;
  }
  const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  const int reps = quick ? 1 : 5;
  std::vector<Measurement> all;
  std::vector<std::pair<std::string, double>> ratios;
  using iga::sst::Method;

  auto emit = [&](const std::string& document)
  {
    if (jsonFile.empty())
    {
      std::fputs(document.c_str(), stdout);
    }
    else
    {
      std::ofstream(jsonFile) << document;
    }
    for (const auto& ratio : ratios)
    {
      std::fprintf(stderr, "%-28s %.2f\n", ratio.first.c_str(), ratio.second);
    }
    return 0;
  };
  if (gpu)
  {
    std::string why;
    if (!gpuStudy(quick, only, all, ratios, why))
    {
      std::fprintf(stderr, "igaBenchmark --gpu: %s; nothing measured\n", why.c_str());
      return emit("{\n  \"skipped\": \"" + why + "\"\n}\n");
    }
    return emit(json(all, ratios));
  }
  // A warm-up frame: thread start-up, page faults and caches are not what the studies measure.
  measure("warm-up", "marsden-sphere", iga::makeMarsdenSphere<double>(2), 0.0, 2, 256, 256, threads,
    Method::SharedSubdivisionTree, 1);
  if (csgOnly)
  {
    csgStudy(quick, threads, reps, all, ratios);
    return emit(json(all, ratios));
  }
  if (fillingOnly)
  {
    all = screenFillingStudy("screen-filling", iga::sst::Backend::Cpu, threads, reps,
      [](const std::string&) { return true; });
    const auto sweep = bladeIsovalueSweep(threads, reps);
    all.insert(all.end(), sweep.begin(), sweep.end());
    return emit(json(all, ratios));
  }
  if (surfacesOnly)
  {
    surfaceStudy(quick, threads, reps, all, ratios);
    preSubdivisionStudy(quick, threads, reps, all, ratios);
    return emit(json(all, ratios));
  }
  if (algebraicOnly)
  {
    algebraicStudy(quick, threads, reps, all, ratios);
    return emit(json(all, ratios));
  }

  engineStudy(quick, threads, reps, all, ratios);
  surfaceStudy(quick, threads, reps, all, ratios);
  csgStudy(quick, threads, reps, all, ratios);

  return emit(json(all, ratios));
}
