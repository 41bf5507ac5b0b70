// Newton's method for the SST pixel problem: find u in a patch's domain with
// F(u) = (N_r(u) / D_r(u))_r = target, each row within its tolerance. Dim = 3 for volumes
// ((x, y, attribute) against (b_s, b_t, isovalue)), Dim = 2 for surfaces ((x, y) against a pixel).
#pragma once

#include "iga/Bounds.h"

namespace iga
{

enum class NewtonStatus
{
  Converged,
  SingularJacobian, ///< the Jacobian became numerically singular
  LeftDomain,       ///< an iterate left the patch's parameter domain
  NoConvergence,    ///< the iteration limit was reached
  InvalidValue,     ///< a denominator vanished or a value was not finite
};

template<class T, int Dim>
struct NewtonResult
{
  NewtonStatus status = NewtonStatus::NoConvergence;
  T u[Dim] = {};
  /// F - target at the last iterate evaluated (a converged u is one Newton step beyond it)
  glm::vec<Dim, T> residual = glm::vec<Dim, T>(T(0));
  int iterations = 0;
};

template<class T>
struct NewtonSettings
{
  int maxIterations = 20;
  /// How far outside [0,1] an iterate may stray before the patch is declared left; neighbouring
  /// patches own solutions beyond that.
  T domainSlack = T(1e-3);
  /// Parametric step size below which the iteration has converged.
  T stepTolerance = T(64) * Epsilon<T>::value;
};

/// Whether a parameter lies in [0, 1] widened by the domain slack (not NaN).
template<class T>
IGA_HD bool withinDomain(T u, T slack)
{
  return u >= -slack && u <= T(1) + slack;
}

/// The converged iteration's Newton step, taken without evaluating again: its residual is about
/// the square of the one tested, so a root ends accurate far beyond the acceptance tests at no
/// evaluation's cost. The values follow it to first order. Not taken where it would leave the
/// domain or the Jacobian is singular.
template<class T, int Dim>
IGA_HD void takeFinalStep(NewtonResult<T, Dim>& result, const glm::mat<Dim, Dim, T>& gradients,
  T* values, const T* derivatives, int channels, int leading, const NewtonSettings<T>& settings)
{
  glm::mat<Dim, Dim, T> inverse;
  if (!invertMatrix<T, Dim>(glm::transpose(gradients), inverse))
  {
    return;
  }
  const glm::vec<Dim, T> step = -(inverse * result.residual);
  for (int d = 0; d < Dim; ++d)
  {
    if (!withinDomain(result.u[d] + step[d], settings.domainSlack))
    {
      return;
    }
  }
  for (int d = 0; d < Dim; ++d)
  {
    result.u[d] += step[d];
    for (int c = 0; c < leading; ++c)
    {
      values[c] += derivatives[d * channels + c] * step[d];
    }
  }
}

/// Solves F(u) = target from the start point u0. Converged means |F_r(u) - target_r| <=
/// tolerance_r for every row and, besides, the last step was below the step tolerance or the
/// residual is 1000 times smaller than the tolerance, so the root is accurate well beyond the
/// acceptance window. A converged u lies in [0,1]^Dim widened by the domain slack: a root on a
/// face shared by two patches is found in both, and callers that keep every hit merge them.
/// Only the channels up to the highest that a row reads are evaluated. On convergence
/// `valuesAtRoot`, if given, receives those homogeneous values at u (the last evaluation, so
/// callers need not evaluate again). Both then take the converged iteration's step
/// (takeFinalStep); `residual` stays the one tested, before it.
template<class T, int Dim>
IGA_HD NewtonResult<T, Dim> solveNewton(const PatchView<const T, Dim>& patch,
  const RationalRow* rows, const T* target, const T* tolerance, const T* u0,
  const NewtonSettings<T>& settings = {}, T* valuesAtRoot = nullptr)
{
  NewtonResult<T, Dim> result;
  constexpr int kMaxChannels = 16;
  const int channels = patch.channels;
  if (channels > kMaxChannels)
  {
    result.status = NewtonStatus::InvalidValue;
    return result;
  }
  for (int d = 0; d < Dim; ++d)
  {
    result.u[d] = u0[d];
  }
  const int leading = leadingChannelsOf<Dim>(rows);
  T values[kMaxChannels];
  T derivatives[Dim * kMaxChannels];
  T lastStep = T(1);
  for (int iteration = 0; iteration <= settings.maxIterations; ++iteration)
  {
    result.iterations = iteration;
    evaluateHomogeneous(patch, result.u, values, derivatives, leading);
    glm::mat<Dim, Dim, T> gradients; // column r: the gradient of row r (J transposed)
    bool small = true, tiny = true;
    for (int r = 0; r < Dim; ++r)
    {
      if (!(absValue(values[rows[r].denominator]) > T(0)))
      {
        result.status = NewtonStatus::InvalidValue;
        return result;
      }
      const T f = rationalValue<T, Dim>(
        values, derivatives, channels, rows[r].numerator, rows[r].denominator, &gradients[r][0]);
      result.residual[r] = f - target[r];
      if (!isFinite(result.residual[r]))
      {
        result.status = NewtonStatus::InvalidValue;
        return result;
      }
      small = small && absValue(result.residual[r]) <= tolerance[r];
      tiny = tiny && absValue(result.residual[r]) <= T(1e-3) * tolerance[r];
    }
    const bool converged = tiny || (small && lastStep <= settings.stepTolerance);
    if (converged || iteration == settings.maxIterations)
    {
      if (converged)
      {
        result.status = NewtonStatus::Converged;
        takeFinalStep(result, gradients, values, derivatives, channels, leading, settings);
        for (int c = 0; valuesAtRoot && c < leading; ++c)
        {
          valuesAtRoot[c] = values[c];
        }
      }
      return result;
    }
    glm::mat<Dim, Dim, T> inverse;
    if (!invertMatrix<T, Dim>(glm::transpose(gradients), inverse))
    {
      result.status = NewtonStatus::SingularJacobian;
      return result;
    }
    const glm::vec<Dim, T> step = -(inverse * result.residual);
    T stepNorm = T(0);
    bool outside = false;
    for (int d = 0; d < Dim; ++d)
    {
      result.u[d] += step[d];
      stepNorm = maxValue(stepNorm, absValue(step[d]));
      outside = outside || !withinDomain(result.u[d], settings.domainSlack);
    }
    if (outside)
    {
      result.status = NewtonStatus::LeftDomain;
      return result;
    }
    lastStep = stepNorm;
  }
  return result;
}

} // namespace iga
