// A VTK-free container of tensor-product NURBS / B-spline patches (trivariate volumes and
// bivariate surfaces) as file readers produce them, and the attributes that make geometry-only
// files useful for isosurfaces. Host only.
#pragma once

#include "iga/BSpline.h"
#include "iga/Validation.h"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace iga
{

/// Patches that share attribute names. Every control net is homogeneous in the standard layout
/// (w*x, w*y, w*z, w, w*a_0, ...), first parametric direction fastest, with channels() values per
/// control point. Patch index p < volumes.size() is a volume, the rest are surfaces in order.
template<class T>
struct NurbsSet
{
  std::vector<BSplinePatch<T, 3>> volumes;
  std::vector<BSplinePatch<T, 2>> surfaces;
  std::vector<std::string> attributeNames;

  int channels() const { return kFirstAttributeChannel + static_cast<int>(attributeNames.size()); }
  int patchCount() const { return static_cast<int>(volumes.size() + surfaces.size()); }
};

/// Number of control points of a patch.
template<class T, int Dim>
size_t controlPointCount(const BSplinePatch<T, Dim>& patch)
{
  size_t count = 1;
  for (int d = 0; d < Dim; ++d)
  {
    count *= static_cast<size_t>(patch.netSize[d] > 0 ? patch.netSize[d] : 0);
  }
  return count;
}

/// Empty when `net` holds netSize[0] x ... x netSize[Dim-1] points of `channels` finite values
/// with positive weights and coordinates within kMaxCoordinate; otherwise one sentence naming the
/// first bad control point by its indices.
template<class T, int Dim>
std::string checkControlNet(const int* netSize, int channels, const std::vector<T>& net)
{
  size_t points = 1;
  for (int d = 0; d < Dim; ++d)
  {
    points *= static_cast<size_t>(netSize[d] > 0 ? netSize[d] : 0);
  }
  if (net.size() != points * static_cast<size_t>(channels))
  {
    return "control net has " + std::to_string(net.size()) + " values, expected " +
           std::to_string(points * channels);
  }
  // The net is laid out as a patch of degrees netSize - 1.
  int degree[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    degree[d] = netSize[d] - 1;
  }
  const int p =
    points > 0 ? firstInvalidPoint(PatchView<const T, Dim>(net.data(), degree, channels)) : -1;
  if (p < 0)
  {
    return std::string();
  }
  std::string where = "control point (";
  size_t rest = size_t(p);
  for (int d = 0; d < Dim; ++d)
  {
    where += (d ? ", " : "") + std::to_string(rest % netSize[d]);
    rest /= netSize[d];
  }
  return where + ")" + invalidPointProblem(net.data() + size_t(p) * channels, channels);
}

/// The same for a patch's net size and channel count.
template<class T, int Dim>
std::string checkControlNet(const BSplinePatch<T, Dim>& patch, const std::vector<T>& net)
{
  return checkControlNet<T, Dim>(patch.netSize, patch.channels, net);
}

/// Whether the control points element `index` draws on (its support in the net) have weights
/// that range over more than `limit`.
template<class T, int Dim>
bool supportWeightsExceed(const BezierExtraction<T, Dim>& extraction, const int* index,
  const std::vector<T>& net, int channels, T limit)
{
  int first[Dim], count = 1;
  for (int d = 0; d < Dim; ++d)
  {
    first[d] = extraction.direction(d).firstBasis[size_t(index[d])];
    count *= extraction.direction(d).degree + 1;
  }
  T lo = std::numeric_limits<T>::infinity(), hi = T(0);
  for (int k = 0; k < count; ++k) // the support's points, first direction fastest
  {
    size_t point = 0, stride = 1;
    for (int d = 0, rest = k; d < Dim; ++d)
    {
      const int order = extraction.direction(d).degree + 1;
      point += size_t(first[d] + rest % order) * stride;
      stride *= size_t(extraction.netSize(d));
      rest /= order;
    }
    const T weight = net[point * size_t(channels) + kWeightChannel];
    lo = std::min(lo, weight);
    hi = std::max(hi, weight);
  }
  return hi > limit * lo;
}

/// Empty unless an element of the patch has Bézier weights that range over more than
/// kMaxWeightRatio (what checkPatch refuses); then names the first such element by its index
/// along each direction. Its Bézier weights are convex combinations of its support's in the net,
/// so only an element whose support ranges that far is extracted, and only when the whole net's
/// weights do. `net` passed checkControlNet.
template<class T, int Dim>
std::string skewedElementProblem(
  const BezierExtraction<T, Dim>& extraction, const std::vector<T>& net, int channels)
{
  // Another extraction's rounding (the device's) may widen an element's weights by a few ulps:
  // the limit here is a hair less, so that no engine refuses an element that passed.
  const T limit = T(kMaxWeightRatio * (1 - 1e-12));
  int netDegree[Dim], degree[Dim]; // the net laid out as a patch of degrees netSize - 1
  for (int d = 0; d < Dim; ++d)
  {
    netDegree[d] = extraction.netSize(d) - 1;
    degree[d] = extraction.direction(d).degree;
  }
  T lo, hi;
  weightRange(PatchView<const T, Dim>(net.data(), netDegree, channels), lo, hi);
  if (!(hi > limit * lo))
  {
    return std::string();
  }
  BezierPatch<T, Dim> element(degree, channels);
  std::vector<T> work(2 * element.coeffs().size());
  for (int e = 0; e < extraction.elementCount(); ++e)
  {
    int index[Dim];
    extraction.elementIndex(e, index);
    if (!supportWeightsExceed(extraction, index, net, channels, limit))
    {
      continue;
    }
    extraction.extract(e, net.data(), channels, element.coeffs().data(), work.data());
    weightRange(static_cast<const BezierPatch<T, Dim>&>(element).view(), lo, hi);
    if (hi > limit * lo)
    {
      std::string where = "element (";
      for (int d = 0; d < Dim; ++d)
      {
        where += (d ? ", " : "") + std::to_string(index[d]);
      }
      return where + "): its Bézier " + weightRatioProblem(double(lo), double(hi));
    }
  }
  return std::string();
}

/// Greville abscissae xi_i = (t_{i+1} + ... + t_{i+p}) / p of the `count` B-splines of degree p:
/// with these control values a polynomial B-spline reproduces its parameter, sum xi_i N_i(u) = u.
template<class T>
std::vector<T> grevilleAbscissae(const std::vector<T>& knots, int degree, int count)
{
  std::vector<T> xi(static_cast<size_t>(count), T(0));
  for (int i = 0; i < count; ++i)
  {
    for (int k = 1; k <= degree; ++k)
    {
      xi[i] += knots[i + k];
    }
    xi[i] /= T(degree);
  }
  return xi;
}

/// Adds `count` attributes to a patch whose net is set: `values` holds `count` values per
/// control point (Euclidean, as a solver's coefficients are), in the net's order; each is
/// weighted into a channel of its own after the patch's attributes.
template<class T, int Dim>
void appendAttributes(BSplinePatch<T, Dim>& patch, const std::vector<T>& values, int count)
{
  const size_t points = controlPointCount(patch);
  const int channels = patch.channels + count;
  std::vector<T> net(points * channels);
  for (size_t p = 0; p < points; ++p)
  {
    const T* from = patch.net.data() + p * patch.channels;
    T* to = net.data() + p * channels;
    std::copy(from, from + patch.channels, to);
    for (int a = 0; a < count; ++a)
    {
      to[patch.channels + a] = from[kWeightChannel] * values[p * count + a];
    }
  }
  patch.net = std::move(net);
  patch.channels = channels;
}

/// Names of the attributes geometryNet() adds, in channel order.
inline std::vector<std::string> geometryAttributeNames()
{
  return { "x", "y", "z", "parameter_u", "parameter_v", "parameter_w" };
}

/// Fills patch.net (and patch.channels) from Euclidean control points (3 values each, first
/// direction fastest) and weights, adding the geometryAttributeNames() attributes so that
/// geometry-only files (G+Smo, GeoPDEs) can be contoured:
///  - "x", "y", "z": the control point coordinates. Exact: attributes share the rational basis of
///    the geometry, so they reproduce the physical coordinates everywhere.
///  - "parameter_u/v/w": the Greville abscissae along each direction (w = 0 on surfaces). Exact
///    for polynomial patches; with varying weights they are the rational blend of the abscissae,
///    which follows the parameter closely but not exactly (withExactParameters makes an
///    element's exact, one degree higher).
/// `knots`, `degree` and `netSize` must be set and valid.
template<class T, int Dim>
void setGeometryNet(
  BSplinePatch<T, Dim>& patch, const std::vector<T>& euclidean, const std::vector<T>& weights)
{
  const int channels = kFirstAttributeChannel + 6;
  const size_t points = controlPointCount(patch);
  std::vector<T> greville[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    greville[d] = grevilleAbscissae(patch.knots[d], patch.degree[d], patch.netSize[d]);
  }
  patch.channels = channels;
  patch.net.assign(points * channels, T(0));
  for (size_t p = 0; p < points; ++p)
  {
    const T w = weights[p];
    T* cp = patch.net.data() + p * channels;
    for (int c = 0; c < 3; ++c)
    {
      cp[c] = w * euclidean[3 * p + c];
      cp[kFirstAttributeChannel + c] = w * euclidean[3 * p + c];
    }
    cp[kWeightChannel] = w;
    size_t rest = p;
    for (int d = 0; d < Dim; ++d)
    {
      cp[kFirstAttributeChannel + 3 + d] = w * greville[d][rest % patch.netSize[d]];
      rest /= patch.netSize[d];
    }
  }
}

/// The Bernstein coefficients, one degree higher along `dir`, of (start (1 - s) + end s) W: W the
/// one-channel patch `weight`, s its parameter along dir. Since (1 - s) B_i^n = (n + 1 - i) /
/// (n + 1) B_i^(n+1) and s B_(i-1)^n = i / (n + 1) B_i^(n+1), coefficient i is start (1 - i / (n
/// + 1)) W_i + end i / (n + 1) W_(i-1).
template<class T, int Dim>
BezierPatch<T, Dim> parameterTimesWeight(const BezierPatch<T, Dim>& weight, int dir, T start, T end)
{
  int degree[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    degree[d] = weight.degree(d) + (d == dir ? 1 : 0);
  }
  BezierPatch<T, Dim> product(degree, 1);
  const auto in = weight.view();
  const auto out = product.view();
  const int n = weight.degree(dir);
  forEachLine(in, dir,
    [&](int base)
    {
      // The line of `product` holding the same points: its base skips the longer lines below.
      const int below = in.stride(dir);
      const int outBase = base % below + base / below / (n + 1) * below * (n + 2);
      for (int i = 0; i <= n + 1; ++i)
      {
        const T a = T(i) / T(n + 1);
        const T previous = i > 0 ? in.coeffs[base + (i - 1) * below] : T(0);
        const T current = i <= n ? in.coeffs[base + i * below] : T(0);
        out.coeffs[outBase + i * out.stride(dir)] =
          start * (T(1) - a) * current + end * a * previous;
      }
    });
  return product;
}

/// An element of a rational patch (standard layout) elevated by one degree in every direction,
/// with exact parameter channels: channel parameterChannel[d] (-1: none) holds start[d] (1 - s_d)
/// + end[d] s_d times the weight, s_d the element's parameter along d, so that the attribute is
/// the patch's parameter along d everywhere. At the element's own degree no coefficients give
/// that where its weights vary (the parameter times the weight has one degree more).
template<class T, int Dim>
BezierPatch<T, Dim> withExactParameters(
  const BezierPatch<T, Dim>& element, const int* parameterChannel, const T* start, const T* end)
{
  BezierPatch<T, Dim> elevated = element;
  int degree[Dim];
  for (int d = 0; d < Dim; ++d)
  {
    elevated = elevateDegree(elevated, d);
    degree[d] = element.degree(d);
  }
  const int channels = element.channels();
  BezierPatch<T, Dim> weight(degree, 1);
  for (size_t p = 0; p < weight.coeffs().size(); ++p)
  {
    weight.coeffs()[p] = element.coeffs()[p * size_t(channels) + kWeightChannel];
  }
  for (int d = 0; d < Dim; ++d)
  {
    if (parameterChannel[d] < 0)
    {
      continue;
    }
    BezierPatch<T, Dim> product = parameterTimesWeight(weight, d, start[d], end[d]);
    for (int other = 0; other < Dim; ++other)
    {
      if (other != d)
      {
        product = elevateDegree(product, other);
      }
    }
    for (size_t p = 0; p < product.coeffs().size(); ++p)
    {
      elevated.coeffs()[p * size_t(channels) + size_t(parameterChannel[d])] = product.coeffs()[p];
    }
  }
  return elevated;
}

} // namespace iga
