// CSG frames: one all-hits engine pass per kind of surface an operand has, then a
// classification of every pixel's merged hits along its ray (CsgClassification.h). An opaque
// frame of one input first finds, per pixel, a surface of the result: the nearest hit of its
// first attribute operand, where the expression changes across it (the others taken at its
// point). The passes then stop at that depth, and the few pixels where that was wrong (a crease)
// are drawn again without it.
#include "iga/sst/Csg.h"

#include "CsgClassification.h"
#include "CsgFrame.h"
#include "FramePlan.h"
#include "ParallelFor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

namespace iga
{
namespace sst
{

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

int attributeIndex(const CsgInput& input, const std::string& name)
{
  for (size_t k = 0; k < input.attributes.size(); ++k)
  {
    if (input.attributes[k] == name)
    {
      return int(k);
    }
  }
  return -1;
}

/// The colour attribute's index in the input, -1 for none.
int colourIndex(const CsgScene& scene, const CsgInput& input)
{
  return scene.colorAttribute.empty() ? -1 : attributeIndex(input, scene.colorAttribute);
}

/// Input i's boundary as outward faces, with what maps their hits back to the volumes.
void addBoundaryPass(const CsgInput& input, int i, CsgPasses& passes)
{
  CsgPass pass;
  pass.kind = CsgPass::Kind::Boundary;
  pass.input = i;
  const auto& volumes = *input.volumes;
  pass.faces = input.boundary ? *input.boundary : boundaryFaces(volumes);
  for (const PatchFace& face : pass.faces)
  {
    const auto& volume = volumes[size_t(face.patch)];
    const bool leftHanded = signedVolume(volume.view()) < 0;
    pass.reversed.push_back(faceNormalPointsInward(face, leftHanded));
    pass.surfaces.push_back(outwardFaceSurface(volume, face, leftHanded));
  }
  passes.list.push_back(std::move(pass));
}

/// The isosurfaces of one attribute in input i: one isovalue per operand naming it.
void addAttributePass(const CsgScene& scene, int i, const std::string& name, CsgPasses& passes)
{
  const csg::Expression& e = scene.expression;
  CsgPass pass;
  pass.kind = CsgPass::Kind::Attribute;
  pass.input = i;
  pass.attribute = attributeIndex(scene.inputs[size_t(i)], name);
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const csg::Operand& operand = e.operands[k];
    if (operand.kind != csg::Operand::Kind::Domain && operand.kind != csg::Operand::Kind::Plane &&
        operand.attribute == name)
    {
      pass.isovalues.push_back(operand.value);
      pass.operandOfIsovalue.push_back(int(k));
    }
  }
  passes.list.push_back(std::move(pass));
}

/// The section of input i's volumes by a plane (a Plane operand's or a Slice's, `label` its
/// CsgPass::operand): the volumes with, as their one attribute, -(a x + b y + c z + d), exact as
/// a rational function of the same weights (and the colour attribute after it), so that the
/// half-space a x + b y + c z + d >= 0 is the region below 0.
void addPlanePass(const CsgScene& scene, int i, const std::array<double, 4>& plane,
  CsgPass::Kind kind, int label, int colour, CsgPasses& passes)
{
  CsgPass pass;
  pass.kind = kind;
  pass.input = i;
  pass.operand = label;
  pass.attribute = 0;
  pass.isovalues = { 0.0 };
  const int channels = kFirstAttributeChannel + (colour >= 0 ? 2 : 1);
  for (const auto& volume : *scene.inputs[size_t(i)].volumes)
  {
    const auto from = volume.view();
    BezierVolume<double> derived(from.degree, channels);
    const auto to = derived.view();
    for (int p = 0; p < from.pointCount(); ++p)
    {
      const double* a = from.point(p);
      double* b = to.point(p);
      std::copy(a, a + kFirstAttributeChannel, b);
      b[kFirstAttributeChannel] =
        -(plane[0] * a[0] + plane[1] * a[1] + plane[2] * a[2] + plane[3] * a[kWeightChannel]);
      if (colour >= 0)
      {
        b[kFirstAttributeChannel + 1] = a[kFirstAttributeChannel + colour];
      }
    }
    pass.volumes.push_back(std::move(derived));
  }
  passes.list.push_back(std::move(pass));
}

/// Every pass the scene needs, with the operands' sources. Throws csg::ExpressionError for an
/// attribute that no input holds.
CsgPasses planPasses(const CsgScene& scene)
{
  const csg::Expression& e = scene.expression;
  CsgPasses passes;
  passes.expression = &e;
  passes.inputs = int(scene.inputs.size());
  passes.sources.assign(e.operands.size() * scene.inputs.size(), -1);
  std::map<std::string, bool> attributePassed;
  for (int i = 0; i < passes.inputs && e.root >= 0; ++i)
  {
    addBoundaryPass(scene.inputs[size_t(i)], i, passes);
  }
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const csg::Operand& operand = e.operands[k];
    if (operand.kind == csg::Operand::Kind::Below || operand.kind == csg::Operand::Kind::Above)
    {
      bool held = false;
      for (int i = 0; i < passes.inputs; ++i)
      {
        const int index = attributeIndex(scene.inputs[size_t(i)], operand.attribute);
        passes.sources[k * size_t(passes.inputs) + size_t(i)] = index;
        held = held || index >= 0;
        if (index >= 0 && !attributePassed[operand.attribute + '\n' + std::to_string(i)])
        {
          attributePassed[operand.attribute + '\n' + std::to_string(i)] = true;
          addAttributePass(scene, i, operand.attribute, passes);
        }
      }
      if (!held)
      {
        throw csg::ExpressionError(
          "no input has the attribute '" + operand.attribute + "'", operand.position);
      }
    }
    else if (operand.kind == csg::Operand::Kind::Plane)
    {
      for (int i = 0; i < passes.inputs; ++i)
      {
        addPlanePass(scene, i, operand.plane, CsgPass::Kind::Plane, int(k),
          colourIndex(scene, scene.inputs[size_t(i)]), passes);
      }
    }
  }
  for (size_t s = 0; s < scene.slices.size(); ++s)
  {
    for (int i = 0; i < passes.inputs; ++i)
    {
      addPlanePass(scene, i, scene.slices[s], CsgPass::Kind::Slice, int(e.operands.size() + s),
        colourIndex(scene, scene.inputs[size_t(i)]), passes);
    }
  }
  return passes;
}

