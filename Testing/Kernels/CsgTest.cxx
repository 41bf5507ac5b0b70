// CSG: the expression grammar, and CSG frames against two independent references: exact
// intervals of analytic solids along each ray, and dense sampling with bisection.
#include "AnalyticTruth.h"

#include "iga/Csg.h"
#include "iga/Datasets.h"
#include "iga/sst/Csg.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{

using iga::csg::Expression;
using iga::csg::ExpressionError;
using iga::csg::Operand;
using iga::csg::parseExpression;

// ---- the grammar -----------------------------------------------------------------------------

size_t errorPosition(const std::string& text)
{
  try
  {
    parseExpression(text);
  }
  catch (const ExpressionError& e)
  {
    return e.position();
  }
  ADD_FAILURE() << "no error for " << text;
  return std::string::npos;
}

TEST(CsgExpression, IntersectionBindsTighterUnionAndDifferenceGoLeftToRight)
{
  EXPECT_EQ(parseExpression("a<0 | b<0 & c<0").text(), "(\"a\"<0 | (\"b\"<0 & \"c\"<0))");
  EXPECT_EQ(parseExpression("a<0 - b<0 | c<0").text(), "((\"a\"<0 - \"b\"<0) | \"c\"<0)");
  EXPECT_EQ(parseExpression("a<0 - (b<0 | c<0)").text(), "(\"a\"<0 - (\"b\"<0 | \"c\"<0))");
  EXPECT_EQ(parseExpression("cube<0 - pips<0").text(), "(\"cube\"<0 - \"pips\"<0)");
  EXPECT_EQ(parseExpression("domain&plane(1, 0,-2, +0.5)").text(), "(domain & plane(1,0,-2,0.5))");
}

TEST(CsgExpression, CutByHalfSpacesIntersectsTheSolidOrTheDomain)
{
  using iga::csg::cutByHalfSpaces;
  EXPECT_EQ(cutByHalfSpaces("a<0 | b<0", {}), "a<0 | b<0");
  EXPECT_EQ(parseExpression(cutByHalfSpaces("a<0 | b<0", { { 0, 0, 1, -0.25 } })).text(),
    "((\"a\"<0 | \"b\"<0) & plane(0,0,1,-0.25))");
  EXPECT_EQ(parseExpression(cutByHalfSpaces(" ", { { 1, 0, 0, 0 }, { 0, 1, 0, 0.1 } })).text(),
    "((domain & plane(1,0,0,0)) & plane(0,1,0,0.10000000000000001))");
  EXPECT_THROW(parseExpression(cutByHalfSpaces("a<", { { 1, 0, 0, 0 } })), ExpressionError);
}

TEST(CsgExpression, OperandsKeepTheirValuesNamesAndPositions)
{
  const Expression e = parseExpression("  \"Temperature (K)\">300 & s.x_1<-1.5e-3");
  ASSERT_EQ(e.operands.size(), 2u);
  EXPECT_EQ(e.operands[0].kind, Operand::Kind::Above);
  EXPECT_EQ(e.operands[0].attribute, "Temperature (K)");
  EXPECT_EQ(e.operands[0].value, 300);
  EXPECT_EQ(e.operands[0].position, 2u);
  EXPECT_EQ(e.operands[1].kind, Operand::Kind::Below);
  EXPECT_EQ(e.operands[1].attribute, "s.x_1");
  EXPECT_EQ(e.operands[1].value, -1.5e-3);
  EXPECT_EQ(e.operands[1].position, 26u);
  // An attribute may be called domain or plane: a comparison makes it one.
  EXPECT_EQ(parseExpression("domain<1").operands[0].kind, Operand::Kind::Below);
}

TEST(CsgExpression, ContainsFollowsTheOperators)
{
  const Expression e = parseExpression("a<0 - b<0 | c<0 & d<0");
  std::vector<uint8_t> scratch;
  for (int bits = 0; bits < 16; ++bits)
  {
    const std::vector<uint8_t> in = { uint8_t(bits & 1), uint8_t((bits >> 1) & 1),
      uint8_t((bits >> 2) & 1), uint8_t((bits >> 3) & 1) };
    const bool expected = (in[0] && !in[1]) || (in[2] && in[3]);
    EXPECT_EQ(e.contains(in, scratch), expected) << "states " << bits;
  }
}

TEST(CsgExpression, ErrorsNameTheProblemAndItsPosition)
{
  EXPECT_EQ(errorPosition("a<"), 2u);
  EXPECT_EQ(errorPosition("a<0 |"), 5u);
  EXPECT_EQ(errorPosition("x<1 & (a<0"), 6u);
  EXPECT_EQ(errorPosition("(a<0 b<0)"), 5u);
  EXPECT_EQ(errorPosition("a<0 b<0"), 4u);
  EXPECT_EQ(errorPosition("a<0 & foo"), 6u);
  EXPECT_EQ(errorPosition("plane(1,0,0)"), 11u);
  EXPECT_EQ(errorPosition("domain | plane(0,0,0,1)"), 9u);
  EXPECT_EQ(errorPosition("a<nan"), 2u);
  EXPECT_EQ(errorPosition("a<1e999"), 2u);
  EXPECT_EQ(errorPosition("\"a<0"), 0u);
  EXPECT_EQ(errorPosition("a<0 & #"), 6u);
  EXPECT_EQ(errorPosition(""), 0u);
  EXPECT_EQ(errorPosition(std::string("a<0\0", 4)), 3u);
  std::string many = "a<0";
  for (int k = 1; k < iga::csg::kMaxOperands; ++k)
    many += " | a<" + std::to_string(k);
  EXPECT_NO_THROW(parseExpression(many));
  EXPECT_EQ(errorPosition(many + " | b<0"), many.size() + 3);
  const std::string deep =
    std::string(iga::csg::kMaxNesting, '(') + "a<0" + std::string(iga::csg::kMaxNesting, ')');
  EXPECT_NO_THROW(parseExpression(deep));
  EXPECT_EQ(errorPosition("(" + deep + ")"), size_t(iga::csg::kMaxNesting));
  EXPECT_EQ(errorPosition("a<+-3"), 2u);
  EXPECT_EQ(errorPosition("a<1e-400"), 2u);
  try
  {
    parseExpression("a<0 | b");
    FAIL() << "no error";
  }
  catch (const ExpressionError& e)
  {
    EXPECT_EQ(std::string(e.what()),
      "'b' needs '<' or '>' and a value (or is it domain or plane?) at position 6");
  }
  // Quoted, domain and plane are attributes' names.
  EXPECT_EQ(errorPosition("\"domain\""), 0u);
  EXPECT_EQ(parseExpression("\"plane\">2").operands[0].kind, Operand::Kind::Above);
}

