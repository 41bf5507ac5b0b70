// The Kernels math compiled by nvcc and run on the device must agree with the host (double)
// results. Without a usable CUDA device every test reports SKIPPED.
#include "TestPatches.h"

#include "iga/Camera.h"
#include "iga/Datasets.h"
#include "iga/sst/PixelProblem.h"

#include <cuda_runtime.h>

using namespace igatest;

namespace
{

bool deviceAvailable(std::string& why)
{
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess)
  {
    why = std::string("no usable CUDA device: ") + cudaGetErrorString(status);
    return false;
  }
  if (count == 0)
  {
    why = "no CUDA device present";
    return false;
  }
  return true;
}

#define REQUIRE_DEVICE()                                                                           \
  do                                                                                               \
  {                                                                                                \
    std::string why;                                                                               \
    if (!deviceAvailable(why))                                                                     \
    {                                                                                              \
      GTEST_SKIP() << why;                                                                         \
    }                                                                                              \
  } while (0)

/// Per patch: evaluate at u, split at the midpoint and evaluate child 5 at u, solve Newton for
/// the target, certify uniqueness. Output per patch: 5 values, 5 child values, 3 u, status,
/// certified.
__global__ void patchKernel(const float* coeffs, int count, int valueCount, const float* params,
  const float* targets, float* out, float* children)
{
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count)
    return;
  const int degree[3] = { 3, 2, 3 };
  const iga::VolumeView<const float> patch(coeffs + i * valueCount, degree, 5);
  float* result = out + i * 15;
  iga::evaluateHomogeneous(patch, params + 3 * i, result, static_cast<float*>(nullptr));
  float* mine = children + static_cast<size_t>(i) * 8 * valueCount;
  iga::splitMidpoint(patch, mine);
  const iga::VolumeView<const float> child(mine + 5 * valueCount, degree, 5);
  iga::evaluateHomogeneous(child, params + 3 * i, result + 5, static_cast<float*>(nullptr));
  const iga::RationalRow rows[3] = { { 0, 3 }, { 1, 3 }, { 4, 3 } };
  const float tolerance[3] = { 1e-4f, 1e-4f, 1e-4f };
  const float u0[3] = { 0.5f, 0.5f, 0.5f };
  const auto solved = iga::solveNewton<float, 3>(patch, rows, targets + 3 * i, tolerance, u0);
  for (int d = 0; d < 3; ++d)
    result[10 + d] = solved.u[d];
  result[13] = float(static_cast<int>(solved.status));
  result[14] = iga::certifyUniqueRoot<float, 3>(patch, rows) ? 1.0f : 0.0f;
}

TEST(KernelsCuda, DeviceResultsMatchHost)
{
  REQUIRE_DEVICE();
  std::mt19937 rng(60);
  std::uniform_real_distribution<double> param(0.1, 0.9);
  const int count = 256;
  std::vector<iga::BezierVolume<float>> patches;
  std::vector<float> coeffs, params, targets;
  std::vector<double> expectedU;
  for (int i = 0; i < count; ++i)
  {
    patches.push_back(nearAffinePatch<float>(rng, 0.1));
    coeffs.insert(coeffs.end(), patches.back().coeffs().begin(), patches.back().coeffs().end());
    const double u[3] = { param(rng), param(rng), param(rng) };
    const auto v = evaluateEuclidean(patches.back().view(), u);
    targets.insert(targets.end(), { float(v[0]), float(v[1]), float(v[4]) });
    for (int d = 0; d < 3; ++d)
    {
      params.push_back(float(u[d]));
      expectedU.push_back(u[d]);
    }
  }
  const int valueCount = patches[0].view().valueCount();
  float *dCoeffs, *dParams, *dTargets, *dOut, *dChildren;
  ASSERT_EQ(cudaMalloc(&dCoeffs, coeffs.size() * sizeof(float)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dParams, params.size() * sizeof(float)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dTargets, targets.size() * sizeof(float)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dOut, count * 15 * sizeof(float)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dChildren, size_t(count) * 8 * valueCount * sizeof(float)), cudaSuccess);
  cudaMemcpy(dCoeffs, coeffs.data(), coeffs.size() * sizeof(float), cudaMemcpyHostToDevice);
  cudaMemcpy(dParams, params.data(), params.size() * sizeof(float), cudaMemcpyHostToDevice);
  cudaMemcpy(dTargets, targets.data(), targets.size() * sizeof(float), cudaMemcpyHostToDevice);
  patchKernel<<<(count + 63) / 64, 64>>>(
    dCoeffs, count, valueCount, dParams, dTargets, dOut, dChildren);
  ASSERT_EQ(cudaDeviceSynchronize(), cudaSuccess);
  std::vector<float> out(count * 15);
  cudaMemcpy(out.data(), dOut, out.size() * sizeof(float), cudaMemcpyDeviceToHost);
  for (float* p : { dCoeffs, dParams, dTargets, dOut, dChildren })
    cudaFree(p);

  for (int i = 0; i < count; ++i)
  {
    const double u[3] = { double(params[3 * i]), double(params[3 * i + 1]),
      double(params[3 * i + 2]) };
    const auto reference = evaluateDirect(patches[i].view(), u);
    double childU[3];
    iga::childToParentParameter<double, 3>(5, u, childU);
    const auto childReference = evaluateDirect(patches[i].view(), childU);
    const double scale = std::max(1.0, maxAbs(reference));
    for (int c = 0; c < 5; ++c)
    {
      EXPECT_NEAR(out[i * 15 + c], double(reference[c]), 1e-5 * scale) << "patch " << i;
      EXPECT_NEAR(out[i * 15 + 5 + c], double(childReference[c]), 1e-5 * scale) << "patch " << i;
    }
    ASSERT_EQ(out[i * 15 + 13], float(static_cast<int>(iga::NewtonStatus::Converged)))
      << "patch " << i;
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(out[i * 15 + 10 + d], expectedU[3 * i + d], 1e-3) << "patch " << i;
    const bool hostCertified = iga::certifyUniqueRoot<float, 3>(patches[i].view(), kPixelRows);
    EXPECT_EQ(out[i * 15 + 14] == 1.0f, hostCertified) << "patch " << i;
  }
}

