#include "coxmesh/cell_complex/topology.h"

#include <algorithm>
#include <bit>
#include <random>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/global_cells.h"
#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh {

namespace {

// Number of cofacets of each cell of `lower` among the cells of `upper` (same kind). (The topology's
// arrays per cell are big blocks: util/huge_page_allocator.h.)
HugeVector<std::uint32_t> coface_counts(const CellLevel& lower, const CellLevel& upper) {
  HugeVector<std::uint32_t> count(lower.size(), 0);
  for (std::uint32_t f : upper.facet_ids) ++count[f];
  return count;
}

// A complex whose Betti numbers mean something: every edge cell has two end points and the
// boundary of the boundary of every cell vanishes over Z/2 (each ridge of a polytope lies in an even
// number of its facets). A walk cut short leaves open cells at its front (an edge with one end);
// their homology would be meaningless (e.g. no component at all), so it is not computed.
//
// ∂∂ = 0 is checked on fingerprints, Freivalds' check of a product of matrices: every cell's
// boundary is summarised by the xor of random 64-bit labels of its facets, and a cell is closed
// when the fingerprints of its facets xor to zero. A closed cell always passes; one that is not
// is caught but with probability 2^-64, the labels being drawn anew per call (no file can be made
// to pass). Each level is one pass over its facet lists in storage order, reading 8 bytes per facet
// from the level below: no facet lists of facets, no parity per ridge.
std::string check_closed(const CellComplex& cc) {
  const GlobalCells cells(cc);
  std::random_device entropy;
  const std::uint64_t seed = std::uint64_t{entropy()} << 32 ^ entropy();
  const auto label = [seed](std::size_t g) { return closedness_label(seed, g); };
  // Per cell of levels j − 1 and j of this kind (written in full before being read: not zeroed).
  UninitializedHugeVector<std::uint64_t> below, fingerprint;
  for (int kind = 0; kind < 2; ++kind) {
    const auto& levels = kind ? cc.boundary : cc.interior;
    for (int j = 1; j < static_cast<int>(levels.size()); ++j) {
      const CellLevel& level = levels[j];
      fingerprint.clear();  // (nothing to copy when it grows)
      fingerprint.resize(level.size());
      const std::size_t facet_first = cells.start(j - 1, kind == 1);
      const bool cut = !kind && !level.boundary_facet.empty();
      const bool read_above = j + 1 < static_cast<int>(levels.size());  // (the top level's fingerprints: unused)
      for (std::uint32_t c = 0; c < level.size(); ++c) {
        if (j == 1) {
          std::size_t ends[2] = {0, 0}, n = 0;
          cells.for_each_facet(1, kind == 1, c, [&](std::size_t v) { ends[n++ % 2] = v; });
          if (n == 2 && ends[0] != ends[1]) {
            fingerprint[c] = label(ends[0]) ^ label(ends[1]);
            continue;
          }
          const std::string edge = kind ? "a boundary edge cell" : "an edge cell";
          if (n != 2) return edge + " has " + std::to_string(n) + (n == 1 ? " end point" : " end points") + ", not 2";
          return edge + " has the same vertex at both ends";
        }
        std::uint64_t mine = 0, boundary_of_boundary = 0;
        const auto facets = level.facets(c);
        for (std::uint32_t f : facets) boundary_of_boundary ^= below[f];
        if (read_above)
          for (std::uint32_t f : facets) mine ^= label(facet_first + f);
        if (cut && level.boundary_facet[c] != CellLevel::kNone) {  // (a boundary cell: its fingerprint here)
          const std::uint32_t f = level.boundary_facet[c];
          mine ^= label(cells.start(j - 1, true) + f);
          cells.for_each_facet(j - 1, true, f, [&](std::size_t g) { boundary_of_boundary ^= label(g); });
        }
        if (boundary_of_boundary != 0)
          return "a " + std::to_string(j) + "-cell is not closed (a face of its boundary is not shared)";
        fingerprint[c] = mine;
      }
      below.swap(fingerprint);
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

// A manifold with corners (stratified complex): the closure of every stratum J (dimension
// n = m − |J|) is a pseudo-manifold with boundary. A cell of stratum J of dimension n − 1 lies in
// exactly 2 cells of dimension n of J; a cell of stratum J lies in exactly one cell of stratum
// J \ {i} for each i ∈ J (on its own simplex: at a corner, one edge along each face); and every
// cell below the top of its stratum lies in a cell of its stratum.
std::string check_stratified_manifold(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  const auto& in = cc.interior;
  for (int j = 0; j < m; ++j) {
    const CellLevel &lower = in[j], &upper = in[j + 1];
    std::vector<std::uint32_t> same(lower.size(), 0), fewer(lower.size(), 0);
    std::vector<std::uint64_t> dropped(lower.size(), 0);
    for (std::uint32_t e = 0; e < upper.size(); ++e)
      for (std::uint32_t c : upper.facets(e)) {
        const std::uint64_t mine = lower.domains[c], theirs = upper.domains[e];
        if (theirs == mine) {
          ++same[c];
        } else if ((theirs & mine) == theirs && std::popcount(mine ^ theirs) == 1) {
          ++fewer[c], dropped[c] |= mine ^ theirs;
        } else {
          return "a cell of domains " + std::to_string(mine) + " is a facet of a cell of domains " +
                 std::to_string(theirs);
        }
      }
    for (std::uint32_t c = 0; c < lower.size(); ++c) {
      const std::uint64_t mine = lower.domains[c];
      const int top = m - std::popcount(mine);
      if (fewer[c] != static_cast<std::uint32_t>(std::popcount(mine)) || dropped[c] != mine)
        return "a " + std::to_string(j) + "-cell of domains " + std::to_string(mine) +
               " does not lie in one cell of each stratum with one domain fewer";
      if (j == top - 1 && same[c] != 2)
        return "a " + std::to_string(j) + "-cell of domains " + std::to_string(mine) + " lies in " +
               std::to_string(same[c]) + " cells of its stratum above it instead of 2";
      if (j < top - 1 && same[c] == 0)
        return "a " + std::to_string(j) + "-cell of domains " + std::to_string(mine) +
               " lies in no cell of its stratum above it";
      if (j > top)
        return "a cell of dimension " + std::to_string(j) + " in a stratum of dimension " + std::to_string(top);
    }
  }
  return "";
}

}  // namespace

TopologyReport analyze_topology(const CellComplex& cc, bool compute_betti) {
  TopologyReport r;
  const int m = cc.manifold_dimension;
  for (int j = 0; j <= m; ++j) {
    r.cells.push_back(cc.interior[j].size());
    r.euler_characteristic += (j % 2 ? -1LL : 1LL) * static_cast<long long>(cc.interior[j].size());
  }
  if (cc.stratified()) {  // (all cells are in `interior`: tell the boundary apart by their domains)
    r.boundary_cells.assign(static_cast<std::size_t>(m), 0);
    for (int j = 0; j < m; ++j)
      for (std::uint64_t domains : cc.interior[j].domains)
        if (domains != 0) --r.cells[j], ++r.boundary_cells[j];
  }
  for (int j = 0; j < m && !cc.stratified(); ++j) {
    const std::size_t n = j < static_cast<int>(cc.boundary.size()) ? cc.boundary[j].size() : 0;
    r.boundary_cells.push_back(n);
    r.euler_characteristic += (j % 2 ? -1LL : 1LL) * static_cast<long long>(n);
  }
  if (cc.interior[0].size() == 0)
    r.manifold_problem = "the complex is empty";
  else if (const std::string open = check_closed(cc); !open.empty())
    r.manifold_problem = "not a closed complex: " + open;
  else
    r.closed = true, r.manifold_problem = cc.stratified() ? check_stratified_manifold(cc) : check_manifold(cc);
  r.is_manifold = r.manifold_problem.empty();
  if (compute_betti && r.closed) r.betti = betti_numbers(cc, r.is_manifold);
  return r;
}

std::vector<StratumCount> stratum_counts(const TopologyReport& topo) {
  std::vector<StratumCount> out;
  const int m = static_cast<int>(topo.cells.size()) - 1;
  const auto add = [&](std::uint64_t domains, int dimension, const std::vector<std::size_t>& cells) {
    if (std::all_of(cells.begin(), cells.end(), [](std::size_t n) { return n == 0; })) return;
    StratumCount& s = out.emplace_back();
    s.domains = domains, s.dimension = dimension;
    s.cells.assign(static_cast<std::size_t>(std::max(dimension, 0)) + 1, 0);
    for (std::size_t j = 0; j < cells.size() && j < s.cells.size(); ++j) s.cells[j] = cells[j];
  };
  add(0, m, topo.cells);
  add(1, m - 1, topo.boundary_cells);
  return out;
}

}  // namespace coxmesh
