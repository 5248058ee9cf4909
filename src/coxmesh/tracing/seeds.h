// Seeds for tracing: projection onto M (Gauss–Newton) and automatic seeding in a box.
#pragma once

#include <optional>
#include <vector>

#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace coxmesh {

/// Projects x onto F^{-1}(0) by Gauss–Newton steps x ← x − J⁺F(x) (minimum-norm steps, J by
/// central differences). Returns the point once |F| ≤ tolerance, or nothing when it does not
/// converge in 100 steps or leaves finite values.
std::optional<std::vector<double>> project_onto_manifold(const ImplicitFunction& f, std::vector<double> x,
                                                         double tolerance = 1e-12);

/// A seed moved off the faces of dimension < d of the triangulation: a point of M on a lattice vertex
/// (the origin of many presets) lies in (d+1)! d-simplices, and there the exact rule's degenerate
/// cases are the slowest. Returns x when it lies inside a d-simplex; otherwise x moved by about h/4
/// in a fixed generic direction and projected back onto M (x itself if that fails or moves farther
/// than h).
std::vector<double> generic_seed(const ImplicitFunction& f, const Triangulation& t, std::vector<double> x);

/// Seeds for every component of M inside `box` (and the domain, if given): `samples` points
/// drawn from a fixed-seed generator are projected onto M; those that converge inside the box
/// and the domain are kept (in draw order, deterministic).
std::vector<std::vector<double>> find_seeds(const ImplicitFunction& f, const ImplicitFunction* domain, const Box& box,
                                            int samples = 2000, std::uint64_t rng_seed = 1);

/// The seeds of a trace, as `coxmesh trace` and the Python package choose them.
struct SeedChoice {
  std::vector<std::vector<double>> seeds;
  std::size_t automatic = 0;   ///< how many of them find_seeds found
  bool skip_unusable = false;  ///< for TraceOptions::skip_unusable_seeds (true when any was found automatically)
};

/// Each given point projected onto M (kept as given when the projection fails), else F's own seed;
/// then, when `automatic` is set or no seed is known, find_seeds in `box` (and the domain); every
/// seed is finally moved off the lower-dimensional faces of `t` (generic_seed).
///   Throws InputError when a given point has the wrong size, or no seed is known and none is found
///   (the message names the box, or says that F is not finite where it was sampled).
SeedChoice choose_seeds(const ImplicitFunction& f, const ImplicitFunction* domain,
                        const std::vector<std::vector<double>>& given, bool automatic, const Box& box,
                        const Triangulation& t);

}  // namespace coxmesh
