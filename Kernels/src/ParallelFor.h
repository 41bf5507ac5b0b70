// Host loops over CPU threads, shared by the CPU driver, the frame preparation and the device
// driver's host side.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace iga
{
namespace sst
{

/// Runs fn(begin, end) over [0, n) on `threads` threads pulling chunks. Callers write results
/// per index, so outputs never depend on the thread count or scheduling.
template<class Fn>
void parallelFor(size_t n, int threads, Fn&& fn)
{
  const size_t grain = std::max<size_t>(1, n / (size_t(std::max(threads, 1)) * 16));
  if (threads <= 1 || n <= grain)
  {
    if (n > 0)
    {
      fn(size_t(0), n);
    }
    return;
  }
  std::atomic<size_t> next{ 0 };
  auto worker = [&]()
  {
    for (;;)
    {
      const size_t begin = next.fetch_add(grain);
      if (begin >= n)
      {
        break;
      }
      fn(begin, std::min(n, begin + grain));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
  {
    pool.emplace_back(worker);
  }
  worker();
  for (auto& thread : pool)
  {
    thread.join();
  }
}

/// Runs fn(part, begin, end) for `parts` contiguous ranges of [0, n) in order of index, on
/// `threads` threads: for results that are gathered per part and then joined in order.
template<class Fn>
void parallelParts(size_t n, size_t parts, int threads, Fn&& fn)
{
  parallelFor(parts, threads,
    [&](size_t first, size_t last)
    {
      for (size_t k = first; k < last; ++k)
      {
        fn(k, n * k / parts, n * (k + 1) / parts);
      }
    });
}

/// Per-pixel offsets from runs over pixels [first, first + pixelCount) (`pixels[r]`, ascending,
/// in that range, starts at `starts[r]`; `starts` has one entry more, the end): each of those
/// pixels gets the start of the first run at or after it, offsets[first + pixelCount] the end.
/// The one pass over those pixels, on all threads; `offsets` is indexed by pixel.
template<class Pixels, class Starts, class Offsets>
void offsetsFromRuns(const Pixels& pixels, const Starts& starts, size_t first, size_t pixelCount,
  int threads, Offsets& offsets)
{
  const size_t runCount = pixels.size();
  parallelFor(runCount + 1, threads,
    [&](size_t begin, size_t end)
    {
      for (size_t r = begin; r < end; ++r)
      {
        const size_t from = r == 0 ? first : size_t(pixels[r - 1]) + 1;
        const size_t to = r < runCount ? size_t(pixels[r]) : first + pixelCount;
        std::fill(offsets.begin() + from, offsets.begin() + to + 1, starts[r]);
      }
    });
}

} // namespace sst
} // namespace iga
