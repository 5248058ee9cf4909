// A dimension fixed at compile time for the common cases, so that loops over it unroll.
#pragma once

#include <type_traits>

namespace coxmesh {

/// f(std::integral_constant<int, D>{}) with D = d when d is one of Ds, and D = 0 (d read at run
/// time) otherwise. Called once per batch of work, not per item: the switch costs a branch, the
/// unrolled loops save one per iteration.
template <int... Ds, class F>
void with_fixed_dimension(int d, F&& f) {
  const bool fixed = ((d == Ds ? (f(std::integral_constant<int, Ds>{}), true) : false) || ...);
  if (!fixed) f(std::integral_constant<int, 0>{});
}

}  // namespace coxmesh
