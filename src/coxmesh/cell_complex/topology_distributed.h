// The topology of a cell complex split between processes (cell_complex_distributed.h), without
// gathering it: counts, Euler characteristic, the manifold check and Z/2 Betti numbers, equal to
// analyze_topology on the whole complex (docs/distributed.md).
#pragma once

#include <cstdint>

#include "coxmesh/cell_complex/cell_complex_distributed.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh {

/// What the distributed topology moved (for reports and benchmarks).
struct DistributedTopologyStats {
  std::uint64_t cells = 0;            ///< in the whole complex
  std::uint64_t cells_to_rank0 = 0;   ///< left by the reductions of the ranks, finished on rank 0
  std::uint64_t cells_left = 0;       ///< left by rank 0's reductions, for the matrix reduction
  std::uint64_t interface_cells = 0;  ///< facets fetched from another rank (the closedness check), over all ranks
};

/// analyze_topology of the complex whose parts the ranks hold (every rank calls it with its part,
/// which it consumes). Each level is cut into P ranges of consecutive ids, which carry on the
/// order of discovery (neighbours mostly have near ids); range r goes to rank r as facet lists.
/// Counts and the Euler characteristic come from the level sizes; the checks of closedness and of
/// the manifold are made per cell by the rank that holds it (with the facet lists of its facets
/// in other ranges, and its coface counts, fetched), the first failure in the one-process order
/// being reported. Betti numbers: each rank removes the vertices of its range (one per component
/// of its own graph, the others with the edges of breadth-first trees) and then coreduces pairs of
/// its cells in sweeps, counting the cells of other ranges as never removed; what is left goes to
/// rank 0, which coreduces it further and computes its homology
/// (betti.h's steps); β_0, and the correction of β_1 for the vertices removed, come from the
/// components of each range glued across ranges. For a manifold, as betti_numbers does, the top
/// cells are not reduced: β_m counts their closed pieces (glued across ranges as the components
/// are), β_(m−1) comes from χ. The result is on every rank. Collective.
TopologyReport analyze_topology_distributed(CellComplexPart&& part, Communicator& comm,
                                            DistributedTopologyStats* stats = nullptr);

}  // namespace coxmesh
