// The point-cloud front end of `coxmesh trace`; see points.h and docs/point_clouds.md.
#include "points.h"

#include <chrono>
#include <cmath>

#include "coxmesh/io/point_cloud_report.h"

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

PreparedPointCloud load_point_cloud(const PointCloudCliOptions& o, std::optional<int> m, std::optional<int> dim,
                                    std::optional<double> edge_length, int threads, bool other_bounds) {
  const auto t0 = std::chrono::steady_clock::now();
  PointReadOptions ro;
  ro.dimension = dim.value_or(0);
  PointCloudMeshOptions po;
  po.m = m;
  po.oracle = sample_oracle_named(o.oracle);
  po.other_bounds = other_bounds;
  PointCloudOptions& prep = po.preparation;
  if (edge_length) prep.edge_length = *edge_length;
  if (o.neighbourhood) prep.radius = *o.neighbourhood;
  if (o.tube) prep.tube = *o.tube;
  if (o.blend_width) prep.blend_width = *o.blend_width;
  prep.function = o.function == "nearest" ? PointCloudFunction::nearest : PointCloudFunction::blended;
  prep.threads = threads;
  PreparedPointCloud pc = prepare_point_set(read_points(o.file, ro), o.file, po, o.use_normals, "--use-normals");
  pc.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();  // reading included
  return pc;
}

void print_point_cloud(std::ostream& os, const PreparedPointCloud& pc) {
  const PointCloudDiagnostics& g = pc.problem.diagnostics;
  const SampleSource& src = pc.source;
  os << "  samples            " << src.read << " read from " << src.file << " (" << src.format << ")";
  if (src.duplicates) os << ", " << src.duplicates << " exact duplicates removed";
  os << "; " << g.components << (g.components == 1 ? " component" : " components") << " in the neighbour graph";
  if (g.isolated_samples) os << "; " << g.isolated_samples << " isolated samples (outliers?) not used as seeds";
  if (g.unseeded_components) os << ", " << g.unseeded_components << " components made only of them not meshed";
  os << "\n"
     << "  sample spacing     " << g.spacing << " (median nearest-neighbour distance); neighbourhood radius "
     << g.radius << " (" << static_cast<int>(g.mean_neighbours + 0.5) << " samples on average)\n"
     << "  edge length        " << g.edge_length << " (" << std::round(10 * g.edge_length / g.spacing) / 10
     << " spacings); tube " << (g.tube_radius > 0 ? std::to_string(g.tube_radius) : "none") << "; function "
     << (g.blend_width > 0 ? "blended (width " + std::to_string(g.blend_width) + ")" : "nearest frame") << "\n"
     << "  frames             " << g.frustrated_edges << " of " << g.compared_edges
     << " compared neighbour-graph edges frustrated" << (g.used_given_normals ? " (normals from the file)" : "")
     << "; samples read and prepared in " << pc.seconds << " s\n";
  for (const std::string& w : pc.warnings()) os << "  warning: " << w << "\n";
}

}  // namespace coxmesh::cli
