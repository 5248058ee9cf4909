// Point clouds between files, arrays and the one-call API (mesh/mesh_point_cloud.h): samples from
// a PointSet, and the "point_cloud" object of the summary every front end shares (`coxmesh trace
// --points FILE --json`, the Python package's summary()).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "coxmesh/io/point_reader.h"
#include "coxmesh/mesh/mesh_point_cloud.h"

namespace coxmesh {

/// Prepares the samples of `set` (read from `file`; empty: given as an array) with
/// mesh_point_cloud.h's prepare_samples. use_normals: orient by the set's normals (InputError when
/// it has none, `normals_option` naming the option in the message).
PreparedPointCloud prepare_point_set(PointSet set, const std::string& file, PointCloudMeshOptions options,
                                     bool use_normals, const std::string& normals_option = "use_normals");

/// The samples, how they were prepared, the oracle used and why, and its counts: keys file (null
/// for an array), format, samples_read, duplicates_removed, samples, components, isolated_samples,
/// unseeded_components, spacing, thickness, neighbourhood_radius, mean_neighbours, edge_length,
/// tube_radius, longest_gap, function, blend_width, graph_edges, compared_edges, frustrated_edges,
/// frames_consistent, setup_seconds, warning (when the frames' warning applies), oracle,
/// local_pca_defects (local-pca), oracle_reason, winding_odd_tetrahedra and
/// winding_uncertain_triangles (winding).
nlohmann::json point_cloud_json(const PreparedPointCloud& cloud, const SampleOracleCounts& counts);

}  // namespace coxmesh
