// Thesis §4.2: the construction of a level of the cell complex (next_level_plain in
// cell_complex.cpp) as a pipeline of batches over a pool of workers: the same level, numbering
// included, for every number of workers (tests/cell_complex/test_cell_complex.cpp).
#include <algorithm>
#include <atomic>
#include <cstring>

#include "coxmesh/cell_complex/next_level.h"
#include "coxmesh/errors.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/util/fixed_dimension.h"
#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh::cells {

namespace {

// Facet lists from the incidences: the cells found from each facet, facet after facet (`counts`
// of them per facet), in discovery order; a counting sort by cell keeps each cell's facets in
// increasing order. (The facet is where a cell id sits, not a second word beside it: half the
// bytes written and read.) Worker p sorts the p-th range of cells: it
// reads every incidence and skips the other ranges', so no counter is written by two workers. The
// arrays are not zeroed beforehand: each worker writes its own range first (and takes its page
// faults), and the prefix sums are per range, then shifted by the ranges before.
void set_facets(CellLevel& level, std::span<const std::uint32_t> incidences, std::span<const std::uint32_t> counts,
                WorkerPool& pool) {
  const std::uint64_t n = level.size(), parts = static_cast<std::uint64_t>(pool.size());
  const auto lo = [&](std::uint64_t p) { return n * p / parts; };
  const auto for_own_incidences = [&](std::uint64_t p, auto&& f) {
    const std::uint64_t first = lo(p), width = lo(p + 1) - first;
    std::size_t r = 0;
    for (std::uint32_t facet = 0; facet < counts.size(); ++facet)
      for (const std::size_t end = r + counts[facet]; r < end; ++r)
        if (incidences[r] - first < width) f(std::uint64_t{incidences[r]}, facet);
  };
  level.facet_offsets.resize(n + 1);
  level.facet_offsets[0] = 0;
  std::uint32_t* ends = level.facet_offsets.data() + 1;  // ends[c] = offsets[c + 1]
  std::vector<std::uint64_t> totals(parts);
  pool.run(parts, [&](std::size_t p, int) {
    std::fill(ends + lo(p), ends + lo(p + 1), 0u);
    for_own_incidences(p, [&](std::uint64_t c, std::uint32_t) { ++ends[c]; });
    std::uint64_t sum = 0;
    for (std::uint64_t c = lo(p); c < lo(p + 1); ++c) ends[c] = static_cast<std::uint32_t>(sum += ends[c]);
    totals[p] = sum;
  });
  level.facet_ids.resize(incidences.size());
  pool.run(parts, [&](std::size_t p, int) {
    std::uint64_t base = 0;
    for (std::size_t q = 0; q < p; ++q) base += totals[q];
    std::vector<std::uint32_t> next(lo(p + 1) - lo(p));  // where the next facet of each cell goes
    for (std::uint64_t c = lo(p); c < lo(p + 1); ++c)    // (a cell starts where the one before ends)
      next[c - lo(p)] = static_cast<std::uint32_t>(c == lo(p) ? base : ends[c - 1] + base);
    for (std::uint64_t c = lo(p); c < lo(p + 1); ++c) ends[c] += static_cast<std::uint32_t>(base);
    for_own_incidences(p, [&](std::uint64_t c, std::uint32_t facet) { level.facet_ids[next[c - lo(p)]++] = facet; });
  });
}

}  // namespace

