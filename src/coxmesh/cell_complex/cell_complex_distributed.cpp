// Thesis §4.2 over several processes: each level of the cell complex from this rank's part of the
// level below, numbered as next_level_plain numbers it (cell_complex.cpp).
#include "coxmesh/cell_complex/cell_complex_distributed.h"

#include <algorithm>
#include <numeric>

#include "coxmesh/lattice/cofaces.h"

namespace coxmesh {

namespace {

int owner_of(const std::uint32_t* key, int d, int ranks) {
  return owner_rank(reinterpret_cast<const std::int32_t*>(key), d, ranks);  // (y, the minimal vertex, first)
}

// The global ids of new cells from their smallest discovery keys g << 32 | s (g < n, the global id
// of a cell of the level below; keys distinct): a key's rank among every rank's keys. Without
// gathering the keys anywhere: a key goes to the rank that holds g's range (the ranks split [0, n)
// into contiguous ranges in rank order), which sorts what it receives and adds the keys of the
// ranges before its own (a prefix sum of one count per rank); the ids come back in the order sent.
std::uint64_t number_by_keys(const std::vector<std::uint64_t>& keys, std::uint64_t n, Communicator& comm,
                             std::vector<std::uint32_t>& ids) {
  const int ranks = comm.size();
  const auto range_of = [&](std::uint64_t key) { return static_cast<int>((key >> 32) * ranks / n); };
  std::vector<std::vector<std::byte>> out(ranks);
  for (const std::uint64_t& key : keys) put(out[range_of(key)], &key, 1);
  std::vector<std::size_t> counts;
  const std::vector<std::byte> in = comm.exchange(out, counts);
  const std::vector<std::size_t> from = counts;  // bytes of keys from each rank
  out.assign(ranks, {});
  std::vector<std::uint64_t> received(in.size() / sizeof(std::uint64_t));
  const std::byte* at = in.data();
  take(at, received.data(), received.size());
  std::vector<std::uint64_t> sorted = received;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::byte> mine;
  const std::uint64_t here = sorted.size();
  put(mine, &here, 1);
  const std::vector<std::byte> totals_bytes = comm.all_gather(mine, counts);
  std::vector<std::uint64_t> totals(ranks);
  at = totals_bytes.data();
  take(at, totals.data(), totals.size());
  const std::uint64_t offset = std::accumulate(totals.begin(), totals.begin() + comm.rank(), std::uint64_t{0});
  std::size_t next = 0;
  for (int r = 0; r < ranks; ++r)
    for (std::size_t i = 0; i < from[r] / sizeof(std::uint64_t); ++i) {
      const auto place = std::lower_bound(sorted.begin(), sorted.end(), received[next++]) - sorted.begin();
      const auto id = static_cast<std::uint32_t>(offset + static_cast<std::uint64_t>(place));
      put(out[r], &id, 1);
    }
  const std::vector<std::byte> back = comm.exchange(out, counts);
  std::vector<const std::byte*> reply(ranks);  // the next id from each range's rank
  for (int r = 0; r < ranks; ++r) reply[r] = r == 0 ? back.data() : reply[r - 1] + counts[r - 1];
  ids.resize(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) take(reply[range_of(keys[i])], &ids[i], 1);
  return std::accumulate(totals.begin(), totals.end(), std::uint64_t{0});
}

// The cells that `out` sends to their owners, as records (packed key, discovery key, `extra`
// doubles), settled on each owner: numbered by their smallest discovery key (prev_size: the size
// of the level the keys' ids are from), in global order here, with the cells they were found from
// as facets (`with_facets`) and the extra values of the smallest key in `data`.
CellLevel settle(std::vector<std::vector<std::byte>>& out, int words, int extra, bool with_facets,
                 std::uint64_t prev_size, Communicator& comm, std::vector<std::uint32_t>& ids, std::uint64_t& size,
                 std::vector<double>* data) {
  std::vector<std::size_t> counts;
  const std::vector<std::byte> in = comm.exchange(out, counts);
  out.clear();
  PackedKeyIndex found(words);
  std::vector<std::uint64_t> first, incidences;  // incidences: (cell here) << 32 | facet
  std::vector<double> values;
  std::uint32_t key[packed_words(kMaxDimension)];
  double x[kMaxDimension];
  const std::size_t record = sizeof(std::uint32_t) * words + sizeof(std::uint64_t) + sizeof(double) * extra;
  for (const std::byte* at = in.data(); at + record <= in.data() + in.size();) {
    std::uint64_t discovery;
    take(at, key, words);
    take(at, &discovery, 1);
    take(at, x, extra);
    const auto [id, fresh] = found.insert(key);
    if (fresh) {
      first.push_back(discovery);
      values.insert(values.end(), x, x + extra);
    } else if (discovery < first[id]) {
      first[id] = discovery;
      std::copy(x, x + extra, values.begin() + static_cast<std::ptrdiff_t>(id) * extra);
    }
    if (with_facets) incidences.push_back(std::uint64_t{id} << 32 | discovery >> 32);
  }
  std::vector<std::uint32_t> global;
  size = number_by_keys(first, prev_size, comm, global);
  const std::uint32_t n = found.size();
  std::vector<std::uint32_t> order(n), place(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return first[a] < first[b]; });
  CellLevel level;
  level.simplices = PackedKeyIndex(words);
  level.simplices.reserve(n);
  ids.resize(n);
  if (data) data->clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    level.simplices.insert(found.key(order[i]));
    ids[i] = global[order[i]];
    place[order[i]] = i;
    if (data)
      data->insert(data->end(), values.begin() + std::ptrdiff_t{order[i]} * extra,
                   values.begin() + std::ptrdiff_t{order[i] + 1} * extra);
  }
  // Facet lists in global ids, increasing (as the single process finds them).
  for (std::uint64_t& e : incidences) e = std::uint64_t{place[e >> 32]} << 32 | (e & 0xFFFFFFFFu);
  std::sort(incidences.begin(), incidences.end());
  level.facet_offsets.assign(n + 1, 0);
  level.facet_ids.resize(incidences.size());
  for (std::size_t i = 0; i < incidences.size(); ++i) {
    ++level.facet_offsets[(incidences[i] >> 32) + 1];
    level.facet_ids[i] = static_cast<std::uint32_t>(incidences[i]);
  }
  for (std::uint32_t c = 0; c < n; ++c) level.facet_offsets[c + 1] += level.facet_offsets[c];
  return level;
}

