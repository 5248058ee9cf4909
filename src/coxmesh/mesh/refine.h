// Refinement of the output vertices onto M = F⁻¹(0): the vertices of the piecewise-linear
// approximation lie on the edges of the ambient triangulation, O(h²) off M (thesis §4.3); a few
// Gauss–Newton steps put them on M (and boundary vertices on M ∩ {D = 0}) without changing the
// complex.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>

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
  std::size_t not_refined = 0;  ///< vertices left where they were: they would have moved too far, or F got worse
  double seconds = 0;
};

/// F and the domain D (null: none) for one worker: a function that is not thread-safe (an
/// expression typed as text) must come fresh for each call.
using RefineFunctions = std::function<std::pair<FunctionPtr, FunctionPtr>()>;

/// Moves every vertex of `cc` onto M: x ← x − J⁺·r(x) (the minimum-norm Gauss–Newton step), where
/// r = F for interior vertices and r = (F, D) for boundary vertices (they stay on ∂D), J = r's
/// Jacobian by central differences (ImplicitFunction has no gradient). It stops when the step no
/// longer shrinks |r| or after options.iterations steps. A vertex that would move farther than
/// options.max_move × longest_edge from where it was, or end with a larger |r| (or a non-finite
/// one), stays where it was and is counted in not_refined. Vertices are split into chunks over
/// options.threads workers, each with its own functions from `make`; the result does not depend
/// on the thread count.
RefinementReport refine_vertices(CellComplex& cc, double longest_edge, const RefineFunctions& make,
                                 const RefineOptions& options = {});

}  // namespace coxmesh
