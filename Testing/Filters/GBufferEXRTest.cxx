// The engine's G-buffer written as OpenEXR and read back with OpenEXR: channel names, row order,
// values and the no-hit conventions.
#include "vtkIGADeepEXR.h"
#include "vtkIGAEXRWriter.h"
#include "vtkIGAGBufferImage.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include "iga/Datasets.h"
#include "iga/sst/Engine.h"

#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineInputFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace
{

std::map<std::string, std::vector<float>> readEXR(const std::string& file, int& width, int& height)
{
  Imf::InputFile in(file.c_str());
  const Imath::Box2i window = in.header().dataWindow();
  width = window.max.x - window.min.x + 1;
  height = window.max.y - window.min.y + 1;
  std::map<std::string, std::vector<float>> channels;
  Imf::FrameBuffer frame;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
  {
    auto& data = channels[it.name()];
    data.resize(size_t(width) * height);
    frame.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()),
                              sizeof(float), sizeof(float) * width));
  }
  in.setFrameBuffer(frame);
  in.readPixels(window.min.y, window.max.y);
  return channels;
}

/// A 40x30 frame of the tube's radius isosurfaces at `isovalues`, coloured by height.
iga::sst::GBuffer tubeFrame(const std::vector<double>& isovalues, bool firstHitOnly)
{
  const auto set = iga::makeTube<double>(0.5, 0.0);
  double bounds[6];
  iga::sst::patchBounds(set.patches, bounds);
  iga::Camera camera = iga::frameBounds(bounds, { -0.5, 0.7, -0.4 }, { 0, 0, 1 }, 30);
  iga::sst::Settings settings;
  settings.width = 40;
  settings.height = 30;
  settings.isovalues = isovalues;
  settings.surfaceAttribute = 1;
  settings.colorAttribute = 2;
  settings.firstHitOnly = firstHitOnly;
  iga::sst::GBuffer gbuffer;
  iga::sst::render(set.patches, camera, settings, iga::sst::Method::SharedSubdivisionTree, gbuffer);
  return gbuffer;
}

TEST(GBufferEXR, ChannelsRowsAndValuesRoundTrip)
{
  const iga::sst::GBuffer gbuffer = tubeFrame({ 0.75 }, true);
  std::vector<float> rgba(40 * 30 * 4);
  for (size_t k = 0; k < rgba.size(); ++k)
    rgba[k] = float(k % 7) / 7.0f;

  const std::string file = testing::TempDir() + "gbuffer.exr";
  vtkNew<vtkIGAEXRWriter> writer;
  writer->SetInputData(vtkIGAGBufferImage::Convert(gbuffer, rgba.data(), "height"));
  writer->SetFileName(file.c_str());
  writer->Write();
  ASSERT_EQ(writer->GetErrorCode(), 0u) << writer->GetLastError();

  int width, height;
  auto channels = readEXR(file, width, height);
  ASSERT_EQ(width, 40);
  ASSERT_EQ(height, 30);
  for (const char* name : { "R", "G", "B", "A", "Z", "P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "u",
         "v", "w", "patch", "height" })
    ASSERT_EQ(channels.count(name), 1u) << "missing channel " << name;
  EXPECT_EQ(channels.size(), 16u);
  int hits = 0, misses = 0;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i)
    {
      const size_t row = size_t(29 - j) * 40 + i; // EXR row 0 is the top row
      const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
      EXPECT_EQ(channels["R"][row], rgba[(size_t(j) * 40 + i) * 4]);
      EXPECT_EQ(channels["A"][row], rgba[(size_t(j) * 40 + i) * 4 + 3]);
      if (!hit)
      {
        ++misses;
        EXPECT_TRUE(std::isinf(channels["Z"][row]));
        EXPECT_EQ(channels["patch"][row], -1.0f);
        EXPECT_TRUE(std::isnan(channels["P.X"][row]));
        continue;
      }
      ++hits;
      EXPECT_FLOAT_EQ(channels["Z"][row], float(hit->eyeDepth));
      EXPECT_FLOAT_EQ(channels["P.Y"][row], float(hit->position[1]));
      EXPECT_FLOAT_EQ(channels["N.Z"][row], float(hit->normal[2]));
      EXPECT_FLOAT_EQ(channels["w"][row], float(hit->uvw[2]));
      EXPECT_EQ(channels["patch"][row], float(hit->patch));
      // The colour attribute is the height, which is the position's z exactly.
      EXPECT_NEAR(channels["height"][row], channels["P.Z"][row], 1e-5);
    }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

