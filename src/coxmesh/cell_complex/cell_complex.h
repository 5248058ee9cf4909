// Thesis §4.2 (the cell complex of M̂).
#pragma once

#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/tracing/trace_manifold.h"

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

  std::uint32_t size() const { return simplices.size(); }
  std::span<const std::uint32_t> facets(std::uint32_t c) const {
    return {facet_ids.data() + facet_offsets[c], facet_ids.data() + facet_offsets[c + 1]};
  }
};

/// The Hasse diagram of M̂ (and of M̂ ∩ ∂D̂): interior[j] for j = 0..m, boundary[j] for j = 0..m−1.
/// Vertex cells of interior[0] are the simplices of S with coordinates `vertices` (row per cell);
/// those of boundary[0] are S_∂ with `boundary_vertices`.
struct CellComplex {
  int ambient_dimension = 0, manifold_dimension = 0;
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
/// thread count.
CellComplex build_cell_complex(TraceResult&& trace, int threads = 1);

/// Peak bytes that tracing, the cell complex and its topology take per traced simplex of an
/// m-manifold, measured (about 200 bytes per cell; 2, 5, 16 and 62 cells per traced simplex for
/// m = 1..4, fourfold more per further dimension): an estimate, for limits set before tracing.
std::size_t estimated_bytes_per_simplex(int m);

}  // namespace coxmesh
