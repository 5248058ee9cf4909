// Thesis §4.3; spec §2.4: the cell complex by coface generation, level by level.
#include "coxmesh/cell_complex/cell_complex.h"

#include "coxmesh/lattice/cofaces.h"

namespace coxmesh {

namespace {

// Level j from level j − 1: every l-coface ν of a cell's simplex is a cell, with that cell as facet.
CellLevel next_level(const CellLevel& prev, int d, int l) {
  CellLevel level;
  level.simplices = PackedKeyIndex(packed_words(d));
  level.simplices.reserve(prev.size());
  std::vector<std::uint64_t> incidences;  // (cell << 32) | facet, in discovery order
  CofaceEnumerator cofaces;
  Simplex mu, nu;
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    mu = prev.simplices.simplex(c, d);
    cofaces.reset(mu, l);
    while (cofaces.next(nu)) {
      const std::uint32_t id = level.simplices.insert(nu).first;
      incidences.push_back((static_cast<std::uint64_t>(id) << 32) | c);
    }
  }
  // Counting sort by cell keeps each cell's facets in increasing order.
  level.facet_offsets.assign(level.size() + 1, 0);
  for (std::uint64_t e : incidences) ++level.facet_offsets[(e >> 32) + 1];
  for (std::uint32_t c = 0; c < level.size(); ++c) level.facet_offsets[c + 1] += level.facet_offsets[c];
  level.facet_ids.resize(incidences.size());
  std::vector<std::uint32_t> fill(level.facet_offsets.begin(), level.facet_offsets.end() - 1);
  for (std::uint64_t e : incidences) level.facet_ids[fill[e >> 32]++] = static_cast<std::uint32_t>(e);
  return level;
}

}  // namespace

std::size_t CellComplex::bytes() const {
  std::size_t b = (vertices.capacity() + boundary_vertices.capacity()) * sizeof(double);
  for (const auto* levels : {&interior, &boundary})
    for (const CellLevel& l : *levels)
      b += l.simplices.bytes() + 4 * (l.facet_offsets.capacity() + l.facet_ids.capacity() + l.boundary_facet.capacity());
  return b;
}

CellComplex build_cell_complex(TraceResult&& trace) {
  CellComplex cc;
  const int d = trace.ambient_dimension, k = trace.codimension, m = d - k;
  cc.ambient_dimension = d;
  cc.manifold_dimension = m;
  const bool has_boundary = trace.boundary_simplices.size() > 0;
  cc.interior.resize(1);
  cc.interior[0].simplices = std::move(trace.simplices);
  cc.interior[0].facet_offsets.assign(cc.interior[0].size() + 1, 0);
  cc.vertices = std::move(trace.points);
  if (m >= 1) {
    cc.boundary.resize(1);
    cc.boundary[0].simplices = std::move(trace.boundary_simplices);
    cc.boundary[0].facet_offsets.assign(cc.boundary[0].size() + 1, 0);
    cc.boundary_vertices = std::move(trace.boundary_points);
  }
  for (int j = 1; j <= m; ++j) {
    cc.interior.push_back(next_level(cc.interior[j - 1], d, k + j));
    if (has_boundary && j <= m - 1) cc.boundary.push_back(next_level(cc.boundary[j - 1], d, k + 1 + j));
  }
  if (!has_boundary) cc.boundary.resize(std::max(m, 0));  // empty levels, uniform shape
  if (has_boundary)
    for (int j = 1; j <= m; ++j) {
      CellLevel& level = cc.interior[j];
      level.boundary_facet.assign(level.size(), CellLevel::kNone);
      std::uint32_t key[packed_words(kMaxDimension)];
      for (std::uint32_t c = 0; c < level.size(); ++c) {
        std::copy(level.simplices.key(c), level.simplices.key(c) + packed_words(d), key);
        level.boundary_facet[c] = cc.boundary[j - 1].simplices.find(key);
      }
    }
  for (auto& l : cc.boundary)
    if (l.simplices.words() != packed_words(d)) l.simplices = PackedKeyIndex(packed_words(d));
  return cc;
}

}  // namespace coxmesh