// ---- scenes ------------------------------------------------------------------------------------

/// The box [-1, 1]^3 cut into cells^3 patches of degree 2 (identity geometry), attribute k the
/// field of sphere k: its solid below 0 is the sphere's inside.
iga::VolumeSet<double> boxWithSpheres(const std::vector<iga::Sphere>& spheres, int cells)
{
  iga::VolumeSet<double> set;
  for (size_t k = 0; k < spheres.size(); ++k)
    set.attributeNames.push_back("s" + std::to_string(k));
  const int degree[3] = { 2, 2, 2 };
  const int channels = iga::kFirstAttributeChannel + int(spheres.size());
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i)
      {
        const int cell[3] = { i, j, k };
        double lo[3], hi[3];
        for (int d = 0; d < 3; ++d)
        {
          lo[d] = -1 + 2.0 * cell[d] / cells;
          hi[d] = -1 + 2.0 * (cell[d] + 1) / cells;
        }
        iga::BezierVolume<double> patch(degree, channels);
        for (size_t s = 0; s < spheres.size(); ++s)
        {
          const auto field = iga::makePolynomialVolume(
            iga::sphereField<double>(spheres[s].centre, spheres[s].radius), lo, hi, degree);
          for (int p = 0; p < patch.view().pointCount(); ++p)
          {
            const double* from = field.view().point(p);
            std::copy(from, from + iga::kFirstAttributeChannel, patch.view().point(p));
            patch.view().point(p)[iga::kFirstAttributeChannel + s] =
              from[iga::kFirstAttributeChannel];
          }
        }
        set.patches.push_back(std::move(patch));
      }
  return set;
}

double sphereValue(const iga::Sphere& s, const glm::dvec3& x)
{
  const glm::dvec3 c(s.centre[0], s.centre[1], s.centre[2]);
  return glm::dot(x - c, x - c) - s.radius * s.radius;
}

double planeValue(const Operand& o, const glm::dvec3& x)
{
  return o.plane[0] * x[0] + o.plane[1] * x[1] + o.plane[2] * x[2] + o.plane[3];
}

bool inBox(const glm::dvec3& x, double slack)
{
  return std::abs(x[0]) <= 1 + slack && std::abs(x[1]) <= 1 + slack && std::abs(x[2]) <= 1 + slack;
}

/// The scene's operands' solids at a point: attribute "sN" is sphere N, a plane its half-space,
/// both within the box.
std::vector<uint8_t> operandsAt(
  const Expression& e, const std::vector<iga::Sphere>& spheres, const glm::dvec3& x)
{
  std::vector<uint8_t> in(e.operands.size());
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const Operand& o = e.operands[k];
    const bool box = inBox(x, 0);
    switch (o.kind)
    {
      case Operand::Kind::Domain:
        in[k] = box;
        break;
      case Operand::Kind::Plane: // the half-space within the box
        in[k] = box && planeValue(o, x) >= 0;
        break;
      default:
      {
        const double f = sphereValue(spheres[size_t(std::stoi(o.attribute.substr(1)))], x);
        in[k] = box && (o.kind == Operand::Kind::Below ? f - o.value < 0 : f - o.value > 0);
      }
    }
  }
  return in;
}

/// A reference first hit: ray parameter (inf for none), the surface it lies on (-1 the box,
/// else the operand), its unit normal, and the side.
struct ReferenceHit
{
  double t = INFINITY;
  int surface = -2;
  glm::dvec3 normal{ 0, 0, 0 };
  bool entering = true; ///< whether the ray enters the result there
};

/// The surface through x among the box and the operands', by the smallest distance.
ReferenceHit surfaceAt(
  const Expression& e, const std::vector<iga::Sphere>& spheres, const glm::dvec3& x, double t)
{
  ReferenceHit hit;
  hit.t = t;
  double best = INFINITY;
  for (int d = 0; d < 3; ++d)
  {
    const double distance = 1 - std::abs(x[d]);
    if (distance < best)
    {
      best = distance;
      hit.surface = -1;
      hit.normal = glm::dvec3(0);
      hit.normal[d] = 1;
    }
  }
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const Operand& o = e.operands[k];
    double distance = INFINITY;
    glm::dvec3 normal;
    if (o.kind == Operand::Kind::Plane)
    {
      const glm::dvec3 n(o.plane[0], o.plane[1], o.plane[2]);
      distance = std::abs(planeValue(o, x)) / glm::length(n);
      normal = glm::normalize(n);
    }
    else if (o.kind != Operand::Kind::Domain)
    {
      const iga::Sphere& s = spheres[size_t(std::stoi(o.attribute.substr(1)))];
      const glm::dvec3 c(s.centre[0], s.centre[1], s.centre[2]);
      const double radius = std::sqrt(s.radius * s.radius + o.value);
      distance = std::abs(glm::length(x - c) - radius);
      normal = glm::normalize(x - c);
    }
    if (distance < best)
    {
      best = distance;
      hit.surface = int(k);
      hit.normal = normal;
    }
  }
  return hit;
}

/// Intervals of a ray inside a solid, sorted and disjoint; +-kFar stands for unbounded.
using Intervals = std::vector<std::array<double, 2>>;
constexpr double kFar = 1e300;

bool within(const Intervals& a, double t)
{
  for (const auto& interval : a)
    if (interval[0] < t && t < interval[1])
      return true;
  return false;
}

