// coxmesh trace: mesh a manifold given by a preset or by equations typed as text (thesis Ch. 4;
// spec §2), report its topology and write it to a file.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "common.h"
#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/oracle/regularity.h"
#include "coxmesh/tracing/seeds.h"
#include "coxmesh/util/parallel_for.h"
#include "presets.h"
#include "report.h"

namespace coxmesh::cli {

namespace {

struct TraceCliOptions {
  std::string preset = "torus";
  std::string function;
  PresetParameters params;
  std::string center;
  TriangulationOptions tri;
  std::vector<std::string> seeds, domains;
  bool auto_seed = false, json = false, quiet = false, no_output = false;
  std::size_t max_simplices = 20'000'000;
  int threads = 0;  // all hardware threads
  std::string box;
  std::optional<double> domain_ball;
  std::string domain_center, cut;
  std::string output, format, project;
  std::vector<const CLI::Option*> preset_only;  // options that make no sense with --function
  const CLI::Option *function_given = nullptr, *dim_given = nullptr, *domain_center_given = nullptr;
};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Progress on stderr once a run has lasted about a second: one updated line on a terminal, plain
// lines (at most one every 2 s) otherwise. Never used with --json or --quiet.
class ProgressDisplay {
 public:
  ProgressDisplay() : tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()), last_(start_) {}
  ~ProgressDisplay() { clear(); }

  void traced(std::size_t simplices) {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || (shown_ && std::chrono::duration<double>(now - last_).count() < (tty_ ? 0.1 : 2.0))) return;
    last_ = now;
    show("tracing: " + std::to_string(simplices) + " simplices, " +
         std::to_string(static_cast<long long>(simplices / elapsed)) + " simplices/s, " + seconds(elapsed));
  }
  // A later phase (cell complex, topology, writing): shown only when progress is already on screen.
  void phase(const std::string& what) {
    if (shown_) show(what + "... (" + seconds(seconds_since(start_)) + ")");
  }
  void clear() {
    if (tty_ && shown_) std::fputs("\r\033[K", stderr);
    shown_ = false;
  }

 private:
  static std::string seconds(double s) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f s", s);
    return buffer;
  }
  void show(const std::string& line) {
    if (tty_) std::fprintf(stderr, "\r\033[K  %s", line.c_str());
    else std::fprintf(stderr, "coxmesh: %s\n", line.c_str());
    std::fflush(stderr);
    shown_ = true;
  }

  bool tty_, shown_ = false;
  Clock::time_point start_, last_;
};

// max(a, b): the intersection of two domains {a < 0} and {b < 0}.
FunctionPtr intersect_domains(FunctionPtr a, FunctionPtr b) {
  if (!a) return b;
  const int d = a->ambient_dimension();
  return make_function(d, 1, [a, b](const double* x, double* v) {
    double va, vb;
    a->evaluate(x, &va);
    b->evaluate(x, &vb);
    v[0] = std::max(va, vb);
  });
}

