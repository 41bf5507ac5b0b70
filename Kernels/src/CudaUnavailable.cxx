// The CUDA driver's stand-in for builds without nvcc.
#include "CudaEngine.h"

namespace iga
{
namespace sst
{
namespace cuda
{

bool usable(std::string& why)
{
  why = "IGAView was built without CUDA";
  return false;
}

void render(const Scene&, const View&, const Settings&, GBuffer&, FrameReport&)
{
  throw Failure("IGAView was built without CUDA");
}

void renderNurbs(const NurbsVolumes&, const View&, const Settings&, GBuffer&, FrameReport&)
{
  throw Failure("IGAView was built without CUDA");
}

} // namespace cuda
} // namespace sst
} // namespace iga
