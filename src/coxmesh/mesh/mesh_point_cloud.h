// Point clouds in one call (thesis Ch. 4): samples of an m-manifold, prepared once (defaults from
// their spacing, frames, tube, seeds), the oracle chosen, then meshed by the pipeline of that
// oracle: the per-vertex function through mesh_manifold, the winding oracle (mesh_winding.h) or the
// thesis prototype's local PCA. The command line and the Python package only read files and print.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/tracing/point_cloud_problem.h"

namespace coxmesh {

/// automatic: the winding oracle where the frames look non-orientable in codimension 2 (and only
/// the tube bounds the walk), the per-vertex function everywhere else.
enum class SampleOracle { automatic, vertex, winding, local_pca };

/// "auto", "vertex", "winding" or "local-pca"; throws InputError for any other name.
SampleOracle sample_oracle_named(const std::string& name);
std::string sample_oracle_name(SampleOracle oracle);

/// Where the samples came from, for the report.
struct SampleSource {
  std::string file;            ///< empty: given as an array
  std::string format;          ///< the file's format, or "array"
  std::size_t read = 0;        ///< samples before removing duplicates
  std::size_t duplicates = 0;  ///< exact duplicates removed
};

struct PointCloudMeshOptions {
  std::optional<int> m;  ///< the manifold dimension; default d − 1
  SampleOracle oracle = SampleOracle::automatic;
  /// Edge length, neighbourhood radius, tube, blend width, function, normals (given: they fix the
  /// signs), threads of the preparation.
  PointCloudOptions preparation;
  /// Something besides the tube bounds the walk (domains, a box) or moves the vertices (refine):
  /// only the per-vertex function allows it, so automatic keeps to it.
  bool other_bounds = false;
};

/// The samples ready to mesh, with the oracle resolved.
struct PreparedPointCloud {
  SampleSource source;
  PointCloudProblem problem;
  SampleOracle oracle = SampleOracle::vertex;  ///< never automatic
  bool oracle_chosen = false;                  ///< by SampleOracle::automatic
  double seconds = 0;                          ///< preparing (tree, frames, seeds)

  std::string oracle_name() const { return sample_oracle_name(oracle); }
  /// Why the oracle is the one used.
  std::string oracle_reason() const {
    return oracle_chosen ? "chosen because the normal frames look non-orientable" : "requested";
  }
  /// What the samples' diagnostics say against the result, a line each: the frames' warning (not
  /// with the winding oracle, which meshes what it is about) and the dimension's.
  std::vector<std::string> warnings() const {
    const PointCloudDiagnostics& g = problem.diagnostics;
    std::vector<std::string> out;
    if (g.frames_inconsistent && oracle != SampleOracle::winding) out.push_back(g.warning);
    if (!g.dimension_warning.empty()) out.push_back(g.dimension_warning);
    return out;
  }
};

/// Prepares n × d samples (row-major, distinct; normals in options.preparation) and resolves the
/// oracle. Throws InputError (sizes, NaN, m, parameters).
PreparedPointCloud prepare_samples(std::vector<double> samples, int d, SampleSource source,
                                   const PointCloudMeshOptions& options);

/// What the winding and local-PCA oracles report beyond a MeshReport (unset: not that oracle).
struct SampleOracleCounts {
  std::optional<std::size_t> local_pca_defects;       ///< LocalPcaResult::defects
  std::optional<std::size_t> winding_odd_tetrahedra;  ///< WindingMeshResult::odd_tetrahedra
  std::uint64_t winding_uncertain_triangles = 0;
};

struct PointCloudMeshReport {
  MeshReport mesh;  ///< automatic_seeds: the samples used as seeds
  SampleOracleCounts counts;
};

/// The caller's domains, made once per worker (they need not be thread-safe) from the tube: the
/// domain that bounds the walk (the tube, or what replaces it) and further faces, each its own
/// (two or more in all make a manifold with corners, see mesh_manifold.h). Only `domain` and
/// `domains` of the result are used.
using DomainMaker = std::function<ManifoldFunctions(const FunctionPtr& tube)>;

/// Meshes the prepared samples on t with their oracle. `options`: limits, threads, progress and, for
/// the per-vertex function only, extra seeds, a box (empty: the samples' box, widened by the
/// tube), refinement; the samples are added as seeds. `while_topology` as for mesh_manifold (after
/// the whole run for the winding and local-PCA oracles). Throws InputError.
PointCloudMeshReport mesh_point_cloud(const Triangulation& t, const PreparedPointCloud& cloud, MeshOptions options,
                                      const DomainMaker& make_domains = {}, const WhileTopology& while_topology = {});

}  // namespace coxmesh
