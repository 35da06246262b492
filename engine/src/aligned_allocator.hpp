// Allocation for the engine's large buffers (framebuffer planes, the triangle setups a draw
// bins): 64-byte aligned, so SIMD kernels load and store whole cache lines; buffers of 2 MiB or
// more are aligned to 2 MiB and, on Linux, advised to live in transparent huge pages. The
// raster phase reads setups at scattered places of a buffer of many megabytes, and with 4 KiB
// pages nearly every triangle it reads costs a TLB miss (measured: benchmarks/RESULTS.md).
#pragma once

#include <cstddef>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tessera::detail {

inline constexpr size_t kHugePageSize = size_t{2} << 20;

template <typename T>
struct CacheAlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  static constexpr std::align_val_t kHugeAlignment{kHugePageSize};

  CacheAlignedAllocator() = default;
  template <typename U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageSize) return static_cast<T*>(::operator new(bytes, kAlignment));
    void* p = ::operator new(bytes, kHugeAlignment);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Advice only: where huge pages are unavailable the call fails and nothing changes.
    madvise(p, (bytes + kHugePageSize - 1) / kHugePageSize * kHugePageSize, MADV_HUGEPAGE);
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < kHugePageSize) {
      ::operator delete(p, kAlignment);
    } else {
      ::operator delete(p, kHugeAlignment);
    }
  }
  template <typename U>
  bool operator==(const CacheAlignedAllocator<U>&) const noexcept {
    return true;
  }
};

template <typename T>
using AlignedVector = std::vector<T, CacheAlignedAllocator<T>>;

}  // namespace tessera::detail
