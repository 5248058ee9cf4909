// Z/2 Betti numbers after coreductions: the reduction runs on what is left.
//
// A coreduction (Mrozek and Batko, "Coreduction homology algorithm", 2009) deletes a pair of cells
// (a, b), a a facet of b, from the chain complex when b has no other remaining facet: the
// elimination of the pivot (a, b) of the boundary matrix, which over Z/2 changes no other entry, so
// homology is kept. What remains need not be a subcomplex, only a chain complex: the boundary
// matrix restricted to it.
#include <algorithm>
#include <climits>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/coreduction_sweeps.h"
#include "coxmesh/cell_complex/global_cells.h"
#include "coxmesh/util/huge_page_allocator.h"
#include "coxmesh/util/union_find.h"

namespace coxmesh {

namespace {

// Coreductions in sweeps over the cells of dimensions 2..top, the vertices and the tree edges
// (`gone`, per cell from the first edge on) deleted first: a cell with one remaining facet is
// deleted with it, and so is a cell of the top dimension with none when the complex has cells
// above (`top_is_cut`): such a cycle of a truncated skeleton carries only the skeleton's own H_top,
// which is not wanted. Passes in increasing dimension repeat until one deletes nothing (a few on
// the traced manifolds). Each reads the facet lists in storage order and one byte per cell: no
// coface lists nor queue of scattered cells, which cost 5–8 times as much for the same result
// (collapses, a cell in one remaining cell deleted with it, left no fewer cells after these on
// S³, T³ and SO(3)). Returns the number of cells left.
std::size_t coreduce_in_sweeps(const GlobalCells& c, int top, bool top_is_cut, HugeVector<std::uint8_t>& gone) {
  const CellComplex& cc = c.complex();
  const std::size_t base = c.start(1, false);
  struct Level {
    const CellLevel* cells;
    std::uint32_t first, facet_first, boundary_first;  // (relative to the first edge)
    bool top;
  };
  std::vector<Level> levels;
  for (int j = 2; j <= top; ++j)
    for (int kind = 0; kind < 2; ++kind) {
      const auto& kinds = kind ? cc.boundary : cc.interior;
      if (j >= static_cast<int>(kinds.size()) || kinds[j].size() == 0) continue;
      levels.push_back({&kinds[j], static_cast<std::uint32_t>(c.start(j, kind == 1) - base),
                        static_cast<std::uint32_t>(c.start(j - 1, kind == 1) - base),
                        static_cast<std::uint32_t>(c.start(j - 1, true) - base), j == top});
    }
  // One cell's move; false when no later pass can delete it (it is gone, or a cycle that stays).
  const auto visit = [&](const Level& l, std::uint32_t a) {
    if (gone[l.first + a]) return false;
    const CellLevel& level = *l.cells;
    std::uint32_t left = 0, facet = 0;
    for (std::uint32_t i = level.facet_offsets[a]; i < level.facet_offsets[a + 1]; ++i)
      if (const std::uint32_t f = l.facet_first + level.facet_ids[i]; !gone[f]) ++left, facet = f;
    if (!level.boundary_facet.empty() && level.boundary_facet[a] != CellLevel::kNone)
      if (const std::uint32_t f = l.boundary_first + level.boundary_facet[a]; !gone[f]) ++left, facet = f;
    if (left == 1) gone[facet] = gone[l.first + a] = 1;
    if (left == 0 && l.top && top_is_cut) gone[l.first + a] = 1;
    return left > 1;
  };
  std::vector<std::uint32_t> sizes;
  for (const Level& l : levels) sizes.push_back(static_cast<std::uint32_t>(l.cells->size()));
  sweep_until_settled(sizes, [&](std::size_t l, std::uint32_t a) { return visit(levels[l], a); });
  return static_cast<std::size_t>(std::count(gone.begin(), gone.end(), 0));
}

// The top cells of a manifold joined across interior (m−1)-cells (two each): one cell of each
// group that has no boundary facet. The sum of such a group's cells is a Z/2 cycle (a closed
// pseudo-manifold), so these are the classes of H_m.
std::vector<std::uint32_t> closed_top_pieces(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  const CellLevel& top = cc.interior[m];
  UnionFind pieces(top.size());
  HugeVector<std::uint32_t> first(cc.interior[m - 1].size(), CellLevel::kNone);
  for (std::uint32_t c = 0; c < top.size(); ++c)
    for (std::uint32_t f : top.facets(c))
      if (first[f] == CellLevel::kNone)
        first[f] = c;
      else
        pieces.unite(first[f], c);
  HugeVector<std::uint8_t> open(top.size(), 0);
  if (!top.boundary_facet.empty())
    for (std::uint32_t c = 0; c < top.size(); ++c)
      if (top.boundary_facet[c] != CellLevel::kNone) open[pieces.find(c)] = 1;
  if (const CellLevel& below = cc.interior[m - 1]; !below.domains.empty())  // stratified: boundary facets
    for (std::uint32_t c = 0; c < top.size(); ++c)
      for (std::uint32_t f : top.facets(c))
        if (below.domains[f] != 0) open[pieces.find(c)] = 1;
  std::vector<std::uint32_t> closed;
  for (std::uint32_t c = 0; c < top.size(); ++c)
    if (pieces.find(c) == c && !open[c]) closed.push_back(c);
  return closed;
}

}  // namespace

std::vector<std::size_t> betti_numbers(const CellComplex& cc, bool manifold) {
  const GlobalCells cells(cc);
  const int m = cc.manifold_dimension;
  if (m == 0) return {cells.count()};
  // β_0: the components of the vertex graph.
  const std::size_t vertices = cells.start(1, false);
  UnionFind components(vertices);
  const std::size_t first_edge = cells.start(1, false);
  // (arrays per cell as big blocks: util/huge_page_allocator.h)
  HugeVector<std::uint8_t> tree_edge(cells.start(2, false) - first_edge, 0);  // a spanning forest's edges
  for (std::size_t g = first_edge; g < cells.start(2, false); ++g) {
    std::uint32_t ends[2] = {0, 0}, n = 0;
    cells.for_each_facet(g, [&](std::size_t v) { ends[n++ & 1] = static_cast<std::uint32_t>(v); });
    // (closed complex: edge cells have two ends)
    tree_edge[g - first_edge] = components.unite(ends[0], ends[1]);
  }
  std::size_t components_count = vertices;
  for (std::uint8_t t : tree_edge) components_count -= t;
  long long euler = 0;
  for (int j = 0; j <= m; ++j)
    euler += (j % 2 ? -1LL : 1LL) * static_cast<long long>(cells.start(j + 1, false) - cells.start(j, false));
  // For a manifold, β_m is known too, and the Euler characteristic gives β_{m−1}: only the
  // (m−1)-skeleton is needed, for β_1 … β_{m−2}, and none of it for m ≤ 2.
  const int top = manifold ? m - 1 : m;
  std::vector<std::size_t> betti(m + 1, 0);
  if (!manifold || m >= 3) {
    // Deletions start from one vertex per component, a 0-cycle that no chain bounds (removing it
    // lowers β_0 by one and changes nothing else), and spread along the spanning forest.
    if (cells.count() > UINT32_MAX) throw InputError("the complex has too many cells (2^32) for its topology");
    HugeVector<std::uint8_t> gone = std::move(tree_edge);  // per cell from the first edge to the top
    gone.resize(cells.start(top + 1, false) - first_edge, 0);
    HugeVector<std::uint8_t> keep;  // (empty when nothing is left)
    if (coreduce_in_sweeps(cells, top, top < m, gone) > 0) {
      keep.assign(cells.count(), 0);
      for (std::size_t i = 0; i < gone.size(); ++i) keep[first_edge + i] = !gone[i];
    }
    if (!keep.empty()) betti = betti_numbers_by_reduction(cc, keep);
  }
  betti[0] += components_count;
  if (manifold) {
    betti[m] = closed_top_pieces(cc).size();
    betti_below_top_from_euler(betti, euler);
  }
  return betti;
}

void betti_below_top_from_euler(std::vector<std::size_t>& betti, long long euler) {
  const int m = static_cast<int>(betti.size()) - 1;
  long long rest = euler;  // (−1)^(m−1) β_{m−1} = χ − the other terms
  for (int j = 0; j <= m; ++j)
    if (j != m - 1) rest -= (j % 2 ? -1LL : 1LL) * static_cast<long long>(betti[j]);
  const long long b = (m - 1) % 2 ? -rest : rest;
  COXMESH_ASSERT(b >= 0);
  betti[m - 1] = static_cast<std::size_t>(b);
}

}  // namespace coxmesh
