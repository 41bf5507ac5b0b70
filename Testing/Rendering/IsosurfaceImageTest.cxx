// vtkIGAIsosurfaceImage, the mapper's frame as an image without OpenGL, and the mapper's probe:
// the image's arrays equal the G-buffer the mapper drew in a window for the same camera; a
// probed hit lies on the analytic sphere and its attribute is the patch's at the returned
// parameter; a boundary face's hit is at its parameter in the volume the face bounds.
#include "RenderingTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGAIsosurfaceImage.h"
#include "vtkIGAIsosurfaceMapper.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include "iga/BezierPatch.h"
#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> readData(const std::string& name)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((std::string(IGAVIEW_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  return reader->GetOutput();
}

/// Channel values of `patch` at parameter `uvw`, divided by the weight (attributes and x, y, z).
std::vector<double> evaluate(const iga::PatchView<const double, 3>& patch, const double* uvw)
{
  std::vector<double> values(size_t(patch.channels));
  iga::evaluateHomogeneous(patch, uvw, values.data(), static_cast<double*>(nullptr));
  const double weight = values[iga::kWeightChannel];
  for (double& value : values)
    value /= weight;
  return values;
}
} // namespace

TEST(IsosurfaceImage, ArraysEqualTheGBufferTheMapperDrewForTheSameCamera)
{
  const auto sphere = readData("marsden_sphere_p3.vtu");
  igatest::MapperScene scene(200, 160);
  scene.mapper->SetInputData(sphere);
  scene.mapper->SetIsovalue(0, 0.0);
  igatest::lookAtTheOriginFromMinusY(scene.renderer->GetActiveCamera());
  scene.window->Render();
  const iga::sst::GBuffer& drawn = scene.mapper->GetLastGBuffer();

  vtkNew<vtkIGAIsosurfaceImage> image;
  image->SetInputData(sphere);
  image->GetMapper()->SetIsovalue(0, 0.0);
  image->SetCamera(scene.renderer->GetActiveCamera());
  image->SetImageSize(200, 160);
  image->Update();
  vtkPointData* pixels = image->GetOutput()->GetPointData();
  auto* depth = vtkDoubleArray::SafeDownCast(pixels->GetArray("Depth"));
  auto* position = vtkDoubleArray::SafeDownCast(pixels->GetArray("Position"));
  auto* hitCount = vtkIntArray::SafeDownCast(pixels->GetArray("HitCount"));
  auto* attribute = vtkDoubleArray::SafeDownCast(pixels->GetArray("sphere"));
  ASSERT_TRUE(depth && position && hitCount && attribute);
  EXPECT_EQ(pixels->GetArray("Block"), nullptr); // a grid, not a composite dataset
  int covered = 0;
  for (int j = 0; j < 160; ++j)
    for (int i = 0; i < 200; ++i)
    {
      const vtkIdType p = j * 200 + i;
      const iga::sst::Hit* hit = drawn.firstHit(i, j);
      ASSERT_EQ(hitCount->GetValue(p), drawn.hitCount(i, j)) << i << ", " << j;
      if (!hit)
      {
        EXPECT_TRUE(std::isnan(depth->GetValue(p)));
        continue;
      }
      ++covered;
      EXPECT_EQ(depth->GetValue(p), hit->eyeDepth);
      for (int d = 0; d < 3; ++d)
        EXPECT_EQ(position->GetComponent(p, d), hit->position[d]);
      EXPECT_LT(std::abs(attribute->GetValue(p)), 1e-9); // on the isosurface sphere = 0
    }
  EXPECT_GT(covered, 3000);
}

TEST(IsosurfaceImage, ProbeIsExactOnTheMarsdenSphere)
{
  const auto sphere = readData("marsden_sphere_p3.vtu");
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(sphere, patches, error, warnings));
  igatest::MapperScene scene(160, 120);
  scene.mapper->SetInputData(sphere);
  scene.mapper->SetIsovalue(0, 0.0);
  igatest::lookAtTheOriginFromMinusY(scene.renderer->GetActiveCamera());
  scene.window->Render();
  ASSERT_EQ(scene.mapper->GetNumberOfAttributes(), 1);
  EXPECT_STREQ(scene.mapper->GetAttributeName(0), "sphere");
  // f = r^2 - 1 over [-1.5, 1.5]^3 takes -1 (the centre) .. 5.75 (the corners); its control
  // values reach down to -7.75.
  double range[2] = { 0, 0 };
  ASSERT_TRUE(scene.mapper->GetAttributeRange("sphere", range));
  EXPECT_NEAR(range[0], -1.0, 1e-12);
  EXPECT_NEAR(range[1], 5.75, 1e-12);
  EXPECT_LT(sphere->GetPointData()->GetArray("sphere")->GetRange()[0], -1.5);
  EXPECT_FALSE(scene.mapper->GetAttributeRange("bogus", range));
  int probed = 0;
  for (int j = 0; j < 120; j += 3)
    for (int i = 0; i < 160; i += 3)
    {
      double position[3], uvw[3];
      vtkNew<vtkFieldData> attributes;
      const vtkIdType cell = scene.mapper->ProbePixel(i, j, position, uvw, attributes);
      if (cell < 0)
        continue;
      ++probed;
      ASSERT_EQ(cell, 0);
      EXPECT_NEAR(std::sqrt(position[0] * position[0] + position[1] * position[1] +
                            position[2] * position[2]),
        1.0, 1e-9);
      const auto values = evaluate(patches.volumes.patches[0].view(), uvw);
      auto* value = vtkDoubleArray::SafeDownCast(attributes->GetArray("sphere"));
      ASSERT_NE(value, nullptr);
      EXPECT_NEAR(value->GetValue(0), values[iga::kFirstAttributeChannel], 1e-12);
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(position[d], values[size_t(d)], 1e-9);
    }
  EXPECT_GT(probed, 200);
  double position[3], uvw[3];
  EXPECT_EQ(scene.mapper->ProbePixel(0, 0, position, uvw, nullptr), -1);   // a corner: nothing
  EXPECT_EQ(scene.mapper->ProbePixel(160, 0, position, uvw, nullptr), -1); // outside
}

