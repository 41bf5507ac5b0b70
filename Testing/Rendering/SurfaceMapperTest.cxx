// vtkIGAIsosurfaceMapper drawing surfaces: the boundary of volumes (DRAW_SURFACES) equals the
// same faces given as quadrilateral cells, frame by frame of a deforming series; picking finds
// the volume a boundary face belongs to; element edges (EdgeVisibility); the real teapot of
// G+Smo's file; regression images.
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGABoundarySurface.h"
#include "vtkIGAGeoPDEsReader.h"
#include "vtkIGAGismoReader.h"
#include "vtkIGAIsosurfaceMapper.h"
#include "vtkIGASyntheticDeformation.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "iga/Datasets.h"
#include "iga/sst/ElementEdges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

namespace
{

struct SurfaceScene : igatest::MapperScene
{
  SurfaceScene()
    : MapperScene(240, 200)
  {
    mapper->SetDrawModeToSurfaces();
  }

  /// Renders `input` and returns the mapper's G-buffer of it.
  iga::sst::GBuffer draw(vtkDataObject* input)
  {
    mapper->SetInputData(input);
    window->Render();
    return mapper->GetLastGBuffer();
  }
};

/// The boundary faces of a grid of hexahedra as quadrilateral cells (vtkIGABoundarySurface).
vtkSmartPointer<vtkUnstructuredGrid> boundaryOf(vtkUnstructuredGrid* volumes)
{
  vtkNew<vtkIGABoundarySurface> boundary;
  boundary->SetInputData(volumes);
  boundary->Update();
  return boundary->GetOutput();
}

/// Pixels covered in one G-buffer only, and the largest difference of first-hit depths.
void expectSameImage(const iga::sst::GBuffer& a, const iga::sst::GBuffer& b, int atLeast)
{
  ASSERT_EQ(a.width, b.width);
  int covered = 0, differ = 0;
  double depth = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i)
    {
      const auto *x = a.firstHit(i, j), *y = b.firstHit(i, j);
      differ += (x != nullptr) != (y != nullptr);
      if (x && y)
      {
        ++covered;
        depth = std::max(depth, std::abs(x->ndcDepth - y->ndcDepth));
      }
    }
  EXPECT_GT(covered, atLeast);
  EXPECT_EQ(differ, 0);
  EXPECT_LT(depth, 1e-9);
}

TEST(SurfaceMapper, BoundaryOfVolumesEqualsItsFacesGivenAsSurfacesFrameByFrame)
{
  SurfaceScene scene;
  scene.look(2.6, -3.4, 3.0, 0, 0, 1);
  vtkNew<vtkIGASyntheticDeformation> deformation;
  deformation->SetInputData(
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.0)));
  for (double time : { 0.2, 0.9 })
  {
    deformation->SetTime(time); // the default twist
    deformation->Update();
    auto volumes = vtkSmartPointer<vtkUnstructuredGrid>::New();
    volumes->ShallowCopy(deformation->GetOutput());
    const iga::sst::GBuffer asVolumes = scene.draw(volumes);
    const iga::sst::GBuffer asFaces = scene.draw(boundaryOf(volumes));
    expectSameImage(asVolumes, asFaces, 8000);
    for (const auto& hit : asVolumes.hits)
      ASSERT_EQ(hit.isovalue, -1) << "only surfaces are drawn";
  }
}

TEST(SurfaceMapper, PickingABoundaryFaceFindsItsVolume)
{
  SurfaceScene scene;
  scene.look(0, -6, 1, 0, 0, 1);
  // The tube's eight patches: quadrant q of the lower half is cell q, of the upper half 4 + q.
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.5, 0.0));
  const iga::sst::GBuffer gbuffer = scene.draw(grid);
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  int checked = 0;
  for (int j = 20; j < gbuffer.height; j += 40)
    for (int i = 20; i < gbuffer.width; i += 40)
    {
      const auto* hit = gbuffer.firstHit(i, j);
      if (!hit)
        continue;
      selector->SetArea(i, j, i, j);
      vtkSmartPointer<vtkSelection> selection;
      selection.TakeReference(selector->Select());
      ASSERT_EQ(selection->GetNumberOfNodes(), 1u);
      const int cell = selection->GetNode(0)->GetSelectionList()->GetVariantValue(0).ToInt();
      // The outer wall seen from -y: x > 0 in quadrant 3 (or 0 at x = 1), z picks the half.
      const int quadrant = std::atan2(hit->position[1], hit->position[0]) < -M_PI / 2 ? 2 : 3;
      EXPECT_EQ(cell, quadrant + (hit->position[2] > 1 ? 4 : 0))
        << "pixel " << i << ", " << j << " at " << hit->position[0] << ", " << hit->position[2];
      ++checked;
    }
  EXPECT_GT(checked, 6);
}

