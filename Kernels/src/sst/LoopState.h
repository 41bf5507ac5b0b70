// What the shared-subdivision-tree loop holds during a frame, for either execution (CpuExec.h,
// ThrustExec.h): the frame's inputs in the execution's memory, set by the driver, and the
// global arrays of the stages (one file each: Sweep.h, Overlap.h, Solution.h, Subdivision.h,
// Compaction.h, GBufferStage.h; Loop.h runs them).
#pragma once

#include "FramePlan.h"
#include "iga/sst/Tree.h"
#include "sst/PixelRuns.h"

#include <algorithm>
#include <chrono>
#include <cstdint>

namespace iga
{
namespace sst
{

/// What the loop knows of an input patch: its shape and where its data lie.
struct PatchShape
{
  int degree[3];    ///< a surface's third is 0 (flatVolume)
  int channels;     ///< of the world patch
  int screenValues; ///< control points times kScreenChannels (= kShadeChannels)
  size_t world;     ///< offset of its world coefficients
  size_t screen;    ///< offset of its screen patch in the initial pool and of its shading patch
};

static_assert(kScreenChannels == kShadeChannels, "screen and shading patches share offsets");

IGA_HD inline VolumeView<const double> viewOf(
  const Node& node, const double* pool, const PatchShape* shapes)
{
  return VolumeView<const double>(pool + node.coeff, shapes[node.patch].degree, kScreenChannels);
}

/// Adds to a counter from any thread of either execution.
IGA_HD inline void addAtomically(unsigned long long* counter, unsigned long long value)
{
#ifdef __CUDA_ARCH__
  atomicAdd(counter, value);
#else
  __atomic_fetch_add(counter, value, __ATOMIC_RELAXED);
#endif
}

/// Lowers a value to `value` if that is smaller, from any thread of either execution.
IGA_HD inline void lowerAtomically(unsigned int* target, unsigned int value)
{
#ifdef __CUDA_ARCH__
  atomicMin(target, value);
#else
  unsigned int current = __atomic_load_n(target, __ATOMIC_RELAXED);
  while (value < current && !__atomic_compare_exchange_n(
                              target, &current, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
  {
  }
#endif
}

/// Stores a flag value that several threads may store at once (a relaxed atomic store on CPU
/// threads, where plain stores from two threads would race).
IGA_HD inline void storeShared(uint8_t* flag, uint8_t value)
{
#ifdef __CUDA_ARCH__
  *flag = value;
#else
  __atomic_store_n(flag, value, __ATOMIC_RELAXED);
#endif
}

/// How many elements of a loop are worth a CPU thread (the grain of CpuExec::forEach; a GPU
/// thread takes one whatever it costs), by what an element costs: a node split into its eight
/// children (tens of microseconds at degree 4), a node analysed, a pixel's tuples solved, a hit
/// shaded. Loops of cheap elements take CpuExec::kCheap.
constexpr size_t kGrainSplit = 1, kGrainNode = 16, kGrainPixel = 64, kGrainHit = 256;

/// How the subdivision stage leaves a node.
enum SplitState : uint8_t
{
  Keep = 0,
  Split = 1,
  AtDepthCap = 2,
  OverBudget = 3
};

/// Slots of LoopState::Tallies, counted on the execution's side until the frame ends.
enum Tally
{
  TuplesAtDepthCap = 0,
  TuplesOverBudget = 1,
  NewtonRuns = 2,        ///< Newton solves of the solution stage
  NewtonEvaluations = 3, ///< their evaluations of F and J
  TallyCount = 4
};

template<class Exec>
struct LoopState
{
  template<class T>
  using Array = typename Exec::template Array<T>;

  Exec exec;
  typename Exec::StageTimer stages;
  FrameReport* report = nullptr;
  uint64_t budget = 0; ///< the loop's share of Settings::memoryBudgetBytes (loopBudgetBytes)
  /// Settings::deadlineMs as a time (none when `deadline` is the clock's maximum), and whether
  /// it has passed.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  bool pastDeadline = false;
  const std::function<void(int, size_t)>* progress = nullptr;
  /// Bytes of the driver's own copies of the input (world patches, roots) for peakBytes.
  size_t driverBytes = 0;

  // The frame's inputs, in the execution's memory, set by the driver.
  FrameConstants frame{};
  size_t pixelCount = 0;
  const PatchShape* shapes = nullptr;
  const Node* initialNodes = nullptr;
  size_t initialCount = 0;
  const double* initialPool = nullptr;
  size_t initialValues = 0;
  const double* shadingPool = nullptr;
  size_t shadingValues = 0;
  /// Per patch, its power form for shading (ray composition's, CPU only), or null for none.
  const PowerShading* powerShading = nullptr;
  const PowerTerm* powerTerms = nullptr;
  ShadingView viewer{};
  double pixelFootprint = 0;

  // Sweep and group (per pass): work items and their per-pixel offsets; the pixels with work
  // left and their group of the round.
  Array<Tuple> Items; ///< (pixel, initial node) sorted by pixel and depth
  Array<uint32_t> ItemNodes, ItemOffsets, Active, NextActive, GroupBegin, GroupEnd;
  // Per pixel, for the whole frame.
  Array<double> BestDepth;
  Array<uint8_t> Unresolved;
  Array<uint32_t> PixelSolves; ///< Newton solves
  // The loop's nodes, coefficients and tuples, and the stages' scratch arrays.
  size_t NodeCount = 0, TupleCount = 0;
  Array<Node> Nodes, NextNodes, Children;
  Array<double> Pool, NextPool, ChildPool;
  Array<Tuple> Tuples, Next;
  Array<uint64_t> Counts; ///< per owner, then scanned into where its items start
  Array<uint32_t> Index, Taken, HitIndex, ToSplit, SplitIndex, FirstTuple;
  Array<uint64_t> ChildValues, SplitCost, NodeBytes, Offsets;
  Array<unsigned long long> FailedTuples; ///< per node, counted with atomics
  Array<uint64_t> Totals;                 ///< results read back together
  Array<unsigned long long> Tallies;      ///< Tally
  Array<unsigned long long> RowPairs;     ///< the sweep's pairs per row, as differences
  Array<uint8_t> Present, Outcomes, SplitFlags, Deferred, KeepFlags, Used;
  Array<uint8_t> ChildMasks; ///< per tuple, the child slots a failed one moves to (bit c: slot c)
  Array<double> Solution;
  // Hits, and the G-buffer stage's runs of them.
  size_t HitCount = 0, RunCount = 0, KeptCount = 0;
  Array<RawHit> Hits;
  Array<Hit> Shaded;
  Array<uint32_t> RunStarts, RunPixels, KeptStarts;
  // Peaks of the frame.
  size_t peak = 0, peakBudgeted = 0;
};

/// The frame's settings and view as the loop takes them; the driver sets the rest of the
/// inputs (frame constants, shapes, initial nodes, shading patches).
template<class Exec>
void setFrame(LoopState<Exec>& s, FrameReport& report, const Settings& settings, const View& view)
{
  s.report = &report;
  s.budget = loopBudgetBytes(settings);
  s.deadline = std::chrono::steady_clock::time_point::max();
  s.pastDeadline = false;
  if (settings.deadlineMs > 0)
  {
    s.deadline = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                   std::chrono::duration<double, std::milli>(settings.deadlineMs));
  }
  s.progress = &settings.progress;
  s.pixelCount = size_t(settings.width) * settings.height;
  s.viewer = shadingViewOf(view, settings);
  s.pixelFootprint = view.pixelFootprint;
}

template<class Array>
auto raw(Array& v) -> decltype(v.data())
{
  return v.data();
}

/// Sizes an array for this frame. Shrinking keeps the allocation, so steady-state frames reuse
/// the memory of earlier ones instead of allocating.
template<class Array>
auto sized(Array& v, size_t n) -> decltype(v.data())
{
  v.resize(n);
  return v.data();
}

template<class Array>
size_t bytesOf(const Array& v)
{
  return v.size() * sizeof(*v.data());
}

/// Reads one value back from the execution's memory.
template<class Exec, class T>
T readBack(const Exec& exec, const T* where)
{
  T value;
  exec.read(where, 1, &value);
  return value;
}

/// Exclusive scan of counts in place with one extra slot at the end; returns the total, which
/// the 32-bit indices of pairs and tuples must reach (checkIndexable). Counts are 64-bit where
/// the total could pass 2^32, so that the check sees it unwrapped.
template<class Exec, class Array>
size_t scanCounts(const Exec& exec, Array& counts, size_t n)
{
  auto* c = raw(counts);
  exec.scan(c, n);
  const size_t total = size_t(readBack(exec, c + n));
  checkIndexable(total);
  return total;
}

/// The band's work items and the loop's arrays, what the loop's share of the memory budget
/// caps, at their sizes in use (each array may keep a larger allocation between iterations and
/// frames).
template<class Exec>
size_t budgetedBytes(const LoopState<Exec>& s)
{
  return bytesOf(s.Items) + bytesOf(s.ItemNodes) + bytesOf(s.Nodes) + bytesOf(s.Pool) +
         bytesOf(s.NextNodes) + bytesOf(s.NextPool) + bytesOf(s.Children) + bytesOf(s.ChildPool) +
         bytesOf(s.Tuples) + bytesOf(s.Next) + bytesOf(s.Outcomes) + bytesOf(s.Solution) +
         bytesOf(s.HitIndex) + bytesOf(s.Counts) + bytesOf(s.Taken) + bytesOf(s.ToSplit) +
         bytesOf(s.SplitFlags) + bytesOf(s.SplitIndex) + bytesOf(s.ChildValues) +
         bytesOf(s.SplitCost) + bytesOf(s.FailedTuples) + bytesOf(s.NodeBytes) +
         bytesOf(s.Deferred) + bytesOf(s.KeepFlags) + bytesOf(s.Used) + bytesOf(s.FirstTuple) +
         bytesOf(s.Index) + bytesOf(s.Offsets) + bytesOf(s.ChildMasks);
}

/// The copies of the input and the hits, which the budget does not cap, and the per-pixel
/// arrays (imageBytes holds those and one hit a pixel).
template<class Exec>
size_t fixedBytes(const LoopState<Exec>& s)
{
  return s.driverBytes + s.initialCount * sizeof(Node) + s.initialValues * sizeof(double) +
         s.shadingValues * sizeof(double) + bytesOf(s.ItemOffsets) + bytesOf(s.Active) +
         bytesOf(s.NextActive) + bytesOf(s.GroupBegin) + bytesOf(s.GroupEnd) +
         bytesOf(s.BestDepth) + bytesOf(s.Unresolved) + bytesOf(s.PixelSolves) + bytesOf(s.Hits);
}

/// Records the working set's peaks; `extra`: bytes of a reference method's own besides the
/// loop's arrays.
template<class Exec>
void trackMemory(LoopState<Exec>& s, size_t extra = 0)
{
  const size_t budgeted = budgetedBytes(s) + extra;
  s.peakBudgeted = std::max(s.peakBudgeted, budgeted);
  s.peak = std::max(s.peak, budgeted + fixedBytes(s));
}

/// Marks the iteration's scratch arrays empty, out of the working set (they keep their
/// allocations for the next iteration).
template<class Exec>
void endIteration(LoopState<Exec>& s)
{
  auto markEmpty = [](auto&... arrays) { (arrays.resize(0), ...); };
  markEmpty(s.NextNodes, s.Children, s.NextPool, s.ChildPool, s.Solution, s.Counts, s.ChildValues,
    s.SplitCost, s.NodeBytes, s.Offsets, s.FailedTuples, s.HitIndex, s.ToSplit, s.SplitIndex,
    s.Index, s.FirstTuple, s.Outcomes, s.SplitFlags, s.Deferred, s.KeepFlags, s.Used, s.Next,
    s.Taken, s.ChildMasks);
}

} // namespace sst
} // namespace iga