// next_level_plain (cell_complex.cpp) in a pipeline. The cells of level j − 1 go in batches of
// chunks, in three stages: the cofaces of each chunk are enumerated, packed and hashed (a task per
// chunk); the batch is numbered, inserting its cofaces into the index in order (one task: the only
// serial step); its incidences are written out (a task per chunk). A parallel round numbers batch b
// while it enumerates batch b + 1 and writes out batch b − 1, with three sets of buffers; the
// numbering starts at once, on the core that enumerated the batch. The result is the same for any
// number of workers; batches bound the extra memory.
CellLevel next_level_pipelined(const CellLevel& prev, int d, int l, WorkerPool& pool) {
  // Batches of up to 8192 cells, and at most 1/32 of the level: the three sets of buffers stay a
  // small part of the memory of the complex.
  constexpr std::uint32_t kChunk = 256, kMaxChunksPerBatch = 32;
  const std::uint32_t chunks_per_batch = std::clamp<std::uint32_t>(prev.size() / (32 * kChunk), 1, kMaxChunksPerBatch);
  const std::uint32_t batch_cells = kChunk * chunks_per_batch;
  const int words = packed_words(d);
  // Level j's simplices are the cofacets of level j − 1's (l = k + j, those have dimension l − 1).
  COXMESH_ASSERT(prev.size() == 0 || prev.simplices.simplex(0, d).k + 1 == l);
  // (padded: neighbouring chunks are filled by different workers; the arrays grow per cell and are
  // written in full after each resize, so they are not zeroed first: a memset call per cell)
  struct alignas(64) Chunk {
    UninitializedHugeVector<std::uint32_t> keys, ids;
    UninitializedHugeVector<std::uint64_t> hashes;
    std::size_t offset = 0;  // of its incidences
  };
  CellLevel level;
  level.simplices = PackedKeyIndex(words);
  level.simplices.reserve_keys(prev.size());  // (its table is sized below, from batch 0: its pages are written at once)
  IndexArray incidences;                      // the cells found from each cell of prev, in discovery order
  IndexArray counts(prev.size());             // how many (its cofacets), per cell of prev
  std::vector<Chunk> buffers[3];
  for (auto& b : buffers) b.resize(chunks_per_batch);
  const std::int64_t batches = (prev.size() + batch_cells - 1) / batch_cells;
  const auto chunks_of = [&](std::int64_t batch) -> std::size_t {
    if (batch < 0 || batch >= batches) return 0;
    return (std::min<std::uint64_t>(prev.size(), (batch + 1) * batch_cells) - batch * batch_cells + kChunk - 1) /
           kChunk;
  };
  const auto enumerate = [&](std::int64_t batch, std::size_t t) {
    Chunk& out = buffers[batch % 3][t];
    out.keys.clear(), out.hashes.clear();
    const std::uint32_t a = static_cast<std::uint32_t>(batch * batch_cells + t * kChunk);
    const std::uint32_t b = std::min(prev.size(), a + kChunk);
    // (d fixed at compile time for the common d, once per chunk: the loops over d and the words
    // unroll; for d = 6 and 9 too: the complex of T³ ⊂ R⁶ and SO(3) ⊂ R⁹ 2-13 % less CPU time)
    with_fixed_dimension<2, 3, 4, 6, 9>(d, [&](auto fixed_d) {
      constexpr int kD = decltype(fixed_d)::value;
      const int key_words = kD != 0 ? packed_words(kD) : words;
      for (std::uint32_t c = a; c < b; ++c) {  // (straight from the packed keys, into arrays grown once per cell)
        const PackedCofacets<kD> cofacets(prev.simplices.key(c), d);
        const std::size_t first = out.hashes.size(), count = cofacets.count();
        out.keys.resize((first + count) * key_words), out.hashes.resize(first + count);
        counts[c] = static_cast<std::uint32_t>(count);
        std::uint32_t* keys = out.keys.data() + first * key_words;
        std::uint64_t* hashes = out.hashes.data() + first;
        cofacets.for_each([&](const std::uint32_t* nu, std::uint64_t hash) {
          // (four words at a time: a loop of single words was an eighth of the enumeration's samples)
          int i = 0;
          for (; i + 4 <= key_words; i += 4) std::memcpy(keys + i, nu + i, 4 * sizeof(std::uint32_t));
          for (; i < key_words; ++i) keys[i] = nu[i];
          keys += key_words;
          *hashes++ = hash;
        });
      }
    });
    out.ids.resize(out.hashes.size());
  };
  std::vector<KeyRun> runs;
  const auto number = [&](std::int64_t batch) {
    runs.clear();
    for (std::size_t t = 0; t < chunks_of(batch); ++t) {
      Chunk& c = buffers[batch % 3][t];
      runs.push_back({c.keys.data(), c.hashes.data(), c.hashes.size(), c.ids.data()});
    }
    level.simplices.insert_runs(runs);
  };
  const auto write_out = [&](std::int64_t batch, std::size_t t) {
    const Chunk& in = buffers[batch % 3][t];
    for (std::size_t r = 0; r < in.ids.size(); ++r) incidences[in.offset + r] = in.ids[r] & ~PackedKeyIndex::kNewBit;
  };
  for (std::int64_t round = 0; round <= batches + 1; ++round) {
    const std::int64_t numbered = round - 1, written = round - 2;
    if (written == 0) {  // room for the whole level at batch 0's rate: no copies as it grows
      std::size_t occurrences = 0;
      for (std::size_t t = 0; t < chunks_of(0); ++t) occurrences += buffers[0][t].ids.size();
      const std::size_t cells0 = std::min(prev.size(), batch_cells);
      incidences.reserve(occurrences * prev.size() / cells0 * 9 / 8);
      // (the index at batch 0's rate too: it comes out slightly above the level's size)
      const std::size_t cells = std::size_t{level.simplices.size()} * prev.size() / cells0;
      if (batches > 2) level.simplices.reserve(std::min<std::size_t>(cells, PackedKeyIndex::kMaxEntries));
    }
    if (numbered == 0) {  // room for batch 0's keys, each new at worst
      std::size_t occurrences = 0;
      for (std::size_t t = 0; t < chunks_of(0); ++t) occurrences += buffers[0][t].ids.size();
      level.simplices.reserve_table(std::min<std::size_t>(occurrences, PackedKeyIndex::kMaxEntries));
    }
    for (std::size_t t = 0; t < chunks_of(written); ++t) {
      Chunk& c = buffers[written % 3][t];
      c.offset = incidences.size();
      incidences.resize(incidences.size() + c.ids.size());
    }
    // One lane per worker: the numbering lane numbers, then helps with the chunks. Lanes are taken
    // in order, lane 0 by the calling thread as a rule, so with the numbering lane turning round by
    // round a batch is mostly numbered by the worker that enumerated it: its keys are in that
    // core's caches (numbering them on the other core costs more: docs/benchmarks.md).
    const std::size_t n_enumerate = chunks_of(round), n_chunks = n_enumerate + chunks_of(written);
    const std::size_t lanes = static_cast<std::size_t>(pool.size());
    const std::size_t numbering_lane = static_cast<std::size_t>(round) % lanes;
    std::atomic<std::size_t> next_chunk{0};
    pool.run(lanes, [&](std::size_t lane, int) {
      if (lane == numbering_lane && chunks_of(numbered) > 0) number(numbered);
      for (std::size_t t; (t = next_chunk.fetch_add(1)) < n_chunks;)
        t < n_enumerate ? enumerate(round, t) : write_out(written, t - n_enumerate);
    });
  }
  set_facets(level, incidences, counts, pool);
  return level;
}

