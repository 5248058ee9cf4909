// Thesis §4.3; spec §2.4: the cell complex by coface generation, level by level.
#include "coxmesh/cell_complex/cell_complex.h"

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

namespace {

// Facet lists from the incidences (cell << 32) | facet: a counting sort by cell keeps each cell's
// facets in increasing order.
void set_facets(CellLevel& level, const std::vector<std::uint64_t>& incidences) {
  level.facet_offsets.assign(level.size() + 1, 0);
  for (std::uint64_t e : incidences) ++level.facet_offsets[(e >> 32) + 1];
  for (std::uint32_t c = 0; c < level.size(); ++c) level.facet_offsets[c + 1] += level.facet_offsets[c];
  level.facet_ids.resize(incidences.size());
  std::vector<std::uint32_t> fill(level.facet_offsets.begin(), level.facet_offsets.end() - 1);
  for (std::uint64_t e : incidences) level.facet_ids[fill[e >> 32]++] = static_cast<std::uint32_t>(e);
}

// Level j from level j − 1: every l-coface ν of a cell's simplex is a cell, with that cell as facet.
CellLevel next_level(const CellLevel& prev, int d, int l) {
  CellLevel level;
  level.simplices = PackedKeyIndex(packed_words(d));
  level.simplices.reserve(prev.size());
  std::vector<std::uint64_t> incidences;  // (cell << 32) | facet, in discovery order
  CofaceEnumerator cofaces;
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    cofaces.reset(prev.simplices.simplex(c, d), l);
    while (const Simplex* nu = cofaces.next()) {
      const std::uint32_t id = level.simplices.insert(*nu).first;
      incidences.push_back((static_cast<std::uint64_t>(id) << 32) | c);
    }
  }
  set_facets(level, incidences);
  return level;
}

// The same level with `workers` threads: batches of cells have their cofaces enumerated, packed
// and hashed in parallel, then numbered in cell order (hashes known ahead, so the table slots are
// prefetched). Batches bound the extra memory.
CellLevel next_level_parallel(const CellLevel& prev, int d, int l, WorkerPool& pool) {
  constexpr std::uint32_t kChunk = 256, kChunksPerBatch = 64;
  const int words = packed_words(d);
  struct Chunk {
    std::vector<std::uint32_t> keys, facets;
    std::vector<std::uint64_t> hashes;
  };
  CellLevel level;
  level.simplices = PackedKeyIndex(words);
  level.simplices.reserve(prev.size());
  std::vector<std::uint64_t> incidences;
  std::vector<Chunk> chunks(kChunksPerBatch);
  for (std::uint32_t first = 0; first < prev.size(); first += kChunk * kChunksPerBatch) {
    const std::uint32_t last = std::min<std::uint64_t>(prev.size(), std::uint64_t{first} + kChunk * kChunksPerBatch);
    const std::size_t n = (last - first + kChunk - 1) / kChunk;
    pool.run(n, [&](std::size_t t, int) {
      Chunk& out = chunks[t];
      out.keys.clear(), out.facets.clear(), out.hashes.clear();
      CofaceEnumerator cofaces;
      std::uint32_t key[packed_words(kMaxDimension)];
      const std::uint32_t a = first + static_cast<std::uint32_t>(t) * kChunk, b = std::min(last, a + kChunk);
      for (std::uint32_t c = a; c < b; ++c) {
        cofaces.reset(prev.simplices.simplex(c, d), l);
        while (const Simplex* nu = cofaces.next()) {
          pack(*nu, key);
          out.keys.insert(out.keys.end(), key, key + words);
          out.hashes.push_back(hash_words(key, words));
          out.facets.push_back(c);
        }
      }
    });
    constexpr std::size_t kAhead = 8;
    for (std::size_t t = 0; t < n; ++t) {
      const Chunk& in = chunks[t];
      for (std::size_t r = 0; r < in.hashes.size(); ++r) {
        if (r + kAhead < in.hashes.size()) level.simplices.prefetch(in.hashes[r + kAhead]);
        const std::uint32_t id = level.simplices.insert(in.keys.data() + r * words, in.hashes[r]).first;
        incidences.push_back((static_cast<std::uint64_t>(id) << 32) | in.facets[r]);
      }
    }
  }
  set_facets(level, incidences);
  return level;
}

CellLevel make_level(const CellLevel& prev, int d, int l, WorkerPool* pool) {
  return pool ? next_level_parallel(prev, d, l, *pool) : next_level(prev, d, l);
}

}  // namespace

std::size_t CellComplex::bytes() const {
  std::size_t b = (vertices.capacity() + boundary_vertices.capacity()) * sizeof(double);
  for (const auto* levels : {&interior, &boundary})
    for (const CellLevel& l : *levels)
      b += l.simplices.bytes() + 4 * (l.facet_offsets.capacity() + l.facet_ids.capacity() + l.boundary_facet.capacity());
  return b;
}

CellComplex build_cell_complex(TraceResult&& trace, int threads) {
  const int workers = resolve_threads(threads);
  const std::unique_ptr<WorkerPool> pool = workers > 1 ? std::make_unique<WorkerPool>(workers) : nullptr;
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
    cc.interior.push_back(make_level(cc.interior[j - 1], d, k + j, pool.get()));
    if (has_boundary && j <= m - 1) cc.boundary.push_back(make_level(cc.boundary[j - 1], d, k + 1 + j, pool.get()));
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
