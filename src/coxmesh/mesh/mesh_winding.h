// The point-cloud pipeline with the winding oracle (tracing/normal_winding_oracle.h): for surfaces
// in R⁴ whose normal bundle is not orientable (RP², the Klein bottle), which no per-vertex
// function can mesh. Trace on any number of threads, the cell complex, its topology.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/tracing/point_cloud_problem.h"

namespace coxmesh {

struct WindingMeshResult {
  CellComplex cells;
  TopologyReport topology;
  TraceStatus status = TraceStatus::complete;
  std::string message;
  /// Cofacets of the traced triangles with an odd number of hit facets: 0 when no facet of theirs is
  /// uncertain (NormalWindingOracle::uncertain_triangles; then they are not counted, there is
  /// nothing to find), else counted.
  std::size_t odd_tetrahedra = 0;
  std::uint64_t uncertain_triangles = 0;  ///< among their facets (counted only when there are any)
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
  double trace_seconds = 0, check_seconds = 0, cell_complex_seconds = 0, topology_seconds = 0;
};

/// Traces the point-cloud problem p (codimension 2) with the winding oracle on t with
/// options.threads workers (every lattice vertex evaluated once in all; the result is the same for
/// any number), checks the cofacets of the trace when a facet was uncertain, builds the cell
/// complex and its topology.
/// Throws InputError when p is not of codimension 2 or no seed reaches the manifold.
WindingMeshResult mesh_normal_winding(const Triangulation& t, const PointCloudProblem& p,
                                      const TraceOptions& options = {});

/// Whether samples need the winding oracle: codimension 2 and frames that cannot be made consistent
/// (PointCloudDiagnostics::frames_inconsistent), i.e. a normal bundle that looks non-orientable.
inline bool wants_winding_oracle(const PointCloudDiagnostics& g) {
  return g.frames_inconsistent && g.ambient_dimension - g.manifold_dimension == 2;
}

}  // namespace coxmesh
