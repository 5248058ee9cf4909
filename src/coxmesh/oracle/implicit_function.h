// Thesis §4.3 (manifolds given as zero sets). Implicit functions F: R^d → R^k whose zero
// set is the manifold, domain functions D: R^d → R (inside where D < 0), and the built-in catalogue.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace coxmesh {

/// F: R^d → R^k. evaluate() must be callable concurrently on a const object (built-ins are).
class ImplicitFunction {
 public:
  virtual ~ImplicitFunction() = default;
  virtual int ambient_dimension() const = 0;  ///< d
  virtual int codimension() const = 0;        ///< k: number of equations
  /// value[0..k) = F(x[0..d)).
  virtual void evaluate(const double* x, double* value) const = 0;
  /// n points, row after row (n × d), into n × k values. Override for vectorised evaluation.
  virtual void evaluate_batch(const double* xs, int n, double* values) const {
    for (int i = 0; i < n; ++i) evaluate(xs + i * ambient_dimension(), values + i * codimension());
  }
  /// A point on the zero set when one is known in closed form (empty otherwise).
  virtual std::vector<double> seed() const { return {}; }
  /// True when evaluate_batch on many points costs much less than as many evaluate() calls (a
  /// function written in an interpreted language): ImplicitOracle then evaluates the vertices of a
  /// whole breadth-first level in one call (still once per vertex). False for the built-ins.
  virtual bool prefers_batches() const { return false; }
};

using FunctionPtr = std::shared_ptr<const ImplicitFunction>;

/// Throws InputError unless f is given and maps R^d to R^k with 1 ≤ k ≤ d: a manifold an oracle of
/// a triangulation of R^d can trace.
void check_manifold_function(const FunctionPtr& f, int d);

/// A callable as an implicit function: `fn(const double* x, double* value)`.
template <class Fn>
class CallableFunction final : public ImplicitFunction {
 public:
  CallableFunction(int d, int k, Fn fn, std::vector<double> seed = {})
      : d_(d), k_(k), fn_(std::move(fn)), seed_(std::move(seed)) {}
  int ambient_dimension() const override { return d_; }
  int codimension() const override { return k_; }
  void evaluate(const double* x, double* value) const override { fn_(x, value); }
  std::vector<double> seed() const override { return seed_; }

 private:
  int d_, k_;
  Fn fn_;
  std::vector<double> seed_;
};

/// Wraps a callable `fn(const double* x, double* value)`; throws InputError unless 1 ≤ k ≤ d.
template <class Fn>
FunctionPtr make_function(int d, int k, Fn fn, std::vector<double> seed = {});

// ---- Built-in manifolds (each with a seed on it) ----------------------------------------------
/// S^m of radius r centred at c in R^d (d ≥ m+1): (|x_{0..m} − c|² − r², x_{m+1} − c_{m+1}, …).
FunctionPtr sphere(int m, int d, double radius, std::vector<double> center = {});
/// Torus in R³ around the z axis: (√(x²+y²) − R)² + z² − r², major radius R > minor radius r.
FunctionPtr torus(double major_radius, double minor_radius);
/// Hyperplane arrangement {Nᵀ(x − p) = 0}: N is d × k with independent columns (normalised).
FunctionPtr affine_plane(const Eigen::MatrixXd& normals, const Eigen::VectorXd& point);
/// Chair surface (x²+y²+z² − a·s²)² − b((z−s)² − 2x²)((z+s)² − 2y²), defaults a=0.8, b=0.4, s=1.
FunctionPtr chair(double a = 0.8, double b = 0.4, double s = 1.0);
/// Iron surface −(x⁶+y⁶+z⁶)/300 + xy²z/2.1 + y² + (z−2)⁴ − 1.
FunctionPtr iron();
/// Lemniscate of revolution (x²+y²+z²)² − 2a²(x² − y² − z²).
FunctionPtr lemniscate_of_revolution(double a = 1.0);
/// Whitney umbrella x² − y²z.
FunctionPtr whitney_umbrella();
/// Moment curve t ↦ (t, t², …, t^d) in R^d: x_i − x_0·x_{i−1} for i = 1..d−1. Unbounded: trace it
/// inside a domain.
FunctionPtr moment_curve(int d);
/// SO(3) ⊂ R⁹ (row-major 3×3 matrices M with MᵀM = I, det M = 1): the 6 equations of MᵀM = I.
FunctionPtr rotation_group_so3();

// ---- Combinators -------------------------------------------------------------------------------
/// (f(x_0..x_{d1−1}), g(x_{d1}..)): the product manifold M_f × M_g in R^{d1+d2}.
FunctionPtr product(FunctionPtr f, FunctionPtr g);
/// f extended to R^d by the extra equations x_i = 0 (i ≥ d_f): M_f embedded in R^d.
FunctionPtr embed(FunctionPtr f, int d);
/// f(A^{-1}(x)): the image A·M_f. A is factorised once (inverse kept), not per evaluation.
FunctionPtr linear_map(FunctionPtr f, const Eigen::MatrixXd& a);
/// f(x − b): M_f translated by b.
FunctionPtr translate(FunctionPtr f, const Eigen::VectorXd& b);
/// −f: same zero set; as a domain, the complement.
FunctionPtr negation(FunctionPtr f);

// ---- Domains (codimension 1, inside where < 0) --------------------------------------------------
/// An axis-parallel box [lo, hi] of R^d.
struct Box {
  std::vector<double> lo, hi;  ///< d coordinates each, lo < hi
  bool contains(const double* x) const;
};
/// max_i max(lo_i − x_i, x_i − hi_i): the open box. A box bounds a walk as any domain does, so the
/// cells along its faces are closed and the output is a manifold with boundary.
FunctionPtr box_domain(const Box& box);
/// |x − c|² − r²: the open ball.
FunctionPtr ball_domain(const std::vector<double>& center, double radius);
/// ⟨n, x⟩ − c: the half-space ⟨n, x⟩ < c.
FunctionPtr half_space_domain(const std::vector<double>& normal, double c);
/// max(a, b): the intersection {a < 0} ∩ {b < 0} of two domains (b alone when a is null). Evaluates
/// in batches when either does.
FunctionPtr domain_intersection(FunctionPtr a, FunctionPtr b);

}  // namespace coxmesh

#include "coxmesh/oracle/implicit_function_impl.h"