TEST(GBufferEXR, WriterReportsProblemsWithTheFileName)
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(4, 4, 4);
  vtkNew<vtkIGAEXRWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName("/nonexistent/dir/out.exr");
  writer->Write();
  EXPECT_NE(writer->GetErrorCode(), 0u);
  EXPECT_NE(std::string(writer->GetLastError()).find("not 2D"), std::string::npos);

  iga::sst::GBuffer empty;
  empty.width = 2;
  empty.height = 2;
  empty.offsets.assign(5, 0);
  writer->SetInputData(vtkIGAGBufferImage::Convert(empty, nullptr, ""));
  writer->Write();
  EXPECT_NE(
    std::string(writer->GetLastError()).find("/nonexistent/dir/out.exr: cannot write OpenEXR"),
    std::string::npos);
}

/// Every layer of an all-hits G-buffer (the tube's two isosurfaces, both sides) written as a
/// deep EXR and read back with OpenEXR: per pixel the same samples in the same order.
TEST(GBufferEXR, DeepImageHoldsEveryLayer)
{
  const iga::sst::GBuffer gbuffer = tubeFrame({ 0.6, 0.85 }, false);
  const std::string file = testing::TempDir() + "deep.exr";
  std::string error;
  ASSERT_TRUE(vtkIGADeepEXR::Write(gbuffer, file, error)) << error;

  Imf::DeepScanLineInputFile in(file.c_str());
  const int width = gbuffer.width, height = gbuffer.height;
  std::vector<unsigned int> counts(size_t(width) * height);
  // The slices first (their pointer tables filled once the counts are known), then the counts,
  // then the samples.
  const char* names[4] = { "Z", "P.X", "operand", "entering" };
  std::vector<std::vector<float>> samples(4);
  std::vector<std::vector<char*>> starts(4, std::vector<char*>(counts.size()));
  Imf::DeepFrameBuffer frame;
  frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
    sizeof(unsigned int), sizeof(unsigned int) * width));
  for (int c = 0; c < 4; ++c)
  {
    frame.insert(
      names[c], Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(starts[size_t(c)].data()),
                  sizeof(char*), sizeof(char*) * width, sizeof(float)));
  }
  in.setFrameBuffer(frame);
  in.readPixelSampleCounts(0, height - 1);
  size_t total = 0;
  for (unsigned int count : counts)
    total += count;
  ASSERT_EQ(total, gbuffer.hits.size());
  for (int c = 0; c < 4; ++c)
  {
    samples[size_t(c)].resize(total);
    size_t at = 0;
    for (size_t p = 0; p < counts.size(); ++p)
    {
      starts[size_t(c)][p] = reinterpret_cast<char*>(samples[size_t(c)].data() + at);
      at += counts[p];
    }
  }
  in.readPixels(0, height - 1);
  int layered = 0;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
    {
      const size_t row = size_t(height - 1 - j) * width + i; // EXR rows run top to bottom
      ASSERT_EQ(int(counts[row]), gbuffer.hitCount(i, j));
      layered += gbuffer.hitCount(i, j) >= 3 ? 1 : 0;
      for (int k = 0; k < gbuffer.hitCount(i, j); ++k)
      {
        const iga::sst::Hit& hit = gbuffer.firstHit(i, j)[k];
        const float* z = reinterpret_cast<const float*>(starts[0][row]);
        const float* x = reinterpret_cast<const float*>(starts[1][row]);
        const float* operand = reinterpret_cast<const float*>(starts[2][row]);
        const float* entering = reinterpret_cast<const float*>(starts[3][row]);
        EXPECT_EQ(z[k], float(hit.eyeDepth));
        EXPECT_EQ(x[k], float(hit.position[0]));
        EXPECT_EQ(operand[k], float(hit.isovalue));
        EXPECT_EQ(entering[k], hit.entersBelow ? 1.0f : 0.0f);
      }
    }
  EXPECT_GT(layered, 100) << "rays through both isosurfaces";
  EXPECT_FALSE(vtkIGADeepEXR::Write(gbuffer, "/nonexistent/dir/deep.exr", error));
  EXPECT_NE(error.find("/nonexistent/dir/deep.exr': cannot write deep OpenEXR"), std::string::npos)
    << error;
}

} // namespace
