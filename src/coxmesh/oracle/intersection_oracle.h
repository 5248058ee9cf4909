// Thesis §4.2 (the intersection oracle), §4.3. The tracer talks to the manifold only
// through this interface, so an implicit function, a point cloud, or anything else plugs in.
#pragma once

#include <cstdint>
#include <span>

#include "coxmesh/errors.h"
#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// What the oracle says of a k-simplex τ (k = codimension of M).
struct Intersection {
  bool hit = false;    ///< τ meets the PL approximation M̂ (transversally)
  double domain = -1;  ///< D̂ at the intersection point: < 0 inside the domain (−1 without domain)
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

  /// True when the oracle promises what the thesis proves of the PL approximation of a regular
  /// level set (§4.2): every cofacet μ of a transverse k-simplex meets M̂ on exactly two of its
  /// facets. The walk then meets each cell of dimension 1 of the cell complex with both its
  /// vertices and can keep them (TraceOptions::keep_cofacets; it keeps none when their incidences
  /// do not add up). False by default: a point cloud's local approximations need not agree
  /// between neighbouring simplices.
  virtual bool two_transverse_facets() const { return false; }
  /// Optional door-in/door-out guess (the pivoting step of PL continuation, thesis §4.2). M̂ meets
  /// each cofacet μ of a transverse k-simplex τ in a segment whose ends lie on exactly two facets of
  /// μ: τ and one other. After pivot_enter(τ) returned true, pivot_exit(v) guesses that other facet
  /// for μ = τ ∪ {v} (v: the lattice vertex of μ not in τ) and returns the index, in τ's vertex
  /// order, of the vertex of τ it lacks; −1 means no guess. The tracer checks every guess with
  /// intersect(), so a wrong guess costs time, never correctness. The defaults make no guesses.
  virtual bool pivot_enter(const Simplex& /*tau*/) { return false; }
  virtual int pivot_exit(const std::int32_t* /*v*/) { return -1; }
  /// Optional: pivot_exit(v) follows soon; an oracle may hint the processor's caches to load what
  /// it will read (the default does nothing).
  virtual void prefetch_pivot(const std::int32_t* /*v*/) {}

  /// Optional: the k-simplices of the breadth-first level about to be walked, packed (pack(),
  /// packed_words(d) words each), before any of their cofacets is tested. An oracle may use it to
  /// compute in one batch what the walk will ask for (the default does nothing).
  virtual void prefetch(std::span<const std::uint32_t> /*packed_simplices*/) {}
};

}  // namespace coxmesh