/// The pass's own settings: all hits, the pass's attribute and isovalues, no clipping (clipping
/// planes cut the result, not the operands), the time left of the frame's deadline.
Settings passSettings(
  const CsgScene& scene, const CsgPass& pass, const Settings& settings, double msElapsed)
{
  Settings s = settings;
  s.firstHitOnly = false;
  s.clipPlanes.clear();
  s.isovalues = pass.isovalues;
  s.surfaceAttribute = pass.attribute < 0 ? 0 : pass.attribute;
  const int colour = colourIndex(scene, scene.inputs[size_t(pass.input)]);
  const bool derived = pass.kind == CsgPass::Kind::Plane || pass.kind == CsgPass::Kind::Slice;
  s.colorAttribute = derived ? (colour >= 0 ? 1 : -1) : colour;
  if (settings.deadlineMs > 0)
  {
    s.deadlineMs = std::max(settings.deadlineMs - msElapsed, 1e-6);
  }
  s.dataVersion = 0;
  return s;
}

/// Where hits of input i's volumes start in the result's patch numbering.
std::vector<int> patchOffsets(const CsgScene& scene)
{
  std::vector<int> offsets(scene.inputs.size() + 1, 0);
  for (size_t i = 0; i < scene.inputs.size(); ++i)
  {
    offsets[i + 1] = offsets[i] + int(scene.inputs[i].volumes->size());
  }
  return offsets;
}

