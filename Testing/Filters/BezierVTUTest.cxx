// Bézier cells in VTK XML files: what VTK 9.2's vtkXMLUnstructuredGridWriter writes (file
// version, active-attribute flags), that the NURBS description survives a .vtu round trip, and
// that a .pvd series written by vtkIGABezierSeriesWriter reads back through ParaView's
// vtkPVDReader and vtkIGABezierSeriesReader with its time steps, the latter refusing bad
// collections with one error.
#include "FilterErrors.h"
#include "vtkIGABezierFileReading.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkIGABezierSeriesReader.h"
#include "vtkIGABezierSeriesWriter.h"
#include "vtkIGADefaultVolumeSource.h"
#include "vtkIGAGeoPDEsReader.h"
#include "vtkIGAGismoReader.h"
#include "vtkIGANurbsData.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkHigherOrderHexahedron.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPVDReader.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include "iga/Datasets.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <sys/stat.h>

namespace
{

vtkSmartPointer<vtkUnstructuredGrid> quarterRing()
{
  vtkNew<vtkIGAGismoReader> reader;
  reader->SetFileName(IGAVIEW_DATA_DIR "/gismo_quarter_ring.xml");
  reader->Update();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->ShallowCopy(reader->GetOutput());
  return grid;
}

/// The error of reading `text` as igaview does (within `memory` bytes, 0: the machine's), ""
/// when it reads.
std::string readingError(const std::string& text, double memory = 0)
{
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  const auto grid =
    vtkIGABezierFileReading::Read("test.vtu", &text, patches, error, warnings, memory);
  EXPECT_EQ(grid == nullptr, !error.empty());
  return error;
}

std::string fileText(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(BezierVTU, BinaryHeadersClaimingMoreThanTheirDataAreRefused)
{
  const std::string sphere = fileText(IGAVIEW_DATA_DIR "/marsden_sphere_p2.vtu");
  EXPECT_EQ(readingError(sphere), "");
  // Its first array's header: 1 block of 32768 bytes, a last block of 648, 70 compressed.
  const std::string header = "AQAAAACAAACIAgAARgAAAA==";
  ASSERT_NE(sphere.find(header), std::string::npos);
  auto with = [&](const std::string& replacement)
  { return std::string(sphere).replace(sphere.find(header), header.size(), replacement); };
  EXPECT_NE(readingError(with("/////wCAAACIAgAARgAAAA==")).find("claims a table of blocks"),
    std::string::npos);
  EXPECT_NE(readingError(with("AQAAAACAAACIAgAA////fw==")).find("claims compressed blocks"),
    std::string::npos);
  EXPECT_NE(readingError(with("AQAAAAAAAACIAgAARgAAAA==")).find("inconsistent block sizes"),
    std::string::npos);
  EXPECT_NE(readingError(with("AQAAAACAAACQAgAARgAAAA==")).find("where the array holds 648"),
    std::string::npos);
  // What the fuzzer found (with its 256 MiB limit), each once a crash, a buffer overflow or an
  // allocation of gigabytes in VTK's reader.
  for (const auto& [file, expected] : std::vector<std::pair<std::string, std::string>>{
         { "zero-blocks-with-data.vtu", "inconsistent block sizes" },
         { "block-size-zero.vtu", "inconsistent block sizes" },
         { "partial-block-3gb.vtu", "where the array holds" },
         { "block-larger-than-array.vtu", "inconsistent block sizes" },
         // Appended and ASCII data, made by hand: a division by zero, an allocation of 17 GB
         // and two aborts.
         { "appended-block-size-zero.vtu", "inconsistent block sizes" },
         { "appended-block-table-4e9.vtu", "claims a table of blocks" },
         { "appended-offsets-past-memory.vtu", "its cell offsets end at 1e+12" },
         { "ascii-offsets-past-memory.vtu", "its cell offsets end at 1e+12" },
         // Found by the fuzzer once appended data was checked: without the '_' VTK reads the
         // appended data from their first character, whose header claims 4 GB.
         { "appended-data-without-marker.vtu", "claims data of 4.281e+09 bytes" },
         // ... and by CI's 30 s run: offsets with a mistyped format attribute, which VTK reads
         // as ASCII.
         { "offsets-without-format.vtu", "its cell offsets end at 1e+12" },
         // ... and by CI's run after the checks' review: compressed offsets without a readable
         // header (a block size of 0 divided), now left to VTK's reader, which says so.
         { "compressed-offsets-without-header.vtu", "is not a readable VTK XML unstructured grid" },
         // ... and by CI's run of 2026-12-04: a misspelt format and no text, which VTK reads as
         // ASCII without a value, taking an unset one as the end of 1e12 ids (8 TB).
         { "offsets-format-misspelt.vtu", "hold no readable last value" } })
  {
    const std::string error =
      readingError(fileText(IGAVIEW_SOURCE_DIR "/Testing/Fuzz/regressions/" + file), 256e6);
    EXPECT_NE(error.find(expected), std::string::npos) << file << ": " << error;
  }
}

/// How vtkXMLUnstructuredGridWriter lays a file out.
struct Layout
{
  const char* name;
  int mode;       ///< vtkXMLWriter::Ascii, Binary or Appended
  bool base64;    ///< appended data encoded
  int compressor; ///< vtkXMLWriter::NONE, ZLIB, LZ4 or LZMA
  bool uint64;    ///< 64-bit headers
  bool bigEndian;
};

const Layout kLayouts[] = {
  { "ascii", vtkXMLWriter::Ascii, false, vtkXMLWriter::NONE, false, false },
  { "binary", vtkXMLWriter::Binary, false, vtkXMLWriter::NONE, false, false },
  { "binary zlib", vtkXMLWriter::Binary, false, vtkXMLWriter::ZLIB, false, false },
  { "binary lz4, big-endian", vtkXMLWriter::Binary, false, vtkXMLWriter::LZ4, false, true },
  { "appended raw", vtkXMLWriter::Appended, false, vtkXMLWriter::NONE, false, false },
  { "appended raw zlib, 64-bit headers", vtkXMLWriter::Appended, false, vtkXMLWriter::ZLIB, true,
    false },
  { "appended base64 lzma", vtkXMLWriter::Appended, true, vtkXMLWriter::LZMA, false, false },
  { "appended base64", vtkXMLWriter::Appended, true, vtkXMLWriter::NONE, false, true },
};

/// The degree-2 sphere's grid as VTK writes it in `layout`, its one cell's offsets ending at
/// `lastOffset` (27 when right) over a connectivity of its 27 points.
std::string sphereText(const Layout& layout, vtkIdType lastOffset)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(IGAVIEW_DATA_DIR "/marsden_sphere_p2.vtu");
  reader->Update();
  vtkNew<vtkUnstructuredGrid> grid;
  grid->DeepCopy(reader->GetOutput());
  vtkNew<vtkIdTypeArray> offsets;
  offsets->InsertNextValue(0);
  offsets->InsertNextValue(lastOffset);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->DeepCopy(grid->GetCells()->GetConnectivityArray());
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  grid->SetCells(VTK_BEZIER_HEXAHEDRON, cells);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetDataMode(layout.mode);
  writer->SetEncodeAppendedData(layout.base64);
  writer->SetCompressorType(layout.compressor);
  writer->SetHeaderType(layout.uint64 ? vtkXMLWriter::UInt64 : vtkXMLWriter::UInt32);
  writer->SetByteOrder(layout.bigEndian ? vtkXMLWriter::BigEndian : vtkXMLWriter::LittleEndian);
  writer->WriteToOutputStringOn();
  EXPECT_EQ(writer->Write(), 1);
  return writer->GetOutputString();
}

/// VTK's reader allocates the connectivity the last cell offset gives, and aborts when it
/// cannot: an offset past the connectivity or beyond the memory is refused in every layout VTK
/// writes (the offset read from ASCII text, raw or base64 bytes, or a decompressed block).
TEST(BezierVTU, CellOffsetsPastTheConnectivityAreRefusedInEveryLayout)
{
  for (const Layout& layout : kLayouts)
  {
    SCOPED_TRACE(layout.name);
    EXPECT_EQ(readingError(sphereText(layout, 27)), "");
    const bool known = layout.mode != vtkXMLWriter::Ascii; // the connectivity's size
    EXPECT_EQ(readingError(sphereText(layout, 28)),
      known ? "'test.vtu': its cell offsets end at 28, past the 27 point ids of its connectivity"
            : "'test.vtu' is not a readable VTK XML unstructured grid with cells (Cannot read "
              "cell connectivity from Cells in piece 0 because the \"connectivity\" array is not "
              "long enough.)");
    EXPECT_EQ(readingError(sphereText(layout, 1000000000000), 1e9),
      "'test.vtu': its cell offsets end at 1e+12, a connectivity of 8e+03 GB, more than this "
      "machine's 1 GB");
  }
}

/// A file whose inline binary arrays run past the first MiB (read from disk, where only that
/// much is scanned for tags) is read: an array's data end where its text does, in the file
/// (refused before: "claims compressed blocks of 1.89e+06 bytes, more than the data's 775257").
TEST(BezierVTU, InlineArraysPastTheFirstMegabyteAreRead)
{
  const auto blade =
    vtkIGABezierHexahedra::ToUnstructuredGrid(iga::makeBlade<double>(iga::bladeLayout(10000), 0));
  const std::string file = testing::TempDir() + "/blade_10k.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(blade);
  writer->SetFileName(file.c_str());
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  ASSERT_EQ(writer->Write(), 1);
  ASSERT_GT(fileText(file).size(), size_t(2) << 20);
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  EXPECT_NE(vtkIGABezierFileReading::Read(file, nullptr, patches, error, warnings), nullptr)
    << error;
  EXPECT_EQ(patches.volumes.patches.size(), size_t(blade->GetNumberOfCells()));
}

/// Appended data (raw or base64) has its binary headers checked as inline data does.
TEST(BezierVTU, AppendedHeadersClaimingMoreThanTheirDataAreRefused)
{
  const std::string raw = sphereText(kLayouts[4], 27);
  const size_t data = raw.find('_', raw.find("<AppendedData")) + 1;
  // The first array's header: 27 weights of 8 bytes.
  ASSERT_EQ(raw.substr(data, 4), std::string("\xd8\0\0\0", 4));
  EXPECT_EQ(readingError(std::string(raw).replace(data, 4, "\xf0\xff\xff\xff")),
    "'test.vtu': a binary data array's header claims data of 4.295e+09 bytes, more than the "
    "data's 1355");
  EXPECT_EQ(readingError(std::string(raw).replace(data, 1, "\xe0")),
    "'test.vtu': a binary data array's header claims data of 224 bytes, where the array holds 216");
  const std::string zlib = sphereText(kLayouts[5], 27);
  const size_t zdata = zlib.find('_', zlib.find("<AppendedData")) + 1;
  EXPECT_EQ(readingError(std::string(zlib).replace(zdata + 8, 8, std::string(8, '\0'))),
    "'test.vtu': a binary data array's header gives inconsistent block sizes");
  EXPECT_NE(readingError(std::string(zlib).replace(zdata, 8, std::string(8, '\xff')))
              .find("claims a table of blocks of 1.476e+20 bytes"),
    std::string::npos);
  const std::string offset = "offset=\"0\"";
  ASSERT_NE(raw.find(offset), std::string::npos);
  EXPECT_EQ(
    readingError(std::string(raw).replace(raw.find(offset), offset.size(), "offset=\"-8\"")),
    "'test.vtu': data array 'RationalWeights' is appended, but the file has no offset into the "
    "appended data that is a whole number");
}

/// An array's component count is a positive whole number and its size fits the memory: VTK
/// allocates tuples times components before it reads (an ASCII array claiming 1e12 components
/// a point ran for minutes).
TEST(BezierVTU, ComponentCountsBeyondTheMemoryAreRefused)
{
  const std::string ascii = sphereText(kLayouts[0], 27);
  const std::string points = "Name=\"Points\" NumberOfComponents=\"3\"";
  ASSERT_NE(ascii.find(points), std::string::npos);
  auto with = [&](const std::string& components)
  {
    return std::string(ascii).replace(ascii.find(points), points.size(),
      "Name=\"Points\" NumberOfComponents=\"" + components + "\"");
  };
  EXPECT_EQ(readingError(with("1000000000000"), 1e12),
    "'test.vtu': data array 'Points' claims 2.16e+14 bytes (1e+12 components a tuple), more than "
    "this machine's 1e+03 GB");
  EXPECT_EQ(readingError(with("1000000"), 1e8),
    "'test.vtu': data array 'Points' claims 2.16e+08 bytes (1e+06 components a tuple), more than "
    "this machine's 0.1 GB");
  // Field data says its tuples itself (VTK aborted allocating 1e12 of them).
  const std::string junk =
    "<FieldData><DataArray type=\"Float64\" Name=\"junk\" "
    "NumberOfTuples=\"TUPLES\" format=\"ascii\">1 2 3</DataArray></FieldData>";
  auto withFieldData = [&](const std::string& tuples)
  {
    return std::string(ascii).insert(
      ascii.find("<Piece"), std::string(junk).replace(junk.find("TUPLES"), 6, tuples));
  };
  EXPECT_EQ(readingError(withFieldData("3")), "");
  EXPECT_EQ(readingError(withFieldData("1000000000000"), 1e12),
    "'test.vtu': data array 'junk' claims 8e+12 bytes (1 components a tuple), more than this "
    "machine's 1e+03 GB");
  EXPECT_EQ(readingError(withFieldData("-1")),
    "'test.vtu': data array 'junk' has NumberOfTuples=\"-1\", not a whole number");
  for (const char* bad : { "-3", "0", "2.5", "3x" })
  {
    EXPECT_EQ(readingError(with(bad)), "'test.vtu': data array 'Points' has NumberOfComponents=\"" +
                                         std::string(bad) + "\", not a positive whole number");
  }
}

TEST(BezierVTU, WriterVersionAndActiveFlagsSurviveARoundTrip)
{
  const auto grid = quarterRing();
  ASSERT_EQ(grid->GetNumberOfCells(), 1);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetDataModeToAscii();
  writer->WriteToOutputStringOn();
  ASSERT_EQ(writer->Write(), 1);
  const std::string text = writer->GetOutputString();

  // VTK 9.2 writes version 2.2; readers before 2.1 reorder higher-order hexahedron points.
  std::smatch version;
  ASSERT_TRUE(std::regex_search(text, version,
    std::regex("<VTKFile type=\"UnstructuredGrid\" version=\"([0-9]+)\\.([0-9]+)\"")));
  const int major = std::stoi(version[1]), minor = std::stoi(version[2]);
  EXPECT_TRUE(major > 2 || (major == 2 && minor >= 1)) << version[0];
  EXPECT_NE(text.find("RationalWeights=\"RationalWeights\""), std::string::npos);
  EXPECT_NE(text.find("HigherOrderDegrees=\"HigherOrderDegrees\""), std::string::npos);

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->ReadFromInputStringOn();
  reader->SetInputString(text);
  reader->Update();
  vtkUnstructuredGrid* back = reader->GetOutput();
  ASSERT_NE(back->GetPointData()->GetRationalWeights(), nullptr) << "active flag lost";
  ASSERT_NE(back->GetCellData()->GetHigherOrderDegrees(), nullptr) << "active flag lost";
  const int degrees[3] = { 2, 1, 1 }; // the middle of the arc: control point (1, 0, 0)
  const int middle = vtkHigherOrderHexahedron::PointIndexFromIJK(1, 0, 0, degrees);
  EXPECT_NEAR(
    back->GetPointData()->GetRationalWeights()->GetComponent(middle, 0), std::sqrt(0.5), 1e-15);

  // The NURBS description travels in field data: grid -> file -> grid -> class is exact.
  vtkNew<vtkIGANurbsData> original, rebuilt;
  ASSERT_EQ(vtkIGANurbsData::FromUnstructuredGrid(grid, original), "");
  ASSERT_EQ(vtkIGANurbsData::FromUnstructuredGrid(back, rebuilt), "");
  const auto a = original->GetPatches(), b = rebuilt->GetPatches();
  ASSERT_EQ(b.volumes.size(), 1u);
  EXPECT_EQ(b.attributeNames, a.attributeNames);
  EXPECT_EQ(b.volumes[0].knots[0], a.volumes[0].knots[0]);
  ASSERT_EQ(b.volumes[0].net.size(), a.volumes[0].net.size());
  for (size_t v = 0; v < a.volumes[0].net.size(); ++v)
    EXPECT_NEAR(b.volumes[0].net[v], a.volumes[0].net[v], 1e-15);
}

/// The default source's series written as a .pvd (its 11 time steps, 0..1).
std::string writeDefaultSeries()
{
  const std::string pvd = testing::TempDir() + "/igaview_series.pvd";
  vtkNew<vtkIGADefaultVolumeSource> source;
  vtkNew<vtkIGABezierSeriesWriter> writer;
  writer->SetFileName(pvd.c_str());
  writer->SetInputConnection(source->GetOutputPort());
  EXPECT_EQ(writer->Write(), 1);
  return pvd;
}

/// `reader` of the default source's series: its 11 steps, and at `requested` the grid of
/// `step`, point for point the source's at that step.
void expectDefaultSeriesStep(vtkAlgorithm* reader, double requested, double step)
{
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 11);
  EXPECT_NEAR(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[3], 0.3, 1e-15);
  reader->UpdateTimeStep(requested);
  auto* grid = vtkUnstructuredGrid::SafeDownCast(reader->GetOutputDataObject(0));
  ASSERT_NE(grid, nullptr) << reader->GetOutputDataObject(0)->GetClassName();
  ASSERT_NE(grid->GetPointData()->GetRationalWeights(), nullptr);
  // Degree 2 in every direction: VTK infers it from the 27 points; no cell arrays at all
  // (see vtkIGABezierHexahedra::CellLayout).
  EXPECT_EQ(grid->GetCellData()->GetNumberOfArrays(), 0);
  EXPECT_EQ(grid->GetCellSize(0), 27);
  vtkNew<vtkIGADefaultVolumeSource> reference;
  reference->UpdateTimeStep(step);
  vtkUnstructuredGrid* expected = reference->GetOutput();
  ASSERT_EQ(grid->GetNumberOfPoints(), expected->GetNumberOfPoints());
  double worst = 0;
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
    for (int d = 0; d < 3; ++d)
      worst = std::max(worst, std::abs(grid->GetPoint(p)[d] - expected->GetPoint(p)[d]));
  EXPECT_EQ(worst, 0.0) << "time " << requested; // binary XML keeps doubles exactly
}

