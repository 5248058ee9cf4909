// Manifold tracing and cell complex, side by side with GUDHI's Coxeter_triangulation module (thesis
// §4.2, §4.3, §4.4). One run, one thread, for every case:
//   * the same triangulation: GUDHI's Ã_d matrix × scale, the same random offset (fixed RNG seed),
//     passed explicitly to coxmesh::Triangulation;
//   * the same manifold (each library's own built-in functions, which compute the same formulas) and
//     the same seed point;
//   * timings (median of `runs`, thread CPU time and wall time): GUDHI manifold_tracing_algorithm vs
//     coxmesh trace_manifold (oracle construction included), GUDHI Cell_complex::construct_complex vs
//     coxmesh build_cell_complex;
//   * |S| (and |S_∂|) of both, which must be equal (tests/gudhi/test_gudhi_tracing.cpp checks the sets);
//   * F evaluations: coxmesh counted by a wrapper around F, against the number of distinct lattice
//     vertices of the k-simplices handed to the oracle (counted by a wrapper around the oracle);
//     GUDHI counted by a wrapper functor;
//   * memory: CellComplex::bytes() per cell, and the peak RSS growth of the whole coxmesh pipeline
//     (oracle + tracing + cell complex) per cell, measured in a forked child (VmHWM after resetting
//     it through /proc/self/clear_refs); the same for GUDHI.
//
// Usage: bench_tracing [runs=3] [case-name-substring]: prints Markdown tables (progress and wall times
// on stderr). bench_tracing profile <case-name-substring> [reps=5]: coxmesh only, for perf.
#include <malloc.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

// GUDHI's headers are included as system headers (see bench/CMakeLists.txt).
#include <gudhi/Coxeter_triangulation.h>
#include <gudhi/Coxeter_triangulation/Cell_complex/Cell_complex.h>
#include <gudhi/Functions/Cartesian_product.h>
#include <gudhi/Functions/Function_Sm_in_Rd.h>
#include <gudhi/Functions/Function_affine_plane_in_Rd.h>
#include <gudhi/Functions/Function_moment_curve_in_Rd.h>
#include <gudhi/Functions/Function_torus_in_R3.h>
#include <gudhi/Implicit_manifold_intersection_oracle.h>
#include <gudhi/Manifold_tracing.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/triangulation/triangulation.h"

namespace {

namespace gct = Gudhi::coxeter_triangulation;
using GTriangulation = gct::Coxeter_triangulation<>;
using GMap = gct::Manifold_tracing<GTriangulation>::Out_simplex_map;
using GCellComplex = gct::Cell_complex<GMap>;

constexpr std::uint64_t kSeed = 20240603;
constexpr int kCoxmeshRunsPerGudhiRun = 3;

// ---- Measurement helpers ----------------------------------------------------------------------------

struct Stopwatch {
  timespec cpu0{};
  std::chrono::steady_clock::time_point wall0;
  Stopwatch() {
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu0);
    wall0 = std::chrono::steady_clock::now();
  }
  // {cpu seconds, wall seconds}
  std::pair<double, double> elapsed() const {
    timespec cpu1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu1);
    const double cpu = (cpu1.tv_sec - cpu0.tv_sec) + 1e-9 * (cpu1.tv_nsec - cpu0.tv_nsec);
    return {cpu, std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count()};
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

long status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0) return std::atol(line.c_str() + n + 1);
  return -1;
}

// Peak resident memory of the two phases of a run, relative to the resident set before it. The
// heap is trimmed and the high-water mark reset (/proc/self/clear_refs) at the start and between the
// phases, so `complex` is the peak while the cell complex is built: the traced simplices it starts
// from (which become its vertex cells) plus everything the construction allocates; the tracing's own
// working memory (oracle cache, table of rejected simplices) is freed by then.
struct MemoryProbe {
  long base_kb = 0, trace_kb = 0, complex_kb = 0;
  static bool reset_peak() {
    malloc_trim(0);
    std::ofstream clear("/proc/self/clear_refs");
    return static_cast<bool>(clear << "5" << std::flush);
  }
  void start() {
    reset_peak();
    base_kb = status_kb("VmRSS:");
  }
  void between_phases() {
    trace_kb = status_kb("VmHWM:");
    reset_peak();
  }
  void end() { complex_kb = status_kb("VmHWM:"); }
};