void checkInputs(const CsgScene& scene)
{
  if (scene.inputs.empty())
  {
    throw std::invalid_argument("a CSG scene needs at least one input");
  }
  for (size_t i = 0; i < scene.inputs.size(); ++i)
  {
    if (!scene.inputs[i].volumes)
    {
      throw std::invalid_argument("CSG input " + std::to_string(i) + " has no volumes");
    }
  }
  for (size_t i = 0; i < scene.inputs.size(); ++i)
  {
    const CsgInput& input = scene.inputs[i];
    for (size_t p = 0; p < input.volumes->size(); ++p)
    {
      if ((*input.volumes)[p].degree(2) < 1)
      {
        throw std::invalid_argument("CSG input " + std::to_string(i) + ", patch " +
                                    std::to_string(p) +
                                    ": a surface (degree 0 in its third direction) bounds no "
                                    "solid; CSG inputs are volumes");
      }
    }
    for (const PatchFace& face : input.boundary ? *input.boundary : std::vector<PatchFace>())
    {
      if (face.patch < 0 || size_t(face.patch) >= input.volumes->size() || face.direction < 0 ||
          face.direction > 2 || face.side < 0 || face.side > 1)
      {
        throw std::invalid_argument(
          "CSG input " + std::to_string(i) + ": a boundary face names no face of its volumes");
      }
    }
  }
  if (scene.expression.root < 0 && scene.slices.empty())
  {
    throw std::invalid_argument("a CSG scene needs an expression or a slice");
  }
  csg::checkExpression(scene.expression);
  for (size_t s = 0; s < scene.slices.size(); ++s)
  {
    if (!csg::isPlane(scene.slices[s]))
    {
      throw std::invalid_argument("slice " + std::to_string(s) + " is not a finite plane");
    }
  }
}

} // namespace

FrameReport renderCsg(
  const CsgScene& scene, const View& view, const Settings& settings, Method method, GBuffer& out)
{
  return renderCsg(
    scene, view, settings,
    [&](const Scene& passScene, const Settings& passSettings, GBuffer& passOut)
    { return render(passScene, view, passSettings, method, passOut); },
    out);
}

