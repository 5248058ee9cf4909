// PackedKeyIndex: growth by tags alone, and ordered batch insertion giving exactly the ids of
// inserting the keys one after the other.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <set>
#include <thread>

#include "coxmesh/lattice/packed_index.h"

using namespace coxmesh;

namespace {

// `n` keys of `words` words drawn from `distinct` possible ones (many repeats), in runs of random size.
struct Batch {
  std::vector<std::vector<std::uint32_t>> keys;
  std::vector<std::vector<std::uint64_t>> hashes;
  std::vector<std::vector<std::uint32_t>> ids;
  std::vector<KeyRun> runs() {
    std::vector<KeyRun> r;
    for (std::size_t c = 0; c < keys.size(); ++c)
      r.push_back({keys[c].data(), hashes[c].data(), hashes[c].size(), ids[c].data()});
    return r;
  }
};

Batch make_batch(std::mt19937_64& rng, int words, std::size_t n, std::uint32_t distinct) {
  Batch b;
  std::uniform_int_distribution<std::uint32_t> pick(0, distinct - 1);
  for (std::size_t done = 0; done < n;) {
    const std::size_t size = std::min<std::size_t>(n - done, rng() % 3000);  // empty runs too
    b.keys.emplace_back(), b.hashes.emplace_back(), b.ids.emplace_back(size, 0xDEADBEEFu);
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint32_t v = pick(rng);
      for (int w = 0; w < words; ++w) b.keys.back().push_back(v * 2654435761u + static_cast<std::uint32_t>(w));
      b.hashes.back().push_back(hash_words(b.keys.back().data() + i * words, words));
    }
    done += size;
  }
  return b;
}

}  // namespace

TEST(PackedKeyIndex, GrowthKeepsEveryKey) {
  PackedKeyIndex index(3);
  std::vector<std::uint32_t> key(3);
  for (std::uint32_t i = 0; i < 100000; ++i) {
    key = {i, i ^ 0x5555u, 7};
    ASSERT_EQ(index.insert(key.data()), std::make_pair(i, true));
  }
  for (std::uint32_t i = 0; i < 100000; ++i) {
    key = {i, i ^ 0x5555u, 7};
    ASSERT_EQ(index.find(key.data()), i);
    key[2] = 8;
    ASSERT_EQ(index.find(key.data()), PackedKeyIndex::kAbsent);
  }
}

// A released index keeps its keys and refuses look-ups (never a silent kAbsent) until reindexed.
TEST(PackedKeyIndex, ReleasedIndexKeepsKeysAndRefusesLookUpsUntilReindexed) {
  PackedKeyIndex index(2);
  for (std::uint32_t i = 0; i < 5000; ++i) {
    const std::uint32_t key[2] = {i * 7919u, i};
    index.insert(key);
  }
  const std::size_t before = index.bytes();
  index.release_index();
  EXPECT_FALSE(index.indexed());
  EXPECT_LT(index.bytes(), before);
  ASSERT_EQ(index.size(), 5000u);
  EXPECT_EQ(index.key(4321)[0], 4321u * 7919u);
  const std::uint32_t probe[2] = {7919u, 1};
  EXPECT_THROW(index.find(probe), std::logic_error);
  EXPECT_THROW(index.insert(probe), std::logic_error);
  index.reindex();
  for (std::uint32_t i = 0; i < 5000; ++i) {
    const std::uint32_t key[2] = {i * 7919u, i};
    ASSERT_EQ(index.find(key), i);
  }
  const std::uint32_t absent[2] = {1, 1};
  EXPECT_EQ(index.find(absent), PackedKeyIndex::kAbsent);
  EXPECT_EQ(index.insert(absent), std::make_pair(5000u, true));
}