TEST(IsosurfaceImage, BoundaryHitsAreAtTheirParameterInTheirVolumeOfTheirBlock)
{
  // The deformed tube as block 0 of a multiblock dataset (flat index 1), its boundary drawn.
  const auto grid = vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeTube<double>(0.5, 0.3));
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, grid);
  // The cells as the grid holds them (written in VTK's orientation, not makeTube's).
  vtkIGABezierHexahedra::Patches cells;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, cells, error, warnings));
  const auto& tube = cells.volumes;
  const auto& names = tube.attributeNames;
  const size_t heightIndex =
    size_t(std::find(names.begin(), names.end(), "height") - names.begin());
  ASSERT_LT(heightIndex, names.size());
  vtkNew<vtkIGAIsosurfaceImage> image;
  image->SetInputData(blocks);
  image->GetMapper()->SetDrawModeToSurfaces();
  image->SetImageSize(160, 160);
  image->Update(); // the default camera: the input framed
  vtkPointData* pixels = image->GetOutput()->GetPointData();
  auto* position = vtkDoubleArray::SafeDownCast(pixels->GetArray("Position"));
  auto* uvw = vtkDoubleArray::SafeDownCast(pixels->GetArray("UVW"));
  auto* cell = vtkIdTypeArray::SafeDownCast(pixels->GetArray("Cell"));
  auto* block = vtkUnsignedIntArray::SafeDownCast(pixels->GetArray("Block"));
  auto* height = vtkDoubleArray::SafeDownCast(pixels->GetArray("height"));
  ASSERT_TRUE(position && uvw && cell && block && height);
  int covered = 0;
  for (vtkIdType p = 0; p < 160 * 160; ++p)
  {
    if (cell->GetValue(p) < 0)
      continue;
    ++covered;
    EXPECT_EQ(block->GetValue(p), 1u); // the first block's flat index
    const auto values = evaluate(tube.patches[size_t(cell->GetValue(p))].view(), uvw->GetTuple3(p));
    for (int d = 0; d < 3; ++d)
      ASSERT_NEAR(position->GetComponent(p, d), values[size_t(d)], 1e-9) << p;
    EXPECT_NEAR(height->GetValue(p), values[iga::kFirstAttributeChannel + heightIndex], 1e-12);
  }
  EXPECT_GT(covered, 0.15 * 160 * 160); // framed as ResetCamera frames it: 4 866 pixels
}

/// All-hits layers: the Marsden sphere's rays through it hit it twice. With three layers asked
/// for, layer 1 holds the far side (on the unit sphere, deeper, its "sphere" value the isovalue),
/// layer 2 is empty; HitCount says two. With AllLayers off the frame keeps one hit, and layer 1
/// is empty everywhere.
TEST(IsosurfaceImage, LayersHoldTheHitsBehindTheFirst)
{
  const auto sphere = readData("marsden_sphere_p3.vtu");
  vtkNew<vtkIGAIsosurfaceImage> image;
  image->SetInputData(sphere);
  image->GetMapper()->SetIsovalue(0, 0.0);
  image->GetMapper()->AllLayersOn();
  image->SetImageSize(96, 96);
  image->SetLayers(3);
  image->Update();
  vtkPointData* pixels = image->GetOutput()->GetPointData();
  auto* depth = vtkDoubleArray::SafeDownCast(pixels->GetArray("Depth"));
  auto* depth1 = vtkDoubleArray::SafeDownCast(pixels->GetArray("Depth_1"));
  auto* position1 = vtkDoubleArray::SafeDownCast(pixels->GetArray("Position_1"));
  auto* value1 = vtkDoubleArray::SafeDownCast(pixels->GetArray("sphere_1"));
  auto* cell2 = vtkIdTypeArray::SafeDownCast(pixels->GetArray("Cell_2"));
  auto* hits = vtkIntArray::SafeDownCast(pixels->GetArray("HitCount"));
  ASSERT_TRUE(depth && depth1 && position1 && value1 && cell2 && hits);
  EXPECT_EQ(pixels->GetArray("Depth_3"), nullptr);
  int twice = 0;
  for (vtkIdType p = 0; p < 96 * 96; ++p)
  {
    EXPECT_EQ(cell2->GetValue(p), -1);
    if (hits->GetValue(p) < 2)
    {
      EXPECT_TRUE(std::isnan(depth1->GetValue(p)));
      continue;
    }
    ++twice;
    EXPECT_EQ(hits->GetValue(p), 2);
    EXPECT_GT(depth1->GetValue(p), depth->GetValue(p));
    const double* x = position1->GetTuple3(p);
    EXPECT_NEAR(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), 1.0, 1e-9);
    EXPECT_NEAR(value1->GetValue(p), 0.0, 1e-6);
  }
  EXPECT_GT(twice, 1000);
  image->GetMapper()->AllLayersOff();
  image->Update();
  depth1 = vtkDoubleArray::SafeDownCast(image->GetOutput()->GetPointData()->GetArray("Depth_1"));
  ASSERT_NE(depth1, nullptr);
  for (vtkIdType p = 0; p < 96 * 96; ++p)
    EXPECT_TRUE(std::isnan(depth1->GetValue(p)));
}