struct PeakMemory {
  long long pipeline = -1, complex = -1;  // bytes: max over both phases, and the cell complex phase
};

// Runs fn(probe) in a forked child (the parent's heap is left alone).
PeakMemory measure_peak(const std::function<void(MemoryProbe&)>& fn) {
  PeakMemory out;
  int fd[2];
  if (pipe(fd) != 0) return out;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    PeakMemory m;
    if (MemoryProbe::reset_peak()) {
      MemoryProbe probe;
      probe.start();
      fn(probe);
      probe.end();
      m.pipeline = 1024LL * (std::max(probe.trace_kb, probe.complex_kb) - probe.base_kb);
      m.complex = 1024LL * (probe.complex_kb - probe.base_kb);
    }
    if (write(fd[1], &m, sizeof m) != sizeof m) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  if (pid < 0 || read(fd[0], &out, sizeof out) != sizeof out) out = PeakMemory{};
  close(fd[0]);
  if (pid > 0) waitpid(pid, nullptr, 0);
  return out;
}

// ---- GUDHI side -------------------------------------------------------------------------------------

// Counts the evaluations of a GUDHI function and the distinct points it is evaluated at (GUDHI
// computes a vertex's Cartesian coordinates the same way every time, so equal vertices give
// bit-identical points).
struct PointHash {
  std::size_t operator()(const std::vector<double>& p) const {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (double x : p) {
      std::uint64_t b;
      std::memcpy(&b, &x, 8);
      h = (h ^ b) * 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
    }
    return h;
  }
};
struct EvaluationLog {
  std::uint64_t calls = 0;
  std::unordered_set<std::vector<double>, PointHash> points;
};

template <class F>
struct Counting {
  F f;
  EvaluationLog* log;
  Eigen::VectorXd operator()(const Eigen::VectorXd& p) const {
    ++log->calls;
    log->points.emplace(p.data(), p.data() + p.size());
    return f(p);
  }
  std::size_t amb_d() const { return f.amb_d(); }
  std::size_t cod_d() const { return f.cod_d(); }
  Eigen::VectorXd seed() const { return f.seed(); }
};

struct GudhiRun {
  double trace_cpu = 0, trace_wall = 0, complex_cpu = 0, complex_wall = 0;
  std::size_t interior = 0, boundary = 0, cells = 0;
};

// One traced run; Domain = std::nullptr_t for no domain.
template <class F, class Domain>
GudhiRun gudhi_run(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const F& f, const Domain& domain,
                   const std::vector<double>& seed, int m, MemoryProbe* probe) {
  GudhiRun r;
  GTriangulation cox(a.rows());
  cox.change_matrix(a);
  cox.change_offset(b);
  const std::vector<Eigen::VectorXd> seeds{Eigen::Map<const Eigen::VectorXd>(seed.data(), seed.size())};
  GMap interior, boundary;
  GCellComplex cc(m);
  if constexpr (std::is_same_v<Domain, std::nullptr_t>) {
    Stopwatch t;
    const auto oracle = gct::make_oracle(f);
    gct::manifold_tracing_algorithm(seeds, cox, oracle, interior);
    std::tie(r.trace_cpu, r.trace_wall) = t.elapsed();
    if (probe) probe->between_phases();
    Stopwatch c;
    cc.construct_complex(interior);
    std::tie(r.complex_cpu, r.complex_wall) = c.elapsed();
  } else {
    Stopwatch t;
    const auto oracle = gct::make_oracle(f, domain);
    gct::manifold_tracing_algorithm(seeds, cox, oracle, interior, boundary);
    std::tie(r.trace_cpu, r.trace_wall) = t.elapsed();
    if (probe) probe->between_phases();
    Stopwatch c;
    cc.construct_complex(interior, boundary);
    std::tie(r.complex_cpu, r.complex_wall) = c.elapsed();
  }
  r.interior = interior.size();
  r.boundary = boundary.size();
  for (const auto& level : cc.interior_simplex_cell_maps()) r.cells += level.size();
  for (const auto& level : cc.boundary_simplex_cell_maps()) r.cells += level.size();
  return r;
}

// ---- coxmesh side -----------------------------------------------------------------------------------

