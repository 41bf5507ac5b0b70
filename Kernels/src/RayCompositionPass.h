// The ray-composition method's pass: per pixel, each patch its work items name (affine, checked
// before the frame) composed with the pixel's ray into a univariate Bernstein polynomial whose
// roots, by the chosen finder, are the pixel's hits. The sweep, the hit policy and the G-buffer
// stage are the other methods'.
#pragma once

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
/// the SST draws), on `threads` threads; sets the report's counts of patches per path.
inline std::vector<AffinePatch> affineWherePossible(
  const Scene& scene, const Settings& settings, int threads, FrameReport& report)
{
  std::vector<AffinePatch> affine(scene.size());
  parallelFor(scene.size(), threads,
    [&](size_t begin, size_t end)
    {
      for (size_t p = begin; p < end; ++p)
      {
        if (p >= scene.volumeCount() ||
            !affineGeometry(
              scene[p], kFirstAttributeChannel + settings.surfaceAttribute, affine[p]))
        {
          affine[p] = AffinePatch();
          affine[p].rayDegree = -1;
        }
      }
    });
  for (const AffinePatch& patch : affine)
  {
    report.rayCompositionPatches += patch.rayDegree >= 0 ? 1 : 0;
  }
  report.sstPatches = scene.size() - report.rayCompositionPatches;
  return affine;
}

/// Every volume's affine form (on `threads` threads); throws std::invalid_argument naming a patch
/// that has none (or a surface, which ray composition does not draw).
inline std::vector<AffinePatch> affinePatches(
  const Scene& scene, const Settings& settings, int threads, FrameReport& report)
{
  if (scene.surfaceCount() > 0)
  {
    throw std::invalid_argument("ray composition draws volumes only, the scene has " +
                                std::to_string(scene.surfaceCount()) + " surfaces");
  }
  std::vector<AffinePatch> affine = affineWherePossible(scene, settings, threads, report);
  for (size_t p = 0; p < scene.size(); ++p)
  {
    if (affine[p].rayDegree < 0)
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
  FrustumForms(
    const std::vector<AffinePatch>& affine, const View& view, const Settings& settings, int threads)
    : Affine(affine)
    , WorldToClip(view.worldToClip)
    , ClipToWorld(glm::inverse(view.worldToClip))
    , Drawn(settings.width, settings.height, settings.farDepths)
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
        const bool made =
          makeFrustumForm(this->Affine[p], this->WorldToClip, this->ClipToWorld, this->Drawn,
            this->Forms[p], [&](size_t count, const auto& fn) { parallelFor(count, threads, fn); });
        this->Made += made ? 1 : 0;
        this->Blossoms += !made && !this->Affine[p].terms.empty() ? 1 : 0;
      });
  }

  const std::vector<AffinePatch>& Affine;
  const glm::dmat4 WorldToClip, ClipToWorld;
  const DrawnPixels Drawn;
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

/// Half the width, in the ray segment's parameter, of the bracket about a seed's root.
constexpr double kSeedHalfWidth = 0.01;

/// A ray's roots on its segment [t0, t1] of origin + t direction: by the finder, or where a
/// first hit is all it needs and the seed frame has a hit at the pixel, from that hit's place
/// along the ray (findNearestRoot, which proves or drops it; `seeded` says which).
inline BernsteinRoots rayRoots(const double* coefficients, int degree, const Settings& settings,
  const RootSettings& rootSettings, const glm::dvec3& origin, const glm::dvec3& direction,
  double t0, double t1, size_t pixel, bool& seeded)
{
  seeded = false;
  const GBuffer* seed = settings.seedFrame;
  if (seed && rootSettings.maxRoots == 1 && seed->width == settings.width &&
      seed->height == settings.height && seed->offsets[pixel] < seed->offsets[pixel + 1])
  {
    const glm::dvec3 hit = seed->hits[seed->offsets[pixel]].position;
    const double t = glm::dot(hit - origin, direction) / glm::dot(direction, direction);
    const double guess = (t - t0) / (t1 - t0);
    if (guess > -kSeedHalfWidth && guess < 1 + kSeedHalfWidth) // else a hit on another patch
    {
      return findNearestRoot(
        coefficients, degree, guess, kSeedHalfWidth, settings.rootFinder, rootSettings, seeded);
    }
  }
  return findBernsteinRoots(coefficients, degree, settings.rootFinder, rootSettings);
}