namespace
{

/// The nearer of the caller's far depths and a pass's own, per pixel (either empty: none).
std::vector<double> nearerFarDepths(const Settings& settings, std::vector<double> far)
{
  if (far.empty())
    return settings.farDepths;
  for (size_t p = 0; p < settings.farDepths.size(); ++p)
    far[p] = std::min(far[p], settings.farDepths[p]);
  return far;
}

/// Runs every pass but `skip` with the far depths `far` (empty: none) within the caller's, all
/// hits.
void drawPasses(const CsgScene& scene, const Settings& settings, const std::vector<double>& far,
  int skip, const CsgPassRenderer& renderPass, CsgPasses& passes, FrameReport& report,
  Clock::time_point start)
{
  const std::vector<BezierVolume<double>> noVolumes;
  for (size_t p = 0; p < passes.list.size(); ++p)
  {
    CsgPass& pass = passes.list[p];
    if (int(p) == skip)
      continue;
    const auto& volumes = pass.kind == CsgPass::Kind::Attribute
                            ? *scene.inputs[size_t(pass.input)].volumes
                          : pass.kind == CsgPass::Kind::Boundary ? noVolumes
                                                                 : pass.volumes;
    Settings s = passSettings(scene, pass, settings, millisecondsSince(start));
    s.farDepths = nearerFarDepths(settings, far);
    addPassReport(report, renderPass(Scene(volumes, pass.surfaces), s, pass.hits));
  }
}

/// The passes classified into `out`, their peak added to the report's.
void classify(const CsgScene& scene, const View& view, const Settings& settings, CsgPasses& passes,
  FrameReport& report, GBuffer& out)
{
  // The passes' G-buffers and derived patches stay until the classification: the frame's peak
  // is the largest pass's working set and all of them.
  size_t held = 0;
  for (const CsgPass& pass : passes.list)
  {
    held += pass.hits.hits.size() * sizeof(Hit) + pass.hits.offsets.size() * sizeof(uint32_t);
    for (const auto& volume : pass.volumes)
    {
      held += size_t(volume.view().valueCount()) * sizeof(double);
    }
  }
  report.peakBytes += held;
  const auto classifyStart = Clock::now();
  passes.patchOffsets = patchOffsets(scene);
  for (const CsgInput& input : scene.inputs)
    passes.volumes.push_back(input.volumes);
  passes.slices = scene.slices.size();
  passes.view = &view;
  passes.clip = &settings.clipPlanes;
  passes.firstHitOnly = settings.firstHitOnly;
  classifyPixels(passes, threadCount(settings), out);
  report.msGBuffer += millisecondsSince(classifyStart);
}

/// The pass whose nearest hits bound an opaque frame (its first attribute pass), or -1 where
/// none does: all layers, several inputs (a point's inside of another input is not at hand), or
/// volumes reaching behind the near plane (the ray then starts inside them).
int boundingPass(
  const CsgScene& scene, const View& view, const Settings& settings, const CsgPasses& passes)
{
  if (!settings.firstHitOnly || scene.inputs.size() != 1 || scene.expression.root < 0)
    return -1;
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (const auto& volume : *scene.inputs[0].volumes)
  {
    const auto v = volume.view();
    for (int p = 0; p < v.pointCount(); ++p)
      for (int d = 0; d < 3; ++d)
      {
        lo[d] = std::min(lo[d], v.point(p)[d] / v.point(p)[kWeightChannel]);
        hi[d] = std::max(hi[d], v.point(p)[d] / v.point(p)[kWeightChannel]);
      }
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec4 clip =
      view.worldToClip * glm::dvec4(corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                           corner & 4 ? hi[2] : lo[2], 1.0);
    if (!(clip.w > 0 && clip.z > -clip.w))
      return -1;
  }
  for (size_t p = 0; p < passes.list.size(); ++p)
  {
    if (passes.list[p].kind == CsgPass::Kind::Attribute)
      return int(p);
  }
  return -1;
}

/// Whether `hit` of the attribute pass is a surface of the result: the expression differs with
/// its operand inside and outside, the other operands taken at its point (inside the volumes),
/// and no clipping plane cuts it away.
bool isResultSurface(const CsgScene& scene, const CsgPasses& passes, const CsgPass& pass,
  const Hit& hit, const Settings& settings, std::vector<uint8_t>& states,
  std::vector<uint8_t>& nodes, std::vector<double>& values)
{
  for (const auto& plane : settings.clipPlanes)
  {
    if (clippedBy(plane, hit.position))
      return false;
  }
  const csg::Expression& e = scene.expression;
  const auto& volume = (*scene.inputs[0].volumes)[size_t(hit.patch)];
  states.assign(e.operands.size(), 1);
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const csg::Operand& operand = e.operands[k];
    if (operand.kind == csg::Operand::Kind::Plane)
    {
      states[k] = planeValue(operand.plane, hit.position) >= 0 ? 1 : 0;
    }
    else if (operand.kind != csg::Operand::Kind::Domain)
    {
      const int source = passes.sources[k * size_t(passes.inputs)];
      const double value =
        attributeInVolume(volume, hit.uvw, kFirstAttributeChannel + source, values);
      states[k] =
        (operand.kind == csg::Operand::Kind::Below ? value < operand.value : value > operand.value)
          ? 1
          : 0;
    }
  }
  const size_t own = size_t(pass.operandOfIsovalue[size_t(hit.isovalue)]);
  states[own] = 1;
  const bool inside = e.contains(states, nodes);
  states[own] = 0;
  return inside != e.contains(states, nodes);
}

/// Per pixel the NDC depth just beyond the nearest hit of `hits` that is a surface of the result
/// (the engine's duplicate tolerance further along the ray), infinity where there is none;
/// `accepted`: whether there is.
std::vector<double> resultBounds(const CsgScene& scene, const View& view, const Settings& settings,
  const CsgPasses& passes, const CsgPass& pass, const GBuffer& hits, std::vector<uint8_t>& accepted)
{
  const size_t pixels = size_t(hits.width) * size_t(hits.height);
  std::vector<double> far(pixels, INFINITY);
  accepted.assign(pixels, 0);
  parallelFor(pixels, threadCount(settings),
    [&](size_t begin, size_t end)
    {
      std::vector<uint8_t> states, nodes;
      std::vector<double> values;
      for (size_t p = begin; p < end; ++p)
      {
        if (hits.offsets[p] == hits.offsets[p + 1])
          continue;
        const Hit& hit = hits.hits[hits.offsets[p]];
        if (!isResultSurface(scene, passes, pass, hit, settings, states, nodes, values))
          continue;
        const glm::dvec3 ray =
          view.parallel ? view.forward : glm::normalize(hit.position - view.eye);
        const double step = 2e-4 * view.pixelFootprint * (view.parallel ? 1.0 : hit.eyeDepth);
        const glm::dvec4 clip = view.worldToClip * glm::dvec4(hit.position + step * ray, 1.0);
        far[p] = std::max(clip.z / clip.w, hit.ndcDepth);
        accepted[p] = 1;
      }
    });
  return far;
}

