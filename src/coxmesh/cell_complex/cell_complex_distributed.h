// Thesis §4.2 over several processes: the cell complex of a distributed trace, each rank building
// the cells it owns, numbered as build_cell_complex numbers them in one process (docs/distributed.md).
#pragma once

#include <cstdint>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/tracing/trace_distributed.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh {

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
};

/// Builds this rank's part from its share of the trace; collective (every rank calls it). A level's
/// cells reach their owners with their discovery keys ((global id of the facet they were found
/// from) << 32 | position among its cofaces); each owner keeps a cell's smallest key, and the level
/// is numbered in the order of those keys, as the single process discovers it. Memory per rank:
/// its cells and, while a level is built, that level's incidences at this rank and the records that
/// cross to or from it. Without `in_global_order`, the levels above the vertex cells stay in the order
/// their cells reached this rank (with their ids): enough for gather_cell_complex and the topology,
/// which place each cell by its id, not for closure_for_writing nor a piece of a file.
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
