// Normal frames of a point cloud (thesis Ch. 4: manifolds given by samples): at each sample the k
// normal directions of its neighbourhood (local PCA), made consistent along the neighbour graph so
// that a single-valued function R^d → R^k can be built from them, and the edges where that fails.
#pragma once

#include <cstdint>
#include <vector>

#include "coxmesh/oracle/sample_tree.h"

namespace coxmesh {

struct FrameOptions {
  double radius = 0;          ///< neighbourhood radius (> 0)
  int min_neighbours = 8;     ///< fewer samples within the radius: the nearest min_neighbours instead
  int max_neighbours = 64;    ///< at most this many nearest samples within the radius go into the PCA
  int graph_neighbours = 12;  ///< the nearest this many samples (within the radius or not) are joined in the graph
  int threads = 1;  ///< worker threads for the PCA and the edge checks (the result is the same for any number)
  /// Normals given with the samples (n × d, codimension 1 only; empty if none): they fix the sign
  /// of each estimated normal instead of the propagation along the tree.
  std::vector<double> reference_normals;
};

/// A direction counts in spread_dimension when the neighbourhood's variance along it is at least
/// this fraction of the largest. Samples of a disc of radius r give about 1 for its two directions;
/// of a curve, (κr)²/15 for its second (curvature κ; the torus of the tests, κr = 0.45: 0.014),
/// plus 3σ²/r² from noise σ (a quarter of the radius, 1.2 spacings, gives 0.19).
inline constexpr double kSpreadFraction = 0.05;

/// The frames and the diagnostics of their synchronisation.
struct SampleFrames {
  int d = 0, k = 0;
  std::vector<double> centers;    ///< n × d: centroid of each sample's neighbourhood
  std::vector<double> normals;    ///< n × k × d: the k orthonormal normals of sample i, one row each
  std::vector<double> flatness;   ///< n: (sum of the k normal eigenvalues) / (trace) of the local covariance
  std::vector<double> thickness;  ///< n: RMS distance of the neighbourhood from its tangent plane (noise and curvature)
  /// n: the directions the neighbourhood spreads in (its covariance's eigenvalues of at least
  /// kSpreadFraction × the largest): about m on an m-manifold, fewer where the samples are of a
  /// lower-dimensional one (a curve given as a surface).
  std::vector<std::uint8_t> spread_dimension;
  std::vector<std::uint16_t> within_radius;  ///< n: other samples within the radius (at most max_neighbours)
  std::vector<std::uint32_t> component;  ///< n: connected component of the neighbour graph (0, 1, … by first sample)
  std::uint32_t components = 0;
  std::size_t graph_edges = 0;       ///< edges of the (symmetrised) neighbour graph
  std::size_t compared_edges = 0;    ///< edges whose normal spaces are within 45°: their frames can be compared
  std::size_t frustrated_edges = 0;  ///< compared edges whose frames disagree: det(U_iᵀU_j) < 0 or a rotation > 60°
  double mean_neighbours = 0;        ///< samples per PCA neighbourhood, on average
  double longest_gap = 0;  ///< longest edge of the Euclidean minimum spanning forest of the non-isolated samples
  const double* frame(std::size_t i) const { return normals.data() + i * k * d; }
};

/// Local PCA at every sample (the k eigenvectors of smallest eigenvalue of the neighbourhood's
/// covariance span the normal space), then orientation: the frames are carried along a minimum
/// spanning tree of the neighbour graph with edge weights 1 − |det(U_iᵀU_j)| (for k = 1 this is
/// the normal propagation of Hoppe et al. 1992), each child's frame turned onto its parent's by the
/// orthogonal factor of U_childᵀU_parent (orthogonal Procrustes): U_child ← U_child·polar(U_childᵀU_parent).
/// Then every graph edge is checked; frustrated edges measure how far the normal bundle is from
/// admitting a consistent frame (0 for the sphere, torus, flat torus, S³; a few per cent for a
/// non-orientable surface such as RP² ⊂ R⁴). `m` is the manifold dimension (1 ≤ m < d).
SampleFrames estimate_frames(const SampleTree& tree, int m, const FrameOptions& options);

}  // namespace coxmesh
