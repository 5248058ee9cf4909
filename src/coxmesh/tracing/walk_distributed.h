// Thesis §4.2 over several processes: the level-synchronous walk of walk_parallel.h with S split
// between ranks (trace_distributed.h). Internal to tracing (not installed).
#pragma once

#include <cstddef>
#include <cstring>
#include <exception>
#include <span>
#include <vector>

#include "coxmesh/tracing/trace_distributed.h"
#include "coxmesh/tracing/walk_common.h"

namespace coxmesh::walk {

// One rank's part of the walk. S is ordered as the sequential walk orders it: level by level, and
// within a level by the discovery that found each simplex first, (id of τ) << 32 | (index of the
// cofacet of τ), or by the order of the seed search's tests. Each rank keeps the simplices it owns
// with their global ids; the ids of a new level come from every rank's discovery keys.
//
//   DistributedWalk w(T, oracle, values, evaluate, options, comm);
//   for (seed : seeds) w.add_seed(seed, true), w.walk();
//   TraceResult r = w.finish();  // complete on rank 0
class DistributedWalk {
 public:
  DistributedWalk(const Triangulation& t, IntersectionOracle& oracle, SharedVertexValues& values,
                  const VertexEvaluator& evaluate, const TraceOptions& options, Communicator& comm);

  void add_seed(std::span<const double> seed, bool must_succeed);
  void walk();
  bool stopped() const { return stopped_; }
  TraceResult finish(DistributedTraceStats* stats);
  /// The share of this rank, nothing gathered (counts summed over the ranks). Collective.
  TracePart finish_part(DistributedTraceStats* stats);

 private:
  // What a test of a k-simplex found that the caller must complete: a transverse simplex inside the
  // domain met for the first time here (the cofacet it was met through is known only to the walk).
  enum class Fresh : std::uint8_t { no, owned, remote };
  // Where classify found a simplex inside: in this rank's part of S, of the next level, or another's.
  enum class Held : std::uint8_t { mine, next, remote };
  // Payloads of others_ besides kMiss and an index into outside_.
  static constexpr std::uint32_t kRemoteInside = 0xFFFFFFFEu;  // another rank's simplex of S
  static constexpr std::uint32_t kUntested = 0xFFFFFFFDu;      // ours, tested (and counted) by another rank

  // Where an absent simplex goes in next_ and in others_ (PackedKeyIndex::find's slots).
  struct Slots {
    std::size_t next = 0, others = 0;
  };
  Found classify(const Simplex& tau);
  Found classify(const Simplex& tau, const std::uint32_t* key, std::uint64_t hash);  // key packed, hash_words
  void fetch_slots(const PendingCofacet& p);
  template <int kD>
  void finish_cofacet(std::uint32_t i, const PendingCofacet& p);
  Found test(const std::uint32_t* key, std::uint64_t hash, const Simplex& tau, int owner, std::uint32_t known,
             const Slots& slots);
  template <int kD>
  void settle(std::uint32_t i, const PendingCofacet& p, const Found& f);
  void walk_level();
  template <int kD>  // (d fixed at compile time, 0: read at run time)
  void walk_level();
  bool start_level();
  void exchange_candidates();
  void append_level();
  std::vector<std::uint64_t> next_keys_in_order(std::vector<std::uint32_t>& order) const;
  void join_level(const std::vector<std::uint32_t>& order, const std::vector<std::uint64_t>& all,
                  const std::vector<std::size_t>& run_begin);
  void fetch_vertex_values(const std::vector<std::int32_t>& vertices);
  std::exception_ptr push_vertex_values(const std::vector<std::int32_t>& vertices);
  void evaluate_here(const std::int32_t* v, double* out);
  // Rethrows, on every rank, the first failure of any rank (nullptr: none here). Collective.
  void agree(std::exception_ptr failure);
  // The job's counts (oracle calls, F evaluations) into `r`, the cost into `stats`. Collective.
  void sum_counts(std::uint64_t& oracle_calls, std::uint64_t& function_evaluations, DistributedTraceStats* stats);

  const Triangulation& t_;
  IntersectionOracle& oracle_;
  SharedVertexValues& values_;
  const VertexEvaluator& evaluate_;
  const TraceOptions& options_;
  Communicator& comm_;
  const int d_, k_, words_, rank_, ranks_;

  // This rank's part of S: keys, global ids (increasing), points, D̂ and settled cofacets (as
  // SequentialWalk::settled_: all of them that this rank or a sender of the simplex walked, with an
  // oracle that promises two transverse facets per cofacet, else the one it was discovered through).
  PackedKeyIndex mine_;
  std::vector<std::uint32_t> global_ids_;
  std::vector<double> points_, domain_values_;
  std::vector<std::uint64_t> settled_;
  const bool settle_cofacets_;
  std::uint64_t global_size_ = 0;                  // |S| over all ranks
  std::uint32_t level_begin_ = 0, level_end_ = 0;  // this rank's part of the level being walked
  // The next level's simplices owned here, with their discovery keys (the smallest seen wins).
  PackedKeyIndex next_;
  std::vector<std::uint64_t> next_keys_, next_settled_;
  std::vector<double> next_data_;  // d + 1 each: point, D̂
  // Every other tested simplex: payload kMiss, kRemoteInside, kUntested (tested by another rank),
  // or an index into outside_ (point, D̂).
  PackedKeyIndex others_;
  std::vector<std::uint32_t> other_payload_;
  std::vector<double> outside_;
  // Lattice vertices whose values are in values_.
  PackedKeyIndex known_vertices_;
  // Per rank: transverse simplices found for it this level, and the keys it owns tested here.
  std::vector<std::vector<std::byte>> candidates_out_, tested_out_;
  // S_∂ found here: (id of τ) << 32 | cofacet, key and point.
  std::vector<std::uint64_t> boundary_keys_;
  std::vector<std::uint32_t> boundary_simplices_;
  std::vector<double> boundary_points_;

  std::uint64_t level_global_size_ = 0;  // the level to walk, over all ranks
  std::uint64_t discovery_ = 0;          // the key of what the current test discovers
  bool reporting_ = true;                // send discoveries and tests to their owners (not in the seed search)
  Fresh fresh_ = Fresh::no;
  Held held_ = Held::mine;  // (of the last simplex classify found inside)
  int fresh_owner_ = 0;
  std::size_t fresh_at_ = 0;  // where its settled cofacets go (next_ id, or byte offset in candidates_out_)
  std::vector<double> point_;
  LastOwner last_owner_;  // (of a tested simplex's minimal vertex)
  std::uint64_t calls_ = 0, tests_ = 0, evaluations_ = 0, vertex_values_sent_ = 0, candidates_sent_ = 0, levels_ = 0;
  std::size_t last_progress_ = 0;
  bool stopped_ = false;
};

}  // namespace coxmesh::walk
