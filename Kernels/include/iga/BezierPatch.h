// Tensor-product rational Bézier patches (Dim = 3: volumes, Dim = 2: surfaces) in homogeneous
// form, with evaluation, subdivision and degree elevation.
//
// A patch stores (degree[0]+1) x ... x (degree[Dim-1]+1) control points, the first parametric
// direction fastest. Each control point is `channels` consecutive values. Every channel is
// homogeneous: the standard layout is (w*x, w*y, w*z, w, w*a_0, w*a_1, ...), so attributes are
// interpolated with the same rational basis as the geometry (as VTK's rational Bézier cells do),
// and subdivision and degree elevation act on all channels alike.
#pragma once

#include "iga/Portability.h"

#include <utility>
#include <vector>

namespace iga
{

/// Channels per control point that split() processes together.
constexpr int kSplitChannels = 8;

/// Channel indices of the standard layout.
constexpr int kWeightChannel = 3;
constexpr int kFirstAttributeChannel = 4;

/// Non-owning view of one patch's coefficients. T may be const.
template<class T, int Dim>
struct PatchView
{
  static_assert(Dim == 2 || Dim == 3, "patches are bivariate or trivariate");
  T* coeffs = nullptr;
  int degree[Dim] = {};
  int channels = 0;

  PatchView() = default;
  IGA_HD PatchView(T* c, const int* deg, int ch)
    : coeffs(c)
    , channels(ch)
  {
    for (int d = 0; d < Dim; ++d)
    {
      degree[d] = deg[d];
    }
  }
  /// A mutable view converts to a read-only one.
  template<class U>
  IGA_HD PatchView(const PatchView<U, Dim>& other)
    : PatchView(other.coeffs, other.degree, other.channels)
  {
  }

  IGA_HD int order(int d) const { return degree[d] + 1; }
  IGA_HD int pointCount() const
  {
    int n = 1;
    for (int d = 0; d < Dim; ++d)
    {
      n *= order(d);
    }
    return n;
  }
  IGA_HD int valueCount() const { return pointCount() * channels; }
  /// Distance in values between neighbouring control points along direction d.
  IGA_HD int stride(int d) const
  {
    int s = channels;
    for (int e = 0; e < d; ++e)
    {
      s *= order(e);
    }
    return s;
  }
  IGA_HD T* point(int linearIndex) const { return coeffs + linearIndex * channels; }
};

template<class T>
using VolumeView = PatchView<T, 3>;
template<class T>
using SurfaceView = PatchView<T, 2>;

/// The engine stores a surface as a volume of degree 0 in its third direction (the same
/// coefficients in the same order), so that one node layout and one loop serve both; volumes
/// have degrees of at least 1 in every direction.
template<class T>
IGA_HD VolumeView<T> flatVolume(const SurfaceView<T>& surface)
{
  const int degree[3] = { surface.degree[0], surface.degree[1], 0 };
  return VolumeView<T>(surface.coeffs, degree, surface.channels);
}

/// Whether a view holds a surface stored by flatVolume.
template<class T>
IGA_HD bool isSurface(const VolumeView<T>& patch)
{
  return patch.degree[2] == 0;
}

/// The surface a flatVolume view stores.
template<class T>
IGA_HD SurfaceView<T> surfaceOf(const VolumeView<T>& flat)
{
  return SurfaceView<T>(flat.coeffs, flat.degree, flat.channels);
}

/// Owning patch for host code.
template<class T, int Dim>
class BezierPatch
{
public:
  BezierPatch() = default;
  BezierPatch(const int* degree, int channels)
  {
    for (int d = 0; d < Dim; ++d)
    {
      this->Degree[d] = degree[d];
    }
    this->Channels = channels;
    this->Coeffs.assign(static_cast<size_t>(this->view().valueCount()), T(0));
  }

