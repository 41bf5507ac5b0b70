// The algebraic surface source against the polynomial it is given: the cell's field equals f at
// random points (through VTK's own cell evaluation), gallery surfaces up to degree 16, pieces,
// and one clear error for each kind of bad input.
#include "vtkIGAAlgebraicSource.h"

#include "FilterErrors.h"

#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include "iga/AlgebraicGallery.h"
#include "iga/PolynomialExpression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <random>

namespace
{

/// The largest |cell field - f| at 30 random points, relative to the largest |f| there.
double fieldError(vtkUnstructuredGrid* grid, const std::string& expression)
{
  const auto f = iga::parsePolynomial(expression);
  vtkDataArray* values = grid->GetPointData()->GetArray("f");
  vtkNew<vtkGenericCell> cell;
  grid->GetCell(0, cell);
  std::vector<double> weights(size_t(cell->GetNumberOfPoints()));
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst = 0, largest = 0;
  for (int s = 0; s < 30; ++s)
  {
    double pcoords[3] = { unit(rng), unit(rng), unit(rng) }, x[3];
    int subId;
    cell->EvaluateLocation(subId, pcoords, x, weights.data());
    double interpolated = 0;
    for (vtkIdType p = 0; p < cell->GetNumberOfPoints(); ++p)
      interpolated += weights[size_t(p)] * values->GetTuple1(cell->GetPointId(p));
    const double exact = f.evaluate(x[0], x[1], x[2]);
    worst = std::max(worst, std::fabs(interpolated - exact));
    largest = std::max(largest, std::fabs(exact));
  }
  return worst / std::max(largest, 1e-300);
}

TEST(AlgebraicSource, TheCellsFieldIsTheExpression)
{
  vtkNew<vtkIGAAlgebraicSource> source;
  source->SetExpression("x^3*y - 2*z^2 + 0.5");
  source->SetBox(-1, 2, 0.5, 1.5, -3, -1);
  ASSERT_TRUE(igatest::updateCollectingErrors(source).empty());
  vtkUnstructuredGrid* grid = source->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  EXPECT_EQ(grid->GetCellType(0), VTK_BEZIER_HEXAHEDRON);
  EXPECT_EQ(grid->GetNumberOfPoints(), 4 * 2 * 3);
  double bounds[6];
  grid->GetBounds(bounds);
  const double box[6] = { -1, 2, 0.5, 1.5, -3, -1 };
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(bounds[k], box[k], 1e-14);
  EXPECT_LT(fieldError(grid, "x^3*y - 2*z^2 + 0.5"), 1e-12);
}

TEST(AlgebraicSource, GallerySurfacesComeWithTheirBoxes)
{
  ASSERT_EQ(vtkIGAAlgebraicSource::GetNumberOfGallerySurfaces(), 12);
  EXPECT_STREQ(vtkIGAAlgebraicSource::GetGallerySurfaceName(11), "super-sphere");
  EXPECT_EQ(vtkIGAAlgebraicSource::GetGallerySurfaceName(12), nullptr);
  for (const char* name : { "kummer", "heart", "super-sphere" })
  {
    vtkNew<vtkIGAAlgebraicSource> source;
    source->SetGallerySurfaceByName(name);
    ASSERT_TRUE(igatest::updateCollectingErrors(source).empty()) << name;
    const iga::AlgebraicSurface* surface = iga::findAlgebraicSurface(name);
    vtkUnstructuredGrid* grid = source->GetOutput();
    double bounds[6];
    grid->GetBounds(bounds);
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(bounds[k], surface->box[k], 1e-14) << name;
    const auto f = iga::parsePolynomial(surface->expression);
    EXPECT_EQ(grid->GetNumberOfPoints(), (f.degree[0] + 1) * (f.degree[1] + 1) * (f.degree[2] + 1))
      << name;
    if (std::string(name) != "super-sphere") // VTK's cells evaluate up to degree 10
    {
      EXPECT_LT(fieldError(grid, surface->expression), 1e-10) << name;
    }
  }
}

TEST(AlgebraicSource, ThePluginsMenuListsTheGallery)
{
  std::ifstream file(std::string(IGAVIEW_SOURCE_DIR) + "/Plugin/IGAViewSources.xml");
  ASSERT_TRUE(file) << "Plugin/IGAViewSources.xml";
  const std::string xml((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const size_t proxy = xml.find("class=\"vtkIGAAlgebraicSource\"");
  ASSERT_NE(proxy, std::string::npos);
  const std::string entries = xml.substr(proxy, xml.find("</EnumerationDomain>", proxy) - proxy);
  for (int k = 0; k < vtkIGAAlgebraicSource::GetNumberOfGallerySurfaces(); ++k)
  {
    const std::string entry = "<Entry value=\"" + std::to_string(k) + "\" text=\"" +
                              vtkIGAAlgebraicSource::GetGallerySurfaceName(k) + "\" />";
    EXPECT_NE(entries.find(entry), std::string::npos) << entry;
  }
}

TEST(AlgebraicSource, AbsFieldsKeepTheElementsTheSurfaceCrosses)
{
  // The unit sphere on 12^3 cubic elements over [-1.2, 1.2]^3: the elements kept are those the
  // sphere may cross, each with the sphere's field to the spline's accuracy, split over pieces.
  vtkNew<vtkIGAAlgebraicSource> source;
  source->SetSplineCells(12);
  ASSERT_TRUE(igatest::updateCollectingErrors(source).empty());
  const vtkIdType kept = source->GetOutput()->GetNumberOfCells();
  EXPECT_GT(kept, 200);
  EXPECT_LT(kept, 12 * 12 * 12 / 2);
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), kept * 64);
  vtkIdType total = 0;
  for (int piece = 0; piece < 3; ++piece)
  {
    source->UpdatePiece(piece, 3, 0);
    total += source->GetOutput()->GetNumberOfCells();
    EXPECT_NEAR(double(source->GetOutput()->GetNumberOfCells()), kept / 3.0, 1.0);
  }
  EXPECT_EQ(total, kept);
  source->SetSplineDegree(2);
  source->UpdatePiece(0, 1, 0);
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), source->GetOutput()->GetNumberOfCells() * 27);
}

