#include "coxmesh/mesh/mesh_manifold.h"

#include <algorithm>
#include <exception>
#include <thread>

#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/oracle/regularity.h"
#include "coxmesh/tracing/seeds.h"
#include "coxmesh/tracing/trace_strata.h"
#include "coxmesh/util/parallel_for.h"
#include "coxmesh/util/stopwatch.h"

namespace coxmesh {

namespace {

MeshReport finish(MeshReport&& report, const MeshOptions& o, const WhileTopology& while_topology);

constexpr const char* kSingularOnTracedSet =
    "F's differential is (nearly) singular on the traced set: 0 is not a regular value of F (F is a square, F >= 0, "
    "or its equations are dependent there); what was meshed is a perturbed level set near F = 0";

// All domain functions as one (their intersection).
FunctionPtr merged_domain(const ManifoldFunctions& w) {
  FunctionPtr merged = w.domain;
  for (const FunctionPtr& face : w.domains) merged = domain_intersection(merged, face);
  return merged;
}

// The domain functions of each face of a manifold with corners, in the order of the strata's bits:
// `domain`, then `domains`, then the box when it bounds the walk.
std::vector<FunctionPtr> faces_of(const ManifoldFunctions& w, const FunctionPtr& bound) {
  std::vector<FunctionPtr> faces;
  if (w.domain) faces.push_back(w.domain);
  faces.insert(faces.end(), w.domains.begin(), w.domains.end());
  if (bound && faces.size() >= 2) faces.push_back(bound);
  return faces;
}

// Moves the vertices onto M (refine.h): the first worker gets `first`, the others fresh functions
// from `make`, each through `to_set`.
template <class ToSet>
RefinementReport refine(CellComplex& cc, double h, int threads, const ManifoldFunctions& first,
                        const ManifoldMaker& make, const ToSet& to_set) {
  RefineOptions ro;
  ro.threads = threads;
  bool first_refiner = true;
  return refine_vertices(
      cc, h,
      [&]() -> RefineSet {
        if (!first_refiner) return to_set(make());
        first_refiner = false;
        return to_set(first);
      },
      ro);
}

}  // namespace

MeshReport mesh_manifold(const Triangulation& t, const ManifoldMaker& make, const MeshOptions& o,
                         const WhileTopology& while_topology) {
  const ManifoldFunctions first = make();
  const FunctionPtr& f = first.f;
  const int d = t.dimension();
  if (!f || f->ambient_dimension() != d)
    throw InputError("the manifold and the triangulation must live in the same R^d");
  Box box = o.search_box;
  if (box.lo.empty()) box = {std::vector<double>(d, -2.0), std::vector<double>(d, 2.0)};
  FunctionPtr bound = o.bounded_by_box ? box_domain(box) : nullptr;
  const auto with_box = [&bound](FunctionPtr domain) { return bound ? domain_intersection(domain, bound) : domain; };
  // Each domain function its own face (a manifold with corners) when there are several.
  const std::vector<FunctionPtr> faces = faces_of(first, bound);
  const bool stratified = faces.size() >= 2;
  const FunctionPtr domain = with_box(merged_domain(first));  // (seeds are searched in all of them)

  MeshReport report;
  SeedChoice seeds;
  if (o.project_seeds) {
    seeds = choose_seeds(*f, domain.get(), o.seeds, o.auto_seed, box, t);
  } else {
    seeds.seeds = o.seeds;
    if (seeds.seeds.empty()) throw SeedError("no seed given");
  }
  report.seeds = seeds.seeds.size();
  report.automatic_seeds = seeds.automatic;

  // Memory bounds the run through an estimate per simplex (deterministic, unlike a measure of the
  // process): the smaller of the two limits applies, and the message names it.
  TraceOptions trace = o.trace;
  trace.skip_unusable_seeds |= seeds.skip_unusable;
  trace.threads = resolve_threads(o.trace.threads);
  trace.keep_cofacets = true;  // (the complex's cells of dimension 1, met by the walk)
  const std::uint64_t by_memory =
      o.max_memory ? o.max_memory / estimated_bytes_per_simplex(d - f->codimension()) : ~std::uint64_t{0};
  const bool memory_binds = by_memory < trace.max_simplices;
  if (memory_binds) trace.max_simplices = std::max<std::uint64_t>(by_memory, 1);

  const auto t0 = Clock::now();
  if (stratified) {
    StratifiedOracle oracle(t, f, faces);
    StrataTraceResult traced = trace_strata(t, oracle, seeds.seeds, trace);
    report.trace_seconds = seconds_since(t0);
    if (traced.vertex_cells.size() == 0)
      throw InputError("no simplex near the " + std::to_string(seeds.seeds.size()) +
                       " seeds meets the manifold inside the domains: the triangulation is too coarse for it (give "
                       "a smaller edge length)");
    report.status = traced.status;
    report.message = traced.message;
    report.function_evaluations = traced.function_evaluations;
    report.oracle_calls = traced.oracle_calls;
    if (o.on_phase) o.on_phase("building the cell complex");
    const auto t1 = Clock::now();
    report.cells = build_stratified_cell_complex(std::move(traced));
    report.cell_complex_seconds = seconds_since(t1);
    const ImplicitFunction* f_only[] = {f.get()};
    const PointArray& xs = report.cells.vertices;
    if (o.check_regularity && singular_on(f_only, {xs.data(), xs.size()}, t.longest_edge()))
      report.warnings.push_back(kSingularOnTracedSet);
    if (o.refine) {
      if (o.on_phase) o.on_phase("refining the vertices onto M");
      report.refinement =
          refine(report.cells, t.longest_edge(), trace.threads, first, make, [&bound](const ManifoldFunctions& w) {
            return RefineSet{w.f, faces_of(w, bound)};
          });
    }
    return finish(std::move(report), o, while_topology);
  }
  // Several workers share the vertex values (F once per vertex in all), each with its own functions.
  const auto shared = trace.threads > 1 ? ImplicitOracle::make_shared_values(t, f, domain) : nullptr;
  bool first_worker = true;
  TraceResult traced;
  TracedComplex built;  // (by complex_tracer)
  if (o.complex_tracer)
    built = o.complex_tracer(t, {f, domain}, seeds.seeds, trace, o.refine, traced);
  else if (o.tracer)
    traced = o.tracer(t, {f, domain}, seeds.seeds, trace);
  else
    traced = trace_manifold(
        t,
        [&]() -> std::unique_ptr<IntersectionOracle> {
          if (first_worker) {
            first_worker = false;
            return std::make_unique<ImplicitOracle>(t, f, domain, shared);
          }
          const ManifoldFunctions w = make();
          return std::make_unique<ImplicitOracle>(t, w.f, with_box(merged_domain(w)), shared);
        },
        seeds.seeds, trace);
  report.trace_seconds = seconds_since(t0);
  const double h = t.longest_edge();
  const ImplicitFunction* f_only[] = {f.get()};
  const std::size_t traced_count = !o.complex_tracer              ? traced.simplices.size()
                                   : built.topology               ? built.topology->cells.at(0)
                                   : built.cells.interior.empty() ? 0
                                                                  : built.cells.interior[0].size();
  if (traced_count == 0) {
    std::vector<double> points;
    for (const auto& x : seeds.seeds) points.insert(points.end(), x.begin(), x.end());
    if (o.check_regularity && singular_on(f_only, points, h))
      throw InputError(
          "F's differential is singular at the seeds: F vanishes identically near them or its equations are "
          "dependent, so 0 is not a regular value of F and there is no manifold to trace");
    throw InputError("no simplex near the " + std::to_string(seeds.seeds.size()) +
                     " seeds meets the manifold: the triangulation is too coarse for it (give a smaller edge length)");
  }
  report.status = traced.status;
  report.message = traced.status == TraceStatus::max_simplices_reached && memory_binds
                       ? "stopped at " + std::to_string(trace.max_simplices) +
                             " simplices, about the memory limit of " + std::to_string(o.max_memory >> 20) +
                             " MiB; give a larger edge length, a domain, or more memory"
                       : traced.message;
  report.function_evaluations = traced.function_evaluations;
  report.oracle_calls = traced.oracle_calls;

  if (o.on_phase) o.on_phase("building the cell complex");
  const auto t1 = Clock::now();
  report.cells =
      o.complex_tracer ? std::move(built.cells) : build_cell_complex(std::move(traced), trace.threads, o.keep_keys);
  report.cell_complex_seconds = seconds_since(t1);
  // The exact rule meshes a perturbed level set where F = 0 is not a regular level: say so.
  const CellComplex& cc = report.cells;
  // (a complex split between processes comes with the verdicts, its vertices being elsewhere)
  if (o.check_regularity &&
      (built.singular_vertices ? *built.singular_vertices
                               : singular_on(f_only, {cc.vertices.data(), cc.vertices.size()}, h)))
    report.warnings.push_back(kSingularOnTracedSet);
  if (o.check_regularity && domain) {
    const ImplicitFunction* f_and_domain[] = {f.get(), domain.get()};
    if (built.singular_boundary_vertices
            ? *built.singular_boundary_vertices
            : singular_on(f_and_domain, {cc.boundary_vertices.data(), cc.boundary_vertices.size()}, h))
      report.warnings.push_back(
          "the domain's boundary is tangent to the manifold along the cut (D = 0 contains M or touches it): the cut "
          "meshed is a perturbed one");
  }
  if (o.refine && built.refinement) {  // (done where the vertices are)
    report.refinement = built.refinement;
  } else if (o.refine) {
    if (o.on_phase) o.on_phase("refining the vertices onto M");
    report.refinement = refine(report.cells, h, trace.threads, first, make, [&](const ManifoldFunctions& w) {
      const FunctionPtr merged = with_box(merged_domain(w));
      return RefineSet{w.f, merged ? std::vector<FunctionPtr>{merged} : std::vector<FunctionPtr>{}};
    });
  }

  if (built.topology) {  // (computed where the cells are)
    report.topology = std::move(*built.topology);
    if (while_topology) while_topology(report);
    return report;
  }
  return finish(std::move(report), o, while_topology);
}

namespace {

// The topology, beside while_topology when there are several threads.
MeshReport finish(MeshReport&& report, const MeshOptions& o, const WhileTopology& while_topology) {
  const TraceOptions& trace = o.trace;
  auto topology = [&report] {
    const auto t2 = Clock::now();
    report.topology = analyze_topology(report.cells);
    report.topology_seconds = seconds_since(t2);
  };
  if (o.on_phase) o.on_phase("computing the topology");
  if (!while_topology) {
    topology();
  } else if (resolve_threads(trace.threads) == 1) {
    topology();
    while_topology(report);
  } else {  // (both only read the mesh; the report's other fields are not written meanwhile)
    std::exception_ptr failed;
    std::thread worker([&] {
      try {
        topology();
      } catch (...) {
        failed = std::current_exception();
      }
    });
    try {
      while_topology(report);
    } catch (...) {
      worker.join();
      throw;
    }
    worker.join();
    if (failed) std::rethrow_exception(failed);
  }
  return std::move(report);
}

}  // namespace

}  // namespace coxmesh
