// The point-cloud front end of `coxmesh trace`; see points.h and docs/point_clouds.md.
#include "points.h"

#include <chrono>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/mesh/mesh_winding.h"
#include "coxmesh/tracing/local_pca_oracle.h"

namespace coxmesh::cli {

void PointCloudCliOptions::add_to(CLI::App& cmd) {
  option = cmd.add_option("--points", file,
                          "mesh the manifold sampled by the points of FILE (.xyz .txt .csv .off .ply .npy); give its "
                          "dimension with --m (default d-1)")
               ->type_name("FILE");
  cmd.add_option(
         "--pc-function", function,
         "point clouds: blended (smooth, tolerates noise; default) or nearest (the frame of the nearest sample)")
      ->check(CLI::IsMember({"blended", "nearest"}));
  cmd.add_option("--oracle", oracle,
                 "point clouds: auto (default: winding where the normal frames look non-orientable in codimension 2, "
                 "else vertex), vertex (a function per lattice vertex: a manifold always), winding (surfaces in R^4 "
                 "such as RP^2 and the Klein bottle: winding numbers of the normal offsets) or local-pca (the thesis "
                 "prototype's per-simplex PCA, for comparison: reports its defects; one thread)")
      ->check(CLI::IsMember({"auto", "vertex", "winding", "local-pca"}));
  cmd.add_option("--neighbourhood", neighbourhood,
                 "point clouds: radius of the neighbourhoods whose PCA gives the normals (default 5 sample spacings)");
  cmd.add_option("--tube", tube,
                 "point clouds: mesh only within T edge lengths of the samples (default 3; 0: no tube)");
  cmd.add_option("--blend-width", blend_width,
                 "point clouds: width of the blended function's Gaussian (default 2 spacings, more for noisy samples)");
  cmd.add_flag("--use-normals", use_normals, "point clouds: orient by the normals in the file instead of propagating");
}

LoadedPointCloud load_point_cloud(const PointCloudCliOptions& o, std::optional<int> m, std::optional<int> dim,
                                  std::optional<double> edge_length, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  PointReadOptions ro;
  ro.dimension = dim.value_or(0);
  PointSet set = read_points(o.file, ro);
  LoadedPointCloud pc;
  pc.file = o.file;
  pc.duplicates = set.duplicates;
  pc.read = set.size() + set.duplicates;
  pc.format = set.format;
  const int d = set.dimension;
  const int mm = m.value_or(d - 1);
  PointCloudOptions po;
  if (edge_length) po.edge_length = *edge_length;
  if (o.neighbourhood) po.radius = *o.neighbourhood;
  if (o.tube) po.tube = *o.tube;
  if (o.blend_width) po.blend_width = *o.blend_width;
  po.function = o.function == "nearest" ? PointCloudFunction::nearest : PointCloudFunction::blended;
  po.threads = threads;
  if (o.use_normals) {
    if (set.normals.empty()) throw InputError("--use-normals: " + o.file + " has no normals");
    po.normals = set.normals;
  }
  pc.problem = make_point_cloud_problem(std::move(set.points), d, mm, po);
  pc.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return pc;
}

MeshReport mesh_with_sample_oracle(const Triangulation& t, const LoadedPointCloud& pc, const TraceOptions& trace,
                                   SampleOracleCounts& counts) {
  MeshReport report;
  const auto fill = [&](auto&& r) {
    report.cells = std::move(r.cells);
    report.topology = std::move(r.topology);
    report.status = r.status;
    report.message = r.message;
    report.function_evaluations = r.function_evaluations;
    report.oracle_calls = r.oracle_calls;
    report.seeds = pc.problem.seeds.size();
    report.trace_seconds = r.trace_seconds;
    report.cell_complex_seconds = r.cell_complex_seconds;
    report.topology_seconds = r.topology_seconds;
  };
  if (pc.oracle == "winding") {
    WindingMeshResult w = mesh_normal_winding(t, pc.problem, trace);
    counts.winding_odd_tetrahedra = w.odd_tetrahedra;
    counts.winding_uncertain_triangles = w.uncertain_triangles;
    w.trace_seconds += w.check_seconds;
    fill(w);
    if (w.odd_tetrahedra)
      report.warnings.push_back(std::to_string(w.odd_tetrahedra) +
                                " tetrahedra next to the trace see an odd number of hit triangles (where the normal "
                                "planes of their vertices are far apart: too few samples?): the mesh is not closed "
                                "there");
  } else if (pc.oracle == "local-pca") {
    LocalPcaResult lp = mesh_local_pca(t, pc.problem, trace);
    counts.local_pca_defects = lp.defects;
    fill(lp);
  } else {
    throw InputError("no oracle of its own named " + pc.oracle);
  }
  return report;
}

void print_point_cloud(std::ostream& os, const LoadedPointCloud& pc) {
  const PointCloudDiagnostics& g = pc.problem.diagnostics;
  os << "  samples            " << pc.read << " read from " << pc.file << " (" << pc.format << ")";
  if (pc.duplicates) os << ", " << pc.duplicates << " exact duplicates removed";
  os << "; " << g.components << (g.components == 1 ? " component" : " components") << " in the neighbour graph";
  if (g.isolated_samples) os << "; " << g.isolated_samples << " isolated samples (outliers?) not used as seeds";
  if (g.unseeded_components) os << ", " << g.unseeded_components << " components made only of them not meshed";
  os << "\n"
     << "  sample spacing     " << g.spacing << " (median nearest-neighbour distance); neighbourhood radius "
     << g.radius << " (" << static_cast<int>(g.mean_neighbours + 0.5) << " samples on average)\n"
     << "  edge length        " << g.edge_length << "; tube "
     << (g.tube_radius > 0 ? std::to_string(g.tube_radius) : "none") << "; function "
     << (g.blend_width > 0 ? "blended (width " + std::to_string(g.blend_width) + ")" : "nearest frame") << "\n"
     << "  frames             " << g.frustrated_edges << " of " << g.compared_edges
     << " compared neighbour-graph edges frustrated" << (g.used_given_normals ? " (normals from the file)" : "")
     << "; samples read and prepared in " << pc.seconds << " s\n";
  // (The winding oracle meshes what the warning is about: its own line says so.)
  if (g.frames_inconsistent && pc.oracle != "winding") os << "  warning: " << g.warning << "\n";
}

nlohmann::json point_cloud_json(const LoadedPointCloud& pc) {
  const PointCloudDiagnostics& g = pc.problem.diagnostics;
  nlohmann::json j = {{"file", pc.file},
                      {"format", pc.format},
                      {"samples_read", pc.read},
                      {"duplicates_removed", pc.duplicates},
                      {"samples", g.samples},
                      {"components", g.components},
                      {"isolated_samples", g.isolated_samples},
                      {"unseeded_components", g.unseeded_components},
                      {"spacing", g.spacing},
                      {"thickness", g.thickness},
                      {"neighbourhood_radius", g.radius},
                      {"mean_neighbours", g.mean_neighbours},
                      {"edge_length", g.edge_length},
                      {"tube_radius", g.tube_radius},
                      {"longest_gap", g.longest_gap},
                      {"function", g.blend_width > 0 ? "blended" : "nearest"},
                      {"blend_width", g.blend_width},
                      {"graph_edges", g.graph_edges},
                      {"compared_edges", g.compared_edges},
                      {"frustrated_edges", g.frustrated_edges},
                      {"frames_consistent", !g.frames_inconsistent},
                      {"setup_seconds", pc.seconds}};
  if (g.frames_inconsistent && pc.oracle != "winding") j["warning"] = g.warning;
  return j;
}

}  // namespace coxmesh::cli
