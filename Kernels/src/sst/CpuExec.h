// The SST stages' data-parallel primitives on CPU threads (the CPU driver). ThrustExec.h has
// the same interface over Thrust (the CUDA driver); the stages are written once over either.
//
//   Array<T>                        growable array in the execution's memory (resize, data, swap)
//   forEach(n, fn[, grain])         fn(k) for k in [0, n), in any order, each k once; `grain`
//                                   the elements worth a thread (few for costly elements)
//   forEachCounting<Local>(n, fn, flush[, grain])
//                                   fn(k, local) as forEach, each thread's Local counts handed
//                                   to flush(local) per chunk (CPU) or per element (GPU)
//   forEachCoveredPixel(starts, owners, n, frame, boxOf, fn)
//                                   fn(owner, item, pixel) for the n items, [starts[o],
//                                   starts[o + 1]) those of owner o: the pixels its box covers
//   scan(values, n)                 exclusive prefix sum in place over n + 1 entries
//   read(from, n, to)               to host memory (where the host waits for the work before)
//   fill, copy                      in the execution's memory
//   select(n, keep, value, out)     value(k) of every k with keep(k), in order; returns how many
//   sum(n, fn)                      the sum of fn(k)
//   sortByPixelThenDepth            (pixel, node) pairs by pixel, nearest node depth, node
//   sortByPixel                     records, stably by pixel
//   offsetsFromRuns                 per-pixel offsets from runs of records sorted by pixel
//   kThreadPerChild                 the subdivision stage's grain: a thread per child (GPU) or
//                                   per split node (CPU, which shares its children's work)
//
// Every primitive writes per index or in index order, so results never depend on the thread
// count.
#pragma once

