// Thesis §4.2 (the manifold tracing algorithm, with boundary).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/errors.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/triangulation/triangulation.h"

namespace coxmesh {

struct TraceOptions {
  std::size_t max_simplices = 20'000'000;  ///< stop (keeping the result) when |S| reaches this
  int seed_search_rings = 3;               ///< rings of d-simplices searched around a seed
  bool skip_unusable_seeds = false;        ///< ignore seeds that reach nothing (automatic seeding)
  /// Worker threads for the OracleFactory overload (0 = all hardware threads). The result, order
  /// included, is the same for every thread count.
  int threads = 1;
  /// Called from the walk, where a breadth-first level starts, each time |S| has grown by
  /// progress_interval simplices, with |S| so far (progress displays; it may throw to cancel).
  std::function<void(std::size_t traced)> progress;
  std::size_t progress_interval = 65536;
  /// Keep the cofacets of S that the walk meets (TraceResult::cofacets), so that build_cell_complex
  /// takes its cells of dimension 1 from them instead of enumerating and numbering them again. The
  /// walk keeps them only where it meets each with all its facets in S: a complete walk, an oracle
  /// that promises two transverse facets per cofacet (IntersectionOracle::two_transverse_facets).
  bool keep_cofacets = false;
};

/// A walk stopped by the simplex limit leaves cells open at its front: its cell complex is not
/// closed, so its topology is not reported. (A box bounds the walk as a domain: box_domain().)
enum class TraceStatus { complete, max_simplices_reached };

/// The cofacets μ of the simplices of S, each with the simplices of S among its facets: the cells of
/// dimension 1 of the cell complex (μ ∩ M̂, a segment between two vertices, or one vertex and the
/// domain's boundary), numbered as build_cell_complex numbers them: by their first facet in S, then
/// in that facet's cofacet order (CofaceEnumerator). A cofacet is named by its first facet and its
/// place in that order, not by its key: 4 bytes instead of a key's 4·packed_words(d) (48 in R⁹),
/// and the walk does not pack it.
struct WalkedCofacets {
  IndexArray facet_offsets, facet_ids;  ///< CSR: ids in S of the facets of each, increasing
  IndexArray places;                    ///< per cofacet, its place among its first facet's cofacets
  std::uint32_t size() const { return static_cast<std::uint32_t>(places.size()); }
  bool empty() const { return places.empty(); }
};

/// The output of tracing (thesis §4.2): S = the k-simplices meeting M̂ inside the domain, each with
/// its intersection point, and S_∂ = the (k+1)-simplices meeting M̂ ∩ ∂D̂, with theirs. Ids are
/// dense and in breadth-first discovery order (deterministic).
struct TraceResult {
  int ambient_dimension = 0, codimension = 0;
  PackedKeyIndex simplices{1};           ///< S: packed k-simplices
  PointArray points;                     ///< |S| × d intersection points
  PackedKeyIndex boundary_simplices{1};  ///< S_∂: packed (k+1)-simplices
  PointArray boundary_points;            ///< |S_∂| × d
  WalkedCofacets cofacets;               ///< with TraceOptions::keep_cofacets, if kept (else empty)
  TraceStatus status = TraceStatus::complete;
  std::string message;  ///< why tracing stopped early (empty when complete)
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
  int manifold_dimension() const { return ambient_dimension - codimension; }
};

/// TraceResult::message of a walk stopped at the limit of max_simplices.
std::string simplex_limit_message(std::size_t max_simplices);

/// Traces every component of M̂ that passes near a seed: locates each seed, finds the k-simplices
/// meeting M̂ among the faces of the d-simplices around it (widening up to seed_search_rings rings
/// of neighbours), then walks breadth-first from k-simplex to k-simplex through their common
/// cofacets. Each candidate is looked up before the oracle is called, and the oracle is called at
/// most once per k-simplex.
///   seeds: points of R^d near M (project them first, see seeds.h). Throws SeedError, InputError,
///   EvaluationError.
///
///   Triangulation T = Triangulation::coxeter(3).scaled(0.1);
///   ImplicitOracle oracle(T, sphere(2, 3, 1.0));
///   TraceResult r = trace_manifold(T, oracle, {{1.0, 0.0, 0.0}});
TraceResult trace_manifold(const Triangulation& triangulation, IntersectionOracle& oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options = {});

/// Makes one oracle per worker thread, called from the calling thread before the walk. Oracles
/// cache and are not thread-safe; a function object shared by several oracles must be safe to
/// evaluate concurrently (the built-ins are; an ExpressionFunction is not: make one per worker).
/// To evaluate F once per lattice vertex in all, build the oracles over one SharedVertexValues:
///
///   auto shared = ImplicitOracle::make_shared_values(T, f);
///   trace_manifold(T, [&] { return std::make_unique<ImplicitOracle>(T, f, nullptr, shared); }, seeds, options);
using OracleFactory = std::function<std::unique_ptr<IntersectionOracle>()>;

/// Multi-threaded tracing with options.threads workers: level-synchronous breadth-first search.
/// Each level's simplices are processed in chunks: a worker starts on its own share of consecutive
/// chunks and then takes chunks from the largest share left (a short lock per chunk, none in the
/// walk itself); it reads S (frozen during the level; through its own indexes of the current and
/// previous levels, the only ones a level's walk meets), remembers what it tested itself and writes
/// discoveries to the chunk's buffer; the buffers are merged in chunk order, so S, S_∂, their ids and
/// points are identical for 1, 2, … N threads and equal to the single-oracle overload's. (An oracle
/// whose walk graph is not symmetric, e.g. one reporting three transverse facets of a cofacet, can
/// make the walk meet a simplex of an older level again; that is detected when S is indexed, and the
/// walk is redone sequentially: the same result, more time.) With one thread it is the single-oracle
/// walk. function_evaluations sums the workers' oracles.
TraceResult trace_manifold(const Triangulation& triangulation, const OracleFactory& make_oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options = {});

}  // namespace coxmesh
