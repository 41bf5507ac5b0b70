// vtkIGAGismoReader and vtkIGAGeoPDEsReader on the samples in Data/ (analytic shapes), on real
// files from G+Smo and GeoPDEs in ../shared/data (skipped visibly when absent), and on damaged
// files (one error naming file and line, no output).
#include "BoundaryChecks.h"
#include "NurbsTestUtilities.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGADisplaceControlPoints.h"
#include "vtkIGAGeoPDEsReader.h"
#include "vtkIGAGismoReader.h"
#include "vtkIGAMFEMReader.h"
#include "vtkIGANurbsData.h"

#include "vtkBase64Utilities.h"
#include "vtkCallbackCommand.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <unistd.h>

using namespace igatest;

namespace
{

const std::string kData = IGAVIEW_DATA_DIR;
const std::string kShared = IGAVIEW_SHARED_DATA_DIR;

bool exists(const std::string& path)
{
  return std::ifstream(path).good();
}

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs a reader on a file, `configure` called on it first; collects the reader's error
/// messages.
template<class Reader>
vtkSmartPointer<vtkUnstructuredGrid> read(const std::string& file,
  std::vector<std::string>* errors = nullptr, Reader** keep = nullptr, double memoryLimitMB = 0,
  const std::function<void(Reader*)>& configure = {})
{
  static std::vector<std::string> ignored;
  auto reader = vtkSmartPointer<Reader>::New();
  std::vector<std::string>* sink = errors ? errors : &ignored;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(sink);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call)); });
  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->SetFileName(file.c_str());
  reader->SetMemoryLimitMB(memoryLimitMB);
  if (configure)
    configure(reader);
  reader->Update();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->ShallowCopy(reader->GetOutput());
  if (keep)
  {
    *keep = reader;
    reader->Register(nullptr);
  }
  return grid;
}

/// The NURBS a reader holds after reading `file`, and its grid.
template<class Reader>
std::pair<iga::NurbsSet<double>, vtkSmartPointer<vtkUnstructuredGrid>> readNurbs(
  const std::string& file)
{
  Reader* reader = nullptr;
  std::vector<std::string> errors;
  auto grid = read<Reader>(file, &errors, &reader);
  EXPECT_TRUE(errors.empty()) << file << ": " << (errors.empty() ? "" : errors[0]);
  auto set = reader->GetNurbsData()->GetPatches();
  reader->Delete();
  return { set, grid };
}

std::vector<double> at(vtkUnstructuredGrid* grid, vtkIdType cell, double u, double v, double w)
{
  const double pcoords[3] = { u, v, w };
  return evaluateCell(grid, cell, pcoords, iga::geometryAttributeNames());
}

/// The quarter ring samples: radius 1 + v exactly on the rational circle, z = w, "x" = x.
void checkQuarterRing(vtkUnstructuredGrid* grid)
{
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  EXPECT_EQ(grid->GetCellType(0), VTK_BEZIER_HEXAHEDRON);
  double degrees[3];
  grid->GetCellData()->GetHigherOrderDegrees()->GetTuple(0, degrees);
  EXPECT_EQ(degrees[0], 2);
  EXPECT_EQ(degrees[1], 1);
  EXPECT_EQ(degrees[2], 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 50; ++s)
  {
    const double u = unit(rng), v = unit(rng), w = unit(rng);
    const auto value = at(grid, 0, u, v, w);
    EXPECT_NEAR(std::hypot(value[0], value[1]), 1 + v, 1e-13);
    EXPECT_NEAR(value[2], w, 1e-13);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(value[3 + c], value[c], 1e-13) << "attribute " << c << " is the coordinate";
  }
}

TEST(NurbsReaders, EachReaderKnowsItsOwnFormat)
{
  vtkNew<vtkIGAGismoReader> gismo;
  vtkNew<vtkIGAGeoPDEsReader> geopdes;
  const std::string xml = kData + "/gismo_quarter_ring.xml",
                    txt = kData + "/geopdes_quarter_ring.txt";
  EXPECT_EQ(gismo->CanReadFile(xml.c_str()), 1);
  EXPECT_EQ(geopdes->CanReadFile(txt.c_str()), 1);
  EXPECT_EQ(gismo->CanReadFile(txt.c_str()), 0);
  EXPECT_EQ(geopdes->CanReadFile(xml.c_str()), 0);
  EXPECT_EQ(gismo->CanReadFile((kData + "/CMakeLists.txt").c_str()), 0);
  EXPECT_EQ(gismo->CanReadFile("/nonexistent.xml"), 0);
  EXPECT_EQ(gismo->CanReadFile(nullptr), 0);
  vtkNew<vtkIGAMFEMReader> mfem;
  const std::string mesh = kData + "/mfem_quarter_ring.mesh";
  EXPECT_EQ(mfem->CanReadFile(mesh.c_str()), 1);
  EXPECT_EQ(mfem->CanReadFile(txt.c_str()), 0);
  EXPECT_EQ(gismo->CanReadFile(mesh.c_str()), 0);
  EXPECT_EQ(geopdes->CanReadFile(mesh.c_str()), 0);
}

TEST(NurbsReaders, GismoQuarterRing)
{
  checkQuarterRing(read<vtkIGAGismoReader>(kData + "/gismo_quarter_ring.xml"));
}

TEST(NurbsReaders, GeoPDEsQuarterRingEqualsTheGismoOne)
{
  const auto geopdes = read<vtkIGAGeoPDEsReader>(kData + "/geopdes_quarter_ring.txt");
  checkQuarterRing(geopdes);
  const auto gismo = read<vtkIGAGismoReader>(kData + "/gismo_quarter_ring.xml");
  ASSERT_EQ(geopdes->GetNumberOfPoints(), gismo->GetNumberOfPoints());
  for (vtkIdType p = 0; p < gismo->GetNumberOfPoints(); ++p)
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(geopdes->GetPoint(p)[d], gismo->GetPoint(p)[d], 1e-15);
}

