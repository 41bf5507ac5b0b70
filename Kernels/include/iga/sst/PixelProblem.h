// The SST pixel problem, shared by every driver (CPU SST, basic scheme, brute force, CUDA).
//
// A world-space patch (standard layout) is mapped to "screen patches" with the channels below:
// X, Y, Z, W are the homogeneous window coordinates (pixel units in x and y, NDC depth in z) of
// the control points, A and V the homogeneous surface attribute and its weight. A pixel (i, j)
// with centre (i + 0.5, j + 0.5) then asks for u with X/W = i + 0.5, Y/W = j + 0.5, A/V = iso,
// the paper's s(u) - o_st = 0 with the pixel offset o_st applied to a patch shared by all pixels.
#pragma once

#include "iga/Jet.h"
#include "iga/Newton.h"

#include <glm/gtc/matrix_access.hpp>

namespace iga
{
namespace sst
{

constexpr int kScreenX = 0;
constexpr int kScreenY = 1;
constexpr int kScreenZ = 2;
constexpr int kScreenW = 3;
constexpr int kScreenAttribute = 4;
constexpr int kScreenWeight = 5;
constexpr int kScreenChannels = 6;

/// Rows of the pixel problem in the screen layout (by value: no static data in device code).
struct PixelRows
{
  RationalRow rows[3];
};
IGA_HD inline PixelRows pixelRows()
{
  return { { { kScreenX, kScreenW }, { kScreenY, kScreenW },
    { kScreenAttribute, kScreenWeight } } };
}

/// Writes the screen patch of a world patch: `windowFromWorld` maps homogeneous world points to
/// homogeneous window coordinates; `attributeChannel` is the world channel of the surface
/// attribute. `out` holds pointCount * kScreenChannels values.
template<class T>
IGA_HD void makeScreenPatch(const VolumeView<const double>& world,
  const glm::dmat4& windowFromWorld, int attributeChannel, T* out)
{
  // The homogeneous window coordinates scale with the distance to the eye; a power of two
  // brings the largest |W| near 1, exactly, so that the solver's products of them neither
  // overflow nor underflow whatever the data's scale (the quotients X/W, Y/W, Z/W are unchanged).
  const int count = world.pointCount();
  double largestW = 0;
  for (int p = 0; p < count; ++p)
  {
    largestW = maxValue(
      largestW, absValue(glm::dot(glm::row(windowFromWorld, 3), glm::make_vec4(world.point(p)))));
  }
  const double normalise = unitPowerOfTwo(largestW);
  for (int p = 0; p < count; ++p)
  {
    const double* cp = world.point(p);
    const glm::dvec4 window = normalise * (windowFromWorld * glm::make_vec4(cp));
    T* s = out + p * kScreenChannels;
    for (int c = 0; c < 4; ++c)
    {
      s[c] = T(window[c]);
    }
    s[kScreenAttribute] = T(cp[attributeChannel]);
    s[kScreenWeight] = T(cp[kWeightChannel]);
  }
}

/// Clipping planes in homogeneous window coordinates: a point is kept where q . (X, Y, Z, W) >= 0
/// for every plane. World planes map here exactly (see clipPlaneToWindow); since world weights
/// are positive, the sign of q . (X, Y, Z, W) is the sign of the world plane's value.
constexpr int kMaxClipPlanes = 6;
template<class T>
struct ClipPlanes
{
  int count = 0;
  T plane[kMaxClipPlanes][4];
};

template<class T>
IGA_HD T clipValue(const T* plane, const T* screen)
{
  return plane[0] * screen[kScreenX] + plane[1] * screen[kScreenY] + plane[2] * screen[kScreenZ] +
         plane[3] * screen[kScreenW];
}

/// Whether homogeneous screen values (one evaluated point) lie on the kept side of every plane.
template<class T>
IGA_HD bool clipKeeps(const ClipPlanes<T>& clip, const T* screen)
{
  for (int k = 0; k < clip.count; ++k)
  {
    if (clipValue(clip.plane[k], screen) < T(0))
    {
      return false;
    }
  }
  return true;
}

/// Whether one plane cuts the whole node away: the plane's value is a polynomial whose Bernstein
/// coefficients are its values at the control points, so all negative means negative everywhere.
template<class T>
IGA_HD bool clippedAway(const VolumeView<const T>& node, const ClipPlanes<T>& clip)
{
  for (int k = 0; k < clip.count; ++k)
  {
    bool allCut = true;
    for (int p = 0; p < node.pointCount() && allCut; ++p)
    {
      allCut = clipValue(clip.plane[k], node.point(p)) < T(0);
    }
    if (allCut)
    {
      return true;
    }
  }
  return false;
}

/// Unknowns of a node's pixel problem: (u, v, w) with X/W, Y/W and A/V on target for a
/// volume's isosurface, (u, v) with X/W and Y/W on target for a surface (stored by flatVolume).
template<class T>
IGA_HD int unknownsOf(const VolumeView<const T>& node)
{
  return isSurface(node) ? 2 : 3;
}

/// A node's coefficients as a patch of Dim parameters.
template<int Dim, class T>
IGA_HD PatchView<const T, Dim> patchOf(const VolumeView<const T>& node)
{
  if constexpr (Dim == 2)
  {
    return surfaceOf(node);
  }
  else
  {
    return node;
  }
}

/// Two slabs that hold a node's projected control points, across its projected u and v edges
/// (normals of unit 1-norm, zero where an edge is degenerate or the projection is not valid).
/// With the window box they bound a node lying askew on screen much more tightly: a piece at 45
/// degrees fills half its box.
template<class T>
struct PixelSlabs
{
  float normal[2][2]; ///< single precision: the test uses the same normals as the range
  T lo[2], hi[2];
};

/// The node's slabs (PixelSlabs), from its control points after the perspective division.
template<class T>
IGA_HD PixelSlabs<T> projectedSlabs(const VolumeView<const T>& node, bool inFront)
{
  PixelSlabs<T> slabs;
  const T* origin = node.point(0);
  const int edgeEnds[2] = { node.degree[0], node.degree[1] * (node.degree[0] + 1) };
  for (int d = 0; d < 2; ++d)
  {
    const T* end = node.point(edgeEnds[d]);
    const T ex = end[kScreenX] / end[kScreenW] - origin[kScreenX] / origin[kScreenW];
    const T ey = end[kScreenY] / end[kScreenW] - origin[kScreenY] / origin[kScreenW];
    const T length = absValue(ex) + absValue(ey);
    const bool usable = inFront && length > T(0) && isFinite(length);
    slabs.normal[d][0] = usable ? float(-ey / length) : 0.0f;
    slabs.normal[d][1] = usable ? float(ex / length) : 0.0f;
    slabs.lo[d] = slabs.hi[d] = T(0);
  }
  for (int p = 0; p < node.pointCount(); ++p)
  {
    const T* cp = node.point(p);
    const T x = cp[kScreenX] / cp[kScreenW], y = cp[kScreenY] / cp[kScreenW];
    for (int d = 0; d < 2; ++d)
    {
      const T h = T(slabs.normal[d][0]) * x + T(slabs.normal[d][1]) * y;
      slabs.lo[d] = p == 0 ? h : minValue(slabs.lo[d], h);
      slabs.hi[d] = p == 0 ? h : maxValue(slabs.hi[d], h);
    }
  }
  return slabs;
}

/// What a node of a subdivision tree knows about itself for the pixel problem. A surface's
/// problem has two unknowns: it uses the leading 2x2 blocks of the matrices and the first two
/// entries of the centre.
template<class T>
struct NodeInfo
{
  Box3<T> box;             ///< window x, y (pixels) and NDC depth, valid when status is InFront
  PixelSlabs<T> slabs;     ///< a tighter window bound, with the box (nodeCoversPixel)
  ProjectionStatus status; ///< where the node lies relative to the eye plane
  bool mayContainSurface;  ///< a surface, or the attribute's Bernstein range holds the isovalue
  /// The attribute is constant (within rounding) and equal to the isovalue: its level set is a
  /// region, no surface, which no subdivision would settle; mayContainSurface is false.
  bool constantAttribute;
  bool visibleDepth;               ///< not entirely in front of the near or beyond the far plane,
                                   ///< nor cut away by a clipping plane
  bool certified;                  ///< at most one root for every pixel (certifyUniqueRoot)
  bool canExclude;                 ///< the Krawczyk data below is valid
  glm::mat<3, 3, T> inverse;       ///< mid([J])^-1 of the pixel problem's Jacobian hull
  glm::mat<3, 3, T> spread;        ///< |mid([J])^-1| rad([J])
  bool hasCentre;                  ///< the centre data below is valid
  T centre[3];                     ///< F at the parametric centre: (X/W, Y/W, A/V), no pixel offset
  glm::mat<3, 3, T> centreInverse; ///< J(centre)^-1
  T centreWeights[2];              ///< W and V at the centre
  /// Row r's Hessian at the centre, packed (uu, vv, ww, uv, uw, vw): Newton's start takes the
  /// quadratic model, as certified nodes span many pixels.
  T centreHessians[3][6];
};

/// What a volume's attribute range says of its isosurface at `isovalue`: `known` false (no
/// range) or the range holding the isovalue may contain surface, unless the attribute is constant
/// there (within rounding), a region that no subdivision would settle. A node's analysis and the
/// frame's test of whole patches before they are projected (FramePlan) take the same verdict.
template<class T>
IGA_HD void attributeVerdict(
  bool known, T lo, T hi, T isovalue, bool& constantAttribute, bool& mayContainSurface)
{
  const bool containsIsovalue = lo <= isovalue && isovalue <= hi;
  constantAttribute = known && containsIsovalue &&
                      hi - lo <= T(16) * Epsilon<T>::value * maxValue(absValue(lo), absValue(hi));
  mayContainSurface = !known || (containsIsovalue && !constantAttribute);
}

/// The cheap part of a node's analysis: window box, eye-plane status, sign change (volumes),
/// clip depth and clipping planes.
template<class T>
IGA_HD void analyzeNodeBounds(
  const VolumeView<const T>& node, T isovalue, const ClipPlanes<T>& clip, NodeInfo<T>& info)
{
  info.status = projectedBounds(node, info.box);
  info.slabs = projectedSlabs(node, info.status == ProjectionStatus::InFront);
  T lo = T(0), hi = T(0);
  const bool known =
    !isSurface(node) && rationalRange(node, kScreenAttribute, kScreenWeight, lo, hi);
  attributeVerdict(known, lo, hi, isovalue, info.constantAttribute, info.mayContainSurface);
  // Z + W < 0 in front of the near plane, Z - W > 0 beyond the far one; both are linear in the
  // homogeneous coefficients, so all coefficients on one side put the whole node there (parts
  // behind the eye are invisible anyway). Valid whatever the signs of W.
  bool nearSide = true, farSide = true;
  for (int p = 0; p < node.pointCount(); ++p)
  {
    const T* cp = node.point(p);
    nearSide = nearSide && cp[kScreenZ] + cp[kScreenW] < T(0);
    farSide = farSide && cp[kScreenZ] - cp[kScreenW] > T(0);
  }
  info.visibleDepth = !nearSide && !farSide && !clippedAway(node, clip);
  info.certified = false;
  info.canExclude = false;
  info.hasCentre = false;
}

enum class TupleOutcome
{
  Hit,       ///< a root, within the clip range and on the kept side of the clipping planes
  Miss,      ///< provably no visible root of this pixel in this node
  Undecided, ///< no certificate or Newton failed: the node must be split for this pixel
};

/// Newton's work on tuples: the solves run and the evaluations of F and J they took.
struct NewtonWork
{
  uint32_t runs = 0;
  uint32_t evaluations = 0;
};

/// The residual G(u) = (X - x W, Y - y W, A - iso V) at a control point; a surface's problem
/// takes its first two entries.
template<class T>
IGA_HD void pixelResidual(const T* cp, T x, T y, T isovalue, T* g)
{
  g[0] = cp[kScreenX] - x * cp[kScreenW];
  g[1] = cp[kScreenY] - y * cp[kScreenW];
  g[2] = cp[kScreenAttribute] - isovalue * cp[kScreenWeight];
}

/// True when the pixel's ray provably misses the surface inside the node: the residual
/// G(u) = (X - x W, Y - y W[, A - iso V]) is a polynomial whose Bernstein coefficients G_i span
/// a convex hull that holds every value of G, so a direction n with n . G_i > 0 for all i
/// excludes a root. Here n is the coefficients' mean, in 3D (volumes) and in the window plane:
/// the directions at hand for a node without centre data. This drops (pixel, node) pairs whose
/// box covers the pixel although the surface piece inside does not, which would otherwise fail
/// Newton and force subdivision.
template<class T>
IGA_HD bool excludesPixel(const VolumeView<const T>& node, int i, int j, T isovalue)
{
  const T x = T(i) + T(0.5), y = T(j) + T(0.5);
  const int count = node.pointCount();
  T mean[3] = { T(0), T(0), T(0) };
  for (int p = 0; p < count; ++p)
  {
    T g[3];
    pixelResidual(node.point(p), x, y, isovalue, g);
    for (int c = 0; c < 3; ++c)
    {
      mean[c] += g[c];
    }
  }
  bool separated3 = !isSurface(node), separated2 = true;
  for (int p = 0; p < count && (separated3 || separated2); ++p)
  {
    T g[3];
    pixelResidual(node.point(p), x, y, isovalue, g);
    const T planar = mean[0] * g[0] + mean[1] * g[1];
    separated2 = separated2 && planar > T(0);
    separated3 = separated3 && planar + mean[2] * g[2] > T(0);
  }
  return separated3 || separated2;
}

namespace detail
{

template<class T, int Dim>
IGA_HD void analyzeNodeSolver(const VolumeView<const T>& node, NodeInfo<T>& info)
{
  Interval<T> scaled[Dim][Dim], jacobian[Dim][Dim];
  if (!rationalJacobianHull(patchOf<Dim>(node), pixelRows().rows, scaled, jacobian))
  {
    return;
  }
  info.certified = certifyUniqueRoot<T, Dim>(scaled);
  glm::mat<Dim, Dim, T> inverse(T(0)), spread(T(0)); // kept only where canExclude
  info.canExclude = preconditioner<T, Dim>(jacobian, inverse, spread);
  info.inverse = glm::mat<3, 3, T>(inverse);
  info.spread = glm::mat<3, 3, T>(spread);
}

/// Newton's start for the pixel whose residual at the centre is `residual`: the root of the
/// node's quadratic model around its centre, by two fixed-point steps from the linear one. Where
/// the model's correction is not small beside the linear step, the model does not hold that far
/// (a node too large or near a singular point) and the linear start is kept.
template<class T, int Dim>
IGA_HD glm::vec<Dim, T> quadraticStart(const NodeInfo<T>& info, const glm::vec<Dim, T>& residual)
{
  const glm::mat<Dim, Dim, T> inverse(info.centreInverse);
  const glm::vec<Dim, T> linear = -(inverse * residual);
  glm::vec<Dim, T> step = linear;
  for (int k = 0; k < 2; ++k)
  {
    glm::vec<Dim, T> curvature;
    for (int r = 0; r < Dim; ++r)
    {
      const T* h = info.centreHessians[r]; // entry (a, b) at a if a == b, else at 2 + a + b
      T q = T(0);
      for (int a = 0; a < Dim; ++a)
      {
        q += h[a] * step[a] * step[a];
        for (int b = a + 1; b < Dim; ++b)
        {
          q += T(2) * h[2 + a + b] * step[a] * step[b];
        }
      }
      curvature[r] = T(0.5) * q;
    }
    step = linear - inverse * curvature;
  }
  T correction = T(0), size = T(0);
  for (int d = 0; d < Dim; ++d)
  {
    correction = maxValue(correction, absValue(step[d] - linear[d]));
    size = maxValue(size, absValue(linear[d]));
  }
  return glm::vec<Dim, T>(T(0.5)) + (correction <= T(0.5) * size ? step : linear);
}

template<class T, int Dim>
IGA_HD void analyzeNodeCentre(const VolumeView<const T>& node, NodeInfo<T>& info)
{
  const T centre[3] = { T(0.5), T(0.5), T(0.5) };
  // The rows' channels (pixelRows): X, Y and W, then A and V for a volume.
  const int channels[5] = { kScreenX, kScreenY, kScreenW, kScreenAttribute, kScreenWeight };
  constexpr int count = Dim == 3 ? 5 : 3;
  Jet<T> jets[5];
  channelJets<T, Dim>(patchOf<Dim>(node), centre, channels, count, jets);
  const Jet<T> rows[3] = { rationalJet(jets[0], jets[2]), rationalJet(jets[1], jets[2]),
    Dim == 3 ? rationalJet(jets[3], jets[4]) : Jet<T>() };
  glm::mat<Dim, Dim, T> gradients; // column r: the gradient of row r (J transposed)
  info.centre[2] = T(0);
  for (int r = 0; r < 3; ++r)
  {
    info.centre[r] = rows[r].value;
    for (int d = 0; d < Dim && r < Dim; ++d)
    {
      gradients[r][d] = rows[r].gradient[d];
    }
    const glm::mat<3, 3, T>& h = rows[r].hessian;
    const T packed[6] = { h[0][0], h[1][1], h[2][2], h[0][1], h[0][2], h[1][2] };
    for (int k = 0; k < 6; ++k)
    {
      info.centreHessians[r][k] = packed[k];
    }
  }
  info.centreWeights[0] = jets[2].value;
  info.centreWeights[1] = Dim == 3 ? jets[4].value : T(0); // a surface has no A/V row
  glm::mat<Dim, Dim, T> inverse(T(0));                     // kept only where hasCentre
  info.hasCentre = invertMatrix<T, Dim>(glm::transpose(gradients), inverse);
  info.centreInverse = glm::mat<3, 3, T>(inverse);
}

template<class T, int Dim>
IGA_HD bool excludesPixelAlongRows(
  const VolumeView<const T>& node, const NodeInfo<T>& info, int i, int j, T isovalue, int rows)
{
  const T x = T(i) + T(0.5), y = T(j) + T(0.5);
  const T weights[3] = { info.centreWeights[0], info.centreWeights[0], info.centreWeights[1] };
  T n[Dim][Dim];
  bool positive[Dim], negative[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    for (int c = 0; c < Dim; ++c)
    {
      n[d][c] = info.centreInverse[c][d] / weights[c];
    }
    positive[d] = negative[d] = (rows >> d & 1) != 0;
  }
  const int count = node.pointCount();
  for (int p = 0; p < count; ++p)
  {
    T g[3];
    pixelResidual(node.point(p), x, y, isovalue, g);
    bool open = false;
    for (int d = 0; d < Dim; ++d)
    {
      T h = T(0);
      for (int c = 0; c < Dim; ++c)
      {
        h += n[d][c] * g[c];
      }
      positive[d] = positive[d] && h > T(0);
      negative[d] = negative[d] && h < T(0);
      open = open || positive[d] || negative[d];
    }
    if (!open)
    {
      return false;
    }
  }
  return true;
}

template<class T, int Dim>
IGA_HD TupleOutcome solvePixel(const VolumeView<const T>& node, int i, int j, T isovalue,
  const T* tolerance, const T* start, T* u, T& ndcDepth, const ClipPlanes<T>& clip,
  NewtonWork* work)
{
  const T target[3] = { T(i) + T(0.5), T(j) + T(0.5), isovalue };
  T values[kScreenChannels];
  const NewtonResult<T, Dim> result =
    solveNewton<T, Dim>(patchOf<Dim>(node), pixelRows().rows, target, tolerance, start, {}, values);
  if (work)
  {
    ++work->runs;
    work->evaluations += uint32_t(result.iterations + 1);
  }
  if (result.status != NewtonStatus::Converged || !(values[kScreenW] > T(0)))
  {
    return TupleOutcome::Undecided;
  }
  ndcDepth = values[kScreenZ] / values[kScreenW];
  u[2] = T(0);
  for (int d = 0; d < Dim; ++d)
  {
    u[d] = result.u[d];
  }
  return ndcDepth >= T(-1) && ndcDepth <= T(1) && clipKeeps(clip, values) ? TupleOutcome::Hit
                                                                          : TupleOutcome::Miss;
}

template<class T, int Dim>
IGA_HD TupleOutcome solveTuple(const VolumeView<const T>& node, const NodeInfo<T>& info, int i,
  int j, T isovalue, const T* tolerance, T* u, T& ndcDepth, const ClipPlanes<T>& clip,
  NewtonWork* work)
{
  // A large uncertified node is split whatever its pixels' exclusions say, and its children's
  // boxes shed most of those pixels anyway: skip the tests there. Small ones keep them, as
  // silhouette nodes are rarely certified.
  if (!info.certified &&
      (info.box.hi[0] - info.box.lo[0]) * (info.box.hi[1] - info.box.lo[1]) > T(256))
  {
    return TupleOutcome::Undecided;
  }
  // O(1) per tuple first: the node's centre data minus the pixel's offset.
  const T target[3] = { T(i) + T(0.5), T(j) + T(0.5), isovalue };
  glm::vec<Dim, T> residual;
  for (int r = 0; r < Dim; ++r)
  {
    residual[r] = info.centre[r] - target[r];
  }
  const T slack = NewtonSettings<T>().domainSlack;
  if (info.canExclude && info.hasCentre &&
      krawczykExcludes<T, Dim>(
        glm::mat<Dim, Dim, T>(info.inverse), glm::mat<Dim, Dim, T>(info.spread), residual, slack))
  {
    return TupleOutcome::Miss;
  }
  if (!info.hasCentre)
  {
    return excludesPixel(node, i, j, isovalue) ? TupleOutcome::Miss : TupleOutcome::Undecided;
  }
  if (!info.certified)
  {
    return excludesPixelAlongRows<T, Dim>(node, info, i, j, isovalue, (1 << Dim) - 1)
             ? TupleOutcome::Miss
             : TupleOutcome::Undecided;
  }
  // Newton's start from the node's quadratic model, then the iteration proper. A start that
  // leaves the node says along which rows the pixel most likely misses it: a proof there saves
  // the split.
  const glm::vec<Dim, T> start = quadraticStart<T, Dim>(info, residual);
  int outside = 0;
  for (int d = 0; d < Dim; ++d)
  {
    outside |= withinDomain(start[d], slack) ? 0 : 1 << d;
  }
  if (outside)
  {
    return excludesPixelAlongRows<T, Dim>(node, info, i, j, isovalue, outside)
             ? TupleOutcome::Miss
             : TupleOutcome::Undecided;
  }
  return solvePixel<T, Dim>(
    node, i, j, isovalue, tolerance, glm::value_ptr(start), u, ndcDepth, clip, work);
}

} // namespace detail

/// The solver part: the Jacobian hull of the pixel problem, the unique-root certificate and the
/// Krawczyk preconditioner, shared by every pixel of the node.
template<class T>
IGA_HD void analyzeNodeSolver(const VolumeView<const T>& node, NodeInfo<T>& info)
{
  if (info.status != ProjectionStatus::InFront || !info.mayContainSurface)
  {
    return;
  }
  isSurface(node) ? detail::analyzeNodeSolver<T, 2>(node, info)
                  : detail::analyzeNodeSolver<T, 3>(node, info);
}

/// F, J and the rows' Hessians at the node's centre, which do not depend on the pixel: one
/// evaluation serves every tuple's Krawczyk test and Newton start. Needed once the node has
/// tuples.
template<class T>
IGA_HD void analyzeNodeCentre(const VolumeView<const T>& node, NodeInfo<T>& info)
{
  if (info.status != ProjectionStatus::InFront)
  {
    return;
  }
  isSurface(node) ? detail::analyzeNodeCentre<T, 2>(node, info)
                  : detail::analyzeNodeCentre<T, 3>(node, info);
}

template<class T>
IGA_HD NodeInfo<T> analyzeNode(
  const VolumeView<const T>& node, T isovalue, const ClipPlanes<T>& clip = ClipPlanes<T>())
{
  NodeInfo<T> info;
  analyzeNodeBounds(node, isovalue, clip, info);
  analyzeNodeSolver(node, info);
  analyzeNodeCentre(node, info);
  return info;
}

/// The pixel centre lies in the node's window box (widened by a rounding margin).
template<class T>
IGA_HD bool boxCoversPixel(const Box3<T>& box, int i, int j)
{
  const T x = T(i) + T(0.5), y = T(j) + T(0.5);
  const T margin = T(1e-6) + T(8) * Epsilon<T>::value * (absValue(x) + absValue(y));
  return box.lo[0] - margin <= x && x <= box.hi[0] + margin && box.lo[1] - margin <= y &&
         y <= box.hi[1] + margin;
}

/// The window point (x, y) lies in the slabs (widened by a rounding margin).
template<class T>
IGA_HD bool slabsHold(const PixelSlabs<T>& slabs, T x, T y)
{
  const T margin = T(1e-6) + T(16) * Epsilon<T>::value * (absValue(x) + absValue(y));
  for (int d = 0; d < 2; ++d)
  {
    const T h = T(slabs.normal[d][0]) * x + T(slabs.normal[d][1]) * y;
    if (h < slabs.lo[d] - margin || h > slabs.hi[d] + margin)
    {
      return false;
    }
  }
  return true;
}

/// The centre of pixel (i, j) lies in the slabs.
template<class T>
IGA_HD bool slabsCoverPixel(const PixelSlabs<T>& slabs, int i, int j)
{
  return slabsHold(slabs, T(i) + T(0.5), T(j) + T(0.5));
}

/// The pixel centre lies in the node's window box and slabs: else the node's piece of the patch
/// cannot hold the pixel's root.
template<class T>
IGA_HD bool nodeCoversPixel(const NodeInfo<T>& info, int i, int j)
{
  return boxCoversPixel(info.box, i, j) && slabsCoverPixel(info.slabs, i, j);
}

/// The same proof along better directions, for a node with centre data: the rows of
/// J(centre)^-1, rescaled from the rational F to the homogeneous residual G (dG ~ diag(W, W, V)
/// dF near a root). Along row d, n . G is about (u_d - root_d) times a positive factor, so when
/// the ray's root lies outside the node in direction d, n . G_i keeps one sign over all the
/// coefficients of a nearly linear node. `rows` is a bit mask of the rows to try.
template<class T>
IGA_HD bool excludesPixelAlongRows(
  const VolumeView<const T>& node, const NodeInfo<T>& info, int i, int j, T isovalue, int rows)
{
  return isSurface(node) ? detail::excludesPixelAlongRows<T, 2>(node, info, i, j, isovalue, rows)
                         : detail::excludesPixelAlongRows<T, 3>(node, info, i, j, isovalue, rows);
}

/// Newton on one (pixel, node) tuple from `start` (unknownsOf(node) values). On a hit `u` holds
/// the root (its third entry 0 for a surface) and `ndcDepth` its NDC depth. A converged root
/// outside the clip range or cut by a clipping plane is a Miss, which is final where the node
/// certifies a unique root. `isovalue` is ignored for a surface. `work`, when given, counts the
/// solve.
template<class T>
IGA_HD TupleOutcome solvePixel(const VolumeView<const T>& node, int i, int j, T isovalue,
  const T* tolerance, const T* start, T* u, T& ndcDepth, const ClipPlanes<T>& clip,
  NewtonWork* work = nullptr)
{
  return isSurface(node) ? detail::solvePixel<T, 2>(
                             node, i, j, isovalue, tolerance, start, u, ndcDepth, clip, work)
                         : detail::solvePixel<T, 3>(
                             node, i, j, isovalue, tolerance, start, u, ndcDepth, clip, work);
}

/// One (pixel, node) tuple of the solution stage: cheap exclusions first, then Newton on
/// certified nodes (counted in `work`, when given).
template<class T>
IGA_HD TupleOutcome solveTuple(const VolumeView<const T>& node, const NodeInfo<T>& info, int i,
  int j, T isovalue, const T* tolerance, T* u, T& ndcDepth,
  const ClipPlanes<T>& clip = ClipPlanes<T>(), NewtonWork* work = nullptr)
{
  return isSurface(node) ? detail::solveTuple<T, 2>(
                             node, info, i, j, isovalue, tolerance, u, ndcDepth, clip, work)
                         : detail::solveTuple<T, 3>(
                             node, info, i, j, isovalue, tolerance, u, ndcDepth, clip, work);
}

/// The directions a node's midpoint split halves by default: all of its unknowns'.
template<class T>
IGA_HD int allAxes(const VolumeView<const T>& node)
{
  return isSurface(node) ? kAllAxes<2> : kAllAxes<3>;
}

namespace detail
{
/// A direction is halved when the node's window position or attribute varies along it by at
/// least this share of the most either varies along any direction.
constexpr double kSplitShare = 0.25;

/// See splitAxes.
template<class T, int Dim>
IGA_HD int splitAxes(const PatchView<const T, Dim>& node)
{
  // Per direction, the mean variation of the control net's window position (pixels, X/W and
  // Y/W) and attribute (A/V) along its lines.
  T window[Dim] = {}, attribute[Dim] = {};
  const int count = node.pointCount();
  for (int p = 0; p < count; ++p)
  {
    const T* a = node.point(p);
    if (!(a[kScreenW] > T(0)))
    {
      return kAllAxes<Dim>; // no window position: straddles the eye plane
    }
    int index = p;
    for (int d = 0; d < Dim; ++d)
    {
      const int along = index % node.order(d);
      index /= node.order(d);
      if (along == node.degree[d])
      {
        continue;
      }
      const T* b = node.point(p + node.stride(d) / node.channels);
      if (!(b[kScreenW] > T(0)))
      {
        return kAllAxes<Dim>;
      }
      window[d] += absValue(b[kScreenX] / b[kScreenW] - a[kScreenX] / a[kScreenW]) +
                   absValue(b[kScreenY] / b[kScreenW] - a[kScreenY] / a[kScreenW]);
      if (Dim == 3)
      {
        attribute[d] +=
          absValue(b[kScreenAttribute] / b[kScreenWeight] - a[kScreenAttribute] / a[kScreenWeight]);
      }
    }
  }
  T mostWindow = T(0), mostAttribute = T(0);
  for (int d = 0; d < Dim; ++d)
  {
    window[d] *= T(node.order(d)) / T(count); // per line
    attribute[d] *= T(node.order(d)) / T(count);
    mostWindow = maxValue(mostWindow, window[d]);
    mostAttribute = maxValue(mostAttribute, attribute[d]);
  }
  int axes = 0;
  for (int d = 0; d < Dim; ++d)
  {
    const bool varies = (mostWindow > T(0) && window[d] >= T(kSplitShare) * mostWindow) ||
                        (mostAttribute > T(0) && attribute[d] >= T(kSplitShare) * mostAttribute);
    axes |= varies ? 1 << d : 0;
  }
  return axes != 0 ? axes : kAllAxes<Dim>;
}
} // namespace detail

/// The directions worth halving when a node is split: those along which its window position
/// or its attribute varies by at least a quarter of the most it varies along any direction, all
/// where the node straddles the eye plane. A node stretched along one direction (where a rational
/// patch's weights range widely, its map changes across a thin layer in parameter space) is
/// halved across the layer alone until it is no longer stretched, instead of into 8 children
/// along the layer as well.
template<class T>
IGA_HD int splitAxes(const VolumeView<const T>& node)
{
  return isSurface(node) ? detail::splitAxes<T, 2>(surfaceOf(node)) : detail::splitAxes<T, 3>(node);
}

/// Children of a node's midpoint split along `axes`.
IGA_HD inline int childCount(int axes)
{
  return 1 << axisCount(axes);
}

/// The node's childCount(axes) children at the parametric midpoint of `axes` (splitMidpoint).
template<class T>
IGA_HD void splitNode(const VolumeView<const T>& node, int axes, T* out)
{
  isSurface(node) ? splitMidpoint<T, 2>(surfaceOf(node), out, axes)
                  : splitMidpoint<T, 3>(node, out, axes);
}

/// Child `child` of splitNode alone (midpointChild).
template<class T>
IGA_HD void nodeChild(const VolumeView<const T>& node, int axes, int child, T* out)
{
  isSurface(node) ? midpointChild<T, 2>(surfaceOf(node), child, out, axes)
                  : midpointChild<T, 3>(node, child, out, axes);
}

} // namespace sst
} // namespace iga
