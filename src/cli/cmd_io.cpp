// coxmesh convert / coxmesh check: re-export and re-check a traced result saved as .cxm.
#include <chrono>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/write_mesh.h"
#include "report.h"

namespace coxmesh::cli {

namespace {

struct ConvertOptions {
  std::string input, output, format, project, pole;
  bool simplices = false;
  bool quiet = false;
};

struct CheckOptions {
  std::string input;
  bool json = false;
};

void convert(const ConvertOptions& o) {
  const MeshFormat format = o.format.empty() ? format_of_path(o.output) : parse_format(o.format);
  check_writable(o.output);
  const NativeFile file = read_native(o.input);
  WriteOptions wo;
  wo.projection = o.project;
  wo.simplices = o.simplices;
  if (!o.pole.empty()) wo.pole = parse_point(o.pole, "--pole");
  wo.native = file.info;
  const WrittenCounts n = write_mesh(o.output, format, file.cells, wo);
  if (!o.quiet) {
    std::cout << "wrote " << o.output << " (" << format_name(format) << ", " << n.points << " points, " << n.cells
              << " cells";
    if (n.skipped) std::cout << "; " << n.skipped << " open cells at the cut not written";
    std::cout << ")\n";
  }
}

void check(const CheckOptions& o) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const NativeFile file = read_native(o.input);
  const double read_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto t1 = Clock::now();
  const TopologyReport topo = analyze_topology(file.cells);
  const double topo_s = std::chrono::duration<double>(Clock::now() - t1).count();
  const CellComplex& cc = file.cells;
  if (o.json) {
    nlohmann::json j = topology_json(cc, topo);
    j["file"] = o.input;
    if (!file.info.source.empty()) j["source"] = file.info.source;
    j["complete"] = file.info.complete;
    if (!file.info.message.empty()) j["message"] = file.info.message;
    j["function_evaluations"] = file.info.function_evaluations;
    j["timings"] = {{"read_seconds", read_s}, {"topology_seconds", topo_s}};
    j["peak_memory_bytes"] = peak_memory_bytes();
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::cout << o.input << ": " << cc.manifold_dimension << "-manifold in R^" << cc.ambient_dimension;
    if (!file.info.source.empty()) std::cout << " (" << file.info.source << ")";
    std::cout << "\n";
    print_topology(std::cout, cc, topo);
    std::cout << "  time               read " << read_s << " s, topology " << topo_s << " s\n";
    if (!file.info.message.empty()) std::cout << "  note: " << file.info.message << "\n";
  }
}

}  // namespace

void register_io(CLI::App& app, int& status) {
  auto c = std::make_shared<ConvertOptions>();
  CLI::App* convert_cmd =
      app.add_subcommand("convert", "re-export a .cxm file (written by trace -o FILE.cxm) to any format");
  convert_cmd->add_option("input", c->input, "a .cxm file")->required();
  convert_cmd->add_option("output", c->output, "the file to write (.vtu .off .ply .obj .mesh .cxm .stl .msh)")
      ->required();
  convert_cmd->add_option("--pole", c->pole, "p1,...,pd: the pole of --project stereographic");
  convert_cmd->add_flag("--simplices", c->simplices,
                        "polygons as triangles and polyhedra as tetrahedra (.vtu .off .ply .obj)");
  convert_cmd->add_option("--format", c->format,
                          "output format, overriding the extension: vtu, off, noff, ply, obj, mesh, cxm, stl, msh");
  convert_cmd->add_option(
      "--project", c->project,
      "3D formats with d != 3: coordinates i,j,k (1-based, default 1,2,3), pca, or a file of 3 rows "
      "of d numbers");
  convert_cmd->add_flag("-q,--quiet", c->quiet, "print nothing but errors");
  convert_cmd->callback([c, &status] { status = run_guarded([&] { convert(*c); }); });

  auto k = std::make_shared<CheckOptions>();
  CLI::App* check_cmd = app.add_subcommand("check",
                                           "re-check a .cxm file: cells, Euler characteristic, Betti numbers, "
                                           "manifold check");
  check_cmd->add_option("input", k->input, "a .cxm file")->required();
  check_cmd->add_flag("--json", k->json, "print the report as JSON (the keys of trace --json that apply)");
  check_cmd->callback([k, &status] { status = run_guarded([&] { check(*k); }); });
}

}  // namespace coxmesh::cli
