// The host block cache behind the CPU driver's arrays: blocks come back for requests they fit,
// the cache stays under its cap, and arrays given a value hold it on reused blocks.
#include "BlockCache.h"
#include "iga/sst/Engine.h"

#include <gtest/gtest.h>

#include <cstring>
#include <thread>

namespace
{

using iga::sst::BlockCache;

TEST(BlockCache, FreedBlocksServeRequestsTheyFit)
{
  BlockCache& cache = BlockCache::instance();
  cache.release();
  void* block = cache.allocate(size_t(1) << 20);
  cache.deallocate(block, size_t(1) << 20);
  EXPECT_EQ(cache.cachedBytes(), size_t(1) << 20);
  // A smaller request it fits without wasting half of it gets the same block, and returns it
  // at its true size.
  void* again = cache.allocate(size_t(900) << 10);
  EXPECT_EQ(again, block);
  EXPECT_EQ(cache.cachedBytes(), 0u);
  cache.deallocate(again, size_t(900) << 10);
  EXPECT_EQ(cache.cachedBytes(), size_t(1) << 20);
  // Too small a request, or a larger one, gets a block of its own.
  void* small = cache.allocate(size_t(256) << 10);
  void* large = cache.allocate(size_t(2) << 20);
  EXPECT_NE(small, block);
  EXPECT_NE(large, block);
  cache.deallocate(small, size_t(256) << 10);
  cache.deallocate(large, size_t(2) << 20);
  EXPECT_EQ(cache.cachedBytes(), (size_t(1) << 20) + (size_t(256) << 10) + (size_t(2) << 20));
  iga::sst::releaseHostCache(); // the engine's public way to the same
  EXPECT_EQ(cache.cachedBytes(), 0u);
}

TEST(BlockCache, StaysUnderItsCapAndLeavesSmallBlocksToMalloc)
{
  BlockCache& cache = BlockCache::instance();
  cache.release();
  const size_t bytes = BlockCache::kCapacityBytes / 5;
  std::vector<void*> blocks;
  for (int k = 0; k < 8; ++k)
  {
    blocks.push_back(cache.allocate(bytes + size_t(k) * 4096));
  }
  for (int k = 0; k < 8; ++k)
  {
    cache.deallocate(blocks[k], bytes + size_t(k) * 4096);
    EXPECT_LE(cache.cachedBytes(), BlockCache::kCapacityBytes);
  }
  EXPECT_GT(cache.cachedBytes(), BlockCache::kCapacityBytes / 2);
  cache.release();
  void* tiny = cache.allocate(1000);
  cache.deallocate(tiny, 1000);
  EXPECT_EQ(cache.cachedBytes(), 0u);
}

TEST(BlockCache, ArraysGivenAValueHoldItOnReusedBlocks)
{
  BlockCache::instance().release();
  const size_t n = size_t(1) << 18;
  {
    iga::sst::Buffer<uint32_t> dirty(n);
    std::memset(dirty.data(), 0xff, n * sizeof(uint32_t));
  }
  iga::sst::Buffer<uint32_t> clean(n, 0u);
  size_t nonZero = 0;
  for (uint32_t v : clean)
  {
    nonZero += v != 0 ? 1 : 0;
  }
  EXPECT_EQ(nonZero, 0u);
  BlockCache::instance().release();
}

TEST(BlockCache, ThreadsAllocatingTogetherGetDistinctBlocks)
{
  BlockCache::instance().release();
  auto work = [](uint8_t tag, bool* ok)
  {
    for (int round = 0; round < 200; ++round)
    {
      iga::sst::Buffer<uint8_t> block(size_t(128 + round % 7 * 32) << 10);
      std::memset(block.data(), tag, block.size());
      std::this_thread::yield();
      for (uint8_t v : block)
      {
        *ok = *ok && v == tag;
      }
    }
  };
  bool ok[4] = { true, true, true, true };
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
  {
    threads.emplace_back(work, uint8_t(t + 1), &ok[t]);
  }
  for (auto& thread : threads)
  {
    thread.join();
  }
  for (bool b : ok)
  {
    EXPECT_TRUE(b) << "two threads shared a block";
  }
  EXPECT_LE(BlockCache::instance().cachedBytes(), BlockCache::kCapacityBytes);
  BlockCache::instance().release();
}

} // namespace
