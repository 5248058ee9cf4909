#include "coxmesh/cell_complex/topology.h"

#include <phat/algorithms/twist_reduction.h>
#include <phat/boundary_matrix.h>
#include <phat/compute_persistence_pairs.h>
#include <phat/persistence_pairs.h>
#include <phat/representations/full_pivot_column.h>
#include <algorithm>

namespace coxmesh {

namespace {

// Number of cofacets of each cell of `lower` among the cells of `upper` (same kind).
std::vector<std::uint32_t> coface_counts(const CellLevel& lower, const CellLevel& upper) {
  std::vector<std::uint32_t> count(lower.size(), 0);
  for (std::uint32_t f : upper.facet_ids) ++count[f];
  return count;
}

// The cells of dimension j of both kinds, numbered one after the other: interior cells first.
struct GlobalIds {
  std::vector<std::size_t> interior, boundary;  // first global id of each level
  std::size_t count = 0;
  explicit GlobalIds(const CellComplex& cc) {
    const int m = cc.manifold_dimension;
    for (int j = 0; j <= m; ++j) {
      interior.push_back(count);
      count += cc.interior[j].size();
      boundary.push_back(count);
      if (j < static_cast<int>(cc.boundary.size())) count += cc.boundary[j].size();
    }
  }
};

// Appends the global ids of the facets of cell c of level j (interior or boundary).
void append_facets(const CellComplex& cc, const GlobalIds& ids, bool boundary, int j, std::uint32_t c,
                   std::vector<std::size_t>& out) {
  const CellLevel& level = boundary ? cc.boundary[j] : cc.interior[j];
  const std::size_t base = boundary ? ids.boundary[j - 1] : ids.interior[j - 1];
  for (std::uint32_t f : level.facets(c)) out.push_back(base + f);
  if (!boundary && !level.boundary_facet.empty() && level.boundary_facet[c] != CellLevel::kNone)
    out.push_back(ids.boundary[j - 1] + level.boundary_facet[c]);
}

// A complex whose Betti numbers mean something: every edge cell has two end points and the
// boundary of the boundary of every cell vanishes over Z/2 (each ridge of a polytope lies in an even
// number of its facets). A walk cut short leaves open cells at its front (an edge with one end);
// their homology would be meaningless (e.g. no component at all), so it is not computed.
std::string check_closed(const CellComplex& cc) {
  const GlobalIds ids(cc);
  std::vector<std::size_t> facets, ridges;
  for (int kind = 0; kind < 2; ++kind) {
    const auto& levels = kind ? cc.boundary : cc.interior;
    for (int j = 1; j < static_cast<int>(levels.size()); ++j)
      for (std::uint32_t c = 0; c < levels[j].size(); ++c) {
        facets.clear();
        append_facets(cc, ids, kind == 1, j, c, facets);
        if (j == 1) {
          if (facets.size() != 2 || facets[0] == facets[1])
            return std::string(kind ? "a boundary" : "an") + " edge cell has " + std::to_string(facets.size()) +
                   " end points";
          continue;
        }
        ridges.clear();
        for (std::size_t g : facets) {
          const bool on_boundary = g >= ids.boundary[j - 1];
          const std::size_t local = g - (on_boundary ? ids.boundary[j - 1] : ids.interior[j - 1]);
          append_facets(cc, ids, on_boundary, j - 1, static_cast<std::uint32_t>(local), ridges);
        }
        std::sort(ridges.begin(), ridges.end());
        for (std::size_t i = 0; i < ridges.size();) {
          std::size_t e = i;
          while (e < ridges.size() && ridges[e] == ridges[i]) ++e;
          if ((e - i) % 2)
            return "a " + std::to_string(j) + "-cell is not closed (a face of its boundary is not shared)";
          i = e;
        }
      }
  }
  return "";
}

std::string check_manifold(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  const auto& in = cc.interior;
  const auto& bd = cc.boundary;
  // (edge cells have two end points: the complex is closed)
  for (int j = 0; j < m; ++j) {
    const auto count = coface_counts(in[j], in[j + 1]);
    for (std::uint32_t c = 0; c < count.size(); ++c) {
      if (count[c] == 0) return "a " + std::to_string(j) + "-cell lies in no " + std::to_string(j + 1) + "-cell";
      if (j == m - 1 && count[c] != 2)
        return "an (m-1)-cell lies in " + std::to_string(count[c]) + " m-cells instead of 2";
    }
  }
  for (int j = 0; j + 1 < m && j + 1 < static_cast<int>(bd.size()); ++j) {
    const auto count = coface_counts(bd[j], bd[j + 1]);
    for (std::uint32_t c = 0; c < count.size(); ++c) {
      if (count[c] == 0) return "a boundary " + std::to_string(j) + "-cell lies in no boundary cell above it";
      if (j == m - 2 && count[c] != 2)
        return "a boundary (m-2)-cell lies in " + std::to_string(count[c]) + " boundary (m-1)-cells instead of 2";
    }
  }
  return "";
}

std::vector<std::size_t> betti_numbers(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  // Global order: by dimension; within dimension j, interior cells then boundary cells.
  const GlobalIds ids(cc);
  const std::vector<std::size_t>& in_base = ids.interior;
  const std::vector<std::size_t>& bd_base = ids.boundary;
  const std::size_t n = ids.count;
  // full_pivot_column: bit_tree_pivot_column negates INT64_MIN, which UBSan rejects.
  phat::boundary_matrix<phat::full_pivot_column> matrix;
  matrix.set_num_cols(static_cast<phat::index>(n));
  std::vector<phat::index> col;
  std::vector<int> dim_of(n);
  for (int j = 0; j <= m; ++j) {
    const CellLevel& li = cc.interior[j];
    for (std::uint32_t c = 0; c < li.size(); ++c) {
      col.clear();
      for (std::uint32_t f : li.facets(c)) col.push_back(static_cast<phat::index>(in_base[j - 1] + f));
      if (!li.boundary_facet.empty() && li.boundary_facet[c] != CellLevel::kNone)
        col.push_back(static_cast<phat::index>(bd_base[j - 1] + li.boundary_facet[c]));
      std::sort(col.begin(), col.end());
      const std::size_t id = in_base[j] + c;
      matrix.set_col(static_cast<phat::index>(id), col);
      matrix.set_dim(static_cast<phat::index>(id), static_cast<phat::dimension>(j));
      dim_of[id] = j;
    }
    if (j >= static_cast<int>(cc.boundary.size())) continue;
    const CellLevel& lb = cc.boundary[j];
    for (std::uint32_t c = 0; c < lb.size(); ++c) {
      col.clear();
      for (std::uint32_t f : lb.facets(c)) col.push_back(static_cast<phat::index>(bd_base[j - 1] + f));
      std::sort(col.begin(), col.end());
      const std::size_t id = bd_base[j] + c;
      matrix.set_col(static_cast<phat::index>(id), col);
      matrix.set_dim(static_cast<phat::index>(id), static_cast<phat::dimension>(j));
      dim_of[id] = j;
    }
  }
  phat::persistence_pairs pairs;
  phat::compute_persistence_pairs<phat::twist_reduction>(pairs, matrix);
  std::vector<std::size_t> betti(m + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++betti[dim_of[i]];
  for (phat::index p = 0; p < pairs.get_num_pairs(); ++p) {
    const auto [birth, death] = pairs.get_pair(p);
    --betti[dim_of[birth]];
    --betti[dim_of[death]];
  }
  return betti;
}

}  // namespace

TopologyReport analyze_topology(const CellComplex& cc, bool compute_betti) {
  TopologyReport r;
  const int m = cc.manifold_dimension;
  for (int j = 0; j <= m; ++j) {
    r.cells.push_back(cc.interior[j].size());
    r.euler_characteristic += (j % 2 ? -1LL : 1LL) * static_cast<long long>(cc.interior[j].size());
  }
  for (int j = 0; j < m; ++j) {
    const std::size_t n = j < static_cast<int>(cc.boundary.size()) ? cc.boundary[j].size() : 0;
    r.boundary_cells.push_back(n);
    r.euler_characteristic += (j % 2 ? -1LL : 1LL) * static_cast<long long>(n);
  }
  if (cc.interior[0].size() == 0)
    r.manifold_problem = "the complex is empty";
  else if (const std::string open = check_closed(cc); !open.empty())
    r.manifold_problem = "not a closed complex: " + open;
  else
    r.closed = true, r.manifold_problem = check_manifold(cc);
  r.is_manifold = r.manifold_problem.empty();
  if (compute_betti && r.closed) r.betti = betti_numbers(cc);
  return r;
}

}  // namespace coxmesh
