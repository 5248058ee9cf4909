// Thesis §4.2 over several processes: trace_manifold with S and the lattice split between the
// ranks of a Communicator (e.g. the processes of mpirun), with the same result.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/oracle/shared_vertex_values.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/triangulation/triangulation.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh {

/// Writes the values at lattice vertex v that an ImplicitOracle keeps: F's k values, then D's.
using VertexEvaluator = std::function<void(const std::int32_t* v, double* out)>;

/// What the distributed walk cost, summed over the ranks (for reports and benchmarks).
struct DistributedTraceStats {
  int ranks = 1;
  std::uint64_t levels = 0;              ///< breadth-first levels walked (each one exchange)
  std::uint64_t bytes_sent = 0;          ///< between ranks, the final gather included
  std::uint64_t vertex_values_sent = 0;  ///< F values sent to ranks that do not own the vertex
  std::uint64_t candidates_sent = 0;     ///< transverse simplices sent to their owner
  std::uint64_t largest_share = 0;       ///< the most simplices of S one rank owns
  std::uint64_t oracle_tests = 0;        ///< simplices tested, counted on every rank that tested them
};

/// The rank that owns lattice vertex v: a hash of its block (a cube of 2^owner_block_bits(d) lattice
/// vertices a side), so that neighbours mostly share an owner. A simplex belongs to the owner of its
/// minimal vertex.
int owner_rank(const std::int32_t* v, int d, int ranks);
/// Blocks of about 2^6 lattice vertices (64 in R^3, 2^d from R^5 on): larger ones cut less of the walk
/// between ranks, smaller ones split a small manifold in high dimension more evenly (SO(3) in R^9:
/// 60 % of S on one of 2 ranks with blocks of 4^9 vertices, 51 % with 2^9).
constexpr int owner_block_bits(int d) { return d >= 5 ? 1 : (6 + d / 2) / d; }
/// owner_rank of the block last asked about, hashed again only when a vertex of another block is
/// asked (the simplices a walk or a level meets in a row mostly share their minimal vertex, and
/// neighbouring vertices their block).
class LastOwner {
 public:
  LastOwner(int d, int ranks) : d_(d), ranks_(ranks), bits_(owner_block_bits(d)) {}
  template <int kD = 0>  // (kD: d fixed at compile time, 0: read at run time)
  int of(const std::int32_t* v) {
    const int d = kD != 0 ? kD : d_;
    std::int32_t diff = owner_ < 0;  // (a loop, not memcmp: a call for a few ints)
    for (int i = 0; i < d; ++i) diff |= (v[i] >> bits_) ^ block_[i];
    if (diff != 0) {
      for (int i = 0; i < d; ++i) block_[i] = v[i] >> bits_;
      owner_ = owner_rank(v, d_, ranks_);
    }
    return owner_;
  }

 private:
  int d_, ranks_, bits_, owner_ = -1;
  std::int32_t block_[kMaxDimension] = {};
};

/// Rethrows on every rank the failure of the first rank that failed (nullptr: none here), with its
/// type (InputError, SeedError, EvaluationError, std::bad_alloc, else std::runtime_error) and
/// message. Collective: every phase that may fail on one rank ends in it, so that no rank waits
/// for a rank that gave up.
void agree_on_failure(Communicator& comm, std::exception_ptr failure);

/// Runs this rank's share of a step, then agrees with the others on whether every rank succeeded
/// (agree_on_failure).
template <class F>
void agreed(Communicator& comm, F&& step) {
  std::exception_ptr failure;
  try {
    step();
  } catch (...) {
    failure = std::current_exception();
  }
  agree_on_failure(comm, failure);
}

/// trace_manifold(T, oracle, seeds, options) split between the ranks of `comm`; every rank calls it
/// with the same arguments. Each rank walks the simplices it owns, level by level; the simplices it
/// discovers for other ranks are sent to them once per level. `oracle` must read the vertex values
/// from `values` (an ImplicitOracle made over it): before each level the values it will need are
/// put there, evaluated by the vertex's owner with `evaluate` and sent in batches, so F is
/// evaluated once per lattice vertex in the whole job. On rank 0 the result, counts included, is
/// the one trace_manifold returns (the same simplices in the same order); other ranks return an
/// empty result. An exception on one rank is thrown, with the same message, on every rank.
TraceResult trace_manifold_distributed(const Triangulation& triangulation, IntersectionOracle& oracle,
                                       SharedVertexValues& values, const VertexEvaluator& evaluate,
                                       const std::vector<std::vector<double>>& seeds, const TraceOptions& options,
                                       Communicator& comm, DistributedTraceStats* stats = nullptr);

/// One rank's share of a distributed trace, kept where it was traced (nothing gathered): the
/// simplices of S it owns, in their global order, and S_∂ as its walk met it (by the owner of τ,
/// not yet deduplicated nor at the owners of the (k+1)-simplices). Status and counts are the job's.
struct TracePart {
  int ambient_dimension = 0, codimension = 0;
  PackedKeyIndex simplices{1};                      ///< this rank's k-simplices of S, global ids increasing
  PointArray points;                                ///< a row of d per simplex
  std::vector<std::uint32_t> ids;                   ///< global id (place in S) of each
  std::uint64_t size = 0;                           ///< |S| over all ranks
  std::vector<std::uint64_t> boundary_discoveries;  ///< per meeting: (id of τ) << 32 | cofacet
  std::vector<std::uint32_t> boundary_keys;         ///< the packed (k+1)-simplex met
  PointArray boundary_points;                       ///< its point (d per meeting)
  TraceStatus status = TraceStatus::complete;
  std::string message;
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
  int manifold_dimension() const { return ambient_dimension - codimension; }
};

/// trace_manifold_distributed without the final gather: every rank returns its share.
TracePart trace_part_distributed(const Triangulation& triangulation, IntersectionOracle& oracle,
                                 SharedVertexValues& values, const VertexEvaluator& evaluate,
                                 const std::vector<std::vector<double>>& seeds, const TraceOptions& options,
                                 Communicator& comm, DistributedTraceStats* stats = nullptr);

}  // namespace coxmesh
