// The default dataset against analytic truth: at time 0 it is an exact circular tube.
#include "vtkIGADefaultVolumeSource.h"

#include "vtkCellType.h"
#include "vtkGenericCell.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

TEST(DefaultVolumeSource, UndeformedTubeIsExactlyCircular)
{
  vtkNew<vtkIGADefaultVolumeSource> source;
  source->SetTime(0.0);
  source->Update();
  vtkUnstructuredGrid* grid = source->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), 8);
  ASSERT_NE(grid->GetPointData()->GetArray("temperature"), nullptr);
  ASSERT_NE(grid->GetPointData()->GetArray("radius"), nullptr);
  std::mt19937 rng(110);
  std::uniform_real_distribution<double> unit(0, 1);
  vtkNew<vtkGenericCell> cell;
  std::vector<double> weights(27);
  for (vtkIdType c = 0; c < 8; ++c)
  {
    EXPECT_EQ(grid->GetCellType(c), VTK_BEZIER_HEXAHEDRON);
    grid->GetCell(c, cell);
    for (int s = 0; s < 20; ++s)
    {
      // Parametric v runs from the inner (r = 0.5) to the outer (r = 1) wall, linearly in r.
      double pcoords[3] = { unit(rng), unit(rng), unit(rng) }, x[3];
      int subId;
      cell->EvaluateLocation(subId, pcoords, x, weights.data());
      EXPECT_NEAR(std::hypot(x[0], x[1]), 0.5 + 0.5 * pcoords[1], 1e-12);
      EXPECT_NEAR(x[2], (c / 4) + pcoords[2], 1e-12);
    }
  }
}

TEST(DefaultVolumeSource, AdvertisesTimeAndDeformsWithIt)
{
  vtkNew<vtkIGADefaultVolumeSource> source;
  source->UpdateInformation();
  vtkInformation* info = source->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 11);
  source->UpdateTimeStep(0.0);
  double rest[6];
  source->GetOutput()->GetBounds(rest);
  source->UpdateTimeStep(1.0);
  double bent[6];
  source->GetOutput()->GetBounds(bent);
  // The bend moves the top of the tube by +0.2 z^2 = 0.8 along x.
  EXPECT_NEAR(rest[1], 1.0, 1e-12); // the control net reaches x = 1 (the 45 degree corner point)
  EXPECT_GT(bent[1], rest[1] + 0.5);
}

TEST(DefaultVolumeSource, PiecesSplitThePatchesWithoutOverlap)
{
  // Pieces of 3 hold floor(8p/3)..floor(8(p+1)/3): 2, 3 and 3 whole patches, 27 points each,
  // whose points together are exactly the whole tube's.
  vtkNew<vtkIGADefaultVolumeSource> whole;
  whole->Update();
  vtkUnstructuredGrid* all = whole->GetOutput();
  const vtkIdType expected[3] = { 2, 3, 3 };
  vtkIdType offset = 0;
  for (int piece = 0; piece < 3; ++piece)
  {
    vtkNew<vtkIGADefaultVolumeSource> source;
    source->UpdatePiece(piece, 3, 0);
    vtkUnstructuredGrid* part = source->GetOutput();
    ASSERT_EQ(part->GetNumberOfCells(), expected[piece]);
    ASSERT_EQ(part->GetNumberOfPoints(), 27 * expected[piece]);
    ASSERT_NE(part->GetPointData()->GetArray("temperature"), nullptr);
    for (vtkIdType p = 0; p < part->GetNumberOfPoints(); ++p)
    {
      double a[3], b[3];
      part->GetPoint(p, a);
      all->GetPoint(offset + p, b);
      EXPECT_EQ(a[0], b[0]);
      EXPECT_EQ(a[1], b[1]);
      EXPECT_EQ(a[2], b[2]);
    }
    offset += part->GetNumberOfPoints();
  }
  EXPECT_EQ(offset, all->GetNumberOfPoints());
  // More pieces than patches: some are empty, valid grids (piece 0 of 10: [0, 0)), the
  // others hold one patch (piece 9 of 10: [7, 8)).
  vtkNew<vtkIGADefaultVolumeSource> source;
  source->UpdatePiece(0, 10, 0);
  EXPECT_EQ(source->GetOutput()->GetNumberOfCells(), 0);
  source->UpdatePiece(9, 10, 0);
  EXPECT_EQ(source->GetOutput()->GetNumberOfCells(), 1);
}
