// vtkIGAIsosurfaceMapper's engine settings in a real render window: progress events, the
// subdivision and memory caps with their once-only warnings, the backend choice and its CPU
// fallback, and the lookup table's own range (UseLookupTableScalarRange).
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "iga/sst/Engine.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPlane.h"
#include "vtkPoints.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{

/// Records the mapper's progress values and the text of its warnings.
class Recorder : public vtkCommand
{
public:
  static Recorder* New() { return new Recorder; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    if (event == vtkCommand::ProgressEvent)
    {
      progress.push_back(*static_cast<double*>(data));
    }
    else if (event == vtkCommand::WarningEvent)
    {
      warnings.emplace_back(static_cast<const char*>(data));
    }
    else if (event == vtkCommand::ErrorEvent)
    {
      errors.emplace_back(static_cast<const char*>(data));
    }
    else if (event == vtkCommand::TextEvent)
    {
      texts.emplace_back(static_cast<const char*>(data));
    }
  }
  int count(const std::string& part) const
  {
    int n = 0;
    for (const auto& warning : warnings)
    {
      n += warning.find(part) != std::string::npos;
    }
    return n;
  }
  std::vector<double> progress;
  std::vector<std::string> warnings;
  std::vector<std::string> errors;
  std::vector<std::string> texts; ///< the output window's plain messages
};

/// The default dataset (the twisted tube at time 0.5), its temperature = 0 sheet coloured by
/// radius, seen from the plugin tests' camera.
struct TubeScene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkNew<Recorder> recorder;
  vtkSmartPointer<vtkImageData> image;

  explicit TubeScene(int width = 240, int height = 200)
  {
    window->SetOffScreenRendering(1);
    window->SetSize(width, height);
    window->AddRenderer(renderer);
    renderer->SetBackground(0, 0, 0);
    mapper->SetInputData(
      vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5)));
    mapper->SetSurfaceArrayName("temperature");
    mapper->SetIsovalue(0, 0.0);
    mapper->AddObserver(vtkCommand::ProgressEvent, recorder);
    mapper->AddObserver(vtkCommand::WarningEvent, recorder);
    mapper->AddObserver(vtkCommand::ErrorEvent, recorder);
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(2.4, -3.0, 2.6);
    camera->SetFocalPoint(0.2, 0.0, 1.0);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(30);
    renderer->ResetCameraClippingRange();
  }

  void render() { image = igatest::renderAndGrab(window); }

  /// Turns the camera a little: the engine must run again, with different counts.
  void turn(double degrees)
  {
    renderer->GetActiveCamera()->Azimuth(degrees);
    renderer->ResetCameraClippingRange();
  }

  const unsigned char* pixel(int i, int j) const
  {
    return static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
  }

  size_t coveredPixels() const { return mapper->GetLastGBuffer().coveredPixels(); }
};

TEST(IsosurfaceMapperSettings, ProgressIsMonotoneAndEndsAtOne)
{
  TubeScene scene;
  scene.render();
  const std::vector<double>& values = scene.recorder->progress;
  ASSERT_GE(values.size(), 3u) << "the start, some subdivision rounds and the end";
  EXPECT_EQ(values.front(), 0.0);
  EXPECT_EQ(values.back(), 1.0);
  int between = 0;
  for (size_t k = 0; k < values.size(); ++k)
  {
    EXPECT_GE(values[k], 0.0);
    EXPECT_LE(values[k], 1.0);
    if (k > 0)
    {
      EXPECT_GE(values[k], values[k - 1]) << "progress went back at event " << k;
    }
    if (k + 1 < values.size())
    {
      EXPECT_LT(values[k], 1.0) << "1 before the end of the frame, at event " << k;
    }
    between += values[k] > 0.0 && values[k] < 1.0;
  }
  EXPECT_GT(between, 0) << "no progress reported between the start and the end";
  EXPECT_EQ(scene.mapper->GetProgress(), 1.0);
  EXPECT_GT(scene.coveredPixels(), 1000u);
  // A frame reused from the last render reports no progress (the engine does not run).
  scene.recorder->progress.clear();
  scene.render();
  EXPECT_TRUE(scene.recorder->progress.empty());
}

