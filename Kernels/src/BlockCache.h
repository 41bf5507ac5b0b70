// Large host blocks kept between the SST loop's iterations and between frames.
//
// The CPU driver allocates and frees its node, coefficient and tuple arrays every iteration.
// glibc hands blocks of that size back to the kernel on free, so every iteration paid for fresh
// zeroed pages again (about 11 000 page faults per 512^2 frame, a tenth of its CPU time). The
// cache keeps freed blocks, up to a byte cap, and hands them out again: the host twin of the
// CUDA driver's persistent device pool.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

namespace iga
{
namespace sst
{

class BlockCache
{
public:
  /// Smaller blocks go straight to operator new: malloc's own bins serve them well.
  static constexpr size_t kMinimumBytes = size_t(64) << 10;
  /// Freed blocks kept at most; beyond it the largest are released.
  static constexpr size_t kCapacityBytes = size_t(512) << 20;

  static BlockCache& instance()
  {
    // Never destroyed: arrays freed during static destruction still find it.
    static BlockCache* cache = new BlockCache;
    return *cache;
  }

  void* allocate(size_t bytes)
  {
    if (bytes < kMinimumBytes)
    {
      return ::operator new(bytes);
    }
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      // The smallest cached block that fits without wasting more than half of itself.
      size_t best = this->Free.size();
      for (size_t k = 0; k < this->Free.size(); ++k)
      {
        const size_t size = sizeOf(this->Free[k]);
        if (size >= bytes && size / 2 <= bytes &&
            (best == this->Free.size() || size < sizeOf(this->Free[best])))
        {
          best = k;
        }
      }
      if (best < this->Free.size())
      {
        char* block = this->Free[best];
        this->FreeBytes -= sizeOf(block);
        this->Free[best] = this->Free.back();
        this->Free.pop_back();
        return block;
      }
    }
    // A header in front of the block remembers its size: a reused block may be larger than the
    // request it serves, and deallocate is told only the request.
    char* block = static_cast<char*>(::operator new(bytes + kHeader)) + kHeader;
    *reinterpret_cast<size_t*>(block - kHeader) = bytes;
    return block;
  }

  void deallocate(void* pointer, size_t bytes)
  {
    if (bytes < kMinimumBytes)
    {
      ::operator delete(pointer);
      return;
    }
    std::lock_guard<std::mutex> lock(this->Mutex);
    char* block = static_cast<char*>(pointer);
    this->Free.push_back(block);
    this->FreeBytes += sizeOf(block);
    while (this->FreeBytes > kCapacityBytes)
    {
      this->releaseLargest();
    }
  }

  /// Bytes held for reuse now.
  size_t cachedBytes()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    return this->FreeBytes;
  }

  /// Gives every cached block back.
  void release()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    while (!this->Free.empty())
    {
      this->releaseLargest();
    }
  }

private:
  static constexpr size_t kHeader = alignof(std::max_align_t) > sizeof(size_t)
                                      ? alignof(std::max_align_t)
                                      : sizeof(size_t);

  BlockCache() = default;

  static size_t sizeOf(const char* block)
  {
    return *reinterpret_cast<const size_t*>(block - kHeader);
  }

  void releaseLargest()
  {
    size_t largest = 0;
    for (size_t k = 1; k < this->Free.size(); ++k)
    {
      largest = sizeOf(this->Free[k]) > sizeOf(this->Free[largest]) ? k : largest;
    }
    this->FreeBytes -= sizeOf(this->Free[largest]);
    ::operator delete(this->Free[largest] - kHeader);
    this->Free[largest] = this->Free.back();
    this->Free.pop_back();
  }

  std::mutex Mutex;
  std::vector<char*> Free; ///< cached blocks, each behind a header with its size
  size_t FreeBytes = 0;
};

/// Allocates through the BlockCache. New elements of trivial types are left uninitialised
/// (they are written before they are read), so arrays grow without zeroing; elements given a
/// value get it.
template<class T>
struct CachedAllocator
{
  using value_type = T;
  template<class U>
  struct rebind
  {
    using other = CachedAllocator<U>;
  };
  CachedAllocator() = default;
  template<class U>
  CachedAllocator(const CachedAllocator<U>&) noexcept
  {
  }
  T* allocate(size_t n) { return static_cast<T*>(BlockCache::instance().allocate(n * sizeof(T))); }
  void deallocate(T* p, size_t n) noexcept { BlockCache::instance().deallocate(p, n * sizeof(T)); }
  template<class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    if constexpr (sizeof...(Args) == 0)
    {
      ::new (static_cast<void*>(p)) U;
    }
    else
    {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  }
  template<class U>
  bool operator==(const CachedAllocator<U>&) const noexcept
  {
    return true;
  }
  template<class U>
  bool operator!=(const CachedAllocator<U>&) const noexcept
  {
    return false;
  }
};

/// A host array of the SST loop whose storage comes from the BlockCache.
template<class T>
using Buffer = std::vector<T, CachedAllocator<T>>;

} // namespace sst
} // namespace iga
