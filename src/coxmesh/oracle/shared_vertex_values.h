// Function values at lattice vertices, shared by the oracles of several threads, so that F is
// evaluated once per lattice vertex however many workers trace.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/util/linear_probe.h"

namespace coxmesh {

/// Thread-safe map lattice vertex → `stride` values. Lookups of stored vertices take no lock and
/// write nothing shared: they read one open-addressing table whose slots are published with release
/// stores after the key and values they point to, so its cache lines stay shared between cores
/// instead of moving at every lookup. The table is one block (one table per shard missed the TLB at
/// almost every lookup: docs/benchmarks.md). Storing a vertex takes the
/// lock of its shard (one of 32, by hash), held while F is evaluated, so no vertex is evaluated
/// twice; its key and values go to the shard's blocks, and its slot is claimed by compare-and-swap
/// (other shards store at the same time). The table is replaced by one twice its size, with every
/// shard locked, when a shard fills half its share of it; readers still probing the old one may
/// miss the newest vertices and then take the lock.
class SharedVertexValues {
 public:
  SharedVertexValues(int d, int stride) : d_(d), stride_(stride) {
    tables_.push_back(std::make_unique<Table>(1024));
    table_.store(tables_.back().get(), std::memory_order_relaxed);
  }
  int dimension() const { return d_; }
  int stride() const { return stride_; }

  /// Copies the values of vertex v (hash = hash_words of its d coordinates) to out, calling
  /// evaluate(out) first if no thread has stored them yet. Returns true when evaluate was called.
  template <class Evaluate>
  bool get(const std::int32_t* v, std::uint64_t hash, double* out, Evaluate&& evaluate) {
    if (const double* stored = find(v, hash)) return std::copy(stored, stored + stride_, out), false;
    const std::uint32_t shard = hash & (kShards - 1);  // (low bits: the table places keys by the top ones)
    Shard& s = shards_[shard];
    double* stored;
    std::size_t stored_in_shard;
    {
      std::unique_lock<std::mutex> lock(s.mutex);
      if (const double* found = find(v, hash)) return std::copy(found, found + stride_, out), false;
      // Each shard may fill up to 3/4 of its share of the table, so the table never fills up; the
      // table doubles when a shard fills half its share. (Counts per shard: one count for all
      // shards would move between the cores at every store.)
      while (4 * (std::size_t{s.size} + 1) * kShards > 3 * table_.load(std::memory_order_acquire)->size()) {
        lock.unlock();  // (grow() takes every shard's lock)
        grow();
        lock.lock();
        if (const double* found = find(v, hash)) return std::copy(found, found + stride_, out), false;
      }
      if (s.size >= kMaxPerShard) throw InputError("more than 2^27 - 2 vertices in one shard of the shared values");
      const std::uint32_t id = s.size;
      std::uint32_t offset;
      const int b = block_of(id, offset);
      if (!s.keys[b]) {
        const std::size_t n = std::size_t{kFirstBlock} << b;
        s.keys[b] = std::make_unique<std::int32_t[]>(n * d_);
        s.values[b] = std::make_unique<double[]>(n * stride_);
      }
      std::copy(v, v + d_, s.keys[b].get() + std::size_t{offset} * d_);
      stored = s.values[b].get() + std::size_t{offset} * stride_;
      try {
        evaluate(stored);
      } catch (...) {  // a later lookup finds NaN, which callers reject like the error itself
        std::fill(stored, stored + stride_, std::numeric_limits<double>::quiet_NaN());
        publish(s, shard, hash, id);
        throw;
      }
      publish(s, shard, hash, id);
      stored_in_shard = s.size;
    }
    if (2 * stored_in_shard * kShards > table_.load(std::memory_order_acquire)->size()) grow();
    std::copy(stored, stored + stride_, out);
    return true;
  }

  /// A hint: get(v, hash) follows soon (its slot is loaded into the cache).
  void prefetch(std::uint64_t hash) const {
    const Table* t = table_.load(std::memory_order_acquire);
    __builtin_prefetch(&t->slots[t->probe.home(LinearProbe::tag_of(hash))]);
  }

