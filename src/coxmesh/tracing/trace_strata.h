// Thesis §4.2 for a manifold with corners: tracing every stratum of M ∩ {D_1 < 0, …, D_p < 0}.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/oracle/stratified_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace coxmesh {

/// A cell of a stratified complex is a pair (simplex μ, stratum J): its key is pack(μ) followed by
/// the bitmask J in two words (low, high).
constexpr int stratum_key_words(int d) { return packed_words(d) + 2; }
inline void pack_stratum_key(const Simplex& mu, std::uint64_t stratum, std::uint32_t* out) {
  pack(mu, out);
  out[packed_words(mu.d)] = static_cast<std::uint32_t>(stratum);
  out[packed_words(mu.d) + 1] = static_cast<std::uint32_t>(stratum >> 32);
}
inline std::uint64_t stratum_of_key(const std::uint32_t* key, int d) {
  return key[packed_words(d)] | static_cast<std::uint64_t>(key[packed_words(d) + 1]) << 32;
}

/// The vertex cells of every stratum: the pairs (ν, J), ν of dimension k + |J|, where ν meets the
/// stratum J (StratifiedOracle::meets), with their points. Ids in breadth-first discovery order.
struct StrataTraceResult {
  int ambient_dimension = 0, codimension = 0, domain_count = 0;
  PackedKeyIndex vertex_cells{1};  ///< keys of stratum_key_words(d) words
  PointArray points;               ///< one row of d coordinates per vertex cell
  TraceStatus status = TraceStatus::complete;
  std::string message;
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
};

/// Walks the vertex graph of all strata at once, from the seeds: from a vertex cell (ν, J) to the
/// ends of the edge cells it may lie on, (J, μ) for the cofacets μ of ν and (J \ {i}, ν) for
/// i ∈ J; the ends of an edge cell (J', μ) are among (J', facets of μ) and (J' ∪ {l}, μ). Every
/// candidate is tested once. A seed searches the k-faces (stratum ∅) and the (k+1)-faces (each
/// single domain) of the d-simplices around it, widening up to options.seed_search_rings rings.
/// Sequential (options.threads is not used): the result is the same for every thread count.
/// options.max_simplices bounds the number of vertex cells. Throws SeedError, EvaluationError.
StrataTraceResult trace_strata(const Triangulation& triangulation, StratifiedOracle& oracle,
                               const std::vector<std::vector<double>>& seeds, const TraceOptions& options = {});

}  // namespace coxmesh
