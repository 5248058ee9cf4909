// What the sample oracles' pipelines (mesh_winding.h, mesh_local_pca.h) share after their walks:
// the trace's status, then the cell complex of the trace (thesis §4.2) and its topology, timed.
// Internal to the mesh layer.
#pragma once

#include <cstddef>
#include <string>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/util/stopwatch.h"

namespace coxmesh {

/// Fills r.status, r.message and r.oracle_calls from the trace; throws InputError when no simplex
/// near the `seeds` seeds met the manifold.
template <class Result>
void record_trace(const TraceResult& traced, std::size_t seeds, Result& r) {
  if (traced.simplices.size() == 0)
    throw InputError("no simplex near the " + std::to_string(seeds) +
                     " seeds meets the manifold: the triangulation is too coarse for it (give a smaller edge length)");
  r.status = traced.status;
  r.message = traced.message;
  r.oracle_calls = traced.oracle_calls;
}

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