void expectOneError(vtkIGAAlgebraicSource* source, const std::string& message)
{
  const auto errors = igatest::updateCollectingErrors(source);
  ASSERT_EQ(errors.size(), 1u) << message;
  EXPECT_NE(errors[0].find(message), std::string::npos) << errors[0];
  EXPECT_EQ(source->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_NE(source->GetErrorCode(), 0ul) << message;
}

TEST(AlgebraicSource, BadInputIsOneErrorNamingIt)
{
  vtkNew<vtkIGAAlgebraicSource> source;
  source->SetExpression("x + w^2");
  expectOneError(source, "expression, position 5: unknown variable 'w'");
  source->SetExpression("x^9*y^8");
  expectOneError(source, "expression: total degree 17 above 16");
  source->SetExpression("x^2 + y^2 + z^2 - 1");
  source->SetBox(-1, 1, 1, -1, -1, 1);
  expectOneError(source, "box: y from 1.000000 to -1.000000 is not a finite interval");
  source->SetBox(-1, 1, -1, 1, -1, std::nan(""));
  expectOneError(source, "box: z from -1.000000 to nan is not a finite interval");
  source->SetBox(-1, 1, -1, 1, -1, 1);
  source->SetGallerySurface(40);
  expectOneError(source, "GallerySurface 40 is not below the gallery's 12 surfaces");
  source->SetGallerySurface(-1);
  const auto errors = [&]
  {
    std::vector<std::string> collected;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetClientData(&collected);
    onError->SetCallback(
      [](vtkObject*, unsigned long, void* client, void* call) {
        static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call));
      });
    source->AddObserver(vtkCommand::ErrorEvent, onError);
    source->SetGallerySurfaceByName("tea-pot");
    source->RemoveObservers(vtkCommand::ErrorEvent);
    return collected;
  }();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("no gallery surface 'tea-pot' (have: sphere, cayley"), std::string::npos)
    << errors[0];
  EXPECT_EQ(source->GetGallerySurface(), -1);
  ASSERT_TRUE(igatest::updateCollectingErrors(source).empty());
  EXPECT_EQ(source->GetOutput()->GetNumberOfCells(), 1);
  EXPECT_EQ(source->GetErrorCode(), 0ul); // a good setting clears the last error
}

} // namespace
