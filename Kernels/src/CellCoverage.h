// Ray composition's isosurface cells in the window: per affine patch and isovalue, the pixels
// whose rays may meet the isosurface and the part of those rays that may, from the window boxes
// of the cells that may hold it (iga/IsosurfaceCells.h).
#pragma once

#include "ParallelFor.h"
#include "iga/FrustumForm.h"
#include "iga/IsosurfaceCells.h"
#include "iga/sst/Engine.h"
#include "iga/sst/Tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

namespace iga
{
namespace sst
{

/// A scene's affine analysis, one AffinePatch a patch (RayCompositionPass.h's
/// affineWherePossible), shared by the frames of one data version.
using AffineForms = std::shared_ptr<const std::vector<AffinePatch>>;

/// Per affine patch and isovalue, the pixels whose rays may meet its isosurface: those the window
/// boxes of its isosurfaceCells cover, or every pixel where the patch has no cells (a box under
/// twice kCellPixels across, a degree above kCellDegree, a corner behind the eye, or
/// Settings::isosurfaceCells off).
class CellCoverage
{
public:
  /// A patch whose window box spans fewer than twice this many pixels gets no cells; one that
  /// spans more gets cells about this size, at most kCellLevels halvings (an ABS field's patches
  /// of 8-16 pixels two or three halvings, a gallery surface's box of 370 about 11-pixel cells).
  /// Finer cells cost more in covering than the rays they save.
  static constexpr double kCellPixels = 2;
  static constexpr int kCellLevels = 5;
  /// Above this degree along a direction the octree costs more than the rays it saves.
  static constexpr int kCellDegree = 8;

