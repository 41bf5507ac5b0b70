// libFuzzer target: the engine's input checks and a small frame on patches decoded from the
// bytes: 1..4 patches, each a volume or a surface, of degrees 1..16 per direction, 0..2
// attributes (none is refused for volumes, drawn for surfaces), control
// values from pairs of bytes (v / 1000, with codes for NaN, infinities, 1e300 and -0), an isovalue,
// first-hit or all-hits, an optional clipping plane. A frame either draws finite hits or throws
// std::invalid_argument naming the problem.
#include "iga/sst/Engine.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace
{

/// Reads the bytes in order, zeros once they run out.
struct ByteReader
{
  const uint8_t* data;
  size_t size, at = 0;
  uint8_t byte() { return at < size ? data[at++] : 0; }
  double value()
  {
    const int16_t v = int16_t(uint16_t(byte()) << 8 | byte());
    switch (v)
    {
      case 32767:
        return std::numeric_limits<double>::quiet_NaN();
      case 32766:
        return std::numeric_limits<double>::infinity();
      case 32765:
        return 1e300;
      case -32768:
        return -0.0;
      default:
        return v / 1000.0;
    }
  }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  ByteReader in{ data, size };
  const int patchCount = in.byte() % 4 + 1;
  const int attributes = in.byte() % 3;
  std::vector<iga::BezierVolume<double>> volumes;
  std::vector<iga::BezierSurface<double>> surfaces;
  for (int p = 0; p < patchCount; ++p)
  {
    const bool surface = (in.byte() & 1) != 0;
    int degree[3];
    for (int& d : degree)
    {
      d = 1 + in.byte() % iga::kMaxDegree;
    }
    std::vector<double>& coeffs =
      surface ? surfaces.emplace_back(degree, iga::kFirstAttributeChannel + attributes).coeffs()
              : volumes.emplace_back(degree, iga::kFirstAttributeChannel + attributes).coeffs();
    for (double& c : coeffs)
    {
      c = in.value();
    }
  }
  iga::sst::Settings settings;
  settings.width = 16;
  settings.height = 12;
  settings.threads = 1;
  settings.backend = iga::sst::Backend::Cpu;
  settings.maxSubdivisionDepth = 12;
  settings.memoryBudgetBytes = size_t(32) << 20;
  settings.isovalues = { in.value() };
  settings.surfaceAttribute = 0;
  settings.colorAttribute = attributes > 1 ? 1 : -1;
  const uint8_t flags = in.byte();
  settings.firstHitOnly = (flags & 1) == 0;
  if (flags & 2)
  {
    settings.clipPlanes.push_back({ in.value(), in.value(), in.value(), in.value() });
  }
  iga::Camera camera;
  camera.position = { 3, -4, 2.5 };
  camera.focalPoint = { 0, 0, 0 };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngle = 40;
  camera.clippingRange[0] = 0.1;
  camera.clippingRange[1] = 100;
  iga::sst::GBuffer gbuffer;
  try
  {
    iga::sst::render(iga::sst::Scene(volumes, surfaces), camera, settings,
      iga::sst::Method::SharedSubdivisionTree, gbuffer);
  }
  catch (const std::invalid_argument&)
  {
    return 0;
  }
  for (const auto& hit : gbuffer.hits)
  {
    if (!(std::isfinite(hit.position[0]) && std::isfinite(hit.position[1]) &&
          std::isfinite(hit.position[2]) && std::isfinite(hit.ndcDepth)))
    {
      __builtin_trap();
    }
  }
  return 0;
}
