// The cell complex as simplices; see simplices.h.
#include "coxmesh/io/simplices.h"

#include <string>
#include <unordered_map>

#include "coxmesh/errors.h"

namespace coxmesh {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// Edges of a 1-manifold turned head to tail: each vertex in two edges is the head of one and the
// tail of the other (walk along each component from an end or from any edge of a closed curve).
void orient_curve_edges(std::vector<std::uint32_t>& edges, std::uint32_t vertices) {
  const std::size_t n = edges.size() / 2;
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::uint32_t> at(2 * static_cast<std::size_t>(vertices), kNone);  // two edges per vertex
  for (std::uint32_t e = 0; e < n; ++e)
    for (int s = 0; s < 2; ++s) {
      std::uint32_t* slot = &at[2 * static_cast<std::size_t>(edges[2 * e + s])];
      slot[slot[0] == kNone ? 0 : 1] = e;
    }
  std::vector<bool> done(n, false);
  auto walk = [&](std::uint32_t e, std::uint32_t tail) {
    while (e != kNone && !done[e]) {
      done[e] = true;
      if (edges[2 * e] != tail) std::swap(edges[2 * e], edges[2 * e + 1]);
      const std::uint32_t head = edges[2 * e + 1];
      const std::uint32_t* slot = &at[2 * static_cast<std::size_t>(head)];
      e = slot[0] == e ? slot[1] : slot[0];
      tail = head;
    }
  };
  for (std::uint32_t v = 0; v < vertices; ++v)  // open curves first, from an end
    if (at[2 * static_cast<std::size_t>(v)] != kNone && at[2 * static_cast<std::size_t>(v) + 1] == kNone)
      walk(at[2 * static_cast<std::size_t>(v)], v);
  for (std::uint32_t e = 0; e < n; ++e) walk(e, edges[2 * e]);
}

// Tetrahedra turned coherently: two sharing a triangle induce opposite orientations on it
// (breadth-first over the shared triangles; on a non-orientable 3-manifold the first choice wins),
// then each connected component turned so that its volume in points3 is positive.
void orient_tetrahedra(std::vector<std::uint32_t>& tets, const double* p3) {
  const std::size_t n = tets.size() / 4;
  struct Face {
    std::uint32_t v[3], tet;
    bool odd;  // the orientation the tetrahedron induces on it, relative to the sorted order
  };
  std::vector<Face> faces;
  faces.reserve(4 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int i = 0; i < 4; ++i) {  // ∂[v0 v1 v2 v3] = Σ (−1)^i [v0 … v̂i … v3]
      Face f{{0, 0, 0}, static_cast<std::uint32_t>(t), (i % 2) == 1};
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) f.v[k++] = tets[4 * t + j];
      for (int a = 0; a < 3; ++a)  // sort, counting transpositions
        for (int b = 0; b + 1 < 3 - a; ++b)
          if (f.v[b] > f.v[b + 1]) std::swap(f.v[b], f.v[b + 1]), f.odd = !f.odd;
      faces.push_back(f);
    }
  std::sort(faces.begin(), faces.end(),
            [](const Face& a, const Face& b) { return std::lexicographical_compare(a.v, a.v + 3, b.v, b.v + 3); });
  // Neighbours across each triangle shared by exactly two tetrahedra, and whether, as stored, the
  // two induce the same orientation on it (then one of them must turn).
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::uint32_t> neighbour(4 * n, kNone);
  std::vector<std::uint8_t> same(4 * n, 0), used(n, 0);
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && std::equal(faces[i].v, faces[i].v + 3, faces[j].v)) ++j;
    if (j == i + 2) {
      const Face &a = faces[i], &b = faces[i + 1];
      if (a.tet != b.tet && used[a.tet] < 4 && used[b.tet] < 4) {
        const std::size_t sa = 4 * static_cast<std::size_t>(a.tet) + used[a.tet]++;
        const std::size_t sb = 4 * static_cast<std::size_t>(b.tet) + used[b.tet]++;
        neighbour[sa] = b.tet, neighbour[sb] = a.tet;
        same[sa] = same[sb] = a.odd == b.odd ? 1 : 0;
      }
    }
    i = j;
  }
  std::vector<std::uint8_t> state(n, 0);  // 0 unvisited, 1 kept, 2 turned
  std::vector<std::uint32_t> queue;
  for (std::size_t start = 0; start < n; ++start) {
    if (state[start]) continue;
    state[start] = 1;
    queue.assign(1, static_cast<std::uint32_t>(start));
    double volume = 0;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::uint32_t t = queue[head];
      const bool turned = state[t] == 2;
      if (p3) {
        const double v = tetrahedron_volume6(p3, tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]);
        volume += turned ? -v : v;
      }
      for (int k = 0; k < 4; ++k) {
        const std::uint32_t u = neighbour[4 * static_cast<std::size_t>(t) + k];
        if (u == kNone || state[u]) continue;
        state[u] = (turned != (same[4 * static_cast<std::size_t>(t) + k] != 0)) ? 2 : 1;
        queue.push_back(u);
      }
    }
    const bool turn_all = volume < 0;
    for (std::uint32_t t : queue)
      if ((state[t] == 2) != turn_all)
        std::swap(tets[4 * static_cast<std::size_t>(t) + 2], tets[4 * static_cast<std::size_t>(t) + 3]);
  }
}

}  // namespace

