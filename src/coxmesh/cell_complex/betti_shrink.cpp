// Z/2 Betti numbers after collapses and coreductions: the reduction runs on what is left.
//
// Both moves delete a pair of cells (a, b), a a facet of b, from the chain complex: a collapse when
// a lies in no other remaining cell, a coreduction (Mrozek and Batko, "Coreduction homology
// algorithm", 2009) when b has no other remaining facet. Either is the elimination of the pivot
// (a, b) of the boundary matrix, which over Z/2 changes no other entry, so homology is kept. What
// remains need not be a subcomplex, only a chain complex: the boundary matrix restricted to it.
#include <climits>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/global_cells.h"
#include "coxmesh/util/union_find.h"

namespace coxmesh {

namespace {

constexpr std::uint32_t kRemoved = 0xFFFFFFFFu;

// Per remaining cell: how many remaining facets and cofaces it has, and the xor of their ids
// (relative to the first id of their dimension), which is the id of the one left when a count is 1.
class Reducer {
 public:
  // Over the cells of dimension ≤ top, all vertices and the edges of a spanning forest of the
  // vertex graph (tree_edge, per edge) removed first: that is the coreduction of each tree from a
  // vertex whose class is known (β_0 counts it) outwards, one edge and the vertex at its far end
  // at a time, done in one pass. `top_is_cut`: the complex has cells above top, and the homology
  // of dimension top is not wanted (only the lower ones). Cells are kept from the first edge on,
  // with 32-bit ids relative to it (the caller checks that they fit).
  Reducer(const GlobalCells& c, int top, bool top_is_cut, const std::vector<std::uint8_t>& tree_edge)
      : cells_(c),
        top_(top),
        top_is_cut_(top_is_cut),
        base_(c.start(1, false)),
        cell_(c.start(top + 1, false) - base_, Counts{}) {
    const std::size_t end = c.start(top + 1, false);
    for (std::size_t g = base_; g < c.start(2, false) && g < end; ++g)
      if (tree_edge[g - base_]) at(g).up = kRemoved;
    for (int j = 2; j <= top; ++j)  // (the facets of edges, vertices, are all removed)
      for (std::size_t g = c.start(j, false); g < c.start(j + 1, false); ++g)
        if (!removed(g))
          c.for_each_facet(g, [&](std::size_t f) {
            if (removed(f)) return;
            ++at(g).down, ++at(f).up;
            at(g).xdown ^= relative(f, j - 1), at(f).xup ^= relative(g, j);
          });
    // The cofaces of each remaining cell below the top, as CSR (the facets are the complex's own
    // lists). Each range is filled from its end, the cells taken in reverse so that every list
    // comes out in increasing order: no second array of positions.
    const std::size_t below_top = std::max(c.start(top, false), base_) - base_;
    std::uint64_t total = 0;
    coface_start_.assign(below_top + 1, 0);
    for (std::size_t i = 0; i < below_top; ++i) {
      total += removed(base_ + i) ? 0 : cell_[i].up;
      if (total > UINT32_MAX) throw InputError("the complex has too many incidences (2^32) for its topology");
      coface_start_[i + 1] = static_cast<std::uint32_t>(total);
    }
    coface_ids_.resize(total);
    for (std::size_t i = 0; i < below_top; ++i) coface_start_[i] = coface_start_[i + 1];
    for (int j = top; j >= 2; --j)
      for (std::size_t g = c.start(j + 1, false); g-- > c.start(j, false);)
        if (!removed(g))
          c.for_each_facet(g, [&](std::size_t f) {
            if (!removed(f)) coface_ids_[--coface_start_[f - base_]] = relative(g, j);
          });
    for (std::size_t g = base_; g < end; ++g)
      if (!removed(g) && (at(g).up == 1 || at(g).down <= 1)) pending_.push_back(static_cast<std::uint32_t>(g - base_));
  }

  bool removed(std::size_t g) const { return g < base_ || g - base_ >= cell_.size() || at(g).up == kRemoved; }

