// An allocator for the big flat arrays of coxmesh (hash tables, key arrays, points, incidences):
// blocks of 2 MiB and more are 2 MiB-aligned, rounded up to whole 2 MiB pages and marked for
// transparent huge pages, so that filling them takes one page fault per 2 MiB instead of one per
// 4 KiB. Page faults are much of the cost of growing tables (measured: 11 µs per 4 KiB fault on a
// virtual machine with shadow page tables, 45 times the cost per byte of a huge-page fault).
// Smaller blocks come from operator new as usual.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace coxmesh {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kPage) return static_cast<T*>(::operator new(bytes));
    // (rounded up to whole 2 MiB pages: a partial last one would get small pages)
    const std::size_t rounded = (bytes + kPage - 1) / kPage * kPage;
    void* p = ::operator new(rounded, std::align_val_t{kPage});
    madvise(p, rounded, MADV_HUGEPAGE);  // (advice only: without THP it is a normal block)
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kPage) return ::operator delete(p);
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

/// The same for arrays that are written in full right after they grow: resize() leaves numbers
/// uninitialised instead of zeroing them (zeroing a table serially cost as much as filling it).
template <class T>
struct UninitializedHugePageAllocator : HugePageAllocator<T> {
  UninitializedHugePageAllocator() = default;
  template <class U>
  UninitializedHugePageAllocator(const UninitializedHugePageAllocator<U>&) {}
  template <class U>
  struct rebind {
    using other = UninitializedHugePageAllocator<U>;
  };
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using UninitializedHugeVector = std::vector<T, UninitializedHugePageAllocator<T>>;

}  // namespace coxmesh