  CellCoverage(const AffineForms& affine, const View& view, const Settings& settings, int threads)
    : Isovalues(settings.isovalues.size())
    , Width(size_t(settings.width))
    , ClipToWorld(glm::inverse(view.worldToClip))
    , Middle(ClipToWorld)
    , Drawn(settings.width, settings.height, settings.farDepths)
    , Masks(affine->size() * settings.isovalues.size())
  {
    const double wScale = std::fabs(this->ClipToWorld[3][3]) + std::fabs(this->ClipToWorld[2][3]);
    this->SharedDepths = std::fabs(this->ClipToWorld[0][3]) <= 1e-14 * wScale &&
                         std::fabs(this->ClipToWorld[1][3]) <= 1e-14 * wScale;
    const glm::dmat4 window = windowFromWorld(view, settings.width, settings.height);
    std::vector<int> levels(this->Masks.size(), 0);
    std::vector<char> undrawn(affine->size(), 0);
    parallelFor(settings.isosurfaceCells ? affine->size() : 0, threads,
      [&](size_t begin, size_t end)
      {
        for (size_t p = begin; p < end; ++p)
        {
          Box3<double> box;
          const int level = cellLevels((*affine)[p], window, box);
          undrawn[p] = level > 0 && !this->drawsIn(box, settings);
          for (size_t iso = 0; iso < this->Isovalues; ++iso)
          {
            levels[p * this->Isovalues + iso] = level;
          }
        }
      });
    // The cells are kept with their levels, the same for the view's every frame; a patch that
    // draws no pixel (a supersampling pass draws few) takes no time to cover.
    const auto cells = cellsOf(affine, settings.isovalues, levels, threads);
    parallelFor(cells->size(), threads,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          const size_t m = (*cells)[k].first;
          if (undrawn[m / this->Isovalues])
          {
            this->Masks[m].whole = false; // no pixel: no ray, and an empty node box
          }
          else
          {
            this->cover((*affine)[m / this->Isovalues], (*cells)[k].second.data(), window, settings,
              this->Masks[m]);
          }
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

  /// Narrows the boxes of initial nodes whose patch and isovalue have cells to the cells'
  /// window boxes (an empty box where none covers a pixel): the sweep then pairs a node with the
  /// pixels its cells cover only, and orders a pixel's items by their cells' nearest depth.
  void narrowNodes(Node* nodes, size_t count) const
  {
    for (size_t n = 0; n < count; ++n)
    {
      Box3<double>& box = nodes[n].info.box;
      const size_t m = size_t(nodes[n].patch) * this->Isovalues + size_t(nodes[n].iso);
      if (nodes[n].iso < 0 || m >= this->Masks.size() || this->Masks[m].whole)
      {
        continue;
      }
      const Box3<double>& cells = this->Masks[m].bounds;
      for (int d = 0; d < 3; ++d)
      {
        box.lo[d] = std::max(box.lo[d], cells.lo[d]);
        box.hi[d] = std::min(box.hi[d], cells.hi[d]);
      }
      if (!(box.lo[0] <= box.hi[0] && box.lo[1] <= box.hi[1] && box.lo[2] <= box.hi[2]))
      {
        box = Box3<double>{ { 1, 1, 1 }, { 0, 0, 0 } }; // covers no pixel centre
      }
    }
  }

  /// The pixels whose rays may meet the patch's isosurfaces, summed over its isovalues (an
  /// upper bound of the rays composed through it); infinite where a mask is whole.
  double pixels(size_t patch) const
  {
    double sum = 0;
    for (size_t iso = 0; iso < this->Isovalues; ++iso)
    {
      const Mask& mask = this->Masks[patch * this->Isovalues + iso];
      if (mask.whole)
      {
        return std::numeric_limits<double>::infinity();
      }
      sum += double(mask.count);
    }
    return sum;
  }

  /// Cells kept over all patches and isovalues.
  size_t cells() const { return this->Cells; }

  /// The pixels the frame draws (all, or those its far depths leave).
  const DrawnPixels& drawn() const { return this->Drawn; }

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
    size_t count = 0;           ///< of bits set
    /// The window boxes of the cells covering pixels, together (empty: lo above hi).
    Box3<double> bounds = { { 1, 1, 1 }, { 0, 0, 0 } };
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
  struct MiddleRay
  {
    glm::dvec4 depthColumn, pointColumn; ///< the unprojection's columns for z and 1
    glm::dvec3 origin, scaledDirection;  ///< its near point, and its direction / |direction|²

    explicit MiddleRay(const glm::dmat4& clipToWorld)
      : depthColumn(clipToWorld[2])
      , pointColumn(clipToWorld[3])
      , origin(at(-1))
    {
      const glm::dvec3 direction = at(1) - this->origin;
      this->scaledDirection = direction / glm::dot(direction, direction);
    }
    glm::dvec3 at(double z) const
    {
      const glm::dvec4 x = z * this->depthColumn + this->pointColumn;
      return glm::dvec3(x) / x.w;
    }
    double parameter(double z) const
    {
      return glm::dot(this->at(z) - this->origin, this->scaledDirection);
    }
  };

  /// An affine patch's point at parameter u in homogeneous window coordinates: origin + u_0
  /// axis[0] + u_1 axis[1] + u_2 axis[2] (the patch is a parallelepiped).
  struct WindowMap
  {
    glm::dvec4 origin, axis[3];

    WindowMap(const AffinePatch& patch, const glm::dmat4& window)
      : origin(window * glm::dvec4(patch.origin, 1.0))
    {
      for (int d = 0; d < 3; ++d)
      {
        this->axis[d] = window * glm::dvec4(patch.axes[d], 0.0);
      }
    }
  };

  /// The window box of the parameter box [lo, lo + size]^3 of an affine patch (its corners'
  /// images); false where a corner is not in front of the eye.
  static bool windowBox(const WindowMap& map, const glm::dvec3& lo, double size, Box3<double>& box)
  {
    const glm::dvec4 first =
      map.origin + lo.x * map.axis[0] + lo.y * map.axis[1] + lo.z * map.axis[2];
    const glm::dvec4 edge[3] = { size * map.axis[0], size * map.axis[1], size * map.axis[2] };
    for (int d = 0; d < 3; ++d)
    {
      box.lo[d] = std::numeric_limits<double>::infinity();
      box.hi[d] = -std::numeric_limits<double>::infinity();
    }
    for (int c = 0; c < 8; ++c)
    {
      glm::dvec4 x = first;
      for (int d = 0; d < 3; ++d)
      {
        x += (c >> d & 1) ? edge[d] : glm::dvec4(0.0);
      }
      if (!(x.w > 0))
      {
        return false;
      }
      const double inverse = 1 / x.w;
      for (int d = 0; d < 3; ++d)
      {
        box.lo[d] = std::min(box.lo[d], x[d] * inverse);
        box.hi[d] = std::max(box.hi[d], x[d] * inverse);
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
    static std::weak_ptr<const std::vector<AffinePatch>> keptForms; // not kept alive by it
    static std::vector<double> keptIsovalues;
    static std::vector<int> keptLevels;
    static std::shared_ptr<const MaskCells> kept;
    {
      std::lock_guard<std::mutex> lock(keptMutex);
      if (keptForms.lock() == affine && keptIsovalues == isovalues && keptLevels == levels)
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
  static int cellLevels(const AffinePatch& patch, const glm::dmat4& window, Box3<double>& box)
  {
    if (patch.rayDegree < 0 || *std::max_element(patch.degree, patch.degree + 3) > kCellDegree ||
        !windowBox(WindowMap(patch, window), glm::dvec3(0.0), 1.0, box))
    {
      return 0;
    }
    const double extent = std::max(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1]);
    return std::max(0, std::min(kCellLevels, int(std::floor(std::log2(extent / kCellPixels)))));
  }

  /// Whether the frame draws a pixel whose centre a window box covers.
  bool drawsIn(const Box3<double>& box, const Settings& settings) const
  {
    const double lo[2] = { 2 * box.lo[0] / settings.width - 1,
      2 * box.lo[1] / settings.height - 1 };
    const double hi[2] = { 2 * box.hi[0] / settings.width - 1,
      2 * box.hi[1] / settings.height - 1 };
    return this->Drawn.in(lo, hi) > 0;
  }

  /// Sets `mask` to the pixels the cells of its 8 octants cover and their tiles' segments, or
  /// leaves it whole (every pixel) where a cell is not in front of the eye.
  void cover(const AffinePatch& patch, const std::vector<ParameterCell>* octants,
    const glm::dmat4& window, const Settings& settings, Mask& mask) const
  {
    // The cells' window boxes and pixel ranges, and the rectangle of those.
    std::vector<std::pair<Box3<double>, std::array<int, 4>>> boxes;
    size_t cells = 0;
    for (int k = 0; k < 8; ++k)
    {
      cells += octants[k].size();
    }
    boxes.reserve(cells);
    int rectangle[4] = { settings.width, -1, settings.height, -1 };
    const WindowMap map(patch, window);
    for (int k = 0; k < 8; ++k)
    {
      for (const ParameterCell& cell : octants[k])
      {
        Box3<double> box;
        std::array<int, 4> range;
        if (!windowBox(map, cell.lo, cell.size, box))
        {
          return;
        }
        pixelRange(box, settings.width, 0, settings.height, range.data());
        if (range[0] <= range[1] && range[2] <= range[3])
        {
          for (int d = 0; d < 3; ++d)
          {
            mask.bounds.lo[d] = boxes.empty() ? box.lo[d] : std::min(mask.bounds.lo[d], box.lo[d]);
            mask.bounds.hi[d] = boxes.empty() ? box.hi[d] : std::max(mask.bounds.hi[d], box.hi[d]);
          }
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
    for (uint64_t word : mask.bits)
    {
      mask.count += size_t(__builtin_popcountll(word));
    }
  }

  /// Widens the segments of the tiles the pixel range (in the rectangle) of a cell's box
  /// touches to the box's depths.
  void widenSegments(const Box3<double>& box, const int* range, Mask& mask) const
  {
    const float first =
      std::nextafter(float(this->Middle.parameter(std::max(box.lo[2], -1.0))), -INFINITY);
    const float last =
      std::nextafter(float(this->Middle.parameter(std::min(box.hi[2], 1.0))), INFINITY);
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
  const MiddleRay Middle;
  const DrawnPixels Drawn;
  bool SharedDepths;       ///< the view's pixel rays share their depths' parameters (MiddleRay)
  std::vector<Mask> Masks; ///< patch * isovalues + iso
  size_t Cells = 0;
};

} // namespace sst
} // namespace iga
