// The thesis prototype's point-cloud oracle (thesis Ch. 4), kept for comparison with the
// per-vertex functions of point_cloud.h: every k-simplex τ gets its own local linear function
// F_τ(x) = Uᵀ(x − q) from a PCA around its barycentre. Since F_τ changes from simplex to simplex, a
// (k+1)-simplex can see an odd number of intersected facets: the output is not a manifold in
// general, and count_defects() measures how far from one it is.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/tracing/point_cloud_problem.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace coxmesh {

/// On a k-simplex τ: b its barycentre; the samples within `radius` of b (at least the m + 2 nearest);
/// U the k eigenvectors of smallest eigenvalue of their covariance (the normal space); q the sample
/// nearest to b. τ is hit iff the barycentric solution λ of [1 … 1; F_τ(v_0) … F_τ(v_k)]·λ = e_0
/// has all λ_j ≥ 0: a plain floating-point test, no symbolic perturbation. The domain (if any) is
/// evaluated at the intersection point Σ λ_j v_j. Not thread-safe (buffers): one per thread.
class LocalPcaOracle final : public IntersectionOracle {
 public:
  LocalPcaOracle(const Triangulation& triangulation, std::shared_ptr<const SampleModel> model, int m, double radius,
                 FunctionPtr domain = nullptr);
  int ambient_dimension() const override { return d_; }
  int codimension() const override { return k_; }
  bool has_domain() const override { return domain_ != nullptr; }
  Intersection intersect(const Simplex& tau, double* point) override;
  /// One local PCA per call.
  std::uint64_t function_evaluations() const override { return evaluations_; }

 private:
  const Triangulation& t_;
  std::shared_ptr<const SampleModel> model_;
  FunctionPtr domain_;
  int d_, k_, m_;
  double radius2_;
  std::uint64_t evaluations_ = 0;
  std::vector<double> vertices_;
  std::vector<std::uint32_t> index_;
  std::vector<double> distance2_;
};

/// The (k+1)-simplices, cofacets of the simplices of S, on which `oracle` hits an odd number of
/// facets. 0 for any per-vertex function with the exact rule (thesis §4.3): each cofacet then
/// holds a segment of M̂ with two ends or none. Asks the oracle about each facet once.
std::size_t count_defects(const TraceResult& traced, IntersectionOracle& oracle);

}  // namespace coxmesh
