// Geometry of a cell complex for the writers: vertex numbering, polygon cycles, polyhedron faces.
#include "coxmesh/io/polygons.h"

#include <algorithm>

namespace coxmesh {

namespace {

// Sorts a cell's few corners (a few tens of numbers) by insertion, where std::sort's set-up costs
// more than the sort; a long list by std::sort.
template <class T>
void sort_few(std::vector<T>& v) {
  if (v.size() > 48) return std::sort(v.begin(), v.end());
  for (std::size_t i = 1; i < v.size(); ++i) {
    const T x = v[i];
    std::size_t j = i;
    for (; j > 0 && x < v[j - 1]; --j) v[j] = v[j - 1];
    v[j] = x;
  }
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// The (j−1)-cells bounding cell c of dimension j of one kind, as ids in the global numbering of
// dimension j − 1 (interior cells first, then boundary cells offset by `interior_below`).
void facets_of(const CellLevel& level, CellKind kind, std::uint32_t c, std::uint32_t interior_below,
               std::vector<std::uint32_t>& out) {
  out.clear();
  const std::uint32_t shift = kind == CellKind::boundary ? interior_below : 0;
  for (std::uint32_t f : level.facets(c)) out.push_back(shift + f);
  if (kind == CellKind::interior && !level.boundary_facet.empty() && level.boundary_facet[c] != CellLevel::kNone)
    out.push_back(interior_below + level.boundary_facet[c]);
}

}  // namespace

const CellLevel* cell_level(const CellComplex& cc, CellKind kind, int j) {
  const auto& levels = kind == CellKind::interior ? cc.interior : cc.boundary;
  return j >= 0 && j < static_cast<int>(levels.size()) ? &levels[j] : nullptr;
}

std::uint32_t cell_count(const CellComplex& cc, CellKind kind, int j) {
  const CellLevel* level = cell_level(cc, kind, j);
  return level ? level->size() : 0;
}

std::uint32_t vertex_count(const CellComplex& cc) {
  return cell_count(cc, CellKind::interior, 0) + cell_count(cc, CellKind::boundary, 0);
}

std::vector<double> vertex_coordinates(const CellComplex& cc) {
  std::vector<double> xs(cc.vertices.begin(), cc.vertices.end());
  xs.insert(xs.end(), cc.boundary_vertices.begin(), cc.boundary_vertices.end());
  return xs;
}

Ragged edge_ends(const CellComplex& cc, CellKind kind) {
  Ragged ends;
  const CellLevel* level = cell_level(cc, kind, 1);
  if (!level) return ends;
  const std::uint32_t n0 = cell_count(cc, CellKind::interior, 0);
  ends.offsets.reserve(level->size() + 1);
  ends.items.reserve(2 * static_cast<std::size_t>(level->size()));
  std::vector<std::uint32_t> list;
  for (std::uint32_t c = 0; c < level->size(); ++c) {
    facets_of(*level, kind, c, n0, list);
    ends.push(list);
  }
  return ends;
}

namespace {

// The two end points (global vertex ids) of every 1-cell in the global edge numbering (interior,
// then boundary), in the order of edge_ends; both kNone when the cell does not have exactly two.
IndexArray edge_end_pairs(const CellComplex& cc) {
  const std::uint32_t n0 = cell_count(cc, CellKind::interior, 0);
  const std::uint32_t n1 = cell_count(cc, CellKind::interior, 1), nb1 = cell_count(cc, CellKind::boundary, 1);
  IndexArray pairs(2 * (std::size_t{n1} + nb1));  // (written in full below)
  std::uint32_t* out = pairs.data();
  for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
    const CellLevel* level = cell_level(cc, kind, 1);
    if (!level) continue;
    const bool boundary = kind == CellKind::boundary;
    const bool closing = !boundary && !level->boundary_facet.empty();
    const std::uint32_t shift = boundary ? n0 : 0;
    for (std::uint32_t c = 0; c < level->size(); ++c, out += 2) {
      const auto facets = level->facets(c);
      const bool extra = closing && level->boundary_facet[c] != CellLevel::kNone;
      if (facets.size() + (extra ? 1 : 0) != 2) {
        out[0] = out[1] = CellLevel::kNone;
      } else {
        out[0] = shift + facets[0];
        out[1] = extra ? n0 + level->boundary_facet[c] : shift + facets[1];
      }
    }
  }
  return pairs;
}

// polygon_cycles, and with `cycle_edges` (kEdges) the global id of each cycle's edges too: edge i joins
// vertices i and i + 1 (the last joins the last vertex and the first).
template <bool kEdges>
Ragged polygon_cycles(const CellComplex& cc, Ragged* cycle_edges) {
  Ragged cycles;
  const IndexArray ends = edge_end_pairs(cc);
  const std::uint32_t n1 = cell_count(cc, CellKind::interior, 1);
  std::vector<std::uint32_t> list, spill;
  std::size_t polygons = 0, corners = 0;  // (sizes known: the arrays grow once)
  for (CellKind kind : {CellKind::interior, CellKind::boundary})
    if (const CellLevel* level = cell_level(cc, kind, 2))
      polygons += level->size(), corners += level->facet_ids.size() + level->boundary_facet.size();
  for (Ragged* r : {&cycles, cycle_edges})
    if (r) r->offsets.reserve(polygons + 1), r->items.reserve(corners);
  // The cycle and its edges are appended as they are found, and taken back if they do not close.
  const auto close_list = [](Ragged& r, bool closed) {
    if (!closed) r.items.resize(r.offsets.back());
    r.offsets.push_back(static_cast<std::uint32_t>(r.items.size()));
  };
  for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
    const CellLevel* level = cell_level(cc, kind, 2);
    if (!level) continue;
    // (an interior polygon with no boundary edge lists its edges as they are: no copy)
    const bool as_listed = kind == CellKind::interior && level->boundary_facet.empty();
    const std::size_t shift = kind == CellKind::boundary ? n1 : 0;  // (of the edges' global ids)
    for (std::uint32_t c = 0; c < level->size(); ++c) {
      // (the edges' ends are read at random: fetched a few polygons ahead)
      if (constexpr std::uint32_t kAhead = 8; c + kAhead < level->size())
        for (std::uint32_t e : level->facets(c + kAhead)) __builtin_prefetch(ends.data() + 2 * (shift + e));
      if (!as_listed) facets_of(*level, kind, c, n1, list);
      const std::span<const std::uint32_t> edges = as_listed ? level->facets(c) : std::span<const std::uint32_t>(list);
      const std::size_t n = edges.size();
      bool closed = n >= 3;
      // (a polygon has a few edges as a rule: their ends and ids on the stack)
      constexpr std::size_t kFew = 16;
      std::uint32_t few[3 * kFew];
      if (n > kFew) spill.resize(3 * n);
      std::uint32_t* first = n > kFew ? spill.data() : few;
      std::uint32_t* second = first + std::max(n, kFew);
      std::uint32_t* id = second + std::max(n, kFew);
      for (std::size_t i = 0; i < n && closed; ++i) {
        first[i] = ends[2 * std::size_t{edges[i]}], second[i] = ends[2 * std::size_t{edges[i]} + 1];
        if constexpr (kEdges) id[i] = edges[i];
        closed = first[i] != CellLevel::kNone;
      }
      if (closed) {
        // Walk: from the second end of the first edge, repeatedly take the edge at the current
        // vertex (a convex polygon has two at each vertex: one is the edge it was reached by).
        // The edges not taken are kept at the front, a taken one swapped with the last of them;
        // a polygon has few edges, so the quadratic search is cheap.
        const std::uint32_t start = first[0];
        cycles.items.push_back(start);
        if constexpr (kEdges) cycle_edges->items.push_back(id[0]);
        std::uint32_t current = second[0];
        std::size_t left = n - 1;
        first[0] = first[left], second[0] = second[left];
        if constexpr (kEdges) id[0] = id[left];
        while (current != start && closed) {
          cycles.items.push_back(current);
          closed = false;
          for (std::size_t i = 0; i < left; ++i) {
            if (first[i] != current && second[i] != current) continue;
            if constexpr (kEdges) cycle_edges->items.push_back(id[i]);
            current = first[i] == current ? second[i] : first[i];
            --left;
            first[i] = first[left], second[i] = second[left];
            if constexpr (kEdges) id[i] = id[left];
            closed = true;
            break;
          }
        }
        closed = closed && left == 0;
      }
      close_list(cycles, closed);
      if constexpr (kEdges) close_list(*cycle_edges, closed);
    }
  }
  return cycles;
}

}  // namespace