// Forwards to the implicit oracle and records the distinct lattice vertices it is asked about.
class VertexCountingOracle final : public coxmesh::IntersectionOracle {
 public:
  VertexCountingOracle(coxmesh::IntersectionOracle& inner, int d) : inner_(inner), vertices_(d) {}
  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  int codimension() const override { return inner_.codimension(); }
  bool has_domain() const override { return inner_.has_domain(); }
  std::uint64_t function_evaluations() const override { return inner_.function_evaluations(); }
  coxmesh::Intersection intersect(const coxmesh::Simplex& tau, double* point) override {
    record(tau);
    return inner_.intersect(tau, point);
  }
  bool pivot_enter(const coxmesh::Simplex& tau) override {
    record(tau);
    return inner_.pivot_enter(tau);
  }
  int pivot_exit(const std::int32_t* v) override {
    vertices_.insert(reinterpret_cast<const std::uint32_t*>(v));
    return inner_.pivot_exit(v);
  }
  std::size_t distinct_vertices() const { return vertices_.size(); }

 private:
  void record(const coxmesh::Simplex& tau) {
    std::int32_t v[coxmesh::kMaxDimension];
    for (int j = 0; j <= tau.k; ++j) {
      tau.vertex(j, v);
      vertices_.insert(reinterpret_cast<const std::uint32_t*>(v));
    }
  }
  coxmesh::IntersectionOracle& inner_;
  coxmesh::PackedKeyIndex vertices_;
};

struct CoxRun {
  double trace_cpu = 0, trace_wall = 0, complex_cpu = 0, complex_wall = 0;
  std::size_t interior = 0, boundary = 0, cells = 0, complex_bytes = 0;
};

CoxRun coxmesh_run(const coxmesh::Triangulation& t, const coxmesh::FunctionPtr& f, const coxmesh::FunctionPtr& domain,
                   const std::vector<double>& seed, MemoryProbe* probe = nullptr) {
  CoxRun r;
  Stopwatch w;
  coxmesh::TraceResult traced;
  {
    coxmesh::ImplicitOracle oracle(t, f, domain);
    traced = coxmesh::trace_manifold(t, oracle, {seed});
  }
  std::tie(r.trace_cpu, r.trace_wall) = w.elapsed();
  if (traced.status != coxmesh::TraceStatus::complete) std::fprintf(stderr, "coxmesh: %s\n", traced.message.c_str());
  r.interior = traced.simplices.size();
  r.boundary = traced.boundary_simplices.size();
  if (probe) probe->between_phases();
  Stopwatch c;
  const coxmesh::CellComplex cc = coxmesh::build_cell_complex(std::move(traced));
  std::tie(r.complex_cpu, r.complex_wall) = c.elapsed();
  for (const auto& l : cc.interior) r.cells += l.size();
  for (const auto& l : cc.boundary) r.cells += l.size();
  r.complex_bytes = cc.bytes();
  return r;
}

// ---- Cases ------------------------------------------------------------------------------------------

struct Result {
  std::string name;
  int d = 0, m = 0;
  double scale = 0;
  GudhiRun gudhi;  // medians in the time fields
  CoxRun cox;
  std::uint64_t gudhi_evaluations = 0, gudhi_points = 0;
  std::uint64_t cox_evaluations = 0, cox_oracle_evaluations = 0, cox_vertices = 0;
  PeakMemory cox_peak, gudhi_peak;
  bool has_cli = false;
  double cli_trace = 0, cli_complex = 0, cli_whole = 0;  // medians, fresh process per run
  std::size_t cli_simplices = 0;
};

struct Case {
  std::string name;
  int d, m;
  double scale;
  coxmesh::FunctionPtr f, domain;
  std::vector<double> seed;
  // Runs GUDHI once on (matrix, offset); with a log, F is wrapped by Counting.
  std::function<GudhiRun(const Eigen::MatrixXd&, const Eigen::VectorXd&, EvaluationLog*, MemoryProbe*)> gudhi;
};

template <class F, class Domain = std::nullptr_t>
std::function<GudhiRun(const Eigen::MatrixXd&, const Eigen::VectorXd&, EvaluationLog*, MemoryProbe*)> gudhi_case(
    F f, std::vector<double> seed, int m, Domain domain = nullptr) {
  return
      [f, seed, m, domain](const Eigen::MatrixXd& a, const Eigen::VectorXd& b, EvaluationLog* log, MemoryProbe* probe) {
        if (log) return gudhi_run(a, b, Counting<F>{f, log}, domain, seed, m, probe);
        return gudhi_run(a, b, f, domain, seed, m, probe);
      };
}