/// `into` with the hits of `from` at the pixels `take` marks.
GBuffer splicePixels(const GBuffer& into, const GBuffer& from, const std::vector<uint8_t>& take)
{
  GBuffer out;
  out.width = into.width;
  out.height = into.height;
  const size_t pixels = size_t(into.width) * size_t(into.height);
  out.offsets.assign(pixels + 1, 0);
  for (size_t p = 0; p < pixels; ++p)
  {
    const GBuffer& source = take[p] ? from : into;
    out.hits.insert(out.hits.end(), source.hits.begin() + source.offsets[p],
      source.hits.begin() + source.offsets[p + 1]);
    out.offsets[p + 1] = uint32_t(out.hits.size());
  }
  return out;
}

/// The bounding pass: its nearest hits first, to bound the others (returned); then all its hits
/// where the nearest is no surface of the result.
std::vector<double> drawBoundingPass(const CsgScene& scene, const View& view,
  const Settings& settings, int bounding, const CsgPassRenderer& renderPass, CsgPasses& passes,
  FrameReport& report, Clock::time_point start)
{
  CsgPass& pass = passes.list[size_t(bounding)];
  const Scene passScene(*scene.inputs[0].volumes);
  Settings s = passSettings(scene, pass, settings, millisecondsSince(start));
  s.firstHitOnly = true;
  GBuffer nearest;
  addPassReport(report, renderPass(passScene, s, nearest));
  std::vector<uint8_t> accepted;
  std::vector<double> far = resultBounds(scene, view, settings, passes, pass, nearest, accepted);
  // Where the nearest hit is the result's, it is the pass's only hit in front of the bound.
  s = passSettings(scene, pass, settings, millisecondsSince(start));
  std::vector<double> skipped(far.size(), INFINITY);
  for (size_t p = 0; p < far.size(); ++p)
  {
    const bool none = nearest.offsets[p] == nearest.offsets[p + 1];
    skipped[p] = accepted[p] || none ? -2.0 : INFINITY;
  }
  s.farDepths = nearerFarDepths(settings, std::move(skipped));
  GBuffer rest;
  addPassReport(report, renderPass(passScene, s, rest));
  pass.hits = splicePixels(rest, nearest, accepted);
  return far;
}

} // namespace

FrameReport renderCsg(const CsgScene& scene, const View& view, const Settings& settings,
  const CsgPassRenderer& renderPass, GBuffer& out)
{
  const auto start = Clock::now();
  checkInputs(scene);
  checkClipPlanes(settings); // they cut the result, so the passes do not see them
  CsgPasses passes = planPasses(scene);
  FrameReport report;
  const int bounding = boundingPass(scene, view, settings, passes);
  std::vector<double> far;
  if (bounding >= 0)
    far = drawBoundingPass(scene, view, settings, bounding, renderPass, passes, report, start);
  drawPasses(scene, settings, far, bounding, renderPass, passes, report, start);
  classify(scene, view, settings, passes, report, out);
  if (bounding >= 0)
  {
    // Where the bound held no surface of the result, the pixel is drawn again without it.
    std::vector<uint8_t> again(far.size(), 0);
    std::vector<double> unbounded(far.size(), -2.0);
    size_t count = 0;
    for (size_t p = 0; p < far.size(); ++p)
    {
      // Any hit found lies in front of the bound and is the pixel's (a slice in front too).
      if (far[p] < INFINITY && out.offsets[p] == out.offsets[p + 1])
      {
        again[p] = 1;
        unbounded[p] = INFINITY;
        ++count;
      }
    }
    if (count > 0)
    {
      CsgPasses redrawn = planPasses(scene);
      GBuffer fixed;
      drawPasses(scene, settings, unbounded, -1, renderPass, redrawn, report, start);
      classify(scene, view, settings, redrawn, report, fixed);
      out = splicePixels(out, fixed, again);
    }
  }
  report.msTotal = millisecondsSince(start);
  return report;
}

} // namespace sst
} // namespace iga