Ragged polygon_cycles(const CellComplex& cc) { return polygon_cycles<false>(cc, nullptr); }

Ragged oriented_polygon_cycles(const CellComplex& cc, const double* points3) {
  const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2);
  // (the edges of the cycles are only needed to orient some: none of a 3-manifold without boundary)
  const int m = cc.manifold_dimension;
  if (m != 2 && (m != 3 || cell_count(cc, CellKind::boundary, 2) == 0)) return polygon_cycles<false>(cc, nullptr);
  Ragged edges;
  Ragged polygons = polygon_cycles<true>(cc, &edges);
  const std::uint32_t n_edges = cell_count(cc, CellKind::interior, 1) + cell_count(cc, CellKind::boundary, 1);
  if (cc.manifold_dimension == 2) orient_polygons(polygons, edges, n_edges, 0, n2, points3);
  if (cc.manifold_dimension == 3) orient_polygons(polygons, edges, n_edges, n2, polygons.size(), points3);
  return polygons;
}

PolyhedronCursor::PolyhedronCursor(const CellComplex& cc, CellKind kind, const Ragged& polygons, const double* points3,
                                   bool complete)
    : level_(cell_level(cc, kind, 3)),
      kind_(kind),
      polygons_(polygons),
      n2_(cell_count(cc, CellKind::interior, 2)),
      as_listed_(level_ && kind == CellKind::interior && level_->boundary_facet.empty()),
      complete_(complete),
      points3_(points3),
      seen_(level_ ? vertex_count(cc) : 0, 0) {}

