// The point-cloud pipeline with the local-PCA oracle of the thesis prototype
// (tracing/local_pca_oracle.h), kept for comparison: trace on one thread, the defect count, the
// cell complex and its topology.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/tracing/point_cloud_problem.h"

namespace coxmesh {

struct LocalPcaResult {
  CellComplex cells;
  TopologyReport topology;
  TraceStatus status = TraceStatus::complete;
  std::string message;
  std::size_t defects = 0;  ///< count_defects() of the trace
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
  double trace_seconds = 0, cell_complex_seconds = 0, topology_seconds = 0;
};

/// Traces the point-cloud problem p with the local-PCA oracle on t (one thread: its walk graph is
/// not symmetric), counts the defects, builds the cell complex and its topology. Throws InputError
/// when no seed reaches the manifold.
LocalPcaResult mesh_local_pca(const Triangulation& t, const PointCloudProblem& p, const TraceOptions& options = {});

}  // namespace coxmesh
