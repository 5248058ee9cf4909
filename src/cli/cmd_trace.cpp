// coxmesh trace: mesh a manifold given by a preset, by equations typed as text or by samples
// (thesis Ch. 4), report its topology and write it to a file.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/native_pieces.h"
#include "coxmesh/io/vtu_pieces.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/mesh/mesh_distributed.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/mesh/mesh_point_cloud.h"
#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/presets.h"
#include "coxmesh/oracle/stratified_oracle.h"
#include "distributed.h"
#include "points.h"
#include "progress.h"
#include "report.h"
#include "trace_summary.h"

namespace coxmesh::cli {

namespace {

struct TraceCliOptions {
  std::string preset = "torus";
  std::string function;
  PresetParameters params;
  std::string center;
  TriangulationOptions tri;
  std::vector<std::string> seeds, domains, cuts;
  bool auto_seed = false, json = false, quiet = false, no_output = false, simplices = false, refine = false;
  std::uint64_t max_simplices = 20'000'000;
  std::uint64_t max_memory = default_memory_limit();
  int threads = 0;  // all hardware threads
  std::string box;
  std::optional<double> domain_ball;
  std::string domain_center;
  std::string output, format, project, pole;
  std::vector<const CLI::Option*> preset_only;  // options that make no sense with --function
  const CLI::Option *function_given = nullptr, *dim_given = nullptr, *domain_center_given = nullptr;
  PointCloudCliOptions points;            // --points FILE and its options (points.h)
  const CLI::Option* m_option = nullptr;  // --m: also the manifold dimension of --points
};

void run(TraceCliOptions o) {
  // The manifold and its domain. Built again for every worker thread: expression functions
  // (muparser) are not thread-safe, so each worker gets its own.
  double default_edge = 0, extent = 2.0;
  std::string name;
  const bool from_text = o.function_given->count() > 0;
  const bool from_points = !o.points.file.empty();
  if (from_points) {
    for (const CLI::Option* opt : o.preset_only)
      if (opt->count() && opt != o.m_option)
        throw InputError(opt->get_name() + " is a preset parameter; it does not apply to --points");
  } else if (from_text) {
    for (const CLI::Option* opt : o.preset_only)
      if (opt->count()) throw InputError(opt->get_name() + " is a preset parameter; it does not apply to --function");
  } else {  // an option the preset does not read must not pass silently
    std::vector<const CLI::Option*> given = o.preset_only;
    given.push_back(o.dim_given);
    for (const CLI::Option* opt : given) {
      if (!opt->count()) continue;
      for (const PresetInfo& info : preset_catalogue())
        if (info.name == o.preset &&
            std::find(info.parameters.begin(), info.parameters.end(), opt->get_name()) == info.parameters.end())
          throw InputError(opt->get_name() + " does not apply to the preset " + o.preset + " (" + info.summary + ")");
    }
  }
  if (o.domain_center_given->count() && !o.domain_ball) throw InputError("--domain-center needs --domain-ball");
  // Samples: read and prepared once; their functions are thread-safe and shared by the workers.
  const bool domains_given = !o.domains.empty() || o.domain_ball || !o.cuts.empty();
  std::optional<PreparedPointCloud> cloud;
  if (from_points) {
    cloud = load_point_cloud(o.points, o.m_option->count() ? std::optional<int>(o.params.m) : std::nullopt,
                             o.params.dim, o.tri.edge_length, o.threads, domains_given || !o.box.empty() || o.refine);
    for (const std::string& w : cloud->warnings())
      if (!o.quiet) std::cerr << "coxmesh: warning: " << w << "\n";
  }
  if (!from_text && !cloud && !o.center.empty()) o.params.center = parse_point(o.center, "--center");
  std::function<ManifoldFunctions()> make_problem = [&o, &cloud, from_text]() -> ManifoldFunctions {
    FunctionPtr f, domain;
    if (cloud) {
      f = cloud->problem.function;
      domain = cloud->problem.domain;
    } else if (from_text) {
      f = expression_function(o.function, o.params.dim);
    } else {
      const Preset preset = make_preset(o.preset, o.params);
      f = preset.function;
      domain = preset.domain;
    }
    const int d = f->ambient_dimension();
    // Domains: the preset's (replaced by --domain-ball if given), then each --domain and --cut:
    // each its own face (several make a manifold with corners).
    if (o.domain_ball) {
      std::vector<double> c =
          o.domain_center.empty() ? std::vector<double>(d, 0.0) : parse_point(o.domain_center, "--domain-center");
      if (static_cast<int>(c.size()) != d)
        throw InputError("--domain-center must have " + std::to_string(d) + " coordinates");
      domain = ball_domain(c, *o.domain_ball);
    }
    std::vector<FunctionPtr> faces;
    for (const std::string& text : o.domains) faces.push_back(expression_domain(text, d));
    for (const std::string& cut : o.cuts) {
      std::vector<double> nc = parse_point(cut, "--cut");
      if (static_cast<int>(nc.size()) != d + 1)
        throw InputError("--cut needs d+1 = " + std::to_string(d + 1) + " numbers n1,...,nd,c");
      const double c = nc.back();
      nc.pop_back();
      faces.push_back(half_space_domain(nc, c));
    }
    if (faces.size() + (domain ? 1 : 0) > static_cast<std::size_t>(kMaxDomains))
      throw InputError("at most " + std::to_string(kMaxDomains) + " domains (--domain, --cut, --domain-ball)");
    return {f, domain, faces};
  };
  const ManifoldFunctions problem = make_problem();
  const FunctionPtr& f = problem.f;
  if (cloud) {
    default_edge = cloud->problem.edge_length;
    name = o.points.file;
  } else if (from_text) {
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
  if (output.empty() && !o.no_output && !o.json)
    output = (cloud       ? std::filesystem::path(o.points.file).stem().string()
              : from_text ? std::string("manifold")
                          : o.preset) +
             ".vtu";
  if (o.no_output && !o.output.empty()) throw InputError("--no-output contradicts -o " + o.output);
  const bool write = !output.empty();
  std::vector<double> pole;
  // NAME.pvtu: .vtu pieces, one per process, and their manifest (vtu_pieces.h).
  std::string extension = std::filesystem::path(output).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const bool vtu_pieces = write && extension == ".pvtu";
  if (vtu_pieces && !MpiSession::communicator())
    throw InputError("-o " + output +
                     ": a .pvtu is written in pieces by several processes (mpirun -n P, P >= 2); "
                     "write .vtu");
  // Several domains: a manifold with corners, meshed by one process, also under mpirun (below).
  const bool corners = problem.domains.size() + (problem.domain ? 1 : 0) >= 2;
  if (vtu_pieces && corners)
    throw InputError("-o " + output +
                     ": a manifold with corners is meshed by one process, not in pieces (under mpirun, by rank "
                     "0); write .vtu");
  const MeshFormat format = !write || vtu_pieces ? MeshFormat::vtu
                            : o.format.empty()   ? format_of_path(output)
                                                 : parse_format(o.format);
  if (write) {
    if (output == "-" && format == MeshFormat::cxm)
      throw InputError("-o -: the native format is binary; give a file name");
    check_writable(output);
    if (!o.pole.empty()) pole = parse_point(o.pole, "--pole");
    if (format != MeshFormat::cxm)  // the spec fits d (pca, stereographic and files: checked again on the points)
      make_projection(o.project, d, {}, pole);
    WriteOptions early;
    early.projection = o.project;
    early.simplices = o.simplices;
    check_format(format, d, d - f->codimension(), early);
    if (corners) check_stratified_format(format, d - f->codimension());
  } else if (o.simplices || !o.pole.empty()) {
    throw InputError(std::string(o.simplices ? "--simplices" : "--pole") +
                     " applies to the output file; there is none");
  }

  MeshOptions mo;
  mo.trace.max_simplices = o.max_simplices;
  mo.max_memory = o.max_memory;
  mo.auto_seed = o.auto_seed;
  mo.search_box = {std::vector<double>(d, -extent), std::vector<double>(d, extent)};
  if (!o.box.empty()) {
    const std::vector<double> b = parse_point(o.box, "--box");
    if (static_cast<int>(b.size()) != 2 * d)
      throw InputError("--box needs 2d = " + std::to_string(2 * d) + " numbers lo1,...,lod,hi1,...,hid");
    mo.search_box = {std::vector<double>(b.begin(), b.begin() + d), std::vector<double>(b.begin() + d, b.end())};
    for (int i = 0; i < d; ++i)
      if (!(mo.search_box.lo[i] < mo.search_box.hi[i]))
        throw InputError("--box: lo must be below hi in every coordinate");
  } else if (cloud) {
    mo.search_box = {};  // the samples' box, widened by the tube (mesh_point_cloud)
  }
  // The box bounds the walk as a domain (cells along it are closed): when given, and for equations
  // whose seeds are searched in the default box. Seeds given by hand: their whole components.
  // (Samples are bounded by their tube.)
  mo.bounded_by_box = !o.box.empty() || (from_text && o.seeds.empty());
  if (from_text) {  // default scale: 40 edges across the narrowest side of the box
    default_edge = mo.search_box.hi[0] - mo.search_box.lo[0];
    for (int i = 1; i < d; ++i) default_edge = std::min(default_edge, mo.search_box.hi[i] - mo.search_box.lo[i]);
    default_edge /= 40;
  }
  TriangulationOptions tri = o.tri;
  if (!tri.scale && !tri.edge_length && tri.matrix_file.empty()) tri.edge_length = default_edge;
  const Triangulation t =
      cloud && tri.offset.empty() ? tri.build(d).with_offset(cloud->problem.centre()) : tri.build(d);

  for (const std::string& s : o.seeds) {
    std::vector<double> x = parse_point(s, "--seed");
    if (static_cast<int>(x.size()) != d)
      throw InputError("--seed " + s + " has " + std::to_string(x.size()) + " coordinates, expected " +
                       std::to_string(d));
    mo.seeds.push_back(std::move(x));
  }

  // Under mpirun the walk is split between the processes and rank 0 reports (distributed.h).
  Communicator* comm = MpiSession::communicator();
  // But for a manifold with corners: its walk (trace_strata.h) is sequential, so rank 0 meshes it
  // as one process does (any format, a .cxm whole) while the others wait for its status asleep
  // (docs/distributed.md).
  int idle_ranks = 0;
  if (comm && corners) {
    if (comm->rank() != 0) throw DistributedPartDone{};
    idle_ranks = comm->size() - 1;
    comm = nullptr;
  }
  DistributedTraceStats distributed;
  WriteOptions piece_options;   // (of .pvtu pieces)
  PartCounts pieces_written{};  // (summed over them: points, cells, skipped cells)
  DistributedTopologyStats topology_stats;
  if (comm) {
    // Samples: every process prepares the same problem from them (the preparation's result does not
    // depend on threads), and the per-vertex function is traced like any F.
    if (cloud && cloud->oracle != SampleOracle::vertex)
      throw InputError("the " + cloud->oracle_name() +
                       " oracle of point clouds is not traced by several processes yet: run without mpirun");
    // .cxm and .pvtu files in pieces, one per process, and a manifest (native_pieces.h,
    // vtu_pieces.h), with --refine each rank refining its vertices before its piece; other formats
    // are written by rank 0 from the gathered trace. Without a file, the ranks build and analyse
    // their parts as for .cxm pieces and write none: no rank gathers the complex.
    const bool pieces = !write || format == MeshFormat::cxm || vtu_pieces;
    piece_options.projection = o.project;
    piece_options.pole = pole;
    piece_options.simplices = o.simplices;
    if (vtu_pieces) check_vtu_pieces(piece_options);
    if (vtu_pieces)
      mo.complex_tracer = distributed_complex_tracer(
          *comm,
          [&](CellComplexPart& part) -> PartCounts {
            // (the part keeps only what the topology reads from here on)
            const CellClosure closure = closure_for_writing(part, *comm);
            const WrittenCounts n =
                write_vtu_piece_file(output, comm->rank(), closure, part.interior_sizes[0], piece_options);
            return {n.points, n.cells, n.skipped};
          },
          &distributed, &pieces_written, &topology_stats);
    else if (pieces) {
      PartWriter write_piece;  // (none without a file: the parts' levels then need no global order)
      if (write)
        write_piece = [&](CellComplexPart& part) {
          write_native_piece_file(output, comm->rank(), part);
          return PartCounts{};
        };
      mo.complex_tracer = distributed_complex_tracer(*comm, write_piece, &distributed, nullptr, &topology_stats);
    } else {
      mo.tracer = distributed_tracer(*comm, &distributed);
    }
  }
  std::optional<ProgressDisplay> progress;
  if (!o.json && !o.quiet && (!comm || comm->rank() == 0)) {
    progress.emplace();
    mo.trace.progress = [&progress](std::size_t traced) { progress->traced(traced); };
    mo.on_phase = [&progress](const std::string& phase) { progress->phase(phase); };
  }
  mo.trace.threads = o.threads;
  mo.refine = o.refine;
  mo.keep_keys = write && format == MeshFormat::cxm;  // (no other file reads them)
  // Expression functions are not thread-safe: every worker but the first gets its own.
  bool first = true;
  // Writing needs no topology: with several threads it runs while the topology is computed.
  WrittenCounts written;
  double write_s = 0;
  const WhileTopology write_file = [&](const MeshReport& r) {
    if (progress) progress->phase("writing " + output);
    WriteOptions wo;
    wo.projection = o.project;
    wo.pole = pole;
    wo.simplices = o.simplices;
    wo.threads = o.threads;
    wo.native.source = cloud ? "points " + o.points.file : from_text ? "function " + o.function : "preset " + o.preset;
    for (const std::string& text : o.domains) wo.native.source += "; domain " + text;
    if (o.domain_ball) wo.native.source += "; domain-ball " + std::to_string(*o.domain_ball);
    for (const std::string& cut : o.cuts) wo.native.source += "; cut " + cut;
    wo.native.complete = r.status == TraceStatus::complete;
    wo.native.message = r.message;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) wo.native.matrix.push_back(t.matrix()(i, j));
    wo.native.offset.assign(t.offset().data(), t.offset().data() + d);
    wo.native.function_evaluations = r.function_evaluations;
    const auto t3 = Clock::now();
    if (vtu_pieces) {
      write_pvtu_manifest_file(output, comm->size(), d, wo);
      written = {pieces_written[0], pieces_written[1], pieces_written[2]};
    } else {
      written = mo.complex_tracer ? write_native_manifest_file(output, comm->size(), r.topology, wo.native)
                                  : write_mesh(output, format, r.cells, wo);
    }
    write_s = seconds_since(t3);
  };
  SampleOracleCounts counts;
  MeshReport report;
  if (cloud) {  // the samples' oracle: its pipeline (mesh_point_cloud.h)
    if (cloud->oracle != SampleOracle::vertex) {
      if (domains_given || !o.box.empty())
        throw InputError("--oracle " + cloud->oracle_name() +
                         " takes no --domain, --domain-ball, --cut or --box (only the tube)");
      if (o.refine) throw InputError("--refine needs the function F; --oracle " + cloud->oracle_name() + " has none");
    }
    DomainMaker domains;  // the tube (or the --domain-ball that replaces it) and each --domain and --cut
    if (domains_given) domains = [&make_problem](const FunctionPtr&) { return make_problem(); };
    PointCloudMeshReport r = mesh_point_cloud(t, *cloud, mo, domains, write ? write_file : WhileTopology{});
    report = std::move(r.mesh);
    counts = r.counts;
  } else {
    report = mesh_manifold(
        t,
        [&]() -> ManifoldFunctions {
          if (first) return first = false, problem;
          return make_problem();
        },
        mo, write ? write_file : WhileTopology{});
  }
  if (!o.json)
    for (const std::string& w : report.warnings) std::cerr << "coxmesh: warning: " << w << "\n";

  if (progress) progress->clear();

  TraceSummary summary{name, d, report, cloud ? &*cloud : nullptr};
  if (!cloud)
    summary.source = from_text ? std::pair<std::string, std::string>{"function", o.function}
                               : std::pair<std::string, std::string>{"preset", o.preset};
  summary.oracle_counts = counts;
  summary.automatic_seeds = report.automatic_seeds;
  if (write) summary.output = TraceSummary::Output{output, format, written, write_s};
  // With -o - the mesh goes to standard output and the summary to standard error.
  std::ostream& out = output == "-" ? std::cerr : std::cout;
  if (o.json)
    print_trace_json(out, summary);
  else if (!o.quiet)
    print_trace_lines(out, summary);
  if (comm && !o.quiet) print_distributed_stats(std::cerr, distributed, report.topology.cells.at(0), topology_stats);
  if (idle_ranks && !o.quiet)
    std::cerr << "coxmesh: " << idle_ranks + 1 << " processes: a manifold with corners is meshed by rank 0 alone, "
              << idle_ranks << " waited\n";
}

}  // namespace

void register_trace(CLI::App& app, int& status) {
  auto o = std::make_shared<TraceCliOptions>();
  CLI::App* cmd = app.add_subcommand("trace",
                                     "mesh a manifold: trace it through the ambient triangulation, report its "
                                     "topology and write it (default: the torus, to torus.vtu)");
  auto* preset =
      cmd->add_option("--preset", o->preset, "built-in manifold (see `coxmesh presets`)")->capture_default_str();
  CLI::Option* function =
      cmd->add_option("--function", o->function,
                      "the manifold as equations \"e1; e2; ...\" = 0 in x1..xd (x,y,z,w when d <= 4), e.g. "
                      "\"x^2+y^2+z^2-1\"")
          ->excludes(preset);
  o->function_given = function;
  o->m_option = cmd->add_option("--m", o->params.m, "intrinsic dimension (sphere, plane; --points: default d-1)");
  o->preset_only.push_back(o->m_option);
  o->dim_given = cmd->add_option("--dim", o->params.dim,
                                 "ambient dimension d (sphere, moment-curve, plane; --function when the "
                                 "variables do not show it)");
  o->preset_only.push_back(cmd->add_option("--radius", o->params.radius, "radius parameter of the preset"));
  o->preset_only.push_back(
      cmd->add_option("--minor-radius", o->params.minor_radius, "second radius (torus, flat-torus)"));
  o->preset_only.push_back(cmd->add_option("--center", o->center, "centre c1,...,cd (sphere, plane's domain)"));
  o->points.add_to(*cmd);
  o->points.option->excludes(preset)->excludes(function);
  o->tri.add_to(*cmd);
  cmd->add_option("--seed", o->seeds, "a point near the manifold (projected onto it); repeat for more")->take_all();
  cmd->add_flag("--auto-seed", o->auto_seed,
                "also find seeds for every component inside the box (always on for --function without --seed)");
  cmd->add_option("--max-simplices", o->max_simplices, "stop when this many simplices are traced")
      ->capture_default_str()
      ->check(unsigned_integer());
  cmd->add_option_function<std::string>(
      "--max-memory", [o](const std::string& text) { o->max_memory = parse_bytes(text, "--max-memory"); },
      "stop before tracing more than fits in about this much memory: bytes, or with a suffix K, M, G, T "
      "(default: 3/4 of the machine's memory)");
  cmd->add_option("--box", o->box,
                  "lo1,...,lod,hi1,...,hid: stop at this box and search seeds in it (--function: default [-2,2]^d)");
  cmd->add_option("--domain", o->domains,
                  "keep the part where this expression is < 0; repeat to intersect (each domain its own face: "
                  "a manifold with corners)")
      ->take_all();
  cmd->add_option("--domain-ball", o->domain_ball, "keep the part inside the ball of this radius");
  o->domain_center_given =
      cmd->add_option("--domain-center", o->domain_center, "centre of --domain-ball (default: origin)");
  cmd->add_option("--cut", o->cuts, "n1,...,nd,c: keep the part where <n,x> < c; repeat for more faces")->take_all();
  cmd->add_option(
      "-o,--output", o->output,
      "write the mesh to FILE (.vtu .off .ply .obj .mesh .cxm .stl .msh); default NAME.vtu (not with --json)");
  cmd->add_option("--format", o->format,
                  "output format, overriding the extension: vtu, off, noff, ply, obj, mesh, cxm, stl, msh");
  cmd->add_flag(
      "--simplices", o->simplices,
      "write polygons as triangles and polyhedra as tetrahedra (.vtu .off .ply .obj; .mesh .stl .msh always)");
  cmd->add_option("--project", o->project,
                  "3D formats with d != 3: coordinates i,j,k (1-based, default 1,2,3), pca, stereographic (R^d to "
                  "R^(d-1)), or a file of 3 rows of d numbers");
  cmd->add_option("--pole", o->pole,
                  "p1,...,pd: the pole of --project stereographic (default: chosen away from the manifold)");
  cmd->add_option("--threads", o->threads,
                  "worker threads (0: all hardware threads); the result is the same for any number")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("--refine", o->refine,
                "move the vertices onto M (Gauss-Newton on F, and on the domains whose boundary a vertex lies on); "
                "each moves at most a quarter of the longest edge");
  cmd->add_flag("--no-output", o->no_output, "write no file");
  cmd->add_flag("--json", o->json, "print the summary as JSON (and write a file only with -o)");
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &status] {
    const auto body = [&] { run(*o); };
    Communicator* const comm = MpiSession::communicator();
    status = comm ? run_distributed_guarded(*comm, body) : run_guarded(body);
  });

  CLI::App* presets = app.add_subcommand("presets", "list the built-in manifolds");
  presets->callback([&status] {
    for (const auto& p : preset_catalogue())
      std::cout << p.name << std::string(18 - p.name.size(), ' ') << p.summary << "\n";
    status = 0;
  });
}

}  // namespace coxmesh::cli