/// The hits of the band's pixels (s.frame's) on the affine patches (rayDegree >= 0), in pixel
/// order: `ordered` holds those of consecutive runs of pixels, one list a run, so that the cost
/// follows the pixels with work (a supersampling pass draws few) rather than the image's size.
/// In first-hit mode a pixel's items beyond its nearest hit so far are skipped, and without
/// clipping planes a ray's roots beyond its first are not looked for.
inline void rayCompositionPass(const View& view, const Settings& settings,
  const std::vector<AffinePatch>& affine, FrustumForms& forms, const LoopState<CpuExec>& s,
  const Node* initialNodes, int threads, std::vector<std::vector<RawHit>>& ordered,
  FrameReport& report)
{
  static const std::vector<ChebyshevInterpolation> interpolation = []
  {
    std::vector<ChebyshevInterpolation> table;
    for (int d = 0; d <= kMaxDegree; ++d)
    {
      table.push_back(chebyshevInterpolation(d));
    }
    return table;
  }();
  const glm::dmat4 clipToWorld = glm::inverse(view.worldToClip);
  const size_t first = passFirstPixel(s.frame), count = passPixelCount(s.frame);
  // A first hit needs a ray's nearest root alone, unless a clipping plane may cut it away.
  RootSettings rootSettings;
  rootSettings.maxRoots =
    s.frame.hits.firstHitOnly && settings.clipPlanes.empty() ? 1 : roots::kMaxRoots;
  std::vector<std::pair<size_t, std::vector<RawHit>>> runs; // (first pixel, its run's hits)
  std::mutex runsMutex;
  std::atomic<size_t> rays{ 0 }, steps{ 0 }, capped{ 0 }, seededRays{ 0 };
  parallelFor(count, threads,
    [&](size_t begin, size_t end)
    {
      std::vector<RawHit> hits;
      size_t localRays = 0, localSteps = 0, localCapped = 0, localSeeded = 0;
      for (size_t k = begin; k < end; ++k)
      {
        const size_t p = first + k;
        if (s.ItemOffsets[p] == s.ItemOffsets[p + 1])
        {
          continue; // no patch (a skipped pixel's none either)
        }
        const double x = 2 * (double(p % settings.width) + 0.5) / settings.width - 1;
        const double y = 2 * (double(p / settings.width) + 0.5) / settings.height - 1;
        const glm::dvec4 nearPoint = clipToWorld * glm::dvec4(x, y, -1, 1);
        const glm::dvec4 farPoint = clipToWorld * glm::dvec4(x, y, 1, 1);
        const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
        const glm::dvec3 direction = glm::dvec3(farPoint) / farPoint.w - origin;
        int done[64][2], doneCount = 0; // (patch, isovalue) pairs met in earlier items
        double best = s.BestDepth[p];
        for (uint32_t item = s.ItemOffsets[p]; item < s.ItemOffsets[p + 1]; ++item)
        {
          const Node& node = initialNodes[s.ItemNodes[item]];
          if (!s.frame.hits.mayMatter(node.info.box.lo[2], best))
          {
            break; // the items are sorted by nearest depth
          }
          bool seen = affine[size_t(node.patch)].rayDegree < 0;
          for (int d = 0; d < doneCount; ++d)
          {
            seen = seen || (done[d][0] == node.patch && done[d][1] == node.iso);
          }
          double t0, t1;
          const AffinePatch& patch = affine[size_t(node.patch)];
          if (seen || !rayInPatch(patch, origin, direction, 0, 1, t0, t1))
          {
            continue;
          }
          if (doneCount < 64)
          {
            done[doneCount][0] = node.patch;
            done[doneCount++][1] = node.iso;
          }
          const glm::dvec3 u0 = patch.inverse * (origin + t0 * direction - patch.origin);
          const glm::dvec3 du = patch.inverse * ((t1 - t0) * direction);
          double coefficients[kMaxOrder];
          const FrustumForm& form = forms.of(size_t(node.patch));
          if (form.degree >= 0)
          {
            composeFrustumRay(form, settings.isovalues[size_t(node.iso)], x, y, t0, t1,
              interpolation[size_t(patch.rayDegree)], coefficients);
          }
          else if (!patch.terms.empty())
          {
            blossomAlongRay(patch.terms.data(), int(patch.terms.size()), patch.rayDegree,
              2.0 * u0 - 1.0, 2.0 * (u0 + du) - 1.0, settings.isovalues[size_t(node.iso)],
              coefficients);
          }
          else
          {
            composeRay(patch, settings.isovalues[size_t(node.iso)], u0, du,
              interpolation[size_t(patch.rayDegree)], coefficients);
          }
          bool seeded;
          const BernsteinRoots roots = rayRoots(coefficients, patch.rayDegree, settings,
            rootSettings, origin, direction, t0, t1, p, seeded);
          ++localRays;
          localSeeded += seeded ? 1 : 0;
          localSteps += size_t(roots.cost.insertions + roots.cost.evaluations);
          localCapped += roots.cost.capped ? 1 : 0;
          for (int r = 0; r < roots.count; ++r)
          {
            const glm::dvec3 position = origin + (t0 + roots.t[r] * (t1 - t0)) * direction;
            const glm::dvec4 clip = view.worldToClip * glm::dvec4(position, 1);
            bool kept = true;
            for (const auto& plane : settings.clipPlanes)
            {
              kept = kept && plane[0] * position.x + plane[1] * position.y + plane[2] * position.z +
                                 plane[3] >=
                               0;
            }
            if (!kept)
            {
              continue;
            }
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
            best = s.frame.hits.afterHit(best, hit.ndcDepth);
          }
        }
      }
      rays += localRays;
      steps += localSteps;
      capped += localCapped;
      seededRays += localSeeded;
      std::lock_guard<std::mutex> lock(runsMutex);
      runs.emplace_back(begin, std::move(hits));
    });
  std::sort(
    runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ordered.clear();
  for (auto& run : runs)
  {
    ordered.push_back(std::move(run.second));
  }
  report.composedRays += rays;
  report.rootFinderSteps += steps;
  report.cappedRays += capped;
  report.seededRays += seededRays;
}

} // namespace sst
} // namespace iga
