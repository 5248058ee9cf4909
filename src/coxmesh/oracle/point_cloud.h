// Thesis Ch. 4 (manifolds given by point clouds): the functions F: R^d → R^k and the tube domain
// built from samples and their frames. Each is an ImplicitFunction: evaluated once per lattice
// vertex and cached by ImplicitOracle, so the exact tracer applies unchanged. See
// docs/point_clouds.md; the whole problem (defaults, seeds) is in tracing/point_cloud_problem.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/sample_frames.h"
#include "coxmesh/oracle/sample_tree.h"

namespace coxmesh {

/// The samples with their frames: what the point-cloud functions read (immutable, shared).
struct SampleModel {
  std::unique_ptr<SampleTree> tree;
  SampleFrames frames;
  /// Distinct for every model made in this process (a key for per-thread memos; an address could be reused).
  std::uint64_t serial = next_serial();

 private:
  static std::uint64_t next_serial();
};

/// F(x) = U_qᵀ(x − c_q), q the sample nearest to x, U_q and c_q its (synchronised) normal frame
/// and neighbourhood centroid: piecewise linear over the Voronoi cells of the samples.
FunctionPtr nearest_frame_function(std::shared_ptr<const SampleModel> model);

/// F(x) = Σ θ_i U_iᵀ(x − p_i) / Σ θ_i over the samples p_i near x, θ_i = exp(−|x − p_i|²/w²): the
/// implicit moving least squares of Shen et al. (2004) and Kolluri (2008), with k-frames in place
/// of normals. Smooth, and averages noise over about a ball of radius w. Uses the (at most 32)
/// nearest samples within 3w; with none there, the nearest frame. Frames are blended as they come
/// (no filtering by agreement: measured, dropping disagreeing frames breaks thin tubes).
FunctionPtr blended_frame_function(std::shared_ptr<const SampleModel> model, double width);

/// D(x) = |x − nearest sample| − radius: inside (D < 0) within `radius` of the samples.
FunctionPtr tube_domain(std::shared_ptr<const SampleModel> model, double radius);

/// Median nearest-neighbour distance of the samples (0 when all coincide), on `threads` workers.
double median_spacing(const SampleTree& tree, int threads = 1);

}  // namespace coxmesh
