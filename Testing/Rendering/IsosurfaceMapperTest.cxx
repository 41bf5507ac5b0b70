// vtkIGAIsosurfaceMapper in a real render window: its depth equals VTK's projection of the
// analytic hit, and it occludes and is occluded by ordinary actors exactly where each is in front.
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "iga/sst/Engine.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropPicker.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Camera.h"
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace
{

struct Scene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkIGAIsosurfaceMapper> mapper;
  vtkNew<vtkActor> isosurface;
  vtkSmartPointer<vtkImageData> image;

  Scene()
  {
    window->SetOffScreenRendering(1);
    window->SetSize(200, 160);
    window->AddRenderer(renderer);
    renderer->SetBackground(0, 0, 0);
    mapper->SetInputData(
      vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeMarsdenSphere<double>(2)));
    mapper->SetIsovalue(0, 0.0);
    isosurface->SetMapper(mapper);
    isosurface->GetProperty()->SetColor(1, 0, 0);
    renderer->AddActor(isosurface);
    igatest::lookAtTheOriginFromMinusY(renderer->GetActiveCamera());
  }

  void addSphere(double x, double y, double z, double radius)
  {
    vtkNew<vtkActor> actor;
    actor->SetMapper(igatest::sphereMapper(x, y, z, radius));
    actor->GetProperty()->SetColor(0, 1, 0);
    actor->GetProperty()->SetAmbient(1);
    actor->GetProperty()->SetDiffuse(0);
    renderer->AddActor(actor);
  }

  void render() { image = igatest::renderAndGrab(window); }

  /// Display coordinates (pixel centre) and VTK's window depth of a world point.
  void display(const double* world, int& i, int& j, double& depth)
  {
    renderer->SetWorldPoint(world[0], world[1], world[2], 1);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    i = int(std::floor(d[0]));
    j = int(std::floor(d[1]));
    depth = d[2];
  }

  const unsigned char* pixel(int i, int j)
  {
    return static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
  }
};