void run(TraceCliOptions o) {
  // The manifold and its domain. Built again for every worker thread: expression functions
  // (muparser) are not thread-safe, so each worker gets its own.
  double default_edge = 0, extent = 2.0;
  std::string name;
  const bool from_text = o.function_given->count() > 0;
  if (from_text) {
    for (const CLI::Option* opt : o.preset_only)
      if (opt->count()) throw InputError(opt->get_name() + " is a preset parameter; it does not apply to --function");
  } else {  // an option the preset does not read must not pass silently
    std::vector<const CLI::Option*> given = o.preset_only;
    given.push_back(o.dim_given);
    for (const CLI::Option* opt : given) {
      if (!opt->count()) continue;
      for (const PresetInfo& info : preset_catalogue())
        if (info.name == o.preset && std::find(info.parameters.begin(), info.parameters.end(), opt->get_name()) == info.parameters.end())
          throw InputError(opt->get_name() + " does not apply to the preset " + o.preset + " (" + info.summary + ")");
    }
  }
  if (o.domain_center_given->count() && !o.domain_ball) throw InputError("--domain-center needs --domain-ball");
  if (!from_text && !o.center.empty()) o.params.center = parse_point(o.center, "--center");
  std::function<std::pair<FunctionPtr, FunctionPtr>()> make_problem = [&o, from_text]() -> std::pair<FunctionPtr, FunctionPtr> {
    FunctionPtr f, domain;
    if (from_text) {
      f = expression_function(o.function, o.params.dim);
    } else {
      const Preset preset = make_preset(o.preset, o.params);
      f = preset.function;
      domain = preset.domain;
    }
    const int d = f->ambient_dimension();
    // Domains: the preset's (replaced by --domain-ball if given), then each --domain and --cut,
    // intersected by max.
    if (o.domain_ball) {
      std::vector<double> c = o.domain_center.empty() ? std::vector<double>(d, 0.0) : parse_point(o.domain_center, "--domain-center");
      if (static_cast<int>(c.size()) != d) throw InputError("--domain-center must have " + std::to_string(d) + " coordinates");
      domain = ball_domain(c, *o.domain_ball);
    }
    for (const std::string& text : o.domains) domain = intersect_domains(domain, expression_domain(text, d));
    if (!o.cut.empty()) {
      std::vector<double> nc = parse_point(o.cut, "--cut");
      if (static_cast<int>(nc.size()) != d + 1) throw InputError("--cut needs d+1 = " + std::to_string(d + 1) + " numbers n1,...,nd,c");
      const double c = nc.back();
      nc.pop_back();
      domain = intersect_domains(domain, half_space_domain(nc, c));
    }
    return {f, domain};
  };
  // (no structured binding: clang 14 cannot capture one in a lambda)
  std::pair<FunctionPtr, FunctionPtr> problem = make_problem();
  FunctionPtr f = std::move(problem.first), domain = std::move(problem.second);
  if (from_text) {
    name = "\"" + o.function + "\"";
  } else {
    const Preset preset = make_preset(o.preset, o.params);
    default_edge = preset.edge_length;
    extent = preset.extent * 1.25;
    name = o.preset;
  }
  const int d = f->ambient_dimension();

  // The output file is checked before the (possibly long) trace: format and projection spec.
  std::string output = o.output;
  if (output.empty() && !o.no_output && !o.json) output = (from_text ? std::string("manifold") : o.preset) + ".vtu";
  if (o.no_output && !o.output.empty()) throw InputError("--no-output contradicts -o " + o.output);
  const bool write = !output.empty();
  const MeshFormat format = !write ? MeshFormat::vtu : o.format.empty() ? format_of_path(output) : parse_format(o.format);
  if (write) {
    if (output == "-" && format == MeshFormat::cxm) throw InputError("-o -: the native format is binary; give a file name");
    check_writable(output);
    if (format != MeshFormat::cxm) make_projection(o.project, d, {});  // the spec fits d (pca and files: checked again on the points)
  }

  TraceOptions options;
  options.max_simplices = o.max_simplices;
  Box search_box{std::vector<double>(d, -extent), std::vector<double>(d, extent)};
  if (!o.box.empty()) {
    const std::vector<double> b = parse_point(o.box, "--box");
    if (static_cast<int>(b.size()) != 2 * d)
      throw InputError("--box needs 2d = " + std::to_string(2 * d) + " numbers lo1,...,lod,hi1,...,hid");
    Box box{std::vector<double>(b.begin(), b.begin() + d), std::vector<double>(b.begin() + d, b.end())};
    for (int i = 0; i < d; ++i)
      if (!(box.lo[i] < box.hi[i])) throw InputError("--box: lo must be below hi in every coordinate");
    search_box = box;
  }
  // The box bounds the walk as a domain (cells along it are closed): when given, and for equations
  // whose seeds are searched in the default box. Seeds given by hand: their whole components.
  const bool bounded_by_box = !o.box.empty() || (from_text && o.seeds.empty());
  if (bounded_by_box) {
    FunctionPtr box = box_domain(search_box);
    domain = intersect_domains(domain, box);
    make_problem = [inner = make_problem, box] {
      auto [fw, dw] = inner();
      return std::pair{fw, intersect_domains(dw, box)};
    };
  }
  if (from_text) {  // default scale: 40 edges across the narrowest side of the box
    default_edge = search_box.hi[0] - search_box.lo[0];
    for (int i = 1; i < d; ++i) default_edge = std::min(default_edge, search_box.hi[i] - search_box.lo[i]);
    default_edge /= 40;
  }
  TriangulationOptions tri = o.tri;
  if (!tri.scale && !tri.edge_length && tri.matrix_file.empty()) tri.edge_length = default_edge;
  const Triangulation t = tri.build(d);

  std::vector<std::vector<double>> seeds;
  for (const std::string& s : o.seeds) {
    std::vector<double> x = parse_point(s, "--seed");
    if (static_cast<int>(x.size()) != d)
      throw InputError("--seed " + s + " has " + std::to_string(x.size()) + " coordinates, expected " + std::to_string(d));
    seeds.push_back(project_onto_manifold(*f, x).value_or(x));
  }
  if (seeds.empty() && !f->seed().empty()) seeds.push_back(f->seed());
  std::size_t automatic = 0;
  if (o.auto_seed || seeds.empty()) {
    auto found = find_seeds(*f, domain.get(), search_box);
    automatic = found.size();
    if (seeds.empty() && found.empty()) {
      // Not finite where sampled (0/0, 1/0, log of a negative): say that, not "no point found".
      std::mt19937_64 random(1);
      std::vector<double> x(d), value(f->codimension());
      int finite = 0;
      std::string example;
      for (int sample = 0; sample < 64; ++sample) {
        for (int i = 0; i < d; ++i)
          x[i] = search_box.lo[i] + std::uniform_real_distribution<double>(0, 1)(random) * (search_box.hi[i] - search_box.lo[i]);
        f->evaluate(x.data(), value.data());
        const bool ok = std::all_of(value.begin(), value.end(), [](double v) { return std::isfinite(v); });
        finite += ok;
        if (!ok && example.empty()) {
          std::ostringstream at;
          at << "(";
          for (int i = 0; i < d; ++i) at << (i ? "," : "") << x[i];
          at << ")";
          example = at.str();
        }
      }
      if (finite == 0)
        throw InputError("F is not finite at any of 64 points sampled in the box (e.g. at " + example +
                         "): check the expression for divisions by zero and logarithms or roots of negative numbers");
      std::ostringstream box_text;
      for (int i = 0; i < d; ++i) box_text << (i ? " x [" : "[") << search_box.lo[i] << "," << search_box.hi[i] << "]";
      throw InputError("no point of the manifold found in the box " + box_text.str() +
                       (domain ? " inside the domain" : "") + ": give --box lo1,...,lod,hi1,...,hid or --seed");
    }
    options.skip_unusable_seeds = true;
    seeds.insert(seeds.end(), found.begin(), found.end());
  }

  for (auto& seed : seeds) seed = generic_seed(*f, t, std::move(seed));

  std::optional<ProgressDisplay> progress;
  if (!o.json && !o.quiet) {
    progress.emplace();
    options.progress = [&progress](std::size_t traced) { progress->traced(traced); };
  }

  const auto t0 = Clock::now();
  options.threads = resolve_threads(o.threads);
  // Several workers share the vertex values (F once per vertex in all); each has its own
  // functions, since an expression evaluator is not thread-safe.
  const auto shared = options.threads > 1 ? ImplicitOracle::make_shared_values(t, f, domain) : nullptr;
  bool first_worker = true;
  TraceResult traced = trace_manifold(t, [&]() -> std::unique_ptr<IntersectionOracle> {
    if (first_worker) {  // the main thread's functions; fresh ones for the other workers
      first_worker = false;
      return std::make_unique<ImplicitOracle>(t, f, domain, shared);
    }
    auto [fw, dw] = make_problem();
    return std::make_unique<ImplicitOracle>(t, fw, dw, shared);
  }, seeds, options);
  const double h = t.longest_edge();
  const ImplicitFunction* f_only[] = {f.get()};
  if (traced.simplices.size() == 0) {
    std::vector<double> seed_points;
    for (const auto& x : seeds) seed_points.insert(seed_points.end(), x.begin(), x.end());
    if (singular_on(f_only, seed_points, h, 48, 0.02))
      throw InputError("F's differential is singular at the seeds: F vanishes identically near them or its equations are "
                       "dependent, so 0 is not a regular value of F and there is no manifold to trace");
    throw InputError("no simplex near the " + std::to_string(seeds.size()) +
                     " seeds meets the manifold: the triangulation is too coarse for it (give a smaller --edge-length)");
  }
  const double trace_s = seconds_since(t0);
  const auto status = traced.status;
  const std::string message = traced.message;
  const std::uint64_t evaluations = traced.function_evaluations, oracle_calls = traced.oracle_calls;

  if (progress) progress->phase("building the cell complex");
  const auto t1 = Clock::now();
  const CellComplex cc = build_cell_complex(std::move(traced), options.threads);
  const double complex_s = seconds_since(t1);
  if (progress) progress->phase("computing the topology");
  const auto t2 = Clock::now();
  const TopologyReport topo = analyze_topology(cc);
  const double topo_s = seconds_since(t2);
  // The exact rule meshes a perturbed level set where F = 0 is not a regular level: say so.
  std::vector<std::string> warnings;
  if (singular_on(f_only, {cc.vertices.data(), cc.vertices.size()}, h))
    warnings.push_back("F's differential is (nearly) singular on the traced set: 0 is not a regular value of F (F is a "
                       "square, F >= 0, or its equations are dependent there); what was meshed is a perturbed level set "
                       "near F = 0");
  if (domain) {
    const ImplicitFunction* f_and_domain[] = {f.get(), domain.get()};
    if (singular_on(f_and_domain, {cc.boundary_vertices.data(), cc.boundary_vertices.size()}, h))
      warnings.push_back("the domain's boundary is tangent to the manifold along the cut (D = 0 contains M or touches "
                         "it): the cut meshed is a perturbed one");
  }
  if (!o.json)
    for (const std::string& w : warnings) std::cerr << "coxmesh: warning: " << w << "\n";

  WrittenCounts written;
  double write_s = 0;
  if (write) {
    if (progress) progress->phase("writing " + output);
    WriteOptions wo;
    wo.projection = o.project;
    wo.native.source = from_text ? "function " + o.function : "preset " + o.preset;
    for (const std::string& text : o.domains) wo.native.source += "; domain " + text;
    if (o.domain_ball) wo.native.source += "; domain-ball " + std::to_string(*o.domain_ball);
    if (!o.cut.empty()) wo.native.source += "; cut " + o.cut;
    wo.native.complete = status == TraceStatus::complete;
    wo.native.message = message;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) wo.native.matrix.push_back(t.matrix()(r, c));
    wo.native.offset.assign(t.offset().data(), t.offset().data() + d);
    wo.native.function_evaluations = evaluations;
    const auto t3 = Clock::now();
    written = write_mesh(output, format, cc, wo);
    write_s = seconds_since(t3);
  }
  if (progress) progress->clear();

  // With -o - the mesh goes to standard output and the summary to standard error.
  std::ostream& out = output == "-" ? std::cerr : std::cout;
  if (o.json) {
    nlohmann::json j = topology_json(cc, topo);
    if (from_text) j["function"] = o.function;
    else j["preset"] = o.preset;
    j["function_evaluations"] = evaluations;
    j["oracle_calls"] = oracle_calls;
    j["seeds"] = seeds.size();
    j["automatic_seeds"] = automatic;
    j["complete"] = status == TraceStatus::complete;
    if (!message.empty()) j["message"] = message;
    if (!warnings.empty()) j["warnings"] = warnings;
    j["timings"] = {{"trace_seconds", trace_s}, {"cell_complex_seconds", complex_s}, {"topology_seconds", topo_s}};
    if (write) {
      j["timings"]["write_seconds"] = write_s;
      j["output"] = {{"path", output}, {"format", format_name(format)}, {"points", written.points},
                     {"cells", written.cells}, {"skipped_cells", written.skipped}};
    }
    j["peak_memory_bytes"] = peak_memory_bytes();
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else if (!o.quiet) {
    out << name << ": " << cc.manifold_dimension << "-manifold in R^" << d << "\n";
    print_topology(out, cc, topo);
    if (automatic) out << "  seeds              " << automatic << " found automatically in the box\n";
    out << "  F evaluations      " << evaluations << " (" << oracle_calls << " oracle calls)\n"
              << "  time               trace " << trace_s << " s ("
              << static_cast<long long>(cc.interior[0].size() / std::max(trace_s, 1e-9)) << " simplices/s), cell complex "
              << complex_s << " s, topology " << topo_s << " s";
    if (write) out << ", write " << write_s << " s";
    out << "\n  peak memory        " << peak_memory_bytes() / (1 << 20) << " MiB\n";
    if (write) {
      out << "  output             " << output << " (" << format_name(format) << ", " << written.points << " points, "
                << written.cells << " cells";
      if (written.skipped) out << "; " << written.skipped << " open cells at the cut not written";
      out << ")\n";
    }
    if (!message.empty()) out << "  note: " << message << "\n";
  }
}

}  // namespace

