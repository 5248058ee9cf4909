// coxmesh trace: mesh a manifold given by a preset (thesis Ch. 4; spec §2).
#include <sys/resource.h>

#include <chrono>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/seeds.h"
#include "presets.h"

namespace coxmesh::cli {

namespace {

struct TraceCliOptions {
  std::string preset = "torus";
  PresetParameters params;
  std::string center;
  TriangulationOptions tri;
  std::vector<std::string> seeds;
  bool auto_seed = false, json = false;
  std::size_t max_simplices = 20'000'000;
  std::string box;
  std::optional<double> domain_ball;
  std::string domain_center, cut;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void run(TraceCliOptions o) {
  if (!o.center.empty()) o.params.center = parse_point(o.center, "--center");
  const Preset preset = make_preset(o.preset, o.params);
  const FunctionPtr f = preset.function;
  const int d = f->ambient_dimension();

  FunctionPtr domain = preset.domain;
  if (o.domain_ball) {
    std::vector<double> c = o.domain_center.empty() ? std::vector<double>(d, 0.0) : parse_point(o.domain_center, "--domain-center");
    if (static_cast<int>(c.size()) != d) throw InputError("--domain-center must have " + std::to_string(d) + " coordinates");
    domain = ball_domain(c, *o.domain_ball);
  }
  if (!o.cut.empty()) {
    std::vector<double> nc = parse_point(o.cut, "--cut");
    if (static_cast<int>(nc.size()) != d + 1) throw InputError("--cut needs d+1 = " + std::to_string(d + 1) + " numbers n1,...,nd,c");
    const double c = nc.back();
    nc.pop_back();
    FunctionPtr half = half_space_domain(nc, c);
    if (domain) {
      FunctionPtr a = domain;
      domain = make_function(d, 1, [a, half](const double* x, double* v) {  // intersection: max
        double va, vb;
        a->evaluate(x, &va);
        half->evaluate(x, &vb);
        v[0] = std::max(va, vb);
      });
    } else {
      domain = half;
    }
  }

  TriangulationOptions tri = o.tri;
  if (!tri.scale && !tri.edge_length && tri.matrix_file.empty()) tri.edge_length = preset.edge_length;
  const Triangulation t = tri.build(d);

  TraceOptions options;
  options.max_simplices = o.max_simplices;
  Box search_box{std::vector<double>(d, -preset.extent * 1.25), std::vector<double>(d, preset.extent * 1.25)};
  if (!o.box.empty()) {
    const std::vector<double> b = parse_point(o.box, "--box");
    if (static_cast<int>(b.size()) != 2 * d)
      throw InputError("--box needs 2d = " + std::to_string(2 * d) + " numbers lo1,...,lod,hi1,...,hid");
    Box box{std::vector<double>(b.begin(), b.begin() + d), std::vector<double>(b.begin() + d, b.end())};
    for (int i = 0; i < d; ++i)
      if (!(box.lo[i] < box.hi[i])) throw InputError("--box: lo must be below hi in every coordinate");
    options.box = box;
    search_box = box;
  }

  std::vector<std::vector<double>> seeds;
  for (const std::string& s : o.seeds) {
    std::vector<double> x = parse_point(s, "--seed");
    if (static_cast<int>(x.size()) != d)
      throw InputError("--seed " + s + " has " + std::to_string(x.size()) + " coordinates, expected " + std::to_string(d));
    seeds.push_back(project_onto_manifold(*f, x).value_or(x));
  }
  if (seeds.empty() && !f->seed().empty()) seeds.push_back(f->seed());
  if (o.auto_seed) {
    auto found = find_seeds(*f, domain.get(), search_box);
    seeds.insert(seeds.end(), found.begin(), found.end());
    options.skip_unusable_seeds = !o.seeds.empty() || found.size() > 0;
  }
  if (seeds.empty()) throw InputError("no seed: give --seed or --auto-seed");

  const auto t0 = std::chrono::steady_clock::now();
  ImplicitOracle oracle(t, f, domain);
  TraceResult traced = trace_manifold(t, oracle, seeds, options);
  const double trace_s = seconds_since(t0);
  const std::size_t n_simplices = traced.simplices.size(), n_boundary = traced.boundary_simplices.size();
  const auto status = traced.status;
  const std::string message = traced.message;
  const std::uint64_t evaluations = traced.function_evaluations, oracle_calls = traced.oracle_calls;

  const auto t1 = std::chrono::steady_clock::now();
  const CellComplex cc = build_cell_complex(std::move(traced));
  const double complex_s = seconds_since(t1);
  const auto t2 = std::chrono::steady_clock::now();
  const TopologyReport topo = analyze_topology(cc);
  const double topo_s = seconds_since(t2);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);

