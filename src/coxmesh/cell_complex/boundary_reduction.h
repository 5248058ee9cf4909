// The column reduction behind every Z/2 Betti number that is not read off the structure: PHAT's
// twist reduction of a boundary matrix (Bauer, Kerber, Reininghaus, Wagner: "PHAT — Persistent
// Homology Algorithms Toolbox", 2014). Internal to the cell complex layer.
#pragma once

#include <phat/algorithms/twist_reduction.h>
#include <phat/boundary_matrix.h>
#include <phat/compute_persistence_pairs.h>
#include <phat/persistence_pairs.h>
#include <phat/representations/full_pivot_column.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace coxmesh {

/// β_0..β_m over Z/2 of the chain complex whose cells are the columns 0, 1, …: column c has
/// dimension dim_of[c] ≤ m, and facets(c, out) appends the columns of its facets (each below c) to
/// out. Every pair of the reduction kills a cell of each of its two dimensions.
template <class Facets>
std::vector<std::size_t> betti_by_column_reduction(int m, const std::vector<int>& dim_of, Facets&& facets) {
  // full_pivot_column: bit_tree_pivot_column negates INT64_MIN, which UBSan rejects.
  phat::boundary_matrix<phat::full_pivot_column> matrix;
  matrix.set_num_cols(static_cast<phat::index>(dim_of.size()));
  std::vector<phat::index> col;
  for (std::size_t c = 0; c < dim_of.size(); ++c) {
    col.clear();
    facets(c, col);
    std::sort(col.begin(), col.end());
    matrix.set_col(static_cast<phat::index>(c), col);
    matrix.set_dim(static_cast<phat::index>(c), static_cast<phat::dimension>(dim_of[c]));
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