TEST(IsosurfaceMapper, DepthMatchesVTKsProjectionOfTheAnalyticHit)
{
  Scene scene;
  scene.render();
  // Rays through a few pixels: analytic first hit with the unit sphere, projected by VTK.
  int checked = 0;
  for (const auto& target : { std::array<double, 3>{ 0, -1, 0 },
         std::array<double, 3>{ 0.5, -0.7, 0.3 }, std::array<double, 3>{ -0.6, -0.6, -0.4 } })
  {
    int i, j;
    double ignored;
    scene.display(target.data(), i, j, ignored);
    // The pixel centre's ray, from VTK's inverse projection.
    double nearPoint[4], farPoint[4];
    scene.renderer->SetDisplayPoint(i + 0.5, j + 0.5, 0);
    scene.renderer->DisplayToWorld();
    scene.renderer->GetWorldPoint(nearPoint);
    scene.renderer->SetDisplayPoint(i + 0.5, j + 0.5, 1);
    scene.renderer->DisplayToWorld();
    scene.renderer->GetWorldPoint(farPoint);
    const glm::dvec3 o = glm::make_vec3(nearPoint) / nearPoint[3];
    const glm::dvec3 d = glm::make_vec3(farPoint) / farPoint[3] - o;
    const double a = glm::dot(d, d), b = 2 * glm::dot(o, d), c = glm::dot(o, o) - 1;
    const double t = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
    const double hit[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
    int hi, hj;
    double expected;
    scene.display(hit, hi, hj, expected);
    ASSERT_EQ(hi, i);
    ASSERT_EQ(hj, j);
    const double depth = scene.window->GetZbufferDataAtPoint(i, j);
    EXPECT_NEAR(depth, expected, 2e-6) << "pixel " << i << "," << j;
    EXPECT_GT(scene.pixel(i, j)[0], 40) << "the isosurface is red";
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // Nothing is drawn outside the sphere: the depth buffer keeps its clear value.
  EXPECT_EQ(scene.window->GetZbufferDataAtPoint(3, 3), 1.0f);
}

TEST(IsosurfaceMapper, OccludesAndIsOccludedByOrdinaryActors)
{
  Scene scene;
  // In front of the isosurface: its near cap pokes out towards the camera.
  scene.addSphere(0, -1.0, 0, 0.25);
  // Inside the isosurface: hidden.
  scene.addSphere(0.55, 0, 0.2, 0.3);
  scene.render();
  const double front[3] = { 0, -1.2, 0 }, inside[3] = { 0.55, -0.3, 0.2 };
  int i, j;
  double depth;
  scene.display(front, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[1], 200) << "the sphere in front is green";
  EXPECT_LT(scene.pixel(i, j)[0], 30);
  scene.display(inside, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[0], 40) << "the isosurface hides the inner sphere";
  EXPECT_LT(scene.pixel(i, j)[1], 30);
  // Next to the front sphere's rim the isosurface is in front again.
  const double beside[3] = { 0.35, -0.93, 0 };
  scene.display(beside, i, j, depth);
  EXPECT_GT(scene.pixel(i, j)[0], 40);
  EXPECT_LT(scene.pixel(i, j)[1], 30);
}

/// A half-opaque red isosurface in front of an opaque green sphere, through VTK's default
/// translucent pass (its order-independent translucency hooks into the mapper's shader).
TEST(IsosurfaceMapper, TranslucentSurfaceBlendsOverWhatIsBehind)
{
  Scene scene;
  scene.addSphere(0.55, 0, 0.2, 0.3); // inside the isosurface
  scene.isosurface->GetProperty()->SetOpacity(0.5);
  scene.isosurface->GetProperty()->SetAmbient(1);
  scene.isosurface->GetProperty()->SetDiffuse(0);
  scene.isosurface->GetProperty()->SetSpecular(0);
  scene.render();
  const double inside[3] = { 0.55, -0.3, 0.2 }, elsewhere[3] = { -0.5, -0.8, -0.2 };
  int i, j;
  double depth;
  scene.display(inside, i, j, depth);
  // Half red surface over the full green sphere.
  EXPECT_NEAR(scene.pixel(i, j)[0], 128, 4);
  EXPECT_NEAR(scene.pixel(i, j)[1], 128, 4);
  scene.display(elsewhere, i, j, depth);
  EXPECT_NEAR(scene.pixel(i, j)[0], 191, 4) << "both sides, half red each, over the background";
  EXPECT_NEAR(scene.pixel(i, j)[1], 0, 4);
}

TEST(IsosurfaceMapper, ReusesTheFrameUntilSomethingChanges)
{
  Scene scene;
  scene.render();
  const double first = scene.mapper->GetLastEngineTime();
  EXPECT_GT(first, 0);
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastEngineTime(), first) << "an unchanged frame ran the engine again";
  scene.renderer->GetActiveCamera()->Azimuth(10);
  scene.render();
  EXPECT_NE(scene.mapper->GetLastEngineTime(), first);
}

TEST(IsosurfaceMapper, DrawsAnInputOlderThanTheOneItDrewLast)
{
  // The scene's sphere was made first; the larger sphere (moved out by 1.5) after it. Drawn
  // in that order, the older sphere's data must be converted again, though its modification
  // time is older than what the mapper last converted.
  Scene scene;
  const vtkSmartPointer<vtkDataObject> older = scene.mapper->GetInputDataObject(0, 0);
  scene.render();
  const size_t sphere = scene.mapper->GetLastGBuffer().coveredPixels();
  auto larger = iga::makeMarsdenSphere<double>(2);
  for (auto& patch : larger.patches)
  {
    const auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      for (int d = 0; d < 3; ++d)
        view.point(p)[d] *= 1.5;
  }
  scene.mapper->SetInputData(vtkIGABezierHexahedra::ToUnstructuredGrid(larger));
  scene.render();
  EXPECT_GT(scene.mapper->GetLastGBuffer().coveredPixels(), sphere + 100);
  scene.mapper->SetInputData(older);
  scene.render();
  EXPECT_EQ(scene.mapper->GetLastGBuffer().coveredPixels(), sphere);
}

/// Two spheres as blocks of a multiblock dataset, the second moved by +2.5 in x.
vtkSmartPointer<vtkMultiBlockDataSet> twoSphereBlocks()
{
  auto moved = iga::makeMarsdenSphere<double>(2);
  for (auto& patch : moved.patches)
  {
    const auto view = patch.view();
    for (int p = 0; p < view.pointCount(); ++p)
      view.point(p)[0] += 2.5 * view.point(p)[iga::kWeightChannel];
  }
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  blocks->SetBlock(0, vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeMarsdenSphere<double>(2)));
  blocks->SetBlock(1, vtkIGABezierHexahedra::ToUnstructuredGrid(moved));
  return blocks;
}