TEST(NurbsReaders, GismoMultiPatchReadsItsPatchesOnly)
{
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(kData + "/gismo_two_blocks.xml");
  ASSERT_EQ(set.volumes.size(), 2u);
  EXPECT_TRUE(set.surfaces.empty()) << "geometry 12 is outside the MultiPatch";
  ASSERT_EQ(grid->GetNumberOfCells(), 3); // 2 knot spans + 1
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 30; ++s)
  {
    // Block 10 is polynomial with Greville control x: parameter_u = x = u exactly.
    const double t = unit(rng);
    const int cell = s % 2;
    const auto value = at(grid, cell, t, unit(rng), unit(rng));
    EXPECT_NEAR(value[0], 0.5 * (cell + t), 1e-14);
    EXPECT_NEAR(value[6], value[0], 1e-14) << "parameter_u";
    // Block 11: z rises to 1.5 at x = 2 on its top face.
    const auto top = at(grid, 2, t, unit(rng), 1.0);
    EXPECT_NEAR(top[2], 1 + 0.5 * (top[0] - 1), 1e-14);
  }
  compareWithCoxDeBoor(set, grid, rng, 20);
}

TEST(NurbsReaders, GismoSurfaceIsABezierQuadrilateral)
{
  const auto grid = read<vtkIGAGismoReader>(kData + "/gismo_quarter_cylinder_surface.xml");
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  EXPECT_EQ(grid->GetCellType(0), VTK_BEZIER_QUADRILATERAL);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 30; ++s)
  {
    const double u = unit(rng), v = unit(rng);
    const auto value = at(grid, 0, u, v, 0);
    EXPECT_NEAR(std::hypot(value[0], value[1]), 1.0, 1e-14);
    EXPECT_NEAR(value[2], 2 * v, 1e-14);
    EXPECT_EQ(value[8], 0.0) << "parameter_w of a surface";
  }
}

TEST(NurbsReaders, GeoPDEsVersion07MultipatchWithSections)
{
  const auto [set, grid] = readNurbs<vtkIGAGeoPDEsReader>(kData + "/geopdes_two_cubes_v07.txt");
  ASSERT_EQ(set.volumes.size(), 2u);
  ASSERT_EQ(grid->GetNumberOfCells(), 2);
  double bounds[6];
  grid->GetBounds(bounds);
  EXPECT_EQ(bounds[0], 0.0);
  EXPECT_EQ(bounds[1], 2.0);
  EXPECT_EQ(bounds[5], 1.0);
  std::mt19937 rng(6);
  compareWithCoxDeBoor(set, grid, rng, 20);
}

#define REQUIRE_SHARED(path)                                                                       \
  if (!exists(path))                                                                               \
  GTEST_SKIP() << "real file " << path << " is absent (../shared/data not available)"

TEST(NurbsReadersRealFiles, GismoQuarterCylinder)
{
  const std::string file = kShared + "/gismo/quarter_cylinder.xml";
  REQUIRE_SHARED(file);
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
  ASSERT_EQ(set.volumes.size(), 1u);
  const auto& patch = set.volumes[0];
  EXPECT_EQ(patch.degree[0], 2);
  EXPECT_EQ(patch.degree[1], 2);
  EXPECT_EQ(patch.degree[2], 1);
  EXPECT_EQ(patch.net[patch.channels + iga::kWeightChannel], 0.7071067812); // written weight
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  // Radii 1, 1.5, 2 along v (so r = 1 + v), height 5 along w.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 50; ++s)
  {
    const double u = unit(rng), v = unit(rng), w = unit(rng);
    const auto value = at(grid, 0, u, v, w);
    EXPECT_NEAR(std::hypot(value[0], value[1]), 1 + v, 1e-9); // 10-digit weight in the file
    EXPECT_NEAR(value[2], 5 * w, 1e-12);
  }
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 50), 1e-12);
}

TEST(NurbsReadersRealFiles, GismoTwistedPipeWithRepeatedKnot)
{
  const std::string file = kShared + "/gismo/twisted_pipe.xml";
  REQUIRE_SHARED(file);
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
  ASSERT_EQ(set.volumes.size(), 1u);
  EXPECT_EQ(set.volumes[0].netSize[0], 10);
  // Spans: 6 along u (0.3333333 and 0.6666667 repeated), 2 and 2.
  EXPECT_EQ(grid->GetNumberOfCells(), 24);
  std::mt19937 rng(8);
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 100), 1e-12);
}

TEST(NurbsReadersRealFiles, GismoGshapedVolume)
{
  const std::string file = kShared + "/gismo/GshapedVolume.xml";
  REQUIRE_SHARED(file);
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
  ASSERT_EQ(set.volumes.size(), 1u);
  EXPECT_EQ(grid->GetNumberOfCells(), 7);
  double bounds[6];
  grid->GetBounds(bounds);
  EXPECT_EQ(bounds[4], 0.0);
  EXPECT_EQ(bounds[5], 1.0);
  std::mt19937 rng(9);
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 100), 1e-12);
}

