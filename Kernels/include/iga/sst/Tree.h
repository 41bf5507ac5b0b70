// The shared subdivision tree's per-element steps (node tests, children, hits, shading and the
// per-pixel merge), written once for the CPU driver and the CUDA driver.
#pragma once

#include "iga/Camera.h"
#include "iga/PowerForm.h"
#include "iga/sst/Engine.h"
#include "iga/sst/HitPolicy.h"
#include "iga/sst/PixelProblem.h"

#include <stddef.h>
#include <stdint.h>

namespace iga
{
namespace sst
{

/// Where a node lies: a sub-patch of an input patch for one isovalue (a volume) or of a surface
/// (iso -1), whose depths and integer offsets locate it in the input patch's parameter cube
/// ([offset, offset + 1] / 2^depth along each direction; a surface's third stays 0), and its
/// place in the SST loop.
struct NodePlace
{
  int patch;
  int iso;
  int level;         ///< the most halvings along one direction below the input patch
  int depth[3];      ///< halvings along each direction
  int64_t offset[3]; ///< which of the 2^depth[d] intervals along d it covers
  size_t coeff;      ///< start of its screen coefficients in the owning pool
  uint32_t initial;  ///< the initial node (SAG work item) it descends from
  bool implicit;     ///< SST: stands for all round pixels in its box, without tuples yet
  bool overBudget;   ///< SST: an implicit node the memory cap did not let split
  uint8_t axes;      ///< SST: the directions its split halves (splitAxes), once it is chosen
};

/// A node of a subdivision tree: its place and what it knows of itself.
struct Node : NodePlace
{
  NodeInfo<double> info;
};

/// A ray/isosurface root before shading.
struct RawHit
{
  uint32_t pixel;
  int patch;
  int iso;
  double ndcDepth;
  double u[3]; ///< in the input patch's parameter cube
};

/// A (pixel, node) pair of the SST loop.
struct Tuple
{
  uint32_t pixel;
  uint32_t node;
};

// The SST loop's memory model, the same in both drivers so that under
// Settings::memoryBudgetBytes they split, and give up, the same nodes and tuples. The budget caps
// the band's work items and the loop's nodes, coefficients, tuples and children.

/// Per tuple, in either driver: the tuple, its outcome, solution (u, depth) and hit index or
/// pixel run, and the compaction's count, offset and child slots.
constexpr uint64_t kBytesPerTuple = sizeof(Tuple) + 2 + 4 * sizeof(double) + 12;
/// Per node record, with the flags, counts and offsets of its stages.
constexpr uint64_t kBytesPerNode = sizeof(Node) + 64;
/// Per work item of the band: its initial node, and the sorted (pixel, node) pair it came from,
/// which the CUDA driver keeps.
constexpr uint64_t kBytesPerWorkItem = sizeof(Tuple) + sizeof(uint32_t);

/// Per hit through the G-buffer stage: the raw hit, its shaded record and the copy delivered,
/// and its pixel run's start, pixel and kept count.
constexpr uint64_t kBytesPerHit = sizeof(RawHit) + 2 * sizeof(Hit) + 3 * sizeof(uint32_t);
/// Per pixel of the image, whatever the scene: the nearest depth, the unresolved flag, the
/// solve count, the group bounds, the work-item offset, the active lists, the G-buffer offset
/// (and the CUDA driver's copy of it), and one hit (imageBytes).
constexpr uint64_t kBytesPerImagePixel = sizeof(double) + 1 + 8 * sizeof(uint32_t) + kBytesPerHit;

/// Nodes with `values` screen coefficients in all.
IGA_HD inline uint64_t nodeBytes(uint64_t nodes, uint64_t values)
{
  return nodes * kBytesPerNode + values * sizeof(double);
}

/// What an iteration holds before its subdivision: work items, nodes and tuples.
IGA_HD inline uint64_t loopBytes(
  uint64_t workItems, uint64_t nodes, uint64_t values, uint64_t tuples)
{
  return workItems * kBytesPerWorkItem + nodeBytes(nodes, values) + tuples * kBytesPerTuple;
}

/// What splitting adds: the children, and the compaction's copy of those it keeps.
IGA_HD inline uint64_t childBytes(uint64_t children, uint64_t values)
{
  return 2 * nodeBytes(children, values);
}

/// Child slots a split node takes in the subdivision stage: up to eight children (childCount),
/// the slots past them empty.
constexpr int kChildSlots = 8;

/// What splitting a node with `values` screen coefficients into `children` adds: its children
/// (kChildSlots records), their copy, and room for the tuples that failed on it to move on (one
/// each in the next iteration), so that the compaction does not give up the work the split was
/// for.
IGA_HD inline uint64_t splitBytes(uint64_t values, int children, uint64_t failedTuples)
{
  return childBytes(kChildSlots, children * values) + failedTuples * kBytesPerTuple;
}

/// The longest prefix [0, count) of a sequence whose running total through element k,
/// `through(k)` (non-decreasing in k), stays within `room`.
template<class Through>
IGA_HD size_t prefixWithin(size_t count, uint64_t room, Through through)
{
  size_t lo = 0, hi = count;
  while (lo < hi)
  {
    const size_t mid = (lo + hi) / 2;
    if (uint64_t(through(mid)) <= room)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return lo;
}

/// How many nodes of `count` the overlap stage turns into tuples, when through(k) tuples come
/// from nodes [0, k]: as many as keep the tuples within the budget's room for them past
/// `held` (loopBytes); the others wait, implicit. When that leaves no tuple at all
/// (`noTuples`, and none fit), the loop would stall: then a band's worth comes in anyway, as
/// many tuples as the band has work items (rowBands keeps room for one each), and at least the
/// first node with tuples, so that a round whose nodes alone fill the budget still moves on
/// in a few iterations rather than a node at a time.
template<class Through>
IGA_HD size_t admittedNodes(
  size_t count, uint64_t budget, uint64_t held, uint64_t workItems, bool noTuples, Through through)
{
  const size_t admitted =
    prefixWithin(count, held < budget ? (budget - held) / kBytesPerTuple : 0, through);
  const bool stalled =
    noTuples && admitted < count && (admitted == 0 || through(admitted - 1) == 0);
  if (!stalled)
  {
    return admitted;
  }
  const uint64_t first = through(admitted); // the tuples of the first node with any
  return prefixWithin(count, first > workItems ? first : workItems, through);
}

/// How many tuples the compaction may hand on: a Tuple each next to all the iteration holds
/// (`held`, children included), then kBytesPerTuple each in the next iteration, next to the
/// work items and the kept children (at most `children` bytes).
IGA_HD inline uint64_t nextTupleRoom(
  uint64_t budget, uint64_t held, uint64_t workItems, uint64_t children)
{
  const uint64_t later = workItems * kBytesPerWorkItem + children;
  const uint64_t now = held < budget ? (budget - held) / sizeof(Tuple) : 0;
  const uint64_t next = later < budget ? (budget - later) / kBytesPerTuple : 0;
  return now < next ? now : next;
}

/// What every per-element step of a frame reads, passed by value (device code gets a copy).
struct FrameConstants
{
  int width;
  int height;
  /// Rows [rowBegin, rowEnd) drawn in this pass: the whole image unless the frame's (pixel,
  /// node) pairs need several passes over bands of rows (rowBands).
  int rowBegin;
  int rowEnd;
  HitPolicy hits;
  int maxSubdivisionDepth;
  double tolerance[3];     ///< Newton's acceptance window (pixels, pixels, attribute)
  ClipPlanes<double> clip; ///< in homogeneous window coordinates
  const double* isovalues; ///< in the driver's memory (host or device)
};

/// The isovalue a node's pixel problem aims at; 0 for a surface's node (iso -1), whose problem
/// has no attribute row.
IGA_HD inline double isovalueOf(const Node& node, const FrameConstants& frame)
{
  return node.iso >= 0 ? frame.isovalues[node.iso] : 0.0;
}

/// The pixels of the frame's pass (its band of rows): [passFirstPixel, + passPixelCount).
/// Per-pixel arrays span the image; each pass reads and writes its own pixels only.
IGA_HD inline size_t passFirstPixel(const FrameConstants& frame)
{
  return size_t(frame.rowBegin) * size_t(frame.width);
}
IGA_HD inline size_t passPixelCount(const FrameConstants& frame)
{
  return size_t(frame.rowEnd - frame.rowBegin) * size_t(frame.width);
}

/// A root node: the whole input patch for one isovalue, or a surface for iso -1.
IGA_HD inline Node rootNode(int patch, int iso)
{
  Node node{};
  node.patch = patch;
  node.iso = iso;
  return node;
}

/// The directions along which a node has been halved `cap` times: not halved further.
IGA_HD inline int axesAtDepthCap(const Node& node, int cap)
{
  int axes = 0;
  for (int d = 0; d < 3; ++d)
  {
    axes |= node.depth[d] >= cap ? 1 << d : 0;
  }
  return axes;
}

/// Halves a node's place along `axes`, to that of its child `child` (splitNode's order).
IGA_HD inline void halvePlace(NodePlace& place, int axes, int child)
{
  for (int d = 0; d < 3; ++d)
  {
    if ((axes >> d) & 1)
    {
      ++place.depth[d];
      place.offset[d] = 2 * place.offset[d] + (upperHalf(axes, child, d) ? 1 : 0);
      place.level = place.depth[d] > place.level ? place.depth[d] : place.level;
    }
  }
}

/// Child `child` of a node's split along `axes` (splitNode), with the parent's analysis.
IGA_HD inline Node childOf(const Node& parent, int axes, int child)
{
  Node node = parent;
  halvePlace(node, axes, child);
  return node;
}

/// Pixel ranges [i0, i1] x [j0, j1] whose centres the box covers within columns [0, width) and
/// rows [rowBegin, rowEnd) (empty when i0 > i1 or j0 > j1).
IGA_HD inline void pixelRange(
  const Box3<double>& box, int width, int rowBegin, int rowEnd, int* range)
{
  const double i0 = ceil(box.lo[0] - 0.5 - 1e-6), i1 = floor(box.hi[0] - 0.5 + 1e-6);
  const double j0 = ceil(box.lo[1] - 0.5 - 1e-6), j1 = floor(box.hi[1] - 0.5 + 1e-6);
  range[0] = i0 > 0 ? int(i0) : 0;
  range[1] = i1 < width - 1 ? int(i1) : width - 1;
  range[2] = j0 > rowBegin ? int(j0) : rowBegin;
  range[3] = j1 < rowEnd - 1 ? int(j1) : rowEnd - 1;
}

/// The pixels of the frame's pass (its band of rows) whose centres the box covers: the pixel
/// range, a rectangle (boxCoversPixel's wider margin holds for all of it). How many, and the
/// k-th row by row, so that a GPU can give every (pixel, box) pair its own thread: a box over
/// a million pixels is not one thread's work.
IGA_HD inline uint32_t coveredPixelCount(const Box3<double>& box, const FrameConstants& frame)
{
  int range[4];
  pixelRange(box, frame.width, frame.rowBegin, frame.rowEnd, range);
  return range[0] <= range[1] && range[2] <= range[3]
           ? uint32_t(range[1] - range[0] + 1) * uint32_t(range[3] - range[2] + 1)
           : 0;
}
IGA_HD inline size_t coveredPixel(const Box3<double>& box, const FrameConstants& frame, uint32_t k)
{
  int range[4];
  pixelRange(box, frame.width, frame.rowBegin, frame.rowEnd, range);
  const uint32_t columns = uint32_t(range[1] - range[0] + 1);
  return size_t(range[2] + int(k / columns)) * frame.width + size_t(range[0] + int(k % columns));
}

/// Calls fn(pixel index) for every pixel of the frame's pass whose centre the box covers, row
/// by row.
template<class Fn>
IGA_HD void forEachCoveredPixel(const Box3<double>& box, const FrameConstants& frame, Fn&& fn)
{
  int range[4];
  pixelRange(box, frame.width, frame.rowBegin, frame.rowEnd, range);
  for (int j = range[2]; j <= range[3]; ++j)
  {
    for (int i = range[0]; i <= range[1]; ++i)
    {
      fn(size_t(j) * frame.width + i);
    }
  }
}

/// Counts a box's covered pixels of the whole image per row as differences over height + 1
/// entries, whose running sums are the rows' counts: add(row, value) adds modulo 2^64, the
/// covered columns at the box's first row and their negation past its last.
template<class Add>
IGA_HD void addRowPairs(const Box3<double>& box, const FrameConstants& frame, Add&& add)
{
  int range[4];
  pixelRange(box, frame.width, 0, frame.height, range);
  if (range[0] <= range[1] && range[2] <= range[3])
  {
    const uint64_t columns = uint64_t(range[1] - range[0] + 1);
    add(range[2], columns);
    add(range[3] + 1, ~columns + 1);
  }
}

/// The owner of item k when owner n's items start at starts[n] (an exclusive scan of counts,
/// n in [0, owners), starts[owners] the total): the last n with starts[n] <= k.
IGA_HD inline uint32_t ownerOf(const uint64_t* starts, size_t owners, size_t k)
{
  size_t lo = 0, hi = owners; // starts[lo] <= k < starts[hi]
  while (hi - lo > 1)
  {
    const size_t mid = (lo + hi) / 2;
    if (starts[mid] <= k)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
    }
  }
  return uint32_t(lo);
}

IGA_HD inline bool onScreen(const Box3<double>& box, int width, int height)
{
  return box.hi[0] >= 0 && box.lo[0] <= width && box.hi[1] >= 0 && box.lo[1] <= height;
}

/// Whether a node may hold visible surface: sign change, not behind the eye, depth and window
/// ranges meeting the view volume.
IGA_HD inline bool worthKeeping(const NodeInfo<double>& info, const FrameConstants& frame)
{
  return info.mayContainSurface && info.status != ProjectionStatus::BehindEye &&
         info.visibleDepth &&
         (info.status != ProjectionStatus::InFront ||
           onScreen(info.box, frame.width, frame.height));
}

/// An implicit node stands for all pixels of its box in the round; it gets explicit (pixel,
/// node) tuples once it is certified, small, or at a cap. Before, every pixel would fail on it
/// without a certificate, so the paper's loop would split it anyway.
IGA_HD inline bool readyForTuples(const Node& node, const FrameConstants& frame)
{
  const Box3<double>& box = node.info.box;
  return node.info.certified || (box.hi[0] - box.lo[0]) * (box.hi[1] - box.lo[1]) <= 256.0 ||
         node.level >= frame.maxSubdivisionDepth || node.overBudget;
}

/// Whether a node's box and slabs hold the pixel and the node may matter to it (the hit policy).
IGA_HD inline bool mayHitPixel(
  const Node& node, uint32_t pixel, double bestDepth, const FrameConstants& frame)
{
  return nodeCoversPixel(node.info, int(pixel % frame.width), int(pixel / frame.width)) &&
         frame.hits.mayMatter(node.info.box.lo[2], bestDepth);
}

/// The end of a pixel's next group of work items (initial nodes sorted by nearest depth) from
/// `cursor`: for a policy by depth groups the nearest item and all items overlapping it in
/// depth (none when it cannot matter), else all items up to `end`.
IGA_HD inline uint32_t groupEnd(const Node* initialNodes, const uint32_t* items, uint32_t cursor,
  uint32_t end, double bestDepth, const HitPolicy& policy)
{
  if (!policy.byDepthGroups())
  {
    return end;
  }
  if (cursor >= end || !policy.mayMatter(initialNodes[items[cursor]].info.box.lo[2], bestDepth))
  {
    return cursor;
  }
  double groupFar = initialNodes[items[cursor]].info.box.hi[2];
  uint32_t last = cursor + 1;
  while (last < end && initialNodes[items[last]].info.box.lo[2] <= groupFar)
  {
    const double far = initialNodes[items[last]].info.box.hi[2];
    groupFar = far > groupFar ? far : groupFar;
    ++last;
  }
  return last;
}

/// Whether initial node n is among a pixel's work items [begin, end) of the round.
IGA_HD inline bool inGroup(const uint32_t* items, uint32_t begin, uint32_t end, uint32_t n)
{
  for (uint32_t k = begin; k < end; ++k)
  {
    if (items[k] == n)
    {
      return true;
    }
  }
  return false;
}

/// How far outside its input patch's parameter cube a root may lie and still be the patch's:
/// Newton accepts roots up to its domain slack outside a node, which keeps roots on faces
/// shared by two nodes; beyond the input patch such a root belongs to the neighbouring patch
/// (found there) or to no patch at all (past an open surface's edge or a volume's outer face).
constexpr double kPatchParameterMargin = 1e-6;

/// A root's parameter in its input patch: node coordinates moved to the patch's cube.
IGA_HD inline double patchParameter(const Node& node, const double* u, int d)
{
  return (double(node.offset[d]) + u[d]) * inversePowerOfTwo(node.depth[d]);
}

/// Whether a root (node coordinates) lies in its input patch, within kPatchParameterMargin.
IGA_HD inline bool rootInPatch(const Node& node, const double* u)
{
  for (int d = 0; d < 3; ++d)
  {
    const double v = patchParameter(node, u, d);
    if (!(v >= -kPatchParameterMargin && v <= 1.0 + kPatchParameterMargin))
    {
      return false;
    }
  }
  return true;
}

/// A root in node coordinates, moved to the input patch's parameter cube. Not clamped: a root
/// up to kPatchParameterMargin outside lies on the pixel's ray, on the patch's polynomial
/// continuation, and merges with its twin found in the neighbouring patch.
IGA_HD inline RawHit rawHitOf(uint32_t pixel, const Node& node, const double* u, double ndcDepth)
{
  RawHit hit;
  hit.pixel = pixel;
  hit.patch = node.patch;
  hit.iso = node.iso;
  hit.ndcDepth = ndcDepth;
  for (int d = 0; d < 3; ++d)
  {
    hit.u[d] = patchParameter(node, u, d);
  }
  return hit;
}

/// solveTuple for a node of the loop, a hit outside the node's input patch a miss.
IGA_HD inline TupleOutcome solveNodeTuple(const VolumeView<const double>& view, const Node& node,
  int i, int j, const FrameConstants& frame, double* u, double& ndcDepth,
  NewtonWork* work = nullptr)
{
  const TupleOutcome outcome = solveTuple(
    view, node.info, i, j, isovalueOf(node, frame), frame.tolerance, u, ndcDepth, frame.clip, work);
  return outcome == TupleOutcome::Hit && !rootInPatch(node, u) ? TupleOutcome::Miss : outcome;
}

/// How a tuple leaves the solution stage: solved (a hit), failed (its node must be split for
/// it) or dropped (provably no visible root, or behind the pixel's best hit).
enum TupleState : uint8_t
{
  Solved,
  Failed,
  Dropped
};

/// The solution stage for one pixel: its tuples [first, last), sorted nearest first, each solved
/// unless it cannot matter next to the best hit so far (the hit policy). Writes every tuple's state
/// and, for a hit, its root (u, NDC depth) at solution[4 t]; returns the pixel's best depth.
/// `certified` counts the tuples tried on certified nodes, `newton` the Newton solves.
/// `viewOf(node)` gives a node's screen patch.
template<class ViewOf>
IGA_HD double solvePixelTuples(const Tuple* tuples, uint32_t first, uint32_t last, uint32_t pixel,
  const Node* nodes, const ViewOf& viewOf, double best, const FrameConstants& frame, uint8_t* state,
  double* solution, uint32_t& certified, NewtonWork& newton)
{
  const int i = int(pixel % frame.width), j = int(pixel / frame.width);
  for (uint32_t t = first; t < last; ++t)
  {
    const Node& node = nodes[tuples[t].node];
    state[t] = Failed;
    if (!frame.hits.mayMatter(node.info.box.lo[2], best))
    {
      state[t] = Dropped;
      continue;
    }
    certified += node.info.certified ? 1 : 0;
    switch (solveNodeTuple(
      viewOf(node), node, i, j, frame, &solution[4 * t], solution[4 * t + 3], &newton))
    {
      case TupleOutcome::Hit:
        state[t] = frame.hits.keeps(solution[4 * t + 3], best) ? Solved : Dropped;
        best = state[t] == Solved ? frame.hits.afterHit(best, solution[4 * t + 3]) : best;
        break;
      case TupleOutcome::Miss:
        state[t] = Dropped;
        break;
      case TupleOutcome::Undecided:
        break;
    }
  }
  return best;
}

/// Whether a pixel its box covers takes a tuple of an implicit node this round: the node may
/// matter to it, its initial node is among the pixel's work items [begin, end) and its slabs
/// hold the pixel.
IGA_HD inline bool roundTakesPixel(const Node& node, size_t pixel, double bestDepth,
  const uint32_t* items, uint32_t begin, uint32_t end, const FrameConstants& frame)
{
  return frame.hits.mayMatter(node.info.box.lo[2], bestDepth) &&
         inGroup(items, begin, end, node.initial) &&
         slabsCoverPixel(node.info.slabs, int(pixel % frame.width), int(pixel / frame.width));
}

// ---- shading ---------------------------------------------------------------------------------

/// Channels of a shading patch: the world patch reduced to what a hit needs.
constexpr int kShadeX = 0; ///< x, y, z homogeneous, then the weight
constexpr int kShadeWeight = 3;
constexpr int kShadeSurface = 4;
constexpr int kShadeColor = 5;
constexpr int kShadeChannels = 6;

/// Copies position, weight, surface and colour attribute (the surface again without a colour
/// attribute) of a world patch into pointCount * kShadeChannels values.
IGA_HD inline void makeShadingPatch(
  const VolumeView<const double>& world, int surfaceChannel, int colorChannel, double* out)
{
  for (int p = 0; p < world.pointCount(); ++p)
  {
    const double* cp = world.point(p);
    double* s = out + p * kShadeChannels;
    for (int c = 0; c < 3; ++c)
    {
      s[kShadeX + c] = cp[c];
    }
    s[kShadeWeight] = cp[kWeightChannel];
    s[kShadeSurface] = cp[surfaceChannel];
    s[kShadeColor] = cp[colorChannel >= 0 ? colorChannel : surfaceChannel];
  }
}

/// The viewer as shading sees it.
struct ShadingView
{
  glm::dvec3 eye;
  glm::dvec3 forward;
  bool parallel;
  bool hasColor;
};

/// The viewer of a frame as shading sees it.
inline ShadingView shadingViewOf(const View& view, const Settings& settings)
{
  ShadingView viewer{};
  viewer.eye = view.eye;
  viewer.forward = view.forward;
  viewer.parallel = view.parallel;
  viewer.hasColor = settings.colorAttribute >= 0;
  return viewer;
}

/// A hit's normal (facing the viewer), whether it enters the region below the isovalue and its
/// eye depth, from its world position, J (J[d] the gradient of world coordinate d in the
/// parameter) and, for a volume, the attribute's gradient in the parameter.
IGA_HD inline void orientHit(
  Hit& hit, glm::dvec3 (&J)[3], glm::dvec3 gradient, bool surface, const ShadingView& viewer)
{
  // Only the normal's direction and the determinant's sign matter: powers of two bring J and
  // the gradient near 1, exactly, so that their products neither overflow nor underflow.
  auto largest = [](const glm::dvec3& v)
  { return maxValue(maxValue(absValue(v.x), absValue(v.y)), absValue(v.z)); };
  const double unitJ =
    unitPowerOfTwo(maxValue(maxValue(largest(J[0]), largest(J[1])), largest(J[2])));
  for (glm::dvec3& row : J)
  {
    row *= unitJ;
  }
  if (!surface)
  {
    gradient *= unitPowerOfTwo(largest(gradient));
  }
  // A volume's isosurface: the attribute's world gradient J^-T grad_u = cof(J) grad_u / det(J),
  // the rows of cof(J) cross products of J's. The cofactor form stays defined where J is
  // singular (collapsed faces); the orientation is fixed below. A surface: x_u x x_v.
  const glm::dvec3 cofactors[3] = { glm::cross(J[1], J[2]), glm::cross(J[2], J[0]),
    glm::cross(J[0], J[1]) };
  const double determinant = glm::dot(J[0], cofactors[0]);
  const glm::dvec3 toEye = viewer.parallel ? -viewer.forward : viewer.eye - hit.position;
  glm::dvec3 normal = normalizedOrZero(
    surface
      ? glm::cross(glm::dvec3(J[0][0], J[1][0], J[2][0]), glm::dvec3(J[0][1], J[1][1], J[2][1]))
      : glm::dvec3(glm::dot(cofactors[0], gradient), glm::dot(cofactors[1], gradient),
          glm::dot(cofactors[2], gradient)));
  if (glm::dot(normal, normal) == 0 || !isFinite(normal[0]))
  {
    normal = normalizedOrZero(toEye);
  }
  const double sign = glm::dot(normal, toEye) < 0 ? -1.0 : 1.0;
  // The attribute falls along the ray where its world gradient points back to the eye. Where J
  // is singular its orientation is unknown and taken as positive. A surface is entered on the
  // side its normal x_u x x_v points away from: where that normal faces the eye.
  hit.entersBelow = (determinant < 0 && !surface ? -sign : sign) > 0;
  hit.normal = sign * normal;
  hit.eyeDepth = glm::dot(hit.position - viewer.eye, viewer.forward);
}

/// The hit of a raw root, its fields but the geometry's.
IGA_HD inline Hit hitOf(const RawHit& raw)
{
  Hit hit;
  hit.ndcDepth = raw.ndcDepth;
  hit.patch = raw.patch;
  hit.isovalue = raw.iso;
  for (int d = 0; d < 3; ++d)
  {
    hit.uvw[d] = raw.u[d];
  }
  return hit;
}

/// World position, normal (facing the viewer), depth and colour value of a root, evaluated on
/// its shading patch in double precision.
IGA_HD inline Hit shadeHit(
  const VolumeView<const double>& shading, const RawHit& raw, const ShadingView& viewer)
{
  // A surface reads no surface attribute, and its colour only when coloured by one.
  const bool surface = isSurface(shading);
  const int leading = surface && !viewer.hasColor ? kShadeSurface : kShadeChannels;
  double values[kShadeChannels], derivatives[3 * kShadeChannels] = {};
  surface ? evaluateHomogeneous<double, 2>(surfaceOf(shading), raw.u, values, derivatives, leading)
          : evaluateHomogeneous<double, 3>(shading, raw.u, values, derivatives, leading);
  Hit hit = hitOf(raw);
  glm::dvec3 J[3], gradient(0.0); // J[d]: the gradient of world coordinate d
  for (int d = 0; d < 3; ++d)
  {
    hit.position[d] = rationalValue<double, 3>(
      values, derivatives, kShadeChannels, kShadeX + d, kShadeWeight, &J[d][0]);
  }
  if (!surface)
  {
    rationalValue<double, 3>(
      values, derivatives, kShadeChannels, kShadeSurface, kShadeWeight, &gradient[0]);
  }
  orientHit(hit, J, gradient, surface, viewer);
  hit.color = viewer.hasColor ? values[kShadeColor] / values[kShadeWeight] : nan("");
  return hit;
}

/// An affine patch's power form for shading (ray composition's patches that have one): its
/// world map origin + axes u and its terms [first, first + count) of the frame's pool; count 0
/// for the others.
struct PowerShading
{
  glm::dvec3 origin;
  glm::dmat3 axes;
  uint32_t first = 0, count = 0;
};

/// shadeHit for a patch with a power form and no colour attribute: the affine map and the
/// form's gradient, without evaluating the patch.
IGA_HD inline Hit shadePowerHit(
  const PowerShading& power, const PowerTerm* terms, const RawHit& raw, const ShadingView& viewer)
{
  Hit hit = hitOf(raw);
  const glm::dvec3 u(raw.u[0], raw.u[1], raw.u[2]);
  hit.position = power.origin + power.axes * u;
  glm::dvec3 J[3];
  for (int d = 0; d < 3; ++d)
  {
    J[d] = glm::dvec3(power.axes[0][d], power.axes[1][d], power.axes[2][d]);
  }
  // d/du = 2 d/ds, a positive factor the normal's direction does not see.
  orientHit(
    hit, J, powerGradient(terms + power.first, int(power.count), 2.0 * u - 1.0), false, viewer);
  hit.color = nan("");
  return hit;
}

} // namespace sst
} // namespace iga
