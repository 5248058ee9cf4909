#include "coxmesh/mesh/mesh_distributed.h"

#include "coxmesh/oracle/implicit_oracle.h"

namespace coxmesh {

Tracer distributed_tracer(Communicator& comm, DistributedTraceStats* stats) {
  return [&comm, stats](const Triangulation& t, const ManifoldFunctions& m,
                        const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
    // The oracle reads every value from `values`, which the walk fills before each level; only the
    // walk's evaluator calls F, on the rank that owns the vertex.
    const auto values = ImplicitOracle::make_shared_values(t, m.f, m.domain);
    ImplicitOracle oracle(t, m.f, m.domain, values);
    const int k = m.f->codimension();
    std::vector<double> x(t.dimension());
    const VertexEvaluator evaluate = [&](const std::int32_t* v, double* out) {
      t.cartesian(v, x.data());
      m.f->evaluate(x.data(), out);
      if (m.domain) m.domain->evaluate(x.data(), out + k);
    };
    TraceResult result = trace_manifold_distributed(t, oracle, *values, evaluate, seeds, options, comm, stats);
    if (comm.rank() != 0) throw DistributedPartDone{};
    return result;
  };
}

}  // namespace coxmesh
