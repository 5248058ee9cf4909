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
  if (traced.simplices.size() == 0)
    throw InputError("no simplex near the " + std::to_string(p.seeds.size()) +
                     " seeds meets the manifold: the triangulation is too coarse for it (give a smaller edge length)");
  r.status = traced.status;
  r.message = traced.message;
  r.oracle_calls = traced.oracle_calls;
  r.defects = count_defects(traced, oracle);
  r.function_evaluations = oracle.function_evaluations();
  build_complex_and_topology(std::move(traced), r);
  return r;
}

}  // namespace coxmesh
