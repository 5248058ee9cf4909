// Thesis §4.2 (manifold tracing, with boundary): the public entry points. The walk itself is in
// walk_sequential.cpp, its many-threaded variant in walk_parallel.cpp.
#include "coxmesh/tracing/trace_manifold.h"

#include <optional>

#include "coxmesh/tracing/walk_parallel.h"
#include "coxmesh/tracing/walk_sequential.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

namespace {

TraceResult run_tracer(const Triangulation& triangulation, std::vector<IntersectionOracle*> oracles,
                       const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  const int d = triangulation.dimension();
  for (IntersectionOracle* o : oracles)
    if (o->ambient_dimension() != d)
      throw InputError("the oracle works in R^" + std::to_string(o->ambient_dimension()) +
                       " but the triangulation is of R^" + std::to_string(d));
  if (seeds.empty()) throw SeedError("no seed given");
  walk::SequentialWalk walk(triangulation, *oracles[0], options);
  std::optional<walk::ParallelWalk> parallel;  // with more than one oracle
  if (oracles.size() > 1) parallel.emplace(walk, oracles);
  for (const auto& seed : seeds) {
    // Past the limit, no more seeds: each would add its simplices and a level of walk (thousands
    // of automatic seeds took S far past the limit).
    if (walk.stopped()) break;
    walk.add_seed(seed, !options.skip_unusable_seeds);
    parallel ? parallel->walk() : walk.walk();
  }
  TraceResult result = walk.finish();
  if (parallel) result.oracle_calls += parallel->oracle_calls();
  for (const IntersectionOracle* o : oracles) result.function_evaluations += o->function_evaluations();
  if (result.status == TraceStatus::max_simplices_reached)
    result.message = simplex_limit_message(options.max_simplices);
  return result;
}

}  // namespace

std::string simplex_limit_message(std::size_t max_simplices) {
  return "stopped at the limit of " + std::to_string(max_simplices) +
         " simplices; the manifold may be unbounded (give a domain or a box) or the scale too fine";
}

TraceResult trace_manifold(const Triangulation& triangulation, IntersectionOracle& oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  return run_tracer(triangulation, {&oracle}, seeds, options);
}

TraceResult trace_manifold(const Triangulation& triangulation, const OracleFactory& make_oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  const int workers = resolve_threads(options.threads);
  std::vector<std::unique_ptr<IntersectionOracle>> owned;
  std::vector<IntersectionOracle*> oracles;
  for (int w = 0; w < workers; ++w) {
    owned.push_back(make_oracle());
    if (!owned.back()) throw InputError("the oracle factory returned no oracle");
    oracles.push_back(owned.back().get());
  }
  return run_tracer(triangulation, std::move(oracles), seeds, options);
}

}  // namespace coxmesh
