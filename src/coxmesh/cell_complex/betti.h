// Z/2 Betti numbers of a closed cell complex (every cell's boundary is a cycle): the reference
// reduction and the fast variant that the reports use; tests check that they agree.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh {

/// β_0..β_m by column reduction (PHAT, twist) of the boundary matrix of all cells ordered by
/// dimension: the reference, whose time and memory grow with the number of cells. With `keep`
/// (per cell in the numbering of GlobalCells): of the matrix restricted to the kept cells, which
/// must be a chain complex (∂∂ = 0), e.g. what collapses and coreductions leave.
std::vector<std::size_t> betti_numbers_by_reduction(const CellComplex& cc, std::span<const std::uint8_t> keep = {});

/// The same numbers, fast. β_0 is the number of components of the vertex graph. If `manifold` (the
/// complex passed the manifold check), β_m is the number of groups of top cells joined across
/// interior (m−1)-cells that have no boundary facet, the Euler characteristic gives β_{m−1}, and
/// only β_1 … β_{m−2} are left, which the (m−1)-skeleton determines: nothing is left for m ≤ 2.
/// Those (or all, for a complex that is not a manifold) come from the reduction of what remains
/// after coreductions (a cell with exactly one remaining facet is removed with it), which keep the
/// homology, started from one vertex per component; they leave nothing of S³ and a few per cent
/// of the cells of T³ and SO(3). O(incidences) per pass over the cells before that reduction.
std::vector<std::size_t> betti_numbers(const CellComplex& cc, bool manifold);

/// β_{m−1} of a manifold (m ≥ 1, m + 1 numbers in `betti`) from its Euler characteristic and the
/// other Betti numbers, Σ (−1)^j β_j = χ: replaces betti[m − 1].
void betti_below_top_from_euler(std::vector<std::size_t>& betti, long long euler);

}  // namespace coxmesh
