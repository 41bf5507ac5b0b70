// vtkIGAIsosurfaceMapper drawing CSG solids and slices (DRAW_CSG): the dice's hits lie on the
// cube outside the pips or on a pip inside the cube while the dice twists; a capped clip and a
// slice of the tube; the twisting dice's .pvd series drawn like the deformation it was written
// from; bad expressions; regression images.
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGABezierSeriesReader.h"
#include "vtkIGABezierSeriesWriter.h"
#include "vtkIGAIsosurfaceMapper.h"
#include "vtkIGASyntheticDeformation.h"

#include "vtkActor.h"
#include "vtkCommand.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkRenderWindow.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace
{

struct CsgScene : igatest::MapperScene
{
  CsgScene()
    : MapperScene(240, 200)
  {
    mapper->SetDrawModeToCsg();
  }

  iga::sst::GBuffer draw(vtkDataObject* input)
  {
    mapper->SetInputData(input);
    window->Render();
    return mapper->GetLastGBuffer();
  }
};

/// Attributes `a` and `b` of the set at a hit's patch and parameter (the material's: a
/// deformation moves the points, not the attributes).
std::array<double, 2> attributesAt(const iga::VolumeSet<double>& set, const iga::sst::Hit& hit)
{
  const auto view = set.patches[size_t(hit.patch)].view();
  std::vector<double> values(size_t(view.channels));
  iga::evaluateHomogeneous<double, 3>(view, &hit.uvw[0], values.data(), nullptr);
  const double w = values[iga::kWeightChannel];
  return { values[iga::kFirstAttributeChannel] / w, values[iga::kFirstAttributeChannel + 1] / w };
}

/// A solid minus its holes ("A<0 - B<0" of the set's two attributes) deformed over time by
/// `deformation`: every first hit lies on the solid's surface outside every hole (operand 0) or
/// on a hole inside the solid (operand 1), so a hole never leaks out of the solid nor is covered
/// by it, and each pixel lies on one surface: the creases are pixel-exact. At least `solid` and
/// `holes` pixels of each; the last frame against the baseline `name`.
void expectSolidMinusHoles(CsgScene& scene, const iga::VolumeSet<double>& set,
  vtkIGASyntheticDeformation* deformation, int solid, int holes, const std::string& name)
{
  scene.mapper->SetCsgExpression(
    (set.attributeNames[0] + "<0 - " + set.attributeNames[1] + "<0").c_str());
  deformation->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(set));
  for (double time : { 0.0, 0.5, 1.0 })
  {
    deformation->SetTime(time);
    deformation->Update();
    auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
    grid->ShallowCopy(deformation->GetOutput());
    const iga::sst::GBuffer gbuffer = scene.draw(grid);
    int onSolid = 0, onHole = 0;
    for (int j = 0; j < gbuffer.height; ++j)
      for (int i = 0; i < gbuffer.width; ++i)
      {
        const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
        if (!hit)
          continue;
        ASSERT_TRUE(hit->entersBelow);
        const auto [outside, hole] = attributesAt(set, *hit);
        if (hit->isovalue == 0)
        {
          EXPECT_LT(std::abs(outside), 1e-5) << "pixel " << i << "," << j;
          EXPECT_GT(hole, -1e-5) << "pixel " << i << "," << j;
          ++onSolid;
        }
        else
        {
          ASSERT_EQ(hit->isovalue, 1);
          EXPECT_LT(std::abs(hole), 1e-5) << "pixel " << i << "," << j;
          EXPECT_LT(outside, 1e-5) << "pixel " << i << "," << j;
          ++onHole;
        }
      }
    EXPECT_GT(onSolid, solid) << "time " << time;
    EXPECT_GT(onHole, holes) << "time " << time;
  }
  igatest::compareWithBaseline(scene.window, name);
}

TEST(CsgMapper, TwistingDiceShowsItsCubeAndPipsAndNothingElse)
{
  CsgScene scene;
  scene.look(3.2, -4.4, 3.6, 0, 0, 0);
  vtkNew<vtkIGASyntheticDeformation> twist;
  twist->SetAxis(2);
  twist->SetAmount(1.2);
  expectSolidMinusHoles(scene, iga::makeDice<double>(), twist, 8000, 800, "MapperTwistedDiceCsg");
}

