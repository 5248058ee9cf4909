// Thesis §4.1 (the intersection oracle); spec §2.1, §3. The tracer talks to the manifold only
// through this interface, so an implicit function, a point cloud, or anything else plugs in.
#pragma once

#include <cstdint>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// What the oracle says of a k-simplex τ (k = codimension of M).
struct Intersection {
  bool hit = false;     ///< τ meets the PL approximation M̂ (transversally)
  double domain = -1;   ///< D̂ at the intersection point: < 0 inside the domain (−1 without domain)
};

class IntersectionOracle {
 public:
  virtual ~IntersectionOracle() = default;
  virtual int ambient_dimension() const = 0;
  virtual int codimension() const = 0;
  /// Tests τ (dimension = codimension()); on a hit writes the intersection point (d coordinates).
  /// Not thread-safe (caches); throws EvaluationError when the function is not finite.
  virtual Intersection intersect(const Simplex& tau, double* point) = 0;
  /// True when a domain function restricts M (then Intersection::domain is meaningful).
  virtual bool has_domain() const { return false; }
  /// Number of function evaluations so far (implicit oracles count one per lattice vertex).
  virtual std::uint64_t function_evaluations() const { return 0; }
};

/// A function returned NaN or ±Inf at a point; the message names the point.
struct EvaluationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace coxmesh