Intervals combine(const Intervals& a, const Intervals& b, Expression::Op op)
{
  std::vector<double> ends = { -kFar, kFar };
  for (const Intervals* list : { &a, &b })
    for (const auto& interval : *list)
      ends.insert(ends.end(), { interval[0], interval[1] });
  std::sort(ends.begin(), ends.end());
  Intervals result;
  for (size_t k = 0; k + 1 < ends.size(); ++k)
  {
    const double middle = 0.5 * (ends[k] + ends[k + 1]);
    const bool inA = within(a, middle), inB = within(b, middle);
    const bool in = op == Expression::Op::Union          ? inA || inB
                    : op == Expression::Op::Intersection ? inA && inB
                                                         : inA && !inB;
    if (!in || ends[k] == ends[k + 1])
      continue;
    if (!result.empty() && result.back()[1] == ends[k])
      result.back()[1] = ends[k + 1];
    else
      result.push_back({ ends[k], ends[k + 1] });
  }
  return result;
}

Intervals boxIntervals(const glm::dvec3& o, const glm::dvec3& d)
{
  double lo = -kFar, hi = kFar;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0)
    {
      if (std::abs(o[a]) > 1)
        return {};
      continue;
    }
    double t0 = (-1 - o[a]) / d[a], t1 = (1 - o[a]) / d[a];
    if (t0 > t1)
      std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  return lo < hi ? Intervals{ { lo, hi } } : Intervals{};
}

Intervals sphereIntervals(
  const iga::Sphere& s, double value, const glm::dvec3& o, const glm::dvec3& d)
{
  const glm::dvec3 c(s.centre[0], s.centre[1], s.centre[2]);
  const double a = glm::dot(d, d), b = 2 * glm::dot(o - c, d),
               cc = glm::dot(o - c, o - c) - s.radius * s.radius - value;
  const double disc = b * b - 4 * a * cc;
  if (disc <= 0)
    return {};
  const double root = std::sqrt(disc);
  return { { (-b - root) / (2 * a), (-b + root) / (2 * a) } };
}

/// The exact first drawn hit of the expression along a ray: the first end of the result's
/// intervals lying in the box (surfaces are drawn within the volumes only).
ReferenceHit exactFirstHit(const Expression& e, const std::vector<iga::Sphere>& spheres,
  const glm::dvec3& o, const glm::dvec3& d)
{
  const Intervals box = boxIntervals(o, d);
  std::vector<Intervals> at(e.nodes.size());
  for (size_t n = 0; n < e.nodes.size(); ++n)
  {
    const Expression::Node& node = e.nodes[n];
    if (node.op != Expression::Op::Leaf)
    {
      at[n] = combine(at[size_t(node.left)], at[size_t(node.right)], node.op);
      continue;
    }
    const Operand& op = e.operands[size_t(node.operand)];
    if (op.kind == Operand::Kind::Domain)
      at[n] = box;
    else if (op.kind == Operand::Kind::Plane)
    {
      const double along = op.plane[0] * d[0] + op.plane[1] * d[1] + op.plane[2] * d[2];
      const double t = -planeValue(op, o) / along;
      at[n] = combine(box, along > 0 ? Intervals{ { t, kFar } } : Intervals{ { -kFar, t } },
        Expression::Op::Intersection);
    }
    else
    {
      const Intervals s =
        sphereIntervals(spheres[size_t(std::stoi(op.attribute.substr(1)))], op.value, o, d);
      at[n] = combine(box, s,
        op.kind == Operand::Kind::Below ? Expression::Op::Intersection
                                        : Expression::Op::Difference);
    }
  }
  for (const auto& interval : at[size_t(e.root)])
    for (int end = 0; end < 2; ++end)
    {
      const double t = interval[size_t(end)];
      if (t > 0 && std::abs(t) < kFar && inBox(o + t * d, 1e-9))
      {
        ReferenceHit hit = surfaceAt(e, spheres, o + t * d, t);
        hit.entering = end == 0;
        return hit;
      }
    }
  return {};
}

/// Every drawn hit by brute force: the result's inside sampled densely along the ray through
/// the box (from just before it to just after it), each change located by bisection.
std::vector<ReferenceHit> sampledHits(const Expression& e, const std::vector<iga::Sphere>& spheres,
  const glm::dvec3& o, const glm::dvec3& d)
{
  const Intervals box = boxIntervals(o, d);
  if (box.empty() || box[0][1] <= 0)
    return {};
  std::vector<uint8_t> scratch;
  auto inside = [&](double t) { return e.contains(operandsAt(e, spheres, o + t * d), scratch); };
  const double t0 = std::max(box[0][0], 0.0), t1 = box[0][1];
  const double margin = 1e-9 * (t1 - t0);
  const int samples = 2000;
  double previous = t0 - margin;
  bool state = inside(previous);
  std::vector<ReferenceHit> hits;
  for (int s = 0; s <= samples + 1; ++s)
  {
    const double next = s <= samples ? t0 + (t1 - t0) * s / samples : t1 + margin;
    if (inside(next) != state)
    {
      double a = previous, b = next;
      for (int k = 0; k < 60; ++k)
      {
        const double m = 0.5 * (a + b);
        (inside(m) == state ? a : b) = m;
      }
      hits.push_back(surfaceAt(e, spheres, o + b * d, b));
      hits.back().entering = !state;
      state = !state;
    }
    previous = next;
  }
  return hits;
}

ReferenceHit sampledFirstHit(const Expression& e, const std::vector<iga::Sphere>& spheres,
  const glm::dvec3& o, const glm::dvec3& d)
{
  const auto hits = sampledHits(e, spheres, o, d);
  return hits.empty() ? ReferenceHit() : hits.front();
}

struct CsgComparison
{
  int compared = 0, ambiguous = 0, mismatched = 0, covered = 0;
  double maxPositionError = 0, maxNormalError = 0;
};

/// A CSG frame's first hits against a reference, pixels next to a change of the reference's
/// surface or coverage (creases, silhouettes) set aside.
/// A reference per pixel of a w x h image along the pixel's ray (origins and directions kept).
template<class Truth>
struct ReferenceImage
{
  int w, h;
  std::vector<Truth> truth;
  std::vector<glm::dvec3> origins, directions;

