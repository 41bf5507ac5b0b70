// The engine's G-buffer written as OpenEXR and read back with OpenEXR: channel names, row order,
// values and the no-hit conventions.
#include "vtkIGAEXRWriter.h"
#include "vtkIGAGBufferImage.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include "iga/Datasets.h"
#include "iga/sst/Engine.h"

#include <ImfChannelList.h>
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

TEST(GBufferEXR, ChannelsRowsAndValuesRoundTrip)
{
  const auto set = iga::makeTube<double>(0.5, 0.0);
  double bounds[6];
  iga::sst::patchBounds(set.patches, bounds);
  iga::Camera camera = iga::frameBounds(bounds, { -0.5, 0.7, -0.4 }, { 0, 0, 1 }, 30);
  iga::sst::Settings settings;
  settings.width = 40;
  settings.height = 30;
  settings.isovalues = { 0.75 };
  settings.surfaceAttribute = 1;
  settings.colorAttribute = 2;
  iga::sst::GBuffer gbuffer;
  iga::sst::render(set.patches, camera, settings, iga::sst::Method::SharedSubdivisionTree, gbuffer);
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

} // namespace