#include "BlockCache.h"
#include "ParallelFor.h"
#include "StageClock.h"
#include "iga/sst/Tree.h"
#include "sst/PixelRuns.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace iga
{
namespace sst
{

struct CpuExec
{
  template<class T>
  using Array = Buffer<T>;
  static constexpr bool kThreadPerChild = false;
  using StageTimer = StageClock;

  int threads = 1;

  /// Elements a thread takes at least in loops of cheap elements (a fill, a flag): a loop of
  /// fewer runs on the calling thread, where waking a second one would cost more than it.
  static constexpr size_t kCheap = 4096;

  template<class Fn>
  void forEach(size_t n, Fn fn, size_t grain = kCheap) const
  {
    parallelFor(
      n, this->threads,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          fn(k);
        }
      },
      grain);
  }

  /// forEach whose elements count into a Local (started as Local{}) that flush(local) receives
  /// once per chunk of elements: counters that all threads share are added to a few times a
  /// loop, not once an element, where their cache line moving between the cores cost more than
  /// the elements' work.
  template<class Local, class Fn, class Flush>
  void forEachCounting(size_t n, Fn fn, Flush flush, size_t grain = kCheap) const
  {
    parallelFor(
      n, this->threads,
      [&](size_t begin, size_t end)
      {
        Local local{};
        for (size_t k = begin; k < end; ++k)
        {
          fn(k, local);
        }
        flush(local);
      },
      grain);
  }

  /// fn(owner, item, pixel) for the items of owners whose items are the pixels their boxes
  /// cover (coveredPixelCount, all of them or none), walking each box row by row.
  template<class BoxOf, class Fn>
  void forEachCoveredPixel(const uint64_t* starts, size_t owners, size_t items,
    const FrameConstants& frame, BoxOf boxOf, Fn fn) const
  {
    parallelFor(owners, items < kCheap ? 1 : this->threads,
      [&](size_t begin, size_t end)
      {
        for (size_t o = begin; o < end; ++o)
        {
          size_t k = starts[o];
          if (k < starts[o + 1])
          {
            sst::forEachCoveredPixel(boxOf(o), frame, [&](size_t p) { fn(uint32_t(o), k++, p); });
          }
        }
      });
  }

  template<class T>
  void scan(T* values, size_t n) const
  {
    T total = 0;
    for (size_t k = 0; k <= n; ++k)
    {
      const T value = k < n ? values[k] : T(0);
      values[k] = total;
      total += value;
    }
  }

  template<class T>
  void read(const T* from, size_t n, T* to) const
  {
    std::copy(from, from + n, to);
  }

  template<class T>
  void fill(T* first, size_t n, T value) const
  {
    std::fill(first, first + n, value);
  }

  /// Copies host memory in (the same memory here).
  template<class T>
  void upload(const T* host, size_t n, T* to) const
  {
    std::copy(host, host + n, to);
  }

  template<class T>
  void copy(const T* from, size_t n, T* to) const
  {
    std::copy(from, from + n, to);
  }

  template<class Keep, class Value>
  size_t select(size_t n, Keep keep, Value value, uint32_t* out) const
  {
    // Counted per part, then written per part: the same output for any thread count.
    const size_t parts = n < kCheap ? 1 : std::min(n, size_t(this->threads) * 8);
    std::vector<size_t> counts(parts + 1, 0);
    parallelParts(n, parts, this->threads,
      [&](size_t part, size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          counts[part] += keep(k) ? 1 : 0;
        }
      });
    this->scan(counts.data(), parts);
    parallelParts(n, parts, this->threads,
      [&](size_t part, size_t begin, size_t end)
      {
        size_t write = counts[part];
        for (size_t k = begin; k < end; ++k)
        {
          if (keep(k))
          {
            out[write++] = uint32_t(value(k));
          }
        }
      });
    return counts[parts];
  }

  template<class Fn>
  size_t sum(size_t n, Fn fn) const
  {
    const size_t parts = n < kCheap ? 1 : std::min(n, size_t(this->threads) * 8);
    std::vector<size_t> sums(parts, 0);
    parallelParts(n, parts, this->threads,
      [&](size_t part, size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          sums[part] += size_t(fn(k));
        }
      });
    return std::accumulate(sums.begin(), sums.end(), size_t(0));
  }

  /// A stable radix sort on the pixel, then each pixel's run by (depth, node) on all threads.
  void sortByPixelThenDepth(Tuple* tuples, size_t n, const Node* nodes, size_t pixelCount) const
  {
    // Pairs one a pixel in pixel order (one initial node: an algebraic surface's frame) are
    // sorted already. The check stops at the first pair out of that order, where most frames'
    // second node begins.
    if (std::adjacent_find(tuples, tuples + n,
          [](const Tuple& a, const Tuple& b) { return a.pixel >= b.pixel; }) == tuples + n)
    {
      return;
    }
    this->sortByPixel(tuples, n, pixelCount);
    Buffer<uint32_t> runs(n + 1);
    const size_t runCount = pixelRuns(*this, tuples, n, runs.data());
    parallelFor(
      runCount, this->threads,
      [&](size_t begin, size_t end)
      {
        for (size_t r = begin; r < end; ++r)
        {
          std::sort(tuples + runs[r], tuples + runs[r + 1],
            [&](const Tuple& a, const Tuple& b)
            {
              const double za = nodes[a.node].info.box.lo[2], zb = nodes[b.node].info.box.lo[2];
              return za < zb || (za == zb && a.node < b.node);
            });
        }
      },
      256);
  }

  /// Groups records by pixel, keeping their order within a pixel: a stable LSD radix sort on
  /// the pixel index, 11 bits a pass. O(records) whatever the image size, where a counting
  /// sort over the pixels paid for every pixel of a large, sparsely covered image. Each pass
  /// counts and scatters contiguous parts of the records on all threads, part after part in
  /// each digit's range, so the order within a pixel stays that of the input.
  template<class Record>
  void sortByPixel(Record* records, size_t n, size_t pixelCount) const
  {
    constexpr int kRadixBits = 11;
    constexpr uint32_t kDigits = uint32_t(1) << kRadixBits;
    if (std::is_sorted(
          records, records + n, [](const Record& a, const Record& b) { return a.pixel < b.pixel; }))
    {
      return;
    }
    Buffer<Record> scratch(n);
    Record* from = records;
    Record* to = scratch.data();
    const size_t parts = n < kCheap ? 1 : size_t(this->threads);
    std::vector<uint32_t> counts(parts * kDigits); // per part (apart: no shared cache lines)
    for (int shift = 0; (size_t(1) << shift) < pixelCount; shift += kRadixBits)
    {
      auto digit = [&](const Record& r) { return (r.pixel >> shift) & (kDigits - 1); };
      std::fill(counts.begin(), counts.end(), 0u);
      parallelParts(n, parts, this->threads,
        [&](size_t part, size_t begin, size_t end)
        {
          uint32_t* partCounts = counts.data() + part * kDigits;
          for (size_t k = begin; k < end; ++k)
          {
            ++partCounts[digit(from[k])];
          }
        });
      uint32_t start = 0; // where each part's records of each digit go, digit by digit
      for (uint32_t d = 0; d < kDigits; ++d)
      {
        for (size_t part = 0; part < parts; ++part)
        {
          const uint32_t count = counts[part * kDigits + d];
          counts[part * kDigits + d] = start;
          start += count;
        }
      }
      parallelParts(n, parts, this->threads,
        [&](size_t part, size_t begin, size_t end)
        {
          uint32_t* next = counts.data() + part * kDigits;
          for (size_t k = begin; k < end; ++k)
          {
            to[next[digit(from[k])]++] = from[k];
          }
        });
      std::swap(from, to);
    }
    if (from != records)
    {
      this->copy(from, n, records);
    }
  }

  void offsetsFromRuns(const uint32_t* pixels, const uint32_t* starts, size_t runs, size_t first,
    size_t pixelCount, uint32_t* offsets) const
  {
    sst::offsetsFromRuns(pixels, starts, runs, first, pixelCount, this->threads, offsets);
  }
};

} // namespace sst
} // namespace iga