  ReferenceImage(const iga::Camera& camera, int width, int height,
    const std::function<Truth(const glm::dvec3&, const glm::dvec3&)>& reference)
    : w(width)
    , h(height)
    , truth(size_t(width) * height)
    , origins(truth.size())
    , directions(truth.size())
  {
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i)
      {
        const size_t p = size_t(j) * w + i;
        igatest::truth::pixelRay(camera, w, h, i, j, origins[p], directions[p]);
        truth[p] = reference(origins[p], directions[p]);
      }
  }

  /// Whether pixel (i, j)'s 3x3 neighbourhood differs from the pixel in `key`: a crease or
  /// silhouette passes nearby and the pixel may go either way.
  template<class Key>
  bool ambiguousAt(int i, int j, const Key& key) const
  {
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
      {
        const int ni = std::clamp(i + di, 0, w - 1), nj = std::clamp(j + dj, 0, h - 1);
        if (key(truth[size_t(nj) * w + ni]) != key(truth[size_t(j) * w + i]))
          return true;
      }
    return false;
  }
};

CsgComparison compareWithReference(const iga::sst::GBuffer& gbuffer, const iga::Camera& camera,
  const std::function<ReferenceHit(const glm::dvec3&, const glm::dvec3&)>& reference)
{
  const ReferenceImage<ReferenceHit> image(camera, gbuffer.width, gbuffer.height, reference);
  const auto& truth = image.truth;
  const int w = image.w, h = image.h;
  CsgComparison result;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const size_t p = size_t(j) * w + i;
      if (image.ambiguousAt(i, j, [](const ReferenceHit& hit) { return hit.surface; }))
      {
        ++result.ambiguous;
        continue;
      }
      ++result.compared;
      const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
      if ((hit != nullptr) != std::isfinite(truth[p].t))
      {
        ++result.mismatched;
        continue;
      }
      if (!hit)
        continue;
      ++result.covered;
      const glm::dvec3 x = image.origins[p] + truth[p].t * image.directions[p];
      result.maxPositionError = std::max(result.maxPositionError, glm::length(hit->position - x));
      result.maxNormalError =
        std::max(result.maxNormalError, 1 - std::abs(glm::dot(hit->normal, truth[p].normal)));
      EXPECT_EQ(hit->entersBelow, truth[p].entering) << "the side of pixel " << i << "," << j;
    }
  return result;
}

/// Every layer of a CSG frame against the sampled reference, pixels whose neighbours' layers
/// lie on other surfaces (creases, silhouettes, near tangencies) set aside.
CsgComparison compareAllLayers(const iga::sst::GBuffer& gbuffer, const iga::Camera& camera,
  const Expression& e, const std::vector<iga::Sphere>& spheres)
{
  const ReferenceImage<std::vector<ReferenceHit>> image(camera, gbuffer.width, gbuffer.height,
    [&](const glm::dvec3& o, const glm::dvec3& d) { return sampledHits(e, spheres, o, d); });
  const auto& truth = image.truth;
  const int w = image.w, h = image.h;
  auto surfaces = [](const std::vector<ReferenceHit>& hits)
  {
    std::vector<int> ids;
    for (const auto& hit : hits)
      ids.push_back(hit.surface);
    return ids;
  };
  CsgComparison result;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const size_t p = size_t(j) * w + i;
      if (image.ambiguousAt(i, j, surfaces))
      {
        ++result.ambiguous;
        continue;
      }
      ++result.compared;
      if (gbuffer.hitCount(i, j) != int(truth[p].size()))
      {
        ++result.mismatched;
        continue;
      }
      result.covered += truth[p].empty() ? 0 : 1;
      for (size_t k = 0; k < truth[p].size(); ++k)
      {
        const iga::sst::Hit& hit = gbuffer.firstHit(i, j)[k];
        const glm::dvec3 x = image.origins[p] + truth[p][k].t * image.directions[p];
        result.maxPositionError = std::max(result.maxPositionError, glm::length(hit.position - x));
        EXPECT_EQ(hit.entersBelow, truth[p][k].entering) << "pixel " << i << "," << j;
      }
    }
  return result;
}

struct CsgCase
{
  iga::VolumeSet<double> set;
  std::vector<iga::Sphere> spheres;
  iga::Camera camera;
};

CsgCase makeCase(const std::vector<iga::Sphere>& spheres, const glm::dvec3& eye)
{
  CsgCase c;
  c.spheres = spheres;
  c.set = boxWithSpheres(spheres, 2);
  const double bounds[6] = { -1, 1, -1, 1, -1, 1 };
  c.camera = igatest::truth::makeCamera(eye, { 0, 0, 0 }, { 0, 0, 1 }, 40, bounds);
  return c;
}

iga::sst::GBuffer renderCase(const CsgCase& c, const std::string& text, int size,
  bool firstHitOnly = true, iga::sst::Method method = iga::sst::Method::SharedSubdivisionTree)
{
  iga::sst::CsgScene scene;
  scene.inputs.push_back({ &c.set.patches, c.set.attributeNames, nullptr });
  scene.expression = parseExpression(text);
  iga::sst::Settings settings;
  settings.width = settings.height = size;
  settings.firstHitOnly = firstHitOnly;
  iga::sst::GBuffer out;
  const auto report =
    iga::sst::renderCsg(scene, iga::sst::makeView(c.camera, size, size), settings, method, out);
  EXPECT_EQ(report.unresolvedPixels, 0u) << text;
  return out;
}

void expectExact(const CsgCase& c, const std::string& text, int minimumCovered)
{
  const auto gbuffer = renderCase(c, text, 96);
  const Expression e = parseExpression(text);
  const auto result = compareWithReference(gbuffer, c.camera,
    [&](const glm::dvec3& o, const glm::dvec3& d) { return exactFirstHit(e, c.spheres, o, d); });
  EXPECT_EQ(result.mismatched, 0) << text;
  EXPECT_GE(result.covered, minimumCovered) << text;
  EXPECT_LT(result.maxPositionError, 1e-6) << text;
  EXPECT_LT(result.maxNormalError, 1e-6) << text;
}

const glm::dvec3 kEye(3.2, -2.4, 2.6);

TEST(CsgFrame, CubeMinusSphereAgainstExactIntervals)
{
  // The sphere reaches out of the box's top face: the dent is the sphere's inside, the box's
  // faces around it are kept.
  expectExact(makeCase({ { { 0.2, -0.1, 1.0 }, 0.6 } }, kEye), "domain - s0<0", 3500);
}