TEST(NurbsReadersRealFiles, GismoTeapotSurfaces)
{
  const std::string file = kShared + "/gismo/teapot.xml";
  REQUIRE_SHARED(file);
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
  EXPECT_TRUE(set.volumes.empty());
  ASSERT_EQ(set.surfaces.size(), 32u);
  ASSERT_EQ(grid->GetNumberOfCells(), 32);
  for (vtkIdType c = 0; c < 32; ++c)
  {
    EXPECT_EQ(grid->GetCellType(c), VTK_BEZIER_QUADRILATERAL);
    EXPECT_EQ(grid->GetCellData()->GetHigherOrderDegrees()->GetComponent(c, 0), 3);
  }
  // Patch 0's corner (u, v) = (0, 0) is its first control point, (1.4, 0, 2.4).
  const auto corner = at(grid, 0, 0, 0, 0);
  EXPECT_NEAR(corner[0], 1.4, 1e-15);
  EXPECT_NEAR(corner[2], 2.4, 1e-15);
  std::mt19937 rng(10);
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 10), 1e-12);
}

TEST(NurbsReadersRealFiles, GeoPDEsTwoCubesVersion21)
{
  const std::string file = kShared + "/geopdes/geo_2cubesb.txt";
  REQUIRE_SHARED(file);
  const auto [set, grid] = readNurbs<vtkIGAGeoPDEsReader>(file);
  ASSERT_EQ(set.volumes.size(), 2u);
  EXPECT_EQ(grid->GetNumberOfCells(), 4); // knot 0.4 splits v of patch 1 and w of patch 2
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto cells = cellsBySpan(grid);
  for (int s = 0; s < 30; ++s)
  {
    // Patch 1: x = 0.5 u (control 0, 0.25, 0.5), z = w; patch 2: x = 0.5 + 0.5 u in the file,
    // which is left-handed there and so read with u reversed.
    const double u = unit(rng), v = unit(rng), w = unit(rng);
    const auto one = at(grid, cells.at({ 0, 0, s % 2, 0 }), u, v, w);
    EXPECT_NEAR(one[0], 0.5 * u, 1e-14);
    EXPECT_NEAR(one[2], w, 1e-14);
    const auto two = at(grid, cells.at({ 1, 0, 0, s % 2 }), u, v, w);
    EXPECT_NEAR(two[0], 1 - 0.5 * u, 1e-14);
  }
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 100), 1e-12);
}

/// The boundary faces (iga/Boundary.h) of the real volume files' Bézier cells: as many as their
/// element grids have outer element faces (the two cubes meet conformingly: 4 of their cells'
/// 24 faces are inner, 4 more on the interface), and they close up: every edge of one is an
/// edge of exactly one other.
TEST(NurbsReadersRealFiles, VolumeBoundariesAreClosed)
{
  for (const auto& [path, faces] : std::vector<std::pair<std::string, size_t>>{
         { "/gismo/quarter_cylinder.xml", 6 }, // 1 x 1 x 1 elements
         { "/gismo/twisted_pipe.xml", 56 },    // 6 x 2 x 2
         { "/gismo/GshapedVolume.xml", 30 },   // 7 x 1 x 1
         { "/geopdes/geo_2cubesb.txt", 16 } }) // 2 patches of 2
  {
    const std::string file = kShared + path;
    REQUIRE_SHARED(file);
    vtkSmartPointer<vtkUnstructuredGrid> grid = path.find("geopdes") != std::string::npos
                                                  ? readNurbs<vtkIGAGeoPDEsReader>(file).second
                                                  : readNurbs<vtkIGAGismoReader>(file).second;
    iga::VolumeSet<double> set;
    std::string error;
    std::vector<std::string> warnings;
    ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, set, error, warnings)) << error;
    const auto boundary = iga::boundaryFaces(set.patches);
    EXPECT_EQ(boundary.size(), faces) << path;
    EXPECT_EQ(igatest::openBoundaryEdges(set.patches, boundary), 0u) << path;
  }
}

