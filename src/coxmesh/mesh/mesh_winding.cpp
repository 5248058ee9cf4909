#include "coxmesh/mesh/mesh_winding.h"

#include <atomic>

#include "coxmesh/mesh/complex_and_topology.h"
#include "coxmesh/tracing/local_pca_oracle.h"
#include "coxmesh/tracing/normal_winding_oracle.h"

namespace coxmesh {

WindingMeshResult mesh_normal_winding(const Triangulation& t, const PointCloudProblem& p, const TraceOptions& options) {
  const PointCloudDiagnostics& g = p.diagnostics;
  if (g.ambient_dimension - g.manifold_dimension != 2)
    throw InputError("the winding oracle meshes manifolds of codimension 2, not " +
                     std::to_string(g.ambient_dimension - g.manifold_dimension));
  auto shared = NormalWindingOracle::make_shared_values(t.dimension(), p.domain != nullptr);
  TraceOptions o = options;
  o.skip_unusable_seeds = true;
  WindingMeshResult r;
  const auto t0 = Clock::now();
  std::atomic<std::uint64_t> uncertain{0};
  TraceResult traced = trace_manifold(
      t,
      [&] {
        auto oracle = std::make_unique<NormalWindingOracle>(t, p.model, g.blend_width, p.domain, shared);
        oracle->count_uncertain_in(&uncertain);
        return oracle;
      },
      p.seeds, o);
  r.trace_seconds = seconds_since(t0);
  record_trace(traced, p.seeds.size(), r);
  r.function_evaluations = traced.function_evaluations;
  // A complete walk has tested every facet of every cofacet of the trace. When none was uncertain,
  // each of those tetrahedra has an even count (NormalWindingOracle::uncertain_triangles), and
  // nothing needs checking. Otherwise each facet of each cofacet once, on one oracle: counts that
  // do not depend on the threads.
  if (uncertain.load() > 0 || traced.status != TraceStatus::complete) {
    const auto t1 = Clock::now();
    NormalWindingOracle check(t, p.model, g.blend_width, p.domain, shared);
    r.odd_tetrahedra = count_defects(traced, check);
    r.uncertain_triangles = check.uncertain_triangles();
    r.function_evaluations += check.function_evaluations();
    r.check_seconds = seconds_since(t1);
  }
  build_complex_and_topology(std::move(traced), r);
  return r;
}

}  // namespace coxmesh
