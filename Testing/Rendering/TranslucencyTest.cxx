// Translucent vtkIGAIsosurfaceMapper surfaces under each of VTK's translucency techniques:
// the default translucent pass (order-independent blending), dual depth peeling
// (vtkRenderer::UseDepthPeeling, VTK's pick on desktop OpenGL, as in ParaView) and the
// classic vtkDepthPeelingPass (VTK's pick without dual depth peeling).
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDepthPeelingPass.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTranslucentPass.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWindowToImageFilter.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

namespace
{

enum class Technique
{
  Blending,         ///< VTK's default translucent pass (order-independent translucency)
  DualDepthPeeling, ///< vtkRenderer::UseDepthPeeling: vtkDualDepthPeelingPass
  DepthPeeling,     ///< vtkDepthPeelingPass in a vtkRenderStepsPass
};

std::string techniqueName(const testing::TestParamInfo<Technique>& info)
{
  switch (info.param)
  {
    case Technique::Blending:
      return "Blending";
    case Technique::DualDepthPeeling:
      return "DualDepthPeeling";
    default:
      return "DepthPeeling";
  }
}

struct Scene
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkSmartPointer<vtkImageData> image;

  /// Depth peeling takes up to `peels` peels.
  explicit Scene(Technique technique, int peels = 4)
  {
    window->SetOffScreenRendering(1);
    window->SetSize(200, 160);
    // Depth peeling needs a window without multisampling and with alpha (vtkRenderer's rule).
    window->SetMultiSamples(0);
    window->SetAlphaBitPlanes(1);
    window->AddRenderer(renderer);
    renderer->SetBackground(0, 0, 0);
    if (technique == Technique::DualDepthPeeling)
    {
      renderer->SetUseDepthPeeling(1);
      renderer->SetMaximumNumberOfPeels(peels);
      renderer->SetOcclusionRatio(0);
    }
    else if (technique == Technique::DepthPeeling)
    {
      vtkNew<vtkTranslucentPass> translucent;
      vtkNew<vtkDepthPeelingPass> peeling;
      peeling->SetTranslucentPass(translucent);
      peeling->SetMaximumNumberOfPeels(peels);
      peeling->SetOcclusionRatio(0);
      vtkNew<vtkRenderStepsPass> steps;
      steps->SetTranslucentPass(peeling);
      renderer->SetPass(steps);
    }
    igatest::lookAtTheOriginFromMinusY(renderer->GetActiveCamera());
  }

  /// A unit-sphere isosurface in the given colour, lit by ambient light only (the colour as is).
  vtkActor* addIsosurface(double r, double g, double b, double opacity)
  {
    vtkNew<vtkIGAIsosurfaceMapper> mapper;
    mapper->SetInputData(
      vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeMarsdenSphere<double>(2)));
    mapper->SetIsovalue(0, 0.0);
    return this->add(mapper, r, g, b, opacity);
  }

  vtkActor* addSphere(double x, double y, double z, double radius)
  {
    return this->add(igatest::sphereMapper(x, y, z, radius), 0, 1, 0, 1);
  }

  /// A square facing the camera at depth y, 3 wide: one translucent layer.
  vtkActor* addSquare(double y, double r, double g, double b, double opacity)
  {
    vtkNew<vtkPlaneSource> source;
    source->SetOrigin(-1.5, y, -1.5);
    source->SetPoint1(1.5, y, -1.5);
    source->SetPoint2(-1.5, y, 1.5);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    return this->add(mapper, r, g, b, opacity);
  }

  vtkActor* add(vtkMapper* mapper, double r, double g, double b, double opacity)
  {
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(r, g, b);
    actor->GetProperty()->SetOpacity(opacity);
    actor->GetProperty()->SetAmbient(1);
    actor->GetProperty()->SetDiffuse(0);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    return actor;
  }

  void render() { image = igatest::renderAndGrab(window); }

  /// The pixel a world point projects to.
  const unsigned char* pixelAt(double x, double y, double z)
  {
    renderer->SetWorldPoint(x, y, z, 1);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    const int i = int(std::floor(d[0])), j = int(std::floor(d[1]));
    int size[3];
    image->GetDimensions(size);
    if (i < 0 || j < 0 || i >= size[0] || j >= size[1])
    {
      ADD_FAILURE() << "(" << x << ", " << y << ", " << z << ") is not in the image";
      static const unsigned char none[3] = { 255, 255, 255 };
      return none;
    }
    return static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
  }
};

#define EXPECT_RGB(pixel, r, g, b, what)                                                           \
  do                                                                                               \
  {                                                                                                \
    const unsigned char* p_ = (pixel);                                                             \
    EXPECT_NEAR(p_[0], r, 6) << what;                                                              \
    EXPECT_NEAR(p_[1], g, 6) << what;                                                              \
    EXPECT_NEAR(p_[2], b, 6) << what;                                                              \
  } while (false)

