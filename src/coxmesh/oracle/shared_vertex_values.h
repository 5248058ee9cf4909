// Function values at lattice vertices, shared by the oracles of several threads, so that F is
// evaluated once per lattice vertex however many workers trace (issue 6).
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

namespace coxmesh {

/// Thread-safe map lattice vertex → `stride` values, in 64 shards chosen by the vertex hash.
/// Lookups of stored vertices take no lock and write nothing shared: they read an open-addressing
/// table whose slots are published with release stores after the key and values they point to, so
/// the cache lines of a shard stay shared between cores instead of moving at every lookup (a lock
/// per lookup cost a third of the parallel walk). Storing a vertex takes the shard's lock, which is
/// held while F is evaluated, so no vertex is evaluated twice. A full table is replaced by one twice
/// its size; readers still probing the old one may miss the newest vertices and then take the lock.
class SharedVertexValues {
 public:
  SharedVertexValues(int d, int stride) : d_(d), stride_(stride) {
    for (Shard& s : shards_) {
      s.tables.push_back(std::make_unique<Table>(16));
      s.table.store(s.tables.back().get(), std::memory_order_relaxed);
    }
  }
  int dimension() const { return d_; }
  int stride() const { return stride_; }

  /// Copies the values of vertex v (hash = hash_words of its d coordinates) to out, calling
  /// evaluate(out) first if no thread has stored them yet. Returns true when evaluate was called.
  template <class Evaluate>
  bool get(const std::int32_t* v, std::uint64_t hash, double* out, Evaluate&& evaluate) {
    Shard& s = shards_[hash & (kShards - 1)];  // (low bits: tables place keys by the top ones)
    if (const double* stored = find(s, v, hash)) return std::copy(stored, stored + stride_, out), false;
    std::lock_guard<std::mutex> lock(s.mutex);
    if (const double* stored = find(s, v, hash)) return std::copy(stored, stored + stride_, out), false;
    if (s.size >= PackedKeyIndex::kMaxEntries) throw InputError("more than 2^31 - 1 vertices in one shard");
    const std::uint32_t id = s.size;
    std::uint32_t offset;
    const int b = block_of(id, offset);
    if (!s.keys[b]) {
      const std::size_t n = std::size_t{kFirstBlock} << b;
      s.keys[b] = std::make_unique<std::int32_t[]>(n * d_);
      s.values[b] = std::make_unique<double[]>(n * stride_);
    }
    std::copy(v, v + d_, s.keys[b].get() + std::size_t{offset} * d_);
    double* stored = s.values[b].get() + std::size_t{offset} * stride_;
    try {
      evaluate(stored);
    } catch (...) {  // a later lookup finds NaN, which callers reject like the error itself
      std::fill(stored, stored + stride_, std::numeric_limits<double>::quiet_NaN());
      publish(s, hash, id);
      throw;
    }
    publish(s, hash, id);
    std::copy(stored, stored + stride_, out);
    return true;
  }

 private:
  static constexpr std::uint32_t kShards = 64, kFirstBlock = 256;

  // Slots: (top 32 bits of the hash) << 32 | (id + 1), 0 = empty; home slot = leading hash bits.
  struct Table {
    explicit Table(std::size_t capacity)
        : slots(capacity), mask(capacity - 1), shift(32 - std::countr_zero(capacity)) {}
    std::size_t home(std::uint32_t tag) const { return static_cast<std::size_t>(tag) >> shift; }
    HugeVector<std::atomic<std::uint64_t>> slots;
    std::size_t mask;
    int shift;
  };
  struct alignas(64) Shard {
    std::atomic<const Table*> table{nullptr};
    std::mutex mutex;  // taken to store a vertex
    std::uint32_t size = 0;
    std::vector<std::unique_ptr<Table>> tables;  // the current one last; older ones stay for readers
    // Entry id's key and values, in blocks of 256·2^b entries that never move.
    std::array<std::unique_ptr<std::int32_t[]>, 32> keys;
    std::array<std::unique_ptr<double[]>, 32> values;
  };

  static int block_of(std::uint32_t id, std::uint32_t& offset) {
    const int b = std::bit_width(id / kFirstBlock + 1) - 1;
    offset = id - kFirstBlock * ((1u << b) - 1);
    return b;
  }

  const double* find(const Shard& s, const std::int32_t* v, std::uint64_t hash) const {
    const Table* t = s.table.load(std::memory_order_acquire);
    const std::uint32_t tag = static_cast<std::uint32_t>(hash >> 32);
    for (std::size_t i = t->home(tag);; i = (i + 1) & t->mask) {
      const std::uint64_t slot = t->slots[i].load(std::memory_order_acquire);
      if (slot == 0) return nullptr;
      if (static_cast<std::uint32_t>(slot >> 32) != tag) continue;
      std::uint32_t offset;
      const int b = block_of(static_cast<std::uint32_t>(slot) - 1, offset);
      const std::int32_t* key = s.keys[b].get() + std::size_t{offset} * d_;
      std::int32_t diff = 0;
      for (int j = 0; j < d_; ++j) diff |= key[j] ^ v[j];
      if (diff == 0) return s.values[b].get() + std::size_t{offset} * stride_;
    }
  }

  // Called with the shard's lock held, after the entry's key and values are written.
  void publish(Shard& s, std::uint64_t hash, std::uint32_t id) {
    ++s.size;
    Table* t = s.tables.back().get();
    if (2 * std::size_t{s.size} > t->slots.size()) {  // load ≤ 1/2
      s.tables.push_back(std::make_unique<Table>(2 * t->slots.size()));
      Table* bigger = s.tables.back().get();
      for (const auto& slot : t->slots)
        if (const std::uint64_t x = slot.load(std::memory_order_relaxed)) place(*bigger, x, std::memory_order_relaxed);
      place(*bigger, (hash >> 32 << 32) | (id + 1), std::memory_order_relaxed);
      s.table.store(bigger, std::memory_order_release);
      return;
    }
    place(*t, (hash >> 32 << 32) | (id + 1), std::memory_order_release);
  }
  static void place(Table& t, std::uint64_t slot, std::memory_order order) {
    std::size_t i = t.home(static_cast<std::uint32_t>(slot >> 32));
    while (t.slots[i].load(std::memory_order_relaxed) != 0) i = (i + 1) & t.mask;
    t.slots[i].store(slot, order);
  }

  int d_, stride_;
  std::array<Shard, kShards> shards_;
};

}  // namespace coxmesh
