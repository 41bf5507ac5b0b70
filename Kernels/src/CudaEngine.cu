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
  why = problem;
  return problem.empty();
}

namespace
{

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
    const cudaError_t status = cudaDeviceSynchronize();
    if (status != cudaSuccess)
    {
      throw Failure(cudaGetErrorString(status));
    }
  }
  catch (const thrust::system_error& e)
  {
    // Its arrays may be in any state: start afresh next frame. After a sticky error freeing
    // them could throw from a destructor, so they are abandoned instead.
    engine().release();
    cudaGetLastError();
    throw Failure(e.what());
  }
  catch (const std::bad_alloc&)
  {
    engine().reset(); // the context is intact: give the memory back
    device::temporaryPool().trim();
    cudaGetLastError();
    throw Failure("out of device memory");
  }
}

} // namespace

void render(const std::vector<BezierVolume<double>>& patches, const View& view,
  const Settings& settings, GBuffer& out, FrameReport& report)
{
  guarded([&](device::Driver& driver) { driver.render(patches, view, settings, out, report); });
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
