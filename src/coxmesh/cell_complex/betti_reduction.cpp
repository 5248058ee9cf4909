// The reference computation of Z/2 Betti numbers: reduction of the whole boundary matrix.
#include <phat/algorithms/twist_reduction.h>
#include <phat/boundary_matrix.h>
#include <phat/compute_persistence_pairs.h>
#include <phat/persistence_pairs.h>
#include <phat/representations/full_pivot_column.h>

#include <algorithm>
#include <climits>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/global_cells.h"

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
  std::vector<std::uint32_t> column(n, kDropped);
  std::vector<int> dim_of;
  for (int j = 0; j <= m; ++j)
    for (std::size_t g = cells.start(j, false); g < cells.start(j + 1, false); ++g)
      if (all || keep[g]) column[g] = static_cast<std::uint32_t>(dim_of.size()), dim_of.push_back(j);
  // full_pivot_column: bit_tree_pivot_column negates INT64_MIN, which UBSan rejects.
  phat::boundary_matrix<phat::full_pivot_column> matrix;
  matrix.set_num_cols(static_cast<phat::index>(dim_of.size()));
  std::vector<phat::index> col;
  for (std::size_t g = 0; g < n; ++g) {
    if (column[g] == kDropped) continue;
    col.clear();
    cells.for_each_facet(g, [&](std::size_t f) {
      if (column[f] != kDropped) col.push_back(static_cast<phat::index>(column[f]));
    });
    std::sort(col.begin(), col.end());
    const auto c = static_cast<phat::index>(column[g]);
    matrix.set_col(c, col);
    matrix.set_dim(c, static_cast<phat::dimension>(dim_of[column[g]]));
  }
  phat::persistence_pairs pairs;
  phat::compute_persistence_pairs<phat::twist_reduction>(pairs, matrix);
  std::vector<std::size_t> betti(m + 1, 0);
  for (int j : dim_of) ++betti[j];
  for (phat::index p = 0; p < pairs.get_num_pairs(); ++p) {
    const auto [birth, death] = pairs.get_pair(p);
    --betti[dim_of[birth]];
    --betti[dim_of[death]];
  }
  return betti;
}

}  // namespace coxmesh