/// The version that lets a GPU engine keep its copy of the patches: the same across camera moves
/// and property edits, new for a moved actor or new data, different between mappers.
TEST(IsosurfaceMapperSettings, DataVersionFollowsTheDataAndTheActorMatrixOnly)
{
  TubeScene scene;
  scene.render();
  const uint64_t first = scene.mapper->GetLastDataVersion();
  EXPECT_NE(first, 0u);
  scene.turn(20);
  scene.mapper->SetIsovalue(0, 0.2);
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastDataVersion(), first);
  scene.actor->SetPosition(0.1, 0, 0);
  scene.render();
  const uint64_t moved = scene.mapper->GetLastDataVersion();
  EXPECT_NE(moved, first);
  scene.mapper->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.8)));
  scene.render();
  EXPECT_NE(scene.mapper->GetLastDataVersion(), moved);
  EXPECT_NE(scene.mapper->GetLastDataVersion(), first);
  TubeScene other;
  other.render();
  EXPECT_NE(other.mapper->GetLastDataVersion() >> 40, first >> 40) << "two mappers, one version";
}

/// The actor's matrix moves the surface: the actor and the camera moved by the same offset give
/// the same hits, offset; moving it back gives the first frame again.
TEST(IsosurfaceMapperSettings, ActorMatrixMovesTheSurface)
{
  TubeScene scene;
  scene.render();
  const iga::sst::GBuffer first = scene.mapper->GetLastGBuffer();
  const double offset[3] = { 0.25, -0.5, 0.125 }; // exact in binary: no rounding in the move
  vtkCamera* camera = scene.renderer->GetActiveCamera();
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  scene.actor->SetPosition(offset[0], offset[1], offset[2]);
  camera->SetPosition(position[0] + offset[0], position[1] + offset[1], position[2] + offset[2]);
  camera->SetFocalPoint(focal[0] + offset[0], focal[1] + offset[1], focal[2] + offset[2]);
  scene.render();
  const iga::sst::GBuffer& moved = scene.mapper->GetLastGBuffer();
  ASSERT_EQ(moved.offsets, first.offsets);
  ASSERT_GT(first.coveredPixels(), 1000u);
  double largest = 0;
  for (size_t h = 0; h < first.hits.size(); ++h)
  {
    for (int d = 0; d < 3; ++d)
    {
      largest = std::max(
        largest, std::abs(moved.hits[h].position[d] - offset[d] - first.hits[h].position[d]));
    }
  }
  EXPECT_LT(largest, 1e-9);
  scene.actor->SetPosition(0, 0, 0);
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  scene.render();
  ASSERT_EQ(scene.mapper->GetLastGBuffer().offsets, first.offsets);
  for (size_t h = 0; h < first.hits.size(); ++h)
  {
    EXPECT_EQ(scene.mapper->GetLastGBuffer().hits[h].position[0], first.hits[h].position[0]);
  }
}

/// Renders an empty frame, then again from a turned camera: `message` is said once.
void expectEmptyAndSaidOnce(TubeScene& scene, const std::string& message)
{
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
  EXPECT_EQ(scene.coveredPixels(), 0u);
  EXPECT_EQ(scene.recorder->count(message), 1);
  scene.turn(4);
  scene.render();
  EXPECT_EQ(scene.recorder->count(message), 1) << "said on every frame";
}