TEST(BezierVTU, PVDSeriesReadsBackWithItsTimeSteps)
{
  const std::string pvd = writeDefaultSeries();
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd.c_str());
  reader->UpdateInformation();
  const double* steps =
    reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  ASSERT_NE(steps, nullptr);
  for (double time : { steps[3], steps[10] })
    expectDefaultSeriesStep(reader, time, time);
}

TEST(BezierVTU, SeriesReaderGivesTheStepAtOrBeforeTheRequestedTime)
{
  const std::string pvd = writeDefaultSeries();
  EXPECT_EQ(vtkIGABezierSeriesReader::CanReadFile(pvd.c_str()), 1);
  EXPECT_EQ(vtkIGABezierSeriesReader::CanReadFile(IGAVIEW_DATA_DIR "/dice.vtu"), 0);
  vtkNew<vtkIGABezierSeriesReader> reader;
  reader->SetFileName(pvd.c_str());
  vtkNew<vtkIGADefaultVolumeSource> source; // its steps, as written
  source->UpdateInformation();
  const double* steps =
    source->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  expectDefaultSeriesStep(reader, steps[3], steps[3]);
  expectDefaultSeriesStep(reader, steps[3] + 0.08, steps[3]); // between steps: the one before
  expectDefaultSeriesStep(reader, -1.0, steps[0]);            // before all: the first
  expectDefaultSeriesStep(reader, 7.0, steps[10]);
  EXPECT_EQ(reader->GetNumberOfTimeSteps(), 11);
  EXPECT_EQ(reader->GetTimeStep(10), steps[10]);
}