bool PolyhedronCursor::load(std::uint32_t c) {
  // (the cells are read in order, their polygons at random: fetched a few cells ahead)
  constexpr std::uint32_t kAhead = 8;
  if (as_listed_ && c + kAhead < size())
    for (std::uint32_t f : level_->facets(c + kAhead)) __builtin_prefetch(&polygons_.offsets[f]);
  if (as_listed_ && c + kAhead / 2 < size())
    for (std::uint32_t f : level_->facets(c + kAhead / 2))
      __builtin_prefetch(polygons_.items.data() + polygons_.offsets[f]);
  if (as_listed_ && c + kAhead / 4 < size())
    for (std::uint32_t f : level_->facets(c + kAhead / 4))
      for (std::uint32_t v : polygons_[f]) {
        __builtin_prefetch(&seen_[v]);
        if (points3_) __builtin_prefetch(points3_ + 3 * std::size_t{v});
      }
  if (as_listed_) {
    faces_ = level_->facets(c);
  } else {
    facets_of(*level_, kind_, c, n2_, listed_faces_);
    faces_ = listed_faces_;
  }
  corners_.clear();
  if (faces_.size() < 4) return false;
  incidences_ = 0;
  for (std::uint32_t f : faces_) {
    const std::uint32_t k = polygons_.offsets[f + 1] - polygons_.offsets[f];
    if (k == 0) return false;
    incidences_ += k;
  }
  // Vertex v's number among the corners, a new one when first met (seen_: the load's stamp and the
  // number, per vertex).
  const std::uint64_t stamp = ++loads_;
  if (complete_) {
    for (std::uint32_t f : faces_)
      for (std::uint32_t v : polygons_[f]) {
        std::uint64_t& seen = seen_[v];
        if (seen >> 32 == stamp) continue;
        seen = stamp << 32;
        corners_.push_back(v);
      }
    // V − E + F = 2 with 2E = the incidences (an edge in two faces each).
    if (2 * (corners_.size() + faces_.size()) != incidences_ + 4 && !closed_by_sorted_edges()) return false;
    sort_few(corners_);
    return true;
  }
  const auto number = [&](std::uint32_t v) {
    std::uint64_t& seen = seen_[v];
    if (seen >> 32 != stamp) {
      const std::uint32_t i = static_cast<std::uint32_t>(corners_.size());
      seen = stamp << 32 | i;
      corners_.push_back(v);
      if (i < 64) once_[i] = twice_[i] = 0;
    }
    return static_cast<std::uint32_t>(seen);
  };
  if (incidences_ > 64) {  // (maybe more than 64 corners, too many for the bit masks below)
    for (std::uint32_t f : faces_)
      for (std::uint32_t v : polygons_[f]) number(v);
    if (!closed_by_sorted_edges()) return false;
  } else {
    // One pass over the faces' cycles: the corners numbered as first met, and every edge counted
    // by those numbers as it goes by (closed: each in exactly two faces).
    for (std::uint32_t f : faces_) {
      const auto cycle = polygons_[f];
      const std::size_t k = cycle.size();
      const std::uint32_t first = number(cycle[0]);
      std::uint32_t a = first;
      for (std::size_t i = 1; i <= k; ++i) {
        const std::uint32_t b = i < k ? number(cycle[i]) : first;
        const std::uint32_t low = std::min(a, b);
        const std::uint64_t bit = std::uint64_t{1} << std::max(a, b);
        a = b;
        if (twice_[low] & bit) return false;
        twice_[low] |= once_[low] & bit;
        once_[low] ^= bit;
      }
    }
    if (!std::all_of(once_, once_ + corners_.size(), [](std::uint64_t edges) { return edges == 0; })) return false;
  }
  sort_few(corners_);
  return true;
}

