// The reference computation of Z/2 Betti numbers: reduction of the whole boundary matrix.
#include <climits>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/boundary_reduction.h"
#include "coxmesh/cell_complex/global_cells.h"
#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh {

std::vector<std::size_t> betti_numbers_by_reduction(const CellComplex& cc, std::span<const std::uint8_t> keep) {
  const GlobalCells cells(cc);
  const int m = cc.manifold_dimension;
  const std::size_t n = cells.count();
  const bool all = keep.empty();
  // Kept cells numbered in the global order (by dimension, so every facet comes first).
  // (32-bit: the array spans all cells, of which few may be kept)
  if (n >= UINT32_MAX) throw InputError("the complex has too many cells (2^32) for its topology");
  constexpr std::uint32_t kDropped = UINT32_MAX;
  HugeVector<std::uint32_t> column(n, kDropped);  // (big blocks: util/huge_page_allocator.h)
  std::vector<int> dim_of;
  std::vector<std::uint32_t> cell_of;  // the inverse of column
  for (int j = 0; j <= m; ++j)
    for (std::size_t g = cells.start(j, false); g < cells.start(j + 1, false); ++g)
      if (all || keep[g]) {
        column[g] = static_cast<std::uint32_t>(dim_of.size());
        dim_of.push_back(j);
        cell_of.push_back(static_cast<std::uint32_t>(g));
      }
  return betti_by_column_reduction(m, dim_of, [&](std::size_t c, std::vector<phat::index>& col) {
    cells.for_each_facet(cell_of[c], [&](std::size_t f) {
      if (column[f] != kDropped) col.push_back(static_cast<phat::index>(column[f]));
    });
  });
}

}  // namespace coxmesh