TEST(IsosurfaceMapper, DrawsCompositeInputAndHardwareSelectionFindsBlockAndPatch)
{
  Scene scene;
  scene.mapper->SetInputData(twoSphereBlocks());
  vtkCamera* camera = scene.renderer->GetActiveCamera();
  camera->SetPosition(1.25, -7, 0);
  camera->SetFocalPoint(1.25, 0, 0);
  scene.render();
  double bounds[6];
  scene.mapper->GetBounds(bounds);
  EXPECT_NEAR(bounds[0], -1.5, 1e-12);
  EXPECT_NEAR(bounds[1], 4.0, 1e-12);
  // Both spheres are drawn.
  const double centres[2][3] = { { 0, -1, 0 }, { 2.5, -1, 0 } };
  int i[2], j[2];
  double depth;
  for (int b = 0; b < 2; ++b)
  {
    scene.display(centres[b], i[b], j[b], depth);
    EXPECT_GT(scene.pixel(i[b], j[b])[0], 40) << "sphere " << b;
  }
  // A prop picker finds the isosurface actor, and nothing on the background.
  vtkNew<vtkPropPicker> picker;
  ASSERT_TRUE(picker->Pick(i[1] + 0.5, j[1] + 0.5, 0, scene.renderer));
  EXPECT_EQ(picker->GetActor(), scene.isosurface.Get());
  EXPECT_FALSE(picker->Pick(2, 2, 0, scene.renderer));
  // The hardware selector reports the block (flat index 2: the root is 0) and the patch (cell 0).
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(i[1], j[1], i[1], j[1]);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  ASSERT_EQ(selection->GetNumberOfNodes(), 1u);
  vtkSelectionNode* node = selection->GetNode(0);
  EXPECT_EQ(node->GetProperties()->Get(vtkSelectionNode::PROP()), scene.isosurface.Get());
  EXPECT_EQ(node->GetProperties()->Get(vtkSelectionNode::COMPOSITE_INDEX()), 2);
  ASSERT_EQ(node->GetSelectionList()->GetNumberOfTuples(), 1);
  EXPECT_EQ(node->GetSelectionList()->GetVariantValue(0).ToInt(), 0);
  // After selecting, the window shows colours again.
  scene.render();
  EXPECT_GT(scene.pixel(i[0], j[0])[0], 40);
}