// The same test for a cell with more than 64 corners: its edges' keys sorted, in pairs.
bool PolyhedronCursor::closed_by_sorted_edges() {
  edges_.clear();
  for (std::uint32_t f : faces_) {
    const auto cycle = polygons_[f];
    const std::size_t k = cycle.size();
    for (std::size_t i = 0; i < k; ++i) edges_.push_back(edge_key(cycle[i], cycle[i + 1 < k ? i + 1 : 0]));
  }
  std::sort(edges_.begin(), edges_.end());
  for (std::size_t i = 0; i < edges_.size(); i += 2)
    if (i + 1 >= edges_.size() || edges_[i] != edges_[i + 1] || (i + 2 < edges_.size() && edges_[i + 2] == edges_[i]))
      return false;
  return true;
}

Ragged polyhedron_faces(const CellComplex& cc, CellKind kind, const Ragged& polygons) {
  Ragged faces;
  PolyhedronCursor cursor(cc, kind, polygons);
  faces.offsets.reserve(std::size_t{cursor.size()} + 1);
  for (std::uint32_t c = 0; c < cursor.size(); ++c)
    faces.push(cursor.load(c) ? cursor.faces() : std::span<const std::uint32_t>{});
  return faces;
}

void orient_polygons(Ragged& polygons, const Ragged& edges, std::uint32_t edge_count, std::uint32_t first,
                     std::uint32_t last, const double* points3) {
  const std::uint32_t n = std::min(last, polygons.size());
  if (n > 0x7FFFFFFFu) throw InputError("more than 2^31 - 1 polygons to orient");
  // Edge → the (at most two) polygons using it and the direction they traverse it, as p << 1 |
  // forward (8 bytes an edge: the breadth-first walk reads them at random). kNone: no such use;
  // kMany in the second: more than two (polygon ids are below 2^31, so neither is a use).
  constexpr std::uint32_t kNone = 0xFFFFFFFFu, kMany = 0xFFFFFFFEu;
  struct Uses {
    std::uint32_t side[2];
  };
  HugeVector<Uses> uses(edge_count, Uses{{kNone, kNone}});  // (big blocks: util/huge_page_allocator.h)
  // The passes below jump around memory (the breadth-first order is spatial, the arrays are in
  // discovery order): what a polygon a few steps ahead will read is prefetched.
  constexpr std::size_t kAhead = 8;
  const auto prefetch_uses = [&](std::uint32_t p) {
    for (std::uint32_t e : edges[p]) __builtin_prefetch(&uses[e]);
  };
  for (std::uint32_t p = first; p < n; ++p) {
    if (p + kAhead < n) prefetch_uses(p + static_cast<std::uint32_t>(kAhead));
    const auto cycle = polygons[p];
    const auto cycle_edges = edges[p];
    for (std::size_t i = 0; i < cycle.size(); ++i) {
      const std::uint32_t a = cycle[i], b = cycle[i + 1 < cycle.size() ? i + 1 : 0];
      Uses& u = uses[cycle_edges[i]];
      const std::uint32_t use = p << 1 | (a < b ? 1u : 0u);
      if (u.side[0] == kNone)
        u.side[0] = use;
      else
        u.side[1] = u.side[1] == kNone ? use : kMany;
    }
  }
  auto reverse = [&](std::uint32_t p) {
    std::reverse(polygons.items.begin() + polygons.offsets[p] + 1, polygons.items.begin() + polygons.offsets[p + 1]);
  };
  HugeVector<std::uint8_t> state(n, 0);  // 0 unvisited, 1 kept, 2 reversed (its component turned outwards)
  HugeVector<std::uint32_t> component;   // breadth-first queue, then the component
  for (std::uint32_t start = first; start < n; ++start) {
    if (state[start] || polygons[start].empty()) continue;
    state[start] = 1;
    component.assign(1, start);
    // With points3: the signed volume of the cone from the origin over the component's fan
    // triangles, summed in the queue's order as each polygon leaves it (its state is then settled).
    double volume = 0;
    for (std::size_t head = 0; head < component.size(); ++head) {
      if (head + kAhead < component.size()) {  // (its edge list first, then, nearer, its uses and points)
        const std::uint32_t ahead = component[head + kAhead];
        __builtin_prefetch(edges.items.data() + edges.offsets[ahead]);
        __builtin_prefetch(polygons.items.data() + polygons.offsets[ahead]);
        __builtin_prefetch(&state[ahead]);
      }
      if (head + kAhead / 2 < component.size()) {
        const std::uint32_t ahead = component[head + kAhead / 2];
        prefetch_uses(ahead);
        if (points3)
          for (std::uint32_t v : polygons[ahead]) __builtin_prefetch(points3 + 3 * std::size_t{v});
      }
      const std::uint32_t p = component[head];
      for (std::uint32_t e : edges[p]) {
        const Uses& u = uses[e];
        if (u.side[1] >= kMany) continue;  // (one use, or more than two)
        const int self = u.side[0] >> 1 == p ? 0 : 1, other = 1 - self;
        const std::uint32_t q = u.side[other] >> 1;
        if (state[q]) continue;
        // Directions as stored; a reversed polygon has its direction flipped. Opposite is wanted.
        const bool p_forward = (u.side[self] & 1) != (state[p] == 2);
        state[q] = p_forward == (u.side[other] & 1) ? 2 : 1;
        component.push_back(q);
      }
      if (!points3) continue;
      // The fan of the cycle as it will be written: a reversed one is read as c0, c(k−1), …, c1.
      const auto cycle = polygons[p];
      const std::size_t k = cycle.size();
      const bool reversed = state[p] == 2;
      const auto at = [&](std::size_t i) { return cycle[reversed && i ? k - i : i]; };
      const double* a = points3 + 3 * static_cast<std::size_t>(cycle[0]);
      for (std::size_t i = 1; i + 1 < k; ++i) {
        const double* b = points3 + 3 * static_cast<std::size_t>(at(i));
        const double* c = points3 + 3 * static_cast<std::size_t>(at(i + 1));
        volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]);
      }
    }
    if (volume < 0)
      for (std::uint32_t p : component) state[p] = static_cast<std::uint8_t>(3 - state[p]);
  }
  // The reversals in the order of the polygons, after the walks: one pass through their lists.
  for (std::uint32_t p = first; p < n; ++p)
    if (state[p] == 2) reverse(p);
}

}  // namespace coxmesh
