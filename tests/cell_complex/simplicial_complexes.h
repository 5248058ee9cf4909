// Simplicial complexes written out by hand, as cell complexes (every face a cell): spheres, the
// torus and the Klein bottle, RP², and unions of them, for the topology's tests.
#pragma once

#include <algorithm>
#include <map>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh::hand_written {

using Simplex_ = std::vector<int>;

// The closed cell complex of the simplicial complex spanned by `top` (simplices of one dimension
// m, as vertex lists): every face a cell, interior cells only. The ambient simplices are not set:
// the topology reads only the incidences.
inline CellComplex simplicial_complex(const std::vector<Simplex_>& top) {
  const int m = static_cast<int>(top.front().size()) - 1;
  std::vector<std::map<Simplex_, std::uint32_t>> ids(m + 1);
  std::vector<std::vector<Simplex_>> cells(m + 1);
  for (Simplex_ s : top) {
    std::sort(s.begin(), s.end());
    for (unsigned mask = 1; mask < (1u << s.size()); ++mask) {
      Simplex_ face;
      for (std::size_t i = 0; i < s.size(); ++i)
        if (mask >> i & 1) face.push_back(s[i]);
      const int j = static_cast<int>(face.size()) - 1;
      if (ids[j].emplace(face, static_cast<std::uint32_t>(cells[j].size())).second) cells[j].push_back(face);
    }
  }
  CellComplex cc;
  cc.manifold_dimension = m;
  cc.interior.resize(m + 1);
  for (int j = 0; j <= m; ++j) {
    CellLevel& level = cc.interior[j];
    level.simplices.append_unindexed(cells[j].size());
    level.facet_offsets.assign(1, 0);
    for (const Simplex_& c : cells[j]) {
      for (std::size_t i = 0; j > 0 && i < c.size(); ++i) {
        Simplex_ facet = c;
        facet.erase(facet.begin() + static_cast<std::ptrdiff_t>(i));
        level.facet_ids.push_back(ids[j - 1].at(facet));
      }
      level.facet_offsets.push_back(static_cast<std::uint32_t>(level.facet_ids.size()));
    }
  }
  for (int j = 0; j < m; ++j) {
    cc.boundary.emplace_back();
    cc.boundary.back().facet_offsets.assign(1, 0);
  }
  return cc;
}

// The boundary of the (m+1)-simplex on vertices first..first+m+1: an m-sphere.
inline std::vector<Simplex_> sphere_boundary(int m, int first) {
  std::vector<Simplex_> top;
  for (int skip = 0; skip <= m + 1; ++skip) {
    Simplex_ s;
    for (int v = 0; v <= m + 1; ++v)
      if (v != skip) s.push_back(first + v);
    top.push_back(s);
  }
  return top;
}

// A 3 × 3 grid of squares, each cut in two triangles, with opposite sides glued: straight for the
// torus, the second pair reversed for the Klein bottle (9 vertices, 18 triangles).
inline std::vector<Simplex_> glued_grid(bool twist) {
  auto vertex = [&](int i, int j) {  // i, j in 0..3
    if (i == 3) i = 0, j = twist ? (3 - j) % 3 : j;
    return i * 3 + j % 3;
  };
  std::vector<Simplex_> top;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      top.push_back({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
      top.push_back({vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1)});
    }
  return top;
}

// RP² with 6 vertices and 10 triangles (the hemi-icosahedron).
inline const std::vector<Simplex_> kProjectivePlane = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                                                       {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};

inline std::vector<Simplex_> join(std::vector<Simplex_> a, const std::vector<Simplex_>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace coxmesh::hand_written