TEST(CsgMapper, TwistingDiceSeriesDrawsLikeTheDeformationItWasWrittenFrom)
{
  CsgScene scene;
  scene.look(3.2, -4.4, 3.6, 0, 0, 0);
  scene.mapper->SetCsgExpression("cube<0 - pips<0");
  vtkNew<vtkIGASyntheticDeformation> twist;
  twist->SetAxis(2);
  twist->SetAmount(1.2);
  twist->SetNumberOfTimeSteps(3);
  twist->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeDice<double>()));
  const std::string pvd = testing::TempDir() + "/igaview_dice_series.pvd";
  vtkNew<vtkIGABezierSeriesWriter> writer;
  writer->SetFileName(pvd.c_str());
  writer->SetInputConnection(twist->GetOutputPort());
  ASSERT_EQ(writer->Write(), 1);
  vtkNew<vtkIGABezierSeriesReader> reader;
  reader->SetFileName(pvd.c_str());
  for (double time : { 0.0, 0.5, 1.0 })
  {
    twist->UpdateTimeStep(time);
    auto deformed = vtkSmartPointer<vtkUnstructuredGrid>::New();
    deformed->ShallowCopy(twist->GetOutput());
    const iga::sst::GBuffer expected = scene.draw(deformed);
    // The mapper draws the reader's output at the time the pipeline asks for.
    scene.mapper->SetInputConnection(reader->GetOutputPort());
    reader->UpdateTimeStep(time);
    scene.window->Render();
    const iga::sst::GBuffer& drawn = scene.mapper->GetLastGBuffer();
    ASSERT_EQ(drawn.hits.size(), expected.hits.size()) << "time " << time;
    EXPECT_GT(drawn.coveredPixels(), 8000u);
    double worst = 0;
    for (size_t h = 0; h < drawn.hits.size(); ++h)
    {
      EXPECT_EQ(drawn.hits[h].isovalue, expected.hits[h].isovalue);
      worst = std::max(worst, glm::length(drawn.hits[h].position - expected.hits[h].position));
    }
    EXPECT_EQ(worst, 0.0) << "time " << time << ": binary XML keeps the control points exactly";
  }
  // The last frame is the twisting dice's regression image at time 1.
  igatest::compareWithBaseline(scene.window, "MapperTwistedDiceCsg");
}

TEST(CsgMapper, BendingCheeseShowsItsBlockAndHolesAndNothingElse)
{
  CsgScene scene;
  scene.look(3.0, -3.2, 2.6, 1.0, 0.6, 0.5);
  vtkNew<vtkIGASyntheticDeformation> bend;
  bend->SetModeToBend();
  bend->SetAxis(0);
  bend->SetAmount(0.25);
  expectSolidMinusHoles(scene, iga::makeCheese<double>(), bend, 6000, 300, "MapperBentCheeseCsg");
}

TEST(CsgMapper, TubeCutOpenWithASliceColouredByTemperature)
{
  CsgScene scene;
  scene.look(2.6, -3.4, 3.0, 0, 0, 1);
  scene.mapper->SetCsgExpression("domain & plane(0, 1, 0, -0.1)");
  scene.mapper->SetSlice(0, 1, 0, 0, 0.2);
  scene.mapper->SetScalarModeToUsePointFieldData();
  scene.mapper->SelectColorArray("temperature");
  scene.mapper->SetScalarRange(-1.2, 1.2);
  scene.mapper->ScalarVisibilityOn();
  // The patches as the mapper reads them (the grid holds them right-handed).
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  vtkIGABezierHexahedra::Patches read;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, read, error, warnings)) << error;
  const auto& tube = read.volumes;
  const iga::sst::GBuffer gbuffer = scene.draw(grid);
  int caps = 0, slices = 0;
  for (const auto& hit : gbuffer.hits)
  {
    if (hit.isovalue < 2)
    {
      EXPECT_GE(hit.position[1], 0.1 - 1e-9) << "the half-space y >= 0.1 is kept";
    }
    EXPECT_NEAR(hit.color, attributesAt(tube, hit)[0], 1e-9) << "coloured by temperature";
    caps += hit.isovalue == 1 ? 1 : 0;
    slices += hit.isovalue == 2 ? 1 : 0; // after the expression's two operands
  }
  EXPECT_GT(caps, 300) << "the cut face";
  EXPECT_GT(slices, 300);
  igatest::compareWithBaseline(scene.window, "MapperTubeCutOpenWithSlice");
}

