// Function values at lattice vertices, shared by the oracles of several threads, so that F is
// evaluated once per lattice vertex however many workers trace (issue 6).
#pragma once

#include <array>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "coxmesh/lattice/packed_index.h"

namespace coxmesh {

/// Thread-safe map lattice vertex → `stride` values. 64 shards, each with its own lock, chosen by
/// the vertex hash: no global lock, and a lookup holds one shard for a probe (and, the first time a
/// vertex is seen, for its evaluation, so no vertex is evaluated twice).
class SharedVertexValues {
 public:
  SharedVertexValues(int d, int stride) : d_(d), stride_(stride) {
    for (Shard& s : shards_) s.index = PackedKeyIndex(d);
  }
  int dimension() const { return d_; }
  int stride() const { return stride_; }

  /// Copies the values of vertex v (hash = hash_words of its d coordinates) to out, calling
  /// evaluate(out) first if no thread has stored them yet. Returns true when evaluate was called.
  template <class Evaluate>
  bool get(const std::int32_t* v, std::uint64_t hash, double* out, Evaluate&& evaluate) {
    Shard& s = shards_[hash & 63];  // (low bits: the shard's index places keys by the top ones)
    std::lock_guard<std::mutex> lock(s.mutex);
    const auto [id, inserted] = s.index.insert(reinterpret_cast<const std::uint32_t*>(v), hash);
    double* stored;
    if (inserted) {
      s.values.resize(s.values.size() + stride_);
      stored = s.values.data() + static_cast<std::size_t>(id) * stride_;
      try {
        evaluate(stored);
      } catch (...) {  // a later lookup finds NaN, which callers reject like the error itself
        std::fill(stored, stored + stride_, std::numeric_limits<double>::quiet_NaN());
        throw;
      }
    } else {
      stored = s.values.data() + static_cast<std::size_t>(id) * stride_;
    }
    std::copy(stored, stored + stride_, out);
    return inserted;
  }

 private:
  struct alignas(64) Shard {
    std::mutex mutex;
    PackedKeyIndex index{1};
    HugeVector<double> values;
  };
  int d_, stride_;
  std::array<Shard, 64> shards_;
};

}  // namespace coxmesh