/// The errors vtkIGABezierSeriesReader reports reading the collection `text` (written beside the
/// default series' files, which it may name).
std::vector<std::string> seriesErrors(const std::string& text)
{
  const std::string pvd = testing::TempDir() + "/igaview_bad_series.pvd";
  std::ofstream(pvd) << text;
  vtkNew<vtkIGABezierSeriesReader> reader;
  reader->SetFileName(pvd.c_str());
  return igatest::updateCollectingErrors(reader);
}

/// A FIFO blocks whoever opens it until a writer comes (none does here): every reader and its
/// CanReadFile refuse it, and a directory, without opening them; so does a series naming one.
TEST(BezierVTU, ReadersRefuseFIFOsAndDirectoriesWithoutOpeningThem)
{
  const std::string fifo = testing::TempDir() + "/igaview_fifo.vtu";
  std::remove(fifo.c_str());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string directory = testing::TempDir();
  for (const std::string& path : { fifo, directory })
  {
    const std::string kind = path == fifo ? "a FIFO" : "a directory";
    const std::string problem = "'" + path + "' is " + kind + ", not a regular file";
    vtkNew<vtkIGAGismoReader> gismo;
    vtkNew<vtkIGAGeoPDEsReader> geopdes;
    EXPECT_EQ(gismo->CanReadFile(path.c_str()), 0);
    EXPECT_EQ(geopdes->CanReadFile(path.c_str()), 0);
    EXPECT_EQ(vtkIGABezierSeriesReader::CanReadFile(path.c_str()), 0);
    gismo->SetFileName(path.c_str());
    vtkNew<vtkIGABezierSeriesReader> series;
    series->SetFileName(path.c_str());
    for (vtkAlgorithm* reader : std::initializer_list<vtkAlgorithm*>{ gismo, series })
    {
      const auto errors = igatest::updateCollectingErrors(reader);
      ASSERT_EQ(errors.size(), 1u) << reader->GetClassName();
      EXPECT_NE(errors[0].find("): " + problem + "\n"), std::string::npos) << errors[0];
    }
    vtkIGABezierHexahedra::Patches patches;
    std::string error;
    std::vector<std::string> warnings;
    EXPECT_EQ(vtkIGABezierFileReading::Read(path, nullptr, patches, error, warnings), nullptr);
    EXPECT_EQ(error, problem);
  }
  const auto errors =
    seriesErrors("<VTKFile type='Collection'><Collection><DataSet timestep='0' file='" + fifo +
                 "'/></Collection></VTKFile>");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("'" + fifo + "' is a FIFO, not a regular file"), std::string::npos)
    << errors[0];
  std::remove(fifo.c_str());
}

