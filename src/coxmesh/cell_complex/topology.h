// Topology of a cell complex: counts, Euler characteristic, Z/2 Betti numbers, manifold check.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh {

struct TopologyReport {
  std::vector<std::size_t> cells;           ///< interior cells per dimension 0..m
  std::vector<std::size_t> boundary_cells;  ///< boundary cells per dimension 0..m−1
  long long euler_characteristic = 0;       ///< of the whole complex
  std::vector<std::size_t> betti;           ///< Z/2 Betti numbers of the whole complex, 0..m; empty unless closed
  bool closed = false;                      ///< every cell's boundary is a cycle (edge cells have two ends)
  bool is_manifold = false;
  std::string manifold_problem;  ///< the first violation found (empty if a manifold)
};

/// Euler characteristic and counts are O(cells); Z/2 Betti numbers (betti.h: collapses and
/// coreductions, then a reduction of what is left) only for a closed
/// complex (a walk stopped by a limit leaves open cells at its front). The manifold check:
/// every interior 1-cell has 2 end points (interior or boundary vertices), every interior
/// (m−1)-cell lies in exactly 2 m-cells, every boundary (m−2)-cell in exactly 2 boundary
/// (m−1)-cells, and every cell of dimension < m lies in some cell of the next dimension.
TopologyReport analyze_topology(const CellComplex& cc, bool compute_betti = true);

/// The random label of the cell of global id g (global_cells.h) in the closedness check of
/// analyze_topology (topology.cpp): splitmix64's mix of a seed drawn per check and g. A cell's
/// fingerprint is the xor of its facets' labels; a cell is closed when its facets' fingerprints xor
/// to zero (the distributed check, topology_distributed.cpp, uses the same labels).
inline std::uint64_t closedness_label(std::uint64_t seed, std::uint64_t g) {
  std::uint64_t z = seed + (g + 1) * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// stratum_counts (cell_complex.h) of a complex that is not stratified, from its report's counts:
/// the interior, and the boundary when it has cells.
std::vector<StratumCount> stratum_counts(const TopologyReport& topo);

}  // namespace coxmesh