// Each worker takes a range of the cofacets, and enumerates the cofacets of each first facet in the
// range once, keeping the keys of the places named (in increasing order per facet).
CellLevel level_from_walk(WalkedCofacets&& walked, const CellLevel& vertices, int d, WorkerPool& pool) {
  const std::size_t n = walked.size(), words = static_cast<std::size_t>(packed_words(d));
  COXMESH_ASSERT(walked.facet_offsets.size() == n + 1 && walked.facet_ids.size() == walked.facet_offsets[n]);
  UninitializedHugeVector<std::uint32_t> keys(n * words);
  const std::size_t parts = static_cast<std::size_t>(pool.size());
  const auto first_facet = [&](std::size_t c) { return walked.facet_ids[walked.facet_offsets[c]]; };
  pool.run(parts, [&](std::size_t p, int) {
    with_fixed_dimension<2, 3, 4, 6, 9>(d, [&](auto fixed_d) {
      constexpr int kD = decltype(fixed_d)::value;
      const std::size_t end = n * (p + 1) / parts;
      for (std::size_t c = n * p / parts; c < end;) {
        const std::uint32_t tau = first_facet(c);
        std::size_t group_end = c;
        while (group_end < end && first_facet(group_end) == tau) ++group_end;
        std::size_t next = c;  // (of the group)
        std::uint32_t place = 0;
        PackedCofacets<kD>(vertices.simplices.key(tau), d).for_each([&](const std::uint32_t* nu, std::uint64_t) {
          if (next < group_end && walked.places[next] == place) std::copy_n(nu, words, keys.data() + next++ * words);
          ++place;
        });
        if (next != group_end)
          throw std::logic_error("level_from_walk: a cofacet's place is past its facet's cofacets");
        c = group_end;
      }
    });
  });
  CellLevel level;
  level.simplices = PackedKeyIndex::from_keys(static_cast<int>(words), std::move(keys));
  level.facet_offsets = std::move(walked.facet_offsets);
  level.facet_ids = std::move(walked.facet_ids);
  return level;
}

}  // namespace coxmesh::cells
