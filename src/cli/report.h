// The topology report shared by `coxmesh trace` and `coxmesh check`: the same JSON keys and the
// same human lines for cells, Euler characteristic, Betti numbers and the manifold check.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/topology_json.h"

namespace coxmesh::cli {

/// The human lines "traced simplices", "cells by dimension", "Euler characteristic …, Betti
/// numbers …", "components", "manifold check", each indented by two spaces.
void print_topology(std::ostream& os, const CellComplex& cc, const TopologyReport& topo);

/// "1 2 1": numbers separated by spaces.
std::string number_list(const std::vector<std::size_t>& v);

/// Peak resident memory of the process in bytes (getrusage).
long long peak_memory_bytes();

}  // namespace coxmesh::cli