double tetrahedron_volume6(const double* p3, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t e) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = p3[3 * static_cast<std::size_t>(b) + i] - p3[3 * static_cast<std::size_t>(a) + i];
    v[i] = p3[3 * static_cast<std::size_t>(c) + i] - p3[3 * static_cast<std::size_t>(a) + i];
    w[i] = p3[3 * static_cast<std::size_t>(e) + i] - p3[3 * static_cast<std::size_t>(a) + i];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

Simplices simplicial_complex(const CellComplex& cc, std::span<const double> points3) {
  const int m = cc.manifold_dimension;
  if (m > 3)
    throw InputError("simplices: only curves, surfaces and 3-manifolds are split into simplices; this is a " +
                     std::to_string(m) + "-manifold");
  const double* p3 = points3.empty() ? nullptr : points3.data();
  const std::uint32_t n0 = cell_count(cc, CellKind::interior, 0), nv = vertex_count(cc);
  Simplices s;
  s.dimension = m;
  if (m == 0) {
    for (std::uint32_t v = 0; v < n0; ++v) s.interior.push_back(v);
    return s;
  }
  if (m == 1) {
    const Ragged ends = edge_ends(cc, CellKind::interior);
    for (std::uint32_t c = 0; c < ends.size(); ++c)
      if (ends[c].size() == 2) {
        s.interior.insert(s.interior.end(), ends[c].begin(), ends[c].end());
      } else {
        ++s.skipped;
      }
    orient_curve_edges(s.interior, nv);
    for (std::uint32_t v = n0; v < nv; ++v) s.boundary.push_back(v);
    return s;
  }
  const Ragged polygons = oriented_polygon_cycles(cc, p3);
  const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2);
  auto add_triangle = [](std::vector<std::uint32_t>& out) {
    return [&out](std::uint32_t a, std::uint32_t b, std::uint32_t c) { out.insert(out.end(), {a, b, c}); };
  };
  if (m == 2) {
    for (std::uint32_t c = 0; c < n2; ++c) {
      if (polygons[c].empty()) ++s.skipped;
      for_each_fan_triangle(polygons[c], add_triangle(s.interior));
    }
    // Boundary edges in the direction in which their polygon runs along them.
    const Ragged ends = edge_ends(cc, CellKind::boundary);
    std::unordered_map<std::uint64_t, std::uint32_t> index;  // edge → position in s.boundary
    for (std::uint32_t c = 0; c < ends.size(); ++c)
      if (ends[c].size() == 2) {
        index.emplace(edge_key(ends[c][0], ends[c][1]), static_cast<std::uint32_t>(s.boundary.size()));
        s.boundary.insert(s.boundary.end(), ends[c].begin(), ends[c].end());
      } else {
        ++s.skipped;
      }
    for (std::uint32_t c = 0; !index.empty() && c < n2; ++c) {
      const auto cycle = polygons[c];
      for (std::size_t i = 0; i < cycle.size(); ++i) {
        const std::uint32_t a = cycle[i], b = cycle[(i + 1) % cycle.size()];
        const auto it = index.find(edge_key(a, b));
        if (it != index.end()) {
          s.boundary[it->second] = a;
          s.boundary[it->second + 1] = b;
        }
      }
    }
    return s;
  }
  for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
    const Ragged faces = polyhedron_faces(cc, kind, polygons);
    for (std::uint32_t c = 0; c < faces.size(); ++c) {
      if (faces[c].empty()) ++s.skipped;
      if (kind == CellKind::interior)
        for_each_cone_tetrahedron(faces[c], polygons, p3,
                                  [&s](std::uint32_t a, std::uint32_t b, std::uint32_t c2, std::uint32_t e) {
                                    s.interior.insert(s.interior.end(), {a, b, c2, e});
                                  });
    }
  }
  orient_tetrahedra(s.interior, p3);
  for (std::uint32_t c = n2; c < polygons.size(); ++c) {
    if (polygons[c].empty()) ++s.skipped;
    for_each_fan_triangle(polygons[c], add_triangle(s.boundary));
  }
  return s;
}

}  // namespace coxmesh
