// The ray-composition method's pass: per pixel, each patch its work items name (affine, checked
// before the frame) composed with the pixel's ray into a univariate Bernstein polynomial whose
// roots, by the chosen finder, are the pixel's hits. The sweep, the hit policy and the G-buffer
// stage are the other methods'.
#pragma once

#include "ParallelFor.h"
#include "iga/FrustumForm.h"
#include "iga/IsosurfaceCells.h"
#include "iga/RayComposition.h"
#include "iga/sst/Engine.h"
#include "sst/CpuExec.h"
#include "sst/LoopState.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace iga
{
namespace sst
{

using AffineForms = std::shared_ptr<const std::vector<AffinePatch>>;

/// What names a scene's affine analysis between frames: Settings::dataVersion (the same
/// non-zero version, the same patches, as for the CUDA driver's copy of them), the surface
/// attribute and the isovalues, and as a check the patches' shapes and first and last values.
struct AffineKey
{
  uint64_t version = 0;
  int attribute = 0;
  std::vector<double> isovalues, fingerprint;

  AffineKey(const Scene& scene, const Settings& settings)
    : version(settings.dataVersion)
    , attribute(settings.surfaceAttribute)
    , isovalues(settings.isovalues)
  {
    fingerprint.reserve(4 * scene.size() + 1);
    fingerprint.push_back(double(scene.volumeCount()));
    for (size_t p = 0; p < scene.size(); ++p)
    {
      const auto v = scene[p];
      fingerprint.push_back(v.degree[0] + 32.0 * (v.degree[1] + 32.0 * v.degree[2]));
      fingerprint.push_back(v.channels);
      fingerprint.push_back(v.coeffs[0]);
      fingerprint.push_back(v.coeffs[v.valueCount() - 1]);
    }
  }
  bool operator==(const AffineKey& other) const
  {
    return version == other.version && attribute == other.attribute &&
           isovalues == other.isovalues && fingerprint == other.fingerprint;
  }
};

/// Each patch's affine form, rayDegree -1 for the surfaces and the volumes without one (which
/// the SST draws), on `threads` threads; sets the report's counts of patches per path. The
/// analysis of the last scene with a non-zero data version is kept for the next frame of that
/// version (a camera move: thousands of ABS patches take some 12 ms).
inline AffineForms affineWherePossible(
  const Scene& scene, const Settings& settings, int threads, FrameReport& report)
{
  static std::mutex keptMutex;
  static std::unique_ptr<AffineKey> keptKey;
  static AffineForms kept;
  std::unique_ptr<AffineKey> key;
  AffineForms forms;
  if (settings.dataVersion != 0)
  {
    key = std::make_unique<AffineKey>(scene, settings);
    std::lock_guard<std::mutex> lock(keptMutex);
    forms = keptKey && *keptKey == *key ? kept : nullptr;
  }
  if (!forms)
  {
    auto affine = std::make_shared<std::vector<AffinePatch>>(scene.size());
    parallelFor(scene.size(), threads,
      [&](size_t begin, size_t end)
      {
        for (size_t p = begin; p < end; ++p)
        {
          AffinePatch& patch = (*affine)[p];
          if (p >= scene.volumeCount() ||
              !affineGeometry(scene[p], kFirstAttributeChannel + settings.surfaceAttribute, patch))
          {
            patch = AffinePatch();
            patch.rayDegree = -1;
          }
        }
      });
    forms = affine;
  }
  if (key)
  {
    std::lock_guard<std::mutex> lock(keptMutex);
    keptKey = std::move(key);
    kept = forms;
  }
  for (const AffinePatch& patch : *forms)
  {
    report.rayCompositionPatches += patch.rayDegree >= 0 ? 1 : 0;
  }
  report.sstPatches = scene.size() - report.rayCompositionPatches;
  return forms;
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

/// Per affine patch and isovalue, the pixels whose rays may meet its isosurface: those the window
/// boxes of its isosurfaceCells cover, or every pixel where the patch has no cells (a box under
/// kCellPixels across, a degree above kCellDegree, a corner behind the eye, or
/// Settings::isosurfaceCells off).
class CellCoverage
{
public:
  /// A patch whose window box spans fewer pixels than this gets no cells; one that spans more
  /// gets cells about this size (at most kCellLevels halvings).
  static constexpr double kCellPixels = 8;
  static constexpr int kCellLevels = 5;
  /// Above this degree along a direction the octree costs more than the rays it saves.
  static constexpr int kCellDegree = 8;

  CellCoverage(const AffineForms& affine, const View& view, const Settings& settings, int threads)
    : Isovalues(settings.isovalues.size())
    , Width(size_t(settings.width))
    , ClipToWorld(glm::inverse(view.worldToClip))
    , Masks(affine->size() * settings.isovalues.size())
  {
    const double wScale = std::fabs(this->ClipToWorld[3][3]) + std::fabs(this->ClipToWorld[2][3]);
    this->SharedDepths = std::fabs(this->ClipToWorld[0][3]) <= 1e-14 * wScale &&
                         std::fabs(this->ClipToWorld[1][3]) <= 1e-14 * wScale;
    const glm::dmat4 window = windowFromWorld(view, settings.width, settings.height);
    std::vector<int> levels(this->Masks.size(), 0);
    parallelFor(settings.isosurfaceCells ? affine->size() : 0, threads,
      [&](size_t begin, size_t end)
      {
        for (size_t p = begin; p < end; ++p)
        {
          for (size_t iso = 0; iso < this->Isovalues; ++iso)
          {
            levels[p * this->Isovalues + iso] = cellLevels((*affine)[p], window);
          }
        }
      });
    const auto cells = cellsOf(affine, settings.isovalues, levels, threads);
    parallelFor(cells->size(), threads,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          const size_t m = (*cells)[k].first;
          this->cover((*affine)[m / this->Isovalues], (*cells)[k].second.data(), window, settings,
            this->Masks[m]);
        }
      });
    for (const auto& mask : *cells)
    {
      for (const auto& octant : mask.second)
      {
        this->Cells += octant.size();
      }
    }
  }

  /// Whether the ray of `pixel` may meet the isosurface of patch `patch` at isovalue `iso`.
  bool mayHit(int patch, int iso, size_t pixel) const
  {
    const Mask& mask = this->Masks[size_t(patch) * this->Isovalues + size_t(iso)];
    if (mask.whole)
    {
      return true;
    }
    size_t local;
    return mask.local(pixel, this->Width, local) && (mask.bits[local / 64] >> (local % 64) & 1);
  }

  /// The part [t0, t1] of pixel rays (origin + t direction from the near plane, t = 0, to the
  /// far plane, t = 1) that the cells covering `pixel`'s tile span; false where the patch has no
  /// cells or the view's rays do not share their depths' parameters.
  bool segment(int patch, int iso, size_t pixel, double& t0, double& t1) const
  {
    const Mask& mask = this->Masks[size_t(patch) * this->Isovalues + size_t(iso)];
    size_t local;
    if (mask.first.empty() || !mask.local(pixel, this->Width, local))
    {
      return false;
    }
    const size_t tile = mask.tileOf(local % mask.width, local / mask.width);
    t0 = mask.first[tile];
    t1 = mask.last[tile];
    return true;
  }

  /// Cells kept over all patches and isovalues.
  size_t cells() const { return this->Cells; }

private:
  /// Segments are kept per tile of kTile x kTile pixels: per pixel they would cost a frame more
  /// in writing them (and the pages) than the rays save.
  static constexpr size_t kTile = 4;

  /// A patch's pixels over the pixel rectangle its cells' window boxes cover, [x0, x0 + width)
  /// x [y0, y0 + height) (a pixel outside it meets none of its isosurface), or every pixel.
  struct Mask
  {
    bool whole = true; ///< every pixel (no cells)
    size_t x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<uint64_t> bits; ///< one a pixel of the rectangle, row by row
    /// Per tile of the rectangle, the ray parameters the boxes of the cells covering any of its
    /// pixels span (rounded outwards); empty where the view's rays do not share them.
    std::vector<float> first, last;

    /// Pixel `pixel`'s index in the rectangle; false outside it.
    bool local(size_t pixel, size_t imageWidth, size_t& index) const
    {
      const size_t i = pixel % imageWidth - this->x0, j = pixel / imageWidth - this->y0;
      index = j * this->width + i;
      return i < this->width && j < this->height; // unsigned: left of or below it wraps
    }
    size_t tileOf(size_t i, size_t j) const
    {
      return j / kTile * ((this->width + kTile - 1) / kTile) + i / kTile;
    }
  };

  /// The parameter t along a pixel ray of the point at NDC depth z. Where the unprojection's w
  /// does not depend on the pixel (VTK's perspective and parallel views), a point's depth fixes
  /// its eye depth, which runs from the near plane's to the far plane's linearly in t: one
  /// parameter for every pixel, read off the middle ray.
  double rayParameter(double z) const
  {
    const auto at = [&](double depth)
    {
      const glm::dvec4 x = this->ClipToWorld * glm::dvec4(0, 0, depth, 1);
      return glm::dvec3(x) / x.w;
    };
    const glm::dvec3 origin = at(-1), direction = at(1) - origin;
    return glm::dot(at(z) - origin, direction) / glm::dot(direction, direction);
  }

  /// The window box of the parameter box [lo, lo + size]^3 of an affine patch (its corners'
  /// images: the patch is a parallelepiped); false where a corner is not in front of the eye.
  static bool windowBox(const AffinePatch& patch, const glm::dmat4& window, const glm::dvec3& lo,
    double size, Box3<double>& box)
  {
    for (int d = 0; d < 3; ++d)
    {
      box.lo[d] = std::numeric_limits<double>::infinity();
      box.hi[d] = -std::numeric_limits<double>::infinity();
    }
    for (int c = 0; c < 8; ++c)
    {
      const glm::dvec3 u =
        lo + size * glm::dvec3(double(c & 1), double(c >> 1 & 1), double(c >> 2));
      const glm::dvec4 x = window * glm::dvec4(patch.origin + patch.axes * u, 1.0);
      if (!(x.w > 0))
      {
        return false;
      }
      for (int d = 0; d < 3; ++d)
      {
        box.lo[d] = std::min(box.lo[d], x[d] / x.w);
        box.hi[d] = std::max(box.hi[d], x[d] / x.w);
      }
    }
    return true;
  }

  /// Sets bits first..last.
  static void setBits(std::vector<uint64_t>& bits, size_t first, size_t last)
  {
    const auto from = [](size_t bit) { return ~uint64_t(0) << (bit % 64); };
    const size_t a = first / 64, b = last / 64;
    const uint64_t upTo = ~uint64_t(0) >> (63 - last % 64);
    if (a == b)
    {
      bits[a] |= from(first) & upTo;
      return;
    }
    bits[a] |= from(first);
    for (size_t w = a + 1; w < b; ++w)
    {
      bits[w] = ~uint64_t(0);
    }
    bits[b] |= upTo;
  }

  /// Per mask with cells (patch * isovalues + iso), the cells of its 8 octants.
  using MaskCells = std::vector<std::pair<size_t, std::vector<std::vector<ParameterCell>>>>;

  /// The cells of the masks with levels, the octants worked on side by side. Being the view's
  /// only through their levels, they are kept for the next frame with the same affine forms
  /// (the same data version: affineWherePossible), isovalues and levels.
  static std::shared_ptr<const MaskCells> cellsOf(const AffineForms& affine,
    const std::vector<double>& isovalues, const std::vector<int>& levels, int threads)
  {
    static std::mutex keptMutex;
    static AffineForms keptForms;
    static std::vector<double> keptIsovalues;
    static std::vector<int> keptLevels;
    static std::shared_ptr<const MaskCells> kept;
    {
      std::lock_guard<std::mutex> lock(keptMutex);
      if (keptForms == affine && keptIsovalues == isovalues && keptLevels == levels)
      {
        return kept;
      }
    }
    auto cells = std::make_shared<MaskCells>();
    for (size_t m = 0; m < levels.size(); ++m)
    {
      if (levels[m] > 0)
      {
        cells->emplace_back(m, std::vector<std::vector<ParameterCell>>(8));
      }
    }
    parallelFor(8 * cells->size(), threads,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          const size_t m = (*cells)[k / 8].first;
          (*cells)[k / 8].second[k % 8] = isosurfaceCells((*affine)[m / isovalues.size()],
            isovalues[m % isovalues.size()], levels[m], int(k % 8));
        }
      });
    std::lock_guard<std::mutex> lock(keptMutex);
    keptForms = affine;
    keptIsovalues = isovalues;
    keptLevels = levels;
    kept = cells;
    return kept;
  }

  /// The octree levels of the patch's cells: about kCellPixels across in the window, none (0)
  /// where the patch gets no cells.
  static int cellLevels(const AffinePatch& patch, const glm::dmat4& window)
  {
    Box3<double> box;
    if (patch.rayDegree < 0 || *std::max_element(patch.degree, patch.degree + 3) > kCellDegree ||
        !windowBox(patch, window, glm::dvec3(0.0), 1.0, box))
    {
      return 0;
    }
    const double extent = std::max(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1]);
    return std::max(0, std::min(kCellLevels, int(std::floor(std::log2(extent / kCellPixels)))));
  }

  /// Sets `mask` to the pixels the cells of its 8 octants cover and their tiles' segments, or
  /// leaves it whole (every pixel) where a cell is not in front of the eye.
  void cover(const AffinePatch& patch, const std::vector<ParameterCell>* octants,
    const glm::dmat4& window, const Settings& settings, Mask& mask) const
  {
    // The cells' window boxes and pixel ranges, and the rectangle of those.
    std::vector<std::pair<Box3<double>, std::array<int, 4>>> boxes;
    int rectangle[4] = { settings.width, -1, settings.height, -1 };
    for (int k = 0; k < 8; ++k)
    {
      for (const ParameterCell& cell : octants[k])
      {
        Box3<double> box;
        std::array<int, 4> range;
        if (!windowBox(patch, window, cell.lo, cell.size, box))
        {
          return;
        }
        pixelRange(box, settings.width, 0, settings.height, range.data());
        if (range[0] <= range[1] && range[2] <= range[3])
        {
          boxes.emplace_back(box, range);
          for (int d = 0; d < 4; d += 2)
          {
            rectangle[d] = std::min(rectangle[d], range[size_t(d)]);
            rectangle[d + 1] = std::max(rectangle[d + 1], range[size_t(d) + 1]);
          }
        }
      }
    }
    mask.whole = false;
    mask.x0 = size_t(std::max(rectangle[0], 0));
    mask.y0 = size_t(std::max(rectangle[2], 0));
    mask.width = size_t(std::max(rectangle[1] - rectangle[0] + 1, 0));
    mask.height = size_t(std::max(rectangle[3] - rectangle[2] + 1, 0));
    mask.bits.assign((mask.width * mask.height + 63) / 64, 0);
    if (this->SharedDepths)
    {
      const size_t tiles = mask.tileOf(0, mask.height + kTile - 1);
      mask.first.assign(tiles, std::numeric_limits<float>::infinity());
      mask.last.assign(tiles, -std::numeric_limits<float>::infinity());
    }
    for (auto& [box, range] : boxes)
    {
      // The range in the rectangle's pixels.
      range[0] -= int(mask.x0), range[1] -= int(mask.x0);
      range[2] -= int(mask.y0), range[3] -= int(mask.y0);
      for (int j = range[2]; j <= range[3]; ++j)
      {
        const size_t row = size_t(j) * mask.width;
        setBits(mask.bits, row + size_t(range[0]), row + size_t(range[1]));
      }
      if (this->SharedDepths)
      {
        this->widenSegments(box, range.data(), mask);
      }
    }
  }

  /// Widens the segments of the tiles the pixel range (in the rectangle) of a cell's box
  /// touches to the box's depths.
  void widenSegments(const Box3<double>& box, const int* range, Mask& mask) const
  {
    const float first =
      std::nextafter(float(this->rayParameter(std::max(box.lo[2], -1.0))), -INFINITY);
    const float last =
      std::nextafter(float(this->rayParameter(std::min(box.hi[2], 1.0))), INFINITY);
    for (size_t tj = size_t(range[2]) / kTile; tj <= size_t(range[3]) / kTile; ++tj)
    {
      for (size_t ti = size_t(range[0]) / kTile; ti <= size_t(range[1]) / kTile; ++ti)
      {
        const size_t tile = mask.tileOf(ti * kTile, tj * kTile);
        mask.first[tile] = std::min(mask.first[tile], first);
        mask.last[tile] = std::max(mask.last[tile], last);
      }
    }
  }

  const size_t Isovalues, Width;
  const glm::dmat4 ClipToWorld;
  bool SharedDepths;       ///< the view's pixel rays share their depths' parameters (rayParameter)
  std::vector<Mask> Masks; ///< patch * isovalues + iso
  size_t Cells = 0;
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
    if (!rayInPatch(patch, ray.origin, ray.direction, 0, 1, t0, t1) ||
        !this->clipToCells(p, node, t0, t1))
    {
      return;
    }
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
      ray.origin, ray.direction, t0, t1, p, seeded);
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
