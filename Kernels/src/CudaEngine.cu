// The CUDA driver: the device driver of DeviceDriver.h on Thrust's CUDA system, one engine per
// process whose device arrays persist across frames, and CUDA errors turned into Failure so
// that the dispatcher redoes the frame on the CPU.
#include "CudaEngine.h"
#include "DeviceDriver.h"

#include <cuda_runtime.h>
#include <thrust/system/system_error.h>

#include <memory>
#include <mutex>
#include <new>

namespace iga
{
namespace sst
{
namespace cuda
{

namespace
{

std::mutex& engineMutex()
{
  static std::mutex mutex;
  return mutex;
}

/// The process's engine, created on first use; its arrays are the frame-to-frame memory pool.
std::unique_ptr<device::Driver>& engine()
{
  static std::unique_ptr<device::Driver> driver;
  return driver;
}

/// Why the GPU can no longer be used in this process, empty while it can: a kernel fault
/// leaves the context failing every call until the process ends. Guarded by engineMutex().
std::string& contextFailure()
{
  static std::string why;
  return why;
}

} // namespace

bool usable(std::string& why)
{
  // Asked once: the answer does not change while the process runs.
  static const std::string problem = []() -> std::string
  {
    int count = 0;
    const cudaError_t status = cudaGetDeviceCount(&count);
    if (status != cudaSuccess)
    {
      cudaGetLastError(); // clear the sticky error of a missing driver
      return std::string("no usable CUDA device (") + cudaGetErrorString(status) + ")";
    }
    return count > 0 ? std::string() : std::string("no CUDA device present");
  }();
  std::lock_guard<std::mutex> lock(engineMutex());
  why = problem.empty() ? contextFailure() : problem;
  return why.empty();
}

namespace
{

/// After a CUDA error in a frame. When the context survived (out of memory, a launch the device
/// refused), the engine is dropped and its memory given back: its arrays may be in any state.
/// When it did not (a kernel fault: every later call fails with the same error), the engine is
/// abandoned, since freeing into a failed context is pointless, and the GPU is not used again.
void recover(const std::string& what)
{
  cudaGetLastError(); // clears an error that did not break the context
  const bool intact = cudaDeviceSynchronize() == cudaSuccess && cudaGetLastError() == cudaSuccess;
  if (intact)
  {
    engine().reset();
    device::temporaryPool().trim();
  }
  else
  {
    engine().release();
    contextFailure() = "the CUDA context failed earlier (" + what + ")";
  }
}

/// Runs `frame` on the process's engine; CUDA errors become Failure.
template<class Frame>
void guarded(Frame frame)
{
  std::lock_guard<std::mutex> lock(engineMutex());
  try
  {
    if (!engine())
    {
      engine().reset(new device::Driver());
    }
    frame(*engine());
    device::check(cudaDeviceSynchronize(), "end of frame");
  }
  catch (const thrust::system_error& e)
  {
    recover(e.what());
    throw Failure(e.what());
  }
  catch (const std::bad_alloc&)
  {
    // Device, page-locked or host memory: std::bad_alloc does not say which.
    recover("out of memory");
    throw Failure("out of memory");
  }
}

} // namespace

void render(
  const Scene& scene, const View& view, const Settings& settings, GBuffer& out, FrameReport& report)
{
  guarded([&](device::Driver& driver) { driver.render(scene, view, settings, out, report); });
}

void renderNurbs(const NurbsVolumes& volumes, const View& view, const Settings& settings,
  GBuffer& out, FrameReport& report)
{
  guarded(
    [&](device::Driver& driver) { driver.renderNurbs(volumes, view, settings, out, report); });
}

} // namespace cuda
} // namespace sst
} // namespace iga