TEST(SurfaceMapper, EdgeVisibilityDrawsTheElementEdgesInTheEdgeColour)
{
  SurfaceScene scene;
  scene.look(2.6, -3.4, 3.0, 0, 0, 1);
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTwistedTube<double>(0.5));
  const iga::sst::GBuffer gbuffer = scene.draw(grid);
  const std::vector<float> plain = scene.mapper->GetLastColours();
  scene.actor->GetProperty()->SetEdgeColor(0, 0, 1);
  scene.actor->GetProperty()->EdgeVisibilityOn();
  scene.window->Render();
  const auto& withEdges = scene.mapper->GetLastColours();
  // Each pixel is its shading blended with the edge colour by the edges' coverage.
  const auto coverage = iga::sst::elementEdgeCoverage(gbuffer, 1.0);
  int edges = 0;
  for (size_t p = 0; p < coverage.size(); ++p)
  {
    const float k = coverage[p], alpha = plain[4 * p + 3];
    const float edge[3] = { 0, 0, 1 };
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(withEdges[4 * p + c], (1 - k) * plain[4 * p + c] + k * edge[c] * alpha, 1e-6)
        << "pixel " << p;
    edges += k > 0.5;
  }
  EXPECT_GT(edges, 300);
  igatest::compareWithBaseline(scene.window, "MapperTubeBoundaryWithEdges");
}

TEST(SurfaceMapper, QuadrilateralsAreDrawnInIsosurfaceModeToo)
{
  // An isovalue and a surface array that no hexahedron has: the quadrilaterals are drawn as
  // they are, with no complaint about the array.
  SurfaceScene scene;
  scene.mapper->SetDrawModeToIsosurfaces();
  scene.mapper->SetIsovalue(0, 0.0);
  scene.mapper->SetSurfaceArrayName("no such array");
  scene.look(6.0, -10.0, 6.5, 0.2, 0, 1.2);
  vtkNew<vtkTest::ErrorObserver> errors;
  scene.mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  const iga::sst::GBuffer gbuffer =
    scene.draw(vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTeapot<double>()));
  EXPECT_GT(gbuffer.coveredPixels(), 5000u);
  EXPECT_FALSE(errors->GetError()) << errors->GetErrorMessage();
}

TEST(SurfaceMapper, TheRealTeapotOfGismosFile)
{
  const std::string file = std::string(IGAVIEW_SHARED_DATA_DIR) + "/gismo/teapot.xml";
  if (!std::ifstream(file))
    GTEST_SKIP() << file << " not found (../shared is absent)";
  vtkNew<vtkIGAGismoReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  SurfaceScene scene;
  scene.look(6.0, -10.0, 6.5, 0.2, 0, 1.2);
  scene.actor->GetProperty()->EdgeVisibilityOn();
  scene.actor->GetProperty()->SetEdgeColor(0.2, 0.2, 0.2);
  const iga::sst::GBuffer gbuffer = scene.draw(reader->GetOutput());
  EXPECT_GT(gbuffer.coveredPixels(), 8000u);
  EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
  for (const auto& hit : gbuffer.hits)
    ASSERT_LT(hit.patch, 32) << "32 bicubic patches, drawn as surfaces";
  igatest::compareWithBaseline(scene.window, "MapperGismoTeapotWithEdges");
}

TEST(SurfaceMapper, SharedGismoAndGeoPDEsFilesShowTheirBoundaries)
{
  const std::string shared = IGAVIEW_SHARED_DATA_DIR;
  const std::vector<std::string> files = { "gismo/quarter_cylinder.xml", "gismo/twisted_pipe.xml",
    "gismo/GshapedVolume.xml", "geopdes/geo_2cubesb.txt" };
  if (!std::ifstream(shared + "/" + files[0]))
    GTEST_SKIP() << shared << " not found (../shared is absent)";
  for (const std::string& file : files)
  {
    SCOPED_TRACE(file);
    vtkSmartPointer<vtkIGANurbsReader> reader;
    if (file.rfind("gismo", 0) == 0)
      reader = vtkSmartPointer<vtkIGAGismoReader>::New();
    else
      reader = vtkSmartPointer<vtkIGAGeoPDEsReader>::New();
    reader->SetFileName((shared + "/" + file).c_str());
    reader->Update();
    SurfaceScene scene;
    // From a corner, where a box shows three faces.
    scene.renderer->GetActiveCamera()->SetPosition(1, -1.3, 1);
    scene.renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    scene.renderer->ResetCamera(reader->GetOutput()->GetBounds());
    const iga::sst::GBuffer gbuffer = scene.draw(reader->GetOutput());
    EXPECT_GT(gbuffer.coveredPixels(), 4000u) << "the volume's boundary fills the view";
    EXPECT_EQ(scene.mapper->GetLastUnresolvedPixels(), 0);
    // Seen from a corner, several boundary faces show.
    std::set<int> faces;
    for (const auto& hit : gbuffer.hits)
      faces.insert(hit.patch);
    EXPECT_GT(faces.size(), 1u);
  }
}

} // namespace
