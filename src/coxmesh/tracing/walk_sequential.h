// Thesis §4.2: the manifold tracing algorithm, one simplex at a time. Internal to tracing (not
// installed); trace_manifold.h is the public interface.
#pragma once

#include <span>
#include <vector>

#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/tracing/walk_common.h"

namespace coxmesh::walk {

class ParallelWalk;

// The walk and its state. S lives in the result and is also the breadth-first queue (S[head..]);
// every other tested k-simplex is remembered in `others_` (not transverse, or transverse outside
// the domain with its point), so the oracle sees each k-simplex at most once.
//
//   SequentialWalk w(T, oracle, options);
//   for (seed : seeds) w.add_seed(seed, true), w.walk();
//   TraceResult r = w.finish();
class SequentialWalk {
 public:
  SequentialWalk(const Triangulation& t, IntersectionOracle& oracle, const TraceOptions& options);

  // Puts into S the k-simplices meeting M̂ inside the domain among the faces of the d-simplices
  // around the seed (up to options.seed_search_rings rings). Throws SeedError if there are none
  // and must_succeed.
  void add_seed(std::span<const double> seed, bool must_succeed);
  // Walks from every simplex of S not walked yet, until S is closed (or the simplex limit).
  void walk();
  // The simplex limit stopped the walk.
  bool stopped() const { return result_.status == TraceStatus::max_simplices_reached; }
  // The result; oracle_calls counts this walk's calls, function_evaluations is left to the caller.
  TraceResult finish();

 private:
  friend class ParallelWalk;  // the level-synchronous variant: appends to S itself

  template <int kD>  // d = kD at compile time, or 0 (walk_common.h)
  void walk_from_head();
  template <int kD>
  void finish_cofacet(const PendingCofacet& p);
  void keep_cofacet(std::uint32_t tau, std::uint32_t place, std::uint32_t other);  // other: an id of S or kMiss
  template <int kD>
  void settle(const Simplex& mu, int facet, std::uint32_t id);  // μ walked to S[id], μ without vertex `facet`

  template <int kD>
  Found classify(const Simplex& tau);
  Found classify(const Simplex& tau, const std::uint32_t* key, std::uint64_t hash);  // key packed, hash_words
  void add_boundary(const Simplex& mu, std::uint32_t inside, const double* outside);
  bool start_level();  // false when the simplex limit stops the walk

  const Triangulation& t_;
  IntersectionOracle& oracle_;
  const TraceOptions& options_;
  const int d_, k_;
  TraceResult result_;
  UninitializedHugeVector<double> domain_values_;  // D̂ at each point of S
  // Cofacets the walk passes by, as from τ it would only find again their other transverse facet, a
  // simplex of S with a smaller id that walked them. With an oracle that promises two transverse
  // facets per cofacet, all of them: bit i (i < 64) of settled_[τ] set for τ's cofacet at place i
  // (CofaceEnumerator order). Otherwise only the one τ was discovered through: arrivals_[τ].
  const bool settle_cofacets_;
  UninitializedHugeVector<std::uint64_t> settled_;
  UninitializedHugeVector<std::uint64_t> arrivals_;  // (a cofacet_code, or kNoCofacet)
  PackedKeyIndex others_;
  std::vector<std::uint32_t> other_payload_;  // kMiss or index into outside_
  std::vector<double> outside_;               // (d + 1) per transverse simplex outside: point, D̂
  std::uint32_t head_ = 0;                    // S[head_..] is the breadth-first queue
  std::uint32_t level_end_ = 0;               // end of the current breadth-first level
  std::size_t last_progress_ = 0;
  std::uint64_t calls_ = 0;
  std::vector<double> point_;
  // The cofacets kept (TraceOptions::keep_cofacets): each once, from its facet of smallest id, which
  // the walk reaches first; with its other transverse facet when that is in S too.
  bool keep_cofacets_ = false;
  IndexArray cofacet_offsets_, cofacet_facets_, cofacet_places_;
  std::uint64_t cofacets_met_ = 0;  // Σ over walked τ of its cofacets: the incidences the kept ones must have
};

}  // namespace coxmesh::walk
