// Thesis §4.2 over several processes: the cell complex of a distributed trace, each rank building
// the cells it owns, numbered as build_cell_complex numbers them in one process (docs/distributed.md).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/tracing/trace_distributed.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh {

/// The topology's share of the complex at one rank (topology_distributed.h): each level's ids cut
/// into P contiguous ranges, range r at rank r (range_start), the levels one after the other as
/// GlobalCells orders them (interior 0, boundary 0, interior 1, …); per cell its facets, and an
/// interior cell's boundary facet, by id over all levels (the first level's cells first), increasing.
struct TopologyRanges {
  std::vector<std::uint32_t> offsets{0}, facets;
  std::span<const std::uint32_t> of(std::uint64_t i) const {
    return {facets.data() + offsets[i], facets.data() + offsets[i + 1]};
  }
};

/// The first id of rank r's range of a level of `size` cells cut between `ranks` ranks.
inline std::uint64_t range_start(std::uint64_t size, int r, int ranks) {
  return size * static_cast<std::uint64_t>(r) / static_cast<std::uint64_t>(ranks);
}
/// The rank whose range holds id u of a level of `size` cells.
inline int range_rank(std::uint64_t u, std::uint64_t size, int ranks) {
  int r = static_cast<int>(u * static_cast<std::uint64_t>(ranks) / size);  // (then a step at most, by rounding)
  while (r + 1 < ranks && range_start(size, r + 1, ranks) <= u) ++r;
  while (range_start(size, r, ranks) > u) --r;
  return r;
}

/// One rank's part of the cell complex: the cells whose ambient simplex it owns (owner_rank of the
/// simplex's minimal vertex, as in the walk). Gathered over the ranks, each cell at its global id,
/// the levels are those build_cell_complex builds from the whole trace (keys, facets, boundary_facet).
struct CellComplexPart {
  /// This rank's cells, each level in global order (but see build_cell_complex_distributed);
  /// facet_ids and boundary_facet hold global ids; vertices (boundary_vertices) has a row per cell
  /// of interior[0] (boundary[0]) here.
  CellComplex cells;
  /// The global id of each cell here (increasing, in global order), per level, as cells.interior and
  /// cells.boundary.
  std::vector<std::vector<std::uint32_t>> interior_ids, boundary_ids;
  /// Cells per level over all ranks.
  std::vector<std::uint64_t> interior_sizes, boundary_sizes;
  /// Without global order (build_cell_complex_distributed): this rank's ranges for the topology,
  /// the levels above the vertex cells then holding no facets.
  std::optional<TopologyRanges> ranges;
};

/// Builds this rank's part from its share of the trace; collective (every rank calls it). A level's
/// cells reach their owners with their discovery keys ((global id of the facet they were found
/// from) << 32 | position among its cofaces); each owner keeps a cell's smallest key, and the level
/// is numbered in the order of those keys, as the single process discovers it. Memory per rank:
/// its cells and, while a level is built, that level's incidences at this rank and the records that
/// cross to or from it. Without `in_global_order` (no file), the levels above the vertex cells stay in
/// the order their cells reached this rank (with their ids) and keep no facets: as each level is
/// numbered, its incidences go straight to the ranks of its cells' ranges (`ranges`), where the
/// topology reads them; such a part serves only analyze_topology_distributed (and its vertex rows).
CellComplexPart build_cell_complex_distributed(TracePart&& trace, Communicator& comm, bool in_global_order = true);

/// The whole complex from all the parts (in any order), each cell at its global id: the one
/// build_cell_complex builds in one process. Throws InputError unless the parts cover every level
/// exactly once and agree on its shape. The keys are not checked (distinct in parts from one run;
/// check_native checks those from files, repeated ones included).
CellComplex assemble_cell_complex(std::vector<CellComplexPart>&& parts);

/// What a rank writes of its part in a mesh file: the cells it owns of the levels the file shows
/// (interior min(m, 3), boundary min(m, 3, m − 1)) and every face of them, fetched from their owners
/// (a complex with ids of its own, each level in global order), with the global id of each cell.
/// Its levels keep no keys (PackedKeyIndex::without_keys): no mesh writer reads them, and at 8–12
/// words per cell in R⁶–R⁹ they would be most of it.
struct CellClosure {
  CellComplex cells;
  std::vector<std::vector<std::uint32_t>> interior_ids, boundary_ids;
};
/// Collective. The levels of `part` are indexed again (for the look-ups of the other ranks), and
/// its keys and vertex rows released as soon as no round needs them: the part is left as
/// release_all_but_incidences leaves it (all that the topology reads).
CellClosure closure_for_writing(CellComplexPart& part, Communicator& comm);

/// Releases the keys of the part's cells and its vertex rows, keeping the incidences, the ids and
/// the sizes: all that the topology reads (topology_distributed.h).
void release_all_but_incidences(CellComplexPart& part);

/// The whole complex on rank 0 (assembled from every rank's part), an empty one elsewhere. Collective.
CellComplex gather_cell_complex(CellComplexPart&& part, Communicator& comm);

}  // namespace coxmesh
