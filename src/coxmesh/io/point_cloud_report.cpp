// Point clouds between files, arrays and the one-call API; see point_cloud_report.h.
#include "coxmesh/io/point_cloud_report.h"

#include <cmath>

#include "coxmesh/errors.h"

namespace coxmesh {

PreparedPointCloud prepare_point_set(PointSet set, const std::string& file, PointCloudMeshOptions options,
                                     bool use_normals, const std::string& normals_option) {
  if (use_normals) {
    if (set.normals.empty())
      throw InputError(normals_option + ": " + (file.empty() ? std::string("the samples have") : file + " has") +
                       " no normals");
    options.preparation.normals = std::move(set.normals);
  }
  SampleSource source{file, set.format, set.size() + set.duplicates, set.duplicates};
  return prepare_samples(std::move(set.points), set.dimension, std::move(source), options);
}

nlohmann::json point_cloud_json(const PreparedPointCloud& cloud, const SampleOracleCounts& counts) {
  const PointCloudDiagnostics& g = cloud.problem.diagnostics;
  nlohmann::json j = {{"file", cloud.source.file.empty() ? nlohmann::json() : nlohmann::json(cloud.source.file)},
                      {"format", cloud.source.format},
                      {"samples_read", cloud.source.read},
                      {"duplicates_removed", cloud.source.duplicates},
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
                      {"apparent_dimension", g.apparent_dimension},
                      {"setup_seconds", cloud.seconds}};
  // Flat samples have no finite radius of curvature: null.
  j["curvature_radius"] = std::isfinite(g.curvature_radius) ? nlohmann::json(g.curvature_radius) : nlohmann::json();
  j["feature_size"] = g.feature_size > 0 ? nlohmann::json(g.feature_size) : nlohmann::json();  // (0: not measured)
  if (const std::vector<std::string> w = cloud.warnings(); !w.empty()) j["warnings"] = w;
  j["oracle"] = cloud.oracle_name();
  if (counts.local_pca_defects) j["local_pca_defects"] = *counts.local_pca_defects;
  if (counts.winding_odd_tetrahedra) {
    j["oracle_reason"] = cloud.oracle_reason();
    j["winding_odd_tetrahedra"] = *counts.winding_odd_tetrahedra;
    j["winding_uncertain_triangles"] = counts.winding_uncertain_triangles;
  }
  return j;
}

}  // namespace coxmesh
