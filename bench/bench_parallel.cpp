// Multi-core scaling of tracing and cell complex construction. For every case: the
// sequential walk (one oracle, the single-thread implementation) against the parallel one with
// 1, 2, 4, … threads (one oracle per worker, sharing the vertex values), and the cell complex with
// the same thread counts. Wall time, best and median of `runs` interleaved runs. Also checks that every run gives the
// same |S| and cell count.
//
// Usage: bench_parallel [max-threads = hardware threads] [runs = 3] [case-name-substring]
// Threads beyond the number of cores only show the overhead; run it on a machine with more cores
// for the scaling curve (the table says how many cores it had).
// On machines with up to 8 cores it also runs one thread pinned to each core in turn ("1 on CPU k"):
// virtual cores need not be equally fast (on the development VM one was often 1.3–1.6 times slower
// than the other on this memory-bound work), and the "bound" row is the best speedup that perfect
// parallel code could reach over the 1-thread time with those cores: best 1-thread time × Σ 1 / (best
// time pinned to core k).
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

using namespace coxmesh;

namespace {

struct Case {
  std::string name;
  FunctionPtr f, domain;
  Triangulation t;
  std::vector<double> seed;
};

std::vector<Case> make_cases() {
  const FunctionPtr circle = sphere(1, 2, 1.0);
  return {
      {"S^2 in R^3", sphere(2, 3, 1.0), nullptr, Triangulation::coxeter(3).with_longest_edge(0.01).rotated(1), {}},
      {"torus in R^3", torus(1.0, 0.4), nullptr, Triangulation::coxeter(3).with_longest_edge(0.012).rotated(2), {}},
      {"S^2 in R^4", sphere(2, 4, 1.0), nullptr, Triangulation::coxeter(4).with_longest_edge(0.03).rotated(3), {}},
      {"S^3 in R^4", sphere(3, 4, 1.0), nullptr, Triangulation::coxeter(4).with_longest_edge(0.12).rotated(4), {}},
      {"S^2 in R^5", sphere(2, 5, 1.0), nullptr, Triangulation::coxeter(5).with_longest_edge(0.05).rotated(5), {}},
      {"S^3 in R^6", sphere(3, 6, 1.0), nullptr, Triangulation::coxeter(6).with_longest_edge(0.3).rotated(6), {}},
      {"flat torus in R^4",
       product(circle, circle),
       nullptr,
       Triangulation::coxeter(4).with_longest_edge(0.05).rotated(7),
       {}},
      {"flat torus in R^4, cut",
       product(circle, circle),
       half_space_domain({0.3, -0.2, 0.9, 0.25}, 0.2),
       Triangulation::coxeter(4).with_longest_edge(0.05).rotated(8),
       {-1, 0, -1, 0}},
  };
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double process_cpu() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Timing {
  double trace = 0, complex = 0, trace_cpu = 0, complex_cpu = 0;  // wall and CPU time of all threads
  std::size_t simplices = 0, cells = 0;
  std::uint64_t evaluations = 0, oracle_calls = 0;
};

// Runs the calling thread on one core (cpu ≥ 0) or on all of them (cpu < 0) until destroyed.
struct PinnedTo {
  explicit PinnedTo(int cpu) {
    if (cpu < 0) return;
    pthread_getaffinity_np(pthread_self(), sizeof(saved), &saved);
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    pinned = pthread_setaffinity_np(pthread_self(), sizeof(one), &one) == 0;
  }
  ~PinnedTo() {
    if (pinned) pthread_setaffinity_np(pthread_self(), sizeof(saved), &saved);
  }
  cpu_set_t saved;
  bool pinned = false;
};

// threads = 0: the sequential overload (one oracle); otherwise the factory overload.
Timing run(const Case& c, int threads, int cpu = -1) {
  const PinnedTo pin(cpu);
  Timing r;
  const std::vector<std::vector<double>> seeds = {c.seed.empty() ? c.f->seed() : c.seed};
  auto t0 = std::chrono::steady_clock::now();
  double c0 = process_cpu();
  TraceResult traced;
  if (threads == 0) {
    ImplicitOracle oracle(c.t, c.f, c.domain);
    traced = trace_manifold(c.t, oracle, seeds);
  } else {
    TraceOptions options;
    options.threads = threads;
    const auto shared = ImplicitOracle::make_shared_values(c.t, c.f, c.domain);
    traced = trace_manifold(
        c.t, [&] { return std::make_unique<ImplicitOracle>(c.t, c.f, c.domain, shared); }, seeds, options);
  }
  r.trace = seconds_since(t0);
  r.trace_cpu = process_cpu() - c0;
  r.simplices = traced.simplices.size();
  r.evaluations = traced.function_evaluations;
  r.oracle_calls = traced.oracle_calls;
  t0 = std::chrono::steady_clock::now();
  c0 = process_cpu();
  const CellComplex cc = build_cell_complex(std::move(traced), std::max(threads, 1));
  r.complex = seconds_since(t0);
  r.complex_cpu = process_cpu() - c0;
  for (const auto* levels : {&cc.interior, &cc.boundary})
    for (const CellLevel& l : *levels) r.cells += l.size();
  return r;
}

// Touches 1.5 GiB once and gives it back, so that the runs reuse memory the machine has already
// backed: on the development VM the first touch of fresh guest memory ran at 0.5 GB/s against
// 15 GB/s for recycled pages, and charged whichever run met it (a third of a run at random).
void warm_up_memory() {
  const std::size_t bytes = std::size_t{3} << 29;
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return;
  madvise(p, bytes, MADV_HUGEPAGE);
  for (std::size_t i = 0; i < bytes; i += 4096) static_cast<volatile char*>(p)[i] = 1;
  munmap(p, bytes);
}

}  // namespace

int main(int argc, char** argv) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int max_threads = argc > 1 ? std::max(1, std::atoi(argv[1])) : cores;
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const std::string filter = argc > 3 ? argv[3] : "";
  std::vector<int> counts = {0};
  for (int n = 1; n <= max_threads; n *= 2) counts.push_back(n);
  if (counts.back() != max_threads) counts.push_back(max_threads);
  std::vector<int> cpus(counts.size(), -1);  // the core a run is pinned to, or -1
  const int pinned_from = static_cast<int>(counts.size());
  if (cores > 1 && cores <= 8)
    for (int k = 0; k < std::min(cores, max_threads); ++k) counts.push_back(1), cpus.push_back(k);

