// coxmesh locate: the minimal simplex containing a point (thesis §3.4).
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "common.h"

namespace coxmesh::cli {

namespace {

struct LocateOptions {
  std::optional<int> dim;
  std::string point, points_file;
  bool json = false;
  TriangulationOptions tri;
};

void print_result(const Simplex& s, const Triangulation& t, bool json) {
  if (json) {
    std::cout << simplex_json(s, t).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return;
  }
  std::vector<double> xs((s.k + 1) * s.d);
  t.vertex_coordinates(s, xs.data());
  std::cout << to_string(s) << "  dimension " << s.dimension() << "  cartesian";
  std::cout.precision(17);
  for (int v = 0; v <= s.k; ++v) {
    std::cout << (v ? "; " : " ");
    for (int i = 0; i < s.d; ++i) std::cout << (i ? "," : "") << xs[v * s.d + i];
  }
  std::cout << "\n";
}

void run(const LocateOptions& o) {
  if (o.point.empty() == o.points_file.empty()) throw InputError("give exactly one of --point and --points");
  if (!o.point.empty()) {
    const std::vector<double> x = parse_point(o.point, "--point");
    const int d = o.dim.value_or(static_cast<int>(x.size()));
    const Triangulation t = o.tri.build(d);
    print_result(t.locate(x), t, o.json);
    return;
  }
  if (!o.dim) throw InputError("--points needs --dim");
  const Triangulation t = o.tri.build(*o.dim);
  std::ifstream file;
  if (o.points_file != "-") {
    std::error_code ec;
    if (std::filesystem::is_directory(o.points_file, ec))
      throw InputError("the points file '" + o.points_file + "' is a directory");
    file.open(o.points_file);
    if (!file) throw InputError("cannot open the points file '" + o.points_file + "'");
  }
  std::istream& in = o.points_file == "-" ? std::cin : file;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::string where = "line " + std::to_string(lineno);
    const std::vector<double> x = parse_point(line, where);
    if (static_cast<int>(x.size()) != *o.dim)
      throw InputError(where + ": the point has " + std::to_string(x.size()) + " coordinates, expected " +
                       std::to_string(*o.dim));
    print_result(t.locate(x), t, o.json);
  }
}

}  // namespace

void register_locate(CLI::App& app, int& status) {
  auto o = std::make_shared<LocateOptions>();
  CLI::App* cmd = app.add_subcommand("locate", "print the minimal simplex containing a point, with its vertices");
  cmd->add_option("--dim", o->dim, "ambient dimension d (implied by --point)");
  cmd->add_option("--point", o->point, "the point x1,...,xd");
  cmd->add_option("--points", o->points_file, "file with one point per line ('-' for standard input)");
  cmd->add_flag("--json", o->json, "print JSON (one object per line with --points)");
  o->tri.add_to(*cmd);
  cmd->callback([o, &status] {
    status = run_guarded([&] {
      if (o->dim && !o->point.empty()) {
        const auto n = parse_point(o->point, "--point").size();
        if (static_cast<int>(n) != *o->dim)
          throw InputError("--point has " + std::to_string(n) + " coordinates, expected " + std::to_string(*o->dim));
      }
      run(*o);
    });
  });
}

}  // namespace coxmesh::cli