// Level j from this rank's part of level j − 1 (next_level_plain): the l-cofaces of each cell's
// simplex go to their owners with the cell's global id and their place among its cofaces.
CellLevel next_level(const CellLevel& prev, const std::vector<std::uint32_t>& prev_ids, std::uint64_t prev_size, int d,
                     int l, Communicator& comm, std::vector<std::uint32_t>& ids, std::uint64_t& size) {
  const int words = packed_words(d), ranks = comm.size();
  std::vector<std::vector<std::byte>> out(ranks);
  CofaceEnumerator cofaces;
  std::uint32_t key[packed_words(kMaxDimension)];
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    std::uint64_t discovery = std::uint64_t{prev_ids[c]} << 32;
    cofaces.reset(prev.simplices.simplex(c, d), l);
    while (const Simplex* nu = cofaces.next()) {
      pack(*nu, key);
      std::vector<std::byte>& o = out[owner_of(key, d, ranks)];
      put(o, key, words);
      put(o, &discovery, 1);
      ++discovery;
    }
  }
  return settle(out, words, 0, true, prev_size, comm, ids, size, nullptr);
}

}  // namespace

CellComplexPart build_cell_complex_distributed(TracePart&& trace, Communicator& comm) {
  CellComplexPart part;
  CellComplex& cc = part.cells;
  const int d = trace.ambient_dimension, k = trace.codimension, m = d - k, words = packed_words(d);
  cc.ambient_dimension = d;
  cc.manifold_dimension = m;
  cc.interior.resize(1);
  cc.interior[0].simplices = std::move(trace.simplices);
  cc.interior[0].facet_offsets.assign(cc.interior[0].size() + 1, 0);
  cc.vertices = std::move(trace.points);
  part.interior_ids = {std::move(trace.ids)};
  part.interior_sizes = {trace.size};
  bool has_boundary = false;
  if (m >= 1) {
    // S_∂ at the owners of its (k+1)-simplices: the first meeting (smallest key) numbers it and
    // gives its point, as in the gathered trace (walk_distributed_exchange.cpp).
    std::vector<std::vector<std::byte>> out(comm.size());
    for (std::size_t i = 0; i < trace.boundary_discoveries.size(); ++i) {
      const std::uint32_t* key = trace.boundary_keys.data() + i * words;
      std::vector<std::byte>& o = out[owner_of(key, d, comm.size())];
      put(o, key, words);
      put(o, &trace.boundary_discoveries[i], 1);
      put(o, trace.boundary_points.data() + i * d, d);
    }
    std::vector<std::uint32_t> ids;
    std::uint64_t size = 0;
    std::vector<double> points;
    cc.boundary.push_back(settle(out, words, d, false, trace.size, comm, ids, size, &points));
    cc.boundary_vertices.assign(points.begin(), points.end());
    part.boundary_ids.push_back(std::move(ids));
    part.boundary_sizes.push_back(size);
    has_boundary = size > 0;
  }
  for (int j = 1; j <= m; ++j) {
    std::vector<std::uint32_t> ids;
    std::uint64_t size = 0;
    cc.interior.push_back(next_level(cc.interior[j - 1], part.interior_ids[j - 1], part.interior_sizes[j - 1], d, k + j,
                                     comm, ids, size));
    part.interior_ids.push_back(std::move(ids));
    part.interior_sizes.push_back(size);
    if (has_boundary && j <= m - 1) {
      cc.boundary.push_back(next_level(cc.boundary[j - 1], part.boundary_ids[j - 1], part.boundary_sizes[j - 1], d,
                                       k + 1 + j, comm, ids, size));
      part.boundary_ids.push_back(std::move(ids));
      part.boundary_sizes.push_back(size);
    }
  }
  if (!has_boundary) {  // empty levels, uniform shape
    cc.boundary.resize(std::max(m, 0));
    part.boundary_ids.resize(cc.boundary.size());
    part.boundary_sizes.resize(cc.boundary.size());
  }
  // A cut cell's boundary cell lies on the same simplex, hence on the same rank.
  if (has_boundary)
    for (int j = 1; j <= m; ++j) {
      CellLevel& level = cc.interior[j];
      level.boundary_facet.resize(level.size());
      for (std::uint32_t c = 0; c < level.size(); ++c) {
        const std::uint32_t b = cc.boundary[j - 1].simplices.find(level.simplices.key(c));
        level.boundary_facet[c] = b == PackedKeyIndex::kAbsent ? CellLevel::kNone : part.boundary_ids[j - 1][b];
      }
    }
  for (auto& l : cc.boundary)
    if (l.simplices.words() != words) l.simplices = PackedKeyIndex(words);
  for (auto* levels : {&cc.interior, &cc.boundary})
    for (CellLevel& l : *levels) l.simplices.release_index();
  return part;
}

}  // namespace coxmesh
