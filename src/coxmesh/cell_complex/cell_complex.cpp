// Thesis §4.2: the cell complex by coface generation, level by level.
#include "coxmesh/cell_complex/cell_complex.h"

#include <algorithm>

#include "coxmesh/cell_complex/next_level.h"
#include "coxmesh/lattice/cofaces.h"

namespace coxmesh {

namespace cells {

// Level j from level j − 1 (thesis §4.2): every l-coface ν of a cell's simplex is a cell, with
// that cell as a facet; cells are numbered in order of discovery, cell by cell of level j − 1, so
// each cell's facets come in increasing order.
CellLevel next_level_plain(const CellLevel& prev, int d, int l) {
  CellLevel level;
  level.simplices = PackedKeyIndex(packed_words(d));
  std::vector<std::vector<std::uint32_t>> facets;  // per cell of level j
  CofaceEnumerator cofaces;
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    cofaces.reset(prev.simplices.simplex(c, d), l);
    while (const Simplex* nu = cofaces.next()) {
      const auto [id, fresh] = level.simplices.insert(*nu);
      if (fresh) facets.emplace_back();
      facets[id].push_back(c);
    }
  }
  level.facet_offsets.assign(1, 0);
  for (const std::vector<std::uint32_t>& f : facets) {
    level.facet_ids.insert(level.facet_ids.end(), f.begin(), f.end());
    level.facet_offsets.push_back(static_cast<std::uint32_t>(level.facet_ids.size()));
  }
  return level;
}

}  // namespace cells

std::size_t CellComplex::bytes() const {
  std::size_t b = held_bytes(vertices) + held_bytes(boundary_vertices);
  for (const auto* levels : {&interior, &boundary})
    for (const CellLevel& l : *levels)
      b += l.simplices.bytes() + held_bytes(l.facet_offsets) + held_bytes(l.facet_ids) + held_bytes(l.boundary_facet) +
           l.domains.capacity() * sizeof(std::uint64_t);
  return b;
}

CellComplex build_cell_complex(TraceResult&& trace, int threads, bool keep_keys) {
  const int workers = resolve_threads(threads);
  WorkerPool pool(workers);
  CellComplex cc;
  const int d = trace.ambient_dimension, k = trace.codimension, m = d - k;
  cc.ambient_dimension = d;
  cc.manifold_dimension = m;
  const bool has_boundary = trace.boundary_simplices.size() > 0;
  cc.interior.resize(1);
  cc.interior[0].simplices = std::move(trace.simplices);
  // (no interior cell is looked up once its level is built: each level's table goes at once, its
  // pages to the next level; a boundary level's serves the boundary facets of the level above)
  cc.interior[0].simplices.release_index();
  cc.interior[0].facet_offsets.assign(cc.interior[0].size() + 1, 0);
  cc.vertices = std::move(trace.points);
  if (m >= 1) {
    cc.boundary.resize(1);
    cc.boundary[0].simplices = std::move(trace.boundary_simplices);
    cc.boundary[0].facet_offsets.assign(cc.boundary[0].size() + 1, 0);
    cc.boundary_vertices = std::move(trace.boundary_points);
  }
  // (keys dropped early give their pages to the next levels and the topology: fewer page faults,
  // a lower peak)
  const auto drop_keys = [](CellLevel& level) { level.simplices = PackedKeyIndex::without_keys(level.size()); };
  for (int j = 1; j <= m; ++j) {
    if (j == 1 && !trace.cofacets.empty())  // (met by the walk, numbered as the pipeline numbers them)
      cc.interior.push_back(cells::level_from_walk(std::move(trace.cofacets), cc.interior[0], d, pool));
    else
      cc.interior.push_back(cells::next_level_pipelined(cc.interior[j - 1], d, k + j, pool));
    cc.interior[j].simplices.release_index();
    if (has_boundary && j <= m - 1)
      cc.boundary.push_back(cells::next_level_pipelined(cc.boundary[j - 1], d, k + 1 + j, pool));
    if (has_boundary) {  // the boundary facet of each cell of level j, in boundary level j − 1
      CellLevel& level = cc.interior[j];
      level.boundary_facet.resize(level.size());
      const std::size_t n = level.size(), parts = static_cast<std::size_t>(pool.size());
      pool.run(parts, [&](std::size_t p, int) {
        for (std::size_t c = n * p / parts; c < n * (p + 1) / parts; ++c)
          level.boundary_facet[c] =
              cc.boundary[j - 1].simplices.find(level.simplices.key(static_cast<std::uint32_t>(c)));
      });
    }
    if (!keep_keys) {
      drop_keys(cc.interior[j - 1]);
      if (has_boundary) drop_keys(cc.boundary[j - 1]);
    } else if (has_boundary) {
      cc.boundary[j - 1].simplices.release_index();
    }
  }
  if (!has_boundary) cc.boundary.resize(std::max(m, 0));  // empty levels, uniform shape
  if (!keep_keys) {
    for (auto* levels : {&cc.interior, &cc.boundary})
      for (CellLevel& l : *levels) drop_keys(l);
    return cc;
  }
  for (auto& l : cc.boundary)
    if (l.simplices.words() != packed_words(d)) l.simplices = PackedKeyIndex(packed_words(d));
  // The keys stay (files, tests); the last tables go (with the others, a quarter to a third of the
  // complex's memory, e.g. 176 MB of SO(3) ⊂ R⁹ at edge 1.1).
  for (auto* levels : {&cc.interior, &cc.boundary})
    for (CellLevel& l : *levels) l.simplices.release_index();
  return cc;
}

std::size_t estimated_bytes_per_simplex(int m) {
  constexpr std::size_t kBytesPerCell = 220;
  constexpr std::size_t kCellsPerSimplex[] = {1, 2, 6, 16, 62};
  std::size_t cells = kCellsPerSimplex[std::clamp(m, 0, 4)];
  for (int j = 4; j < m && cells < (std::size_t{1} << 40); ++j) cells *= 4;
  return kBytesPerCell * cells;
}

}  // namespace coxmesh
