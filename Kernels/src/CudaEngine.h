// The CUDA driver of the shared-subdivision-tree engine, as the host dispatcher sees it. Built
// from CudaEngine.cu where nvcc is available, from CudaUnavailable.cxx otherwise.
#pragma once

#include "iga/sst/Engine.h"

#include <stdexcept>
#include <string>

namespace iga
{
namespace sst
{
namespace cuda
{

/// A CUDA error during a frame (out of memory, launch failure): the frame is redone on the CPU.
struct Failure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Whether frames can run on a GPU; if not, `why` says so in a few words.
bool usable(std::string& why);

/// The shared-subdivision-tree frame on the GPU. Throws std::invalid_argument for bad input,
/// as the CPU path does, and Failure for CUDA errors.
void render(const Scene& scene, const View& view, const Settings& settings, GBuffer& out,
  FrameReport& report);

/// The same for NURBS volumes, whose Bézier elements are extracted on the device.
void renderNurbs(const NurbsVolumes& volumes, const View& view, const Settings& settings,
  GBuffer& out, FrameReport& report);

} // namespace cuda
} // namespace sst
} // namespace iga
