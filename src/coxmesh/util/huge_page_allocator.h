// An allocator for the big flat arrays of coxmesh (hash tables, key arrays): blocks of 8 MiB and
// more are 2 MiB-aligned and marked for transparent huge pages, so that filling them takes one page
// fault per 2 MiB instead of one per 4 KiB (page faults are much of the cost of growing tables,
// and a sequential step of the parallel walk). Smaller blocks come from operator new as usual: a
// partly used last huge page would cost them too much memory.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <new>
#include <vector>

namespace coxmesh {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t{2} << 20, kHuge = std::size_t{8} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHuge) return static_cast<T*>(::operator new(bytes));
    void* p = ::operator new(bytes, std::align_val_t{kPage});
    madvise(p, bytes, MADV_HUGEPAGE);  // (advice only: without THP it is a normal block)
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kHuge) return ::operator delete(p);
    ::operator delete(p, std::align_val_t{kPage});
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const {
    return true;
  }
};

/// A std::vector whose big buffers use huge pages.
template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace coxmesh
