// The CPU threads' primitives: the worker pool behind parallelFor (every index once, across many
// loops, loops inside loops and loops of two threads at once, cheap loops on the caller, an
// exception thrown again once every thread has left the loop), and
// CpuExec's select, forEachCounting, scan, sum and sorts against serial references.
#include "ParallelFor.h"
#include "sst/CpuExec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace
{

using iga::sst::parallelFor;

/// Runs a parallel loop over n indices and checks that each was visited exactly once.
void expectEveryIndexOnce(size_t n, int threads)
{
  std::vector<std::atomic<int>> visits(n);
  parallelFor(n, threads,
    [&](size_t begin, size_t end)
    {
      for (size_t k = begin; k < end; ++k)
      {
        ++visits[k];
      }
    });
  for (size_t k = 0; k < n; ++k)
  {
    ASSERT_EQ(visits[k].load(), 1) << "index " << k << " of " << n;
  }
}

TEST(WorkerPool, EveryIndexOnceOverManyLoops)
{
  for (int loop = 0; loop < 2000; ++loop)
  {
    expectEveryIndexOnce(size_t(1 + loop % 97) * 31, 1 + loop % 4);
  }
}

TEST(WorkerPool, LoopsInsideLoopsAndFromTwoThreads)
{
  std::atomic<size_t> total{ 0 };
  parallelFor(64, 3,
    [&](size_t begin, size_t end)
    {
      for (size_t k = begin; k < end; ++k)
      {
        parallelFor(100, 2, [&](size_t b, size_t e) { total += e - b; });
      }
    });
  EXPECT_EQ(total.load(), 6400u);
  auto loops = [] { expectEveryIndexOnce(100000, 2); };
  std::thread other(
    [&]
    {
      for (int k = 0; k < 50; ++k)
        loops();
    });
  for (int k = 0; k < 50; ++k)
  {
    loops();
  }
  other.join();
}

TEST(WorkerPool, AnExceptionIsThrownAgainOnceTheLoopIsLeft)
{
  for (int loop = 0; loop < 200; ++loop)
  {
    std::atomic<size_t> visited{ 0 };
    EXPECT_THROW(parallelFor(10000, 2,
                   [&](size_t begin, size_t end)
                   {
                     if (begin <= 5000 && 5000 < end)
                     {
                       throw std::runtime_error("index 5000");
                     }
                     visited += end - begin;
                   }),
      std::runtime_error);
    EXPECT_LT(visited.load(), 10000u);
    expectEveryIndexOnce(10000, 2); // the pool serves the next loop
  }
}

TEST(WorkerPool, CheapLoopsStayOnTheCaller)
{
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  parallelFor(
    1000, 2, [&](size_t, size_t) { elsewhere = elsewhere || std::this_thread::get_id() != caller; },
    4096);
  EXPECT_FALSE(elsewhere);
}

TEST(CpuExec, PrimitivesMatchSerialReferences)
{
  std::mt19937 random(7);
  for (int threads : { 1, 2, 3 })
  {
    iga::sst::CpuExec exec;
    exec.threads = threads;
    for (size_t n : { size_t(0), size_t(1), size_t(1000), size_t(50000) })
    {
      std::vector<uint32_t> values(n);
      for (auto& v : values)
      {
        v = random() % 1000;
      }
      // select: the indices of the odd values, in order; sum of the values.
      std::vector<uint32_t> selected(n), expected;
      const size_t count = exec.select(
        n, [&](size_t k) { return values[k] % 2 == 1; }, [](size_t k) { return k; },
        selected.data());
      for (size_t k = 0; k < n; ++k)
      {
        if (values[k] % 2 == 1)
        {
          expected.push_back(uint32_t(k));
        }
      }
      selected.resize(count);
      EXPECT_EQ(selected, expected);
      EXPECT_EQ(exec.sum(n, [&](size_t k) { return values[k]; }),
        std::accumulate(values.begin(), values.end(), size_t(0)));
      // forEachCounting: every element's count reaches the shared counter, once.
      struct Count
      {
        size_t odd = 0;
      };
      std::atomic<size_t> odd{ 0 };
      exec.forEachCounting<Count>(
        n, [&](size_t k, Count& local) { local.odd += values[k] % 2; },
        [&](const Count& local) { odd += local.odd; }, 64);
      EXPECT_EQ(odd.load(), expected.size());
      // scan: exclusive, the total in the extra slot.
      std::vector<uint64_t> scanned(values.begin(), values.end());
      scanned.push_back(0);
      exec.scan(scanned.data(), n);
      uint64_t running = 0;
      for (size_t k = 0; k <= n; ++k)
      {
        ASSERT_EQ(scanned[k], running);
        running += k < n ? values[k] : 0;
      }
      // sortByPixel: stable, as std::stable_sort.
      struct Record
      {
        uint32_t pixel;
        uint32_t order;
      };
      std::vector<Record> records(n);
      for (size_t k = 0; k < n; ++k)
      {
        records[k] = { uint32_t(random() % 5000), uint32_t(k) };
      }
      std::vector<Record> reference = records;
      std::stable_sort(reference.begin(), reference.end(),
        [](const Record& a, const Record& b) { return a.pixel < b.pixel; });
      exec.sortByPixel(records.data(), n, 5000);
      for (size_t k = 0; k < n; ++k)
      {
        ASSERT_EQ(records[k].order, reference[k].order);
      }
    }
  }
}

} // namespace