  // Removes cell g (a cell whose homology class is known, or one of a pair).
  void remove(std::size_t g) {
    const int j = cells_.dimension(g);
    at(g).up = kRemoved;
    if (j > 1)  // (no vertex remains)
      cells_.for_each_facet(g, [&](std::size_t f) {
        if (removed(f)) return;
        at(f).xup ^= relative(g, j);
        if (--at(f).up == 1) pending_.push_back(static_cast<std::uint32_t>(f - base_));
      });
    if (j < top_) {
      const std::size_t first = cells_.start(j + 1, false);
      for (std::uint32_t i = coface_start_[g - base_]; i < coface_start_[g - base_ + 1]; ++i) {
        const std::size_t c = first + coface_ids_[i];
        if (removed(c)) continue;
        at(c).xdown ^= relative(g, j);
        if (--at(c).down <= 1) pending_.push_back(static_cast<std::uint32_t>(c - base_));  // (0: see reduce())
      }
    }
  }

  // Collapses and coreduces while a cell has exactly one remaining coface or facet.
  void reduce() {
    for (std::size_t head = 0; head < pending_.size(); ++head) {
      if (head >= kCompactAt && 2 * head >= pending_.size()) {  // (keeps the queue short)
        pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      const std::size_t a = base_ + pending_[head];
      if (removed(a)) continue;
      const int j = cells_.dimension(a);
      std::size_t b;
      if (at(a).down == 1)  // (coreductions first: collapses alone stall on 3-manifolds)
        b = cells_.start(j - 1, false) + at(a).xdown;
      else if (at(a).up == 1)
        b = cells_.start(j + 1, false) + at(a).xup;
      else if (j == top_ && at(a).down == 0 && top_is_cut_) {
        // A cycle of the top dimension of a truncated skeleton: removing it changes only the
        // skeleton's own H_top, which is not wanted.
        remove(a);
        continue;
      } else
        continue;
      remove(a);
      remove(b);
    }
  }

 private:
  std::uint32_t relative(std::size_t g, int j) const { return static_cast<std::uint32_t>(g - cells_.start(j, false)); }
  struct Counts {
    std::uint32_t down = 0, up = 0, xdown = 0, xup = 0;
  };
  Counts& at(std::size_t g) { return cell_[g - base_]; }
  const Counts& at(std::size_t g) const { return cell_[g - base_]; }

  const GlobalCells& cells_;
  int top_;
  bool top_is_cut_;
  std::size_t base_;  // the first edge: vertices are all removed
  static constexpr std::size_t kCompactAt = 1 << 16;
  std::vector<Counts> cell_;  // (one cache line holds all four)
  std::vector<std::uint32_t> coface_start_;
  std::vector<std::uint32_t> coface_ids_;  // relative to the first cell of the dimension above
  std::vector<std::uint32_t> pending_;     // FIFO of cells whose count became 1 (the order matters:
                                           // first in, first out leaves far fewer cells than a stack)
};

// The top cells of a manifold joined across interior (m−1)-cells (two each): one cell of each
// group that has no boundary facet. The sum of such a group's cells is a Z/2 cycle (a closed
// pseudo-manifold), so these are the classes of H_m.
std::vector<std::uint32_t> closed_top_pieces(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  const CellLevel& top = cc.interior[m];
  UnionFind pieces(top.size());
  std::vector<std::uint32_t> first(cc.interior[m - 1].size(), CellLevel::kNone);
  for (std::uint32_t c = 0; c < top.size(); ++c)
    for (std::uint32_t f : top.facets(c))
      if (first[f] == CellLevel::kNone)
        first[f] = c;
      else
        pieces.unite(first[f], c);
  std::vector<std::uint8_t> open(top.size(), 0);
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
  std::vector<std::uint8_t> tree_edge(cells.start(2, false) - first_edge, 0);  // a spanning forest's edges
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
    std::vector<std::uint8_t> keep(cells.count());
    {  // (its arrays go before the reduction's: they are the peak of the topology's memory)
      Reducer reducer(cells, top, top < m, tree_edge);
      reducer.reduce();
      for (std::size_t g = 0; g < keep.size(); ++g) keep[g] = !reducer.removed(g);
    }
    betti = betti_numbers_by_reduction(cc, keep);
  }
  betti[0] += components_count;
  if (manifold) {
    betti[m] = closed_top_pieces(cc).size();
    long long rest = euler;  // (−1)^(m−1) β_{m−1} = χ − the other terms
    for (int j = 0; j <= m; ++j)
      if (j != m - 1) rest -= (j % 2 ? -1LL : 1LL) * static_cast<long long>(betti[j]);
    const long long b = (m - 1) % 2 ? -rest : rest;
    COXMESH_ASSERT(b >= 0);
    betti[m - 1] = static_cast<std::size_t>(b);
  }
  return betti;
}

}  // namespace coxmesh
