// Runs of records sorted by pixel (work items, tuples, hits): where each pixel's run starts.
// Written once over the primitives, for the stages and for CpuExec's segmented sort.
#pragma once

#include "iga/Portability.h"

#include <cstddef>
#include <cstdint>

namespace iga
{
namespace sst
{

/// Writes where each run of `records` (n of them, sorted by pixel) starts to starts[0, runs)
/// and n to starts[runs]; returns the number of runs. `starts` holds n + 1 entries.
template<class Exec, class Record>
size_t pixelRuns(const Exec& exec, const Record* records, size_t n, uint32_t* starts)
{
  const size_t runs = exec.select(
    n, [=] IGA_HD(size_t k) { return k == 0 || records[k].pixel != records[k - 1].pixel; },
    [] IGA_HD(size_t k) { return k; }, starts);
  exec.fill(starts + runs, 1, uint32_t(n));
  return runs;
}

} // namespace sst
} // namespace iga
