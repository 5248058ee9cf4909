// `coxmesh trace --points FILE`: the options of the point-cloud front end (thesis Ch. 4), reading
// the file into the library's prepared samples (mesh_point_cloud.h), and the human lines of what
// it chose and found.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "coxmesh/mesh/mesh_point_cloud.h"

namespace coxmesh::cli {

struct PointCloudCliOptions {
  std::string file;
  std::string function = "blended";
  // auto (winding where the frames look non-orientable in codimension 2, else vertex), vertex (a
  // function per lattice vertex), winding (normal_winding_oracle.h) or local-pca (per simplex)
  std::string oracle = "auto";
  std::optional<double> neighbourhood, tube, blend_width;
  bool use_normals = false;
  CLI::Option* option = nullptr;  // --points itself (for excludes)

  void add_to(CLI::App& cmd);
};

/// Reads and prepares the samples (mesh_point_cloud.h; the oracle resolved). m: the manifold
/// dimension (default d − 1); dim: the expected d (optional); edge_length: the user's
/// --edge-length (optional); threads: --threads (0: all hardware threads; the result is the same
/// for any number); other_bounds: domains, a box or --refine given. Throws InputError.
PreparedPointCloud load_point_cloud(const PointCloudCliOptions& o, std::optional<int> m, std::optional<int> dim,
                                    std::optional<double> edge_length, int threads, bool other_bounds);

/// The human lines of the trace summary (indented by two spaces), the warning included.
void print_point_cloud(std::ostream& os, const PreparedPointCloud& pc);

}  // namespace coxmesh::cli