/// Writes `text` to a temporary file and reads it; expects one error that names the file and
/// contains `expected`, and no cells.
template<class Reader>
void expectError(const std::string& name, const std::string& text, const std::string& expected)
{
  const std::string file = testing::TempDir() + "/" + name;
  std::ofstream(file, std::ios::binary) << text;
  std::vector<std::string> errors;
  const auto grid = read<Reader>(file, &errors);
  ASSERT_EQ(errors.size(), 1u) << name;
  EXPECT_NE(errors[0].find(file + ":"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find(expected), std::string::npos) << "got: " << errors[0];
  EXPECT_EQ(grid->GetNumberOfCells(), 0);
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// G+Smo reads files whose XML declaration follows a comment (its filedata/volumes/fichera.xml),
// which XML itself does not allow: read alike, with errors on the lines where they are.
TEST(NurbsReaders, GismoDeclarationAfterACommentIsRead)
{
  const std::string good = slurp(kData + "/gismo_quarter_ring.xml");
  ASSERT_EQ(good.rfind("<?xml ", 0), 0u);
  const std::string commentFirst = "<!-- a comment first, as G+Smo writes some -->\n  " + good;
  const std::string file = testing::TempDir() + "/comment-first.xml";
  std::ofstream(file, std::ios::binary) << commentFirst;
  const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
  checkQuarterRing(grid);
  const auto [reference, referenceGrid] =
    readNurbs<vtkIGAGismoReader>(kData + "/gismo_quarter_ring.xml");
  ASSERT_EQ(set.volumes.size(), 1u);
  EXPECT_EQ(set.volumes[0].net, reference.volumes[0].net);
  expectError<vtkIGAGismoReader>("comment-first-count.xml",
    replaced(commentFirst, "   0 2 1\n", "   0 2\n"), ":21: <coefs> has 35 values, expected 36");
  // A second declaration, or one after an element, stays an error; so does a late one that
  // names another encoding than UTF-8 or holds markup.
  expectError<vtkIGAGismoReader>(
    "declaration-twice.xml", "<?xml version=\"1.0\"?>\n" + commentFirst, ":3: not well-formed XML");
  for (const auto& [from, to] :
    { std::pair<std::string, std::string>{ "encoding=\"UTF-8\"", "encoding=\"ISO-8859-1\"" },
      { "<?xml version=\"1.0\"", "<?xml version=\"1.0\" <xml>" } })
  {
    expectError<vtkIGAGismoReader>("declaration-kept.xml", replaced(commentFirst, from, to),
      ":2: not well-formed XML (column 2): XML or text declaration not at start of entity");
  }
}

TEST(NurbsReaders, DamagedGismoFilesGiveOneError)
{
  const std::string good = slurp(kData + "/gismo_quarter_ring.xml");
  using R = vtkIGAGismoReader;
  const std::string truncated = good.substr(0, good.size() / 2);
  const auto lastLine = std::count(truncated.begin(), truncated.end(), '\n') + 1;
  expectError<R>(
    "truncated.xml", truncated, ":" + std::to_string(lastLine) + ": not well-formed XML");
  expectError<R>("count.xml", replaced(good, "   0 2 1\n", "   0 2\n"),
    ":20: <coefs> has 35 values, expected 36");
  expectError<R>("knots.xml", replaced(good, "0 0 1 1</KnotVector>", "0 1 0 1</KnotVector>"),
    ":12: <KnotVector> (direction 1): knots are not non-decreasing at index 2");
  expectError<R>("weight.xml", replaced(good, "<weights>1 ", "<weights>-1 "),
    ":18: <weights> weight 1 is -1.000000, weights must be positive");
  expectError<R>("nan.xml", replaced(good, "   1 1 0\n", "   1 nan 0\n"),
    ":20: <coefs> value 5 'nan' is not finite");
  expectError<R>("type.xml", replaced(good, "TensorNurbs3\"", "THBSpline3\""),
    ":5: <Geometry> type 'THBSpline3' is not supported");
  expectError<R>("degree.xml", replaced(good, "degree=\"2\"", "degree=\"x\""),
    ":9: <KnotVector> needs an integer attribute degree");
  expectError<R>("empty.xml", "<xml></xml>", "has no <Geometry> or <MultiPatch> element");
  const std::string blocks = slurp(kData + "/gismo_two_blocks.xml");
  expectError<R>("ids.xml", replaced(blocks, "10 11</patches>", "10 13</patches>"),
    ":72: <patches> refers to geometry id 13, which no top-level <Geometry> has");
  // Found by the fuzzer: an id beyond 64-bit integers was converted to one (undefined).
  expectError<R>("huge-id.xml", replaced(blocks, "10 11</patches>", "10 1e308</patches>"),
    ":72: <patches> id 1e+308 is not an integer in -2^53..2^53");
  // Nested deeper than any G+Smo file: refused before the parser's tree (built and destroyed
  // recursively) could overflow the stack.
  std::string deep = "<xml>";
  for (int level = 0; level < 30000; ++level)
    deep += "<a>";
  for (int level = 0; level < 30000; ++level)
    deep += "</a>";
  expectError<R>("deep.xml", deep + "</xml>", "elements are nested more than 256 levels deep");
  std::vector<std::string> errors;
  const std::string missing = testing::TempDir() + "/no_such_file.xml";
  read<R>(missing, &errors);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("cannot open '" + missing + "'"), std::string::npos) << errors[0];
}

/// A GeoPDEs block of degree 16 in each direction, n control points each (open uniform knots).
std::string degree16Block(int n)
{
  std::ostringstream text;
  text << "# nurbs geometry v.2.1\n3 3 1\nPATCH 1\n16 16 16\n" << n << " " << n << " " << n << "\n";
  for (int d = 0; d < 3; ++d)
  {
    for (int k = 0; k <= 16; ++k)
      text << "0 ";
    for (int k = 1; k < n - 16; ++k)
      text << double(k) / (n - 16) << " ";
    for (int k = 0; k <= 16; ++k)
      text << "1 ";
    text << "\n";
  }
  for (int d = 0; d < 3; ++d)
  {
    for (int p = 0; p < n * n * n; ++p)
      text << (d == 0 ? p % n : d == 1 ? (p / n) % n : p / (n * n)) << " ";
    text << "\n";
  }
  for (int p = 0; p < n * n * n; ++p)
    text << "1 ";
  return text.str() + "\n";
}

/// 76 KB of degree-16 NURBS expand to 28 MB of Bézier cells (54 MB with the copy their
/// attribute ranges are found on): a file whose cells exceed MemoryLimitMB is refused with the
/// size, before any is built.
TEST(NurbsReaders, CellsBeyondTheMemoryLimitAreRefused)
{
  const std::string file = testing::TempDir() + "/degree16.txt";
  std::ofstream(file) << degree16Block(20);
  std::vector<std::string> errors;
  const auto refused = read<vtkIGAGeoPDEsReader>(file, &errors, nullptr, 10);
  ASSERT_EQ(errors.size(), 1u);
  // 64 cells of 17^3 points, 88 bytes each: the grid's 10 channels (coordinates, weight, the
  // six geometric attributes) and a connectivity entry (elements are extracted one at a time);
  // 80 more for the attribute ranges' copy of the cells' coefficients; and the grid's copy of
  // the 20^3-point net.
  EXPECT_NE(errors[0].find(file + ": its 64 Bézier cells would need 0.0535 GB to build, more "
                                  "than the reader's memory limit of 0.0105 GB (MemoryLimitMB)"),
    std::string::npos)
    << errors[0];
  EXPECT_EQ(refused->GetNumberOfCells(), 0);
  errors.clear();
  const auto built = read<vtkIGAGeoPDEsReader>(file, &errors, nullptr, 100);
  EXPECT_EQ(built->GetNumberOfCells(), 64);
  EXPECT_TRUE(errors.empty());
  // The estimate is the grid's own size (VTK's count, in KiB) within a few percent.
  EXPECT_NEAR(double(built->GetActualMemorySize()) * 1024, 0.0283e9, 0.05 * 0.0283e9);
}

/// A file is read whole before it is parsed: one larger than the memory limit is refused unread
/// (a sparse file of 4 GB here; a file of that many zeros used to be read until memory ran out).
TEST(NurbsReaders, FilesBeyondTheMemoryLimitAreRefusedUnread)
{
  const std::string file = testing::TempDir() + "/igaview_huge.xml";
  std::ofstream(file) << "<?xml version=\"1.0\"?>\n<xml>\n<Geometry type=\"TensorNurbs3\">\n";
  ASSERT_EQ(truncate(file.c_str(), off_t(4) << 30), 0);
  std::vector<std::string> errors;
  read<vtkIGAGismoReader>(file, &errors, nullptr, 100);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find(file + ": the file holds 4.29 GB, more than the reader's memory limit "
                                  "of 0.105 GB (MemoryLimitMB)"),
    std::string::npos)
    << errors[0];
  std::remove(file.c_str());
}

