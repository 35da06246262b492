// Allocation for the engine's large buffers (framebuffer planes, the triangle setups a draw
// bins): 64-byte aligned, so SIMD kernels load and store whole cache lines; on Linux the whole
// 2 MiB pages inside a buffer of 4 MiB or more are advised to be transparent huge pages. The
// raster phase reads setups at scattered places of a buffer of many megabytes, and with 4 KiB
// pages nearly every triangle it reads costs a TLB miss (measured: benchmarks/RESULTS.md
// decision 1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
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

  CacheAlignedAllocator() = default;
  template <typename U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    void* p = ::operator new(bytes, kAlignment);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Advice only, for the whole 2 MiB pages inside the buffer (no alignment slack is
    // allocated for it); where huge pages are unavailable the call fails and nothing changes.
    if (bytes >= 2 * kHugePageSize) {
      const uintptr_t begin =
          (reinterpret_cast<uintptr_t>(p) + kHugePageSize - 1) & ~(kHugePageSize - 1);
      const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHugePageSize - 1);
      if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
    }
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) noexcept {
    ::operator delete(p, kAlignment);
  }
  template <typename U>
  bool operator==(const CacheAlignedAllocator<U>&) const noexcept {
    return true;
  }
};

template <typename T>
using AlignedVector = std::vector<T, CacheAlignedAllocator<T>>;

// CacheAlignedAllocator for arrays whose elements are always written before they are read:
// elements made without a value (resize(), emplace_back()) are default-initialized, which for
// a trivial type leaves the memory untouched, so a writer can fill them with streaming stores
// instead of first writing zeros through the cache.
template <typename T>
struct UninitializedAllocator : CacheAlignedAllocator<T> {
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace tessera::detail
