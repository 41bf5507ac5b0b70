// libFuzzer target: CSG expressions. The bytes are an expression: it parses, or throws
// csg::ExpressionError with a position within the text; one that parses is written back and
// reads as the same expression, and is drawn at 12x10 over a box of two patches holding two
// sphere fields (attributes a and b), by the input's length once or twice (overlapping), with a
// slice and a clipping plane or not: the frame draws finite hits or throws
// std::invalid_argument (an attribute the box lacks).
#include "FuzzFrame.h"
#include "iga/Csg.h"
#include "iga/Datasets.h"
#include "iga/sst/Csg.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

/// The box [-1, 1] x [-1, 1] x [-1, 1] as two degree-2 patches (split at x = 0), attributes a
/// and b the fields of two spheres.
iga::VolumeSet<double> makeBox()
{
  const double centres[2][3] = { { -0.3, 0, 0.2 }, { 0.4, 0.1, -0.2 } };
  const int degree[3] = { 2, 2, 2 };
  iga::VolumeSet<double> set;
  set.attributeNames = { "a", "b" };
  for (int half = 0; half < 2; ++half)
  {
    const double lo[3] = { half ? 0.0 : -1.0, -1, -1 }, hi[3] = { half ? 1.0 : 0.0, 1, 1 };
    iga::BezierVolume<double> patch(degree, iga::kFirstAttributeChannel + 2);
    for (int s = 0; s < 2; ++s)
    {
      const auto field =
        iga::makePolynomialVolume(iga::sphereField<double>(centres[s], 0.6), lo, hi, degree);
      for (int p = 0; p < patch.view().pointCount(); ++p)
      {
        const double* from = field.view().point(p);
        for (int c = 0; c < iga::kFirstAttributeChannel; ++c)
          patch.view().point(p)[c] = from[c];
        patch.view().point(p)[iga::kFirstAttributeChannel + s] = from[iga::kFirstAttributeChannel];
      }
    }
    set.patches.push_back(std::move(patch));
  }
  return set;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const iga::VolumeSet<double> box = makeBox();
  const std::string text(reinterpret_cast<const char*>(data), size);
  iga::csg::Expression expression;
  try
  {
    expression = iga::csg::parseExpression(text);
  }
  catch (const iga::csg::ExpressionError& e)
  {
    if (e.position() > text.size())
      std::abort(); // an error must point into the text (or at its end)
    return 0;
  }
  const std::string written = expression.text();
  if (iga::csg::parseExpression(written).text() != written)
    std::abort(); // what is written back must read as the same expression
  iga::sst::CsgScene scene;
  scene.inputs.push_back({ &box.patches, box.attributeNames, nullptr });
  if (size % 3 == 0)
    scene.inputs.push_back({ &box.patches, box.attributeNames, nullptr });
  if (size % 5 < 2)
    scene.slices.push_back({ 0.3, 1, 0, -0.1 });
  scene.expression = expression;
  scene.colorAttribute = "a";
  const iga::Camera camera = fuzzBoxCamera();
  iga::sst::Settings settings = fuzzFrameSettings(size);
  settings.backend = iga::sst::Backend::Cpu;
  if (size % 7 < 3)
    settings.clipPlanes.push_back({ 0, 0, -1, 0.4 });
  iga::sst::GBuffer out;
  try
  {
    iga::sst::renderCsg(scene, iga::sst::makeView(camera, 12, 10), settings,
      iga::sst::Method::SharedSubdivisionTree, out);
  }
  catch (const std::invalid_argument&)
  {
    return 0;
  }
  for (const auto& hit : out.hits)
    if (!std::isfinite(hit.eyeDepth) || hit.isovalue < 0 ||
        hit.isovalue >= int(expression.operands.size() + scene.slices.size()))
      std::abort();
  return 0;
}
