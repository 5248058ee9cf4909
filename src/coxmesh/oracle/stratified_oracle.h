// Thesis §4.2–§4.3 with several domain functions: the strata of a manifold with corners
// M ∩ {D_1 < 0, …, D_p < 0}, all decided by one symbolic perturbation.
#pragma once

#include <cstdint>
#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/triangulation/triangulation.h"

namespace coxmesh {

/// At most this many domain functions: a stratum is a bitmask of them.
inline constexpr int kMaxDomains = 64;

/// The stratum J ⊆ {D_1 … D_p} (a bitmask) of M̂ is F̂ = 0, D̂_i = 0 for i ∈ J, D̂_l < 0 for the
/// others: of dimension m − |J|. A simplex ν of dimension k + |J| meets it in at most one point.
/// Every question is the lexicographic test of thesis §4.3 (transversality.h) on the system whose
/// rows are 1, F_1 … F_k, then the domains in their order: D_i with the vertices of ν for i ∈ J, and
/// D_l with a slack column (D̂_l + t_l = 0, t_l > 0) for the others. That traces
///   F̂ = (ε, …, ε^k),  D̂_i = −ε^{k+i},
/// one generic perturbation for all strata, so every simplex meets every stratum in the right
/// dimension and the traced object is a PL manifold with corners even when lattice vertices lie
/// on several D_i = 0 (a value D = 0 counts as outside, as with one domain).
/// Evaluates F and every D once per lattice vertex (a private cache). Not thread-safe.
///
///   StratifiedOracle oracle(T, sphere(2, 3, 1.0), {half_space_domain({-1, 0, 0}, 0), …});
///   double p[3];  if (oracle.meets(nu, 0b011, p)) ...   // ν of dimension k + 2
class StratifiedOracle {
 public:
  /// Throws InputError when the functions and T disagree on d, or with more than kMaxDomains domains.
  StratifiedOracle(const Triangulation& triangulation, FunctionPtr f, std::vector<FunctionPtr> domains);

  int ambient_dimension() const { return d_; }
  int codimension() const { return k_; }
  int domain_count() const { return static_cast<int>(domains_.size()); }

  /// Does ν (dimension codimension() + popcount(stratum)) meet the stratum inside the other
  /// domains? Then writes the point (d coordinates, the unperturbed one). Throws EvaluationError
  /// where a function is not finite, InputError when more than 31 rows would be active.
  bool meets(const Simplex& nu, std::uint64_t stratum, double* point);

  std::uint64_t calls() const { return calls_; }
  std::uint64_t function_evaluations() const { return vertices_.size(); }

 private:
  std::uint32_t vertex_values(const std::int32_t* v);  // evaluates F, then each D, once; the row id

  Triangulation triangulation_;
  FunctionPtr f_;
  std::vector<FunctionPtr> domains_;
  int d_, k_, stride_;
  PackedKeyIndex vertices_;
  std::vector<double> values_;  // stride_ per vertex of vertices_
  std::uint64_t calls_ = 0;
};

}  // namespace coxmesh
