// What the device driver needs of the CUDA runtime: arrays on the device that grow without
// initialising (a growing thrust::device_vector fills its new elements, one kernel and one
// synchronisation each), page-locked host buffers for transfers, the pool of Thrust's
// temporaries, device counters and stage times on the device's clock. Compiled by nvcc for the
// CUDA system and by g++ for Thrust's host system (the driver's logic tests).
#pragma once

#include "StageClock.h"
#include "iga/Portability.h"

#include <thrust/device_ptr.h>
#include <thrust/execution_policy.h>
#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
#include <cuda_runtime.h>
#include <thrust/system/cuda/error.h>
#include <thrust/system/cuda/execution_policy.h>
#include <thrust/system_error.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <utility>
#include <vector>

// The driver compiled for the CUDA system and for Thrust's host system (the logic tests) may
// meet in one binary: an inline namespace per system keeps their symbols apart.
#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
#define IGA_DEVICE_SYSTEM_BEGIN                                                                    \
  inline namespace cuda_system                                                                     \
  {
#else
#define IGA_DEVICE_SYSTEM_BEGIN                                                                    \
  inline namespace host_system                                                                     \
  {
#endif
#define IGA_DEVICE_SYSTEM_END }

namespace iga
{
namespace sst
{
namespace device
{
IGA_DEVICE_SYSTEM_BEGIN

#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
inline void check(cudaError_t status, const char* what)
{
  if (status != cudaSuccess)
  {
    throw thrust::system_error(status, thrust::cuda_category(), what);
  }
}

/// Throws std::bad_alloc when an allocation found no memory left, thrust::system_error for any
/// other failure: after a kernel fault every call fails with the fault's error, which is not
/// an out-of-memory error and must not be treated as one.
inline void checkAllocation(cudaError_t status, const char* what)
{
  if (status == cudaErrorMemoryAllocation)
  {
    cudaGetLastError();
    throw std::bad_alloc();
  }
  check(status, what);
}

/// Device memory.
inline void* allocateDevice(size_t bytes)
{
  void* block = nullptr;
  checkAllocation(cudaMalloc(&block, bytes), "device allocation");
  return block;
}

/// Its status is ignored: it runs in destructors, and after a kernel fault the memory goes with
/// the context anyway.
inline void freeDevice(void* block)
{
  cudaFree(block);
}

/// Device-to-device copy, ordered on the default stream (no host synchronisation).
inline void copyOnDevice(void* to, const void* from, size_t bytes)
{
  check(cudaMemcpyAsync(to, from, bytes, cudaMemcpyDeviceToDevice), "device copy");
}

/// Host-to-device and device-to-host copies; they return when the copy is complete.
inline void copyToDevice(void* to, const void* from, size_t bytes)
{
  check(cudaMemcpy(to, from, bytes, cudaMemcpyHostToDevice), "upload");
}

inline void copyToHost(void* to, const void* from, size_t bytes)
{
  check(cudaMemcpy(to, from, bytes, cudaMemcpyDeviceToHost), "download");
}

/// Page-locked host memory: transfers from and to it run at the bus's speed, without the
/// driver's bounce buffers.
inline void* allocatePinned(size_t bytes)
{
  void* block = nullptr;
  checkAllocation(cudaMallocHost(&block, bytes), "page-locked allocation");
  return block;
}

inline void freePinned(void* block)
{
  cudaFreeHost(block);
}
#else
inline void* allocateDevice(size_t bytes)
{
  void* block = std::malloc(bytes);
  if (!block)
  {
    throw std::bad_alloc();
  }
  return block;
}

inline void freeDevice(void* block)
{
  std::free(block);
}

inline void copyOnDevice(void* to, const void* from, size_t bytes)
{
  std::memmove(to, from, bytes);
}

inline void copyToDevice(void* to, const void* from, size_t bytes)
{
  std::memcpy(to, from, bytes);
}

inline void copyToHost(void* to, const void* from, size_t bytes)
{
  std::memcpy(to, from, bytes);
}

inline void* allocatePinned(size_t bytes)
{
  return allocateDevice(bytes);
}

inline void freePinned(void* block)
{
  std::free(block);
}
#endif

inline void copyOnHost(void* to, const void* from, size_t bytes)
{
  std::memcpy(to, from, bytes);
}

/// A growable block of trivially copyable elements in memory from `Allocate` and `Free`.
/// Growing keeps the contents and leaves new elements uninitialised; shrinking keeps the
/// allocation, so that a steady stream of frames allocates nothing.
template<class T, void* (*Allocate)(size_t), void (*Free)(void*),
  void (*Move)(void*, const void*, size_t)>
class Block
{
public:
  Block() = default;
  Block(const Block&) = delete;
  Block& operator=(const Block&) = delete;
  ~Block()
  {
    if (this->Data)
    {
      Free(this->Data);
    }
  }

  size_t size() const { return this->Size; }
  T* data() { return this->Data; }
  const T* data() const { return this->Data; }

  void resize(size_t n)
  {
    if (n > this->Capacity)
    {
      // Geometric growth: arrays that grow by appending (tuples, hits) reallocate rarely.
      const size_t capacity = std::max(n, this->Capacity + this->Capacity / 2);
      T* grown = static_cast<T*>(Allocate(capacity * sizeof(T)));
      if (this->Data)
      {
        Move(grown, this->Data, this->Size * sizeof(T));
        Free(this->Data);
      }
      this->Data = grown;
      this->Capacity = capacity;
    }
    this->Size = n;
  }

  void swap(Block& other)
  {
    std::swap(this->Data, other.Data);
    std::swap(this->Size, other.Size);
    std::swap(this->Capacity, other.Capacity);
  }

private:
  T* Data = nullptr;
  size_t Size = 0;
  size_t Capacity = 0;
};

/// An array on the device.
template<class T>
class Array : public Block<T, allocateDevice, freeDevice, copyOnDevice>
{
public:
  thrust::device_ptr<T> begin() { return thrust::device_pointer_cast(this->data()); }
  thrust::device_ptr<T> end() { return this->begin() + this->size(); }

  /// Copies n host values to the device.
  void upload(const T* host, size_t n)
  {
    this->resize(n);
    if (n > 0)
    {
      copyToDevice(this->data(), host, n * sizeof(T));
    }
  }

  template<class Allocator>
  Array& operator=(const std::vector<T, Allocator>& host)
  {
    this->upload(host.data(), host.size());
    return *this;
  }
};

/// Page-locked host memory, the staging area of large transfers.
template<class T>
using PinnedArray = Block<T, allocatePinned, freePinned, copyOnHost>;

#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
/// Thrust's temporary storage (sort, scan, copy_if, reduce) from device blocks kept across calls
/// and frames, so that steady-state frames do not call cudaMalloc. Frames are serialised (one
/// engine per process behind a mutex), and so are its uses. A block given back is reused by
/// later work on the same stream, which runs after the work that used it.
class TemporaryPool
{
public:
  using value_type = char;

  char* allocate(std::ptrdiff_t bytes)
  {
    const auto free = this->Free.lower_bound(bytes);
    if (free != this->Free.end())
    {
      char* block = free->second;
      this->Used.emplace(block, free->first);
      this->Free.erase(free);
      return block;
    }
    char* block = static_cast<char*>(allocateDevice(size_t(bytes)));
    this->Used.emplace(block, bytes);
    return block;
  }

  void deallocate(char* block, size_t)
  {
    const auto used = this->Used.find(block);
    this->Free.emplace(used->second, block);
    this->Used.erase(used);
  }

  /// Gives the free blocks back to the device (after an out-of-memory error).
  void trim()
  {
    for (const auto& free : this->Free)
    {
      freeDevice(free.second);
    }
    this->Free.clear();
  }

private:
  std::multimap<std::ptrdiff_t, char*> Free;
  std::map<char*, std::ptrdiff_t> Used;
};

inline TemporaryPool& temporaryPool()
{
  static TemporaryPool pool;
  return pool;
}

/// The execution policy of every device algorithm: the device, with pooled temporaries, and no
/// synchronisation after each algorithm (Thrust's `par` waits for every kernel to finish). The
/// host waits only where it reads a result back.
inline auto exec()
{
  return thrust::cuda::par_nosync(temporaryPool());
}
#else
inline auto exec()
{
  return thrust::device;
}
#endif

#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
/// Stage times of a frame on the device's clock. Launches are queued ahead of the device, so
/// the host's clock would charge a stage's work to whichever stage next waits for a result.
class StageTimer
{
public:
  StageTimer() = default;
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer()
  {
    for (cudaEvent_t event : this->Events)
    {
      cudaEventDestroy(event);
    }
  }

  /// Starts the first stage.
  void begin()
  {
    this->Targets.clear();
    this->record(0);
  }

  /// Ends a stage and starts the next; the stage's milliseconds are added to `ms` by finish().
  void end(double& ms)
  {
    this->Targets.push_back(&ms);
    this->record(this->Targets.size()); // event k + 1 ends stage k
  }

  /// Waits for the last stage and adds the times.
  void finish()
  {
    if (this->Targets.empty())
    {
      return;
    }
    check(cudaEventSynchronize(this->Events[this->Targets.size()]), "stage timer");
    for (size_t k = 0; k < this->Targets.size(); ++k)
    {
      float ms = 0;
      check(cudaEventElapsedTime(&ms, this->Events[k], this->Events[k + 1]), "stage timer");
      *this->Targets[k] += double(ms);
    }
  }

private:
  void record(size_t k)
  {
    if (k == this->Events.size())
    {
      cudaEvent_t event;
      check(cudaEventCreate(&event), "stage timer");
      this->Events.push_back(event);
    }
    check(cudaEventRecord(this->Events[k]), "stage timer");
  }

  std::vector<cudaEvent_t> Events; ///< kept from frame to frame
  std::vector<double*> Targets;
};
#else
/// Thrust's host system runs every algorithm before it returns: the host's clock is the
/// device's.
using StageTimer = StageClock;
#endif

IGA_DEVICE_SYSTEM_END
} // namespace device
} // namespace sst
} // namespace iga
