#include "coxmesh/io/topology_json.h"

namespace coxmesh {

nlohmann::json topology_json(const CellComplex& cc, const TopologyReport& topo) {
  nlohmann::json j;
  j["ambient_dimension"] = cc.ambient_dimension;
  j["manifold_dimension"] = cc.manifold_dimension;
  // The counts of the report: a complex split between processes is not here (mesh_distributed.h).
  // (a stratified complex has the vertex cells of all strata in interior[0])
  const bool counted = !topo.cells.empty();
  j["traced_simplices"] = counted ? topo.cells[0] : cc.interior.empty() ? 0 : cc.interior[0].size();
  j["boundary_simplices"] = counted               ? (topo.boundary_cells.empty() ? 0 : topo.boundary_cells[0])
                            : cc.boundary.empty() ? 0
                                                  : cc.boundary[0].size();
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
  // The strata: the interior (domains 0) and, per set of domain functions whose boundaries meet
  // there (bit i: domain i + 1), its dimension and cells; corners are its vertex cells of dimension 0.
  std::size_t corners = 0;
  j["strata"] = nlohmann::json::array();
  for (const StratumCount& s : counted && !cc.stratified() ? stratum_counts(topo) : stratum_counts(cc)) {
    if (s.domains != 0 && s.dimension == 0) corners += s.cells[0];
    nlohmann::json domains = nlohmann::json::array();
    for (int i = 0; i < 64; ++i)
      if (s.domains >> i & 1) domains.push_back(i + 1);
    j["strata"].push_back({{"domains", domains}, {"dimension", s.dimension}, {"cells", s.cells}});
  }
  j["corners"] = corners;
  j["cell_complex_bytes"] = cc.bytes();
  return j;
}

}  // namespace coxmesh
