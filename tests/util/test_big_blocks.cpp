// Big blocks (util/huge_page_allocator.h): a freed block is reused by the next one that fits, kept
// pages are gathered into a bigger block, what a kept block held never leaks into a zeroed vector,
// and the kept memory stays bounded by the bytes in use; also from two threads at once.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

#include "coxmesh/util/huge_page_allocator.h"

using coxmesh::UninitializedHugeVector;
using coxmesh::zeroed_huge_vector;

namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;

UninitializedHugeVector<std::uint64_t> written(std::size_t bytes, std::uint64_t value) {
  UninitializedHugeVector<std::uint64_t> v(bytes / 8);
  std::fill(v.begin(), v.end(), value);
  return v;
}

bool all_zero(const UninitializedHugeVector<std::uint64_t>& v) {
  return std::all_of(v.begin(), v.end(), [](std::uint64_t x) { return x == 0; });
}

// Resident bytes of this process (/proc/self/statm), 0 where unknown.
std::size_t resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long size = 0, resident = 0;
  const int read = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return read == 2 ? resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE)) : 0;
}

}  // namespace

#if !defined(__SANITIZE_ADDRESS__)  // (GCC's AddressSanitizer build maps every block afresh)
TEST(BigBlocks, AFreedBlockIsReusedAndZeroedWhenAskedTo) {
  const std::uint64_t* address = nullptr;
  {
    const auto v = written(6 * kMiB, ~std::uint64_t{0});
    address = v.data();
  }
  const auto again = zeroed_huge_vector<std::uint64_t>(6 * kMiB / 8);
  EXPECT_EQ(again.data(), address);  // (the same pages, not new ones)
  EXPECT_TRUE(all_zero(again));
}
#endif

// Two kept blocks, apart in memory, gathered into one bigger block: every byte of it usable, and
// zero when a zeroed vector asks for it.
TEST(BigBlocks, KeptPagesGatheredIntoABiggerBlock) {
  {
    auto a = written(4 * kMiB, 1);
    auto spacer = written(2 * kMiB, 2);  // (keeps a and b from merging into one block)
    auto b = written(4 * kMiB, 3);
    spacer.clear();
  }
  const auto big = zeroed_huge_vector<std::uint64_t>(14 * kMiB / 8);
  EXPECT_TRUE(all_zero(big));
  auto copy = written(14 * kMiB, 5);
  EXPECT_TRUE(std::all_of(copy.begin(), copy.end(), [](std::uint64_t x) { return x == 5; }));
}

// A block far bigger than what is in use goes back to the system when freed.
TEST(BigBlocks, KeptMemoryIsBounded) {
  const std::size_t before = resident_bytes();
  if (before == 0) GTEST_SKIP() << "no /proc/self/statm";
  { const auto v = written(256 * kMiB, 7); }
  EXPECT_LT(resident_bytes(), before + 64 * kMiB);
}

#if !defined(__SANITIZE_ADDRESS__)
// A freed block as big as the rest in use is kept for the next phase (a cell complex's level takes
// the pages of the keys it dropped), and kept blocks go back to the system as the bytes in use fall.
TEST(BigBlocks, KeptMemoryFollowsTheBytesInUse) {
  const std::size_t before = resident_bytes();
  if (before == 0) GTEST_SKIP() << "no /proc/self/statm";
  {
    const auto in_use = written(96 * kMiB, 1);
    const std::uint64_t* address = nullptr;
    {
      const auto phase = written(96 * kMiB, 2);
      address = phase.data();
    }
    const auto next = written(96 * kMiB, 3);
    EXPECT_EQ(next.data(), address);  // (kept, then reused)
  }
  EXPECT_LT(resident_bytes(), before + 64 * kMiB);  // (both given back once nothing is in use)
}
#endif

// Two threads taking and giving back blocks at once (the walk's workers do): each sees its own
// numbers and zeroed vectors are zero.
TEST(BigBlocks, TwoThreadsAtOnce) {
  std::vector<int> failures(2, 0);
  auto work = [&](int t) {
    for (int round = 0; round < 40; ++round) {
      const std::size_t bytes = (2 + (round * 3 + t) % 7) * kMiB;
      const auto v = written(bytes, static_cast<std::uint64_t>(t * 1000 + round));
      const auto z = zeroed_huge_vector<std::uint64_t>(bytes / 8 + 1);
      if (!all_zero(z)) ++failures[t];
      if (!std::all_of(v.begin(), v.end(),
                       [&](std::uint64_t x) { return x == static_cast<std::uint64_t>(t * 1000 + round); }))
        ++failures[t];
    }
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  EXPECT_EQ(failures[0], 0);
  EXPECT_EQ(failures[1], 0);
}