std::vector<Case> make_cases() {
  std::vector<Case> cases;
  auto sphere_case = [&](int m, int d, double scale) {
    std::vector<double> seed(d, 0.0);
    seed[0] = 1.0;
    char name[32];
    std::snprintf(name, sizeof name, "S^%d in R^%d", m, d);
    cases.push_back({name, d, m, scale, coxmesh::sphere(m, d, 1.0), nullptr, seed,
                     gudhi_case(gct::Function_Sm_in_Rd(1.0, m, d), seed, m)});
  };
  auto torus_case = [&](double scale) {
    const double major = 1.0, minor = 0.4;
    std::vector<double> seed{major + minor, 0, 0};
    // GUDHI's Function_torus_in_R3(R, r) is z² + (√(x²+y²) − r)² − R²: r is the major radius.
    cases.push_back({"torus in R^3", 3, 2, scale, coxmesh::torus(major, minor), nullptr, seed,
                     gudhi_case(gct::Function_torus_in_R3(minor, major), seed, 2)});
  };
  const auto circle = gct::Function_Sm_in_Rd(1.0, 1);
  const auto cox_flat_torus = coxmesh::product(coxmesh::sphere(1, 2, 1.0), coxmesh::sphere(1, 2, 1.0));
  auto flat_torus_case = [&](double scale) {
    std::vector<double> seed{1, 0, 1, 0};
    cases.push_back({"flat torus in R^4", 4, 2, scale, cox_flat_torus, nullptr, seed,
                     gudhi_case(gct::make_product_function(circle, circle), seed, 2)});
  };
  {
    std::vector<double> seed{1.0, 0.0};
    cases.push_back({"circle in R^2", 2, 1, 0.0003, coxmesh::sphere(1, 2, 1.0), nullptr, seed,
                     gudhi_case(gct::Function_Sm_in_Rd(1.0, 1, 2), seed, 1)});
  }
  sphere_case(2, 3, 0.044);
  torus_case(0.048);
  sphere_case(2, 4, 0.08);
  sphere_case(3, 4, 0.2);
  sphere_case(1, 5, 0.002);
  sphere_case(2, 5, 0.115);
  sphere_case(3, 6, 0.45);
  flat_torus_case(0.14);
  {
    const int d = 6;
    const coxmesh::FunctionPtr f = coxmesh::moment_curve(d);
    const std::vector<double> seed = f->seed();
    const double radius = 1.5;
    cases.push_back({"moment curve in R^6, ball", d, 1, 0.002, f,
                     coxmesh::ball_domain(std::vector<double>(d, 0.0), radius), seed,
                     gudhi_case(gct::Function_moment_curve_in_Rd(1.0, d), seed, 1,
                                gct::Function_Sm_in_Rd(radius, d - 1, Eigen::VectorXd::Zero(d)))});
  }
  {
    // Half-space ⟨n, x⟩ < ⟨n, p⟩, unit normal n (GUDHI's affine plane evaluates nᵀ(x − p)).
    Eigen::VectorXd n(4);
    n << 0.3, -0.2, 0.9, 0.25;
    n.normalize();
    const Eigen::VectorXd p = (Eigen::VectorXd(4) << 0.1, 0.2, 0.3, 0.4).finished();
    std::vector<double> seed{-1, 0, 0, 1};
    cases.push_back({"flat torus in R^4, cut", 4, 2, 0.14, cox_flat_torus,
                     coxmesh::half_space_domain({n[0], n[1], n[2], n[3]}, n.dot(p)), seed,
                     gudhi_case(gct::make_product_function(circle, circle), seed, 2,
                                gct::Function_affine_plane_in_Rd(Eigen::MatrixXd(n), p))});
  }
  // The scales of GUDHI's own examples, where its trace takes seconds.
  const std::size_t small = cases.size();
  sphere_case(2, 3, 0.02);
  torus_case(0.024);
  sphere_case(3, 4, 0.12);
  sphere_case(3, 6, 0.3);
  flat_torus_case(0.06);
  for (std::size_t i = small; i < cases.size(); ++i) cases[i].name += ", GUDHI's scale";
  // The order of the tables in docs/benchmarks.md: circle R², S² R³, torus R³, S² R⁴, S³ R⁴, S¹ R⁵, S² R⁵, S³ R⁶,
  // flat torus R⁴, moment curve R⁶ in a ball, flat torus R⁴ cut by a hyperplane; then GUDHI's scales.
  return cases;
}

