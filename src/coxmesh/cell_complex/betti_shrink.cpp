// Z/2 Betti numbers after collapses and coreductions: the reduction runs on what is left.
//
// Both moves delete a pair of cells (a, b), a a facet of b, from the chain complex: a collapse when
// a lies in no other remaining cell, a coreduction (Mrozek and Batko, "Coreduction homology
// algorithm", 2009) when b has no other remaining facet. Either is the elimination of the pivot
// (a, b) of the boundary matrix, which over Z/2 changes no other entry, so homology is kept. What
// remains need not be a subcomplex, only a chain complex: the boundary matrix restricted to it.
#include <algorithm>
#include <climits>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/global_cells.h"
#include "coxmesh/util/union_find.h"

namespace coxmesh {

namespace {

constexpr std::uint32_t kRemoved = 0xFFFFFFFFu;

// Per remaining cell: how many remaining facets and cofaces it has, and the xor of their ids,
// which is the id of the one left when a count is 1. Cells are numbered from the first edge on
// (vertices are all removed first), 32-bit (the caller checks that they fit).
class Reducer {
 public:
  // Over the cells of dimension ≤ top, all vertices and the edges of a spanning forest of the
  // vertex graph (tree_edge, per edge) removed first: that is the coreduction of each tree from a
  // vertex whose class is known (β_0 counts it) outwards, one edge and the vertex at its far end
  // at a time, done in one pass. `top_is_cut`: the complex has cells above top, and the homology
  // of dimension top is not wanted (only the lower ones).
  Reducer(const GlobalCells& c, int top, bool top_is_cut, const std::vector<std::uint8_t>& tree_edge)
      : top_(top), top_is_cut_(top_is_cut), base_(c.start(1, false)), cell_(c.start(top + 1, false) - base_, Counts{}) {
    const CellComplex& cc = c.complex();
    // The levels from the edges to the top, interior then boundary, with their facet arrays read
    // directly (no search for a cell's level per visit).
    for (int j = 1; j <= top; ++j)
      for (int kind = 0; kind < 2; ++kind) {
        Level& l = levels_.emplace_back();
        l.first = relative(c.start(j, kind == 1));
        l.end = relative(kind ? c.start(j + 1, false) : c.start(j, true));
        l.dimension = j;
        if (j < 2 || l.first == l.end) continue;  // (the facets of edges, vertices, are all removed)
        const CellLevel& level = kind ? cc.boundary[j] : cc.interior[j];
        l.offsets = level.facet_offsets.data();
        l.ids = level.facet_ids.data();
        l.facet_first = relative(c.start(j - 1, kind == 1));
        if (!kind && !level.boundary_facet.empty()) {
          l.boundary_facet = level.boundary_facet.data();
          l.boundary_first = relative(c.start(j - 1, true));
        }
      }
    below_top_ = relative(std::max(c.start(top, false), base_));
    for (std::uint32_t e = 0; e < tree_edge.size() && e < cell_.size(); ++e)
      if (tree_edge[e]) cell_[e].up = kRemoved, ++removed_count_;
    const std::uint32_t first_face = top >= 2 ? levels_[2].first : static_cast<std::uint32_t>(cell_.size());
    for (std::uint32_t a = first_face; a < cell_.size(); ++a)
      for_each_facet(a, [&](std::uint32_t f) {
        if (cell_[f].up == kRemoved) return;
        ++cell_[a].down, ++cell_[f].up;
        cell_[a].xdown ^= f, cell_[f].xup ^= a;
      });
    // The cofaces of each remaining cell below the top, as CSR (the facets are the complex's own
    // lists). Each range is filled from its end, the cells taken in reverse so that every list
    // comes out in increasing order: no second array of positions.
    std::uint64_t total = 0;
    coface_start_.assign(below_top_ + 1, 0);
    for (std::uint32_t i = 0; i < below_top_; ++i) {
      total += cell_[i].up == kRemoved ? 0 : cell_[i].up;
      if (total > UINT32_MAX) throw InputError("the complex has too many incidences (2^32) for its topology");
      coface_start_[i + 1] = static_cast<std::uint32_t>(total);
    }
    coface_ids_.resize(total);
    for (std::uint32_t i = 0; i < below_top_; ++i) coface_start_[i] = coface_start_[i + 1];
    for (std::uint32_t a = static_cast<std::uint32_t>(cell_.size()); a-- > first_face;)
      for_each_facet(a, [&](std::uint32_t f) {
        if (cell_[f].up != kRemoved) coface_ids_[--coface_start_[f]] = a;
      });
    for (std::uint32_t a = 0; a < cell_.size(); ++a)
      if (cell_[a].up != kRemoved && (cell_[a].up == 1 || cell_[a].down <= 1)) pending_.push_back(a);
  }