TEST(CsgFrame, UnionOfTwoOverlappingSpheres)
{
  expectExact(makeCase({ { { -0.3, 0.1, 0 }, 0.55 }, { { 0.3, -0.1, 0.1 }, 0.5 } }, kEye),
    "s0<0 | s1<0", 600);
}

TEST(CsgFrame, SphereIntersectedWithASlabOfTwoPlanes)
{
  expectExact(makeCase({ { { 0, 0, 0 }, 0.8 } }, kEye),
    "s0<0 & plane(0, 0, 1, 0.3) & plane(0, 0, -1, 0.3)", 1000);
}

TEST(CsgFrame, SolidReachingTheDomainBoundaryIsCappedByIt)
{
  // The sphere sticks out of the box on two sides: the box closes it with flat caps.
  expectExact(makeCase({ { { 0.5, 0, 0.6 }, 0.75 } }, kEye), "s0<0", 1200);
}

TEST(CsgFrame, SolidCrossingTheDomainWithoutItsIsosurface)
{
  // Rays through the caps on two faces see no sphere between them: the attribute's sign there
  // comes from its value on the boundary.
  const CsgCase c = makeCase({ { { 0, 0, 0 }, 1.3 } }, kEye);
  expectExact(c, "s0<0", 3000);
  expectExact(c, "domain - s0<0", 1000);
}

TEST(CsgFrame, SphereTangentToAPlane)
{
  const CsgCase c = makeCase({ { { 0, 0, -0.2 }, 0.5 } }, kEye);
  expectExact(c, "s0<0 | plane(0, 0, 1, -0.3)", 1300);
  expectExact(c, "s0<0 - plane(0, 0, 1, -0.3)", 400);
  expectExact(c, "domain - plane(0, 0, 1, -0.3) - s0<0", 2000);
}

TEST(CsgFrame, AboveAndTwoValuesOfOneAttribute)
{
  const CsgCase c = makeCase({ { { 0.1, 0, 0 }, 0.5 } }, kEye);
  expectExact(c, "s0<0.5 & s0>0", 1500); // a shell between the radii 0.5 and sqrt(0.5)
  expectExact(c, "s0>0.2", 3000);
}

TEST(CsgFrame, AllLayersAlternateBetweenEnteringAndLeaving)
{
  const CsgCase c = makeCase({ { { 0.2, -0.1, 1.0 }, 0.6 }, { { -0.4, 0.3, -0.2 }, 0.4 } }, kEye);
  const auto all = renderCase(c, "domain - s0<0 - s1<0", 64, false);
  const auto first = renderCase(c, "domain - s0<0 - s1<0", 64, true);
  int layered = 0;
  for (int j = 0; j < all.height; ++j)
    for (int i = 0; i < all.width; ++i)
    {
      const int count = all.hitCount(i, j);
      ASSERT_EQ(count > 0, first.hitCount(i, j) > 0);
      layered += count >= 4 ? 1 : 0;
      const iga::sst::Hit* hits = all.firstHit(i, j);
      for (int k = 0; k < count; ++k)
      {
        EXPECT_EQ(hits[k].entersBelow, k % 2 == 0) << "pixel " << i << "," << j;
        if (k > 0)
        {
          EXPECT_LE(hits[k - 1].eyeDepth, hits[k].eyeDepth);
        }
      }
      if (count > 0)
      {
        EXPECT_EQ(hits[0].eyeDepth, first.firstHit(i, j)->eyeDepth);
      }
    }
  EXPECT_GT(layered, 100) << "rays through the cavity cross it";
}

TEST(CsgFrame, HitsNameTheOperandAndTheVolumeParameter)
{
  const CsgCase c = makeCase({ { { 0.2, -0.1, 1.0 }, 0.6 } }, kEye);
  const auto gbuffer = renderCase(c, "domain - s0<0", 64);
  int onSphere = 0, onBox = 0;
  for (const auto& hit : gbuffer.hits)
  {
    ASSERT_GE(hit.patch, 0);
    ASSERT_LT(hit.patch, int(c.set.patches.size()));
    double values[iga::kFirstAttributeChannel + 1];
    iga::evaluateHomogeneous<double, 3>(
      c.set.patches[size_t(hit.patch)].view(), &hit.uvw[0], values, nullptr);
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(values[d] / values[iga::kWeightChannel], hit.position[d], 1e-9);
    (hit.isovalue == 1 ? onSphere : onBox) += 1;
    EXPECT_TRUE(hit.isovalue == 0 || hit.isovalue == 1);
  }
  EXPECT_GT(onSphere, 100);
  EXPECT_GT(onBox, 100);
}

/// An opaque frame (its passes bounded by the result's nearest surface found first) against the
/// first layer of every-layer frame (unbounded passes): the same surface at every pixel.
void expectFirstLayers(
  const iga::sst::GBuffer& opaque, const iga::sst::GBuffer& layers, const std::string& text)
{
  int differing = 0, covered = 0;
  for (int j = 0; j < opaque.height; ++j)
    for (int i = 0; i < opaque.width; ++i)
    {
      const iga::sst::Hit* a = opaque.firstHit(i, j);
      const iga::sst::Hit* b = layers.firstHit(i, j);
      covered += a ? 1 : 0;
      differing += (a == nullptr) != (b == nullptr) ||
                       (a && (a->isovalue != b->isovalue || a->patch != b->patch ||
                               glm::length(a->position - b->position) > 1e-9))
                     ? 1
                     : 0;
    }
  EXPECT_EQ(differing, 0) << text << ": " << covered << " pixels covered";
}

