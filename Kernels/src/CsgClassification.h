// The CSG classification stage: per pixel, the hits of every pass merged front to back and
// walked along the ray, each operand's inside known after each hit, and a hit kept where the
// expression's result changes there.
#pragma once

#include "ParallelFor.h"

#include "iga/Boundary.h"
#include "iga/Csg.h"
#include "iga/sst/Engine.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace iga
{
namespace sst
{

/// One all-hits engine pass of a CSG frame and what its hits stand for.
struct CsgPass
{
  enum class Kind
  {
    Boundary,  ///< an input's boundary faces, outward: where the ray enters or leaves its volumes
    Attribute, ///< an attribute's isosurfaces in an input, one isovalue per operand naming it
    Plane,     ///< a plane operand's section of an input's volumes
    Slice,     ///< a slice's section of an input's volumes: drawn, not classified
  };
  Kind kind = Kind::Boundary;
  int input = 0;
  int attribute = -1; ///< the attribute index (Attribute), 0 (Plane: its derived channel)
  int operand = -1;   ///< Plane: the operand; Slice: the number of operands plus the slice
  std::vector<double> isovalues;
  std::vector<int> operandOfIsovalue;          ///< Attribute: Hit::isovalue -> operand
  std::vector<PatchFace> faces;                ///< Boundary: the faces, Hit::patch's order
  std::vector<uint8_t> reversed;               ///< Boundary: outwardFaceSurface reversed t
  std::vector<BezierSurface<double>> surfaces; ///< Boundary: the outward faces, every channel
  std::vector<BezierVolume<double>> volumes;   ///< Plane: the volumes with the plane's field
  GBuffer hits;
};

/// The passes of a frame and what classification needs besides.
struct CsgPasses
{
  const csg::Expression* expression = nullptr;
  int inputs = 0;
  /// Per operand and input (operand * inputs + input): the attribute index of a Below/Above
  /// operand in that input, -1 where the input lacks it (and for other operands).
  std::vector<int> sources;
  std::vector<CsgPass> list;
  size_t slices = 0; ///< Slice passes' CsgPass::operand is the operands' count plus 0..slices-1
  std::vector<int> patchOffsets; ///< per input, its first volume in the result's numbering
  std::vector<const std::vector<BezierVolume<double>>*> volumes; ///< per input
  const View* view = nullptr;
  const std::vector<std::array<double, 4>>* clip = nullptr;
  bool firstHitOnly = true;
};

/// Below this |cos| between a hit's normal and the ray, the ray touches the surface rather
/// than crossing it: the hit changes no operand's inside (a tangential touch must not flip it).
constexpr double kTouchCosine = 1e-9;

/// a x + b y + c z + d at x.
inline double planeValue(const std::array<double, 4>& plane, const glm::dvec3& x)
{
  return plane[0] * x[0] + plane[1] * x[1] + plane[2] * x[2] + plane[3];
}

/// Whether a clipping plane cuts x away. A point on the plane within rounding stays: the cap of
/// a solid cut by the same half-space (igaview's --clip) lies on it.
inline bool clippedBy(const std::array<double, 4>& plane, const glm::dvec3& x)
{
  const double scale = std::abs(plane[0] * x[0]) + std::abs(plane[1] * x[1]) +
                       std::abs(plane[2] * x[2]) + std::abs(plane[3]);
  return planeValue(plane, x) < -1e-9 * scale;
}

/// The rational attribute at `channel` of a volume at parameter `uvw` (`values`: scratch).
inline double attributeInVolume(const BezierVolume<double>& volume, const glm::dvec3& uvw,
  int channel, std::vector<double>& values)
{
  const auto view = volume.view();
  values.resize(size_t(view.channels));
  const double u[3] = { uvw[0], uvw[1], uvw[2] };
  evaluateHomogeneous<double, 3>(view, u, values.data(), nullptr);
  return values[size_t(channel)] / values[kWeightChannel];
}

/// Classifies one pixel at a time, keeping its scratch between pixels.
class PixelClassifier
{
public:
  explicit PixelClassifier(const CsgPasses& passes)
    : Passes(passes)
    , Operands(passes.expression->operands)
  {
  }

  /// Appends the result's surfaces and the slices at `pixel`, front to back (the nearest alone
  /// for firstHitOnly), to `out`.
  void classify(size_t pixel, std::vector<Hit>& out)
  {
    const size_t first = out.size();
    if (this->Passes.expression->root >= 0)
    {
      this->classifyResult(pixel, out);
    }
    this->addSlices(pixel, out);
    std::sort(out.begin() + long(first), out.end(),
      [](const Hit& a, const Hit& b) { return a.eyeDepth < b.eyeDepth; });
    if (this->Passes.firstHitOnly && out.size() > first + 1)
    {
      out.resize(first + 1);
    }
  }

private:
  /// Events closer along the ray than the engine's duplicate tolerance (1e-4 of a pixel's
  /// footprint) are one crossing seen twice or more: a face two inputs share (leaving one,
  /// entering the other), a plane in overlapping inputs, a root on a face two patches share.
  /// Each such group is applied at once and makes at most one surface.
  void classifyResult(size_t pixel, std::vector<Hit>& out)
  {
    this->gather(pixel);
    this->startStates();
    const csg::Expression& expression = *this->Passes.expression;
    const View& view = *this->Passes.view;
    for (int n = 0, end = 0; n < int(this->Events.size()); n = end)
    {
      const double depth = this->Events[size_t(n)].hit->eyeDepth;
      const double tolerance = 1e-4 * view.pixelFootprint * (view.parallel ? 1.0 : std::abs(depth));
      for (end = n + 1; end < int(this->Events.size()) &&
                        this->Events[size_t(end)].hit->eyeDepth - depth <= tolerance;
           ++end)
      {
      }
      // Half-spaces change between hits too (outside the volumes): their sides are taken at
      // each group, before and after it.
      this->setPlaneSides(n, end, true);
      this->operandStates(n - 1, this->Before);
      const bool wasInside = expression.contains(this->Before, this->Nodes);
      for (int m = n; m < end; ++m)
      {
        this->apply(m);
      }
      this->setPlaneSides(n, end, false);
      this->operandStates(end - 1, this->After);
      const bool inside = expression.contains(this->After, this->Nodes);
      if (inside != wasInside && this->emit(this->surfaceOf(n, end), inside, out) &&
          this->Passes.firstHitOnly)
      {
        return;
      }
    }
  }

  /// The event of group [n, end) that stands for its surface: the first of an operand whose
  /// inside changed (a boundary hit for a domain's or an attribute's closure), else the first.
  int surfaceOf(int n, int end) const
  {
    for (int m = n; m < end; ++m)
    {
      const int k = this->Events[size_t(m)].operand;
      if (k >= 0 ? this->Before[size_t(k)] != this->After[size_t(k)] : this->Before != this->After)
      {
        return m;
      }
    }
    return n;
  }

  /// Each slice's nearest hit at `pixel` (a ray crosses a plane once: overlapping inputs find
  /// the crossing in each).
  void addSlices(size_t pixel, std::vector<Hit>& out)
  {
    this->SliceSeen.assign(this->Passes.slices, 0);
    for (const CsgPass& pass : this->Passes.list)
    {
      if (pass.kind != CsgPass::Kind::Slice ||
          pass.hits.offsets[pixel] == pass.hits.offsets[pixel + 1])
      {
        continue;
      }
      Hit hit = pass.hits.hits[pass.hits.offsets[pixel]];
      uint8_t& seen = this->SliceSeen[size_t(pass.operand) - this->Operands.size()];
      if (seen || this->clipped(hit))
      {
        continue;
      }
      seen = 1;
      hit.isovalue = pass.operand; // entersBelow: below -(a x + b y + c z + d), the + side
      hit.patch += this->Passes.patchOffsets[size_t(pass.input)];
      out.push_back(hit);
    }
  }

  bool clipped(const Hit& hit) const
  {
    for (const auto& plane : *this->Passes.clip)
    {
      if (clippedBy(plane, hit.position))
      {
        return true;
      }
    }
    return false;
  }

  struct Event
  {
    const Hit* hit;
    int pass;
    int operand; ///< the Attribute or Plane operand, -1 for a Boundary hit
    bool touch;
  };

  const CsgPass& passOf(const Event& e) const { return this->Passes.list[size_t(e.pass)]; }
  bool isBoundary(const Event& e) const { return e.operand < 0; }
  int sourceOf(int k, int input) const
  {
    return this->Passes.sources[size_t(k) * size_t(this->Passes.inputs) + size_t(input)];
  }
  /// Operand k's attribute sign state in input i (Below).
  int8_t& belowState(size_t k, int input)
  {
    return this->Below[k * size_t(this->Passes.inputs) + size_t(input)];
  }

  void gather(size_t pixel)
  {
    this->Events.clear();
    const View& view = *this->Passes.view;
    for (int p = 0; p < int(this->Passes.list.size()); ++p)
    {
      const CsgPass& pass = this->Passes.list[size_t(p)];
      if (pass.kind == CsgPass::Kind::Slice)
      {
        continue;
      }
      for (uint32_t h = pass.hits.offsets[pixel]; h < pass.hits.offsets[pixel + 1]; ++h)
      {
        const Hit& hit = pass.hits.hits[h];
        const int operand = pass.kind == CsgPass::Kind::Attribute
                              ? pass.operandOfIsovalue[size_t(hit.isovalue)]
                              : pass.operand;
        const glm::dvec3 ray =
          view.parallel ? view.forward : glm::normalize(hit.position - view.eye);
        const bool touch = std::abs(glm::dot(hit.normal, ray)) < kTouchCosine;
        this->Events.push_back({ &hit, p, operand, touch });
      }
    }
    // Ties in pass order, then in each pass's own (its hits lie in one array): the order of a
    // stable sort, without the buffer std::stable_sort allocates for every pixel.
    std::sort(this->Events.begin(), this->Events.end(),
      [](const Event& a, const Event& b)
      {
        return a.hit->eyeDepth != b.hit->eyeDepth ? a.hit->eyeDepth < b.hit->eyeDepth
               : a.pass != b.pass                 ? a.pass < b.pass
                                                  : a.hit < b.hit;
      });
  }

  /// The state before the ray's first hit: inside an input where its first boundary crossing
  /// leaves it; every attribute's sign unknown until asked for.
  void startStates()
  {
    this->Domain.assign(size_t(this->Passes.inputs), 2);
    for (const Event& e : this->Events)
    {
      uint8_t& state = this->Domain[size_t(this->passOf(e).input)];
      if (this->isBoundary(e) && !e.touch && state == 2)
      {
        state = e.hit->entersBelow ? 0 : 1;
      }
    }
    for (uint8_t& state : this->Domain)
    {
      state = state == 1 ? 1 : 0;
    }
    this->Below.assign(this->Operands.size() * size_t(this->Passes.inputs), -1);
    this->PlaneSide.assign(this->Operands.size(), 0);
  }

  /// Every plane operand's side just before or after the group of events [n, end): from the
  /// side its own crossing in the group passes to or from, else at the group's position (a touch
  /// of its own plane keeps the side it had).
  void setPlaneSides(int n, int end, bool before)
  {
    for (size_t k = 0; k < this->Operands.size(); ++k)
    {
      if (this->Operands[k].kind != csg::Operand::Kind::Plane)
      {
        continue;
      }
      int own = -1;
      bool touched = false;
      for (int m = n; m < end; ++m)
      {
        const Event& e = this->Events[size_t(m)];
        if (e.operand == int(k) && e.touch)
        {
          touched = true;
        }
        else if (e.operand == int(k) && own < 0)
        {
          own = m;
        }
      }
      if (own >= 0)
      {
        this->PlaneSide[k] = this->Events[size_t(own)].hit->entersBelow != before ? 1 : 0;
      }
      else if (!touched)
      {
        const Event& at = this->Events[size_t(before ? n : end - 1)];
        this->PlaneSide[k] = planeValue(this->Operands[k].plane, at.hit->position) >= 0 ? 1 : 0;
      }
    }
  }

  /// Event n's change of the domains' and attributes' states.
  void apply(int n)
  {
    const Event& e = this->Events[size_t(n)];
    const int input = this->passOf(e).input;
    if (!e.touch && this->isBoundary(e))
    {
      this->Domain[size_t(input)] = e.hit->entersBelow ? 1 : 0;
      for (size_t k = 0; k < this->Operands.size(); ++k)
      {
        this->belowState(k, input) = -1;
      }
    }
    else if (!e.touch && this->passOf(e).kind == CsgPass::Kind::Attribute)
    {
      this->belowState(size_t(e.operand), input) = e.hit->entersBelow ? 1 : 0;
    }
  }

  /// Each operand's inside after event n (-1: before the first).
  void operandStates(int n, std::vector<uint8_t>& states)
  {
    states.assign(this->Operands.size(), 0);
    for (size_t k = 0; k < this->Operands.size(); ++k)
    {
      const csg::Operand& operand = this->Operands[k];
      bool inside = false;
      for (int i = 0; i < this->Passes.inputs && !inside; ++i)
      {
        switch (operand.kind)
        {
          case csg::Operand::Kind::Domain:
            inside = this->Domain[size_t(i)] != 0;
            break;
          case csg::Operand::Kind::Plane: // the half-space within the volumes
            inside = this->PlaneSide[k] != 0 && this->Domain[size_t(i)] != 0;
            break;
          case csg::Operand::Kind::Below:
          case csg::Operand::Kind::Above:
            if (this->Domain[size_t(i)] && this->sourceOf(int(k), i) >= 0)
            {
              const bool below = this->below(int(k), i, n);
              inside = operand.kind == csg::Operand::Kind::Below ? below : !below;
            }
            break;
        }
      }
      states[k] = inside ? 1 : 0;
    }
  }

  /// Whether operand k's attribute is below its value in input i after event n, inside the
  /// input: known from the last crossing, else from the next one before the ray leaves the
  /// input (the sign holds until then), else from the attribute where the ray leaves it, or at
  /// event n (passes bounded by a far depth may end before either).
  bool below(int k, int input, int n)
  {
    int8_t& state = this->belowState(size_t(k), input);
    if (state >= 0)
    {
      return state != 0;
    }
    state = 0;
    for (size_t m = size_t(n + 1); m < this->Events.size(); ++m)
    {
      const Event& e = this->Events[m];
      if (e.touch || this->passOf(e).input != input)
      {
        continue;
      }
      if (e.operand == k)
      {
        state = e.hit->entersBelow ? 0 : 1;
        return state != 0;
      }
      if (this->isBoundary(e) && !e.hit->entersBelow)
      {
        state = this->attributeAt(e, k) < this->Operands[size_t(k)].value ? 1 : 0;
        return state != 0;
      }
    }
    if (n >= 0 && this->passOf(this->Events[size_t(n)]).input == input)
    {
      state = this->attributeAt(this->Events[size_t(n)], k) < this->Operands[size_t(k)].value;
    }
    return state != 0;
  }

  /// Operand k's attribute at a hit: from the face's net (every channel of the volume) for a
  /// boundary hit, else from the input's volume at the hit's parameter.
  double attributeAt(const Event& e, int k) const
  {
    const CsgPass& pass = this->passOf(e);
    const int channel = kFirstAttributeChannel + this->sourceOf(k, pass.input);
    if (this->isBoundary(e))
    {
      const auto face = pass.surfaces[size_t(e.hit->patch)].view();
      this->Values.resize(size_t(face.channels));
      const double st[2] = { e.hit->uvw[0], e.hit->uvw[1] };
      evaluateHomogeneous<double, 2>(face, st, this->Values.data(), nullptr);
      return this->Values[size_t(channel)] / this->Values[kWeightChannel];
    }
    return attributeInVolume((*this->Passes.volumes[size_t(pass.input)])[size_t(e.hit->patch)],
      e.hit->uvw, channel, this->Values);
  }

  /// Appends event n as a surface of the result (entering it where `entering`), unless a
  /// clipping plane cuts it away; whether it was kept.
  bool emit(int n, bool entering, std::vector<Hit>& out) const
  {
    const Event& e = this->Events[size_t(n)];
    const CsgPass& pass = this->passOf(e);
    Hit hit = *e.hit;
    if (this->clipped(hit))
    {
      return false;
    }
    hit.isovalue = e.operand;
    for (size_t k = 0; k < this->Operands.size(); ++k)
    {
      if (this->Before[k] != this->After[k])
      {
        hit.isovalue = int(k);
        break;
      }
    }
    hit.entersBelow = entering;
    int patch = hit.patch;
    if (pass.kind == CsgPass::Kind::Boundary)
    {
      const PatchFace& face = pass.faces[size_t(hit.patch)];
      const double s = hit.uvw[0], t = hit.uvw[1];
      faceParameterInVolume(face, pass.reversed[size_t(hit.patch)] != 0, s, t, &hit.uvw[0]);
      patch = face.patch;
    }
    hit.patch = this->Passes.patchOffsets[size_t(pass.input)] + patch;
    out.push_back(hit);
    return true;
  }

  const CsgPasses& Passes;
  const std::vector<csg::Operand>& Operands;
  std::vector<Event> Events;
  std::vector<uint8_t> Domain;    ///< per input: inside its volumes
  std::vector<int8_t> Below;      ///< per operand and input: 1 below, 0 above, -1 unknown
  std::vector<uint8_t> PlaneSide; ///< per operand: inside the half-space (Plane operands)
  std::vector<uint8_t> Before, After, Nodes;
  std::vector<uint8_t> SliceSeen; ///< per slice: its hit at this pixel is out
  mutable std::vector<double> Values;
};

/// Classifies every pixel of the passes (all of one size) into `out`, on `threads` threads.
inline void classifyPixels(const CsgPasses& passes, int threads, GBuffer& out)
{
  const GBuffer& first = passes.list.front().hits;
  out.width = first.width;
  out.height = first.height;
  const size_t pixels = size_t(out.width) * size_t(out.height);
  const size_t parts = std::max<size_t>(1, std::min<size_t>(pixels, size_t(threads) * 8));
  std::vector<std::vector<Hit>> partHits(parts);
  std::vector<uint32_t> counts(pixels, 0);
  parallelParts(pixels, parts, threads,
    [&](size_t part, size_t begin, size_t end)
    {
      PixelClassifier classifier(passes);
      for (size_t p = begin; p < end; ++p)
      {
        const size_t before = partHits[part].size();
        classifier.classify(p, partHits[part]);
        counts[p] = uint32_t(partHits[part].size() - before);
      }
    });
  out.offsets.assign(pixels + 1, 0);
  for (size_t p = 0; p < pixels; ++p)
  {
    out.offsets[p + 1] = out.offsets[p] + counts[p];
  }
  out.hits.clear();
  out.hits.reserve(out.offsets[pixels]);
  for (const auto& hits : partHits)
  {
    out.hits.insert(out.hits.end(), hits.begin(), hits.end());
  }
}

} // namespace sst
} // namespace iga
