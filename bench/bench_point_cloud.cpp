// Point clouds side by side: coxmesh's per-vertex function traced on Ã_d against GUDHI's tangential
// complex (Debian libgudhi-dev with CGAL), on the same samples (tests/oracle/point_samples.h), one
// core each. Prints one line per library and case: Z/2 Betti numbers, wall and CPU time (the CPU
// time is what a quiet machine's wall time would be: the development machine is shared), peak
// memory so far.
//
//   bench_point_cloud [--coxmesh-only] [--winding] [case n noise]...
//   (default: the table of docs/benchmarks.md, "Point clouds"; --winding: the winding oracle for
//   every case, not only where the frames look non-orientable)
#include <CGAL/Epick_d.h>
#include <gudhi/Persistent_cohomology.h>
#include <gudhi/Simplex_tree.h>
#include <gudhi/Tangential_complex.h>
#include <sys/resource.h>

#include <chrono>
#include <ctime>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/mesh/mesh_winding.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/point_cloud_problem.h"
#include "point_samples.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }
double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
long peak_mib() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}
std::string list(const std::vector<std::size_t>& v) {
  std::ostringstream s;
  for (std::size_t i = 0; i < v.size(); ++i) s << (i ? " " : "") << v[i];
  return s.str();
}

// The library's choice, as `trace --points` makes it: the per-vertex function, or the winding oracle
// where the frames say the normal bundle is not orientable (or always, with `winding`).
void run_coxmesh(const coxmesh::test::Samples& s, bool winding, double* spacing) {
  using namespace coxmesh;
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  PointCloudProblem p = make_point_cloud_problem(s.points, s.d, s.m);  // one thread (the default)
  const double setup = cpu_seconds() - c0;
  const Triangulation t = Triangulation::coxeter(s.d).with_longest_edge(p.edge_length).with_offset(p.centre());
  TopologyReport topo;
  std::string oracle = "vertex";
  if (winding || wants_winding_oracle(p.diagnostics)) {
    oracle = "winding";
    const WindingMeshResult r = mesh_normal_winding(t, p);
    topo = r.topology;
    oracle += ", " + std::to_string(r.odd_tetrahedra) + " odd tetrahedra, check " +
              std::to_string(static_cast<int>(1000 * r.check_seconds)) + " ms";
  } else {
    ImplicitOracle o(t, p.function, p.domain);
    TraceOptions options;
    options.skip_unusable_seeds = true;
    TraceResult r = trace_manifold(t, o, p.seeds, options);
    topo = analyze_topology(build_cell_complex(std::move(r)));
  }
  *spacing = p.diagnostics.spacing;
  const double cpu = cpu_seconds() - c0;
  std::cout << "  coxmesh  betti " << list(topo.betti) << (topo.is_manifold ? ", manifold" : ", NOT a manifold") << " ("
            << oracle << "), " << seconds(t0) << " s (CPU " << cpu << " s, " << 1e6 * cpu / s.size()
            << " us/sample, of which setup " << 1e6 * setup / s.size() << "), peak " << peak_mib() << " MiB\n";
}

// GUDHI's tangential complex, its perturbation fix-up (maximal translation 0.1 spacing, 10 s at
// most), and Z/2 Betti numbers by persistent cohomology.
void run_gudhi(const coxmesh::test::Samples& s, double spacing) {
  using Kernel = CGAL::Epick_d<CGAL::Dynamic_dimension_tag>;
  using TC = Gudhi::tangential_complex::Tangential_complex<Kernel, CGAL::Dynamic_dimension_tag, CGAL::Sequential_tag>;
  Kernel kernel;
  std::vector<Kernel::Point_d> points;
  for (std::size_t i = 0; i < s.size(); ++i)
    points.emplace_back(s.points.begin() + i * s.d, s.points.begin() + (i + 1) * s.d);
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  TC tc(points, s.m, kernel);
  tc.compute_tangential_complex();
  const double build = seconds(t0);
  const auto before = tc.number_of_inconsistent_simplices();
  const auto t1 = Clock::now();
  const auto fix = tc.fix_inconsistencies_using_perturbation(0.1 * spacing, 10.0);
  const double fixing = seconds(t1);
  Gudhi::Simplex_tree<> tree;
  tc.create_complex(tree);
  Gudhi::persistent_cohomology::Persistent_cohomology<Gudhi::Simplex_tree<>, Gudhi::persistent_cohomology::Field_Zp>
      pcoh(tree, true);
  pcoh.init_coefficients(2);
  pcoh.compute_persistent_cohomology();
  std::vector<std::size_t> betti;
  for (int b : pcoh.betti_numbers()) betti.push_back(b);
  std::cout << "  GUDHI    betti " << list(betti) << ", " << before.num_inconsistent_stars
            << " inconsistent stars before the fix-up, " << fix.final_num_inconsistent_stars
            << (fix.success ? " after (fixed)" : " after (not fixed)") << ", complex " << build << " s + fix-up "
            << fixing << " s, total " << seconds(t0) << " s (CPU " << cpu_seconds() - c0 << " s, "
            << 1e6 * (cpu_seconds() - c0) / s.size() << " us/sample), peak " << peak_mib() << " MiB\n";
}

}  // namespace

int main(int argc, char** argv) {
  struct Case {
    std::string name;
    std::size_t n;
    double noise;
  };
  std::vector<Case> cases;
  bool gudhi = true, winding = false;
  int i = 1;
  for (; i < argc && argv[i][0] == '-'; ++i) {
    const std::string flag = argv[i];
    if (flag == "--coxmesh-only")
      gudhi = false;
    else if (flag == "--winding")
      winding = true;
    else
      return std::cerr << "unknown option " << flag << "\n", 2;
  }
  for (; i + 2 < argc; i += 3) cases.push_back({argv[i], std::stoul(argv[i + 1]), std::stod(argv[i + 2])});
  if (cases.empty())
    cases = {{"torus", 2000, 0},      {"torus", 2000, 0.01},    {"torus", 10000, 0},         {"torus", 10000, 0.01},
             {"sphere", 10000, 0.01}, {"flat-torus", 10000, 0}, {"flat-torus", 10000, 0.01}, {"s3", 10000, 0},
             {"s3", 50000, 0},        {"rp2", 2000, 0},         {"rp2", 10000, 0.01},        {"klein", 10000, 0.01}};
  for (const Case& c : cases) {
    const coxmesh::test::Samples s = coxmesh::test::sample_manifold(c.name, c.n, c.noise);
    std::cout << c.name << ", " << c.n << " samples, noise " << c.noise << "\n";
    double spacing = 0;
    run_coxmesh(s, winding, &spacing);  // first: its peak memory is the lower one
    if (gudhi) run_gudhi(s, spacing);
  }
}