TEST(IsosurfaceMapper, PositionalSpotLightLightsOnlyItsCone)
{
  Scene scene;
  scene.isosurface->GetProperty()->SetAmbient(0);
  scene.isosurface->GetProperty()->SetDiffuse(1);
  scene.isosurface->GetProperty()->SetSpecular(0);
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(true);
  spot->SetPosition(0, -3, 0);
  spot->SetFocalPoint(0.4, 0, 0.3);
  spot->SetConeAngle(12);
  spot->SetExponent(1);
  spot->SetAttenuationValues(1, 0, 0);
  scene.renderer->AddLight(spot);
  scene.render();
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  const auto& colours = scene.mapper->GetLastColours();
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.4, 3, 0.3));
  int lit = 0, dark = 0;
  for (int p = 0; p < gbuffer.width * gbuffer.height; ++p)
  {
    const auto* hit = gbuffer.firstHit(p % gbuffer.width, p / gbuffer.width);
    if (!hit)
      continue;
    const glm::dvec3 toHit = glm::normalize(hit->position - glm::dvec3(0, -3, 0));
    const double angle = std::acos(glm::dot(toHit, axis)) * 180 / M_PI;
    if (std::abs(angle - 12) < 0.5)
      continue; // the cone's rim
    if (angle < 12)
    {
      // Lambert times the spot falloff cos(angle)^1 (vtkLight semantics), no attenuation.
      const double expected =
        std::max(0.0, glm::dot(hit->normal, -toHit)) * std::cos(angle * M_PI / 180);
      EXPECT_NEAR(colours[4 * size_t(p)], expected, 1e-5) << "inside the cone, pixel " << p;
      ++lit;
    }
    else
    {
      EXPECT_EQ(colours[4 * size_t(p)], 0.0f) << "outside the cone, pixel " << p;
      ++dark;
    }
  }
  EXPECT_GT(lit, 100);
  EXPECT_GT(dark, 1000);
}

} // namespace

namespace
{

/// The window's centre pixel with the scene's actor drawn by its IGA mapper and by VTK's own
/// mapper of a polygonal unit sphere, in that order; every covered pixel of the IGA frame must
/// hold `expected` (premultiplied, opaque).
std::array<std::array<int, 3>, 2> centreByBothMappers(Scene& scene, const double* expected)
{
  std::array<std::array<int, 3>, 2> centres;
  scene.render();
  const auto& gbuffer = scene.mapper->GetLastGBuffer();
  const auto& colours = scene.mapper->GetLastColours();
  int covered = 0;
  for (int p = 0; p < gbuffer.width * gbuffer.height; ++p)
  {
    if (!gbuffer.firstHit(p % gbuffer.width, p / gbuffer.width))
      continue;
    ++covered;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(colours[4 * size_t(p) + c], expected[c], 1e-6) << "pixel " << p;
  }
  EXPECT_GT(covered, 5000);
  const int i = 100, j = 80;
  for (int c = 0; c < 3; ++c)
    centres[0][c] = scene.pixel(i, j)[c];
  scene.isosurface->SetMapper(igatest::sphereMapper(0, 0, 0, 1));
  scene.render();
  for (int c = 0; c < 3; ++c)
    centres[1][c] = scene.pixel(i, j)[c];
  scene.isosurface->SetMapper(scene.mapper);
  return centres;
}

TEST(IsosurfaceMapper, UnlitWithoutLightsOrLightingAsVTKDrawsItsOwnSurfaces)
{
  Scene scene;
  vtkProperty* property = scene.isosurface->GetProperty();
  property->SetColor(0.2, 0.6, 0.9);
  property->SetAmbient(0.25);
  property->SetDiffuse(0.5);
  property->SetSpecular(0.5);
  const double expected[3] = { 0.75 * 0.2, 0.75 * 0.6, 0.75 * 0.9 };
  // ParaView's view with its light kit and headlight off: no light in the renderer.
  scene.renderer->AutomaticLightCreationOff();
  scene.renderer->RemoveAllLights();
  auto centres = centreByBothMappers(scene, expected);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(centres[0][c], centres[1][c], 1) << "no lights, channel " << c;
  // A light, but lighting off in the property.
  scene.renderer->AutomaticLightCreationOn();
  property->LightingOff();
  centres = centreByBothMappers(scene, expected);
  EXPECT_GT(scene.renderer->GetLights()->GetNumberOfItems(), 0);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(centres[0][c], centres[1][c], 1) << "lighting off, channel " << c;
}

} // namespace
