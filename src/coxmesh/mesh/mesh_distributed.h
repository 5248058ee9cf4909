// mesh_manifold with its walk split between processes: a MeshOptions::tracer over a Communicator
// (tracing/trace_distributed.h). Rank 0 builds the mesh from the whole result.
#pragma once

#include <array>
#include <cstdint>

#include "coxmesh/cell_complex/cell_complex_distributed.h"
#include "coxmesh/cell_complex/topology_distributed.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/tracing/trace_distributed.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh {

/// Thrown by distributed_tracer on the ranks other than 0 once their part of the walk is on rank 0:
/// they have nothing left to do in mesh_manifold. Not an error (not a std::exception).
struct DistributedPartDone {};

/// A MeshOptions::tracer: trace_manifold_distributed over `comm`, each rank with an ImplicitOracle
/// of F and D over its own vertex values. Every rank runs mesh_manifold with the same arguments;
/// rank 0 gets the result trace_manifold would give, the others throw DistributedPartDone.
/// `stats`, when given, receives the cost of the walk.
///
///   mo.tracer = distributed_tracer(comm);
///   try { MeshReport r = mesh_manifold(t, make, mo); /* rank 0 */ } catch (const DistributedPartDone&) {}
Tracer distributed_tracer(Communicator& comm, DistributedTraceStats* stats = nullptr);

/// Counts of what a rank wrote (e.g. points, cells and skipped cells of a file), summed over the ranks.
using PartCounts = std::array<std::uint64_t, 3>;
/// Writes one rank's part of the cell complex (e.g. its piece of the output file); may be collective, and may
/// release_all_but_incidences(part) once it has read the rest.
using PartWriter = std::function<PartCounts(CellComplexPart&)>;

/// A MeshOptions::complex_tracer: the walk and the cell complex split over `comm`, each rank building
/// the cells it owns (cell_complex_distributed.h), refining their vertex rows when asked (each vertex
/// moves on its own: the rows of one refinement of the whole complex, refine.h), and writing them
/// with `write_part` (every rank agrees on whether all succeeded before going on; `written`, if
/// given, gets the counts summed over the ranks); then the ranks compute the topology together
/// (topology_distributed.h) and the regularity verdicts over the vertices, each over its own cells.
/// Rank 0 gets them, with a complex that has the dimensions but no cells; the other ranks throw
/// DistributedPartDone.
ComplexTracer distributed_complex_tracer(Communicator& comm, PartWriter write_part,
                                         DistributedTraceStats* stats = nullptr, PartCounts* written = nullptr,
                                         DistributedTopologyStats* topology_stats = nullptr);

}  // namespace coxmesh
