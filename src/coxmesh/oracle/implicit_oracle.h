// Thesis §4.3: the intersection oracle of an implicit manifold F̂ = 0 (optionally within D̂ < 0), with
// F and D evaluated exactly once per lattice vertex.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/oracle/shared_vertex_values.h"
#include "coxmesh/oracle/small_lu.h"
#include "coxmesh/triangulation/triangulation.h"

namespace coxmesh {

/// The oracle of M = F^{-1}(0) ∩ {D < 0} on a triangulation T. Keeps a cache lattice vertex →
/// (F, D) values: every lattice vertex is evaluated once. Not thread-safe: one per thread. The
/// oracles of several threads evaluate each vertex once in all when they share a
/// SharedVertexValues (then F and D are only called under its locks, but from any thread).
///
///   ImplicitOracle oracle(T, sphere(2, 3, 1.0));
///   double p[3];  if (oracle.intersect(tau, p).hit) ...
///
///   auto shared = ImplicitOracle::make_shared_values(T, f, domain);   // for a worker pool
///   auto worker_oracle = std::make_unique<ImplicitOracle>(T, f, domain, shared);
class ImplicitOracle final : public IntersectionOracle {
 public:
  /// Throws InputError when F, D and T disagree on d, or F has more equations than d.
  ImplicitOracle(const Triangulation& triangulation, FunctionPtr f, FunctionPtr domain = nullptr,
                 std::shared_ptr<SharedVertexValues> shared = nullptr);
  /// A table of vertex values the oracles of (T, f, domain) can share.
  static std::shared_ptr<SharedVertexValues> make_shared_values(const Triangulation& t, const FunctionPtr& f,
                                                                const FunctionPtr& domain = nullptr) {
    return std::make_shared<SharedVertexValues>(t.dimension(), f->codimension() + (domain ? 1 : 0));
  }

  int ambient_dimension() const override { return d_; }
  int codimension() const override { return k_; }
  bool has_domain() const override { return domain_ != nullptr; }
  bool two_transverse_facets() const override { return true; }  // (exact signs: thesis §4.2)
  Intersection intersect(const Simplex& tau, double* point) override;
  std::uint64_t function_evaluations() const override { return evaluations_; }
  bool pivot_enter(const Simplex& tau) override;
  int pivot_exit(const std::int32_t* v) override;
  void prefetch_pivot(const std::int32_t* v) override;
  /// When F or D prefers batches (and without SharedVertexValues): evaluates, in one
  /// evaluate_batch call each, every lattice vertex of the level's cofacets not cached yet. The
  /// walk evaluates each of them anyway, so F is still called once per vertex.
  void prefetch(std::span<const std::uint32_t> packed_simplices) override;

  /// How many times pivot_enter(τ) reused what intersect(τ) computed of M(τ) (see keep_factors_).
  std::uint64_t factorizations_reused() const { return factorizations_reused_; }

  /// Switches the private per-vertex cache off (every query re-evaluates F): the benchmark's ablation.
  void set_cache_enabled(bool on) { cache_enabled_ = on; }
  std::size_t cache_bytes() const {
    return cache_.bytes() + values_.capacity() * sizeof(double) + front_keys_.capacity() * sizeof(std::int32_t) +
           front_values_.capacity() * sizeof(double) + front_used_.capacity() +
           kept_keys_.capacity() * sizeof(std::uint32_t) + kept_factors_.capacity() * sizeof(double) +
           kept_rows_.capacity() * sizeof(int);
  }

 private:
  // The hot paths with d fixed at compile time for the common d (D = d), else D = 0 (d_ read at
  // run time): the loops over a vertex's coordinates unroll (util/fixed_dimension.h).
  template <int D>
  const double* values_at(const std::int32_t* v);  // F (and D) at a lattice vertex
  template <int D>
  void prefetch_pivot_d(const std::int32_t* v);
  template <int N>
  int pivot_exit_n(const double* val);
  int pivot_exit_tie(std::uint32_t tied, const double* w);
  void evaluate(const std::int32_t* v, double* out);
  void system_matrix(const Simplex& tau, double* m, double* domain_values);
  std::string not_finite_message(const std::int32_t* v, int i, double value) const;

  Triangulation triangulation_;
  FunctionPtr f_, domain_;
  int d_, k_, stride_;
  std::shared_ptr<SharedVertexValues> shared_;
  static constexpr int kFrontBits = 14;
  static constexpr std::size_t kFrontSlots = std::size_t{1} << kFrontBits;  // recent vertices, direct-mapped
  template <int D>
  std::size_t front_slot(const std::int32_t* v) const;
  template <int D>
  bool front_holds(std::size_t slot, const std::int32_t* v) const;  // v's values are in its slot
  std::vector<std::int32_t> front_keys_;
  std::vector<double> front_values_;
  std::vector<std::uint8_t> front_used_;
  PackedKeyIndex cache_;       // without shared_: every vertex this oracle met
  HugeVector<double> values_;  // stride_ per cached vertex: F values, then D
  std::vector<double> scratch_;
  bool batches_ = false;                             // prefetch evaluates levels in batches
  std::vector<double> batch_points_, batch_values_;  // prefetch's vertices (Cartesian) and F, D there
  // intersect(τ) keeps M(τ)'s factors (its common case; k = 1: F at τ's ends) for pivot_enter(τ),
  // which would look up F at τ's vertices and factor M(τ) again: the sequential walk enters the simplices in the order
  // intersect found them inside the domain (S's order), so a queue suffices. A simplex entered out of that order
  // (another walk) switches the queue off: only a factorization of the same τ is ever reused.
  void keep_factors(const Simplex& tau, bool factored, const double* lambda);
  bool take_kept_factors(const Simplex& tau);
  // (The walk's front of new simplices: 16–32 k simplices for SO(3) at edge 1.1; at most 2¹⁷ kept, ≤ 70 MB at k = 6.)
  static constexpr std::size_t kMaxKeptFactors = std::size_t{1} << 17;
  SmallLu intersect_lu_;
  bool keep_factors_ = true;
  std::uint64_t factorizations_reused_ = 0;
  std::size_t kept_head_ = 0, kept_tail_ = 0, kept_capacity_ = 0;   // entries [head, tail) at index % capacity
  std::vector<std::uint32_t> kept_keys_;                            // τ packed, per entry
  std::vector<double> kept_factors_;                                // n·n factors, then λ (n values), per entry
  std::vector<int> kept_rows_;                                      // P's n rows per entry; −1 first: none kept
  SmallLu pivot_lu_;                                                // M(τ) of the last pivot_enter
  std::array<double, SmallLu::kMaxN> pivot_lambda_;                 // its barycentric solution (k = 1: F at τ's ends)
  std::array<double, SmallLu::kMaxN * SmallLu::kMaxN> pivot_rows_;  // rows of M(τ)⁻¹, for ties
  std::uint32_t pivot_rows_ready_ = 0;                              // which rows are computed
  std::uint64_t evaluations_ = 0;
  bool cache_enabled_ = true;
};

}  // namespace coxmesh
