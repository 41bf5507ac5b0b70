// libFuzzer target: algebraic surfaces. The bytes are a polynomial expression: it parses, or
// throws std::invalid_argument naming a position within the text (or none, for a total degree
// above 16); one that parses is drawn by ray composition at 12x10 over the box [-1, 1]^3 with
// the root finder the input's length picks: finite hits, or a refusal. The same bytes, read as
// up to 17 doubles, are a Bernstein polynomial for every finder: sorted roots in [0, 1], or
// the input named invalid.
#include "FuzzFrame.h"
#include "iga/BernsteinRoots.h"
#include "iga/PolynomialExpression.h"
#include "iga/sst/Engine.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

void checkRoots(const uint8_t* data, size_t size)
{
  double c[iga::kMaxOrder] = {};
  const int count = int(std::min(size / sizeof(double), size_t(iga::kMaxOrder)));
  if (count == 0)
    return;
  std::memcpy(c, data, size_t(count) * sizeof(double));
  for (int f = 0; f < iga::kRootFinderCount; ++f)
  {
    const auto roots = iga::findBernsteinRoots(c, count - 1, iga::RootFinder(f));
    for (int k = 0; k < roots.count; ++k)
    {
      if (!(roots.t[k] >= 0 && roots.t[k] <= 1) || (k > 0 && !(roots.t[k - 1] < roots.t[k])))
        std::abort(); // roots lie in [0, 1], sorted, distinct
    }
  }
}

void drawExpression(const std::string& text, size_t size)
{
  iga::Polynomial3<double> field;
  try
  {
    field = iga::parsePolynomial(text);
  }
  catch (const std::invalid_argument& e)
  {
    const char* at = std::strstr(e.what(), "position ");
    if (at && size_t(std::atol(at + 9)) > text.size() + 1)
      std::abort(); // an error must point into the text (or just past its end)
    return;
  }
  const double box[6] = { -1, 1, -1, 1, -1, 1 };
  std::vector<iga::BezierVolume<double>> patches;
  try
  {
    patches.push_back(iga::makeAlgebraicVolume(field, box));
  }
  catch (const std::invalid_argument&)
  {
    return; // coefficients that overflow
  }
  const iga::Camera camera = fuzzBoxCamera();
  iga::sst::Settings settings = fuzzFrameSettings(size);
  settings.isovalues = { 0.0 };
  settings.rootFinder = iga::RootFinder(size % iga::kRootFinderCount);
  iga::sst::GBuffer out;
  try
  {
    iga::sst::render(patches, camera, settings, iga::sst::Method::RayComposition, out);
  }
  catch (const std::invalid_argument&)
  {
    return; // non-finite coefficients, or a field whose degree along rays passes 16
  }
  for (const auto& hit : out.hits)
  {
    if (!std::isfinite(hit.ndcDepth) || !std::isfinite(hit.position.x))
      std::abort();
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  checkRoots(data, size);
  drawExpression(std::string(reinterpret_cast<const char*>(data), size), size);
  return 0;
}