/// A temperature that is 0.5 everywhere, drawn at 0.5: said once by name and value, not
/// subdivided to the depth cap (which took 15 s and 2.5 GB).
TEST(IsosurfaceMapperSettings, ConstantAttributeAtTheIsovalueIsSaidOnce)
{
  TubeScene scene;
  auto set = iga::makeTwistedTube<double>(0.5);
  const auto& names = set.attributeNames;
  const int channel = iga::kFirstAttributeChannel +
                      int(std::find(names.begin(), names.end(), "temperature") - names.begin());
  for (auto& patch : set.patches)
  {
    auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      view.point(p)[channel] = 0.5 * view.point(p)[iga::kWeightChannel];
  }
  scene.mapper->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(set));
  scene.mapper->SetIsovalue(0, 0.5);
  expectEmptyAndSaidOnce(scene,
    "attribute 'temperature' is constant (= 0.5) on 8 of 8 patches: a constant field has no "
    "isosurface there");
}

/// A frame that draws nothing says why, once: isovalues outside the attribute's range (with
/// the range), or a surface that the clipping planes cut away.
TEST(IsosurfaceMapperSettings, AnEmptyFrameSaysWhy)
{
  TubeScene scene;
  scene.mapper->SetIsovalue(0, 50.0);
  expectEmptyAndSaidOnce(scene,
    "nothing to draw: the isosurface 'temperature' = 50 lies outside the attribute's range [");

  scene.mapper->SetIsovalue(0, 0.0);
  vtkNew<vtkPlane> above; // keeps z >= 100, above the tube
  above->SetOrigin(0, 0, 100);
  above->SetNormal(0, 0, 1);
  scene.mapper->AddClippingPlane(above);
  scene.render();
  EXPECT_EQ(scene.coveredPixels(), 0u);
  EXPECT_EQ(scene.recorder->count("nothing drawn: the isosurface 'temperature' = 0 lies outside "
                                  "the view, the clipping planes cut it away, or the attribute "
                                  "does not reach that value"),
    1);
  scene.mapper->RemoveAllClippingPlanes();
  scene.render();
  EXPECT_GT(scene.coveredPixels(), 1000u);
  EXPECT_EQ(scene.recorder->count("nothing"), 2);
}

TEST(IsosurfaceMapperSettings, InsideOutCellsAreDrawnAsTheRightHandedOnesAndSaidOnce)
{
  TubeScene right, insideOut;
  // The generator's own left-handed patches, kept as they are.
  insideOut.mapper->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(
    iga::makeTwistedTube<double>(0.5), vtkIGABezierHexahedra::CellLayout::AsGiven));
  right.render();
  insideOut.render();
  const std::string said = "8 of 8 cells are inside-out for VTK";
  EXPECT_EQ(insideOut.recorder->count(said), 1);
  EXPECT_EQ(right.recorder->warnings.size(), 0u);
  // The same surface: coverage equal but for silhouette pixels, colours alike.
  const double covered = double(right.coveredPixels());
  EXPECT_GT(covered, 1000);
  EXPECT_NEAR(double(insideOut.coveredPixels()), covered, 0.01 * covered);
  int differ = 0;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 240; ++i)
      for (int c = 0; c < 3; ++c)
        differ += std::abs(int(right.pixel(i, j)[c]) - int(insideOut.pixel(i, j)[c])) > 8;
  EXPECT_LT(differ, 0.02 * covered);
  insideOut.turn(4);
  insideOut.render();
  EXPECT_EQ(insideOut.recorder->count(said), 1) << "said again for a new camera";
}

