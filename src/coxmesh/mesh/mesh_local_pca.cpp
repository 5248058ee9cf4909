#include "coxmesh/mesh/mesh_local_pca.h"

#include "coxmesh/mesh/complex_and_topology.h"
#include "coxmesh/tracing/local_pca_oracle.h"

namespace coxmesh {

LocalPcaResult mesh_local_pca(const Triangulation& t, const PointCloudProblem& p, const TraceOptions& options) {
  const PointCloudDiagnostics& g = p.diagnostics;
  LocalPcaOracle oracle(t, p.model, g.manifold_dimension, g.radius, p.domain);
  TraceOptions o = options;
  o.skip_unusable_seeds = true;
  o.threads = 1;  // the walk graph is not symmetric: the parallel walk would redo it sequentially
  LocalPcaResult r;
  const auto t0 = Clock::now();
  TraceResult traced = trace_manifold(t, oracle, p.seeds, o);
  r.trace_seconds = seconds_since(t0);
  record_trace(traced, p.seeds.size(), r);
  r.defects = count_defects(traced, oracle);
  r.function_evaluations = oracle.function_evaluations();
  build_complex_and_topology(std::move(traced), r);
  return r;
}

}  // namespace coxmesh