class Translucency : public testing::TestWithParam<Technique>
{
};

/// Depth order needs peeling: VTK's default (order-independent) blending averages the layers
/// whatever their order.
class TranslucencyInDepthOrder : public Translucency
{
};

/// A half-opaque red isosurface over an opaque green sphere inside it (its near side only: the
/// far side is behind the green), and over the background (both sides: 1/2 + 1/4 red).
TEST_P(Translucency, SurfaceBlendsOverWhatIsBehind)
{
  Scene scene(GetParam());
  scene.addSphere(0.55, 0, 0.2, 0.3);
  scene.addIsosurface(1, 0, 0, 0.5);
  scene.render();
  EXPECT_RGB(scene.pixelAt(0.55, -0.3, 0.2), 128, 128, 0, "half red over the green sphere");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.8, -0.2), 191, 0, 0, "both sides over the black background");
  EXPECT_RGB(scene.pixelAt(1.2, 0, 1.2), 0, 0, 0, "nothing drawn outside the surface");
  // Again, with the same frame (nothing changed: the mapper reuses it, every peel still draws).
  scene.render();
  EXPECT_RGB(scene.pixelAt(0.55, -0.3, 0.2), 128, 128, 0, "second render");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.8, -0.2), 191, 0, 0, "second render, both sides");
}

/// A half-opaque blue square in front of the isosurface, then between its near and far sides:
/// each layer blends over the ones behind it (the k-th layer's colour weighs 1/2^k).
TEST_P(TranslucencyInDepthOrder, SurfaceAndPolygonBlendInDepthOrder)
{
  Scene scene(GetParam());
  scene.addIsosurface(1, 0, 0, 0.5);
  vtkActor* square = scene.addSquare(-1.5, 0, 0, 1, 0.5);
  scene.render();
  // Blue 1/2, red's near side 1/4, its far side 1/8.
  EXPECT_RGB(scene.pixelAt(0, -1, 0), 96, 0, 128, "blue square in front of the red surface");
  EXPECT_RGB(scene.pixelAt(1.2, 0, 1.2), 0, 0, 128, "the square alone");
  square->SetPosition(0, 2, 0); // y = 0.5: between the surface's near and far sides
  scene.render();
  // Red 1/2, blue 1/4, red 1/8.
  EXPECT_RGB(scene.pixelAt(0, -1, 0), 159, 0, 64, "the square inside the red surface");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.8, -0.2), 159, 0, 64, "elsewhere on the surface");
  EXPECT_RGB(scene.pixelAt(1.2, 0, 1.2), 0, 0, 128, "the square alone");
}

/// Two half-opaque isosurfaces, one partly behind the other; then swapped (the same drawing
/// order, the other depth order).
TEST_P(TranslucencyInDepthOrder, TwoSurfacesBlendInDepthOrder)
{
  Scene scene(GetParam());
  vtkActor* red = scene.addIsosurface(1, 0, 0, 0.5);
  vtkActor* blue = scene.addIsosurface(0, 0, 1, 0.5);
  blue->SetPosition(0.8, 2, 0);
  scene.render();
  // On the red sphere's near side, in front of the blue sphere: red's two sides 1/2 + 1/4, then
  // blue's 1/8 + 1/16.
  EXPECT_RGB(scene.pixelAt(0.5, -0.85, 0), 191, 0, 48, "red in front of blue");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.85, 0), 191, 0, 0, "red alone");
  red->SetPosition(0.8, 2, 0);
  blue->SetPosition(0, 0, 0);
  scene.render();
  EXPECT_RGB(scene.pixelAt(0.5, -0.85, 0), 48, 0, 191, "blue in front of red");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.85, 0), 0, 0, 191, "blue alone");
}

/// Two nested isosurfaces of one actor (the Marsden sphere's field at -0.5 and 0: radii
/// sqrt(1/2) and 1) and a VTK polygonal sphere of radius 0.85 between them, all half opaque:
/// six layers through the centre, interleaved, each weighing 1/2^k in depth order.
TEST_P(TranslucencyInDepthOrder, NestedSurfacesAndAPolygonalSphereInterleave)
{
  Scene scene(GetParam(), 8);
  vtkActor* nested = scene.addIsosurface(1, 0, 0, 0.5);
  static_cast<vtkIGAIsosurfaceMapper*>(nested->GetMapper())->SetIsovalue(1, -0.5);
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(0.85);
  ball->SetThetaResolution(96);
  ball->SetPhiResolution(96);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  scene.add(ballMapper, 0, 1, 0, 0.5);
  scene.render();
  // Along the view axis: red (outer), green, red (inner), red (inner), green, red (outer).
  const double red = 1.0 / 2 + 1.0 / 8 + 1.0 / 16 + 1.0 / 64, green = 1.0 / 4 + 1.0 / 32;
  EXPECT_RGB(scene.pixelAt(0, -1, 0), 255 * red, 255 * green, 0, "six layers");
  // Past the inner sphere (|x| > 0.71) but inside the ball: four layers, red green green red.
  const double redOut = 1.0 / 2 + 1.0 / 16, greenOut = 1.0 / 4 + 1.0 / 8;
  EXPECT_RGB(scene.pixelAt(0.78, -0.2, 0), 255 * redOut, 255 * greenOut, 0, "four layers");
}