TEST(IsosurfaceMapperSettings, FrameDeadlineStopsTheFrameSaysSoOnceAndComputesItAgain)
{
  TubeScene full, cut;
  full.mapper->SetFrameDeadline(100.0); // far beyond this frame: no effect
  full.render();
  EXPECT_EQ(full.recorder->warnings.size(), 0u);
  EXPECT_GT(full.coveredPixels(), 1000u);
  // A deadline passed before the first iteration: nothing found, every pixel with work left.
  cut.mapper->SetFrameDeadline(1e-9);
  cut.render();
  const std::string said = "the frame stopped at its deadline (FrameDeadline 1e-09 s): ";
  EXPECT_EQ(cut.recorder->count(said), 1);
  EXPECT_EQ(cut.coveredPixels(), 0u);
  EXPECT_GE(cut.mapper->GetLastUnresolvedPixels(), vtkIdType(full.coveredPixels()));
  EXPECT_EQ(cut.recorder->count("pixels left unresolved at the"), 0) << "no cap was hit";
  // The same view again is computed again, not taken from the cut frame; said once only.
  cut.recorder->progress.clear();
  cut.render();
  EXPECT_FALSE(cut.recorder->progress.empty());
  EXPECT_EQ(cut.recorder->count(said), 1);
  // Without the deadline the frame is whole.
  cut.mapper->SetFrameDeadline(0);
  cut.render();
  EXPECT_EQ(cut.coveredPixels(), full.coveredPixels());
  EXPECT_EQ(cut.mapper->GetLastUnresolvedPixels(), 0);
}

TEST(IsosurfaceMapperSettings, DepthCapLeavesUnresolvedPixelsWarnedOnceAndReruns)
{
  TubeScene scene;
  scene.mapper->SetMaximumSubdivisionDepth(2);
  EXPECT_EQ(scene.mapper->GetMaximumSubdivisionDepth(), 2);
  scene.render();
  const vtkIdType shallow = scene.mapper->GetLastUnresolvedPixels();
  EXPECT_GT(shallow, 100) << "two levels below the input patches resolve no silhouette";
  EXPECT_EQ(scene.recorder->count("pixels left unresolved"), 1);
  EXPECT_EQ(scene.recorder->count("subdivision depth cap (MaximumSubdivisionDepth 2:"), 1);

  // Another camera: the engine runs again, still with unresolved pixels, and stays quiet.
  scene.recorder->progress.clear();
  scene.turn(4);
  scene.render();
  EXPECT_FALSE(scene.recorder->progress.empty()) << "the engine did not run again";
  EXPECT_GT(scene.mapper->GetLastUnresolvedPixels(), 100);
  EXPECT_EQ(scene.recorder->count("pixels left unresolved"), 1) << "warned on every frame";

  // The default depth: the engine runs again (the depth is part of the frame's key) and
  // resolves every pixel, covering more of them.
  const size_t shallowCovered = scene.coveredPixels();
  const double shallowTime = scene.mapper->GetLastEngineTime();
  scene.recorder->progress.clear();
  scene.mapper->SetMaximumSubdivisionDepth(22);
  scene.render();
  EXPECT_FALSE(scene.recorder->progress.empty()) << "a new depth did not re-run the engine";
  EXPECT_NE(scene.mapper->GetLastEngineTime(), shallowTime);
  EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
  EXPECT_GT(scene.coveredPixels(), shallowCovered);
  EXPECT_EQ(scene.recorder->count("pixels left unresolved"), 1);

  // The clamp, and a changed setting reports again.
  scene.mapper->SetMaximumSubdivisionDepth(99);
  EXPECT_EQ(scene.mapper->GetMaximumSubdivisionDepth(), 40);
  scene.mapper->SetMaximumSubdivisionDepth(2);
  scene.render();
  EXPECT_EQ(scene.recorder->count("pixels left unresolved"), 2);
}

