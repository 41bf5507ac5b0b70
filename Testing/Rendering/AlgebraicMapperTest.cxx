// Algebraic surfaces through the VTK pipeline: vtkIGAAlgebraicSource's volume drawn by the
// mapper, which takes the ray-composition path for it (affine geometry) and the tree for curved
// patches; hits on the surface (|f| / K, Reimers and Seland's metric), the same hits as the
// tree's, every root finder by name, and a clear error where ray composition is forced on
// curved patches.
#include "RenderingTestUtilities.h"
#include "vtkIGAAlgebraicSource.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "iga/AlgebraicGallery.h"
#include "iga/BernsteinRoots.h"
#include "iga/Datasets.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Engine.h"
#include "iga/sst/Supersampling.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{

struct AlgebraicScene : igatest::MapperScene
{
  vtkNew<vtkIGAAlgebraicSource> source;
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;

  explicit AlgebraicScene(const char* surface)
    : MapperScene(120, 120)
  {
    source->SetGallerySurfaceByName(surface);
    mapper->SetInputConnection(source->GetOutputPort());
    mapper->SetSurfaceArrayName("f");
    mapper->SetIsovalue(0, 0.0);
    mapper->SetNumberOfThreads(2);
    onError->SetClientData(&errors);
    onError->SetCallback(
      [](vtkObject*, unsigned long, void* client, void* call) {
        static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call));
      });
    mapper->AddObserver(vtkCommand::ErrorEvent, onError);
    const double* box = iga::findAlgebraicSurface(surface)->box;
    const double centre[3] = { (box[0] + box[1]) / 2, (box[2] + box[3]) / 2,
      (box[4] + box[5]) / 2 };
    const double size = box[1] - box[0];
    look(centre[0] - 1.6 * size, centre[1] - 2.0 * size, centre[2] + 1.2 * size, centre[0],
      centre[1], centre[2]);
  }

  iga::sst::GBuffer draw()
  {
    window->Render();
    return mapper->GetLastGBuffer();
  }

  /// K: the largest Bernstein coefficient of f.
  double largestCoefficient()
  {
    source->Update();
    double range[2];
    source->GetOutput()->GetPointData()->GetArray("f")->GetRange(range);
    return std::max(std::fabs(range[0]), std::fabs(range[1]));
  }
};

TEST(AlgebraicMapper, GallerySurfacesTakeRayCompositionAndAgreeWithTheTree)
{
  for (const char* name : { "sphere", "tangle" })
  {
    SCOPED_TRACE(name);
    AlgebraicScene scene(name);
    const auto f = iga::parsePolynomial(iga::findAlgebraicSurface(name)->expression);
    const iga::sst::GBuffer composed = scene.draw();
    EXPECT_EQ(scene.mapper->GetLastRayCompositionPatches(), 1);
    EXPECT_EQ(scene.mapper->GetLastSstPatches(), 0);
    EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
    ASSERT_GT(composed.coveredPixels(), 2000u);
    const double largest = scene.largestCoefficient();
    for (const auto& hit : composed.hits)
    {
      EXPECT_LT(
        std::fabs(f.evaluate(hit.position.x, hit.position.y, hit.position.z)) / largest, 1e-9);
      if (std::string(name) == "sphere")
      {
        EXPECT_NEAR(glm::length(hit.position), 1.0, 1e-9);
      }
    }
    scene.mapper->SetMethodToSharedSubdivisionTree();
    const iga::sst::GBuffer tree = scene.draw();
    EXPECT_EQ(scene.mapper->GetLastRayCompositionPatches(), 0);
    EXPECT_EQ(scene.mapper->GetLastSstPatches(), 1);
    // The same first hits, to 1e-6, but for pixels grazing the silhouette (the tree and ray
    // composition decide a tangent ray's touch differently).
    size_t differing = 0;
    for (int j = 0; j < composed.height; ++j)
      for (int i = 0; i < composed.width; ++i)
      {
        const auto* a = composed.firstHit(i, j);
        const auto* b = tree.firstHit(i, j);
        differing += (!a != !b) || (a && b && glm::length(a->position - b->position) > 1e-6);
      }
    EXPECT_LE(differing, composed.coveredPixels() / 200);
    EXPECT_TRUE(scene.errors.empty());
  }
}

