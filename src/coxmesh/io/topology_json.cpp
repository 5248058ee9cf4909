#include "coxmesh/io/topology_json.h"

namespace coxmesh {

nlohmann::json topology_json(const CellComplex& cc, const TopologyReport& topo) {
  nlohmann::json j;
  j["ambient_dimension"] = cc.ambient_dimension;
  j["manifold_dimension"] = cc.manifold_dimension;
  j["traced_simplices"] = cc.interior.empty() ? 0 : cc.interior[0].size();
  j["boundary_simplices"] = cc.boundary.empty() ? 0 : cc.boundary[0].size();
  j["cells"] = topo.cells;
  j["boundary_cells"] = topo.boundary_cells;
  j["closed"] = topo.closed;
  if (topo.closed) {
    j["euler_characteristic"] = topo.euler_characteristic;
    j["betti"] = topo.betti;
    j["components"] = topo.betti.empty() ? 0 : topo.betti[0];
  }
  j["is_manifold"] = topo.is_manifold;
  if (!topo.is_manifold) j["manifold_problem"] = topo.manifold_problem;
  j["cell_complex_bytes"] = cc.bytes();
  return j;
}

}  // namespace coxmesh
