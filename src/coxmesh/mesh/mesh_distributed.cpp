#include "coxmesh/mesh/mesh_distributed.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/oracle/regularity.h"

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

// singular_on over the rows of one kind of vertex cell of the whole complex, each rank measuring the
// samples among its rows: the same points, hence the same verdict.
bool singular_on_parts(std::span<const ImplicitFunction* const> functions, const PointArray& rows,
                       const std::vector<std::uint32_t>& ids, std::uint64_t n, double h, Communicator& comm) {
  const std::size_t d = static_cast<std::size_t>(functions.front()->ambient_dimension());
  const std::uint64_t tested = std::min<std::uint64_t>(n, kRegularitySamples);
  std::uint64_t counts[2] = {0, 0};  // finite measures, singular ones
  for (std::uint64_t s = 0; s < tested; ++s) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), static_cast<std::uint32_t>(s * n / tested));
    if (it == ids.end() || *it != s * n / tested) continue;
    const double r = regularity(functions, rows.data() + static_cast<std::size_t>(it - ids.begin()) * d, h);
    if (std::isnan(r)) continue;
    ++counts[0];
    counts[1] += r < kRegularityThreshold;
  }
  comm.sum(counts, 2);
  return counts[0] > 0 && 4 * counts[1] > counts[0];
}

// The refinement of the whole complex from each rank's: the largest |F| of all, the counts summed
// (rank 0 gets them; the time is rank 0's).
RefinementReport merged_refinement(RefinementReport mine, Communicator& comm) {
  std::uint64_t counts[2] = {mine.vertices, mine.not_refined};
  comm.sum(counts, 2);
  mine.vertices = counts[0];
  mine.not_refined = counts[1];
  const double largest[2] = {mine.max_abs_f_before, mine.max_abs_f_after};
  std::vector<std::byte> bytes(sizeof largest);
  std::memcpy(bytes.data(), largest, sizeof largest);
  std::vector<std::size_t> sizes;
  const std::vector<std::byte> all = comm.gather_to_root(bytes, sizes);
  for (std::size_t at = 0; at + sizeof largest <= all.size(); at += sizeof largest) {
    double theirs[2];
    std::memcpy(theirs, all.data() + at, sizeof theirs);
    mine.max_abs_f_before = std::max(mine.max_abs_f_before, theirs[0]);
    mine.max_abs_f_after = std::max(mine.max_abs_f_after, theirs[1]);
  }
  return mine;
}

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
                                         PartCounts* written, DistributedTopologyStats* topology_stats) {
  return [&comm, write_part, stats, written, topology_stats](
             const Triangulation& t, const ManifoldFunctions& m, const std::vector<std::vector<double>>& seeds,
             const TraceOptions& options, bool refine, TraceResult& traced) {
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
    // (a piece of a file lists its cells in global order; without one, the topology gets each level's
    // incidences in its ranges as the level is numbered)
    CellComplexPart cells = build_cell_complex_distributed(std::move(part), comm, write_part != nullptr);
    TracedComplex out;  // (the verdicts first: the writer may release the vertex rows)
    if (!empty) {
      const ImplicitFunction* f_only[] = {m.f.get()};
      const double h = t.longest_edge();
      out.singular_vertices =
          singular_on_parts(f_only, cells.cells.vertices, cells.interior_ids[0], cells.interior_sizes[0], h, comm);
      if (m.domain && !cells.boundary_sizes.empty()) {
        const ImplicitFunction* f_and_domain[] = {m.f.get(), m.domain.get()};
        out.singular_boundary_vertices = singular_on_parts(f_and_domain, cells.cells.boundary_vertices,
                                                           cells.boundary_ids[0], cells.boundary_sizes[0], h, comm);
      }
    }
    std::exception_ptr failure;
    PartCounts counts{};
    RefinementReport refined;
    try {
      // Each vertex moves on its own (refine.h), so refining the rows of this rank's vertex cells
      // before its piece is written gives them as one refinement of the whole complex does.
      if (!empty && refine) {
        RefineOptions one_thread;
        one_thread.threads = 1;
        const RefineSet set{m.f, m.domain ? std::vector<FunctionPtr>{m.domain} : std::vector<FunctionPtr>{}};
        refined = refine_vertices(
            cells.cells, t.longest_edge(), [&set] { return set; }, one_thread);
      }
      if (!empty && write_part) counts = write_part(cells);
    } catch (...) {
      failure = std::current_exception();
    }
    agree_on_failure(comm, failure);
    if (!empty && refine) out.refinement = merged_refinement(refined, comm);
    comm.sum(counts.data(), static_cast<int>(counts.size()));
    if (written) *written = counts;
    release_all_but_incidences(cells);
    out.cells.ambient_dimension = cells.cells.ambient_dimension;
    out.cells.manifold_dimension = cells.cells.manifold_dimension;
    out.cells.interior.resize(cells.cells.interior.size());
    out.cells.boundary.resize(cells.cells.boundary.size());
    out.topology = analyze_topology_distributed(std::move(cells), comm, topology_stats);
    if (comm.rank() != 0) throw DistributedPartDone{};
    return out;
  };
}

}  // namespace coxmesh
