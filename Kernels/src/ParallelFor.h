// Host loops over CPU threads, shared by the CPU driver, the frame preparation and the device
// driver's host side.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <unistd.h>

namespace iga
{
namespace sst
{

/// Lets a spinning thread's sibling run (x86's pause), or yields elsewhere.
inline void cpuRelax()
{
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

/// Threads kept for parallelFor. The SST loop runs a few dozen parallel loops an iteration,
/// with a little serial work between them: starting a thread costs tens of microseconds, and
/// waking a sleeping one about as much. So the threads are started once, and between loops
/// they spin a short while (kSpins pauses: 60 microseconds on the project's machines, less on
/// processors with a shorter pause) before they sleep.
class WorkerPool
{
public:
  static constexpr int kSpins = 1 << 11;

  static WorkerPool& instance()
  {
    // Never destroyed: its threads wait until the process ends.
    static WorkerPool* pool = new WorkerPool;
    return *pool;
  }

  /// Runs job() on the calling thread and on `helpers` other threads at once, and returns when
  /// all have returned; job must not throw (parallelFor catches for it). A loop started while
  /// the pool serves another (a loop inside a loop, or another thread's), or in a process forked
  /// from the pool's, gets threads of its own.
  void run(int helpers, const std::function<void()>& job)
  {
    if (getpid() != this->Owner || this->Busy.exchange(true, std::memory_order_acquire))
    {
      std::vector<std::thread> threads;
      for (int t = 0; t < helpers; ++t)
      {
        threads.emplace_back(job);
      }
      job();
      for (auto& thread : threads)
      {
        thread.join();
      }
      return;
    }
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      while (this->Threads.size() < size_t(helpers))
      {
        this->Threads.emplace_back([this, index = this->Threads.size(),
                                     seen = this->Generation.load()] { this->serve(index, seen); });
      }
      this->Job = &job;
      this->Helpers = size_t(helpers);
      this->Pending.store(size_t(helpers));
      this->Generation.fetch_add(1, std::memory_order_release);
    }
    this->Wake.notify_all();
    job();
    for (int spin = 0; spin < kSpins && this->Pending.load(std::memory_order_acquire) != 0; ++spin)
    {
      cpuRelax();
    }
    {
      std::unique_lock<std::mutex> lock(this->Mutex);
      this->Done.wait(lock, [this] { return this->Pending.load() == 0; });
    }
    this->Busy.store(false, std::memory_order_release);
  }

private:
  WorkerPool()
    : Owner(getpid())
  {
  }

  /// A pool thread: runs the job of every generation it is a helper of.
  void serve(size_t index, uint64_t seen)
  {
    for (;;)
    {
      uint64_t generation = this->Generation.load(std::memory_order_acquire);
      for (int spin = 0; spin < kSpins && generation == seen; ++spin)
      {
        cpuRelax();
        generation = this->Generation.load(std::memory_order_acquire);
      }
      const std::function<void()>* job = nullptr;
      {
        // The generation, its job and helpers as the caller set them together.
        std::unique_lock<std::mutex> lock(this->Mutex);
        this->Wake.wait(lock, [&] { return this->Generation.load() != seen; });
        seen = this->Generation.load();
        job = index < this->Helpers ? this->Job : nullptr;
      }
      if (job)
      {
        (*job)();
        if (this->Pending.fetch_sub(1, std::memory_order_acq_rel) == 1)
        {
          std::lock_guard<std::mutex> lock(this->Mutex);
          this->Done.notify_one();
        }
      }
    }
  }

  const pid_t Owner;               ///< the process whose threads these are
  std::atomic<bool> Busy{ false }; ///< while the pool serves a loop
  std::mutex Mutex;                ///< guards the fields below but the atomics, and sleeping
  std::condition_variable Wake, Done;
  std::vector<std::thread> Threads;
  const std::function<void()>* Job = nullptr; ///< of the current generation
  size_t Helpers = 0;                         ///< of the current generation
  std::atomic<size_t> Pending{ 0 };           ///< helpers still running the job
  std::atomic<uint64_t> Generation{ 0 };      ///< loops started
};

/// Runs fn(begin, end) over [0, n) on `threads` threads pulling chunks of at least `minimum`
/// indices (so a loop of at most `minimum` runs on the calling thread alone: for cheap
/// elements, waking a thread costs more). Callers write results per index, so outputs never
/// depend on the thread count or scheduling. An exception thrown by fn stops the loop's other
/// chunks and is thrown again, once all threads have left the loop.
template<class Fn>
void parallelFor(size_t n, int threads, Fn&& fn, size_t minimum = 1)
{
  const size_t grain = std::max(minimum, n / (size_t(std::max(threads, 1)) * 16));
  if (threads <= 1 || n <= grain)
  {
    if (n > 0)
    {
      fn(size_t(0), n);
    }
    return;
  }
  std::atomic<size_t> next{ 0 };
  std::exception_ptr failure;
  std::mutex failureMutex;
  const std::function<void()> worker = [&]()
  {
    for (;;)
    {
      const size_t begin = next.fetch_add(grain);
      if (begin >= n)
      {
        break;
      }
      try
      {
        fn(begin, std::min(n, begin + grain));
      }
      catch (...)
      {
        std::lock_guard<std::mutex> lock(failureMutex);
        failure = failure ? failure : std::current_exception();
        next.store(n); // the other threads take no further chunk
        break;
      }
    }
  };
  WorkerPool::instance().run(threads - 1, worker);
  if (failure)
  {
    std::rethrow_exception(failure);
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
inline void offsetsFromRuns(const uint32_t* pixels, const uint32_t* starts, size_t runCount,
  size_t first, size_t pixelCount, int threads, uint32_t* offsets)
{
  parallelFor(runCount + 1, threads,
    [&](size_t begin, size_t end)
    {
      for (size_t r = begin; r < end; ++r)
      {
        const size_t from = r == 0 ? first : size_t(pixels[r - 1]) + 1;
        const size_t to = r < runCount ? size_t(pixels[r]) : first + pixelCount;
        std::fill(offsets + from, offsets + to + 1, starts[r]);
      }
    });
}

} // namespace sst
} // namespace iga
