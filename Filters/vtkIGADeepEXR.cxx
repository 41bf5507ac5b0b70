#include "vtkIGADeepEXR.h"

#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfHeader.h>
#include <ImfPartType.h>

#include <array>
#include <exception>
#include <functional>
#include <vector>

namespace
{

/// A channel's name and its value at a hit.
struct DeepChannel
{
  const char* name;
  std::function<float(const iga::sst::Hit&)> value;
};

std::vector<DeepChannel> deepChannels()
{
  using Hit = iga::sst::Hit;
  return {
    { "Z", [](const Hit& h) { return float(h.eyeDepth); } },
    { "P.X", [](const Hit& h) { return float(h.position[0]); } },
    { "P.Y", [](const Hit& h) { return float(h.position[1]); } },
    { "P.Z", [](const Hit& h) { return float(h.position[2]); } },
    { "N.X", [](const Hit& h) { return float(h.normal[0]); } },
    { "N.Y", [](const Hit& h) { return float(h.normal[1]); } },
    { "N.Z", [](const Hit& h) { return float(h.normal[2]); } },
    { "u", [](const Hit& h) { return float(h.uvw[0]); } },
    { "v", [](const Hit& h) { return float(h.uvw[1]); } },
    { "w", [](const Hit& h) { return float(h.uvw[2]); } },
    { "patch", [](const Hit& h) { return float(h.patch); } },
    { "operand", [](const Hit& h) { return float(h.isovalue); } },
    { "entering", [](const Hit& h) { return h.entersBelow ? 1.0f : 0.0f; } },
  };
}

} // namespace

bool vtkIGADeepEXR::Write(
  const iga::sst::GBuffer& gbuffer, const std::string& file, std::string& error)
{
  const int width = gbuffer.width, height = gbuffer.height;
  if (width < 1 || height < 1 || gbuffer.offsets.size() != size_t(width) * height + 1)
  {
    error = "'" + file + "': the G-buffer is empty or inconsistent";
    return false;
  }
  const std::vector<DeepChannel> channels = deepChannels();
  // Samples channel by channel, in the G-buffer's hit order; per pixel of the EXR image (rows
  // top to bottom) its count and, per channel, where its samples start.
  const size_t pixels = size_t(width) * height, hits = gbuffer.hits.size();
  std::vector<std::vector<float>> values(channels.size(), std::vector<float>(hits));
  for (size_t c = 0; c < channels.size(); ++c)
  {
    for (size_t h = 0; h < hits; ++h)
    {
      values[c][h] = channels[c].value(gbuffer.hits[h]);
    }
  }
  std::vector<unsigned int> counts(pixels);
  std::vector<std::vector<char*>> starts(channels.size(), std::vector<char*>(pixels));
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const size_t from = size_t(j) * width + i, to = size_t(height - 1 - j) * width + i;
      counts[to] = gbuffer.offsets[from + 1] - gbuffer.offsets[from];
      for (size_t c = 0; c < channels.size(); ++c)
      {
        starts[c][to] = reinterpret_cast<char*>(values[c].data() + gbuffer.offsets[from]);
      }
    }
  }
  try
  {
    Imf::Header header(width, height);
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
      sizeof(unsigned int), sizeof(unsigned int) * size_t(width)));
    for (size_t c = 0; c < channels.size(); ++c)
    {
      header.channels().insert(channels[c].name, Imf::Channel(Imf::FLOAT));
      frame.insert(
        channels[c].name, Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(starts[c].data()),
                            sizeof(char*), sizeof(char*) * size_t(width), sizeof(float)));
    }
    Imf::DeepScanLineOutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
  }
  catch (const std::exception& e)
  {
    error = "'" + file + "': cannot write deep OpenEXR: " + e.what();
    return false;
  }
  return true;
}
