#include "coxmesh/mesh/mesh_distributed.h"

#include "coxmesh/oracle/implicit_oracle.h"

namespace coxmesh {

namespace {

// The vertex values, the oracle over them and the evaluator that a rank of the walk needs.
struct RankOracle {
  RankOracle(const Triangulation& t, const ManifoldFunctions& m)
      : values(ImplicitOracle::make_shared_values(t, m.f, m.domain)),
        oracle(t, m.f, m.domain, values),
        x(t.dimension()),
        evaluate([&t, m, this](const std::int32_t* v, double* out) {
          t.cartesian(v, x.data());
          m.f->evaluate(x.data(), out);
          if (m.domain) m.domain->evaluate(x.data(), out + m.f->codimension());
        }) {}
  // The oracle reads every value from `values`, which the walk fills before each level; only the
  // walk's evaluator calls F, on the rank that owns the vertex.
  std::shared_ptr<SharedVertexValues> values;
  ImplicitOracle oracle;
  std::vector<double> x;
  VertexEvaluator evaluate;
};

}  // namespace

Tracer distributed_tracer(Communicator& comm, DistributedTraceStats* stats) {
  return [&comm, stats](const Triangulation& t, const ManifoldFunctions& m,
                        const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
    RankOracle r(t, m);
    TraceResult result = trace_manifold_distributed(t, r.oracle, *r.values, r.evaluate, seeds, options, comm, stats);
    if (comm.rank() != 0) throw DistributedPartDone{};
    return result;
  };
}

ComplexTracer distributed_complex_tracer(Communicator& comm, PartWriter write_part, DistributedTraceStats* stats,
                                         PartCounts* written) {
  return [&comm, write_part, stats, written](const Triangulation& t, const ManifoldFunctions& m,
                                             const std::vector<std::vector<double>>& seeds, const TraceOptions& options,
                                             TraceResult& traced) {
    TracePart part = [&] {  // (the vertex values go before the complex is built)
      RankOracle r(t, m);
      return trace_part_distributed(t, r.oracle, *r.values, r.evaluate, seeds, options, comm, stats);
    }();
    traced.ambient_dimension = part.ambient_dimension;
    traced.codimension = part.codimension;
    traced.status = part.status;
    traced.message = part.message;
    traced.oracle_calls = part.oracle_calls;
    traced.function_evaluations = part.function_evaluations;
    const bool empty = part.size == 0;  // (mesh_manifold says why)
    CellComplexPart cells = build_cell_complex_distributed(std::move(part), comm);
    std::exception_ptr failure;
    PartCounts counts{};
    try {
      if (!empty && write_part) counts = write_part(cells);
    } catch (...) {
      failure = std::current_exception();
    }
    agree_on_failure(comm, failure);
    comm.sum(counts.data(), static_cast<int>(counts.size()));
    if (written) *written = counts;
    CellComplex whole = gather_cell_complex(std::move(cells), comm);
    if (comm.rank() != 0) throw DistributedPartDone{};
    return whole;
  };
}

}  // namespace coxmesh