void register_trace(CLI::App& app, int& status) {
  auto o = std::make_shared<TraceCliOptions>();
  CLI::App* cmd = app.add_subcommand("trace", "mesh a manifold: trace it through the ambient triangulation, report its "
                                              "topology and write it (default: the torus, to torus.vtu)");
  auto* preset = cmd->add_option("--preset", o->preset, "built-in manifold (see `coxmesh presets`)")->capture_default_str();
  o->function_given = cmd->add_option("--function", o->function,
                  "the manifold as equations \"e1; e2; ...\" = 0 in x1..xd (x,y,z,w when d <= 4), e.g. "
                  "\"x^2+y^2+z^2-1\"")
      ->excludes(preset);
  o->preset_only.push_back(cmd->add_option("--m", o->params.m, "intrinsic dimension (sphere, plane)"));
  o->dim_given = cmd->add_option("--dim", o->params.dim, "ambient dimension d (sphere, moment-curve, plane; --function when the "
                                          "variables do not show it)");
  o->preset_only.push_back(cmd->add_option("--radius", o->params.radius, "radius parameter of the preset"));
  o->preset_only.push_back(cmd->add_option("--minor-radius", o->params.minor_radius, "second radius (torus, flat-torus)"));
  o->preset_only.push_back(cmd->add_option("--center", o->center, "centre c1,...,cd (sphere, plane's domain)"));
  o->tri.add_to(*cmd);
  cmd->add_option("--seed", o->seeds, "a point near the manifold (projected onto it); repeat for more")->take_all();
  cmd->add_flag("--auto-seed", o->auto_seed,
                "also find seeds for every component inside the box (always on for --function without --seed)");
  cmd->add_option("--max-simplices", o->max_simplices, "stop when this many simplices are traced")
      ->capture_default_str()
      ->check(unsigned_integer());
  cmd->add_option("--box", o->box,
                  "lo1,...,lod,hi1,...,hid: stop at this box and search seeds in it (--function: default [-2,2]^d)");
  cmd->add_option("--domain", o->domains, "keep the part where this expression is < 0; repeat to intersect")->take_all();
  cmd->add_option("--domain-ball", o->domain_ball, "keep the part inside the ball of this radius");
  o->domain_center_given = cmd->add_option("--domain-center", o->domain_center, "centre of --domain-ball (default: origin)");
  cmd->add_option("--cut", o->cut, "n1,...,nd,c: keep the part where <n,x> < c");
  cmd->add_option("-o,--output", o->output,
                  "write the mesh to FILE (.vtu .off .ply .obj .mesh .cxm); default NAME.vtu (not with --json)");
  cmd->add_option("--format", o->format, "output format, overriding the extension: vtu, off, noff, ply, obj, mesh, cxm");
  cmd->add_option("--project", o->project,
                  "3D formats with d != 3: coordinates i,j,k (1-based, default 1,2,3), pca, or a file of 3 rows of d "
                  "numbers");
  cmd->add_option("--threads", o->threads, "worker threads (0: all hardware threads); the result is the same for any number")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("--no-output", o->no_output, "write no file");
  cmd->add_flag("--json", o->json, "print the summary as JSON (and write a file only with -o)");
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &status] { status = run_guarded([&] { run(*o); }); });

  CLI::App* presets = app.add_subcommand("presets", "list the built-in manifolds");
  presets->callback([&status] {
    for (const auto& p : preset_catalogue()) std::cout << p.name << std::string(18 - p.name.size(), ' ') << p.summary << "\n";
    status = 0;
  });
}

}  // namespace coxmesh::cli