  PatchView<T, Dim> view()
  {
    return PatchView<T, Dim>(this->Coeffs.data(), this->Degree, this->Channels);
  }
  PatchView<const T, Dim> view() const
  {
    return PatchView<const T, Dim>(this->Coeffs.data(), this->Degree, this->Channels);
  }
  int degree(int d) const { return this->Degree[d]; }
  int channels() const { return this->Channels; }
  std::vector<T>& coeffs() { return this->Coeffs; }
  const std::vector<T>& coeffs() const { return this->Coeffs; }

private:
  std::vector<T> Coeffs;
  int Degree[Dim] = {};
  int Channels = 0;
};

template<class T>
using BezierVolume = BezierPatch<T, 3>;
template<class T>
using BezierSurface = BezierPatch<T, 2>;

namespace detail
{
/// A degree known at compile time, so that the recurrence below unrolls.
template<int N>
struct FixedDegree
{
  IGA_HD constexpr operator int() const { return N; }
};

template<class T, class Degree>
IGA_HD void bernsteinBasis(Degree degree, T t, T* basis, T* derivative)
{
  const int n = degree;
  const T s = T(1) - t;
  basis[0] = T(1);
  for (int r = 1; r <= n; ++r)
  {
    if (r == n && derivative)
    {
      // dB_i^n = n (B_{i-1}^{n-1} - B_i^{n-1})
      for (int i = 0; i <= n; ++i)
      {
        const T left = i > 0 ? basis[i - 1] : T(0);
        const T right = i < n ? basis[i] : T(0);
        derivative[i] = T(n) * (left - right);
      }
    }
    basis[r] = t * basis[r - 1];
    for (int i = r - 1; i > 0; --i)
    {
      basis[i] = s * basis[i] + t * basis[i - 1];
    }
    basis[0] = s * basis[0];
  }
  if (n == 0 && derivative)
  {
    derivative[0] = T(0);
  }
}
} // namespace detail

/// Bernstein basis B_i^n(t), i = 0..n, by the triangular (de Casteljau) recurrence, and
/// optionally its derivative. `basis` and `derivative` hold n+1 values.
template<class T>
IGA_HD void bernsteinBasis(int n, T t, T* basis, T* derivative)
{
  switch (n)
  {
    case 1:
      return detail::bernsteinBasis(detail::FixedDegree<1>(), t, basis, derivative);
    case 2:
      return detail::bernsteinBasis(detail::FixedDegree<2>(), t, basis, derivative);
    case 3:
      return detail::bernsteinBasis(detail::FixedDegree<3>(), t, basis, derivative);
    case 4:
      return detail::bernsteinBasis(detail::FixedDegree<4>(), t, basis, derivative);
    default:
      return detail::bernsteinBasis(n, t, basis, derivative);
  }
}

/// Evaluates the homogeneous channels at parameter u (Dim values in [0,1]) and, if `derivatives`
/// is not null, their first partial derivatives: derivatives[d * channels + c] = dC_c/du_d.
/// `leading` > 0 evaluates only the first `leading` channels (the layout stays that of all of
/// them; the others are left unwritten): a solver whose rows read only those skips the rest.
template<class T, int Dim>
IGA_HD void evaluateHomogeneous(
  const PatchView<const T, Dim>& patch, const T* u, T* values, T* derivatives, int leading = 0);

namespace detail
{
/// Orders, channel count and evaluated leading channels of an evaluation, known at run time...
struct RuntimeShape
{
  int n0, n1, n2, channels, evaluated;
};
/// ... or at compile time (the common tri-degree cases), so that the loops below unroll.
template<int N, int C, int E>
struct FixedShape
{
  static constexpr int n0 = N, n1 = N, n2 = N, channels = C, evaluated = E;
};

/// Trivariate evaluation contracting one direction at a time (sum factorisation): about
/// 2 (p+1)^3 operations a channel for value and gradient instead of 4 (p+1)^3 and the basis
/// products. Here the contractions along v and w of the lines along u that `lines(c, j, k, line,
/// dline)` gives (the channel's value and u-derivative on control row (j, k)).
template<class T, class Shape, class Lines>
IGA_HD void contractLines(const Shape& shape, const T (&basis)[3][kMaxOrder],
  const T (&dbasis)[3][kMaxOrder], Lines lines, T* values, T* derivatives)
{
  const int n1 = shape.n1, n2 = shape.n2, C = shape.channels, E = shape.evaluated;
  for (int c = 0; c < E; ++c)
  {
    T value = T(0), du = T(0), dv = T(0), dw = T(0);
    for (int k = 0; k < n2; ++k)
    {
      T v = T(0), vu = T(0), vv = T(0);
      for (int j = 0; j < n1; ++j)
      {
        T line, dline;
        lines(c, j, k, line, dline);
        v += basis[1][j] * line;
        vu += basis[1][j] * dline;
        vv += dbasis[1][j] * line;
      }
      value += basis[2][k] * v;
      du += basis[2][k] * vu;
      dv += basis[2][k] * vv;
      dw += dbasis[2][k] * v;
    }
    values[c] = value;
    if (derivatives)
    {
      derivatives[c] = du;
      derivatives[C + c] = dv;
      derivatives[2 * C + c] = dw;
    }
  }
}

/// The line along u of channel c on control row (j, k): its value and u-derivative.
template<class T, class Shape>
IGA_HD void contractAlongU(const T* coeffs, const Shape& shape, const T (&basis)[3][kMaxOrder],
  const T (&dbasis)[3][kMaxOrder], int c, int jk, T& line, T& dline)
{
  const int n0 = shape.n0, C = shape.channels;
  const T* p = coeffs + (jk * n0) * C + c;
  line = T(0);
  dline = T(0);
  for (int i = 0; i < n0; ++i)
  {
    line += basis[0][i] * p[i * C];
    dline += dbasis[0][i] * p[i * C];
  }
}

/// Two loop orders of one contraction, as each processor is faster with: one channel at a time,
/// each line contracted where it is used, with no scratch (the GPU's: a thread's stack in the
/// solution kernel 7.2 -> 2.1 KB, volume frames 3-20% faster on an H200)...
template<class T, class Shape>
IGA_HD void evaluateByChannel(const T* coeffs, const Shape& shape, const T (&basis)[3][kMaxOrder],
  const T (&dbasis)[3][kMaxOrder], T* values, T* derivatives)
{
  contractLines(
    shape, basis, dbasis,
    [&](int c, int j, int k, T& line, T& dline)
    { contractAlongU(coeffs, shape, basis, dbasis, c, k * shape.n1 + j, line, dline); },
    values, derivatives);
}

/// Scratch limit of the channels-inner order below (n1 n2 evaluated channels).
constexpr int kFactorisedScratch = 6 * 6 * 8;

/// ... or every line first, the channels of a control row innermost, kept in scratch (the CPU's:
/// the compiler vectorises across adjacent channels; volume frames 8-10% faster on 2 cores).
template<class T, class Shape>
IGA_HD void evaluateChannelsInner(const T* coeffs, const Shape& shape,
  const T (&basis)[3][kMaxOrder], const T (&dbasis)[3][kMaxOrder], T* values, T* derivatives)
{
  const int n1 = shape.n1, E = shape.evaluated;
  T lines[2][kFactorisedScratch]; // value and u-derivative at (j, k, c)
  for (int jk = 0; jk < n1 * shape.n2; ++jk)
  {
    for (int c = 0; c < E; ++c)
    {
      contractAlongU(
        coeffs, shape, basis, dbasis, c, jk, lines[0][jk * E + c], lines[1][jk * E + c]);
    }
  }
  contractLines(
    shape, basis, dbasis,
    [&](int c, int j, int k, T& line, T& dline)
    {
      line = lines[0][(k * n1 + j) * E + c];
      dline = lines[1][(k * n1 + j) * E + c];
    },
    values, derivatives);
}

/// Bivariate evaluation contracting u first: about 3 (p+1)^2 C operations for value and
/// gradient, no scratch.
template<class T, class Shape>
IGA_HD void evaluateFactorised2(const T* coeffs, const Shape& shape, const T (&basis)[2][kMaxOrder],
  const T (&dbasis)[2][kMaxOrder], T* values, T* derivatives)
{
  const int n0 = shape.n0, n1 = shape.n1, C = shape.channels, E = shape.evaluated;
  for (int c = 0; c < E; ++c)
  {
    T value = T(0), du = T(0), dv = T(0);
    for (int j = 0; j < n1; ++j)
    {
      T v = T(0), vu = T(0);
      const T* p = coeffs + (j * n0) * C + c;
      for (int i = 0; i < n0; ++i)
      {
        v += basis[0][i] * p[i * C];
        vu += dbasis[0][i] * p[i * C];
      }
      value += basis[1][j] * v;
      du += basis[1][j] * vu;
      dv += dbasis[1][j] * v;
    }
    values[c] = value;
    if (derivatives)
    {
      derivatives[c] = du;
      derivatives[C + c] = dv;
    }
  }
}

/// Calls fn(shape) with a compile-time shape for equal degrees 1..5 of a 6-channel patch (the
/// engine's screen and shading patches, `fixed`), so that the loops unroll, else with `runtime`.
template<int E, class Fn>
IGA_HD void withDegree(int degree, const RuntimeShape& runtime, Fn fn)
{
  switch (degree)
  {
    case 1:
      return fn(FixedShape<2, 6, E>());
    case 2:
      return fn(FixedShape<3, 6, E>());
    case 3:
      return fn(FixedShape<4, 6, E>());
    case 4:
      return fn(FixedShape<5, 6, E>());
    case 5:
      return fn(FixedShape<6, 6, E>());
    default:
      return fn(runtime);
  }
}

/// The same, all six channels evaluated or the four of a surface's pixel problem (X, Y, Z, W).
template<class Fn>
IGA_HD void withShape(bool fixed, int degree, const RuntimeShape& runtime, Fn fn)
{
  if (fixed && runtime.evaluated == 4)
  {
    return withDegree<4>(degree, runtime, fn);
  }
  return withDegree<6>(fixed && runtime.evaluated == 6 ? degree : 0, runtime, fn);
}

template<class T>
IGA_HD void evaluateFactorised(const PatchView<const T, 2>& patch, const T (&basis)[2][kMaxOrder],
  const T (&dbasis)[2][kMaxOrder], T* values, T* derivatives, int leading)
{
  const int p = patch.degree[0];
  withShape(patch.channels == 6 && patch.degree[1] == p, p,
    RuntimeShape{ patch.order(0), patch.order(1), 1, patch.channels, leading },
    [&](const auto& shape)
    { evaluateFactorised2(patch.coeffs, shape, basis, dbasis, values, derivatives); });
}

template<class T>
IGA_HD void evaluateFactorised(const PatchView<const T, 3>& patch, const T (&basis)[3][kMaxOrder],
  const T (&dbasis)[3][kMaxOrder], T* values, T* derivatives, int leading)
{
  const int p = patch.degree[0];
  withShape(patch.channels == 6 && patch.degree[1] == p && patch.degree[2] == p, p,
    RuntimeShape{ patch.order(0), patch.order(1), patch.order(2), patch.channels, leading },
    [&](const auto& shape)
    {
#ifndef __CUDA_ARCH__
      if (shape.n1 * shape.n2 * shape.evaluated <= kFactorisedScratch)
      {
        return evaluateChannelsInner(patch.coeffs, shape, basis, dbasis, values, derivatives);
      }
#endif
      evaluateByChannel(patch.coeffs, shape, basis, dbasis, values, derivatives);
    });
}
} // namespace detail

template<class T, int Dim>
IGA_HD void evaluateHomogeneous(
  const PatchView<const T, Dim>& patch, const T* u, T* values, T* derivatives, int leading)
{
  leading = leading > 0 && leading < patch.channels ? leading : patch.channels;
  T basis[Dim][kMaxOrder];
  T dbasis[Dim][kMaxOrder];
  for (int d = 0; d < Dim; ++d)
  {
    bernsteinBasis(patch.degree[d], u[d], basis[d], dbasis[d]);
  }
  detail::evaluateFactorised(patch, basis, dbasis, values, derivatives, leading);
}

/// The rational function numerator/denominator from homogeneous values, with its gradient by the
/// quotient rule: d(N/D) = (dN D - N dD) / D^2.
template<class T, int Dim>
IGA_HD T rationalValue(
  const T* values, const T* derivatives, int channels, int numerator, int denominator, T* gradient)
{
  const T n = values[numerator];
  const T den = values[denominator];
  const T f = n / den;
  if (gradient)
  {
    for (int d = 0; d < Dim; ++d)
    {
      const T dn = derivatives[d * channels + numerator];
      const T dden = derivatives[d * channels + denominator];
      gradient[d] = (dn - f * dden) / den;
    }
  }
  return f;
}

/// Calls fn(base) for the first control point of every line of control points along direction
/// `dir`; the line's points are then base + i * stride(dir), i = 0..degree[dir].
template<class T, int Dim, class Fn>
IGA_HD void forEachLine(const PatchView<T, Dim>& patch, int dir, Fn fn)
{
  int below = 1;
  for (int d = 0; d < dir; ++d)
  {
    below *= patch.order(d);
  }
  const int lines = patch.pointCount() / patch.order(dir);
  const int blockSize = below * patch.order(dir);
  for (int line = 0; line < lines; ++line)
  {
    fn((line % below) + (line / below) * blockSize);
  }
}

namespace detail
{
template<class T, int Dim, class Degree, class Channels>
IGA_HD void splitParts(const PatchView<const T, Dim>& patch, Degree degree, Channels channelCount,
  int dir, T t, T* left, T* right)
{
  const int n = degree;
  const int stride = patch.stride(dir);
  const int channels = channelCount;
  const T s = T(1) - t;
  // Whole control points at a time (channels innermost) while they fit the scratch; one
  // channel at a time otherwise.
  const int width = channels <= kSplitChannels ? channels : 1;
  forEachLine(patch, dir,
    [&](int base)
    {
      const int offset = base * channels;
      for (int c0 = 0; c0 < channels; c0 += width)
      {
        T work[kMaxOrder * kSplitChannels];
        for (int i = 0; i <= n; ++i)
        {
          for (int c = 0; c < width; ++c)
          {
            work[i * width + c] = patch.coeffs[offset + i * stride + c0 + c];
          }
        }
        for (int c = 0; c < width && left; ++c)
        {
          left[offset + c0 + c] = work[c];
        }
        for (int c = 0; c < width && right; ++c)
        {
          right[offset + n * stride + c0 + c] = work[n * width + c];
        }
        for (int r = 1; r <= n; ++r)
        {
          for (int i = 0; i <= n - r; ++i)
          {
            for (int c = 0; c < width; ++c)
            {
              work[i * width + c] = s * work[i * width + c] + t * work[(i + 1) * width + c];
            }
          }
          for (int c = 0; c < width && left; ++c)
          {
            left[offset + r * stride + c0 + c] = work[c];
          }
          for (int c = 0; c < width && right; ++c)
          {
            right[offset + (n - r) * stride + c0 + c] = work[(n - r) * width + c];
          }
        }
      }
    });
}
} // namespace detail

/// Splits a patch at parameter t of direction dir into the parts [0,t] (coefficients `left`)
/// and [t,1] (`right`), both reparametrised to [0,1] and laid out like `patch`. Either may be
/// null (that part is not written) and either may alias `patch`: each line is read whole before
/// it is written.
template<class T, int Dim>
IGA_HD void splitParts(const PatchView<const T, Dim>& patch, int dir, T t, T* left, T* right)
{
  using detail::FixedDegree;
  const int n = patch.degree[dir];
  switch (patch.channels == 6 ? n : 0) // the engine's screen patches unroll
  {
    case 2:
      return detail::splitParts(patch, FixedDegree<2>(), FixedDegree<6>(), dir, t, left, right);
    case 3:
      return detail::splitParts(patch, FixedDegree<3>(), FixedDegree<6>(), dir, t, left, right);
    default:
      return detail::splitParts(patch, n, patch.channels, dir, t, left, right);
  }
}

/// Both parts (see splitParts); `left` may alias `patch`. All three share degrees and channels.
template<class T, int Dim>
IGA_HD void split(const PatchView<const T, Dim>& patch, int dir, T t, const PatchView<T, Dim>& left,
  const PatchView<T, Dim>& right)
{
  splitParts<T, Dim>(patch, dir, t, left.coeffs, right.coeffs);
}

/// Directions given as bits (bit d for direction d): all of a patch's.
template<int Dim>
constexpr int kAllAxes = (1 << Dim) - 1;

/// How many directions `axes` names.
IGA_HD inline int axisCount(int axes)
{
  return (axes & 1) + ((axes >> 1) & 1) + ((axes >> 2) & 1);
}

/// Whether child `child` of a midpoint split along `axes` covers the upper half [0.5, 1] of
/// direction d (one of `axes`): bit k of the child's index for the k-th direction of `axes`.
IGA_HD inline bool upperHalf(int axes, int child, int d)
{
  return ((child >> axisCount(axes & ((1 << d) - 1))) & 1) != 0;
}

/// Splits a patch at the parametric midpoint of the directions in `axes` (all by default) into
/// 2^axisCount(axes) children written to `out` (consecutive blocks of patch.valueCount() values),
/// ordered as upperHalf says.
template<class T, int Dim>
IGA_HD void splitMidpoint(const PatchView<const T, Dim>& patch, T* out, int axes = kAllAxes<Dim>)
{
  const int size = patch.valueCount();
  for (int i = 0; i < size; ++i)
  {
    out[i] = patch.coeffs[i];
  }
  int children = 1;
  for (int d = 0; d < Dim; ++d)
  {
    if (((axes >> d) & 1) == 0)
    {
      continue;
    }
    for (int child = 0; child < children; ++child)
    {
      const PatchView<T, Dim> lower(out + child * size, patch.degree, patch.channels);
      const PatchView<T, Dim> upper(out + (child + children) * size, patch.degree, patch.channels);
      split<T, Dim>(lower, d, T(0.5), lower, upper);
    }
    children *= 2;
  }
}

/// Child `child` of splitMidpoint alone, written to `out` (patch.valueCount() values): the same
/// operations on the same values, so the same result, with one GPU thread per child instead of
/// one per parent.
template<class T, int Dim>
IGA_HD void midpointChild(
  const PatchView<const T, Dim>& patch, int child, T* out, int axes = kAllAxes<Dim>)
{
  const int size = patch.valueCount();
  for (int i = 0; i < size; ++i)
  {
    out[i] = patch.coeffs[i];
  }
  const PatchView<const T, Dim> current(out, patch.degree, patch.channels);
  for (int d = 0; d < Dim; ++d)
  {
    if (((axes >> d) & 1) == 0)
    {
      continue;
    }
    const bool upper = upperHalf(axes, child, d);
    splitParts<T, Dim>(current, d, T(0.5), upper ? nullptr : out, upper ? out : nullptr);
  }
}

/// Maps a child's parameter to its parent's for a child of splitMidpoint along `axes`.
template<class T, int Dim>
IGA_HD void childToParentParameter(int child, const T* childU, T* parentU, int axes = kAllAxes<Dim>)
{
  for (int d = 0; d < Dim; ++d)
  {
    parentU[d] = ((axes >> d) & 1)
                   ? T(0.5) * (childU[d] + (upperHalf(axes, child, d) ? T(1) : T(0)))
                   : childU[d];
  }
}

/// Raises the degree of direction dir by one. `out` has degree[dir] + 1 there and must not alias.
template<class T, int Dim>
IGA_HD void elevateDegree(
  const PatchView<const T, Dim>& patch, int dir, const PatchView<T, Dim>& out)
{
  const int n = patch.degree[dir];
  const int inStride = patch.stride(dir);
  const int outStride = out.stride(dir);
  const int channels = patch.channels;
  // Lines of `out` correspond one to one (same enumeration order) to lines of `patch`.
  int below = 1;
  for (int d = 0; d < dir; ++d)
  {
    below *= patch.order(d);
  }
  const int lines = patch.pointCount() / patch.order(dir);
  for (int line = 0; line < lines; ++line)
  {
    const int inBase = (line % below) + (line / below) * below * (n + 1);
    const int outBase = (line % below) + (line / below) * below * (n + 2);
    const T* in = patch.coeffs + inBase * channels;
    T* result = out.coeffs + outBase * channels;
    for (int i = 0; i <= n + 1; ++i)
    {
      // Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i
      const T a = T(i) / T(n + 1);
      for (int c = 0; c < channels; ++c)
      {
        const T previous = i > 0 ? in[(i - 1) * inStride + c] : T(0);
        const T current = i <= n ? in[i * inStride + c] : T(0);
        result[i * outStride + c] = a * previous + (T(1) - a) * current;
      }
    }
  }
}

/// Host convenience: elevates direction dir by `times` steps.
template<class T, int Dim>
BezierPatch<T, Dim> elevateDegree(const BezierPatch<T, Dim>& patch, int dir, int times = 1)
{
  BezierPatch<T, Dim> current = patch;
  for (int step = 0; step < times; ++step)
  {
    int degree[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      degree[d] = current.degree(d) + (d == dir ? 1 : 0);
    }
    BezierPatch<T, Dim> next(degree, current.channels());
    elevateDegree<T, Dim>(current.view(), dir, next.view());
    current = std::move(next);
  }
  return current;
}

} // namespace iga