 private:
  // (32 shards: growing holds every shard's lock and the growth lock, and ThreadSanitizer follows at
  // most 64 locks held at once)
  static constexpr std::uint32_t kShards = 32, kFirstBlock = 256;
  static constexpr std::uint32_t kIdBits = 27, kMaxPerShard = (1u << kIdBits) - 2;

  // Slots (util/linear_probe.h): (top 32 bits of the hash) << 32 | shard << 27 | (id in the shard
  // + 1), 0 = empty.
  struct Table {
    explicit Table(std::size_t capacity) : slots(capacity), probe(capacity) {}
    std::size_t size() const { return slots.size(); }
    HugeVector<std::atomic<std::uint64_t>> slots;
    LinearProbe probe;
  };
  struct alignas(64) Shard {
    std::mutex mutex;  // taken to store a vertex
    std::uint32_t size = 0;
    // Entry id's key and values, in blocks of 256·2^b entries that never move.
    std::array<std::unique_ptr<std::int32_t[]>, 32> keys;
    std::array<std::unique_ptr<double[]>, 32> values;
  };

  static int block_of(std::uint32_t id, std::uint32_t& offset) {
    const int b = std::bit_width(id / kFirstBlock + 1) - 1;
    offset = id - kFirstBlock * ((1u << b) - 1);
    return b;
  }

  const double* find(const std::int32_t* v, std::uint64_t hash) const {
    const Table* t = table_.load(std::memory_order_acquire);
    const double* values = nullptr;
    t->probe.find(
        LinearProbe::tag_of(hash), [t](std::size_t i) { return t->slots[i].load(std::memory_order_acquire); },
        [&](std::uint32_t payload) {
          const Shard& s = shards_[payload >> kIdBits];
          std::uint32_t offset;
          const int b = block_of((payload & ((1u << kIdBits) - 1)) - 1, offset);
          const std::int32_t* key = s.keys[b].get() + std::size_t{offset} * d_;
          std::int32_t diff = 0;
          for (int j = 0; j < d_; ++j) diff |= key[j] ^ v[j];
          if (diff == 0) values = s.values[b].get() + std::size_t{offset} * stride_;
          return diff == 0;
        });
    return values;
  }

  // Called with the shard's lock held, after the entry's key and values are written.
  void publish(Shard& s, std::uint32_t shard, std::uint64_t hash, std::uint32_t id) {
    ++s.size;
    const std::uint64_t slot = LinearProbe::entry(hash, (shard << kIdBits) | (id + 1));
    Table& t = *tables_.back();  // (the current table: it only changes with every shard locked)
    t.probe.walk(LinearProbe::tag_of(hash), [&](std::size_t i) {  // (other shards claim slots at the same time)
      std::uint64_t empty = 0;
      return t.slots[i].compare_exchange_strong(empty, slot, std::memory_order_release, std::memory_order_relaxed);
    });
  }

  // Doubles the table unless another thread did; no shard lock may be held by the caller.
  void grow() {
    std::lock_guard<std::mutex> growing(grow_mutex_);
    std::array<std::unique_lock<std::mutex>, kShards> locks;
    std::size_t fullest = 0;
    for (std::uint32_t k = 0; k < kShards; ++k) {
      locks[k] = std::unique_lock<std::mutex>(shards_[k].mutex);
      fullest = std::max<std::size_t>(fullest, shards_[k].size);
    }
    if (2 * fullest * kShards <= tables_.back()->size()) return;  // (another thread grew it)
    const Table& old = *tables_.back();
    tables_.push_back(std::make_unique<Table>(2 * old.size()));
    Table& bigger = *tables_.back();
    for (const auto& slot : old.slots) {
      const std::uint64_t x = slot.load(std::memory_order_relaxed);
      if (x == 0) continue;
      const std::size_t i = bigger.probe.find_empty(
          LinearProbe::tag_of(x), [&](std::size_t j) { return bigger.slots[j].load(std::memory_order_relaxed); });
      bigger.slots[i].store(x, std::memory_order_relaxed);
    }
    table_.store(&bigger, std::memory_order_release);  // old tables stay for readers still in them
  }

  int d_, stride_;
  std::array<Shard, kShards> shards_;
  std::atomic<const Table*> table_{nullptr};
  std::vector<std::unique_ptr<Table>> tables_;  // the current one last
  std::mutex grow_mutex_;
};

}  // namespace coxmesh