TEST(CsgFrame, RandomTreesAgainstDenseSampling)
{
  std::mt19937 random(20261202);
  std::uniform_real_distribution<double> unit(-1, 1);
  int trees = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    std::vector<iga::Sphere> spheres(3);
    for (auto& s : spheres)
    {
      for (double& x : s.centre)
        x = 0.7 * unit(random);
      s.radius = 0.45 + 0.25 * unit(random);
    }
    // 3 to 8 operands joined by random operators, parenthesised at random.
    const int count = 3 + trial % 6;
    std::string text;
    for (int k = 0; k < count; ++k)
    {
      const int kind = int(random() % 5);
      std::string operand =
        kind == 0   ? "domain"
        : kind == 1 ? "plane(" + std::to_string(unit(random)) + "," + std::to_string(unit(random)) +
                        ",1," + std::to_string(0.5 * unit(random)) + ")"
                    : "s" + std::to_string(random() % 3) + (kind == 4 ? ">" : "<") +
                        std::to_string(0.1 * unit(random));
      if (k > 0)
        text += std::string(" ") + "|&-"[random() % 3] + " ";
      const bool group = k + 1 < count && random() % 3 == 0;
      text += group ? "(" + operand : operand;
      if (group)
      {
        text +=
          std::string(" ") + "|&-"[random() % 3] + " s" + std::to_string(random() % 3) + "<0)";
        ++k;
      }
    }
    const Expression e = parseExpression(text);
    const glm::dvec3 eye(3.2 * unit(random), 3.2 * unit(random), 2.5 + unit(random));
    CsgCase c = makeCase(spheres, eye);
    const auto gbuffer = renderCase(c, text, 64);
    const auto result = compareWithReference(gbuffer, c.camera,
      [&](const glm::dvec3& o, const glm::dvec3& d) { return sampledFirstHit(e, spheres, o, d); });
    EXPECT_EQ(result.mismatched, 0) << text;
    EXPECT_LT(result.maxPositionError, 1e-6) << text;
    trees += result.covered > 100 ? 1 : 0;
    // Every layer, as a translucent view draws them (at 32x32: the reference samples each ray
    // whole).
    const auto all = renderCase(c, text, 32, false);
    const auto layers = compareAllLayers(all, c.camera, e, spheres);
    expectFirstLayers(renderCase(c, text, 32, true), all, text);
    EXPECT_EQ(layers.mismatched, 0) << text << " (all layers)";
    EXPECT_LT(layers.maxPositionError, 1e-6) << text << " (all layers)";
    EXPECT_GT(layers.compared, layers.ambiguous) << text << " (all layers)";
  }
  EXPECT_GE(trees, 6) << "most random trees show something";
}

TEST(CsgFrame, TwoInputsMeetingAtAFace)
{
  // The box's halves x < 0 and x > 0 as two inputs: rays cross from one to the other where
  // each has a boundary face; the result is that of the whole box.
  const CsgCase c = makeCase({ { { 0.2, -0.1, 1.0 }, 0.6 }, { { -0.1, 0.2, 0 }, 0.9 } }, kEye);
  std::vector<iga::BezierVolume<double>> halves[2];
  for (size_t p = 0; p < c.set.patches.size(); ++p)
    halves[p % 2].push_back(c.set.patches[p]); // patch i + 2 (j + 2 k): x cell i
  iga::sst::CsgScene scene;
  scene.inputs.push_back({ &halves[0], c.set.attributeNames, nullptr });
  scene.inputs.push_back({ &halves[1], { "s1", "s0" }, nullptr }); // names in another order
  for (auto& patch : halves[1])
    for (int p = 0; p < patch.view().pointCount(); ++p)
      std::swap(patch.view().point(p)[iga::kFirstAttributeChannel],
        patch.view().point(p)[iga::kFirstAttributeChannel + 1]);
  for (const std::string text : { "domain - s0<0", "s1<0 - s0<0", "s1<0 & plane(1, 0, 0.3, 0.1)" })
  {
    scene.expression = parseExpression(text);
    iga::sst::Settings settings;
    settings.width = settings.height = 96;
    iga::sst::GBuffer out;
    iga::sst::renderCsg(scene, iga::sst::makeView(c.camera, 96, 96), settings,
      iga::sst::Method::SharedSubdivisionTree, out);
    const auto result = compareWithReference(out, c.camera,
      [&](const glm::dvec3& o, const glm::dvec3& d)
      { return exactFirstHit(scene.expression, c.spheres, o, d); });
    EXPECT_EQ(result.mismatched, 0) << text;
    EXPECT_GT(result.covered, 1000) << text;
    EXPECT_LT(result.maxPositionError, 1e-6) << text;
    for (const auto& hit : out.hits)
      EXPECT_LE((hit.patch < 4 ? 1 : -1) * hit.position[0], 1e-9)
        << "input 0's patches (x < 0) come first, then input 1's";
  }
}

/// All layers of a CSG frame of `inputs` seen by `camera`, clipped by `clip`.
iga::sst::GBuffer allLayers(const std::vector<iga::sst::CsgInput>& inputs, const std::string& text,
  const iga::Camera& camera, const std::vector<std::array<double, 4>>& clip = {},
  const std::vector<std::array<double, 4>>& slices = {})
{
  iga::sst::CsgScene scene;
  scene.inputs = inputs;
  if (!text.empty())
    scene.expression = parseExpression(text);
  scene.slices = slices;
  iga::sst::Settings settings;
  settings.width = settings.height = 64;
  settings.firstHitOnly = false;
  settings.clipPlanes = clip;
  iga::sst::GBuffer out;
  iga::sst::renderCsg(scene, iga::sst::makeView(camera, 64, 64), settings,
    iga::sst::Method::SharedSubdivisionTree, out);
  return out;
}

double boxDistance(const glm::dvec3& x)
{
  return std::abs(1 - std::max({ std::abs(x[0]), std::abs(x[1]), std::abs(x[2]) }));
}

TEST(CsgFrame, TouchingInputsShowNoInnerFaceInAnyLayerClippedOrFromInside)
{
  // The box's halves x < 0 and x > 0 as two inputs: the face x = 0 they share is left and
  // entered at once, which is no surface of their union.
  const CsgCase c = makeCase({ { { 0, 0, 0 }, 0.5 } }, kEye);
  std::vector<iga::BezierVolume<double>> halves[2];
  for (size_t p = 0; p < c.set.patches.size(); ++p)
    halves[p % 2].push_back(c.set.patches[p]);
  const std::vector<iga::sst::CsgInput> inputs = { { &halves[0], c.set.attributeNames, nullptr },
    { &halves[1], c.set.attributeNames, nullptr } };
  const double bounds[6] = { -1, 1, -1, 1, -1, 1 };
  const iga::Camera sideways =
    igatest::truth::makeCamera({ -4.0, 0.6, 0.5 }, { 0, 0, 0 }, { 0, 0, 1 }, 30, bounds);
  iga::Camera inside = sideways;
  inside.position = { -0.6, 0.1, 0.05 };
  inside.clippingRange[0] = 1e-3;
  struct View
  {
    const iga::Camera& camera;
    std::vector<std::array<double, 4>> clip;
    const char* what;
  };
  for (const View& v : { View{ sideways, {}, "all layers" },
         View{ sideways, { { -1, 0, 0, 0 } }, "clipped to x <= 0" },
         View{ inside, {}, "eye inside the first input" } })
  {
    const auto out = allLayers(inputs, "domain - s0<0", v.camera, v.clip);
    int outer = 0, ball = 0;
    for (const auto& hit : out.hits)
    {
      const bool onBox = boxDistance(hit.position) < 1e-6,
                 onBall = std::abs(glm::length(hit.position) - 0.5) < 1e-6;
      EXPECT_TRUE(onBox || onBall) << v.what << ": a hit at x = " << hit.position[0];
      outer += onBox;
      ball += onBall;
    }
    EXPECT_GT(outer, 500) << v.what;
    EXPECT_GT(ball, 100) << v.what;
  }
}