/// The image takes its share of the budget first: 400 x 320 pixels at 365 bytes (the engine's
/// 325, the mapper's colour and depth on the host and as textures) need 45 MiB, so 16 MiB
/// draws nothing, said once, and 61 MiB leaves the engine 16.
TEST(IsosurfaceMapperSettings, TinyMemoryBudgetLeavesUnresolvedPixelsWarnedOnce)
{
  EXPECT_EQ(vtkIGAIsosurfaceMapper::GetImageBytes(1, 1), 325u + 40u);
  EXPECT_EQ(vtkIGAIsosurfaceMapper::GetImageBytes(400, 320), 400u * 320u * 365u);
  TubeScene scene(400, 320);
  scene.mapper->SetMemoryBudgetMB(1);
  EXPECT_EQ(scene.mapper->GetMemoryBudgetMB(), 16) << "clamped to 16 MiB";
  scene.render();
  EXPECT_EQ(scene.coveredPixels(), 0);
  ASSERT_EQ(scene.recorder->errors.size(), 1u);
  EXPECT_NE(scene.recorder->errors[0].find(
              "nothing drawn: a 400x320 image needs 45 MiB (365 bytes a pixel), more than the "
              "memory budget (MemoryBudgetMB 16): raise it or make the view smaller"),
    std::string::npos);
  EXPECT_STREQ(scene.mapper->GetLastRefusal(),
    "a 400x320 image needs 45 MiB (365 bytes a pixel), more than the memory budget "
    "(MemoryBudgetMB 16): raise it or make the view smaller");
  scene.turn(4);
  scene.render();
  EXPECT_EQ(scene.recorder->errors.size(), 1u) << "said once";

  scene.mapper->SetMemoryBudgetMB(61);
  scene.render();
  EXPECT_GT(scene.mapper->GetLastUnresolvedPixels(), 0);
  EXPECT_EQ(scene.recorder->count("at the memory budget (MemoryBudgetMB 61:"), 1);
  scene.turn(4);
  scene.render();
  EXPECT_GT(scene.mapper->GetLastUnresolvedPixels(), 0);
  EXPECT_EQ(scene.recorder->count("pixels left unresolved"), 1);
  // The default budget resolves them.
  scene.mapper->SetMemoryBudgetMB(4096);
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
}

TEST(IsosurfaceMapperSettings, MissingSurfaceArrayIsReportedOnce)
{
  TubeScene scene;
  scene.mapper->SetSurfaceArrayName("bogus");
  scene.render();
  scene.turn(4);
  scene.render();
  ASSERT_EQ(scene.recorder->errors.size(), 1u);
  EXPECT_NE(scene.recorder->errors[0].find("no point array named 'bogus'"), std::string::npos);
  EXPECT_EQ(scene.window->GetZbufferDataAtPoint(120, 100), 1.0f) << "nothing drawn";
  // Another bad name is a changed setting: reported too; a good one draws.
  scene.mapper->SetSurfaceArrayName("bogus2");
  scene.render();
  EXPECT_EQ(scene.recorder->errors.size(), 2u);
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.render();
  EXPECT_EQ(scene.recorder->errors.size(), 2u);
  EXPECT_GT(scene.coveredPixels(), 1000u);
}

// A refused render forgets the frame before it, so that what reads the mapper afterwards (the
// viewer's readout, an export) does not take the last good frame for this one.
TEST(IsosurfaceMapperSettings, ARefusedRenderSaysWhyAndForgetsTheFrameBeforeIt)
{
  TubeScene scene;
  scene.render();
  EXPECT_STREQ(scene.mapper->GetLastRefusal(), "");
  ASSERT_GT(scene.coveredPixels(), 1000u);
  ASSERT_GT(scene.mapper->GetLastEngineTime(), 0.0);

  scene.mapper->SetSurfaceArrayName("bogus");
  scene.render();
  EXPECT_STREQ(
    scene.mapper->GetLastRefusal(), "no point array named 'bogus' to draw isosurfaces of");
  EXPECT_EQ(scene.mapper->GetLastGBuffer().width, 0);
  EXPECT_EQ(scene.coveredPixels(), 0u);
  EXPECT_EQ(scene.mapper->GetLastEngineTime(), 0.0);

  // After a good frame, an input that cannot be drawn (a NaN control point) is refused each
  // render, said once.
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.render();
  ASSERT_STREQ(scene.mapper->GetLastRefusal(), "");
  ASSERT_GT(scene.coveredPixels(), 1000u);
  const size_t errorsBefore = scene.recorder->errors.size();
  auto bad = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  bad->GetPoints()->SetPoint(3, std::nan(""), 0, 0);
  scene.mapper->SetInputData(bad);
  for (int frame = 0; frame < 2; ++frame)
  {
    scene.turn(3);
    scene.render();
    EXPECT_NE(std::string(scene.mapper->GetLastRefusal()).find("cannot draw the input: "),
      std::string::npos)
      << scene.mapper->GetLastRefusal();
    EXPECT_EQ(scene.coveredPixels(), 0u);
  }
  EXPECT_EQ(scene.recorder->errors.size(), errorsBefore + 1);

  // No isovalue: nothing to draw, which is no refusal, and the frame before is forgotten too.
  scene.mapper->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5)));
  scene.render();
  ASSERT_GT(scene.coveredPixels(), 1000u);
  scene.mapper->SetNumberOfIsovalues(0);
  scene.render();
  EXPECT_STREQ(scene.mapper->GetLastRefusal(), "");
  EXPECT_EQ(scene.coveredPixels(), 0u);
  scene.mapper->SetIsovalue(0, 0.0);

  scene.mapper->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5)));
  scene.render();
  EXPECT_STREQ(scene.mapper->GetLastRefusal(), "");
  EXPECT_GT(scene.coveredPixels(), 1000u);
}

