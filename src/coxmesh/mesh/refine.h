// Refinement of the output vertices onto M = F⁻¹(0): the vertices of the piecewise-linear
// approximation lie on the edges of the ambient triangulation, O(h²) off M (thesis §4.3); a few
// Gauss–Newton steps put them on M (and a vertex on the boundary of some domains on M ∩ {D_i = 0}
// for those domains) without changing the complex.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/oracle/implicit_function.h"

namespace coxmesh {

struct RefineOptions {
  int iterations = 12;     ///< Gauss–Newton steps at most per vertex
  double max_move = 0.25;  ///< a vertex may move at most this fraction of the longest edge
  int threads = 1;         ///< workers (0: all hardware threads)
};

struct RefinementReport {
  double max_abs_f_before = 0, max_abs_f_after = 0;  ///< max over vertices and equations of |F|
  std::size_t vertices = 0;                          ///< interior and boundary vertices
  /// Vertices left where they were: they would have moved too far, left a domain, or F got worse.
  std::size_t not_refined = 0;
  double seconds = 0;
};

/// F and the domain functions D_1, …, D_p (none: no domain) for one worker. Bit i of a vertex's
/// stratum stands for domains[i]: the boundary vertices of a complex with one domain have the
/// stratum 1, the vertices of a stratified complex their CellLevel::domains.
struct RefineSet {
  FunctionPtr f;
  std::vector<FunctionPtr> domains;
};
/// Makes the functions of one worker: a function that is not thread-safe (an expression typed as
/// text) must come fresh for each call.
using RefineFunctions = std::function<RefineSet()>;

/// Moves every vertex of `cc` onto M: x ← x − J⁺·r(x) (the minimum-norm Gauss–Newton step), where
/// r = (F, D_i for i in the vertex's stratum), so that a vertex on the boundary of some domains
/// stays on it, J = r's Jacobian by central differences (ImplicitFunction has no gradient). It
/// stops when the step no longer shrinks |r| or after options.iterations steps. A vertex that would
/// move farther than options.max_move × longest_edge from where it was, leave one of the other
/// domains (end with D_l ≥ 0 and larger than at the start, for l not in its stratum), or end with a larger |r| (or a
/// non-finite one) stays where it was and is counted in not_refined. Vertices are split into chunks over
/// options.threads workers, each with its own functions from `make`; the result does not depend on
/// the thread count.
///   Throws InputError when F and the complex live in different R^d, or a stratum names a domain
///   that `make` does not give.
RefinementReport refine_vertices(CellComplex& cc, double longest_edge, const RefineFunctions& make,
                                 const RefineOptions& options = {});

}  // namespace coxmesh
