// Thesis §4.2 with many threads: the level-synchronous variant of the sequential walk
// (walk_sequential.h), with the same S in the same order. Internal to tracing (not installed).
#pragma once

#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "coxmesh/tracing/walk_sequential.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh::walk {

// Walks S of a SequentialWalk breadth-first level by level, one worker per oracle (the first
// oracle being the sequential walk's). Each level's simplices are processed in chunks by the
// sequential walk's loop; what a chunk discovers goes to the chunk's buffer, and the buffers are
// merged into S in chunk order, so S and its order are those of the sequential walk.
//
//   SequentialWalk seq(T, *oracles[0], options);
//   ParallelWalk par(seq, oracles);
//   for (seed : seeds) seq.add_seed(seed, true), par.walk();
class ParallelWalk {
 public:
  ParallelWalk(SequentialWalk& walk, const std::vector<IntersectionOracle*>& oracles);

  void walk();
  std::uint64_t oracle_calls() const;  // the workers' calls (the sequential walk counts its own)

 private:
  // What one chunk of a level discovered, in encounter order: inside simplices (key, hash, point,
  // D̂) and boundary simplices (key, point). Merged in chunk order, so the result is deterministic.
  struct alignas(64) ChunkOutput {
    std::vector<std::uint32_t> inside_keys, boundary_keys;
    std::vector<std::uint64_t> inside_hashes, inside_arrivals;
    std::vector<double> inside_data, boundary_points;
    std::vector<std::uint32_t> inside_ids;  // per inside simplex, its id in S (set by the merge)
    // The cofacets kept (TraceOptions::keep_cofacets), as SequentialWalk keeps them; `other` is an
    // id of S, kMiss, or kRow | chunk << 32 | row: an inside simplex output by a chunk of the level.
    struct KeptCofacet {
      std::uint32_t tau, place;
      std::uint64_t other;
    };
    static constexpr std::uint64_t kRow = std::uint64_t{1} << 63;
    std::vector<KeptCofacet> kept;
    // Cofacets walked to a simplex of the next level (`row`: kRow | chunk << 32 | row), at their
    // place among its cofacets: SequentialWalk::settled_, set by the merge.
    struct Settled {
      std::uint64_t row;
      std::uint32_t place;
    };
    std::vector<Settled> settled;
    std::uint64_t cofacets_met = 0;
    void clear() {
      inside_keys.clear(), boundary_keys.clear(), inside_hashes.clear(), inside_arrivals.clear(), inside_data.clear(),
          boundary_points.clear(), inside_ids.clear(), kept.clear(), settled.clear();
      cofacets_met = 0;
    }
  };
  // A worker's oracle and its memory of the simplices it tested in the current level that were not
  // in S: workers share nothing but S, which no one modifies during a level.
  struct alignas(64) Worker {
    IntersectionOracle* oracle;
    PackedKeyIndex tested;
    std::vector<std::uint32_t> payload;     // kMiss or index into data
    std::vector<std::uint32_t> output_in;   // per tested simplex inside: the first chunk that output it
    std::vector<std::uint32_t> output_row;  // and its row there
    std::vector<double> data;               // (d + 1) per transverse simplex: point, D̂
    std::uint64_t calls;
    // The simplices of S that a level's walk can meet: its own and the previous level's (a
    // neighbour of a simplex of level L is in level L − 1, L or L + 1). Two small indexes of
    // ids [near_range[i].first, near_range[i].second) of S instead of S's big one, whose lookups
    // missed the caches; one pair per worker, built by the worker itself: lookups of lines that
    // another core wrote last cost several times a local read.
    PackedKeyIndex near[2];
    std::pair<std::uint32_t, std::uint32_t> near_range[2];
  };
  // Which chunks of a level are left: worker w starts at the front of its own contiguous share, so
  // it keeps to one region of the manifold (its caches, its memory of tested simplices); a worker
  // out of chunks takes the last chunk of the largest remaining share.
  class ChunkClaims {
   public:
    void reset(std::size_t chunks, std::size_t workers) {
      shares_.clear();
      for (std::size_t w = 0; w < workers; ++w) shares_.push_back({chunks * w / workers, chunks * (w + 1) / workers});
    }
    bool claim(std::size_t share, std::size_t& chunk) {
      std::lock_guard<std::mutex> lock(mutex_);
      auto& [front, back] = shares_[share];
      if (front < back) return chunk = front++, true;
      std::size_t largest = 0;
      for (std::size_t w = 1; w < shares_.size(); ++w)
        if (shares_[w].second - shares_[w].first > shares_[largest].second - shares_[largest].first) largest = w;
      if (shares_[largest].first == shares_[largest].second) return false;
      return chunk = --shares_[largest].second, true;
    }

   private:
    std::mutex mutex_;
    std::vector<std::pair<std::size_t, std::size_t>> shares_;  // [front, back) per worker
  };
  // What a parallel walk changes, to undo it when it has to be redone sequentially.
  struct Mark {
    std::uint32_t head, simplices, boundary_simplices;
    std::size_t last_progress;
    TraceStatus status;
    std::size_t kept_cofacets;
    std::uint64_t cofacets_met;
  };

  bool walk_levels();
  Mark mark() const;
  void undo(const Mark& m);
  void process_chunk(std::uint32_t chunk, std::uint32_t begin, std::uint32_t end, Worker& worker, ChunkOutput& out);
  // (`other`: where an inside simplex is, as ChunkOutput::KeptCofacet::other)
  Found classify_in_level(const Simplex& tau, std::uint32_t chunk, Worker& worker, ChunkOutput& out,
                          std::uint64_t& other);
  void keep_cofacets(std::size_t n_chunks);
  void settle(const Simplex& mu, int facet, std::uint64_t other, ChunkOutput& out);
  void open_windows(Worker& worker) const;
  static inline std::uint32_t find_near(const Worker& worker, const std::uint32_t* key, std::uint64_t hash);
  const std::uint32_t* source_key(const std::vector<ChunkOutput>& outputs, std::uint64_t source) const {
    return outputs[source >> 32].inside_keys.data() + static_cast<std::uint32_t>(source) * packed_words(d_);
  }
  void merge(std::size_t n_chunks);
  void fill(std::uint32_t begin, std::uint32_t end);
  void fill_pending();

  SequentialWalk& s_;  // S and the queue; the walk redone when the parallel one fails
  const int d_, k_;
  std::vector<Worker> workers_;
  // The chunks' outputs of the last two levels: the merge appends level L + 1 to S without copying
  // it, and the workers of level L + 1 copy each simplex in when they take its chunk (`fill`).
  std::vector<ChunkOutput> chunks_[2];
  int current_ = 0;                                        // which of chunks_ the level being walked writes
  std::vector<std::uint64_t> sources_;                     // per simplex of S from `pending_.first`: chunk << 32 | row
  std::pair<std::uint32_t, std::uint32_t> pending_{0, 0};  // ids of S appended and not copied in yet
  ChunkClaims claims_;
  std::pair<std::uint32_t, std::uint32_t> level_, previous_level_;  // ids of S
  std::vector<std::uint64_t> firsts_;  // the merge's hash table: tag << 32 | 1 + index into sources_
  std::unique_ptr<WorkerPool> pool_;   // started by the first parallel level
};

}  // namespace coxmesh::walk
