// B-spline / NURBS patches and their Bézier extraction.
//
// Extraction turns each non-empty knot span of a tensor-product B-spline patch into one Bézier
// patch. Per direction it is a set of (p+1) x (p+1) matrices C_e with
//   Bézier point j of span e = sum_i C_e[j][i] * control point (first_e + i),
// so a moved control net (a deforming simulation) is re-extracted by matrix products alone,
// without touching the knots again. Works for open and unclamped knot vectors and repeated knots.
#pragma once

#include "iga/BezierPatch.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace iga
{

/// Extraction operator of one parametric direction.
template<class T>
struct ExtractionOperator1D
{
  int degree = 0;
  std::vector<int> firstBasis; ///< per element: index of its first control point
  std::vector<T> matrices;     ///< per element: (p+1)^2 values, row j = Bézier point j
  std::vector<T> spanStart;    ///< per element: knot interval [spanStart, spanEnd]
  std::vector<T> spanEnd;
  int elementCount() const { return static_cast<int>(firstBasis.size()); }
  const T* matrix(int element) const
  {
    return matrices.data() + static_cast<size_t>(element) * (degree + 1) * (degree + 1);
  }
};

/// Checks a knot vector for a direction of degree p with `controlPoints` control points; throws
/// std::invalid_argument naming the problem.
template<class T>
void validateKnotVector(const std::vector<T>& knots, int degree, int controlPoints)
{
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (degree < 1 || degree > kMaxDegree)
  {
    fail("degree " + std::to_string(degree) + " is outside 1.." + std::to_string(kMaxDegree));
  }
  if (controlPoints < degree + 1)
  {
    fail(std::to_string(controlPoints) + " control points are too few for degree " +
         std::to_string(degree) + " (need at least " + std::to_string(degree + 1) + ")");
  }
  const size_t expected = static_cast<size_t>(controlPoints) + degree + 1;
  if (knots.size() != expected)
  {
    fail("knot vector has " + std::to_string(knots.size()) + " knots, expected " +
         std::to_string(expected) + " (control points + degree + 1)");
  }
  for (size_t i = 0; i < knots.size(); ++i)
  {
    if (!isFinite(knots[i]))
    {
      fail("knot " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && knots[i] < knots[i - 1])
    {
      fail("knots are not non-decreasing at index " + std::to_string(i) + " (" +
           std::to_string(knots[i - 1]) + " > " + std::to_string(knots[i]) + ")");
    }
  }
  // Multiplicity above p+1 leaves a basis function with empty support.
  for (size_t i = 0, run = 1; i + 1 < knots.size(); ++i)
  {
    run = knots[i + 1] == knots[i] ? run + 1 : 1;
    if (run > static_cast<size_t>(degree + 1))
    {
      fail("knot " + std::to_string(knots[i]) +
           " has multiplicity above degree + 1 = " + std::to_string(degree + 1));
    }
  }
  if (!(knots[degree] < knots[controlPoints]))
  {
    fail("the parametric domain [knot p, knot n] is empty");
  }
}

/// The blossom of the B-spline basis on span k evaluated at (args[0..p-1]), applied to the p+1
/// local control "points" given as rows of `local` ((p+1) x width values); de Boor's algorithm with
/// one argument per level. Result in local[p * width ..].
template<class T>
void blossomOnSpan(
  const std::vector<T>& knots, int degree, int span, const T* args, T* local, int width)
{
  for (int r = 1; r <= degree; ++r)
  {
    for (int i = degree; i >= r; --i)
    {
      const T left = knots[span - degree + i];
      const T right = knots[span + i - r + 1];
      const T alpha = (args[r - 1] - left) / (right - left);
      for (int c = 0; c < width; ++c)
      {
        local[i * width + c] =
          (T(1) - alpha) * local[(i - 1) * width + c] + alpha * local[i * width + c];
      }
    }
  }
}

/// Builds the extraction operator of one direction (validates the knots first).
template<class T>
ExtractionOperator1D<T> buildExtractionOperator(
  const std::vector<T>& knots, int degree, int controlPoints)
{
  validateKnotVector(knots, degree, controlPoints);
  ExtractionOperator1D<T> op;
  op.degree = degree;
  const int p = degree;
  std::vector<T> local(static_cast<size_t>(p + 1) * (p + 1));
  std::vector<T> args(p);
  for (int span = p; span < controlPoints; ++span)
  {
    const T a = knots[span], b = knots[span + 1];
    if (!(a < b))
    {
      continue;
    }
    op.firstBasis.push_back(span - p);
    op.spanStart.push_back(a);
    op.spanEnd.push_back(b);
    const size_t offset = op.matrices.size();
    op.matrices.resize(offset + static_cast<size_t>(p + 1) * (p + 1));
    // Bézier point j on [a,b] is the blossom at (a^(p-j), b^j); apply it to the unit vectors.
    for (int j = 0; j <= p; ++j)
    {
      for (int i = 0; i < p; ++i)
      {
        args[i] = i < p - j ? a : b;
      }
      for (int i = 0; i <= p; ++i)
      {
        for (int c = 0; c <= p; ++c)
        {
          local[i * (p + 1) + c] = i == c ? T(1) : T(0);
        }
      }
      blossomOnSpan(knots, p, span, args.data(), local.data(), p + 1);
      for (int i = 0; i <= p; ++i)
      {
        op.matrices[offset + j * (p + 1) + i] = local[p * (p + 1) + i];
      }
    }
  }
  return op;
}

/// Extracts one Bézier element of a tensor-product control net (homogeneous channels, first
/// direction fastest, netSize[d] points along d). `matrices[d]` and `first[d]` describe the
/// element along direction d. `work` holds 2 * (p+1)^Dim * channels values. Applies one direction
/// at a time (sum factorisation, O(p^(Dim+1)) per channel).
template<class T, int Dim>
IGA_HD void extractElement(const T* net, const int* netSize, int channels, const int* degree,
  const T* const* matrices, const int* first, T* out, T* work)
{
  int order[Dim];
  int localCount = 1;
  for (int d = 0; d < Dim; ++d)
  {
    order[d] = degree[d] + 1;
    localCount *= order[d];
  }
  // Gather the local control points.
  T* current = work;
  T* next = work + localCount * channels;
  int index[Dim] = {};
  for (int p = 0; p < localCount; ++p)
  {
    int global = 0;
    for (int d = Dim - 1; d >= 0; --d)
    {
      global = global * netSize[d] + first[d] + index[d];
    }
    for (int c = 0; c < channels; ++c)
    {
      current[p * channels + c] = net[global * channels + c];
    }
    for (int d = 0; d < Dim; ++d)
    {
      if (++index[d] < order[d])
      {
        break;
      }
      index[d] = 0;
    }
  }
  for (int d = 0; d < Dim; ++d)
  {
    const PatchView<T, Dim> view(current, degree, channels);
    const int stride = view.stride(d);
    const T* C = matrices[d];
    const int n = order[d];
    forEachLine(view, d,
      [&](int base)
      {
        const int offset = base * channels;
        for (int j = 0; j < n; ++j)
        {
          for (int c = 0; c < channels; ++c)
          {
            T sum = T(0);
            for (int i = 0; i < n; ++i)
            {
              sum += C[j * n + i] * current[offset + i * stride + c];
            }
            next[offset + j * stride + c] = sum;
          }
        }
      });
    T* swap = current;
    current = next;
    next = swap;
  }
  for (int v = 0; v < localCount * channels; ++v)
  {
    out[v] = current[v];
  }
}

/// A tensor-product B-spline patch with a homogeneous control net (standard layout: w*x, w*y, w*z,
/// w, w*a...), first direction fastest.
template<class T, int Dim>
struct BSplinePatch
{
  int degree[Dim] = {};
  std::vector<T> knots[Dim];
  int netSize[Dim] = {};
  int channels = 0;
  std::vector<T> net;
};

/// Extraction of a whole tensor-product patch: built once from the knots, applied to any control
/// net of the same size (e.g. every time step of a deforming volume).
template<class T, int Dim>
class BezierExtraction
{
public:
  BezierExtraction() = default;
  BezierExtraction(const std::vector<T>* knots, const int* degree, const int* netSize)
  {
    for (int d = 0; d < Dim; ++d)
    {
      try
      {
        this->Operators[d] = buildExtractionOperator(knots[d], degree[d], netSize[d]);
      }
      catch (const std::invalid_argument& e)
      {
        throw std::invalid_argument("direction " + std::to_string(d) + ": " + e.what());
      }
      this->NetSize[d] = netSize[d];
      this->Degree[d] = degree[d];
    }
  }

  const ExtractionOperator1D<T>& direction(int d) const { return this->Operators[d]; }
  /// Control points along direction d of the nets it applies to.
  int netSize(int d) const { return this->NetSize[d]; }
  int elementCount() const
  {
    int n = 1;
    for (int d = 0; d < Dim; ++d)
    {
      n *= this->Operators[d].elementCount();
    }
    return n;
  }
  /// Element index along each direction of a linear element index (first direction fastest).
  void elementIndex(int element, int* perDirection) const
  {
    for (int d = 0; d < Dim; ++d)
    {
      perDirection[d] = element % this->Operators[d].elementCount();
      element /= this->Operators[d].elementCount();
    }
  }

  /// Extracts every element of `net` (netSize points, `channels` homogeneous values each).
  std::vector<BezierPatch<T, Dim>> apply(const std::vector<T>& net, int channels) const
  {
    size_t points = 1;
    for (int d = 0; d < Dim; ++d)
    {
      points *= static_cast<size_t>(this->NetSize[d]);
    }
    if (net.size() != points * channels)
    {
      throw std::invalid_argument("control net has " + std::to_string(net.size()) +
                                  " values, expected " + std::to_string(points * channels));
    }
    std::vector<BezierPatch<T, Dim>> patches(
      this->elementCount(), BezierPatch<T, Dim>(this->Degree, channels));
    std::vector<T> work(2 * patches.front().coeffs().size());
    for (int e = 0; e < this->elementCount(); ++e)
    {
      this->extract(e, net.data(), channels, patches[e].coeffs().data(), work.data());
    }
    return patches;
  }

  /// Extracts element `e` of a net of the right size into `out` (the element's coefficients);
  /// `work` holds twice as many values. Callers that spread elements over threads use it.
  void extract(int e, const T* net, int channels, T* out, T* work) const
  {
    int element[Dim];
    this->elementIndex(e, element);
    const T* matrices[Dim];
    int first[Dim];
    for (int d = 0; d < Dim; ++d)
    {
      matrices[d] = this->Operators[d].matrix(element[d]);
      first[d] = this->Operators[d].firstBasis[element[d]];
    }
    extractElement<T, Dim>(net, this->NetSize, channels, this->Degree, matrices, first, out, work);
  }

private:
  ExtractionOperator1D<T> Operators[Dim];
  int NetSize[Dim] = {};
  int Degree[Dim] = {};
};

/// Bézier patches of a B-spline patch (validates knots and net size).
template<class T, int Dim>
std::vector<BezierPatch<T, Dim>> extractBezier(const BSplinePatch<T, Dim>& patch)
{
  return BezierExtraction<T, Dim>(patch.knots, patch.degree, patch.netSize)
    .apply(patch.net, patch.channels);
}

} // namespace iga
