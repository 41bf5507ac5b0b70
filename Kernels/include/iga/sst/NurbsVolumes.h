// NURBS volumes as the engine takes them: per volume its Bézier extraction and its current
// control net. A header of its own, without the engine, for code that only hands them over.
#pragma once

#include "iga/BSpline.h"
#include "iga/NurbsSet.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace iga
{
namespace sst
{

/// NURBS / B-spline volumes as they deform: per volume its Bézier extraction (built once from
/// the knots) and its current control net (homogeneous, standard layout, first direction
/// fastest, `channels` values per point). The engine draws their Bézier elements, numbered
/// volume by volume in each extraction's element order (first direction fastest): Hit::patch
/// is that number. The CUDA driver extracts the elements on the device, so a deforming volume
/// sends only its moved net each frame.
struct NurbsVolumes
{
  std::vector<const BezierExtraction<double, 3>*> extractions;
  std::vector<const std::vector<double>*> nets;
  int channels = 0;
  /// Names the extractions (knots, degrees, net sizes) for drivers that keep them on a GPU;
  /// equal non-zero versions reuse the copy there. Settings::dataVersion names the nets.
  uint64_t extractionVersion = 0;
};

/// Checks NURBS volumes: one net per extraction, of the extraction's size, finite values and
/// positive weights, and elements' weights within kMaxWeightRatio (skewedElementProblem). Their
/// Bézier elements are then valid too: extraction takes convex combinations of control points.
/// Throws std::invalid_argument naming the volume and point or element.
inline void checkNurbsVolumes(const NurbsVolumes& volumes)
{
  if (volumes.nets.size() != volumes.extractions.size())
  {
    throw std::invalid_argument(std::to_string(volumes.extractions.size()) + " extractions but " +
                                std::to_string(volumes.nets.size()) + " control nets");
  }
  if (volumes.channels < kFirstAttributeChannel + 1)
  {
    throw std::invalid_argument("control points have " + std::to_string(volumes.channels) +
                                " channels; position, weight and an attribute need " +
                                std::to_string(kFirstAttributeChannel + 1));
  }
  for (size_t v = 0; v < volumes.nets.size(); ++v)
  {
    const std::string name = "volume " + std::to_string(v) + ": ";
    if (!volumes.extractions[v] || !volumes.nets[v])
    {
      throw std::invalid_argument(name + "no extraction or no control net");
    }
    const auto& extraction = *volumes.extractions[v];
    int netSize[3];
    for (int d = 0; d < 3; ++d)
    {
      const int degree = extraction.direction(d).degree;
      if (degree < 1 || degree > kMaxDegree)
      {
        throw std::invalid_argument(name + "degree " + std::to_string(degree) + " is outside 1.." +
                                    std::to_string(kMaxDegree));
      }
      netSize[d] = extraction.netSize(d);
    }
    std::string problem = checkControlNet<double, 3>(netSize, volumes.channels, *volumes.nets[v]);
    if (problem.empty())
    {
      problem = skewedElementProblem<double, 3>(extraction, *volumes.nets[v], volumes.channels);
    }
    if (!problem.empty())
    {
      throw std::invalid_argument(name + problem);
    }
  }
}

} // namespace sst
} // namespace iga
