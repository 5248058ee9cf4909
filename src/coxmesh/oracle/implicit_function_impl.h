// Template definitions for implicit_function.h.
#pragma once

#include <string>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

template <class Fn>
FunctionPtr make_function(int d, int k, Fn fn, std::vector<double> seed) {
  check_dimension(d);
  if (k < 1 || k > d)
    throw InputError("the number of equations must be between 1 and d = " + std::to_string(d) + ", got " +
                     std::to_string(k));
  if (!seed.empty() && static_cast<int>(seed.size()) != d)
    throw InputError("the seed has " + std::to_string(seed.size()) + " coordinates, expected " + std::to_string(d));
  return std::make_shared<CallableFunction<Fn>>(d, k, std::move(fn), std::move(seed));
}

}  // namespace coxmesh
