// The SST stages' data-parallel primitives over Thrust: the CUDA driver's (nvcc, CUDA system),
// and in the driver's logic tests Thrust's sequential host system (g++). The interface is
// CpuExec.h's; the stages are written once over either.
#pragma once

#include "DeviceRuntime.h"
#include "iga/sst/Tree.h"

#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/fill.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/transform.h>
#include <thrust/transform_reduce.h>

namespace iga
{
namespace sst
{
namespace device
{
IGA_DEVICE_SYSTEM_BEGIN

/// Copies device memory to host memory (the host waits for the work before it).
template<class T>
void download(const T* first, size_t count, T* host)
{
  if (count > 0)
  {
    copyToHost(host, first, count * sizeof(T));
  }
}

/// Orders (pixel, node) pairs by pixel, then nearest node depth, then node.
struct TupleOrder
{
  const Node* nodes;
  IGA_HD bool operator()(const Tuple& a, const Tuple& b) const
  {
    if (a.pixel != b.pixel)
    {
      return a.pixel < b.pixel;
    }
    const double za = nodes[a.node].info.box.lo[2], zb = nodes[b.node].info.box.lo[2];
    return za < zb || (za == zb && a.node < b.node);
  }
};

struct PixelOrder
{
  template<class Record>
  IGA_HD bool operator()(const Record& a, const Record& b) const
  {
    return a.pixel < b.pixel;
  }
};

template<class BoxOf, class Fn>
struct CoveredPixelOfOwner
{
  const uint64_t* starts;
  size_t owners;
  FrameConstants frame;
  BoxOf boxOf;
  Fn fn;
  IGA_HD void operator()(size_t k) const
  {
    const uint32_t o = ownerOf(starts, owners, k);
    fn(o, k, coveredPixel(boxOf(o), frame, uint32_t(k - starts[o])));
  }
};

/// An element of forEachCounting: its own counts, flushed at once.
template<class Local, class Fn, class Flush>
struct CountingElement
{
  Fn fn;
  Flush flush;
  IGA_HD void operator()(size_t k) const
  {
    Local local{};
    fn(k, local);
    flush(local);
  }
};

struct ThrustExec
{
  template<class T>
  using Array = device::Array<T>;
  /// A parent's eight children in one thread left most of the GPU idle.
  static constexpr bool kThreadPerChild = true;
  using StageTimer = device::StageTimer;

  /// `grain` is the CPU's: a GPU thread takes one element whatever it costs.
  template<class Fn>
  void forEach(size_t n, Fn fn, size_t = 1) const
  {
    if (n > 0)
    {
      thrust::for_each_n(exec(), thrust::counting_iterator<size_t>(0), n, fn);
    }
  }

  template<class Local, class Fn, class Flush>
  void forEachCounting(size_t n, Fn fn, Flush flush, size_t = 1) const
  {
    this->forEach(n, CountingElement<Local, Fn, Flush>{ fn, flush });
  }

  /// A thread per (owner, pixel) item, which finds its owner by binary search and its pixel by
  /// coveredPixel: a box over a million pixels is not one thread's work.
  template<class BoxOf, class Fn>
  void forEachCoveredPixel(const uint64_t* starts, size_t owners, size_t items,
    const FrameConstants& frame, BoxOf boxOf, Fn fn) const
  {
    this->forEach(items, CoveredPixelOfOwner<BoxOf, Fn>{ starts, owners, frame, boxOf, fn });
  }

  template<class T>
  void scan(T* values, size_t n) const
  {
    thrust::exclusive_scan(exec(), values, values + n + 1, values);
  }

  template<class T>
  void read(const T* from, size_t n, T* to) const
  {
    download(from, n, to);
  }

  template<class T>
  void fill(T* first, size_t n, T value) const
  {
    thrust::fill(exec(), first, first + n, value);
  }

  /// Copies host memory to the execution's.
  template<class T>
  void upload(const T* host, size_t n, T* to) const
  {
    if (n > 0)
    {
      copyToDevice(to, host, n * sizeof(T));
    }
  }

  template<class T>
  void copy(const T* from, size_t n, T* to) const
  {
    thrust::copy(exec(), from, from + n, to);
  }

  template<class Keep, class Value>
  size_t select(size_t n, Keep keep, Value value, uint32_t* out) const
  {
    const size_t count = size_t(thrust::copy_if(exec(), thrust::counting_iterator<size_t>(0),
                                  thrust::counting_iterator<size_t>(n), out, keep) -
                                out);
    thrust::transform(exec(), out, out + count, out, value);
    return count;
  }

  template<class Fn>
  size_t sum(size_t n, Fn fn) const
  {
    return thrust::transform_reduce(exec(), thrust::counting_iterator<size_t>(0),
      thrust::counting_iterator<size_t>(n), fn, size_t(0), thrust::plus<size_t>());
  }

  void sortByPixelThenDepth(Tuple* tuples, size_t n, const Node* nodes, size_t) const
  {
    thrust::sort(exec(), tuples, tuples + n, TupleOrder{ nodes });
  }

  template<class Record>
  void sortByPixel(Record* records, size_t n, size_t) const
  {
    thrust::stable_sort(exec(), records, records + n, PixelOrder());
  }

  /// Per pixel a binary search for the first run at or after it. (Filling the gaps between
  /// runs, one thread a run, left a sparse frame's last thread two million pixels to write:
  /// 50 ms at 1080p.)
  void offsetsFromRuns(const uint32_t* pixels, const uint32_t* starts, size_t runs, size_t first,
    size_t pixelCount, uint32_t* offsets) const
  {
    this->forEach(pixelCount + 1,
      [=] IGA_HD(size_t k)
      {
        const size_t p = first + k;
        size_t lo = 0, hi = runs;
        while (lo < hi)
        {
          const size_t mid = (lo + hi) / 2;
          if (pixels[mid] < p)
          {
            lo = mid + 1;
          }
          else
          {
            hi = mid;
          }
        }
        offsets[p] = starts[lo];
      });
  }
};

IGA_DEVICE_SYSTEM_END
} // namespace device
} // namespace sst
} // namespace iga