  std::printf(
      "%d hardware threads; wall time, best and median of %d interleaved runs; speedup = best 1-thread time / "
      "best time (the sequential row: the single-thread overload, one oracle)\n\n",
      cores, runs);
  std::printf(
      "| case | \\|S\\| | cells | threads | trace s (best / median) | trace speedup | trace CPU s | complex s "
      "(best / median) | complex speedup | complex CPU s | F evaluations | oracle calls |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : make_cases()) {
    if (c.name.find(filter) == std::string::npos) continue;
    // Runs are interleaved over the thread counts, so that slow phases of a shared machine hit all
    // of them alike.
    std::vector<std::vector<Timing>> timings(counts.size());
    warm_up_memory();
    for (int i = 0; i < runs; ++i)
      for (std::size_t n = 0; n < counts.size(); ++n) timings[n].push_back(run(c, counts[n], cpus[n]));
    auto column = [](const std::vector<Timing>& ts, double Timing::*field) {
      std::vector<double> v;
      for (const Timing& t : ts) v.push_back(t.*field);
      return v;
    };
    const std::size_t simplices = timings[0][0].simplices, cells = timings[0][0].cells;
    const double one_trace = min_of(column(timings[1], &Timing::trace));
    const double one_complex = min_of(column(timings[1], &Timing::complex));
    for (std::size_t n = 0; n < counts.size(); ++n) {
      for (const Timing& t : timings[n])
        if (t.simplices != simplices || t.cells != cells) {
          std::fprintf(stderr, "%s: %d threads gave |S| %zu and %zu cells, the sequential walk %zu and %zu\n",
                       c.name.c_str(), counts[n], t.simplices, t.cells, simplices, cells);
          return 1;
        }
      const auto trace = column(timings[n], &Timing::trace), complex = column(timings[n], &Timing::complex);
      const Timing& last = timings[n].back();
      const std::string label = counts[n] == 0 ? "sequential"
                                : cpus[n] >= 0 ? "1 on CPU " + std::to_string(cpus[n])
                                               : std::to_string(counts[n]);
      std::printf("| %s | %zu | %zu | %s | %.3f / %.3f | %.2f | %.3f | %.3f / %.3f | %.2f | %.3f | %llu | %llu |\n",
                  c.name.c_str(), simplices, cells, label.c_str(), min_of(trace), median(trace),
                  one_trace / min_of(trace), median(column(timings[n], &Timing::trace_cpu)), min_of(complex),
                  median(complex), one_complex / min_of(complex), median(column(timings[n], &Timing::complex_cpu)),
                  static_cast<unsigned long long>(last.evaluations),
                  static_cast<unsigned long long>(last.oracle_calls));
      std::fflush(stdout);
    }
    if (pinned_from < static_cast<int>(counts.size())) {
      double trace_rate = 0, complex_rate = 0;  // summed speeds of the cores, in runs per second
      for (std::size_t n = pinned_from; n < counts.size(); ++n) {
        trace_rate += 1 / min_of(column(timings[n], &Timing::trace));
        complex_rate += 1 / min_of(column(timings[n], &Timing::complex));
      }
      std::printf("| %s | | | bound, %d cores | | %.2f | | | %.2f | | | |\n", c.name.c_str(),
                  static_cast<int>(counts.size()) - pinned_from, one_trace * trace_rate, one_complex * complex_rate);
    }
  }
  return 0;
}