TEST(NurbsReaders, DamagedGeoPDEsFilesGiveOneError)
{
  const std::string good = slurp(kData + "/geopdes_quarter_ring.txt");
  using R = vtkIGAGeoPDEsReader;
  expectError<R>("truncated.txt", good.substr(0, good.find("0 0 0 1 1 1")),
    ":7: the file ends where knot vector 1 should follow");
  expectError<R>(
    "count.txt", replaced(good, "3 2 2\n", "3 2 3\n"), ":10: knot vector 3: 4 values, expected 5");
  expectError<R>("knots.txt", replaced(good, "0 0 0 1 1 1", "0 0 1 0 1 1"),
    ":8: knot vector 1: knots are not non-decreasing at index 3");
  expectError<R>("weight.txt", replaced(good, "\n1 0.70710678118654757 1 1", "\n1 0 1 1"),
    ":14: weights: weight 2 is 0.000000, weights must be positive");
  expectError<R>("nan.txt", replaced(good, "3 3 1\nPATCH 1\n2 1 1", "3 3 1\nPATCH 1\n2 nan 1"),
    ":6: degrees: '2 nan 1' is not a line of finite numbers");
  expectError<R>("dimension.txt", replaced(good, "3 3 1\n", "1 3 1\n"),
    ":4: header: parametric dimension 1 in physical dimension 3 is not supported");
  expectError<R>("patch.txt", good + "PATCH 2\n",
    ":15: 'PATCH 2' follows where boundaries do: more patches than the header's 1");
  expectError<R>("junk.txt", good + "JUNK 1\n", "the file ends where number of boundary sides");
  expectError<R>("version.txt", replaced(good, "v.2.1", "v.99999999999.1"),
    ":1: 'nurbs geometry v.9999999...' names no GeoPDEs version");
  // A hundred thousand digits: a regex over them overflowed the stack.
  expectError<R>("long-version.txt", replaced(good, "v.2.1", "v." + std::string(100000, '7')),
    ":1: 'nurbs geometry v.7777777...' names no GeoPDEs version");
  const std::string cubes = slurp(kData + "/geopdes_two_cubes_v07.txt");
  expectError<R>("interfaces.txt", replaced(cubes, "3 2 1 1\n", "3 2 2 1\n"),
    "'SUBDOMAIN 1': the header announces 2 interfaces, the file has 1");
  expectError<R>("subdomains.txt", replaced(cubes, "3 2 1 1\n", "3 2 1 2\n"),
    "'BOUNDARY 1': the header announces 2 subdomains, the file has 1");
  expectError<R>("more-interfaces.txt", replaced(cubes, "3 2 1 1\n", "3 2 0 0\n"),
    "'INTERFACE 1' follows where boundaries do: more interfaces than the header's 0");
  expectError<R>("side.txt", replaced(cubes, "1 2\n2 1\n1 1 1", "1 2\n3 1\n1 1 1"),
    "interface side: patch 3 side 1 does not exist");
  expectError<R>("more-patches.txt", replaced(cubes, "3 2 1 1\n", "3 1 1 1\n"),
    ":16: 'PATCH 2' follows where interfaces do: more patches than the header's 1");
  expectError<R>("more-interfaces-than-subdomains.txt", replaced(cubes, "3 2 1 1\n", "3 2 0 1\n"),
    ":26: 'INTERFACE 1' follows where subdomains do: more interfaces than the header's 0");
}

// GeoPDEs reads its sections by the header's counts, their names free text: its own
// multipatch/geo_fichera.txt names a boundary "EXTERNAL BOUNDARY".
TEST(NurbsReaders, GeoPDEsSectionNamesAreFreeText)
{
  const std::string cubes = slurp(kData + "/geopdes_two_cubes_v07.txt");
  const std::string renamed =
    replaced(replaced(replaced(cubes, "BOUNDARY 1\n", "EXTERNAL BOUNDARY\n"), "INTERFACE 1\n",
               "the middle face\n"),
      "SUBDOMAIN 1\n", "both cubes\n");
  const std::string file = testing::TempDir() + "/renamed-sections.txt";
  std::ofstream(file, std::ios::binary) << renamed;
  const auto [set, grid] = readNurbs<vtkIGAGeoPDEsReader>(file);
  const auto [reference, referenceGrid] =
    readNurbs<vtkIGAGeoPDEsReader>(kData + "/geopdes_two_cubes_v07.txt");
  ASSERT_EQ(set.volumes.size(), 2u);
  EXPECT_EQ(set.volumes[1].net, reference.volumes[1].net);
  EXPECT_EQ(grid->GetNumberOfCells(), 2);
}