TEST(IsosurfaceMapperSettings, CUDABackendFallsBackToTheSameCPUImage)
{
  TubeScene cpu, cuda;
  cpu.mapper->SetBackendToCPU();
  EXPECT_EQ(cpu.mapper->GetBackend(), vtkIGAIsosurfaceMapper::BACKEND_CPU);
  cuda.mapper->SetBackendToCUDA();
  EXPECT_EQ(cuda.mapper->GetBackend(), vtkIGAIsosurfaceMapper::BACKEND_CUDA);
  cpu.render();
  cuda.render();
  if (std::string(cuda.mapper->GetLastBackend()) == "cuda")
  {
    GTEST_SKIP() << "a CUDA device drew the frame: there is no fallback to test here";
  }
  EXPECT_STREQ(cpu.mapper->GetLastBackend(), "cpu");
  EXPECT_STREQ(cpu.mapper->GetLastNotice(), "");
  EXPECT_STREQ(cuda.mapper->GetLastBackend(), "cpu");
  const std::string notice = cuda.mapper->GetLastNotice();
  EXPECT_EQ(notice.rfind("CUDA asked for, but ", 0), 0u) << notice;
  EXPECT_NE(notice.find("drawing on CPU threads"), std::string::npos) << notice;
  EXPECT_EQ(cuda.recorder->count(notice), 1);
  EXPECT_EQ(cpu.recorder->warnings.size(), 0u);
  // The same image, bit for bit.
  ASSERT_EQ(cpu.mapper->GetLastColours().size(), cuda.mapper->GetLastColours().size());
  EXPECT_TRUE(cpu.mapper->GetLastColours() == cuda.mapper->GetLastColours());
  int differ = 0;
  for (int j = 0; j < 200; ++j)
  {
    for (int i = 0; i < 240; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        differ += cpu.pixel(i, j)[c] != cuda.pixel(i, j)[c];
      }
    }
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(cuda.coveredPixels(), 1000u);

  // A second frame computed (another camera) does not repeat the notice.
  cuda.recorder->progress.clear();
  cuda.turn(4);
  cuda.render();
  EXPECT_FALSE(cuda.recorder->progress.empty());
  EXPECT_EQ(cuda.recorder->count(notice), 1);
  EXPECT_EQ(cuda.recorder->warnings.size(), 1u);

  // A new backend re-runs the engine; automatic is not warned about (a plain message).
  cpu.recorder->progress.clear();
  cpu.mapper->SetBackendToAutomatic();
  cpu.render();
  EXPECT_FALSE(cpu.recorder->progress.empty()) << "a new backend did not re-run the engine";
  EXPECT_STREQ(cpu.mapper->GetLastBackend(), "cpu");
  EXPECT_STRNE(cpu.mapper->GetLastNotice(), "");
  EXPECT_EQ(cpu.recorder->warnings.size(), 0u);
}

