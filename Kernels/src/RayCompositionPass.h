// The ray-composition method's pass: per pixel, each patch its work items name (affine, checked
// before the frame) composed with the pixel's ray into a univariate Bernstein polynomial whose
// roots, by the chosen finder, are the pixel's hits. The sweep, the hit policy and the G-buffer
// stage are the other methods'.
#pragma once

#include "CellCoverage.h"
#include "FramePlan.h"
#include "ParallelFor.h"
#include "iga/FrustumForm.h"
#include "iga/RayComposition.h"
#include "iga/sst/Engine.h"
#include "sst/CpuExec.h"
#include "sst/LoopState.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace iga
{
namespace sst
{

/// Each patch's affine form, rayDegree -1 for the surfaces and the volumes without one (which
/// the SST draws), on `threads` threads; sets the report's counts of patches per path. The
/// analysis is kept for the next frame with the same DataKey (a camera move: thousands of ABS
/// patches take some 12 ms).
inline AffineForms affineWherePossible(
  const Scene& scene, const Settings& settings, int threads, FrameReport& report)
{
  // With its count of affine patches, counted once (a large set's are many).
  struct Analysis
  {
    AffineForms forms;
    size_t affinePatches = 0;
  };
  static KeptByDataKey<Analysis> kept;
  const Analysis analysis = kept.get(scene, settings,
    [&]
    {
      auto affine = std::make_shared<std::vector<AffinePatch>>(scene.size());
      parallelFor(scene.size(), threads,
        [&](size_t begin, size_t end)
        {
          for (size_t p = begin; p < end; ++p)
          {
            AffinePatch& patch = (*affine)[p];
            if (p >= scene.volumeCount() ||
                !affineGeometry(
                  scene[p], kFirstAttributeChannel + settings.surfaceAttribute, patch))
            {
              patch = AffinePatch();
              patch.rayDegree = -1;
            }
          }
        });
      return Analysis{ affine, size_t(std::count_if(affine->begin(), affine->end(),
                                 [](const AffinePatch& patch) { return patch.rayDegree >= 0; })) };
    });
  report.rayCompositionPatches += analysis.affinePatches;
  report.sstPatches = scene.size() - report.rayCompositionPatches;
  return analysis.forms;
}

/// The affine patches' power forms for shading (PowerShading, count 0 for a patch without one)
/// and their terms in one pool.
struct PowerShadingTable
{
  std::vector<PowerShading> patches;
  std::vector<PowerTerm> terms;
};

/// The power shading table of an affine analysis, kept with it for the next frame that has the
/// same (thousands of ABS patches' terms are megabytes to copy).
inline std::shared_ptr<const PowerShadingTable> powerShadingOf(const AffineForms& affine)
{
  static std::mutex keptMutex;
  static std::weak_ptr<const std::vector<AffinePatch>> keptForms; // not kept alive by it
  static std::shared_ptr<const PowerShadingTable> kept;
  {
    std::lock_guard<std::mutex> lock(keptMutex);
    if (keptForms.lock() == affine)
    {
      return kept;
    }
  }
  auto table = std::make_shared<PowerShadingTable>();
  table->patches.assign(affine->size(), PowerShading());
  for (size_t p = 0; p < affine->size(); ++p)
  {
    const AffinePatch& patch = (*affine)[p];
    if (patch.rayDegree >= 0 && !patch.terms.empty())
    {
      PowerShading& power = table->patches[p];
      power.origin = patch.origin;
      power.axes = patch.axes;
      power.first = uint32_t(table->terms.size());
      power.count = uint32_t(patch.terms.size());
      table->terms.insert(table->terms.end(), patch.terms.begin(), patch.terms.end());
    }
  }
  std::lock_guard<std::mutex> lock(keptMutex);
  keptForms = affine;
  kept = table;
  return kept;
}

/// Every volume's affine form (on `threads` threads); throws std::invalid_argument naming a patch
/// that has none (or a surface, which ray composition does not draw).
inline AffineForms affinePatches(
  const Scene& scene, const Settings& settings, int threads, FrameReport& report)
{
  if (scene.surfaceCount() > 0)
  {
    throw std::invalid_argument("ray composition draws volumes only, the scene has " +
                                std::to_string(scene.surfaceCount()) + " surfaces");
  }
  AffineForms affine = affineWherePossible(scene, settings, threads, report);
  for (size_t p = 0; p < scene.size(); ++p)
  {
    if ((*affine)[p].rayDegree < 0)
    {
      throw std::invalid_argument("ray composition needs affine geometry and a degree along rays "
                                  "of at most 16: " +
                                  scene.name(p) + " has not");
    }
  }
  return affine;
}

/// The affine patches' frustum forms for the view where they pay for the pixels drawn
/// (makeFrustumForm). A few patches' forms are made at once, each form's samples spread over the
/// threads; many patches' (ABS fields) each the first time a ray needs it, on the asking thread,
/// so that a patch hidden behind a first hit pays for none. Safe to ask from several threads.
class FrustumForms
{
public:
  FrustumForms(const std::vector<AffinePatch>& affine, const View& view, int threads,
    const CellCoverage& coverage)
    : Affine(affine)
    , Coverage(coverage)
    , WorldToClip(view.worldToClip)
    , ClipToWorld(glm::inverse(view.worldToClip))
    , Forms(affine.size())
    , Once(new std::once_flag[affine.size()])
  {
    if (affine.size() < 16 * size_t(std::max(threads, 1)))
    {
      for (size_t p = 0; p < affine.size(); ++p)
      {
        this->make(p, threads);
      }
    }
  }

  /// Patch p's form (degree -1: none, its rays composed without one).
  const FrustumForm& of(size_t p)
  {
    this->make(p, 1);
    return this->Forms[p];
  }

  /// Of the patches made or asked for: forms made, and patches without one composed by their
  /// blossom.
  size_t made() const { return this->Made; }
  size_t blossoms() const { return this->Blossoms; }

private:
  void make(size_t p, int threads)
  {
    std::call_once(this->Once[p],
      [&]
      {
        const bool made = makeFrustumForm(this->Affine[p], this->WorldToClip, this->ClipToWorld,
          this->Coverage.drawn(), this->Coverage.pixels(p), this->Forms[p],
          [&](size_t count, const auto& fn) { parallelFor(count, threads, fn); });
        this->Made += made ? 1 : 0;
        this->Blossoms += !made && !this->Affine[p].terms.empty() ? 1 : 0;
      });
  }

  const std::vector<AffinePatch>& Affine;
  const CellCoverage& Coverage;
  const glm::dmat4 WorldToClip, ClipToWorld;
  std::vector<FrustumForm> Forms;
  std::unique_ptr<std::once_flag[]> Once;
  std::atomic<size_t> Made{ 0 }, Blossoms{ 0 };
};

/// Removes the work items of affine patches (ray composition's) from the band's lists, so that
/// the SST's rounds see the others only.
inline void dropAffineItems(
  LoopState<CpuExec>& s, const std::vector<AffinePatch>& affine, const Node* initialNodes)
{
  const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
  uint32_t kept = s.ItemOffsets[first];
  for (size_t p = first; p < first + count; ++p)
  {
    const uint32_t begin = s.ItemOffsets[p], end = s.ItemOffsets[p + 1];
    s.ItemOffsets[p] = kept;
    s.GroupBegin[p] = s.GroupEnd[p] = kept;
    for (uint32_t item = begin; item < end; ++item)
    {
      if (affine[size_t(initialNodes[s.ItemNodes[item]].patch)].rayDegree < 0)
      {
        s.ItemNodes[kept++] = s.ItemNodes[item];
      }
    }
  }
  s.ItemOffsets[first + count] = kept;
  s.ItemNodes.resize(kept);
}

/// Half the width, a fraction of the ray's segment through the patch, of the bracket about a
/// seed's root.
constexpr double kSeedHalfWidth = 0.01;

/// A ray's roots on its segment [t0, t1] of origin + t direction: by the finder, or where a
/// first hit is all it needs and the seed frame has a hit at the pixel, from that hit's place
/// along the ray (findNearestRoot, which proves or drops it; `seeded` says which), bracketed
/// by `halfWidth` of the segment.
inline BernsteinRoots rayRoots(const double* coefficients, int degree, const Settings& settings,
  const RootSettings& rootSettings, const glm::dvec3& origin, const glm::dvec3& direction,
  double t0, double t1, size_t pixel, double halfWidth, bool& seeded)
{
  seeded = false;
  const GBuffer* seed = settings.seedFrame;
  if (seed && rootSettings.maxRoots == 1 && seed->width == settings.width &&
      seed->height == settings.height && seed->offsets[pixel] < seed->offsets[pixel + 1])
  {
    const glm::dvec3 hit = seed->hits[seed->offsets[pixel]].position;
    const double t = glm::dot(hit - origin, direction) / glm::dot(direction, direction);
    const double guess = (t - t0) / (t1 - t0);
    if (guess > -halfWidth && guess < 1 + halfWidth) // else a hit on another patch
    {
      return findNearestRoot(
        coefficients, degree, guess, halfWidth, settings.rootFinder, rootSettings, seeded);
    }
  }
  return findBernsteinRoots(coefficients, degree, settings.rootFinder, rootSettings);
}

namespace detail
{
/// What the pass reads of an initial node, packed: node records are large, and an ABS field's
/// pixels go through thousands of them.
struct ComposedNode
{
  int patch;
  int iso;
  double nearest; ///< NDC depth
};

/// A pixel's ray: its NDC x and y, and origin + t direction from the near (t = 0) to the far
/// plane (t = 1).
struct PixelRay
{
  double x, y;
  glm::dvec3 origin, direction;
};

inline PixelRay pixelRay(const glm::dmat4& clipToWorld, const Settings& settings, size_t p)
{
  PixelRay ray;
  ray.x = 2 * (double(p % settings.width) + 0.5) / settings.width - 1;
  ray.y = 2 * (double(p / settings.width) + 0.5) / settings.height - 1;
  const glm::dvec4 nearPoint = clipToWorld * glm::dvec4(ray.x, ray.y, -1, 1);
  const glm::dvec4 farPoint = clipToWorld * glm::dvec4(ray.x, ray.y, 1, 1);
  ray.origin = glm::dvec3(nearPoint) / nearPoint.w;
  ray.direction = glm::dvec3(farPoint) / farPoint.w - ray.origin;
  return ray;
}

/// Counts of the pass, per thread then summed.
struct CompositionCounts
{
  size_t rays = 0, steps = 0, capped = 0, seeded = 0;
};
} // namespace detail

/// The ray-composition pass over a band's pixels: its inputs, and a pixel's work.
class CompositionPass
{
public:
  CompositionPass(const View& view, const Settings& settings,
    const std::vector<AffinePatch>& affine, FrustumForms& forms, const CellCoverage& coverage,
    const LoopState<CpuExec>& s)
    : TheView(view)
    , Config(settings)
    , Affine(affine)
    , Forms(forms)
    , Coverage(coverage)
    , Loop(s)
    , ClipToWorld(glm::inverse(view.worldToClip))
    , Nodes(s.initialCount)
  {
    // A (patch, isovalue) with several roots (split at the eye plane) has its ray composed once
    // a pixel; where none has, no pixel keeps a list of those done.
    std::vector<std::pair<int, int>> roots(s.initialCount);
    for (size_t n = 0; n < s.initialCount; ++n)
    {
      const Node& node = s.initialNodes[n];
      this->Nodes[n] = { node.patch, node.iso, node.info.box.lo[2] };
      roots[n] = { node.patch, node.iso };
    }
    std::sort(roots.begin(), roots.end());
    this->RepeatedRoots = std::adjacent_find(roots.begin(), roots.end()) != roots.end();
    // A first hit needs a ray's nearest root alone, unless a clipping plane may cut it away.
    this->Roots.maxRoots =
      s.frame.hits.firstHitOnly && settings.clipPlanes.empty() ? 1 : roots::kMaxRoots;
  }

  /// Appends pixel p's hits on the affine patches its work items name, nearest first where the
  /// hit policy keeps the nearest only.
  void drawPixel(size_t p, std::vector<RawHit>& hits, detail::CompositionCounts& counts) const
  {
    detail::PixelRay ray;
    bool rayMade = false; // not for a pixel whose items all miss (cells, patches the SST draws)
    int done[64][2], doneCount = 0; // (patch, isovalue) pairs met in earlier items
    double best = this->Loop.BestDepth[p];
    for (uint32_t item = this->Loop.ItemOffsets[p]; item < this->Loop.ItemOffsets[p + 1]; ++item)
    {
      const detail::ComposedNode& node = this->Nodes[this->Loop.ItemNodes[item]];
      if (!this->Loop.frame.hits.mayMatter(node.nearest, best))
      {
        break; // the items are sorted by nearest depth
      }
      bool seen = false;
      for (int d = 0; d < doneCount; ++d)
      {
        seen = seen || (done[d][0] == node.patch && done[d][1] == node.iso);
      }
      if (seen || this->Affine[size_t(node.patch)].rayDegree < 0 ||
          !this->Coverage.mayHit(node.patch, node.iso, p))
      {
        continue;
      }
      if (this->RepeatedRoots && doneCount < 64)
      {
        done[doneCount][0] = node.patch;
        done[doneCount++][1] = node.iso;
      }
      if (!rayMade)
      {
        ray = detail::pixelRay(this->ClipToWorld, this->Config, p);
        rayMade = true;
      }
      this->drawPatch(p, ray, node, hits, counts, best);
    }
  }

private:
  /// The hits of the pixel's ray on one patch and isovalue.
  void drawPatch(size_t p, const detail::PixelRay& ray, const detail::ComposedNode& node,
    std::vector<RawHit>& hits, detail::CompositionCounts& counts, double& best) const
  {
    const AffinePatch& patch = this->Affine[size_t(node.patch)];
    double t0, t1;
    if (!rayInPatch(patch, ray.origin, ray.direction, 0, 1, t0, t1))
    {
      return;
    }
    // A seed's bracket keeps its width along the ray where the cells shorten the segment.
    const double throughPatch = t1 - t0;
    if (!this->clipToCells(p, node, t0, t1))
    {
      return;
    }
    const double seedHalfWidth = std::min(0.5, kSeedHalfWidth * throughPatch / (t1 - t0));
    const glm::dvec3 u0 = patch.inverse * (ray.origin + t0 * ray.direction - patch.origin);
    const glm::dvec3 du = patch.inverse * ((t1 - t0) * ray.direction);
    const double isovalue = this->Config.isovalues[size_t(node.iso)];
    double coefficients[kMaxOrder];
    const FrustumForm& form = this->Forms.of(size_t(node.patch));
    if (form.degree >= 0)
    {
      composeFrustumRay(
        form, isovalue, ray.x, ray.y, t0, t1, interpolation(patch.rayDegree), coefficients);
    }
    else if (!patch.terms.empty())
    {
      blossomAlongRay(patch.terms.data(), int(patch.terms.size()), patch.rayDegree, 2.0 * u0 - 1.0,
        2.0 * (u0 + du) - 1.0, isovalue, coefficients);
    }
    else
    {
      composeRay(patch, isovalue, u0, du, interpolation(patch.rayDegree), coefficients);
    }
    bool seeded;
    const BernsteinRoots roots = rayRoots(coefficients, patch.rayDegree, this->Config, this->Roots,
      ray.origin, ray.direction, t0, t1, p, seedHalfWidth, seeded);
    ++counts.rays;
    counts.seeded += seeded ? 1 : 0;
    counts.steps += size_t(roots.cost.insertions + roots.cost.evaluations);
    counts.capped += roots.cost.capped ? 1 : 0;
    for (int r = 0; r < roots.count; ++r)
    {
      const glm::dvec3 position = ray.origin + (t0 + roots.t[r] * (t1 - t0)) * ray.direction;
      if (!this->keptByClipPlanes(position))
      {
        continue;
      }
      const glm::dvec4 clip = this->TheView.worldToClip * glm::dvec4(position, 1);
      RawHit hit;
      hit.pixel = uint32_t(p);
      hit.patch = node.patch;
      hit.iso = node.iso;
      hit.ndcDepth = clip.z / clip.w;
      const glm::dvec3 u = u0 + roots.t[r] * du;
      for (int d = 0; d < 3; ++d)
      {
        hit.u[d] = std::min(std::max(u[d], 0.0), 1.0);
      }
      hits.push_back(hit);
      best = this->Loop.frame.hits.afterHit(best, hit.ndcDepth);
    }
  }

  /// Narrows [t0, t1] to the segment of the cells covering the pixel (no isosurface lies
  /// nearer or farther); false where nothing is left.
  bool clipToCells(size_t p, const detail::ComposedNode& node, double& t0, double& t1) const
  {
    double first, last;
    if (!this->Coverage.segment(node.patch, node.iso, p, first, last))
    {
      return true;
    }
    t0 = std::max(t0, first - 1e-9);
    t1 = std::min(t1, last + 1e-9);
    return t0 < t1;
  }

  bool keptByClipPlanes(const glm::dvec3& x) const
  {
    for (const auto& plane : this->Config.clipPlanes)
    {
      if (!(plane[0] * x.x + plane[1] * x.y + plane[2] * x.z + plane[3] >= 0))
      {
        return false;
      }
    }
    return true;
  }

  static const ChebyshevInterpolation& interpolation(int degree)
  {
    static const std::vector<ChebyshevInterpolation> table = []
    {
      std::vector<ChebyshevInterpolation> made;
      for (int d = 0; d <= kMaxDegree; ++d)
      {
        made.push_back(chebyshevInterpolation(d));
      }
      return made;
    }();
    return table[size_t(degree)];
  }

  const View& TheView;
  const Settings& Config;
  const std::vector<AffinePatch>& Affine;
  FrustumForms& Forms;
  const CellCoverage& Coverage;
  const LoopState<CpuExec>& Loop;
  const glm::dmat4 ClipToWorld;
  std::vector<detail::ComposedNode> Nodes;
  bool RepeatedRoots = false;
  RootSettings Roots;
};

/// The hits of the band's pixels (s.frame's) on the affine patches (rayDegree >= 0), in pixel
/// order: `ordered` holds those of consecutive runs of pixels, one list a run, so that the cost
/// follows the pixels with work (a supersampling pass draws few) rather than the image's size.
/// In first-hit mode a pixel's items beyond its nearest hit so far are skipped, and without
/// clipping planes a ray's roots beyond its first are not looked for.
inline void rayCompositionPass(const View& view, const Settings& settings,
  const std::vector<AffinePatch>& affine, FrustumForms& forms, const CellCoverage& coverage,
  const LoopState<CpuExec>& s, int threads, std::vector<std::vector<RawHit>>& ordered,
  FrameReport& report)
{
  const CompositionPass pass(view, settings, affine, forms, coverage, s);
  const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
  std::vector<std::pair<size_t, std::vector<RawHit>>> runs; // (first pixel, its run's hits)
  detail::CompositionCounts total;
  std::mutex runsMutex;
  parallelFor(count, threads,
    [&](size_t begin, size_t end)
    {
      std::vector<RawHit> hits;
      detail::CompositionCounts counts;
      for (size_t p = first + begin; p < first + end; ++p)
      {
        if (s.ItemOffsets[p] < s.ItemOffsets[p + 1]) // else no patch (nor for a skipped pixel)
        {
          pass.drawPixel(p, hits, counts);
        }
      }
      std::lock_guard<std::mutex> lock(runsMutex);
      runs.emplace_back(begin, std::move(hits));
      total.rays += counts.rays;
      total.steps += counts.steps;
      total.capped += counts.capped;
      total.seeded += counts.seeded;
    });
  std::sort(
    runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ordered.clear();
  for (auto& run : runs)
  {
    ordered.push_back(std::move(run.second));
  }
  report.composedRays += total.rays;
  report.rootFinderSteps += total.steps;
  report.cappedRays += total.capped;
  report.seededRays += total.seeded;
}

} // namespace sst
} // namespace iga