// A reordered copy holds the keys in the order given, without a table until reindexed.
TEST(PackedKeyIndex, UnindexedCopyReordersTheKeys) {
  PackedKeyIndex index(3);
  for (std::uint32_t i = 0; i < 3000; ++i) {
    const std::uint32_t key[3] = {i, i * 31u, 5u};
    index.insert(key);
  }
  std::vector<std::uint32_t> order(2000);
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = (i * 7u + 11u) % 3000u;  // (distinct)
  PackedKeyIndex copy = PackedKeyIndex::unindexed_copy(index, order);
  EXPECT_FALSE(copy.indexed());
  ASSERT_EQ(copy.size(), 2000u);
  for (std::uint32_t i = 0; i < order.size(); ++i)
    ASSERT_TRUE(std::equal(copy.key(i), copy.key(i) + 3, index.key(order[i]))) << i;
  EXPECT_THROW(copy.find(index.key(order[0])), std::logic_error);
  copy.reindex();
  for (std::uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(copy.find(index.key(order[i])), i);
  EXPECT_EQ(copy.find(index.key(1)), PackedKeyIndex::kAbsent);  // (1 is not in the order)
  EXPECT_EQ(index.size(), 3000u);                               // (the source is untouched)
}

// Against one insert() after the other, from a table already holding some of the keys.
TEST(PackedKeyIndex, InsertRunsGivesTheIdsOfSequentialInsertion) {
  std::mt19937_64 rng(12);
  for (int words : {1, 4, 9})
    for (std::size_t n : {std::size_t{100}, std::size_t{9000}, std::size_t{60000}}) {
      const std::uint32_t distinct = static_cast<std::uint32_t>(n / 2 + 1);
      Batch before = make_batch(rng, words, n / 3, distinct), batch = make_batch(rng, words, n, distinct);
      PackedKeyIndex expected(words), actual(words);
      for (auto* index : {&expected, &actual}) index->insert_runs(before.runs());
      std::vector<std::vector<std::uint32_t>> expected_ids;
      for (std::size_t c = 0; c < batch.keys.size(); ++c) {
        expected_ids.emplace_back();
        for (std::size_t i = 0; i < batch.hashes[c].size(); ++i) {
          const auto [id, fresh] = expected.insert(batch.keys[c].data() + i * words, batch.hashes[c][i]);
          expected_ids.back().push_back(fresh ? id | PackedKeyIndex::kNewBit : id);
        }
      }
      actual.insert_runs(batch.runs());
      ASSERT_EQ(actual.size(), expected.size());
      ASSERT_EQ(batch.ids, expected_ids) << words << " words, " << n << " keys";
      for (std::uint32_t id = 0; id < actual.size(); ++id) {
        ASSERT_TRUE(std::equal(actual.key(id), actual.key(id) + words, expected.key(id)));
        ASSERT_EQ(actual.find(actual.key(id)), id);
      }
    }
}

// Keys appended unindexed are found after index_appended(), with the table grown across several
// doublings at once; a key appended although present is reported (the smallest such id), stays
// unindexed, and the rest is indexed; truncate() forgets the later ids.
namespace {
// One key appended unindexed (the bulk append of one).
std::uint32_t append_one(PackedKeyIndex& index, const std::uint32_t* key, std::uint64_t hash) {
  const std::uint32_t id = index.append_unindexed(1);
  index.set_appended(id, key, hash);
  return id;
}
}  // namespace

TEST(PackedKeyIndex, AppendedKeysAreIndexedAndDuplicatesReported) {
  std::mt19937_64 rng(5);
  for (int words : {1, 3}) {
    PackedKeyIndex index(words);
    std::vector<std::uint32_t> key(words);
    const auto make = [&](std::uint32_t i) {
      for (int w = 0; w < words; ++w) key[w] = i * 2654435761u + static_cast<std::uint32_t>(w);
      return key.data();
    };
    for (std::uint32_t i = 0; i < 1000; ++i) index.insert(make(i));
    for (std::uint32_t i = 1000; i < 50000; ++i) ASSERT_EQ(append_one(index, make(i), hash_words(make(i), words)), i);
    EXPECT_EQ(index.find(make(1500)), PackedKeyIndex::kAbsent);  // not indexed yet
    EXPECT_EQ(index.unindexed(), 49000u);
    EXPECT_EQ(index.index_appended(), PackedKeyIndex::kAbsent);
    EXPECT_EQ(index.unindexed(), 0u);
    for (std::uint32_t i = 0; i < 50000; ++i) ASSERT_EQ(index.find(make(i)), i);
    EXPECT_EQ(index.find(make(50000)), PackedKeyIndex::kAbsent);
    // Two keys that are there already, among new ones, in random order of hashes.
    std::vector<std::uint32_t> extra = {50000, 50001, 70, 50002, 49000, 50003};
    std::shuffle(extra.begin(), extra.end(), rng);
    std::uint32_t first_duplicate = PackedKeyIndex::kAbsent;
    for (std::uint32_t i : extra) {
      const std::uint32_t id = append_one(index, make(i), hash_words(make(i), words));
      if (i < 50000) first_duplicate = std::min(first_duplicate, id);
    }
    EXPECT_EQ(index.index_appended(), first_duplicate);
    for (std::uint32_t id = 50000; id < index.size(); ++id) {
      const std::uint32_t found = index.find(index.key(id));
      ASSERT_TRUE(found == id || found < 50000) << id;
    }
    index.truncate(30000);
    EXPECT_EQ(index.size(), 30000u);
    for (std::uint32_t i = 0; i < 50000; ++i) ASSERT_EQ(index.find(make(i)), i < 30000 ? i : PackedKeyIndex::kAbsent);
  }
}

// The parallel walk's bulk append: n ids at once, keys written afterwards in any order (here by two
// threads, each taking every other id), then indexed like keys appended one by one.
TEST(PackedKeyIndex, RepeatedKeysFoundBySortingHashes) {
  std::mt19937_64 rng(11);
  for (const int words : {1, 3, 8}) {
    // Distinct keys, then the same with copies of earlier keys planted: the smallest id that
    // repeats an earlier key is reported, whichever way the keys come in.
    const std::size_t n = 50000;
    UninitializedHugeVector<std::uint32_t> keys(n * words);
    for (std::size_t i = 0; i < n; ++i)
      for (int w = 0; w < words; ++w) keys[i * words + w] = static_cast<std::uint32_t>(i * 2654435761u) + w;
    const PackedKeyIndex distinct = PackedKeyIndex::from_keys(words, UninitializedHugeVector<std::uint32_t>(keys));
    ASSERT_EQ(distinct.size(), n);
    EXPECT_FALSE(distinct.indexed());
    EXPECT_EQ(distinct.repeated_key(), PackedKeyIndex::kAbsent) << words;
    for (int trial = 0; trial < 5; ++trial) {
      UninitializedHugeVector<std::uint32_t> planted = keys;
      std::uint32_t first = PackedKeyIndex::kAbsent;
      for (int copies = 0; copies < 3; ++copies) {
        const std::size_t to = 1 + rng() % (n - 1), from = rng() % to;
        std::copy_n(keys.data() + from * words, words, planted.data() + to * words);
        first = std::min(first, static_cast<std::uint32_t>(to));
      }
      // (a planted copy may overwrite the original of another: recount from the keys themselves)
      std::set<std::vector<std::uint32_t>> seen;
      std::uint32_t expected = PackedKeyIndex::kAbsent;
      for (std::uint32_t i = 0; i < n && expected == PackedKeyIndex::kAbsent; ++i)
        if (!seen.insert({planted.begin() + i * words, planted.begin() + (i + 1) * words}).second) expected = i;
      ASSERT_NE(expected, PackedKeyIndex::kAbsent);
      EXPECT_LE(expected, first);
      EXPECT_EQ(PackedKeyIndex::from_keys(words, std::move(planted)).repeated_key(), expected) << words;
    }
  }
  // Every key the same: one run of equal hashes, sorted rather than compared pair by pair.
  UninitializedHugeVector<std::uint32_t> same(200000 * 2, 7u);
  EXPECT_EQ(PackedKeyIndex::from_keys(2, std::move(same)).repeated_key(), 1u);
  // Keys that collide in the 32 bits sorted (only the full keys tell them apart) are not repeats:
  // word pairs with the same hash tag found by search would do, but any tags that collide by
  // chance among 2^20 keys (about 2^7 pairs) are compared as well.
  UninitializedHugeVector<std::uint32_t> many(std::size_t{1} << 20);
  for (std::uint32_t i = 0; i < many.size(); ++i) many[i] = i;
  EXPECT_EQ(PackedKeyIndex::from_keys(1, std::move(many)).repeated_key(), PackedKeyIndex::kAbsent);
  EXPECT_EQ(PackedKeyIndex(4).repeated_key(), PackedKeyIndex::kAbsent);
  EXPECT_THROW(PackedKeyIndex::from_keys(3, UninitializedHugeVector<std::uint32_t>(4)), std::logic_error);
}

TEST(PackedKeyIndex, ParallelWritesOfKeysAppendedInBulk) {
  for (int words : {1, 4}) {
    PackedKeyIndex index(words);
    const auto make = [&](std::uint32_t i) {
      std::vector<std::uint32_t> key(words);
      for (int w = 0; w < words; ++w) key[w] = i * 2246822519u + static_cast<std::uint32_t>(w);
      return key;
    };
    for (std::uint32_t i = 0; i < 100; ++i) index.insert(make(i).data());
    std::uint32_t next = 100;
    for (std::uint32_t n : {1u, 0u, 700u, 20000u, 3u, 150000u}) {  // grows through big blocks
      ASSERT_EQ(index.append_unindexed(n), next);
      ASSERT_EQ(index.size(), next + n);
      const auto write = [&](std::uint32_t parity) {
        for (std::uint32_t id = next + n; id-- > next;)
          if (id % 2 == parity) index.set_appended(id, make(id).data(), hash_words(make(id).data(), words));
      };
      std::thread other(write, 1);
      write(0);
      other.join();
      next += n;
    }
    EXPECT_EQ(index.unindexed(), next - 100);
    EXPECT_EQ(index.index_appended(), PackedKeyIndex::kAbsent);
    for (std::uint32_t i = 0; i < next; ++i) ASSERT_EQ(index.find(make(i).data()), i);
    EXPECT_EQ(index.find(make(next).data()), PackedKeyIndex::kAbsent);
    // A big array grown with headroom counts the pages written, not the capacity reserved.
    EXPECT_LE(index.bytes(), HugePageAllocator<std::uint32_t>::round_up(std::size_t{4} * words * next) +
                                 HugePageAllocator<std::uint64_t>::round_up(8 * (2 * std::size_t{next} + 2) * 2));
  }
}

TEST(HugePageAllocator, GrowingWithHeadroomKeepsTheContents) {
  UninitializedHugeVector<std::uint64_t> v;
  std::size_t moves = 0;
  for (std::uint64_t n = 1; n <= 3'000'000; n = n * 3 / 2 + 1) {
    const std::size_t old = v.size();
    const std::uint64_t* before = v.data();
    grow_with_headroom(v, n);
    moves += v.data() != before;
    for (std::size_t i = old; i < n; ++i) v[i] = i * i;
  }
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], i * i);
  EXPECT_LE(moves, 10u);  // 8 times the capacity per move: a few moves from 1 to 3 million
  EXPECT_LE(held_bytes(v), HugePageAllocator<std::uint64_t>::round_up(8 * v.size()));
}

