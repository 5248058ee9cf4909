// Thesis §4.2 (the cell complex of M̂).
#pragma once

#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/tracing/trace_strata.h"

namespace coxmesh {

/// The cells of one dimension j and one kind (interior or boundary). Cell c is the polytope
/// μ_c ∩ M̂ (∩ ∂D̂ for boundary cells), μ_c its ambient simplex: of dimension k + j for interior
/// cells, k + 1 + j for boundary cells. Struct of arrays, 32-bit ids, CSR incidences.
struct CellLevel {
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  // (arrays that the construction writes in full, by several threads: not zeroed first)
  /// Ambient simplex of each cell; id = cell id. build_cell_complex keeps the keys and releases
  /// the hash table: reindex() before find().
  PackedKeyIndex simplices{1};
  IndexArray facet_offsets{0};  ///< CSR: facets of c are facet_ids[offsets[c] .. offsets[c+1])
  IndexArray facet_ids;         ///< cells of dimension j − 1 of the same kind
  /// Interior cells (j ≥ 1) with a domain: the boundary cell of dimension j − 1 on the same
  /// simplex (it closes the cut polytope), or kNone. Empty without a domain.
  IndexArray boundary_facet;
  /// Per cell, the domain functions whose boundary it lies on (bit i: D_{i+1} = 0): filled in a
  /// stratified complex (several domain functions), empty otherwise.
  std::vector<std::uint64_t> domains;

  std::uint32_t size() const { return simplices.size(); }
  std::span<const std::uint32_t> facets(std::uint32_t c) const {
    return {facet_ids.data() + facet_offsets[c], facet_ids.data() + facet_offsets[c + 1]};
  }
};

/// The Hasse diagram of M̂ (and of M̂ ∩ ∂D̂): interior[j] for j = 0..m, boundary[j] for j = 0..m−1.
/// Vertex cells of interior[0] are the simplices of S with coordinates `vertices` (row per cell);
/// those of boundary[0] are S_∂ with `boundary_vertices`.
/// A stratified complex (domain_count ≥ 2: a manifold with corners) keeps every cell in interior[j]
/// by its dimension j, whatever its stratum, with CellLevel::domains telling the strata apart; its
/// keys are stratum keys (trace_strata.h), every facet of a cell is in the level below, and the
/// boundary levels are empty.
struct CellComplex {
  int ambient_dimension = 0, manifold_dimension = 0;
  int domain_count = 0;  ///< the domain functions of a stratified complex (0 otherwise)
  bool stratified() const { return domain_count > 0; }
  std::vector<CellLevel> interior, boundary;
  PointArray vertices, boundary_vertices;

  std::size_t bytes() const;  ///< memory held, for reports
};

/// Builds the cell complex level by level (thesis §4.2): the cells of dimension j are the
/// (k+j)-cofaces of the simplices of the cells of dimension j − 1; each coface found from a cell
/// records that cell as a facet. Consumes the trace result (its indices become level 0).
/// `threads` workers (0 = all hardware threads) run batches of cells through a pipeline: cofaces
/// enumerated in parallel, numbered in order by one task, incidences written out in parallel; the
/// facet lists are sorted in parallel too. The complex, numbering included, is identical for every
/// thread count. Without `keep_keys`, each level's keys are dropped as soon as the levels above no
/// longer need them (PackedKeyIndex::without_keys): cell counts, facets and vertices stay, which
/// is all the topology, refinement and mesh writers read; only the native format and the Python
/// API's simplices need the keys.
CellComplex build_cell_complex(TraceResult&& trace, int threads = 1, bool keep_keys = true);

/// The stratified complex of a manifold with corners, level by level: the cells (J, ν) of dimension j
/// are, for every cell (J, μ) of dimension j − 1, the (J, ν) for the cofacets ν of μ and the
/// (J \ {i}, μ) for i ∈ J, each with the cell it came from as a facet (thesis §4.2, the boundary cell
/// of a simplex being a facet of its interior cell, with one stratum per set of domains). Sequential;
/// the numbering is that of discovery, facets in increasing order.
CellComplex build_stratified_cell_complex(StrataTraceResult&& trace);

/// Cells per stratum: for each set of domains (bitmask; 0 = the interior) that has cells, their
/// number in each dimension 0..m − popcount(domains). A complex with one domain has the strata 0
/// and 1 (its boundary). Sorted by the bitmask.
struct StratumCount {
  std::uint64_t domains = 0;
  int dimension = 0;               ///< m − popcount(domains)
  std::vector<std::size_t> cells;  ///< per dimension 0..dimension
};
std::vector<StratumCount> stratum_counts(const CellComplex& cc);

/// Peak bytes that tracing, the cell complex and its topology take per traced simplex of an
/// m-manifold, measured (about 200 bytes per cell; 2, 5, 16 and 62 cells per traced simplex for
/// m = 1..4, fourfold more per further dimension): an estimate, for limits set before tracing.
std::size_t estimated_bytes_per_simplex(int m);

}  // namespace coxmesh