/// `xml` with the numbers of every <KnotVector>, <weights> and <coefs> written as G+Smo's binary
/// output writes them: base64 of little-endian doubles (floats), the element marked
/// format="FORMAT".
std::string inBase64(const std::string& xml, const std::string& format, bool floats)
{
  const std::regex element("<(KnotVector|weights|coefs)([^>]*)>([^<]*)</");
  std::string out;
  auto last = xml.cbegin();
  for (std::sregex_iterator m(xml.begin(), xml.end(), element), end; m != end; ++m)
  {
    std::istringstream in((*m)[3].str());
    std::vector<unsigned char> bytes;
    for (double value; in >> value;)
    {
      const float single = float(value);
      const auto* raw = floats ? reinterpret_cast<const unsigned char*>(&single)
                               : reinterpret_cast<const unsigned char*>(&value);
      bytes.insert(bytes.end(), raw, raw + (floats ? 4 : 8));
    }
    std::vector<unsigned char> text(bytes.size() * 2 + 4);
    text.resize(vtkBase64Utilities::Encode(bytes.data(), bytes.size(), text.data()));
    out.append(last, (*m)[0].first);
    out += "<" + (*m)[1].str() + (*m)[2].str() + " format=\"" + format + "\">\n" +
           std::string(text.begin(), text.end()) + "\n</";
    last = (*m)[0].second;
  }
  return out.append(last, xml.cend());
}

// G+Smo writes numbers as base64 when asked for binary output (its
// filedata/pde/poisson2d_bvp_bin.xml): read as the decimal text they encode.
TEST(NurbsReaders, GismoBase64NumbersAreRead)
{
  const std::string good = slurp(kData + "/gismo_quarter_ring.xml");
  const auto [reference, referenceGrid] =
    readNurbs<vtkIGAGismoReader>(kData + "/gismo_quarter_ring.xml");
  for (const bool floats : { false, true })
  {
    const std::string format = floats ? "B64Float32" : "B64Float64";
    const std::string file = testing::TempDir() + "/base64-" + format + ".xml";
    std::ofstream(file, std::ios::binary) << inBase64(good, format, floats);
    const auto [set, grid] = readNurbs<vtkIGAGismoReader>(file);
    ASSERT_EQ(set.volumes.size(), 1u) << format;
    ASSERT_EQ(set.volumes[0].net.size(), reference.volumes[0].net.size());
    for (size_t k = 0; k < set.volumes[0].net.size(); ++k)
      EXPECT_NEAR(set.volumes[0].net[k], reference.volumes[0].net[k], floats ? 1e-7 : 0.0) << k;
    if (!floats)
      checkQuarterRing(grid);
  }
  const std::string encoded = inBase64(good, "b64float64", false);
  using R = vtkIGAGismoReader;
  expectError<R>("base64-junk.xml",
    replaced(encoded, "<weights format=\"b64float64\">\n", "<weights format=\"b64float64\">\n*"),
    ":24: <weights> format 'b64float64': the text is not base64 of doubles");
  expectError<R>("base64-int.xml",
    replaced(encoded, "<weights format=\"b64float64\">", "<weights format=\"b64int32\">"),
    ":24: <weights> format 'b64int32' is not supported (ascii, b64float64, b64float32)");
  const size_t weights = encoded.find("<weights format=\"b64float64\">\n") + 29;
  expectError<R>("base64-empty.xml",
    encoded.substr(0, weights) + encoded.substr(encoded.find("</weights>")),
    ":24: <weights> has 0 values, expected 12 (one per control point)");
}

} // namespace

// G+Smo solutions: a MultiPatch per field in the geometry's basis, as G+Smo writes them.
TEST(NurbsReaders, GismoSolutionFieldsAreAttributes)
{
  const auto grid = read<vtkIGAGismoReader>(kData + "/gismo_quarter_ring_solution.xml");
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  const std::vector<std::string> fields = { "temperature", "displacement_0", "displacement_1",
    "displacement_2" };
  for (const auto& name : fields)
    ASSERT_NE(grid->GetPointData()->GetArray(name.c_str()), nullptr) << name;
  vtkDataArray* vector = grid->GetPointData()->GetArray("displacement");
  ASSERT_NE(vector, nullptr);
  ASSERT_EQ(vector->GetNumberOfComponents(), 3);
  // The vector moves the control points a quarter turn's worth: the cells then hold x + (-y, x, 0).
  vtkNew<vtkIGADisplaceControlPoints> displace;
  displace->SetInputData(grid);
  displace->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "displacement");
  displace->Update();
  vtkUnstructuredGrid* moved = displace->GetOutput();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 50; ++s)
  {
    const double pcoords[3] = { unit(rng), unit(rng), unit(rng) };
    const auto value = evaluateCell(grid, 0, pcoords, fields);
    EXPECT_NEAR(value[3], value[0] - 2 * value[2], 1e-13);
    EXPECT_NEAR(value[4], -value[1], 1e-13);
    EXPECT_NEAR(value[5], value[0], 1e-13);
    EXPECT_NEAR(value[6], 0.0, 1e-13);
    const auto after = evaluateCell(moved, 0, pcoords, {});
    EXPECT_NEAR(after[0], value[0] - value[1], 1e-13);
    EXPECT_NEAR(after[1], value[1] + value[0], 1e-13);
    EXPECT_NEAR(after[2], value[2], 1e-13);
  }
}

