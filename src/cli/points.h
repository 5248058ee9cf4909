// `coxmesh trace --points FILE`: the point-cloud front end (thesis Ch. 4). Reads the samples, builds
// the problem (function, tube domain, seeds, edge length) and reports what it chose and found, so
// that cmd_trace.cpp only has to plug the function into its usual pipeline.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "coxmesh/io/point_reader.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/tracing/point_cloud_problem.h"

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

struct LoadedPointCloud {
  std::string file;
  std::size_t read = 0, duplicates = 0;
  std::string format;
  double seconds = 0;  ///< reading and preparing (tree, frames, seeds)
  PointCloudProblem problem;
  std::string oracle;          ///< the oracle used: vertex, winding or local-pca (--oracle auto resolved)
  bool oracle_chosen = false;  ///< by --oracle auto

  /// Why the oracle is the one used, for the summary.
  std::string oracle_reason() const {
    return oracle_chosen ? "chosen because the normal frames look non-orientable" : "requested";
  }
};

/// Reads and prepares the samples. m: the manifold dimension (default d − 1); dim: the expected
/// d (optional); edge_length: the user's --edge-length (optional); threads: --threads (0: all
/// hardware threads; the result is the same for any number). Throws InputError.
LoadedPointCloud load_point_cloud(const PointCloudCliOptions& o, std::optional<int> m, std::optional<int> dim,
                                  std::optional<double> edge_length, int threads = 1);

/// What --oracle local-pca and winding report beyond a MeshReport (unset: not that oracle).
struct SampleOracleCounts {
  std::optional<std::size_t> local_pca_defects;       ///< LocalPcaResult::defects
  std::optional<std::size_t> winding_odd_tetrahedra;  ///< WindingMeshResult::odd_tetrahedra
  std::uint64_t winding_uncertain_triangles = 0;
};

/// Meshes the samples with their oracle "local-pca" or "winding" (their own pipelines, not
/// mesh_manifold's) on t: the report without automatic seeds and with a warning when the winding
/// oracle leaves odd tetrahedra; their counts go to `counts`. Throws InputError.
MeshReport mesh_with_sample_oracle(const Triangulation& t, const LoadedPointCloud& pc, const TraceOptions& trace,
                                   SampleOracleCounts& counts);

/// The human lines of the trace summary (indented by two spaces), the warning included.
void print_point_cloud(std::ostream& os, const LoadedPointCloud& pc);
/// The "point_cloud" object of the JSON summary.
nlohmann::json point_cloud_json(const LoadedPointCloud& pc);

}  // namespace coxmesh::cli
