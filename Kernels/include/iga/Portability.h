// One macro makes every numeric function callable from host code (g++) and CUDA device code
// (nvcc), so the CPU and GPU engines share a single source.
#pragma once

#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(__CUDACC__)
#define IGA_HD __host__ __device__
#else
#define IGA_HD
#endif

namespace iga
{

/// Highest polynomial degree per parametric direction that the kernels accept.
constexpr int kMaxDegree = 16;
constexpr int kMaxOrder = kMaxDegree + 1;

// Overloads instead of std:: math so that the same call compiles in device code.
IGA_HD inline float absValue(float x)
{
  return fabsf(x);
}
IGA_HD inline double absValue(double x)
{
  return fabs(x);
}
IGA_HD inline float squareRoot(float x)
{
  return sqrtf(x);
}
IGA_HD inline double squareRoot(double x)
{
  return sqrt(x);
}

/// True for finite numbers; false for NaN and +-inf (x - x is NaN exactly for those).
template<class T>
IGA_HD inline bool isFinite(T x)
{
  return x - x == T(0);
}

template<class T>
IGA_HD inline T minValue(T a, T b)
{
  return b < a ? b : a;
}

template<class T>
IGA_HD inline T maxValue(T a, T b)
{
  return a < b ? b : a;
}

/// Machine epsilon without <limits>, which is host-only in older CUDA toolchains.
template<class T>
struct Epsilon;
template<>
struct Epsilon<float>
{
  static constexpr float value = 1.1920929e-7f;
};
template<>
struct Epsilon<double>
{
  static constexpr double value = 2.220446049250313e-16;
};

/// 2^-e, exactly: built from its exponent bits for e in [0, 1022] (a library call to ldexp cost
/// more than the arithmetic around it in the hot loops that place roots in their patches).
IGA_HD inline double inversePowerOfTwo(int e)
{
  if (e < 0 || e > 1022)
  {
    return ldexp(1.0, -e);
  }
  const uint64_t bits = uint64_t(1023 - e) << 52;
  double value;
  memcpy(&value, &bits, sizeof value);
  return value;
}

/// The power of two that brings a magnitude into [0.5, 1), exactly (1 for 0 and non-finite
/// values; subnormal magnitudes only as far as a finite factor, 2^1023, takes them): scaling by
/// it changes no quotient and keeps products of such values in range.
IGA_HD inline double unitPowerOfTwo(double magnitude)
{
  int exponent = 0;
  frexp(magnitude, &exponent);
  return magnitude > 0 && isFinite(magnitude) ? ldexp(1.0, -exponent < 1023 ? -exponent : 1023)
                                              : 1.0;
}

/// Binomial coefficient C(n, k) for the small n used by Bernstein bases (exact in double up to
/// n = 66).
IGA_HD inline double binomial(int n, int k)
{
  if (k < 0 || k > n)
  {
    return 0.0;
  }
  if (k > n - k)
  {
    k = n - k;
  }
  double result = 1.0;
  for (int i = 1; i <= k; ++i)
  {
    result = result * double(n - k + i) / double(i);
  }
  return result;
}

} // namespace iga