  if (o.json) {
    nlohmann::json j;
    j["preset"] = o.preset;
    j["ambient_dimension"] = d;
    j["manifold_dimension"] = cc.manifold_dimension;
    j["traced_simplices"] = n_simplices;
    j["boundary_simplices"] = n_boundary;
    j["cells"] = topo.cells;
    j["boundary_cells"] = topo.boundary_cells;
    j["euler_characteristic"] = topo.euler_characteristic;
    j["betti"] = topo.betti;
    j["components"] = topo.betti.empty() ? 0 : topo.betti[0];
    j["is_manifold"] = topo.is_manifold;
    if (!topo.is_manifold) j["manifold_problem"] = topo.manifold_problem;
    j["function_evaluations"] = evaluations;
    j["oracle_calls"] = oracle_calls;
    j["seeds"] = seeds.size();
    j["complete"] = status == TraceStatus::complete;
    if (!message.empty()) j["message"] = message;
    j["timings"] = {{"trace_seconds", trace_s}, {"cell_complex_seconds", complex_s}, {"topology_seconds", topo_s}};
    j["cell_complex_bytes"] = cc.bytes();
    j["peak_memory_bytes"] = static_cast<long long>(usage.ru_maxrss) * 1024;
    std::cout << j.dump(2) << "\n";
  } else {
    auto list = [](const std::vector<std::size_t>& v) {
      std::string s;
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + std::to_string(v[i]);
      return s;
    };
    std::cout << o.preset << ": " << cc.manifold_dimension << "-manifold in R^" << d << "\n"
              << "  traced simplices   " << n_simplices << " (" << n_boundary << " on the boundary)\n"
              << "  cells by dimension " << list(topo.cells);
    if (n_boundary) std::cout << "  (boundary: " << list(topo.boundary_cells) << ")";
    std::cout << "\n  Euler characteristic " << topo.euler_characteristic << ", Betti numbers (Z/2) "
              << list(topo.betti) << "\n"
              << "  manifold check     " << (topo.is_manifold ? "passed" : "FAILED: " + topo.manifold_problem) << "\n"
              << "  F evaluations      " << evaluations << " (" << oracle_calls << " oracle calls)\n"
              << "  time               trace " << trace_s << " s (" << static_cast<long long>(n_simplices / std::max(trace_s, 1e-9))
              << " simplices/s), cell complex " << complex_s << " s, topology " << topo_s << " s\n"
              << "  peak memory        " << usage.ru_maxrss / 1024 << " MiB\n";
    if (!message.empty()) std::cout << "  note: " << message << "\n";
  }
}

}  // namespace

void register_trace(CLI::App& app, int& status) {
  auto o = std::make_shared<TraceCliOptions>();
  CLI::App* cmd = app.add_subcommand("trace", "mesh a manifold: trace it through the ambient triangulation");
  cmd->add_option("--preset", o->preset, "built-in manifold (see `coxmesh presets`)")->capture_default_str();
  cmd->add_option("--m", o->params.m, "intrinsic dimension (sphere, plane)");
  cmd->add_option("--dim", o->params.dim, "ambient dimension (sphere, moment-curve, plane)");
  cmd->add_option("--radius", o->params.radius, "radius parameter of the preset");
  cmd->add_option("--minor-radius", o->params.minor_radius, "second radius (torus, flat-torus)");
  cmd->add_option("--center", o->center, "centre c1,...,cd (sphere, plane's domain)");
  o->tri.add_to(*cmd);
  cmd->add_option("--seed", o->seeds, "a point near the manifold (projected onto it); repeat for more")->take_all();
  cmd->add_flag("--auto-seed", o->auto_seed, "also find seeds for every component inside the box");
  cmd->add_option("--max-simplices", o->max_simplices, "stop when this many simplices are traced")->capture_default_str();
  cmd->add_option("--box", o->box, "lo1,...,lod,hi1,...,hid: stop at this box (and search seeds in it)");
  cmd->add_option("--domain-ball", o->domain_ball, "keep the part inside the ball of this radius");
  cmd->add_option("--domain-center", o->domain_center, "centre of --domain-ball (default: origin)");
  cmd->add_option("--cut", o->cut, "n1,...,nd,c: keep the part where <n,x> < c");
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  cmd->callback([o, &status] { status = run_guarded([&] { run(*o); }); });

  CLI::App* presets = app.add_subcommand("presets", "list the built-in manifolds");
  presets->callback([&status] {
    for (const auto& p : preset_catalogue()) std::cout << p.name << std::string(18 - p.name.size(), ' ') << p.summary << "\n";
    status = 0;
  });
}

}  // namespace coxmesh::cli