TEST(NurbsReaders, GismoFieldsOutsideTheGeometrysBasisGiveOneError)
{
  const std::string file = slurp(kData + "/gismo_quarter_ring_solution.xml");
  // The temperature's patch (the second Geometry) with weights 1, as a B-spline field on the
  // NURBS ring would have, or another knot vector: not the geometry's basis.
  const size_t second = file.find("<Geometry", file.find("<Geometry") + 1);
  const std::string head = file.substr(0, second), tail = file.substr(second);
  const std::string weights = "1 0.70710678118654757 1 1 0.70710678118654757 1 1 "
                              "0.70710678118654757 1 1 0.70710678118654757 1";
  expectError<vtkIGAGismoReader>("weights-field.xml",
    head + replaced(tail, weights, "1 1 1 1 1 1 1 1 1 1 1 1"),
    "a field patch whose weights are not its geometry patch's (control point 2)");
  expectError<vtkIGAGismoReader>("knots-field.xml",
    head + replaced(tail, "0 0 0 1 1 1", "0 0 0 2 2 2"),
    "a field patch whose basis is not its geometry patch's (direction 0)");
  expectError<vtkIGAGismoReader>("count-field.xml",
    replaced(
      file, "<patches type=\"id_range\">2 2</patches>", "<patches type=\"id_index\">2 4</patches>"),
    "has 2 patches, the geometry 1: a field has one patch per geometry patch");
}

// MFEM: the quarter ring of Data/ (hand-written in both of MFEM's forms) with fields known
// exactly, MFEM's own exact unit ball (faces shared in every orientation), MFEM's files in
// ../shared/data, and damaged files.

/// The MFEM quarter ring with its GridFunctions: radius 1 + v on the exact arcs, z = w,
/// pressure = 3x - 2z + 1 and position = (x, y, z) wherever evaluated.
TEST(NurbsReaders, MFEMQuarterRingWithItsFields)
{
  std::vector<std::string> errors;
  const auto grid = read<vtkIGAMFEMReader>(kData + "/mfem_quarter_ring.mesh", &errors, nullptr, 0,
    [](vtkIGAMFEMReader* reader)
    {
      reader->AddGridFunctionFileName((kData + "/mfem_quarter_ring_pressure.gf").c_str());
      reader->AddGridFunctionFileName((kData + "/mfem_quarter_ring_position.gf").c_str());
    });
  ASSERT_TRUE(errors.empty()) << errors[0];
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  // Named after the files.
  const std::string stem = "mfem_quarter_ring_";
  const std::vector<std::string> fields = { stem + "pressure", stem + "position_0",
    stem + "position_1", stem + "position_2" };
  for (const auto& name : fields)
    ASSERT_NE(grid->GetPointData()->GetArray(name.c_str()), nullptr) << name;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int s = 0; s < 50; ++s)
  {
    const double pcoords[3] = { unit(rng), unit(rng), unit(rng) };
    const auto value = evaluateCell(grid, 0, pcoords, fields);
    EXPECT_NEAR(std::hypot(value[0], value[1]), 1 + pcoords[1], 1e-13);
    EXPECT_NEAR(value[2], pcoords[2], 1e-13);
    EXPECT_NEAR(value[3], 3 * value[0] - 2 * value[2] + 1, 1e-12);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(value[4 + c], value[c], 1e-13);
  }
}

TEST(NurbsReaders, MFEMPatchesFormEqualsTheTopologyForm)
{
  const auto topology = readNurbs<vtkIGAMFEMReader>(kData + "/mfem_quarter_ring.mesh").first;
  const auto patches = readNurbs<vtkIGAMFEMReader>(kData + "/mfem_quarter_ring_patches.mesh").first;
  ASSERT_EQ(topology.volumes.size(), 1u);
  ASSERT_EQ(patches.volumes.size(), 1u);
  const auto& a = topology.volumes[0].net;
  const auto& b = patches.volumes[0].net;
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    EXPECT_NEAR(a[k], b[k], 1e-15) << k;
}

/// MFEM's data/ball-nurbs.mesh: 7 patches of degree 4 (a cube and six shells), every face
/// interior shared by two patches in its own orientation. The boundary is the unit sphere and
/// closes up; the inner faces match (else they would be boundary too).
TEST(NurbsReaders, MFEMExactUnitBall)
{
  const std::string file = std::string(IGAVIEW_SOURCE_DIR) + "/Testing/Data/mfem/ball-nurbs.mesh";
  const auto grid = readNurbs<vtkIGAMFEMReader>(file).second;
  ASSERT_EQ(grid->GetNumberOfCells(), 7);
  iga::VolumeSet<double> set;
  std::string error;
  std::vector<std::string> warnings;
  ASSERT_TRUE(vtkIGABezierHexahedra::FromUnstructuredGrid(grid, set, error, warnings)) << error;
  const auto boundary = iga::boundaryFaces(set.patches);
  ASSERT_EQ(boundary.size(), 6u);
  EXPECT_EQ(igatest::openBoundaryEdges(set.patches, boundary), 0u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst = 0;
  for (const auto& face : boundary)
    for (int s = 0; s < 40; ++s)
    {
      double pcoords[3] = { unit(rng), unit(rng), unit(rng) };
      pcoords[face.direction] = face.side;
      const auto x = evaluateCell(grid, face.patch, pcoords, {});
      worst = std::max(worst, std::abs(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1));
    }
  EXPECT_LT(worst, 1e-13);
}

/// MFEM's data/disc-nurbs.mesh: 5 quadrilateral patches (a square and four around it) whose
/// outer sides lie on the circle of radius 2 sqrt(2), exactly.
TEST(NurbsReaders, MFEMDiscOfQuadrilaterals)
{
  const std::string file = std::string(IGAVIEW_SOURCE_DIR) + "/Testing/Data/mfem/disc-nurbs.mesh";
  const auto grid = readNurbs<vtkIGAMFEMReader>(file).second;
  ASSERT_EQ(grid->GetNumberOfCells(), 5);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  int onCircle = 0;
  for (vtkIdType c = 0; c < 5; ++c)
  {
    EXPECT_EQ(grid->GetCellType(c), VTK_BEZIER_QUADRILATERAL);
    for (int side = 0; side < 4; ++side)
    {
      double worst = 0;
      for (int s = 0; s < 20; ++s)
      {
        double pcoords[3] = { unit(rng), unit(rng), 0 };
        pcoords[side / 2] = side % 2;
        const auto x = evaluateCell(grid, c, pcoords, {});
        worst = std::max(worst, std::abs(std::hypot(x[0], x[1]) - 2 * std::sqrt(2.0)));
      }
      onCircle += worst < 1e-13 ? 1 : 0;
    }
  }
  EXPECT_EQ(onCircle, 4);
}

TEST(NurbsReadersRealFiles, MFEMCubeBeamAndCurves)
{
  const std::string cube = kShared + "/mfem/cube-nurbs.mesh",
                    beam = kShared + "/mfem/beam-hex-nurbs.mesh",
                    curves = kShared + "/mfem/nurbs-segments3d-patches.mesh";
  REQUIRE_SHARED(cube);
  double bounds[6];
  readNurbs<vtkIGAMFEMReader>(cube).second->GetBounds(bounds);
  EXPECT_EQ(std::vector<double>(bounds, bounds + 6), std::vector<double>({ 0, 1, 0, 1, 0, 1 }));
  const auto [set, grid] = readNurbs<vtkIGAMFEMReader>(beam);
  EXPECT_EQ(set.volumes.size(), 2u);
  EXPECT_EQ(grid->GetNumberOfCells(), 8); // 4 elements along each patch
  grid->GetBounds(bounds);
  EXPECT_EQ(std::vector<double>(bounds, bounds + 6), std::vector<double>({ 0, 8, 0, 1, 0, 1 }));
  std::mt19937 rng(13);
  EXPECT_LT(compareWithCoxDeBoor(set, grid, rng, 100), 1e-12);
  std::vector<std::string> errors;
  EXPECT_EQ(read<vtkIGAMFEMReader>(curves, &errors)->GetNumberOfCells(), 0);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find(":12: dimension 1: NURBS curves are not drawn"), std::string::npos)
    << errors[0];
}

