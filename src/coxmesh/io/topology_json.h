// The topology report as JSON, with the keys every front end shares (`coxmesh trace --json`,
// `coxmesh check --json`, the Python package's summary()).
#pragma once

#include <nlohmann/json.hpp>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"

namespace coxmesh {

/// Keys ambient_dimension, manifold_dimension, traced_simplices (|S| = interior vertex cells),
/// boundary_simplices (|S_∂| = boundary vertex cells), cells, boundary_cells, closed,
/// euler_characteristic, betti and components (only for a closed complex: an open one has no
/// topology to report), is_manifold, manifold_problem (only when not a manifold), strata (per
/// stratum: "domains", the 1-based domain functions whose boundaries it lies on, [] for the
/// interior; "dimension"; "cells" per dimension), corners (vertex cells of 0-dimensional strata
/// other than the interior: where m domain boundaries meet M), cell_complex_bytes.
nlohmann::json topology_json(const CellComplex& cc, const TopologyReport& topo);

}  // namespace coxmesh
