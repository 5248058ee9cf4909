// The last two steps of the sample oracles' pipelines (mesh_winding.h, mesh_local_pca.h), timed:
// the cell complex of the trace (thesis §4.2) and its topology. Internal to the mesh layer.
#pragma once

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/util/stopwatch.h"

namespace coxmesh {

/// Fills r.cells, r.topology, r.cell_complex_seconds and r.topology_seconds from the trace.
template <class Result>
void build_complex_and_topology(TraceResult&& traced, Result& r) {
  const auto t0 = Clock::now();
  r.cells = build_cell_complex(std::move(traced));
  r.cell_complex_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  r.topology = analyze_topology(r.cells);
  r.topology_seconds = seconds_since(t1);
}

}  // namespace coxmesh