/// Without a GPU the automatic backend's notice is a plain message, once per process however
/// many mappers draw.
TEST(IsosurfaceMapperSettings, AutomaticFallbackIsNoticedOncePerProcess)
{
  vtkNew<Recorder> output;
  const unsigned long observer =
    vtkOutputWindow::GetInstance()->AddObserver(vtkCommand::TextEvent, output);
  TubeScene first, second;
  first.render();
  second.render();
  vtkOutputWindow::GetInstance()->RemoveObserver(observer);
  const std::string notice = first.mapper->GetLastNotice();
  if (notice.empty())
  {
    GTEST_SKIP() << "the automatic backend found a GPU: " << first.mapper->GetLastBackend();
  }
  EXPECT_STREQ(second.mapper->GetLastNotice(), notice.c_str());
  int shown = 0;
  for (const auto& text : output->texts)
  {
    shown += text.find(notice) != std::string::npos;
  }
  // Alone in its process (as ctest runs it) exactly once; after other tests at most once.
  const bool alone = ::testing::UnitTest::GetInstance()->test_to_run_count() == 1;
  EXPECT_EQ(shown, alone ? 1 : std::min(shown, 1));
  EXPECT_EQ(first.recorder->warnings.size() + second.recorder->warnings.size(), 0u);
}

TEST(IsosurfaceMapperSettings, LookupTableKeepsItsRangeWhenAskedTo)
{
  TubeScene scene;
  vtkProperty* property = scene.actor->GetProperty();
  property->SetAmbient(1); // the pixel is the table's colour
  property->SetDiffuse(0);
  property->SetSpecular(0);
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.667, 0.0);
  lut->SetRange(0.7, 0.9); // radius spans 0.5..1: both ends are clamped
  lut->Build();
  scene.mapper->SetLookupTable(lut);
  scene.mapper->SetScalarModeToUsePointFieldData();
  scene.mapper->SelectColorArray("radius");
  scene.mapper->ScalarVisibilityOn();
  scene.mapper->SetScalarRange(0.0, 2.0);
  scene.mapper->UseLookupTableScalarRangeOn();
  scene.render();
  EXPECT_EQ(lut->GetRange()[0], 0.7);
  EXPECT_EQ(lut->GetRange()[1], 0.9);

  // Every covered pixel shows the table's colour of the radius at its hit.
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  auto compare = [&](int& checked, int& wrong)
  {
    checked = wrong = 0;
    for (int j = 0; j < gbuffer.height; j += 3)
    {
      for (int i = 0; i < gbuffer.width; i += 3)
      {
        const auto* hit = gbuffer.firstHit(i, j);
        if (!hit)
        {
          continue;
        }
        const unsigned char* expected = lut->MapValue(hit->color);
        for (int c = 0; c < 3; ++c)
        {
          wrong += std::abs(int(scene.pixel(i, j)[c]) - int(expected[c])) > 1;
        }
        ++checked;
      }
    }
  };
  int checked, wrong;
  compare(checked, wrong);
  EXPECT_GT(checked, 100);
  EXPECT_EQ(wrong, 0);
  // The low end of the table (blue) and its high end (red) are both on screen.
  int blue = 0, red = 0;
  for (int j = 0; j < gbuffer.height; ++j)
  {
    for (int i = 0; i < gbuffer.width; ++i)
    {
      const unsigned char* p = scene.pixel(i, j);
      blue += p[2] > 200 && p[0] < 30;
      red += p[0] > 200 && p[2] < 30;
    }
  }
  EXPECT_GT(blue, 50);
  EXPECT_GT(red, 50);

  // Off (vtkMapper's default): the mapper's ScalarRange replaces the table's range.
  scene.mapper->UseLookupTableScalarRangeOff();
  scene.render();
  EXPECT_EQ(lut->GetRange()[0], 0.0);
  EXPECT_EQ(lut->GetRange()[1], 2.0);
  compare(checked, wrong);
  EXPECT_EQ(wrong, 0);
}

} // namespace
