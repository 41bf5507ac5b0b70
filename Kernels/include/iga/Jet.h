// Second-order jets (value, gradient and Hessian in the parameters) of a patch's homogeneous
// channels and of their rational quotients, on either driver: for curvatures and for the
// engine's quadratic model of a node around its centre.
#pragma once

#include "iga/BezierPatch.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace iga
{

/// Value, gradient and Hessian in u of a function of a patch's parameters (entries past the
/// patch's dimension are zero).
template<class T>
struct Jet
{
  T value = T(0);
  glm::vec<3, T> gradient = glm::vec<3, T>(T(0));
  glm::mat<3, 3, T> hessian = glm::mat<3, 3, T>(T(0));
};

namespace detail
{
/// Bernstein basis of degree n at t with first and second derivatives.
template<class T>
IGA_HD void bernsteinWithSecond(int n, T t, T* b, T* d1, T* d2)
{
  bernsteinBasis(n, t, b, d1);
  for (int i = 0; i <= n; ++i)
  {
    d2[i] = T(0);
  }
  if (n < 2)
  {
    return;
  }
  T lower[kMaxOrder];
  bernsteinBasis(n - 2, t, lower, static_cast<T*>(nullptr));
  for (int i = 0; i <= n; ++i)
  {
    const T a = i >= 2 ? lower[i - 2] : T(0);
    const T b1 = i >= 1 && i - 1 <= n - 2 ? lower[i - 1] : T(0);
    const T c = i <= n - 2 ? lower[i] : T(0);
    d2[i] = T(n * (n - 1)) * (a - T(2) * b1 + c);
  }
}
} // namespace detail

/// The jets at u of `count` homogeneous channels of a patch, channels[k] into jets[k]. The
/// tensor product is contracted one direction at a time, keeping the partial derivatives of
/// total order up to two.
template<class T, int Dim>
IGA_HD void channelJets(
  const PatchView<const T, Dim>& patch, const T* u, const int* channels, int count, Jet<T>* jets)
{
  // basis[d][a]: the Bernstein basis of direction d differentiated a times; a surface's third
  // direction is of degree 0.
  T basis[3][3][kMaxOrder];
  int orders[3] = { 1, 1, 1 };
  for (int d = 0; d < 3; ++d)
  {
    if (d < Dim)
    {
      orders[d] = patch.order(d);
      detail::bernsteinWithSecond(patch.degree[d], u[d], basis[d][0], basis[d][1], basis[d][2]);
    }
    else
    {
      basis[d][0][0] = T(1);
      basis[d][1][0] = basis[d][2][0] = T(0);
    }
  }
  for (int k = 0; k < count; ++k)
  {
    // partial[a][b][c]: differentiated a times in u, b in v, c in w (a + b + c <= 2).
    T partial[3][3][3] = {};
    for (int l = 0; l < orders[2]; ++l)
    {
      T plane[3][3] = {};
      for (int j = 0; j < orders[1]; ++j)
      {
        T line[3] = {};
        const T* p = patch.coeffs + (l * orders[1] + j) * orders[0] * patch.channels + channels[k];
        for (int i = 0; i < orders[0]; ++i)
        {
          for (int a = 0; a < 3; ++a)
          {
            line[a] += basis[0][a][i] * p[i * patch.channels];
          }
        }
        for (int a = 0; a < 3; ++a)
        {
          for (int b = 0; a + b < 3; ++b)
          {
            plane[a][b] += basis[1][b][j] * line[a];
          }
        }
      }
      for (int a = 0; a < 3; ++a)
      {
        for (int b = 0; a + b < 3; ++b)
        {
          for (int c = 0; a + b + c < 3; ++c)
          {
            partial[a][b][c] += basis[2][c][l] * plane[a][b];
          }
        }
      }
    }
    // The partial derivative in directions r and s; -1 for none.
    auto at = [&](int r, int s)
    {
      const int order[3] = { (r == 0) + (s == 0), (r == 1) + (s == 1), (r == 2) + (s == 2) };
      return partial[order[0]][order[1]][order[2]];
    };
    jets[k].value = partial[0][0][0];
    for (int r = 0; r < 3; ++r)
    {
      jets[k].gradient[r] = at(r, -1);
      for (int s = 0; s < 3; ++s)
      {
        jets[k].hessian[r][s] = at(r, s);
      }
    }
  }
}

/// The jet of numerator / denominator (the quotient rule to second order).
template<class T>
IGA_HD Jet<T> rationalJet(const Jet<T>& n, const Jet<T>& d)
{
  Jet<T> q;
  q.value = n.value / d.value;
  q.gradient = (n.gradient - q.value * d.gradient) / d.value;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      q.hessian[i][j] = (n.hessian[i][j] - q.gradient[i] * d.gradient[j] -
                          q.gradient[j] * d.gradient[i] - q.value * d.hessian[i][j]) /
                        d.value;
    }
  }
  return q;
}

} // namespace iga