// Where 8 times the capacity is more address space than the process may have, growth falls back to
// the vector's own (in a child process with a limit on its address space).
TEST(HugePageAllocator, GrowingWithHeadroomFallsBackWhenAddressSpaceIsShort) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "sanitizers map address space of their own";
#else
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    constexpr std::size_t kMiB = std::size_t{1} << 20;
    UninitializedHugeVector<char> v(64 * kMiB);
    std::ifstream statm("/proc/self/statm");
    std::size_t pages = 0;
    statm >> pages;
    const rlim_t limit = pages * static_cast<std::size_t>(sysconf(_SC_PAGESIZE)) + 300 * kMiB;
    const rlimit r{limit, limit};
    if (setrlimit(RLIMIT_AS, &r) != 0) _exit(2);
    try {
      grow_with_headroom(v, 64 * kMiB + 1);  // 8 × 64 MiB does not fit under the limit, 2 × does
    } catch (...) {
      _exit(3);
    }
    _exit(v.size() == 64 * kMiB + 1 && v.capacity() < 512 * kMiB ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
#endif
}

// New hash tables rely on this: small blocks are zeroed by hand, big ones come zero-filled from the
// kernel; also right after a block of the same size was written and freed.
TEST(HugePageAllocator, ZeroedVectorsAreZero) {
  for (std::size_t n : {std::size_t{100}, (std::size_t{2} << 20) / 8, (std::size_t{5} << 20) / 8 + 3})
    for (int round = 0; round < 2; ++round) {
      {
        UninitializedHugeVector<std::uint64_t> dirty(n);
        std::fill(dirty.begin(), dirty.end(), ~std::uint64_t{0});
      }
      const auto v = zeroed_huge_vector<std::uint64_t>(n);
      ASSERT_EQ(v.size(), n);
      ASSERT_TRUE(std::all_of(v.begin(), v.end(), [](std::uint64_t x) { return x == 0; })) << n << " words";
    }
}

// A level handed to a mesh writer keeps its size without its keys: no memory for them, no look-up.
TEST(PackedKeyIndex, WithoutKeysCountsOnly) {
  const PackedKeyIndex index = PackedKeyIndex::without_keys(1000);
  EXPECT_EQ(index.size(), 1000u);
  EXPECT_EQ(index.words(), 0);
  EXPECT_FALSE(index.indexed());
  EXPECT_EQ(index.bytes(), 0u);
  const std::uint32_t key[1] = {7};
  EXPECT_THROW(index.find(key), std::logic_error);
}