/// In a viewport away from the window's corner (the peeling passes draw into their own
/// framebuffer, from its corner): the same pixels.
TEST_P(Translucency, SurfaceInAnOffsetViewport)
{
  Scene scene(GetParam());
  scene.renderer->SetViewport(0.3, 0.2, 1, 1);
  scene.addSphere(0.55, 0, 0.2, 0.3);
  scene.addIsosurface(1, 0, 0, 0.5);
  scene.render();
  EXPECT_RGB(scene.pixelAt(0.55, -0.3, 0.2), 128, 128, 0, "half red over the green sphere");
  EXPECT_RGB(scene.pixelAt(-0.5, -0.8, -0.2), 191, 0, 0, "both sides over the black background");
}

/// Dual depth peeling with one peel: the front and back layers are peeled, the surface's two
/// sides between them are blended in the final alpha-blending stage.
TEST(TranslucencyPeeling, SurfaceLeftToTheLastStageOfDualDepthPeeling)
{
  Scene scene(Technique::DualDepthPeeling);
  scene.renderer->SetMaximumNumberOfPeels(1);
  scene.addSquare(-1.5, 0, 0, 1, 0.5);
  scene.addIsosurface(1, 0, 0, 0.5);
  scene.addSquare(1.5, 0, 1, 0, 0.5);
  scene.render();
  // Blue 1/2, red 1/4 + 1/8, green 1/16.
  EXPECT_RGB(scene.pixelAt(0, -1, 0), 96, 16, 128, "blue over both red sides over green");
}

/// Depth peeling on a multisampled window draws no translucent geometry with VTK 9.2 (Mesa):
/// the mapper says so, once, and not without depth peeling or multisampling.
TEST(TranslucencyPeeling, DepthPeelingOnAMultisampledWindowIsReported)
{
  for (const auto& [technique, samples, expected] :
    { std::make_tuple(Technique::DualDepthPeeling, 8, 1),
      std::make_tuple(Technique::DepthPeeling, 4, 1), std::make_tuple(Technique::Blending, 8, 0),
      std::make_tuple(Technique::DualDepthPeeling, 0, 0) })
  {
    Scene scene(technique);
    scene.window->SetMultiSamples(samples);
    vtkActor* actor = scene.addIsosurface(1, 0, 0, 0.5);
    std::vector<std::string> warnings;
    vtkNew<vtkCallbackCommand> recorder;
    recorder->SetClientData(&warnings);
    recorder->SetCallback(
      [](vtkObject*, unsigned long, void* clientData, void* callData)
      {
        static_cast<std::vector<std::string>*>(clientData)
          ->push_back(static_cast<const char*>(callData));
      });
    actor->GetMapper()->AddObserver(vtkCommand::WarningEvent, recorder);
    scene.render();
    scene.render();
    const std::string what = "technique " + std::to_string(int(technique)) + ", " +
                             std::to_string(samples) + " multisamples";
    ASSERT_EQ(int(warnings.size()), expected) << what;
    if (expected)
    {
      EXPECT_NE(warnings[0].find("SetMultiSamples(0)"), std::string::npos) << warnings[0];
    }
  }
}

/// Opaque surfaces are drawn by the opaque pass whatever the technique: the same image.
TEST_P(Translucency, OpaqueSceneIsTheSameImage)
{
  auto renderOpaque = [](Technique technique)
  {
    Scene scene(technique);
    scene.addIsosurface(1, 0, 0, 1)->GetProperty()->SetDiffuse(0.7);
    scene.addSphere(0, -1.0, 0, 0.25);
    scene.render();
    vtkSmartPointer<vtkImageData> image = scene.image;
    return image;
  };
  vtkSmartPointer<vtkImageData> reference = renderOpaque(Technique::Blending);
  vtkSmartPointer<vtkImageData> image = renderOpaque(GetParam());
  auto* a = vtkUnsignedCharArray::SafeDownCast(reference->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfValues(), b->GetNumberOfValues());
  vtkIdType differing = 0, covered = 0;
  for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k)
  {
    differing += a->GetValue(k) != b->GetValue(k);
    covered += a->GetValue(k) != 0;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(covered, 1000);
}

INSTANTIATE_TEST_SUITE_P(Techniques, Translucency,
  testing::Values(Technique::Blending, Technique::DualDepthPeeling, Technique::DepthPeeling),
  techniqueName);
INSTANTIATE_TEST_SUITE_P(Peeling, TranslucencyInDepthOrder,
  testing::Values(Technique::DualDepthPeeling, Technique::DepthPeeling), techniqueName);

} // namespace