TEST(CsgFrame, OverlappingInputsFindEachCrossingOnce)
{
  // The same volumes given twice: a plane's section and a slice are crossed once per ray.
  const CsgCase c = makeCase({ { { 0, 0, 0 }, 0.5 } }, kEye);
  const iga::sst::CsgInput input{ &c.set.patches, c.set.attributeNames, nullptr };
  for (const std::string text : { "domain & plane(0, 0, 1, 0.1)", "" })
  {
    const std::vector<std::array<double, 4>> slices =
      text.empty() ? std::vector<std::array<double, 4>>{ { 1, 0, 0, 0.2 } }
                   : std::vector<std::array<double, 4>>{};
    const auto once = allLayers({ input }, text, c.camera, {}, slices);
    const auto twice = allLayers({ input, input }, text, c.camera, {}, slices);
    ASSERT_GT(once.hits.size(), 500u);
    EXPECT_EQ(once.offsets, twice.offsets) << text;
  }
}

TEST(CsgFrame, SurfacesAreNoSolids)
{
  const CsgCase c = makeCase({ { { 0, 0, 0 }, 0.5 } }, kEye);
  // A patch of degree 0 across: the engine's form of a surface.
  const int degree[3] = { 2, 2, 0 };
  std::vector<iga::BezierVolume<double>> flat(1, iga::BezierVolume<double>(degree, 5));
  for (int p = 0; p < flat[0].view().pointCount(); ++p)
    std::copy_n(c.set.patches[0].view().point(p), 5, flat[0].view().point(p));
  try
  {
    allLayers({ { &flat, c.set.attributeNames, nullptr } }, "domain", c.camera);
    FAIL() << "no error";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("CSG input 0, patch 0: a surface"), std::string::npos)
      << e.what();
  }
}

TEST(CsgFrame, BasicSchemeAgrees)
{
  const CsgCase c = makeCase({ { { 0.2, -0.1, 1.0 }, 0.6 } }, kEye);
  const auto sst = renderCase(c, "domain - s0<0 & plane(1, 1, 0, 0.2)", 48, false);
  const auto basic =
    renderCase(c, "domain - s0<0 & plane(1, 1, 0, 0.2)", 48, false, iga::sst::Method::BasicScheme);
  ASSERT_EQ(sst.offsets, basic.offsets);
  for (size_t h = 0; h < sst.hits.size(); ++h)
  {
    EXPECT_EQ(sst.hits[h].isovalue, basic.hits[h].isovalue);
    EXPECT_LT(glm::length(sst.hits[h].position - basic.hits[h].position), 1e-7);
  }
}

// ---- slices ------------------------------------------------------------------------------------

iga::sst::GBuffer renderSlices(const iga::VolumeSet<double>& set, const std::string& colour,
  const std::vector<std::array<double, 4>>& slices, const iga::Camera& camera, int size,
  const std::string& expression = "", const std::vector<std::array<double, 4>>& clip = {})
{
  iga::sst::CsgScene scene;
  scene.inputs.push_back({ &set.patches, set.attributeNames, nullptr });
  scene.slices = slices;
  scene.colorAttribute = colour;
  if (!expression.empty())
    scene.expression = parseExpression(expression);
  iga::sst::Settings settings;
  settings.width = settings.height = size;
  settings.firstHitOnly = false;
  settings.clipPlanes = clip;
  iga::sst::GBuffer out;
  iga::sst::renderCsg(scene, iga::sst::makeView(camera, size, size), settings,
    iga::sst::Method::SharedSubdivisionTree, out);
  return out;
}

/// Every hit's position and colour against the math core's evaluation of its patch at its
/// parameter; the largest differences.
std::array<double, 2> evaluationErrors(
  const iga::VolumeSet<double>& set, int colour, const iga::sst::GBuffer& gbuffer)
{
  std::array<double, 2> errors = { 0, 0 };
  for (const auto& hit : gbuffer.hits)
  {
    const auto view = set.patches[size_t(hit.patch)].view();
    std::vector<double> values(size_t(view.channels));
    iga::evaluateHomogeneous<double, 3>(view, &hit.uvw[0], values.data(), nullptr);
    const double w = values[iga::kWeightChannel];
    for (int d = 0; d < 3; ++d)
      errors[0] = std::max(errors[0], std::abs(values[size_t(d)] / w - hit.position[d]));
    errors[1] = std::max(
      errors[1], std::abs(values[size_t(iga::kFirstAttributeChannel + colour)] / w - hit.color));
  }
  return errors;
}