  std::size_t remaining() const { return cell_.size() - removed_count_; }

  bool removed(std::size_t g) const {
    return g < base_ || g - base_ >= cell_.size() || cell_[g - base_].up == kRemoved;
  }

  // Collapses and coreductions while a cell has exactly one remaining coface or facet.
  void reduce() {
    for (std::size_t head = 0; head < pending_.size(); ++head) {
      if (head >= kCompactAt && 2 * head >= pending_.size()) {  // (keeps the queue short)
        pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      // The queue's cells are scattered over arrays far larger than the cache: fetch ahead.
      if (head + 2 * kAhead < pending_.size()) {
        const std::uint32_t f = pending_[head + 2 * kAhead];
        __builtin_prefetch(&cell_[f]);
        const Level& l = level_of(f);
        if (l.offsets) __builtin_prefetch(&l.offsets[f - l.first]);
        if (f < below_top_) __builtin_prefetch(&coface_start_[f]);
      }
      if (head + kAhead < pending_.size()) {
        const std::uint32_t f = pending_[head + kAhead];
        if (cell_[f].up != kRemoved) {
          const Level& l = level_of(f);
          if (l.offsets) __builtin_prefetch(&l.ids[l.offsets[f - l.first]]);
          if (f < below_top_) __builtin_prefetch(coface_ids_.data() + coface_start_[f]);
        }
      }
      if (head + kAhead / 2 < pending_.size()) {  // (and the other cell of its pair, if any)
        const Counts& cf = cell_[pending_[head + kAhead / 2]];
        if (cf.up != kRemoved && (cf.down == 1 || cf.up == 1)) {
          const std::uint32_t b = cf.down == 1 ? cf.xdown : cf.xup;
          __builtin_prefetch(&cell_[b]);
          if (b < below_top_) __builtin_prefetch(&coface_start_[b]);
        }
      }
      if (head + kAhead * 3 / 8 < pending_.size()) {  // (the list of those cofaces)
        const Counts& cf = cell_[pending_[head + kAhead * 3 / 8]];
        if (cf.up != kRemoved && cf.down == 1 && cf.xdown < below_top_)
          __builtin_prefetch(coface_ids_.data() + coface_start_[cf.xdown]);
      }
      if (head + kAhead / 4 < pending_.size()) {  // (and the cofaces of a coreduction's edge)
        const Counts& cf = cell_[pending_[head + kAhead / 4]];
        if (cf.up != kRemoved && cf.down == 1 && cf.xdown < below_top_)
          for (std::uint32_t i = coface_start_[cf.xdown]; i < coface_start_[cf.xdown + 1]; ++i)
            __builtin_prefetch(&cell_[coface_ids_[i]]);
      }
      const std::uint32_t a = pending_[head];
      const Counts& ca = cell_[a];
      if (ca.up == kRemoved) continue;
      const int j = dimension(a);
      // A pair's cells are removed without visiting the other cell of the pair, nor lists
      // whose cells are all removed: most visits of random cells are saved.
      if (ca.down == 1) {  // (coreductions first: collapses alone stall on 3-manifolds)
        const std::uint32_t b = ca.xdown;
        remove(a, j, false, ca.up != 0);
        remove(b, j - 1, cell_[b].down != 0, true);
      } else if (ca.up == 1) {
        const std::uint32_t b = ca.xup;
        remove(a, j, ca.down != 0, false);
        remove(b, j + 1, true, cell_[b].up != 0);
      } else if (j == top_ && ca.down == 0 && top_is_cut_) {
        // A cycle of the top dimension of a truncated skeleton: removing it changes only the
        // skeleton's own H_top, which is not wanted.
        remove(a, j, false, false);
      }
    }
  }

 private:
  struct Level {
    std::uint32_t first = 0, end = 0;  // its cells
    int dimension = 0;
    const std::uint32_t* offsets = nullptr;  // facet CSR of the complex
    const std::uint32_t* ids = nullptr;
    std::uint32_t facet_first = 0;                  // the first cell of the facets' level
    const std::uint32_t* boundary_facet = nullptr;  // (interior cells cut by a domain)
    std::uint32_t boundary_first = 0;
  };

  std::uint32_t relative(std::size_t g) const { return static_cast<std::uint32_t>(g - base_); }

  const Level& level_of(std::uint32_t a) const {
    int l = 0;
    while (a >= levels_[l].end) ++l;  // (2 per dimension: a short scan)
    return levels_[l];
  }
  int dimension(std::uint32_t a) const { return level_of(a).dimension; }

  template <class F>
  void for_each_facet(std::uint32_t a, F&& f) const {
    const Level& l = level_of(a);
    if (!l.ids) return;
    const std::uint32_t local = a - l.first;
    for (std::uint32_t i = l.offsets[local]; i < l.offsets[local + 1]; ++i) f(l.facet_first + l.ids[i]);
    if (l.boundary_facet && l.boundary_facet[local] != CellLevel::kNone) f(l.boundary_first + l.boundary_facet[local]);
  }

  // Removes cell a of dimension j (a cell whose homology class is known, or one of a pair).
  // (visit_...: false when every remaining facet or coface is the other cell of the pair, removed
  // next, or none remains)
  void remove(std::uint32_t a, int j, bool visit_facets, bool visit_cofaces) {
    cell_[a].up = kRemoved, ++removed_count_;
    if (visit_facets)
      for_each_facet(a, [&](std::uint32_t f) {
        Counts& cf = cell_[f];
        if (cf.up == kRemoved) return;
        cf.xup ^= a;
        if (--cf.up == 1) pending_.push_back(f);
      });
    if (visit_cofaces && j < top_)
      for (std::uint32_t i = coface_start_[a]; i < coface_start_[a + 1]; ++i) {
        Counts& cc = cell_[coface_ids_[i]];
        if (cc.up == kRemoved) continue;
        cc.xdown ^= a;
        if (--cc.down <= 1) pending_.push_back(coface_ids_[i]);  // (0: see reduce())
      }
  }

  struct Counts {
    std::uint32_t down = 0, up = 0, xdown = 0, xup = 0;
  };

  int top_;
  bool top_is_cut_;
  std::size_t base_;  // the first edge: vertices are all removed
  static constexpr std::size_t kCompactAt = 1 << 16;
  static constexpr std::size_t kAhead = 16;
  std::vector<Level> levels_;    // (dimension, kind) from the edges to the top
  std::uint32_t below_top_ = 0;  // the cells below the top dimension: [0, below_top_)
  std::size_t removed_count_ = 0;
  std::vector<Counts> cell_;  // (one cache line holds all four)
  std::vector<std::uint32_t> coface_start_;
  std::vector<std::uint32_t> coface_ids_;
  std::vector<std::uint32_t> pending_;  // FIFO of cells whose count became 1 (the order matters:
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
    std::vector<std::uint8_t> keep;  // (empty when nothing is left)
    {  // (its arrays go before the reduction's: they are the peak of the topology's memory)
      Reducer reducer(cells, top, top < m, tree_edge);
      reducer.reduce();
      if (reducer.remaining() > 0) {
        keep.resize(cells.count());
        for (std::size_t g = 0; g < keep.size(); ++g) keep[g] = !reducer.removed(g);
      }
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