TEST(CsgMapper, OverlappingBlocksAreSolidsOfTheirOwn)
{
  // Two Marsden spheres (boxes [-1.5, 1.5]^3 holding the unit ball's field), the second moved by
  // 1.2 in x: the boxes and the balls overlap. Each block is closed by its own boundary, so the
  // union of the balls has only their outer surfaces, and the union of the boxes only theirs.
  auto moved = iga::makeMarsdenSphere<double>(2);
  for (auto& patch : moved.patches)
    for (int p = 0; p < patch.view().pointCount(); ++p)
      patch.view().point(p)[0] += 1.2 * patch.view().point(p)[iga::kWeightChannel];
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeMarsdenSphere<double>(2)));
  blocks->SetBlock(1, vtkIGABezierHexahedra::ToUnstructuredGrid(moved));
  CsgScene scene;
  scene.look(2.0, -7.0, 3.0, 0.6, 0, 0);
  scene.mapper->SetCsgExpression("sphere<0");
  scene.mapper->AllLayersOn(); // every layer checked, not only the nearest
  scene.mapper->SetInputData(blocks);
  scene.window->Render();
  const glm::dvec3 centres[2] = { { 0, 0, 0 }, { 1.2, 0, 0 } };
  int balls[2] = { 0, 0 };
  for (const auto& hit : scene.mapper->GetLastGBuffer().hits)
  {
    const double r0 = glm::length(hit.position - centres[0]),
                 r1 = glm::length(hit.position - centres[1]);
    const int on = std::abs(r0 - 1) < std::abs(r1 - 1) ? 0 : 1;
    EXPECT_NEAR(on == 0 ? r0 : r1, 1, 1e-6) << "on a ball";
    EXPECT_GE(on == 0 ? r1 : r0, 1 - 1e-6) << "outside the other ball";
    EXPECT_EQ(hit.patch >= 1, on == 1) << "the block's patch (one patch a block)";
    ++balls[on];
  }
  EXPECT_GT(balls[0], 1000);
  EXPECT_GT(balls[1], 1000);
  scene.mapper->SetCsgExpression("domain");
  scene.window->Render();
  int faces = 0;
  for (const auto& hit : scene.mapper->GetLastGBuffer().hits)
  {
    // On the union's outside: a box's face, not inside the other box.
    const glm::dvec3 local[2] = { hit.position - centres[0], hit.position - centres[1] };
    auto inside = [](const glm::dvec3& x) {
      return std::max({ std::abs(x[0]), std::abs(x[1]), std::abs(x[2]) }) < 1.5 - 1e-6;
    };
    EXPECT_FALSE(inside(local[0]) || inside(local[1])) << "inside a box at " << hit.position[0];
    ++faces;
  }
  EXPECT_GT(faces, 5000);
}

TEST(CsgMapper, AllLayersFillTheGBufferAndDrawTheSameImage)
{
  CsgScene scene;
  scene.look(2.6, -3.4, 3.0, 0, 0, 1);
  scene.mapper->SetCsgExpression("domain - radius<0.8");
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  const iga::sst::GBuffer first = scene.draw(grid);
  const std::vector<float> colours = scene.mapper->GetLastColours();
  scene.mapper->AllLayersOn();
  scene.window->Render();
  const iga::sst::GBuffer& all = scene.mapper->GetLastGBuffer();
  EXPECT_EQ(all.coveredPixels(), first.coveredPixels());
  EXPECT_GT(all.hits.size(), 2 * first.hits.size()) << "the tube's walls, each entered and left";
  for (int j = 0; j < all.height; ++j)
    for (int i = 0; i < all.width; ++i)
      if (first.firstHit(i, j))
      {
        // The same root, though Newton may reach it from other nodes' starts: equal to rounding.
        ASSERT_NEAR(all.firstHit(i, j)->eyeDepth, first.firstHit(i, j)->eyeDepth,
          1e-12 * first.firstHit(i, j)->eyeDepth);
      }
  EXPECT_EQ(scene.mapper->GetLastColours(), colours) << "an opaque surface shows its first layer";
}

