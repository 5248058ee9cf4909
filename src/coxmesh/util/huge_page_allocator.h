// An allocator for the big flat arrays of coxmesh (hash tables, key arrays, points, incidences,
// and any array per cell or per simplex): blocks of 2 MiB and more are mapped directly, 2
// MiB-aligned and rounded up to whole 2 MiB pages, so they arrive zero-filled by the kernel
// (zeroed_huge_vector does not zero them again) and can be backed by transparent huge pages; freed,
// they are kept for the next ones (big_blocks below), so that a later phase (the topology, a
// writer) takes the pages an earlier one freed instead of fresh ones from the heap, each a page
// fault, and a slow one on a virtual machine whose host has taken the page back.
// Smaller blocks come from operator new as usual.
// Huge pages are asked for (madvise) only with COXMESH_HUGE_PAGES=1 in the environment: where the
// system enables them for all memory they are used anyway, and asking for them is a gamble. On a
// virtual machine that backs its memory lazily, the first touch of a huge page cost 30 times the
// first touch of the same bytes in 4 KiB pages, and asking made whole runs 2.5 times slower;
// elsewhere it had saved a part of the page faults (docs/benchmarks.md, "Page faults").
#pragma once

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string_view>
#include <utility>
#include <vector>

namespace coxmesh {

/// COXMESH_HUGE_PAGES=1 in the environment (read once).
inline bool huge_pages_requested() {
  static const bool requested = [] {
    const char* value = std::getenv("COXMESH_HUGE_PAGES");
    return value != nullptr && value == std::string_view("1");
  }();
  return requested;
}

// Blocks of whole 2 MiB pages, 2 MiB-aligned. A freed block is kept for the next ones (up to a
// bound) instead of going back to the system at once: its pages are written already, and a page
// written for the first time costs a page fault and the kernel's zeroing, so the phases of a run
// reuse each other's pages (util/big_blocks.cpp).
namespace big_blocks {
/// A block of `bytes` (a multiple of 2 MiB).
void* take(std::size_t bytes);
/// Whether the last block take() returned on this thread came zero-filled from the system (false
/// for a kept block, which holds what it held).
bool last_take_zero_filled();
void give_back(void* p, std::size_t bytes);
}  // namespace big_blocks

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T) - kPage) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kPage) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(big_blocks::take(round_up(bytes)));  // (a partial last 2 MiB would get small pages)
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kPage) return ::operator delete(p);
    big_blocks::give_back(p, round_up(n * sizeof(T)));
  }
  static std::size_t round_up(std::size_t bytes) { return (bytes + kPage - 1) / kPage * kPage; }
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

/// n zeros, without writing them when the block comes zero-filled from the kernel (≥ 2 MiB): a new
/// hash table then costs its page faults only, not a second pass that zeroes it.
template <class T>
UninitializedHugeVector<T> zeroed_huge_vector(std::size_t n) {
  UninitializedHugeVector<T> v;
  v.reserve(n);
  v.resize(n);
  if (v.capacity() * sizeof(T) < HugePageAllocator<T>::kPage || !big_blocks::last_take_zero_filled()) {
    std::fill(v.begin(), v.end(), T{});
  } else {
    // A hash table is read at random before it is written: each page would fault twice (the shared
    // zero page, then a page of its own), at about 2.5 times the cost of writing it up front here
    // (docs/benchmarks.md, "Surfaces end to end"). Kernels before 5.14 ignore the advice.
#if defined(MADV_POPULATE_WRITE) && !defined(__SANITIZE_ADDRESS__)
    madvise(v.data(), HugePageAllocator<T>::round_up(n * sizeof(T)), MADV_POPULATE_WRITE);
#endif
  }
  return v;
}

/// Memory held by a vector that only grew: its capacity, except for a big block, of which only the
/// pages up to its size were ever written (the kernel backs the others on first write).
template <class V>
std::size_t held_bytes(const V& v) {
  using T = typename V::value_type;
  const std::size_t capacity = v.capacity() * sizeof(T);
  if (capacity < HugePageAllocator<T>::kPage) return capacity;
  return std::min(capacity, HugePageAllocator<T>::round_up(v.size() * sizeof(T)));
}

/// v.insert(v.end(), p, p + n) for a few numbers, without a call to copy them. A big block of
/// whole 2 MiB pages grows eightfold, not twofold: it moves (a serial copy) and its new pages are
/// written for the first time (a page fault each) less often, and the pages never written cost
/// nothing. held_bytes() is what doubling would give: from such a block, doubling gives blocks of
/// whole 2 MiB pages too, at least as big as the vector, so held_bytes() counts round_up(size) either way.
template <class V>
void append_few(V& v, const typename V::value_type* p, std::size_t n) {
  if (v.capacity() - v.size() < n) {
    using T = typename V::value_type;
    constexpr std::size_t kPage = HugePageAllocator<T>::kPage, kHeadroom = 8;
    const std::size_t doubled = v.size() + std::max(v.size(), n);  // (what a vector's insert reserves)
    const std::size_t bytes = v.capacity() * sizeof(T);
    bool grown = false;
    if (bytes >= kPage && bytes % kPage == 0 && kHeadroom * v.capacity() < v.max_size()) {
      try {
        v.reserve(std::max(kHeadroom * v.capacity(), doubled));
        grown = true;
      } catch (const std::bad_alloc&) {  // (the vector is unchanged: it doubles below)
      }
    }
    if (!grown) v.reserve(doubled);
  }
  // (resize then copy: one capacity check, not one per push_back; with an uninitialised allocator
  // resize writes nothing)
  const std::size_t size = v.size();
  v.resize(size + n);
  std::copy_n(p, n, v.data() + size);
}

/// Gives v room for one big block (2 MiB) when it has less, for an array that will grow by appends
/// (append_few): a big block's pages cost nothing until written, so a small array costs the pages
/// it fills, and a big one moves first at 2 MiB, not every time it doubles from a few bytes on (each
/// move a copy, and a page fault per page of the new block). Not under AddressSanitizer, which gets
/// every block written in full (big_blocks.cpp).
template <class V>
void reserve_big_block(V& v) {
#if !defined(__SANITIZE_ADDRESS__)
  using T = typename V::value_type;
  v.reserve(std::max(v.capacity(), HugePageAllocator<T>::kPage / sizeof(T)));
#else
  (void)v;
#endif
}

/// Resizes v to n elements; when v has to move, it reserves kHeadroom times its capacity. A move
/// copies v serially, a big block's pages cost nothing until written: arrays that grow level after
/// level while several threads wait (the parallel walk's) move less often. Where the system
/// refuses that much address space, it grows as a vector does.
template <class V>
void grow_with_headroom(V& v, std::size_t n) {
  constexpr std::size_t kHeadroom = 8;
  if (n > v.capacity() && n < kHeadroom * v.capacity() && kHeadroom * v.capacity() < v.max_size()) {
    try {
      v.reserve(kHeadroom * v.capacity());
    } catch (const std::bad_alloc&) {  // (the vector is unchanged; resize below grows it normally)
    }
  }
  v.resize(n);
}

}  // namespace coxmesh