TEST(NurbsReaders, DamagedMFEMFilesGiveOneError)
{
  const std::string ring = slurp(kData + "/mfem_quarter_ring.mesh");
  expectError<vtkIGAMFEMReader>("title.mesh", replaced(ring, "v1.0", "v9"),
    "1: 'MFEM NURBS mesh v9' is not an MFEM NURBS mesh");
  expectError<vtkIGAMFEMReader>("edge.mesh", replaced(ring, "\n2 3 7\n", "\n2 3 6\n"),
    "its edge 3-7 is not in the edges section");
  expectError<vtkIGAMFEMReader>("knots.mesh", replaced(ring, "2 3 0 0 0 1 1 1", "2 3 0 0 1 1 1"),
    "knot vector 0: knot vector has 5 knots, expected 6");
  expectError<vtkIGAMFEMReader>(
    "weight.mesh", replaced(ring, "weights\n1\n", "weights\n-1\n"), "weight 0 is -1");
  expectError<vtkIGAMFEMReader>(
    "short.mesh", ring.substr(0, ring.size() - 12), "the file ends where nodes should follow");
  expectError<vtkIGAMFEMReader>(
    "kv.mesh", replaced(ring, "\n0 0 1\n", "\n7 0 1\n"), "names knot vector 7 of 3");
  expectError<vtkIGAMFEMReader>("parallel.mesh", replaced(ring, "\n0 3 2\n", "\n1 3 2\n"),
    "element 0: its edges along direction 0 have 3 and 2 control points");
  expectError<vtkIGAMFEMReader>("geometry.mesh", replaced(ring, "1 5 0 1", "1 3 0 1"),
    "element 0 has geometry 3, a mesh of dimension 3 needs 5");
}

// MFEM's "unitweights" in place of the weights: every weight 1.
TEST(NurbsReaders, MFEMUnitWeights)
{
  std::string ring = slurp(kData + "/mfem_quarter_ring.mesh");
  const size_t from = ring.find("weights\n"), to = ring.find("FiniteElementSpace");
  ring.replace(from, to - from, "unitweights\n\n");
  const std::string file = testing::TempDir() + "/unitweights.mesh";
  std::ofstream(file, std::ios::binary) << ring;
  const auto grid = readNurbs<vtkIGAMFEMReader>(file).second;
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  double range[2];
  grid->GetPointData()->GetRationalWeights()->GetRange(range);
  EXPECT_EQ(range[0], 1.0);
  EXPECT_EQ(range[1], 1.0);
}

TEST(NurbsReaders, DamagedMFEMGridFunctionsGiveOneError)
{
  const std::string gf = slurp(kData + "/mfem_quarter_ring_pressure.gf");
  for (const auto& [name, text, expected] : std::vector<std::array<std::string, 3>>{
         { "order.gf", replaced(gf, "NURBS2", "NURBS3"), "its space is NURBS3, the mesh's NURBS2" },
         { "few.gf", gf.substr(0, gf.size() - 4), "the file ends where values should follow" },
         { "many.gf", gf + "7\n", "more values than the mesh's 12 control points take" } })
  {
    const std::string file = testing::TempDir() + "/" + name;
    std::ofstream(file, std::ios::binary) << text;
    std::vector<std::string> errors;
    const auto grid = read<vtkIGAMFEMReader>(kData + "/mfem_quarter_ring.mesh", &errors, nullptr, 0,
      [&file](vtkIGAMFEMReader* reader) { reader->AddGridFunctionFileName(file.c_str()); });
    EXPECT_EQ(grid->GetNumberOfCells(), 0) << name;
    ASSERT_GE(errors.size(), 1u) << name;
    EXPECT_NE(errors[0].find("GridFunction " + file + ":"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find(expected), std::string::npos) << errors[0];
  }
}
