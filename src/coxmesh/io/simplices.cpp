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
  for (std::uint32_t c = n2; c < polygons.size(); ++c) {
    if (polygons[c].empty()) ++s.skipped;
    for_each_fan_triangle(polygons[c], add_triangle(s.boundary));
  }
  return s;
}

}  // namespace coxmesh
