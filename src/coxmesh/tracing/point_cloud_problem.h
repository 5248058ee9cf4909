// Thesis Ch. 4 (manifolds given by point clouds): an m-manifold known only through samples, meshed
// by the same tracer as an implicit one. The samples define a function F: R^d → R^k, one value per
// lattice vertex, and a tube domain around them; the exact tracer then makes the output a PL
// manifold whatever the samples, and only the correctness of its topology depends on their density
// and noise. This file chooses the defaults (scale from the sample spacing) and the seeds.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "coxmesh/oracle/point_cloud.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace coxmesh {

enum class PointCloudFunction { nearest, blended };

struct PointCloudOptions {
  /// Longest edge of the triangulation; 0: edge_factor × spacing, or × max(spacing, thickness)
  /// for noisy curves and surfaces (the median thickness over half a spacing).
  double edge_length = 0;
  /// 0: for curves 2.5, or 2 when the samples are noisy; for surfaces the same, but up to 6 where
  /// a fifth of the radius of curvature is longer than 2.5 spacings; 2(m − 1) above (the cell
  /// complex of an m-manifold grows like (size/h)^m with a constant growing fast with m: S³ from
  /// 50,000 samples takes 0.3 GB at 4 spacings, 1.9 GB at 2, with the same topology).
  double edge_factor = 0;
  double radius = 0;  ///< PCA neighbourhood radius; 0: radius_factor × spacing
  double radius_factor = 5.0;
  int min_neighbours = 0;  ///< fewer samples within the radius: use this many nearest (0: 4(m + 1))
  double tube = 3.0;       ///< tube radius in edge lengths, at least 3/4 of the largest gap (the domain); 0: no tube
  PointCloudFunction function = PointCloudFunction::blended;
  /// w of the blended function; 0: blend_factor × max(spacing, thickness), so that it averages
  /// over the noise when the samples are noisier than they are dense, times thickness / spacing
  /// within [1, 1.5].
  double blend_width = 0;
  double blend_factor = 2.0;
  int seeds_per_component = 8;
  std::vector<double> normals;  ///< optional n × d normals given with the samples (codimension 1): fix the signs
  /// Worker threads for the preparation (spacing, PCA, edge checks; 0: all hardware threads). The
  /// problem is the same for any number.
  int threads = 1;
};

/// What the construction found out about the samples (printed by the CLI).
struct PointCloudDiagnostics {
  std::size_t samples = 0;
  int ambient_dimension = 0, manifold_dimension = 0;
  double spacing = 0;    ///< median distance from a sample to its nearest other sample
  double thickness = 0;  ///< median RMS distance of a neighbourhood from its tangent plane: noise (and curvature)
  /// r²/(7 × thickness), r the radius: the radius of curvature of clean samples of a surface
  /// (infinite when they are flat; too long when noise dominates the thickness)
  double curvature_radius = 0;
  /// Where the surface rule would give more than 2.5 spacings: the radius of the smallest empty
  /// ball tangent to the samples along their normals (a low quantile; 0 when not measured). The
  /// edge stays within half of it (other sheets nearby, folds).
  double feature_size = 0;
  double radius = 0, edge_length = 0, tube_radius = 0, blend_width = 0;
  double longest_gap = 0;        ///< longest edge of a Euclidean minimum spanning forest of the non-isolated samples
  double mean_neighbours = 0;    ///< samples per PCA neighbourhood
  std::uint32_t components = 0;  ///< connected components of the neighbour graph
  std::size_t isolated_samples = 0;     ///< samples with at most m others within the radius: never seeds
  std::size_t unseeded_components = 0;  ///< components made only of isolated samples: not traced
  std::size_t graph_edges = 0, compared_edges = 0, frustrated_edges = 0;
  bool used_given_normals = false;
  /// Frustrated edges are significant (more than 8 and more than √compared_edges): the normal
  /// bundle looks non-orientable (e.g. RP² ⊂ R⁴), and no single-valued function can have the
  /// sampled manifold as its zero set; or the normals are noise. Either way the traced topology
  /// cannot be trusted. `warning` then says so in one line (empty otherwise).
  bool frames_inconsistent = false;
  std::string warning;
  /// The median over the samples of the directions their neighbourhood spreads in
  /// (SampleFrames::spread_dimension). Below m the samples are of a lower-dimensional manifold (a
  /// curve given as a surface: what is traced around it is a thin m-manifold whose topology is not
  /// the samples'); `dimension_warning` then says so in one line (empty otherwise).
  int apparent_dimension = 0;
  std::string dimension_warning;
};

/// Everything the tracer needs: F, the domain, seeds (samples spread over every component of the
/// neighbour graph), a box around the samples (where they and their tube lie: the domain bounds the
/// walk) and the edge length to triangulate with.
struct PointCloudProblem {
  std::shared_ptr<const SampleModel> model;
  FunctionPtr function, domain;
  std::vector<std::vector<double>> seeds;
  Box box;
  double edge_length = 0;
  PointCloudDiagnostics diagnostics;

  /// The centre of the box: where the front ends put the lattice's origin unless told otherwise,
  /// so that samples far from 0 (a scan in geographic coordinates) keep small lattice coordinates.
  Eigen::VectorXd centre() const {
    Eigen::VectorXd c(static_cast<Eigen::Index>(box.lo.size()));
    for (Eigen::Index i = 0; i < c.size(); ++i) c[i] = 0.5 * (box.lo[i] + box.hi[i]);
    return c;
  }
};

/// Builds the point-cloud problem for samples of an m-manifold in R^d (n × d row-major, distinct
/// points, n ≥ m + 2). Throws InputError on bad sizes or parameters.
///
///   PointCloudProblem p = make_point_cloud_problem(points, 3, 2);
///   Triangulation T = Triangulation::coxeter(3).with_longest_edge(p.edge_length).with_offset(p.centre());
///   ImplicitOracle oracle(T, p.function, p.domain);
///   TraceResult r = trace_manifold(T, oracle, p.seeds, {.skip_unusable_seeds = true});
PointCloudProblem make_point_cloud_problem(std::vector<double> samples, int d, int m,
                                           const PointCloudOptions& options = {});

}  // namespace coxmesh
