// Cost of functions typed as text: muparser expressions (ExpressionFunction) against the
// compiled C++ built-ins computing the same formulas.
//   * ns per evaluation of F, on a pool of random points, for the sphere S² ⊂ R³, the torus in R³
//     and S³ ⊂ R⁵ (two equations);
//   * time of trace_manifold (oracle construction included; F is evaluated once per lattice
//     vertex) for the torus and the sphere, expression vs preset, and the slowdown.
// Plain harness, one thread, median of `runs`. Usage: bench_expression [runs=5]. Prints Markdown.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/triangulation/triangulation.h"

namespace {

using Clock = std::chrono::steady_clock;
using coxmesh::FunctionPtr;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median ns per evaluation of f over `evaluations` calls cycling through a pool of points.
double ns_per_evaluation(const coxmesh::ImplicitFunction& f, int runs, long evaluations) {
  const int d = f.ambient_dimension(), k = f.codimension(), pool = 4096;
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<double> xs(static_cast<std::size_t>(pool) * d), value(k);
  for (double& x : xs) x = u(rng);
  std::vector<double> times;
  volatile double sink = 0;
  for (int r = 0; r < runs; ++r) {
    double acc = 0;
    const auto t0 = Clock::now();
    for (long i = 0; i < evaluations; ++i) {
      f.evaluate(xs.data() + (i % pool) * d, value.data());
      acc += value[0];
    }
    times.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() /
                    static_cast<double>(evaluations));
    sink = sink + acc;
  }
  return median(times);
}

struct TraceTime {
  double seconds;
  std::size_t simplices;
  std::uint64_t evaluations;
};

// Median time of trace_manifold for two functions of the same manifold, runs interleaved (a, b,
// a, b, …) so that load drifts on the machine affect both alike.
std::pair<TraceTime, TraceTime> trace_times(const FunctionPtr& a, const FunctionPtr& b, double edge,
                                            const std::vector<double>& seed, int runs) {
  const coxmesh::Triangulation t = coxmesh::Triangulation::coxeter(a->ambient_dimension()).with_longest_edge(edge);
  std::vector<double> times[2];
  TraceTime out[2]{};
  for (int r = 0; r < runs; ++r)
    for (int which = 0; which < 2; ++which) {
      const auto t0 = Clock::now();
      coxmesh::ImplicitOracle oracle(t, which == 0 ? a : b);
      const coxmesh::TraceResult result = coxmesh::trace_manifold(t, oracle, {seed});
      times[which].push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      out[which].simplices = result.simplices.size();
      out[which].evaluations = result.function_evaluations;
    }
  out[0].seconds = median(times[0]);
  out[1].seconds = median(times[1]);
  return {out[0], out[1]};
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  struct Eval {
    const char* name;
    FunctionPtr compiled, text;
  };
  const std::vector<Eval> evals = {
      {"sphere S^2 in R^3", coxmesh::sphere(2, 3, 1.0), coxmesh::expression_function("x^2+y^2+z^2-1")},
      {"torus in R^3", coxmesh::torus(1.0, 0.4), coxmesh::expression_function("(sqrt(x^2+y^2)-1)^2+z^2-0.4^2")},
      {"S^3 in R^5 (2 equations)", coxmesh::sphere(3, 5, 1.0),
       coxmesh::expression_function("x1^2+x2^2+x3^2+x4^2-1; x5")},
  };
  std::printf("## Evaluation of F (ns per call, median of %d runs of 2,000,000 calls)\n\n", runs);
  std::printf("| function | compiled C++ | muparser expression | slowdown |\n|---|---:|---:|---:|\n");
  std::vector<double> extra_ns;  // muparser minus compiled, per case
  for (const Eval& e : evals) {
    const double a = ns_per_evaluation(*e.compiled, runs, 2'000'000), b = ns_per_evaluation(*e.text, runs, 2'000'000);
    extra_ns.push_back(b - a);
    std::printf("| %s | %.1f | %.1f | %.1fx |\n", e.name, a, b, b / a);
  }

  const double edges[] = {0.03, 0.03, 0.3};
  const std::vector<double> seeds[] = {{1, 0, 0}, {1.4, 0, 0}, {1, 0, 0, 0, 0}};  // on each manifold
  std::printf("\n## Tracing (trace_manifold with oracle construction, seconds, median of %d interleaved runs)\n\n",
              runs);
  std::printf(
      "The predicted slowdown is 1 + (F evaluations x extra ns per evaluation) / preset time: F is\n"
      "evaluated once per lattice vertex, so the expression only costs where F is called.\n\n");
  std::printf(
      "| case | edge | simplices | F evaluations | preset (compiled) | expression | measured slowdown | predicted |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t i = 0; i < evals.size(); ++i) {
    const auto [a, b] = trace_times(evals[i].compiled, evals[i].text, edges[i], seeds[i], runs);
    if (a.simplices != b.simplices)
      std::printf("(!) different results: %zu vs %zu simplices\n", a.simplices, b.simplices);
    const double predicted = 1 + static_cast<double>(a.evaluations) * extra_ns[i] * 1e-9 / a.seconds;
    std::printf("| %s | %.2f | %zu | %llu | %.4f | %.4f | %.3fx | %.3fx |\n", evals[i].name, edges[i], a.simplices,
                static_cast<unsigned long long>(a.evaluations), a.seconds, b.seconds, b.seconds / a.seconds, predicted);
  }
  return 0;
}