TEST(AlgebraicMapper, EveryRootFinderByNameDrawsTheSameSurface)
{
  AlgebraicScene scene("tangle");
  const iga::sst::GBuffer reference = scene.draw();
  for (int f = 0; f < iga::kRootFinderCount; ++f)
  {
    const char* name = iga::rootFinderName(iga::RootFinder(f));
    scene.mapper->SetRootFinderByName(name);
    EXPECT_EQ(scene.mapper->GetRootFinder(), f) << name;
    const iga::sst::GBuffer composed = scene.draw();
    ASSERT_EQ(composed.offsets, reference.offsets) << name;
    for (size_t h = 0; h < composed.hits.size(); ++h)
      EXPECT_LT(glm::length(composed.hits[h].position - reference.hits[h].position), 1e-9) << name;
  }
  scene.mapper->SetRootFinderByName("secant");
  ASSERT_EQ(scene.errors.size(), 1u);
  EXPECT_NE(scene.errors[0].find("root finder 'secant' is none of"), std::string::npos)
    << scene.errors[0];
  EXPECT_EQ(scene.mapper->GetRootFinder(), vtkIGAIsosurfaceMapper::ROOT_FINDER_POLAR_NEWTON);
}

/// With frame coherency a camera turned by a degree is drawn from the frame before's hits: most
/// rays seeded, and the cold frame's G-buffer (positions within 1e-9).
TEST(AlgebraicMapper, FrameCoherencySeedsACameraMoveAndKeepsTheImage)
{
  const auto drawTurned = [](bool coherent, vtkIdType& seeded)
  {
    AlgebraicScene scene("kummer");
    scene.mapper->SetFrameCoherency(coherent);
    scene.draw();
    scene.renderer->GetActiveCamera()->Azimuth(1);
    const iga::sst::GBuffer turned = scene.draw();
    seeded = scene.mapper->GetLastSeededRays();
    EXPECT_TRUE(scene.errors.empty());
    return turned;
  };
  vtkIdType coldSeeded = 0, seeded = 0;
  const iga::sst::GBuffer cold = drawTurned(false, coldSeeded);
  const iga::sst::GBuffer coherent = drawTurned(true, seeded);
  EXPECT_EQ(coldSeeded, 0);
  EXPECT_GT(size_t(seeded), cold.coveredPixels() / 2);
  ASSERT_GT(cold.coveredPixels(), 2000u);
  ASSERT_EQ(coherent.offsets, cold.offsets);
  for (size_t h = 0; h < cold.hits.size(); ++h)
    EXPECT_LT(glm::length(coherent.hits[h].position - cold.hits[h].position), 1e-9) << h;
}

TEST(AlgebraicMapper, CurvedPatchesTakeTheTreeAndForcedRayCompositionIsRefused)
{
  igatest::MapperScene scene(120, 100);
  scene.mapper->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5)));
  scene.mapper->SetSurfaceArrayName("temperature");
  scene.mapper->SetIsovalue(0, 0.0);
  scene.look(2.4, -3.0, 2.6, 0.2, 0.0, 1.0);
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call)); });
  scene.mapper->AddObserver(vtkCommand::ErrorEvent, onError);
  scene.window->Render();
  EXPECT_EQ(scene.mapper->GetLastSstPatches(), 8);
  EXPECT_EQ(scene.mapper->GetLastRayCompositionPatches(), 0);
  EXPECT_GT(scene.mapper->GetLastGBuffer().coveredPixels(), 1000u);
  scene.mapper->SetMethodToRayComposition();
  scene.window->Render();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("ray composition needs affine geometry"), std::string::npos)
    << errors[0];
  EXPECT_NE(errors[0].find("patch 0 has not"), std::string::npos) << errors[0];
}

