// Thesis §4.2: the cell complex of a manifold with corners, one stratum per set of domains.
#include <algorithm>
#include <bit>
#include <map>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/lattice/cofaces.h"

namespace coxmesh {

namespace {

// Level j from level j − 1. A cofacet ν of μ meets the stratum J where μ does (near a point of μ,
// inside ν), and the stratum J \ {i} meets μ itself near every point of the cell (J, μ); each is a
// cell of dimension j (the perturbation is generic), and every facet of a cell is found this way.
CellLevel next_stratified_level(const CellLevel& prev, int d) {
  const int words = stratum_key_words(d);
  CellLevel level;
  level.simplices = PackedKeyIndex(words);
  // (cell, facet) pairs in the order found, facets increasing (prev in order): a counting sort by
  // cell then gives the CSR lists sorted, with no list per cell. No pair comes twice: the cofaces
  // of one simplex differ, and differ from it.
  std::vector<std::uint32_t> cell_of, facet_of;
  std::uint32_t key[stratum_key_words(kMaxDimension)];
  const auto add = [&](const Simplex& nu, std::uint64_t stratum, std::uint32_t facet) {
    pack_stratum_key(nu, stratum, key);
    const auto [id, fresh] = level.simplices.insert(key);
    if (fresh) level.domains.push_back(stratum);
    cell_of.push_back(id), facet_of.push_back(facet);
  };
  CofaceEnumerator cofaces;
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    const Simplex mu = unpack(prev.simplices.key(c), d);
    const std::uint64_t stratum = prev.domains[c];
    if (mu.k < d) {
      cofaces.reset(mu, mu.k + 1);
      while (const Simplex* nu = cofaces.next()) add(*nu, stratum, c);
    }
    for (std::uint64_t rest = stratum; rest != 0; rest &= rest - 1) add(mu, stratum & ~(rest & (~rest + 1)), c);
  }
  level.facet_offsets.assign(level.size() + 1, 0);
  for (std::uint32_t id : cell_of) ++level.facet_offsets[id + 1];
  for (std::uint32_t c = 0; c < level.size(); ++c) level.facet_offsets[c + 1] += level.facet_offsets[c];
  level.facet_ids.resize(cell_of.size());
  std::vector<std::uint32_t> next(level.facet_offsets.begin(), level.facet_offsets.end() - 1);
  for (std::size_t i = 0; i < cell_of.size(); ++i) level.facet_ids[next[cell_of[i]]++] = facet_of[i];
  return level;
}

}  // namespace

CellComplex build_stratified_cell_complex(StrataTraceResult&& trace) {
  CellComplex cc;
  const int d = trace.ambient_dimension, m = d - trace.codimension;
  cc.ambient_dimension = d;
  cc.manifold_dimension = m;
  cc.domain_count = std::max(trace.domain_count, 1);
  cc.interior.resize(1);
  CellLevel& vertices = cc.interior[0];
  vertices.simplices = std::move(trace.vertex_cells);
  vertices.facet_offsets.assign(vertices.size() + 1, 0);
  vertices.domains.resize(vertices.size());
  for (std::uint32_t c = 0; c < vertices.size(); ++c)
    vertices.domains[c] = stratum_of_key(vertices.simplices.key(c), d);
  cc.vertices = std::move(trace.points);
  for (int j = 1; j <= m; ++j) cc.interior.push_back(next_stratified_level(cc.interior[j - 1], d));
  cc.boundary.resize(std::max(m, 0));
  for (CellLevel& l : cc.boundary) l.simplices = PackedKeyIndex(stratum_key_words(d));  // (one key width)
  for (auto* levels : {&cc.interior, &cc.boundary})  // (as build_cell_complex: the keys stay, the tables go)
    for (CellLevel& l : *levels) l.simplices.release_index();
  return cc;
}

std::vector<StratumCount> stratum_counts(const CellComplex& cc) {
  const int m = cc.manifold_dimension;
  std::map<std::uint64_t, StratumCount> strata;
  const auto count = [&](std::uint64_t domains, int j, std::size_t n) {
    if (n == 0) return;
    StratumCount& s = strata[domains];
    s.domains = domains;
    s.dimension = m - std::popcount(domains);
    s.cells.resize(static_cast<std::size_t>(std::max(s.dimension, 0)) + 1, 0);
    if (j <= s.dimension) s.cells[j] += n;
  };
  for (int j = 0; j < static_cast<int>(cc.interior.size()); ++j) {
    const CellLevel& level = cc.interior[j];
    if (level.domains.empty())
      count(0, j, level.size());
    else
      for (std::uint64_t domains : level.domains) count(domains, j, 1);
  }
  for (int j = 0; j < static_cast<int>(cc.boundary.size()); ++j) count(1, j, cc.boundary[j].size());
  std::vector<StratumCount> out;
  for (auto& [domains, s] : strata) out.push_back(std::move(s));
  return out;
}

}  // namespace coxmesh