TEST(CsgMapper, CappedClipIsTheCutSolidWithTheSlicesCut)
{
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  // The capped clip y >= 0.1 of the volumes, and a slice x = -0.2 across both halves.
  auto draw = [&](const char* expression, bool cappedClip, bool clippingPlane)
  {
    CsgScene scene;
    scene.look(2.6, -3.4, 3.0, 0, 0, 1);
    scene.mapper->SetCsgExpression(expression);
    scene.mapper->SetSlice(0, 1, 0, 0, 0.2);
    if (cappedClip)
      scene.mapper->SetCappedClip(0, 0, 1, 0, -0.1);
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(0, 0.1, 0);
    plane->SetNormal(0, 1, 0);
    if (clippingPlane)
      scene.mapper->AddClippingPlane(plane);
    return scene.draw(grid);
  };
  const iga::sst::GBuffer capped = draw("", true, false);
  // The same by hand: the cut solid typed out, the half-space as a clipping plane.
  const iga::sst::GBuffer byHand = draw("domain & plane(0, 1, 0, -0.1)", false, true);
  ASSERT_EQ(capped.hits.size(), byHand.hits.size());
  int caps = 0;
  for (size_t h = 0; h < capped.hits.size(); ++h)
  {
    EXPECT_EQ(capped.hits[h].isovalue, byHand.hits[h].isovalue);
    EXPECT_LT(glm::length(capped.hits[h].position - byHand.hits[h].position), 1e-12);
    EXPECT_GE(capped.hits[h].position[1], 0.1 - 1e-9) << "the half-space y >= 0.1 is kept";
    caps += capped.hits[h].isovalue == 1 ? 1 : 0;
  }
  EXPECT_GT(caps, 300) << "the cut face";
  // Without the clipping plane the slice shows on the cut-away side too.
  const iga::sst::GBuffer uncutSlice = draw("domain & plane(0, 1, 0, -0.1)", false, false);
  EXPECT_GT(uncutSlice.coveredPixels(), capped.coveredPixels() + 100);
}

TEST(CsgMapper, ACappedClipWithoutNormalIsRefused)
{
  CsgScene scene;
  vtkNew<vtkTest::ErrorObserver> errors;
  scene.mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  scene.mapper->SetCappedClip(0, 0, 0, 0, 1);
  ASSERT_TRUE(errors->GetError());
  EXPECT_NE(errors->GetErrorMessage().find("capped clip 0: the normal (a, b, c) is zero"),
    std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_EQ(scene.mapper->GetNumberOfCappedClips(), 0);
}

TEST(CsgMapper, BadExpressionsAreSaidOnceAndTheLastGoodOneKept)
{
  CsgScene scene;
  scene.look(2.6, -3.4, 3.0, 0, 0, 1);
  scene.mapper->SetCsgExpression("radius<0.8");
  vtkNew<vtkTest::ErrorObserver> errors;
  scene.mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  const iga::sst::GBuffer before = scene.draw(grid);
  ASSERT_GT(before.coveredPixels(), 3000u);
  scene.mapper->SetCsgExpression("radius<0.8 & (");
  ASSERT_TRUE(errors->GetError());
  EXPECT_NE(errors->GetErrorMessage().find("expression ends where an operand or '(' is expected "
                                           "at position 14; the previous one is kept"),
    std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_STREQ(scene.mapper->GetCsgExpression(), "radius<0.8");
  errors->Clear();
  scene.window->Render();
  EXPECT_EQ(scene.mapper->GetLastGBuffer().hits.size(), before.hits.size()) << "the same image";
  // An attribute the data lack is said when drawing, once.
  scene.mapper->SetCsgExpression("domain - heat>0");
  scene.window->Render();
  EXPECT_NE(errors->GetErrorMessage().find("no input has the attribute 'heat' at position 9"),
    std::string::npos)
    << errors->GetErrorMessage();
  errors->Clear();
  scene.window->Render();
  EXPECT_FALSE(errors->GetError()) << "said once";
  // Quadrilaterals alone bound no solid: said, not drawn.
  vtkNew<vtkTest::ErrorObserver> warnings;
  scene.mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  scene.draw(vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTeapot<double>()));
  EXPECT_NE(
    warnings->GetWarningMessage().find("DRAW_CSG draws solids of hexahedra"), std::string::npos)
    << warnings->GetWarningMessage();
}

} // namespace