TEST(AlgebraicMapper, ColoursByTheIsosurfacesCurvatureInWorldCoordinates)
{
  // The tube's radius = 0.75 at rest is a cylinder on rational patches: mean 1 / 1.5,
  // Gaussian 0; scaled by the actor's matrix to radius 1.5, mean 1 / 3.
  igatest::MapperScene scene(120, 100);
  scene.mapper->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.0)));
  scene.mapper->SetSurfaceArrayName("radius");
  scene.mapper->SetIsovalue(0, 0.75);
  scene.mapper->SetScalarModeToUsePointFieldData();
  scene.mapper->ScalarVisibilityOn();
  scene.mapper->SelectColorArray("curvature_mean");
  scene.mapper->SetScalarRange(0, 1);
  scene.look(3.0, -2.5, 2.2, 0, 0, 1);
  const auto expectColours = [&](double expected, const char* what)
  {
    scene.window->Render();
    const auto& hits = scene.mapper->GetLastGBuffer().hits;
    ASSERT_GT(hits.size(), 1000u) << what;
    for (const auto& hit : hits)
      ASSERT_NEAR(hit.color, expected, 1e-9) << what;
  };
  expectColours(1 / 1.5, "mean");
  scene.mapper->SelectColorArray("curvature_gauss");
  expectColours(0.0, "Gaussian");
  scene.mapper->SelectColorArray("curvature_mean");
  scene.actor->SetScale(2.0);
  scene.look(6.0, -5.0, 4.4, 0, 0, 2);
  expectColours(1 / 3.0, "mean, scaled by 2");
}

/// Antialiasing: the pixels whose colour differs from a neighbour's take their four samples'
/// mean, the rest keep theirs; unlit in one colour (the unit sphere's mean curvature 1 through
/// the table), a supersampled pixel is that colour times its coverage, and the window shows it
/// blended over the background in that proportion.
TEST(AlgebraicMapper, AntialiasingBlendsSilhouettePixelsByTheirCoverage)
{
  AlgebraicScene scene("sphere");
  scene.mapper->SetScalarModeToUsePointFieldData();
  scene.mapper->ScalarVisibilityOn();
  scene.mapper->SelectColorArray("curvature_mean");
  scene.mapper->SetScalarRange(0, 2);
  scene.actor->GetProperty()->LightingOff();
  const iga::sst::GBuffer aliased = scene.draw();
  const std::vector<float> before = scene.mapper->GetLastColours();
  EXPECT_EQ(scene.mapper->GetLastAntialiasedPixels(), 0);
  scene.mapper->AntialiasingOn();
  const vtkSmartPointer<vtkImageData> shown = igatest::renderAndGrab(scene.window);
  const iga::sst::GBuffer smoothed = scene.mapper->GetLastGBuffer();
  const std::vector<float>& after = scene.mapper->GetLastColours();
  ASSERT_EQ(smoothed.offsets, aliased.offsets); // the G-buffer stays the centres'
  const auto mask = iga::sst::contrastingPixels(before, 120, 120, 0.1f);
  const size_t marked = size_t(std::count(mask.begin(), mask.end(), 1));
  EXPECT_EQ(scene.mapper->GetLastAntialiasedPixels(), vtkIdType(marked));
  ASSERT_GT(marked, 150u);
  const float* colour = nullptr; // an inner pixel's
  for (size_t p = 0; p < mask.size() && !colour; ++p)
    colour = !mask[p] && before[4 * p + 3] > 0 ? &before[4 * p] : nullptr;
  ASSERT_NE(colour, nullptr);
  double background[3];
  scene.renderer->GetBackground(background);
  size_t partial = 0;
  for (size_t p = 0; p < mask.size(); ++p)
  {
    const float* rgba = &after[4 * p];
    if (!mask[p])
    {
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(rgba[c], before[4 * p + c]) << p;
      continue;
    }
    const float alpha = rgba[3];
    EXPECT_NEAR(4 * alpha, std::round(4 * alpha), 1e-5) << p;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(rgba[c], alpha * colour[c], 1e-5) << p;
    if (alpha > 0 && alpha < 1)
    {
      ++partial;
      const auto* pixel =
        static_cast<unsigned char*>(shown->GetScalarPointer(int(p % 120), int(p / 120), 0));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(pixel[c], 255 * (rgba[c] + (1 - alpha) * background[c]), 2.0) << p;
    }
  }
  EXPECT_GT(partial, marked / 4); // both sides of the edge are marked, one often whole
  EXPECT_TRUE(scene.errors.empty());
}

} // namespace