TEST(BezierVTU, SeriesReaderRefusesBadCollectionsWithOneError)
{
  writeDefaultSeries(); // igaview_series/igaview_series_0.vtu exists: a good step
  const std::string head = "<VTKFile type=\"Collection\"><Collection>";
  const std::string tail = "</Collection></VTKFile>";
  const std::string good = "<DataSet timestep=\"0\" file=\"igaview_series_0.vtu\"/>";
  std::string deep;
  for (int i = 0; i < 1000; ++i)
    deep += "<a>";
  const std::vector<std::pair<std::string, std::string>> cases = {
    { head + tail, "the collection lists no DataSet" },
    { head + "<DataSet timestep=\"nan\" file=\"a.vtu\"/>" + tail,
      "DataSet 0 has no finite timestep" },
    { head + "<DataSet timestep=\"1x\" file=\"a.vtu\"/>" + tail,
      "DataSet 0 has no finite timestep" },
    { head + good + "<DataSet timestep=\"1\"/>" + tail, "DataSet 1 names no file" },
    { head + good + good + tail, "several parts at time 0 \\(each time step must be one file\\)" },
    { head + "<DataSet timestep=\"0\" file=\"missing.vtu\"/>" + tail,
      "time step 0 of '.*': cannot open '.*missing.vtu'" },
    { head + "<DataSet timestep=\"0\" file=\"igaview_series.pvd\"/>" + tail,
      "time step 0 of '.*': '.*igaview_series.pvd' is not a readable VTK XML unstructured grid" },
    { head + good, ":1: not well-formed XML \\(column [0-9]+\\): " },
    { head + deep, "elements are nested more than 256 levels deep" },
    { "<VTKFile type=\"UnstructuredGrid\"><Collection/></VTKFile>", "not a VTK collection" },
  };
  for (const auto& [text, message] : cases)
  {
    const auto errors = seriesErrors(text);
    ASSERT_EQ(errors.size(), 1u) << text;
    EXPECT_TRUE(std::regex_search(errors[0], std::regex(message))) << errors[0];
  }
}

} // namespace