/// The SST pixel stage on the device: node analysis and tuple solves for every pixel of a small
/// image against the screen patch of a Marsden sphere's octant.
__global__ void tupleKernel(const double* node, int width, int height, int* outcome, double* depth)
{
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= width * height)
    return;
  const int degree[3] = { 3, 3, 3 };
  const iga::VolumeView<const double> view(node, degree, iga::sst::kScreenChannels);
  const auto info = iga::sst::analyzeNode(view, 0.0);
  const double tolerance[3] = { 1e-3, 1e-3, 1e-9 };
  double u[3], ndc = 0;
  outcome[p] = int(iga::sst::solveTuple(view, info, p % width, p / width, 0.0, tolerance, u, ndc));
  depth[p] = ndc;
}

/// Screen-space sub-patches of the degree-3 sphere volume at subdivision level 3, seen by a
/// 48x48 camera; returns the first that is certified and hit by some pixel, with its analysis.
std::vector<double> pickCertifiedNode(int width, int height)
{
  const auto set = iga::makeMarsdenSphere<double>(3);
  iga::Camera camera;
  camera.position = { 3, 2.5, 2 };
  camera.focalPoint = { 0, 0, 0 };
  camera.viewUp = { 0, 0, 1 };
  camera.clippingRange[0] = 1;
  camera.clippingRange[1] = 10;
  glm::dmat4 window(1.0);
  window[0][0] = window[3][0] = 0.5 * width;
  window[1][1] = window[3][1] = 0.5 * height;
  const glm::dmat4 M = window * iga::worldToClip(camera, double(width) / height);
  const auto world = set.patches[0].view();
  const int count = world.pointCount() * iga::sst::kScreenChannels;
  std::vector<double> nodes(count);
  iga::sst::makeScreenPatch<double>(world, M, iga::kFirstAttributeChannel, nodes.data());
  const int degree[3] = { 3, 3, 3 };
  for (int level = 0; level < 3; ++level)
  {
    std::vector<double> children(nodes.size() * 8);
    for (size_t n = 0; n < nodes.size() / count; ++n)
      iga::splitMidpoint<double, 3>(
        iga::VolumeView<const double>(nodes.data() + n * count, degree, iga::sst::kScreenChannels),
        children.data() + 8 * n * count);
    nodes.swap(children);
  }
  const double tolerance[3] = { 1e-3, 1e-3, 1e-9 };
  for (size_t n = 0; n < nodes.size() / count; ++n)
  {
    const iga::VolumeView<const double> view(
      nodes.data() + n * count, degree, iga::sst::kScreenChannels);
    const auto info = iga::sst::analyzeNode(view, 0.0);
    if (!info.certified)
      continue;
    for (int p = 0; p < width * height; ++p)
    {
      double u[3], ndc;
      if (iga::sst::solveTuple(view, info, p % width, p / width, 0.0, tolerance, u, ndc) ==
          iga::sst::TupleOutcome::Hit)
        return std::vector<double>(nodes.begin() + n * count, nodes.begin() + (n + 1) * count);
    }
  }
  return {};
}

TEST(KernelsCuda, PixelStageMatchesHost)
{
  REQUIRE_DEVICE();
  const int width = 48, height = 48;
  const std::vector<double> screen = pickCertifiedNode(width, height);
  ASSERT_FALSE(screen.empty()) << "no certified sub-patch with hits in the test scene";
  double *dNode, *dDepth;
  int* dOutcome;
  ASSERT_EQ(cudaMalloc(&dNode, screen.size() * sizeof(double)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dDepth, width * height * sizeof(double)), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&dOutcome, width * height * sizeof(int)), cudaSuccess);
  cudaMemcpy(dNode, screen.data(), screen.size() * sizeof(double), cudaMemcpyHostToDevice);
  tupleKernel<<<(width * height + 63) / 64, 64>>>(dNode, width, height, dOutcome, dDepth);
  ASSERT_EQ(cudaDeviceSynchronize(), cudaSuccess);
  std::vector<int> outcome(width * height);
  std::vector<double> depth(width * height);
  cudaMemcpy(outcome.data(), dOutcome, outcome.size() * sizeof(int), cudaMemcpyDeviceToHost);
  cudaMemcpy(depth.data(), dDepth, depth.size() * sizeof(double), cudaMemcpyDeviceToHost);
  cudaFree(dNode);
  cudaFree(dDepth);
  cudaFree(dOutcome);

  const int degree[3] = { 3, 3, 3 };
  const iga::VolumeView<const double> view(screen.data(), degree, iga::sst::kScreenChannels);
  const auto info = iga::sst::analyzeNode(view, 0.0);
  const double tolerance[3] = { 1e-3, 1e-3, 1e-9 };
  int hits = 0;
  for (int p = 0; p < width * height; ++p)
  {
    double u[3], ndc = 0;
    const int host =
      int(iga::sst::solveTuple(view, info, p % width, p / width, 0.0, tolerance, u, ndc));
    EXPECT_EQ(outcome[p], host) << "pixel " << p;
    if (host == int(iga::sst::TupleOutcome::Hit))
    {
      ++hits;
      EXPECT_NEAR(depth[p], ndc, 1e-9) << "pixel " << p;
    }
  }
  EXPECT_GT(hits, 0);
}

} // namespace