coxmesh::FunctionPtr counting(const coxmesh::FunctionPtr& f, std::uint64_t* calls) {
  return coxmesh::make_function(f->ambient_dimension(), f->codimension(), [f, calls](const double* x, double* v) {
    ++*calls;
    f->evaluate(x, v);
  });
}

// ---- The command-line tool on the same case: what a user runs -------------------------------------

// The preset arguments of `coxmesh trace` for case c (empty: no preset is the same manifold).
std::string cli_preset(const Case& c) {
  if (c.domain) return "";
  if (c.name.starts_with("torus in R^3")) return "--preset torus";
  if (c.name.starts_with("flat torus in R^4")) return "--preset flat-torus";
  if (c.name.starts_with("S^") && c.m >= 2)
    return "--preset sphere --m " + std::to_string(c.m) + " --dim " + std::to_string(c.d);
  return "";
}

std::string comma_list(const double* x, int n) {
  std::string out;
  char buf[32];
  for (int i = 0; i < n; ++i) std::snprintf(buf, sizeof buf, i ? ",%.17g" : "%.17g", x[i]), out += buf;
  return out;
}

// One run of `binary trace` in a fresh process on triangulation (a, b): whole wall time and the
// phases the tool reports in its JSON summary.
void cli_run(const std::string& binary, const Case& c, const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
             double& trace, double& complex, double& whole, std::size_t& simplices) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string stem = (dir / ("coxmesh-bench-" + std::to_string(getpid()))).string();
  {
    std::ofstream matrix(stem + ".matrix");
    for (int i = 0; i < a.rows(); ++i) {
      const Eigen::VectorXd row = a.row(i).transpose();
      matrix << comma_list(row.data(), static_cast<int>(row.size())) << "\n";
    }
  }
  std::string command = binary + " trace " + cli_preset(c) + " --matrix " + stem + ".matrix --offset " +
                        comma_list(b.data(), c.d) + " --seed " + comma_list(c.seed.data(), c.d) +
                        " --threads 1 --json --no-output > " + stem + ".json";
  const auto start = std::chrono::steady_clock::now();
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "error: %s failed\n", command.c_str());
    std::exit(1);
  }
  whole = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ifstream in(stem + ".json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  trace = summary["timings"]["trace_seconds"], complex = summary["timings"]["cell_complex_seconds"];
  simplices = summary["traced_simplices"];
  std::filesystem::remove(stem + ".matrix"), std::filesystem::remove(stem + ".json");
}

