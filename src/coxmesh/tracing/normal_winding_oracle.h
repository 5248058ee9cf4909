// An oracle for point clouds of surfaces in R⁴ whose normal bundle is not orientable (RP², the
// Klein bottle): no function R⁴ → R² has them as a regular zero set, so the per-vertex functions
// of point_cloud.h cannot mesh them. This one still stores data once per lattice vertex, but data
// with no orientation: a vector n(v) (the blended normal offset from the samples) and the normal
// plane N(v) there. A triangle τ of the triangulation is hit when n turns once around 0 along τ's
// boundary: the winding number, summed from one angle per edge (n's turn along the edge, measured
// after projecting one end's offset onto the other's plane). Edge terms cancel on the boundary of
// every tetrahedron, so each tetrahedron has an even number of hit facets whatever the data, as
// long as its facets are certain (uncertain_triangles): see docs/point_clouds.md. No function can
// do this, and neither can a sign or frame chosen per simplex (a flat bundle: normal Euler number
// 0, while RP² ⊂ R⁴ has ±2, Massey 1969).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/oracle/point_cloud.h"
#include "coxmesh/oracle/shared_vertex_values.h"
#include "coxmesh/triangulation/triangulation.h"

namespace coxmesh {

/// The winding oracle of codimension 2 (thesis Ch. 4: an oracle is anything that decides whether M
/// meets a k-simplex). n(x) = Σ θ_i P_i(x − p_i) / Σ θ_i with θ_i = exp(−|x − p_i|²/w²) and P_i the
/// projector onto sample i's normal plane (the nearest sample's offset P_q(x − c_q) when w = 0);
/// N(x) = the normal plane of the sample nearest to x. Frames only express these in coordinates:
/// nothing depends on their choice or orientation. Not thread-safe (buffers): one per thread; with
/// a SharedVertexValues, every lattice vertex is evaluated once in all.
class NormalWindingOracle final : public IntersectionOracle {
 public:
  /// Throws InputError unless the samples have codimension 2.
  NormalWindingOracle(const Triangulation& triangulation, std::shared_ptr<const SampleModel> model, double width,
                      FunctionPtr domain = nullptr, std::shared_ptr<SharedVertexValues> shared = nullptr);
  /// A table of vertex data the oracles of one problem can share.
  static std::shared_ptr<SharedVertexValues> make_shared_values(int d, bool with_domain);

  int ambient_dimension() const override { return d_; }
  int codimension() const override { return 2; }
  bool has_domain() const override { return domain_ != nullptr; }
  Intersection intersect(const Simplex& tau, double* point) override;
  std::uint64_t function_evaluations() const override { return evaluations_; }
  /// Triangles decided where the planes of their vertices are far apart (more than about 60°), their
  /// orientations do not agree around the triangle, or the edge turns do not close up to within a
  /// quarter turn of a whole one. Every tetrahedron whose four facets are none of these has an even
  /// number of hit facets; 0 where the samples resolve the surface.
  std::uint64_t uncertain_triangles() const { return uncertain_; }
  /// Also counts them in `total` (shared by the oracles of several threads; null: not).
  void count_uncertain_in(std::atomic<std::uint64_t>* total) { total_uncertain_ = total; }

 private:
  void evaluate(const std::int32_t* v, double* out);
  void vertex_data(const std::int32_t* v, double* out);

  Triangulation t_;
  std::shared_ptr<const SampleModel> model_;
  FunctionPtr domain_;
  std::shared_ptr<SharedVertexValues> shared_;
  int d_, stride_;
  double inv_w2_, reach2_;
  void count_uncertain() {
    ++uncertain_;
    if (total_uncertain_) total_uncertain_->fetch_add(1, std::memory_order_relaxed);
  }

  std::uint64_t evaluations_ = 0, uncertain_ = 0;
  std::atomic<std::uint64_t>* total_uncertain_ = nullptr;
};

}  // namespace coxmesh
