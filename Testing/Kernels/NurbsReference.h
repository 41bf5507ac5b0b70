// Cox-de Boor evaluation of B-spline / NURBS patches: the textbook definition, independent of
// the blossom-based extraction it checks. Shared by the Kernels and Filters tests (VTK-free).
#pragma once

#include "iga/NurbsSet.h"

#include <vector>

namespace igatest
{

/// All B-splines N_{i,p}(u), i = 0..count-1, by the Cox-de Boor recursion (0/0 = 0); at the end
/// of the domain the last non-empty span is used.
inline std::vector<double> coxDeBoor(const std::vector<double>& t, int p, int count, double u)
{
  const double end = t[count];
  std::vector<double> N(t.size() - 1, 0.0);
  for (size_t i = 0; i + 1 < t.size(); ++i)
  {
    const bool inside = t[i] <= u && u < t[i + 1];
    const bool atEnd = u == end && t[i] < t[i + 1] && t[i + 1] == end;
    N[i] = inside || atEnd ? 1.0 : 0.0;
  }
  for (int k = 1; k <= p; ++k)
  {
    for (size_t i = 0; i + k + 1 < t.size(); ++i)
    {
      double value = 0;
      if (t[i + k] > t[i])
        value += (u - t[i]) / (t[i + k] - t[i]) * N[i];
      if (t[i + k + 1] > t[i + 1])
        value += (t[i + k + 1] - u) / (t[i + k + 1] - t[i + 1]) * N[i + 1];
      N[i] = value;
    }
  }
  N.resize(count);
  return N;
}

/// Euclidean values (x, y, z, attributes...) of a patch at global parameter u (Dim values).
/// Works in double precision whatever the patch's scalar type.
template<class T, int Dim>
std::vector<double> evaluateNurbs(const iga::BSplinePatch<T, Dim>& patch, const double* u)
{
  std::vector<double> basis[Dim];
  for (int d = 0; d < Dim; ++d)
    basis[d] = coxDeBoor(std::vector<double>(patch.knots[d].begin(), patch.knots[d].end()),
      patch.degree[d], patch.netSize[d], u[d]);
  std::vector<double> h(patch.channels, 0.0);
  const size_t points = iga::controlPointCount(patch);
  for (size_t p = 0; p < points; ++p)
  {
    double b = 1;
    size_t rest = p;
    for (int d = 0; d < Dim; ++d)
    {
      b *= basis[d][rest % patch.netSize[d]];
      rest /= patch.netSize[d];
    }
    for (int c = 0; c < patch.channels; ++c)
      h[c] += b * double(patch.net[p * patch.channels + c]);
  }
  std::vector<double> result;
  for (int c = 0; c < patch.channels; ++c)
    if (c != iga::kWeightChannel)
      result.push_back(h[c] / h[iga::kWeightChannel]);
  return result;
}

} // namespace igatest