Result run_case(const Case& c, int runs, std::mt19937_64& rng, const std::string& cli) {
  Result r;
  r.name = c.name;
  r.d = c.d;
  r.m = c.m;
  r.scale = c.scale;
  const Eigen::MatrixXd a = c.scale * GTriangulation(c.d).matrix();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd b(c.d);
  for (int i = 0; i < c.d; ++i) b(i) = c.scale * u(rng);
  const coxmesh::Triangulation t(a, b);

  // Counting runs (untimed).
  {
    EvaluationLog log;
    c.gudhi(a, b, &log, nullptr);
    r.gudhi_evaluations = log.calls;
    r.gudhi_points = log.points.size();
  }
  {
    std::uint64_t calls = 0;
    coxmesh::ImplicitOracle oracle(t, counting(c.f, &calls), c.domain);
    VertexCountingOracle counted(oracle, c.d);
    const coxmesh::TraceResult traced = coxmesh::trace_manifold(t, counted, {c.seed});
    r.cox_evaluations = calls;
    r.cox_oracle_evaluations = traced.function_evaluations;
    r.cox_vertices = counted.distinct_vertices();
  }
  // Peak memory (forked children).
  r.cox_peak = measure_peak([&](MemoryProbe& probe) { coxmesh_run(t, c.f, c.domain, c.seed, &probe); });
  r.gudhi_peak = measure_peak([&](MemoryProbe& probe) { c.gudhi(a, b, nullptr, &probe); });

  // Timed runs, alternating the two libraries.
  std::vector<double> g[4], x[4];
  for (int i = 0; i < runs; ++i) {
    const GudhiRun gr = c.gudhi(a, b, nullptr, nullptr);
    g[0].push_back(gr.trace_cpu), g[1].push_back(gr.trace_wall), g[2].push_back(gr.complex_cpu),
        g[3].push_back(gr.complex_wall);
    r.gudhi = gr;
    for (int j = 0; j < kCoxmeshRunsPerGudhiRun; ++j) {  // coxmesh is cheap: more runs, a steadier median
      const CoxRun cr = coxmesh_run(t, c.f, c.domain, c.seed);
      x[0].push_back(cr.trace_cpu), x[1].push_back(cr.trace_wall), x[2].push_back(cr.complex_cpu),
          x[3].push_back(cr.complex_wall);
      r.cox = cr;
    }
  }
  r.gudhi.trace_cpu = median(g[0]), r.gudhi.trace_wall = median(g[1]);
  r.gudhi.complex_cpu = median(g[2]), r.gudhi.complex_wall = median(g[3]);
  r.cox.trace_cpu = median(x[0]), r.cox.trace_wall = median(x[1]);
  r.cox.complex_cpu = median(x[2]), r.cox.complex_wall = median(x[3]);
  if (!cli.empty() && !cli_preset(c).empty()) {
    std::vector<double> y[3];
    for (int i = 0; i < runs; ++i) {
      double trace, complex, whole;
      cli_run(cli, c, a, b, trace, complex, whole, r.cli_simplices);
      y[0].push_back(trace), y[1].push_back(complex), y[2].push_back(whole);
    }
    r.has_cli = true;
    r.cli_trace = median(y[0]), r.cli_complex = median(y[1]), r.cli_whole = median(y[2]);
  }
  return r;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// `bench_tracing profile <case> [reps]`: coxmesh only (trace + cell complex), for perf.
int profile(const std::string& filter, int reps) {
  std::mt19937_64 rng(kSeed);
  for (const Case& c : make_cases()) {
    std::mt19937_64 case_rng(rng());
    if (c.name.find(filter) == std::string::npos) continue;
    const Eigen::MatrixXd a = c.scale * GTriangulation(c.d).matrix();
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::VectorXd b(c.d);
    for (int i = 0; i < c.d; ++i) b(i) = c.scale * u(case_rng);
    const coxmesh::Triangulation t(a, b);
    for (int i = 0; i < reps; ++i) {
      const CoxRun r = coxmesh_run(t, c.f, c.domain, c.seed);
      std::printf("%s: |S| %zu, trace %.4f s, complex %.4f s\n", c.name.c_str(), r.interior, r.trace_cpu,
                  r.complex_cpu);
    }
    return 0;
  }
  std::fprintf(stderr, "no case matches '%s'\n", filter.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 2 && std::string(argv[1]) == "profile") return profile(argv[2], argc > 3 ? std::atoi(argv[3]) : 5);
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string filter = argc > 2 ? argv[2] : "";
  const char* cli_env = std::getenv("COXMESH_CLI");  // the tool to run on the same cases, if set
  const std::string cli = cli_env ? cli_env : "";
  std::mt19937_64 rng(kSeed);
  std::vector<Result> results;
  for (const Case& c : make_cases()) {
    std::mt19937_64 case_rng(rng());  // offsets do not depend on the filter
    if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
    std::fprintf(stderr, "running %s ...\n", c.name.c_str());
    results.push_back(run_case(c, runs, case_rng, cli));
  }

  std::printf(
      "Single thread; thread CPU time, median of %d runs (GUDHI) and %d runs (coxmesh); wall times on stderr.\n\n",
      runs, runs * kCoxmeshRunsPerGudhiRun);
  std::printf(
      "| case | scale | \\|S\\| (+\\|S_∂\\|) | cells | GUDHI trace s | coxmesh trace s | trace × | coxmesh simplices/s "
      "| GUDHI complex s | coxmesh complex s | complex × |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Result& r : results) {
    char sizes[64];
    if (r.cox.boundary)
      std::snprintf(sizes, sizeof sizes, "%zu (+%zu)", r.cox.interior, r.cox.boundary);
    else
      std::snprintf(sizes, sizeof sizes, "%zu", r.cox.interior);
    const bool same =
        r.cox.interior == r.gudhi.interior && r.cox.boundary == r.gudhi.boundary && r.cox.cells == r.gudhi.cells;
    std::printf("| %s | %g | %s%s | %zu | %.3f | %.4f | %.1f | %.3g | %.3f | %.4f | %.1f |\n", r.name.c_str(), r.scale,
                sizes, same ? "" : " **≠ GUDHI**", r.cox.cells, r.gudhi.trace_cpu, r.cox.trace_cpu,
                r.gudhi.trace_cpu / r.cox.trace_cpu, r.cox.interior / r.cox.trace_cpu, r.gudhi.complex_cpu,
                r.cox.complex_cpu, r.gudhi.complex_cpu / r.cox.complex_cpu);
  }
  if (!cli.empty()) {
    std::printf(
        "\nThrough the command-line tool: `coxmesh trace` with the same preset, matrix, offset and seed, one "
        "thread, a fresh process per run (median of %d); its own wall-clock phases against GUDHI's CPU time "
        "above.\n\n",
        runs);
    std::printf("| case | \\|S\\| | tool trace s | trace × | tool complex s | complex × | whole command s |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    double log_trace = 0, log_complex = 0;
    int n = 0;
    for (const Result& r : results) {
      if (!r.has_cli) continue;
      const double tx = r.gudhi.trace_cpu / r.cli_trace, cx = r.gudhi.complex_cpu / r.cli_complex;
      std::printf("| %s | %zu%s | %.4f | %.1f | %.4f | %.1f | %.3f |\n", r.name.c_str(), r.cli_simplices,
                  r.cli_simplices == r.cox.interior ? "" : " **≠**", r.cli_trace, tx, r.cli_complex, cx, r.cli_whole);
      log_trace += std::log(tx), log_complex += std::log(cx), ++n;
    }
    if (n)
      std::printf("\nGeometric means: trace × %.1f, complex × %.1f.\n", std::exp(log_trace / n),
                  std::exp(log_complex / n));
  }
  std::printf(
      "\nMemory, bytes per cell (cells of every dimension, interior and boundary). \"structure\" = "
      "CellComplex::bytes(); \"peak, complex\" = peak RSS while the cell complex is built (the traced simplices "
      "it starts from included) minus the RSS before tracing; \"peak, all\" = the same over tracing and "
      "construction.\n\n");
  std::printf(
      "| case | cells | coxmesh structure | coxmesh peak, complex | coxmesh peak, all | GUDHI peak, complex "
      "| GUDHI peak, all |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Result& r : results) {
    const double n = static_cast<double>(r.cox.cells), g = static_cast<double>(r.gudhi.cells);
    std::printf("| %s | %zu | %.0f | %.0f | %.0f | %.0f | %.0f |\n", r.name.c_str(), r.cox.cells,
                r.cox.complex_bytes / n, r.cox_peak.complex / n, r.cox_peak.pipeline / n, r.gudhi_peak.complex / g,
                r.gudhi_peak.pipeline / g);
  }
  std::printf("\nFunction evaluations (F only; the domain function is not counted):\n\n");
  std::printf(
      "| case | coxmesh F evaluations | distinct lattice vertices queried | equal | GUDHI F evaluations "
      "| GUDHI distinct points | GUDHI evaluations per vertex |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Result& r : results)
    std::printf("| %s | %llu | %llu | %s | %llu | %llu | %.1f |\n", r.name.c_str(),
                static_cast<unsigned long long>(r.cox_evaluations), static_cast<unsigned long long>(r.cox_vertices),
                r.cox_evaluations == r.cox_vertices && r.cox_oracle_evaluations == r.cox_vertices ? "yes" : "**no**",
                static_cast<unsigned long long>(r.gudhi_evaluations), static_cast<unsigned long long>(r.gudhi_points),
                static_cast<double>(r.gudhi_evaluations) / r.gudhi_points);
  for (const Result& r : results)
    std::fprintf(
        stderr,
        "{\"case\": \"%s\", \"gudhi_trace_wall\": %s, \"coxmesh_trace_wall\": %s, \"gudhi_complex_wall\": %s, "
        "\"coxmesh_complex_wall\": %s, \"gudhi_simplices\": %zu, \"gudhi_boundary\": %zu, \"gudhi_cells\": %zu}\n",
        r.name.c_str(), fmt("%.4f", r.gudhi.trace_wall).c_str(), fmt("%.5f", r.cox.trace_wall).c_str(),
        fmt("%.4f", r.gudhi.complex_wall).c_str(), fmt("%.5f", r.cox.complex_wall).c_str(), r.gudhi.interior,
        r.gudhi.boundary, r.gudhi.cells);
  return 0;
}