TEST(CsgSlices, MarsdenSphereSlicesLieOnTheirPlanesColouredByTheField)
{
  const auto set = iga::makeMarsdenSphere<double>(3);
  const double bounds[6] = { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 };
  const auto camera =
    igatest::truth::makeCamera({ 4, -3, 3.5 }, { 0, 0, 0 }, { 0, 0, 1 }, 40, bounds);
  const std::vector<std::array<double, 4>> slices = { { 0, 0, 1, -0.2 }, { 1, 1, 0, 0.3 } };
  const auto gbuffer = renderSlices(set, "sphere", slices, camera, 96);
  int onSlice[2] = { 0, 0 }, twoLayers = 0;
  for (const auto& hit : gbuffer.hits)
  {
    ASSERT_TRUE(hit.isovalue == 0 || hit.isovalue == 1) << "slices follow the (no) operands";
    const auto& plane = slices[size_t(hit.isovalue)];
    const glm::dvec3 n(plane[0], plane[1], plane[2]);
    EXPECT_LT(std::abs(glm::dot(n, hit.position) + plane[3]) / glm::length(n), 1e-9);
    EXPECT_NEAR(hit.color, glm::dot(hit.position, hit.position) - 1, 1e-9);
    ++onSlice[hit.isovalue];
  }
  for (int j = 0; j < gbuffer.height; ++j)
    for (int i = 0; i < gbuffer.width; ++i)
      twoLayers += gbuffer.hitCount(i, j) == 2 ? 1 : 0;
  EXPECT_GT(onSlice[0], 1500);
  EXPECT_GT(onSlice[1], 700);
  EXPECT_GT(twoLayers, 500) << "where the slices overlap on screen, both are kept";
  const auto errors = evaluationErrors(set, 0, gbuffer);
  EXPECT_LT(errors[0], 1e-9);
  EXPECT_LT(errors[1], 1e-9);
}

TEST(CsgSlices, DeformedTubeSlicesAndCappedClip)
{
  const auto tube = iga::makeTube<double>(0.5, 0.8);
  double lo[3], hi[3];
  iga::controlPointBounds(tube, lo, hi);
  const double bounds[6] = { lo[0], hi[0], lo[1], hi[1], lo[2], hi[2] };
  const glm::dvec3 centre(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
  const auto camera =
    igatest::truth::makeCamera(centre + glm::dvec3(4, -3, 2.5), centre, { 0, 0, 1 }, 40, bounds);
  const std::vector<std::array<double, 4>> slice = { { 0.2, 1, 0.1, -centre[1] } };
  const auto sliced = renderSlices(tube, "temperature", slice, camera, 96);
  EXPECT_GT(sliced.hits.size(), 300u);
  for (const auto& hit : sliced.hits)
    EXPECT_LT(
      std::abs(0.2 * hit.position[0] + hit.position[1] + 0.1 * hit.position[2] - centre[1]), 1e-9);
  auto errors = evaluationErrors(tube, 0, sliced);
  EXPECT_LT(errors[0], 1e-9);
  EXPECT_LT(errors[1], 1e-9);
  // The tube cut by the half-space y >= centre: the cut face is the slice's section, capped.
  const std::array<double, 4> half = { 0.2, 1, 0.1, -centre[1] };
  const std::string cutOpen = iga::csg::cutByHalfSpaces("", { half });
  const auto capped = renderSlices(tube, "temperature", {}, camera, 96, cutOpen);
  int caps = 0;
  for (const auto& hit : capped.hits)
  {
    EXPECT_GE(0.2 * hit.position[0] + hit.position[1] + 0.1 * hit.position[2] - centre[1], -1e-9);
    caps += hit.isovalue == 1 ? 1 : 0;
  }
  EXPECT_EQ(caps, int(sliced.hits.size())) << "the cap is the slice";
  errors = evaluationErrors(tube, 0, capped);
  EXPECT_LT(errors[0], 1e-9);
  EXPECT_LT(errors[1], 1e-9);
  // Clipping planes cut slices as they cut everything drawn.
  const auto clipped = renderSlices(tube, "", slice, camera, 96, "", { { 0, 0, 1, -centre[2] } });
  EXPECT_GT(clipped.hits.size(), 150u);
  EXPECT_LT(clipped.hits.size(), sliced.hits.size());
  for (const auto& hit : clipped.hits)
  {
    EXPECT_GE(hit.position[2], centre[2]);
    EXPECT_TRUE(std::isnan(hit.color)) << "no colour attribute";
  }
  // igaview's --clip: the solid cut by the half-space and everything drawn clipped by its plane.
  // The cap on that plane stays whole; a slice across it keeps only its kept side.
  const std::vector<std::array<double, 4>> across = { { 0, 0, 1, -centre[2] } };
  const auto cut = renderSlices(tube, "temperature", across, camera, 96, cutOpen, { half });
  const auto uncut = renderSlices(tube, "temperature", across, camera, 96, cutOpen);
  int cutCaps = 0, cutSlice = 0, uncutSlice = 0;
  for (const auto& hit : cut.hits)
  {
    cutCaps += hit.isovalue == 1 ? 1 : 0;
    if (hit.isovalue == 2)
    {
      ++cutSlice;
      EXPECT_GE(0.2 * hit.position[0] + hit.position[1] + 0.1 * hit.position[2] + half[3], -1e-9);
    }
  }
  for (const auto& hit : uncut.hits)
    uncutSlice += hit.isovalue == 2 ? 1 : 0;
  EXPECT_EQ(cutCaps, caps) << "the clipping plane keeps the cap lying on it";
  EXPECT_GT(cutSlice, 50);
  EXPECT_LT(cutSlice, uncutSlice) << "the slice is cut";
}

TEST(CsgSlices, BadSlicesAreRefused)
{
  const auto set = iga::makeMarsdenSphere<double>(2);
  const double bounds[6] = { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 };
  const auto camera =
    igatest::truth::makeCamera({ 4, -3, 3.5 }, { 0, 0, 0 }, { 0, 0, 1 }, 40, bounds);
  EXPECT_THROW(renderSlices(set, "", { { 0, 0, 0, 1 } }, camera, 8), std::invalid_argument);
  EXPECT_THROW(renderSlices(set, "", { { NAN, 0, 1, 1 } }, camera, 8), std::invalid_argument);
  EXPECT_THROW(renderSlices(set, "", {}, camera, 8), std::invalid_argument);
}

TEST(CsgFrame, MissingAttributeNamesItsPosition)
{
  const CsgCase c = makeCase({ { { 0, 0, 0 }, 0.5 } }, kEye);
  try
  {
    renderCase(c, "domain - temperature<0", 16);
    FAIL() << "no error";
  }
  catch (const ExpressionError& e)
  {
    EXPECT_EQ(e.position(), 9u);
    EXPECT_EQ(std::string(e.what()), "no input has the attribute 'temperature' at position 9");
  }
}

} // namespace
