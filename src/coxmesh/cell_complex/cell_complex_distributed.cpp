// Thesis §4.2 over several processes: each level of the cell complex from this rank's part of the
// level below, numbered as next_level_plain numbers it (cell_complex.cpp).
#include "coxmesh/cell_complex/cell_complex_distributed.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <numeric>
#include <span>
#include <stdexcept>

#include "coxmesh/errors.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/util/fixed_dimension.h"

namespace coxmesh {

namespace {

int owner_of(const std::uint32_t* key, int d, int ranks) {
  return owner_rank(reinterpret_cast<const std::int32_t*>(key), d, ranks);  // (y, the minimal vertex, first)
}

// The place of each of `keys` (distinct, from one range: their g = key >> 32 span at most n / P
// values) in increasing order: a counting sort by g, then by the whole key among the few of one g.
std::vector<std::uint32_t> places_in_order(const std::vector<std::uint64_t>& keys) {
  std::vector<std::uint32_t> place(keys.size());
  if (keys.empty()) return place;
  const auto [lo, hi] = std::minmax_element(keys.begin(), keys.end());
  const std::uint64_t first_g = *lo >> 32;
  std::vector<std::uint32_t> start((*hi >> 32) - first_g + 2, 0);
  for (const std::uint64_t key : keys) ++start[(key >> 32) - first_g + 1];
  for (std::size_t g = 1; g < start.size(); ++g) start[g] += start[g - 1];
  std::vector<std::uint32_t> sorted(keys.size());  // indices of keys, by g
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < keys.size(); ++i) sorted[next[(keys[i] >> 32) - first_g]++] = i;
  }
  for (std::size_t g = 0; g + 1 < start.size(); ++g)
    if (start[g + 1] - start[g] > 1)
      std::sort(sorted.begin() + start[g], sorted.begin() + start[g + 1],
                [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  for (std::uint32_t p = 0; p < sorted.size(); ++p) place[sorted[p]] = p;
  return place;
}

// The global ids of new cells from their smallest discovery keys g << 32 | s (g < n, the global id
// of a cell of the level below; keys distinct): a key's rank among every rank's keys. Without
// gathering the keys anywhere: a key goes to the rank that holds g's range (the ranks split [0, n)
// into contiguous ranges in rank order), which orders what it receives and adds the keys of the
// ranges before its own (a prefix sum of one count per rank); the ids come back in the order sent.
std::uint64_t number_by_keys(const std::vector<std::uint64_t>& keys, std::uint64_t n, Communicator& comm,
                             std::vector<std::uint32_t>& ids) {
  const int ranks = comm.size();
  // Each key's range once (a division), the messages sized from their counts and written in place.
  std::vector<int> range(keys.size());
  std::vector<std::size_t> sizes(ranks, 0);
  for (std::size_t i = 0; i < keys.size(); ++i) ++sizes[range[i] = static_cast<int>((keys[i] >> 32) * ranks / n)];
  std::vector<std::vector<std::byte>> out(ranks);
  std::vector<std::byte*> to(ranks);
  for (int r = 0; r < ranks; ++r) out[r].resize(sizes[r] * sizeof(std::uint64_t)), to[r] = out[r].data();
  for (std::size_t i = 0; i < keys.size(); ++i)
    std::memcpy(to[range[i]], &keys[i], sizeof(std::uint64_t)), to[range[i]] += sizeof(std::uint64_t);
  std::vector<std::size_t> counts;
  const std::vector<std::byte> in = comm.exchange(out, counts);
  const std::vector<std::size_t> from = counts;  // bytes of keys from each rank
  out.assign(ranks, {});
  std::vector<std::uint32_t> place;  // of each key received, among them
  agreed(comm, [&] {
    std::vector<std::uint64_t> received(in.size() / sizeof(std::uint64_t));
    const std::byte* at = in.data();
    take(at, received.data(), received.size());
    place = places_in_order(received);
  });
  std::vector<std::byte> mine;
  const std::uint64_t here = place.size();
  put(mine, &here, 1);
  const std::vector<std::byte> totals_bytes = comm.all_gather(mine, counts);
  std::vector<std::uint64_t> totals(ranks);
  const std::byte* at = totals_bytes.data();
  take(at, totals.data(), totals.size());
  const std::uint64_t offset = std::accumulate(totals.begin(), totals.begin() + comm.rank(), std::uint64_t{0});
  std::size_t next = 0;
  for (int r = 0; r < ranks; ++r) {
    out[r].resize(from[r] / sizeof(std::uint64_t) * sizeof(std::uint32_t));
    for (std::size_t i = 0; i < from[r] / sizeof(std::uint64_t); ++i) {
      const auto id = static_cast<std::uint32_t>(offset + place[next++]);
      std::memcpy(out[r].data() + i * sizeof(std::uint32_t), &id, sizeof id);
    }
  }
  const std::vector<std::byte> back = comm.exchange(out, counts);
  std::vector<const std::byte*> reply(ranks);  // the next id from each range's rank
  for (int r = 0; r < ranks; ++r) reply[r] = r == 0 ? back.data() : reply[r - 1] + counts[r - 1];
  ids.resize(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) take(reply[range[i]], &ids[i], 1);
  return std::accumulate(totals.begin(), totals.end(), std::uint64_t{0});
}

// The cells of a level that reach their owner (this rank), each with a discovery key (packed key,
// discovery key, `extra` doubles): per cell its smallest key and that key's extra values, and, with
// `facets`, every cell it was found from. Records for this rank are added as they are made; the
// others arrive in one exchange. Records are inserted in batches, the table's slots fetched ahead
// (insert_runs): a level's cells are millions of random look-ups.
struct Arrivals {
  Arrivals(int words, int extra, bool facets)
      : found(words),
        extra(extra),
        facets(facets),
        batch_keys(kBatch * words),
        batch_ids(kBatch),
        batch_hashes(kBatch),
        batch_discoveries(kBatch),
        batch_values(kBatch * extra) {}

  void add(const std::uint32_t* key, std::uint64_t discovery, const double* x) {
    add(key, hash_words(key, found.words()), discovery, x);
  }
  template <int kWords = 0>  // (kWords: the key's words fixed at compile time, 0: read at run time)
  void add(const std::uint32_t* key, std::uint64_t hash, std::uint64_t discovery, const double* x) {
    const int words = kWords != 0 ? kWords : found.words();
    // (into arrays of a batch's size: a few words each, no growth to check)
    std::uint32_t* to = batch_keys.data() + batched * words;
    for (int i = 0; i < words; ++i) to[i] = key[i];
    batch_hashes[batched] = hash;
    batch_discoveries[batched] = discovery;
    for (int i = 0; i < extra; ++i) batch_values[batched * extra + i] = x[i];
    if (++batched == kBatch) flush();
  }
  // Inserts the batch: ids in the order of add(), as one insert per record would give them.
  void flush() {
    const std::size_t n = batched;
    if (n == 0) return;
    const KeyRun run{batch_keys.data(), batch_hashes.data(), n, batch_ids.data()};
    found.insert_runs({&run, 1});
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t id = batch_ids[i] & ~PackedKeyIndex::kNewBit;
      const std::uint64_t discovery = batch_discoveries[i];
      const double* x = batch_values.data() + i * extra;
      if (batch_ids[i] & PackedKeyIndex::kNewBit) {
        first.push_back(discovery);
        values.insert(values.end(), x, x + extra);
      } else if (discovery < first[id]) {
        first[id] = discovery;
        std::copy(x, x + extra, values.begin() + static_cast<std::ptrdiff_t>(id) * extra);
      }
      if (facets) incidences.push_back(std::uint64_t{id} << 32 | discovery >> 32);
    }
    batched = 0;
    if (expected > n) {  // room for the level at the first batch's rate: no copies as it grows
      const std::size_t cells =
          std::min<std::size_t>(found.size() * (expected / n) + found.size(), PackedKeyIndex::kMaxEntries);
      found.reserve(cells), first.reserve(cells), values.reserve(cells * extra);
      if (facets) incidences.reserve(expected);
    }
    expected = 0;
  }
  // A record for `owner`: added here, or appended to its message.
  void send(std::vector<std::vector<std::byte>>& out, int owner, int rank, const std::uint32_t* key,
            std::uint64_t discovery, const double* x) {
    if (owner == rank) return add(key, discovery, x);
    append(out[owner], key, discovery, x);
  }
  template <int kWords = 0>
  void send(std::vector<std::vector<std::byte>>& out, int owner, int rank, const std::uint32_t* key, std::uint64_t hash,
            std::uint64_t discovery, const double* x) {
    if (owner == rank) return add<kWords>(key, hash, discovery, x);
    append(out[owner], key, discovery, x);
  }
  void append(std::vector<std::byte>& out, const std::uint32_t* key, std::uint64_t discovery, const double* x) const {
    std::byte record[sizeof(std::uint32_t) * packed_words(kMaxDimension) + sizeof(std::uint64_t) +
                     sizeof(double) * kMaxDimension];  // (one append per record)
    std::byte* at = record;
    const auto write = [&](const auto* p, std::size_t n) {
      if (n > 0) std::memcpy(at, p, n * sizeof *p), at += n * sizeof *p;
    };
    write(key, static_cast<std::size_t>(found.words()));
    write(&discovery, 1);
    write(x, static_cast<std::size_t>(extra));
    out.insert(out.end(), record, at);
  }

  static constexpr std::size_t kBatch = 4096;
  std::size_t expected = 0;  // records this rank will get, if known (an estimate): sizes the arrays after one batch
  PackedKeyIndex found;
  int extra;
  bool facets;
  std::vector<std::uint64_t> first, incidences;  // incidences: (cell here) << 32 | facet
  std::vector<double> values;
  std::vector<std::uint32_t> batch_keys, batch_ids;
  std::vector<std::uint64_t> batch_hashes, batch_discoveries;
  std::vector<double> batch_values;
  std::size_t batched = 0;  // records in the batch
};

CellLevel ordered_level(Arrivals& a, const std::vector<std::uint32_t>& global, std::vector<std::uint32_t>& ids,
                        std::vector<double>* data);
CellLevel level_as_arrived(Arrivals& a, std::vector<std::uint32_t>& global, std::vector<std::uint32_t>& ids,
                           std::vector<std::uint64_t>& incidences);

// The level that `arrivals` and the messages `out` make, settled on each owner: numbered by the
// cells' smallest discovery keys (prev_size: the size of the level the keys' ids are from), in
// global order here with their facets, or, given `incidences`, as they arrived, their incidences
// ((cell here) << 32 | facet) handed out instead; the extra values of the smallest key in `data`
// (in global order only). The level's keys come without a hash table (reindex() builds it).
CellLevel settle(Arrivals& arrivals, std::vector<std::vector<std::byte>>& out, std::uint64_t prev_size,
                 Communicator& comm, std::vector<std::uint32_t>& ids, std::uint64_t& size, std::vector<double>* data,
                 std::vector<std::uint64_t>* incidences = nullptr) {
  std::vector<std::size_t> counts;
  std::vector<std::byte> in = comm.exchange(out, counts);
  out.clear();
  const int words = arrivals.found.words(), extra = arrivals.extra;
  std::uint32_t key[packed_words(kMaxDimension)] = {};
  double x[kMaxDimension] = {};
  const std::size_t record = sizeof(std::uint32_t) * words + sizeof(std::uint64_t) + sizeof(double) * extra;
  agreed(comm, [&] {
    // (the bytes left, not at + record: on an empty buffer's null pointer that is undefined)
    const std::byte* const end = in.data() + in.size();
    for (const std::byte* at = in.data(); static_cast<std::size_t>(end - at) >= record;) {
      std::uint64_t discovery;
      take(at, key, words);
      take(at, &discovery, 1);
      take(at, x, extra);
      arrivals.add(key, discovery, x);
    }
    arrivals.flush();
  });
  in = {};
  std::vector<std::uint32_t> global;
  size = number_by_keys(arrivals.first, prev_size, comm, global);
  CellLevel level;
  agreed(comm, [&] {
    level =
        incidences ? level_as_arrived(arrivals, global, ids, *incidences) : ordered_level(arrivals, global, ids, data);
  });
  return level;
}

// (global id) << 32 | i sorted by global id (distinct, below 2^bits): least significant digit
// radix sort on the high word.
void sort_by_high_word(std::vector<std::uint64_t>& v, int bits) {
  constexpr int kDigit = 11;
  std::vector<std::uint64_t> sorted(v.size());
  for (int low = 32; low < 32 + bits; low += kDigit) {
    const int width = std::min(kDigit, 32 + bits - low);
    const std::uint64_t mask = (std::uint64_t{1} << width) - 1;
    std::vector<std::uint32_t> start((std::size_t{1} << width) + 1, 0);
    for (const std::uint64_t e : v) ++start[((e >> low) & mask) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    for (const std::uint64_t e : v) sorted[start[(e >> low) & mask]++] = e;
    v.swap(sorted);
  }
}

// Facet lists in global ids, increasing (as the single process finds them), of the n cells of
// `incidences` ((cell) << 32 | facet) whose places in the level `place(cell)` gives: a counting
// sort by place; a cell's facets found here come in increasing order when the level below was
// enumerated in global order, those from other ranks after them.
template <class Place>
void set_facets(CellLevel& level, std::uint32_t n, std::vector<std::uint64_t>& incidences, Place&& place) {
  level.facet_offsets.assign(n + 1, 0);
  for (const std::uint64_t e : incidences) ++level.facet_offsets[place(e >> 32) + 1];
  for (std::uint32_t c = 0; c < n; ++c) level.facet_offsets[c + 1] += level.facet_offsets[c];
  level.facet_ids.resize(incidences.size());
  {
    std::vector<std::uint32_t> next(level.facet_offsets.begin(), level.facet_offsets.end() - 1);
    for (const std::uint64_t e : incidences) level.facet_ids[next[place(e >> 32)]++] = static_cast<std::uint32_t>(e);
  }
  for (std::uint32_t c = 0; c < n; ++c) {
    const auto from = level.facet_ids.begin() + level.facet_offsets[c],
               to = level.facet_ids.begin() + level.facet_offsets[c + 1];
    if (!std::is_sorted(from, to)) std::sort(from, to);
  }
  std::vector<std::uint64_t>().swap(incidences);
}

// The cells that arrived here as they arrived, with their global ids (`global`, taken), and their
// incidences for send_to_ranges: when no one reads this rank's level in global order (without a
// file, the topology reads each cell's facets in its range), neither the reordering of
// ordered_level (a sort and a copy of the level) nor facet lists here are needed.
CellLevel level_as_arrived(Arrivals& a, std::vector<std::uint32_t>& global, std::vector<std::uint32_t>& ids,
                           std::vector<std::uint64_t>& incidences) {
  a.found.release_index();
  CellLevel level;
  level.simplices = std::move(a.found);
  a.found = PackedKeyIndex(level.simplices.words());
  ids = std::move(global);
  incidences = std::move(a.incidences);
  return level;
}

// Appends to `ranges` this rank's range of a level of `size` cells just numbered (ids: of the cells
// here; incidences: (cell here) << 32 | facet's id in its level, `below` the first id of that level
// over all levels; the boundary facets' level starts at `boundary_below`): each incidence goes to
// the rank of its cell's range as (id, facet) in one exchange, and the receiving rank lists them
// by cell. Sent as the level is numbered, not as facet lists from its owners: the lists are made
// once, where the topology reads them. Collective.
void send_to_ranges(TopologyRanges& ranges, std::vector<std::uint64_t>& incidences,
                    const std::vector<std::uint32_t>& ids, std::uint64_t size, std::uint32_t below,
                    const IndexArray& boundary_facet, std::uint32_t boundary_below, Communicator& comm) {
  const int ranks = comm.size();
  std::vector<std::vector<std::byte>> out(ranks);
  agreed(comm, [&] {
    std::vector<int> range(ids.size());  // (of each cell here)
    std::vector<std::size_t> records(ranks, 0);
    std::vector<std::uint64_t> ends(ranks - 1);  // (of the ranges but the last: a search, no division per cell)
    for (int r = 0; r + 1 < ranks; ++r) ends[r] = range_start(size, r + 1, ranks);
    for (std::size_t c = 0; c < ids.size(); ++c)
      range[c] = static_cast<int>(std::upper_bound(ends.begin(), ends.end(), std::uint64_t{ids[c]}) - ends.begin());
    for (const std::uint64_t e : incidences) ++records[range[e >> 32]];
    for (std::size_t c = 0; c < boundary_facet.size(); ++c) records[range[c]] += boundary_facet[c] != CellLevel::kNone;
    std::vector<std::uint32_t*> to(ranks);
    for (int r = 0; r < ranks; ++r) {
      out[r].resize(records[r] * 2 * sizeof(std::uint32_t));
      to[r] = reinterpret_cast<std::uint32_t*>(out[r].data());  // (operator new: aligned)
    }
    for (const std::uint64_t e : incidences) {
      const std::size_t c = e >> 32;
      std::uint32_t*& w = to[range[c]];
      *w++ = ids[c], *w++ = below + static_cast<std::uint32_t>(e);
    }
    for (std::size_t c = 0; c < boundary_facet.size(); ++c)
      if (boundary_facet[c] != CellLevel::kNone) {
        std::uint32_t*& w = to[range[c]];
        *w++ = ids[c], *w++ = boundary_below + boundary_facet[c];
      }
  });
  std::vector<std::uint64_t>().swap(incidences);
  std::vector<std::size_t> counts;
  const std::vector<std::byte> in = comm.exchange(out, counts);
  out = {};
  agreed(comm, [&] {
    // (a counting sort by cell: counts one place ahead, then starts, then ends as the facets go in)
    const std::uint64_t lo = range_start(size, comm.rank(), ranks), n = range_start(size, comm.rank() + 1, ranks) - lo;
    const std::size_t base = ranges.offsets.size() - 1, entries = in.size() / (2 * sizeof(std::uint32_t));
    std::vector<std::uint32_t>& offsets = ranges.offsets;
    offsets.resize(base + n + 2, 0);
    const auto word = [&](std::size_t i) {
      std::uint32_t x;
      std::memcpy(&x, in.data() + i * sizeof x, sizeof x);
      return x;
    };
    for (std::size_t k = 0; k < entries; ++k) {
      const std::uint64_t u = word(2 * k) - lo;
      if (u >= n) throw std::logic_error("an incidence sent to the rank that does not hold its cell's range");
      ++offsets[base + 2 + u];
    }
    offsets[base + 1] = offsets[base];
    for (std::size_t i = base + 2; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
    ranges.facets.resize(ranges.facets.size() + entries);
    for (std::size_t k = 0; k < entries; ++k) ranges.facets[offsets[base + 1 + (word(2 * k) - lo)]++] = word(2 * k + 1);
    offsets.pop_back();
    for (std::size_t i = base; i < base + n; ++i) {
      const auto from = ranges.facets.begin() + offsets[i], to = ranges.facets.begin() + offsets[i + 1];
      if (!std::is_sorted(from, to)) std::sort(from, to);
    }
  });
}

// Frees a level's keys, keeping its size: neither the topology nor a mesh writer reads a key.
void release_keys(CellLevel& level) { level.simplices = PackedKeyIndex::without_keys(level.simplices.size()); }

// A level without facets (the vertex cells) in `ranges`: its range's cells, with none.
void add_empty_range(TopologyRanges& ranges, std::uint64_t size, Communicator& comm) {
  const std::uint64_t n = range_start(size, comm.rank() + 1, comm.size()) - range_start(size, comm.rank(), comm.size());
  ranges.offsets.resize(ranges.offsets.size() + n, ranges.offsets.back());
}

// The cells that arrived here in global order (by their smallest keys, whose ranks `global` holds),
// with their facets.
CellLevel ordered_level(Arrivals& a, const std::vector<std::uint32_t>& global, std::vector<std::uint32_t>& ids,
                        std::vector<double>* data) {
  a.found.release_index();  // (the keys are all it needs now)
  const std::vector<double>& values = a.values;
  const int extra = a.extra;
  const std::uint32_t n = a.found.size();
  std::vector<std::uint32_t> order(n), place(n);
  {
    std::vector<std::uint64_t> by_id(n);
    std::uint32_t largest = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      by_id[i] = std::uint64_t{global[i]} << 32 | i;
      largest = std::max(largest, global[i]);
    }
    sort_by_high_word(by_id, std::bit_width(largest));
    for (std::uint32_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(by_id[i]);
  }
  CellLevel level;
  level.simplices = PackedKeyIndex::unindexed_copy(a.found, order);
  a.found = PackedKeyIndex(a.found.words());
  ids.resize(n);
  if (data) data->clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    ids[i] = global[order[i]];
    place[order[i]] = i;
    if (data)
      data->insert(data->end(), values.begin() + std::ptrdiff_t{order[i]} * extra,
                   values.begin() + std::ptrdiff_t{order[i] + 1} * extra);
  }
  set_facets(level, n, a.incidences, [&](std::uint64_t c) { return place[c]; });
  return level;
}

// Level j from this rank's part of level j − 1 (next_level_plain): the l-cofaces of each cell's
// simplex go to their owners with the cell's global id and their place among its cofaces.
CellLevel next_level(const CellLevel& prev, const std::vector<std::uint32_t>& prev_ids, std::uint64_t prev_size, int d,
                     int l, Communicator& comm, std::vector<std::uint32_t>& ids, std::uint64_t& size,
                     std::vector<std::uint64_t>* incidences) {
  const int words = packed_words(d), ranks = comm.size();
  std::vector<std::vector<std::byte>> out(ranks);
  Arrivals arrivals(words, 0, true);
  const double no_values = 0;      // (no extra values at this level)
  LastOwner last_owner(d, ranks);  // (a cell's cofaces mostly share their minimal vertex)
  COXMESH_ASSERT(prev.size() == 0 || prev.simplices.simplex(0, d).k + 1 == l);  // (cofacets: PackedCofacets)
  {  // the records this rank makes, from the first cells' cofacets (the few from other ranks aside)
    constexpr std::uint32_t kSample = 256;
    std::size_t sampled = 0;
    const std::uint32_t n = std::min(prev.size(), kSample);
    for (std::uint32_t c = 0; c < n; ++c) sampled += PackedCofacets(prev.simplices.key(c), d).count();
    if (n > 0) arrivals.expected = sampled * prev.size() / n;
  }
  agreed(comm, [&] {
    // (d fixed at compile time for the common d, as in the one-process complex: the loops over d and
    // over the key's words unroll)
    with_fixed_dimension<2, 3, 4, 6, 9>(d, [&](auto fixed_d) {
      constexpr int kD = decltype(fixed_d)::value;
      constexpr int kWords = kD != 0 ? packed_words(kD) : 0;
      for (std::uint32_t c = 0; c < prev.size(); ++c) {
        std::uint64_t discovery = std::uint64_t{prev_ids[c]} << 32;
        // (straight from the packed keys, with their hashes, as the one-process complex enumerates them)
        PackedCofacets<kD>(prev.simplices.key(c), d).for_each([&](const std::uint32_t* nu, std::uint64_t hash) {
          // (y, the minimal vertex, first in the key)
          arrivals.send<kWords>(out, last_owner.of<kD>(reinterpret_cast<const std::int32_t*>(nu)), comm.rank(), nu,
                                hash, discovery++, &no_values);
        });
      }
    });
  });
  return settle(arrivals, out, prev_size, comm, ids, size, nullptr, incidences);
}

}  // namespace

CellComplexPart build_cell_complex_distributed(TracePart&& trace, Communicator& comm, bool in_global_order) {
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
  // Without global order, each level's incidences go to the topology's ranges as it is numbered;
  // the levels come in the order of the ranges (interior j, then boundary j), each starting where
  // the one before ended.
  std::vector<std::uint64_t> incidences, *const to_ranges = in_global_order ? nullptr : &incidences;
  if (to_ranges) part.ranges.emplace();
  std::uint64_t next_start = 0;
  std::vector<std::uint32_t> interior_start, boundary_start;  // (the first id of each level over all levels)
  const auto numbered = [&](std::vector<std::uint32_t>& starts, std::uint64_t size) {
    starts.push_back(static_cast<std::uint32_t>(next_start));
    next_start += size;
  };
  numbered(interior_start, trace.size);
  if (to_ranges) add_empty_range(*part.ranges, trace.size, comm);
  bool has_boundary = false;
  if (m >= 1) {
    // S_∂ at the owners of its (k+1)-simplices: the first meeting (smallest key) numbers it and
    // gives its point, as in the gathered trace (walk_distributed_exchange.cpp).
    std::vector<std::vector<std::byte>> out(comm.size());
    Arrivals arrivals(words, d, false);
    for (std::size_t i = 0; i < trace.boundary_discoveries.size(); ++i) {
      const std::uint32_t* key = trace.boundary_keys.data() + i * words;
      arrivals.send(out, owner_of(key, d, comm.size()), comm.rank(), key, trace.boundary_discoveries[i],
                    trace.boundary_points.data() + i * d);
    }
    std::vector<std::uint32_t> ids;
    std::uint64_t size = 0;
    std::vector<double> points;
    cc.boundary.push_back(settle(arrivals, out, trace.size, comm, ids, size, &points));
    cc.boundary_vertices.assign(points.begin(), points.end());
    part.boundary_ids.push_back(std::move(ids));
    part.boundary_sizes.push_back(size);
    numbered(boundary_start, size);
    if (to_ranges) add_empty_range(*part.ranges, size, comm);
    has_boundary = size > 0;
  }
  const IndexArray no_boundary_facets;
  // Hash tables only while a look-up needs them (a boundary level, for the boundary facets of the
  // interior level above it): they are a quarter to a third of a level's memory.
  cc.interior[0].simplices.release_index();
  for (int j = 1; j <= m; ++j) {
    std::vector<std::uint32_t> ids;
    std::uint64_t size = 0;
    cc.interior.push_back(next_level(cc.interior[j - 1], part.interior_ids[j - 1], part.interior_sizes[j - 1], d, k + j,
                                     comm, ids, size, to_ranges));
    part.interior_ids.push_back(std::move(ids));
    part.interior_sizes.push_back(size);
    CellLevel& level = cc.interior[j];
    level.simplices.release_index();
    if (has_boundary) {  // (a cut cell's boundary cell lies on the same simplex, hence here)
      level.boundary_facet.resize(level.size());
      cc.boundary[j - 1].simplices.reindex();  // (settle gives keys only)
      for (std::uint32_t c = 0; c < level.size(); ++c) {
        const std::uint32_t b = cc.boundary[j - 1].simplices.find(level.simplices.key(c));
        level.boundary_facet[c] = b == PackedKeyIndex::kAbsent ? CellLevel::kNone : part.boundary_ids[j - 1][b];
      }
    }
    if (to_ranges) {
      send_to_ranges(*part.ranges, incidences, part.interior_ids[j], size, interior_start[j - 1], level.boundary_facet,
                     has_boundary ? boundary_start[j - 1] : 0, comm);
      level.boundary_facet = IndexArray{};  // (sent: the topology reads it in its range)
    }
    numbered(interior_start, size);
    if (has_boundary && j <= m - 1) {
      cc.boundary.push_back(next_level(cc.boundary[j - 1], part.boundary_ids[j - 1], part.boundary_sizes[j - 1], d,
                                       k + 1 + j, comm, ids, size, to_ranges));
      part.boundary_ids.push_back(std::move(ids));
      part.boundary_sizes.push_back(size);
      if (to_ranges)
        send_to_ranges(*part.ranges, incidences, part.boundary_ids[j], size, boundary_start[j - 1], no_boundary_facets,
                       0, comm);
      numbered(boundary_start, size);
    }
    if (j - 1 < static_cast<int>(cc.boundary.size())) cc.boundary[j - 1].simplices.release_index();
    if (to_ranges) {  // (the keys of the levels below have served: the topology reads none)
      release_keys(cc.interior[j - 1]);
      if (j - 1 < static_cast<int>(cc.boundary.size())) release_keys(cc.boundary[j - 1]);
    }
  }
  if (!has_boundary) {  // empty levels, uniform shape
    cc.boundary.resize(std::max(m, 0));
    part.boundary_ids.resize(cc.boundary.size());
    part.boundary_sizes.resize(cc.boundary.size());
  }
  for (auto& l : cc.boundary)
    if (l.size() == 0 && l.simplices.words() != words) l.simplices = PackedKeyIndex(words);  // (released keys stay so)
  for (auto* levels : {&cc.interior, &cc.boundary})
    for (CellLevel& l : *levels) l.simplices.release_index();
  return part;
}

namespace {

// One part's cells of one level, wherever they are (a CellComplexPart, or a message).
struct LevelView {
  std::uint32_t n = 0;
  std::uint64_t facet_entries = 0;
  const std::uint32_t *keys = nullptr, *offsets = nullptr, *facets = nullptr, *boundary_facet = nullptr, *ids = nullptr;
  const double* rows = nullptr;  // vertex coordinates (level 0)
};

LevelView view_of(const CellLevel& l, const std::vector<std::uint32_t>& ids, const PointArray* rows) {
  if (ids.size() != l.size()) throw InputError("a part of the cell complex has cells without ids");
  return {l.size(),
          l.facet_ids.size(),
          l.size() ? l.simplices.key(0) : nullptr,
          l.facet_offsets.data(),
          l.facet_ids.data(),
          l.boundary_facet.empty() ? nullptr : l.boundary_facet.data(),
          ids.data(),
          rows ? rows->data() : nullptr};
}

// The level of n cells from the views of every part, each cell at its global id; with `rows`
// (level 0) the vertex coordinates too. Throws InputError unless every cell is in one part. Each
// cell's arrays go where its id says (keys, facet counts, rows; then the facet lists at their
// offsets), with no hash table.
CellLevel assemble_level(const std::vector<LevelView>& views, std::uint64_t n, int d, PointArray* rows) {
  if (n >= PackedKeyIndex::kAbsent) throw InputError("too many cells in a level");
  // (checked before anything of size n is allocated: n may come from a file)
  std::uint64_t given = 0, entries = 0;
  bool boundary_facets = false;
  for (const LevelView& v : views) {
    given += v.n, entries += v.facet_entries;
    boundary_facets |= v.boundary_facet != nullptr;
  }
  const char* const not_once = "the parts of the cell complex do not number its cells once each";
  if (given != n) throw InputError(not_once);
  if (entries >= (std::uint64_t{1} << 32)) throw InputError("too many facets in a level");
  const std::size_t words = static_cast<std::size_t>(packed_words(d));
  // n ids, none out of range nor twice: each of the n cells placed once.
  std::vector<bool> placed(n, false);
  UninitializedHugeVector<std::uint32_t> keys(n * words);  // (all written below)
  CellLevel level;
  level.facet_offsets.assign(n + 1, 0);
  if (boundary_facets) level.boundary_facet.assign(n, CellLevel::kNone);
  if (rows) rows->resize(n * d);
  for (const LevelView& v : views)
    for (std::uint32_t c = 0; c < v.n; ++c) {
      const std::uint32_t g = v.ids[c];
      if (g >= n || placed[g]) throw InputError(not_once);
      placed[g] = true;
      if (v.offsets[c] > v.offsets[c + 1] || v.offsets[c + 1] > v.facet_entries)
        throw InputError("a part of the cell complex has bad facet offsets");
      std::copy_n(v.keys + c * words, words, keys.data() + g * words);
      level.facet_offsets[g + 1] = v.offsets[c + 1] - v.offsets[c];
      if (v.boundary_facet) level.boundary_facet[g] = v.boundary_facet[c];
      if (rows) std::copy_n(v.rows + std::size_t{c} * d, d, rows->data() + std::size_t{g} * d);
    }
  for (std::uint64_t g = 0; g < n; ++g) level.facet_offsets[g + 1] += level.facet_offsets[g];
  level.facet_ids.resize(entries);
  for (const LevelView& v : views)
    for (std::uint32_t c = 0; c < v.n; ++c)
      std::copy(v.facets + v.offsets[c], v.facets + v.offsets[c + 1],
                level.facet_ids.begin() + level.facet_offsets[v.ids[c]]);
  level.simplices = PackedKeyIndex::from_keys(static_cast<int>(words), std::move(keys));
  return level;
}

// One part's level as a message, and the view of such a message.
void put_level(std::vector<std::byte>& out, const CellLevel& l, const std::vector<std::uint32_t>& ids,
               const PointArray* rows) {
  const std::size_t start = out.size();
  const std::uint64_t shape[] = {l.size(), l.facet_ids.size(), l.boundary_facet.size(), rows ? rows->size() : 0};
  put(out, shape, 4);
  if (l.size()) put(out, l.simplices.key(0), std::size_t{l.size()} * l.simplices.words());
  put(out, l.facet_offsets.data(), l.facet_offsets.size());
  put(out, l.facet_ids.data(), l.facet_ids.size());
  put(out, l.boundary_facet.data(), l.boundary_facet.size());
  put(out, ids.data(), ids.size());
  out.resize(out.size() + (out.size() - start) % 8);  // (the rows aligned: see view_message)
  if (rows) put(out, rows->data(), rows->size());
}

LevelView view_message(const std::byte* in, int words) {
  // (every array of a message starts at a multiple of 4 bytes from its start, the rows at 8; the
  // gathered bytes of a rank start at a multiple of 8, as every message is padded to one)
  const std::byte* const start = in;
  std::uint64_t shape[4];
  take(in, shape, 4);
  const auto at = [&](std::size_t count) {
    const auto* p = reinterpret_cast<const std::uint32_t*>(in);
    in += count * sizeof(std::uint32_t);
    return p;
  };
  LevelView v;
  v.n = static_cast<std::uint32_t>(shape[0]);
  v.facet_entries = shape[1];
  v.keys = at(shape[0] * words);
  v.offsets = at(shape[0] + 1);
  v.facets = at(shape[1]);
  v.boundary_facet = shape[2] ? at(shape[2]) : nullptr;
  v.ids = at(shape[0]);
  in += (in - start) % 8;
  v.rows = shape[3] ? reinterpret_cast<const double*>(in) : nullptr;
  return v;
}

}  // namespace

CellComplex assemble_cell_complex(std::vector<CellComplexPart>&& parts) {
  if (parts.empty()) throw InputError("no part of a cell complex to assemble");
  CellComplex cc;
  const CellComplexPart& first = parts[0];
  const int d = first.cells.ambient_dimension;
  cc.ambient_dimension = d;
  cc.manifold_dimension = first.cells.manifold_dimension;
  for (const CellComplexPart& p : parts)
    if (p.cells.ambient_dimension != d || p.cells.manifold_dimension != cc.manifold_dimension ||
        p.interior_sizes != first.interior_sizes || p.boundary_sizes != first.boundary_sizes ||
        p.cells.interior.size() != first.interior_sizes.size() ||
        p.cells.boundary.size() != first.boundary_sizes.size())
      throw InputError("the parts of the cell complex do not agree on its shape");
  for (int kind = 0; kind < 2; ++kind) {
    const std::vector<std::uint64_t> sizes = kind ? first.boundary_sizes : first.interior_sizes;
    for (std::size_t j = 0; j < sizes.size(); ++j) {
      std::vector<LevelView> views;
      for (const CellComplexPart& p : parts) {
        const PointArray* rows = j > 0 ? nullptr : kind ? &p.cells.boundary_vertices : &p.cells.vertices;
        views.push_back(view_of(kind ? p.cells.boundary[j] : p.cells.interior[j],
                                kind ? p.boundary_ids[j] : p.interior_ids[j], rows));
      }
      PointArray* rows = j > 0 ? nullptr : kind ? &cc.boundary_vertices : &cc.vertices;
      (kind ? cc.boundary : cc.interior).push_back(assemble_level(views, sizes[j], d, rows));
      for (CellComplexPart& p : parts) (kind ? p.cells.boundary : p.cells.interior)[j] = CellLevel{};  // (memory)
    }
  }
  parts.clear();
  return cc;
}

// Level by level, so that rank 0 holds the complex and one level's messages at most.
CellComplex gather_cell_complex(CellComplexPart&& part, Communicator& comm) {
  CellComplex cc;
  const int d = part.cells.ambient_dimension, words = packed_words(d);
  cc.ambient_dimension = d;
  cc.manifold_dimension = part.cells.manifold_dimension;
  for (int kind = 0; kind < 2; ++kind) {
    const std::vector<std::uint64_t> sizes = kind ? part.boundary_sizes : part.interior_sizes;
    for (std::size_t j = 0; j < sizes.size(); ++j) {
      CellLevel& mine = kind ? part.cells.boundary[j] : part.cells.interior[j];
      PointArray* my_rows = j > 0 ? nullptr : kind ? &part.cells.boundary_vertices : &part.cells.vertices;
      std::vector<std::byte> message;
      put_level(message, mine, kind ? part.boundary_ids[j] : part.interior_ids[j], my_rows);
      message.resize((message.size() + 7) / 8 * 8);  // (the next rank's doubles stay aligned)
      mine = CellLevel{};
      if (my_rows) *my_rows = PointArray{};
      std::vector<std::size_t> counts;
      const std::vector<std::byte> all = comm.gather_to_root(message, counts);
      message = {};
      agreed(comm, [&] {  // (the others wait for rank 0 before the next level: it may fail)
        if (comm.rank() != 0) return;
        std::vector<LevelView> views;
        const std::byte* at = all.data();
        for (const std::size_t count : counts) views.push_back(view_message(at, words)), at += count;
        PointArray* rows = j > 0 ? nullptr : kind ? &cc.boundary_vertices : &cc.vertices;
        (kind ? cc.boundary : cc.interior).push_back(assemble_level(views, sizes[j], d, rows));
      });
    }
  }
  part = CellComplexPart{};
  return comm.rank() == 0 ? std::move(cc) : CellComplex{};
}

namespace {

// The cells of one level of a closure that other ranks own, in the order they arrive.
struct Halo {
  std::vector<std::uint32_t> keys;  // (packed, one after the other: read by the next round's requests only)
  std::vector<std::uint32_t> ids, facet_offsets{0}, facets, boundary_facet;
  std::vector<double> rows;
};

}  // namespace

CellClosure closure_for_writing(CellComplexPart& part, Communicator& comm) {
  CellComplex& cc = part.cells;
  const int d = cc.ambient_dimension, m = cc.manifold_dimension, words = packed_words(d);
  const int ranks = comm.size();
  const int top[2] = {std::min(m, 3), m >= 1 ? std::min({m, 3, m - 1}) : -1};  // interior, boundary
  const bool has_boundary = !part.boundary_sizes.empty() && part.boundary_sizes[0] > 0;
  const auto level_of = [&](int kind, int j) -> CellLevel& { return kind ? cc.boundary[j] : cc.interior[j]; };
  const auto ids_of = [&](int kind, int j) -> std::vector<std::uint32_t>& {
    return kind ? part.boundary_ids[j] : part.interior_ids[j];
  };
  // Per level: which of this rank's cells are in the closure, and the cells of other ranks in it.
  std::vector<std::vector<std::uint8_t>> mine[2];
  std::vector<Halo> halo[2];
  for (int kind = 0; kind < 2; ++kind)
    for (int j = 0; j <= top[kind]; ++j) {
      mine[kind].emplace_back(level_of(kind, j).size(), j == top[kind] ? 1 : 0);
      halo[kind].emplace_back();
    }
  // The cell of global id g of level j of this rank, or kAbsent.
  const auto own = [&](int kind, int j, std::uint32_t g) {
    const std::vector<std::uint32_t>& ids = ids_of(kind, j);
    const auto at = std::lower_bound(ids.begin(), ids.end(), g);
    return at != ids.end() && *at == g ? static_cast<std::uint32_t>(at - ids.begin()) : PackedKeyIndex::kAbsent;
  };
  // Level by level downwards: the facets of the closure's cells join it; those of other ranks are
  // asked from the owners of the faces of their cells' simplices (most cells have none).
  for (int j = std::max(top[0], top[1]); j >= 1; --j) {
    std::vector<std::vector<std::byte>> requests(ranks);
    PackedKeyIndex asked[2] = {PackedKeyIndex(words), PackedKeyIndex(words)};
    agreed(comm, [&] {
      std::uint32_t key[packed_words(kMaxDimension)];
      FaceEnumerator faces;
      const auto ask_faces = [&](int kind, const std::uint32_t* cell_key) {
        const Simplex s = unpack(cell_key, d);
        faces.reset(s, s.dimension() - 1);
        for (Simplex f; faces.next(f);) {
          pack(f, key);
          const int owner = owner_of(key, d, ranks);
          if (owner == comm.rank() || !asked[kind].insert(key).second) continue;
          const std::uint32_t k = static_cast<std::uint32_t>(kind);
          put(requests[owner], &k, 1);
          put(requests[owner], key, words);
        }
      };
      // (a cell's facets of its kind, and its boundary facet, which lies on its simplex)
      const auto take_facets = [&](int kind, std::span<const std::uint32_t> facets, std::uint32_t bf,
                                   const std::uint32_t* key, bool here) {
        bool remote = false;
        for (const std::uint32_t g : facets) {
          const std::uint32_t c = own(kind, j - 1, g);
          if (c == PackedKeyIndex::kAbsent)
            remote = true;
          else
            mine[kind][j - 1][c] = 1;
        }
        if (remote) ask_faces(kind, key);
        if (kind == 1 || bf == CellLevel::kNone) return;
        if (here) {
          mine[1][j - 1][own(1, j - 1, bf)] = 1;
        } else if (asked[1].insert(key).second) {
          const std::uint32_t k = 1;
          put(requests[owner_of(key, d, ranks)], &k, 1);
          put(requests[owner_of(key, d, ranks)], key, words);
        }
      };
      for (int kind = 0; kind < 2; ++kind) {
        if (j > top[kind]) continue;
        const CellLevel& level = level_of(kind, j);
        for (std::uint32_t c = 0; c < level.size(); ++c)
          if (mine[kind][j][c])
            take_facets(kind, level.facets(c),
                        level.boundary_facet.empty() ? CellLevel::kNone : level.boundary_facet[c],
                        level.simplices.key(c), true);
        const Halo& h = halo[kind][j];
        for (std::uint32_t i = 0; i < h.ids.size(); ++i)
          take_facets(kind, {h.facets.data() + h.facet_offsets[i], h.facets.data() + h.facet_offsets[i + 1]},
                      h.boundary_facet[i], h.keys.data() + std::size_t{i} * words, false);
      }
    });
    // The owners look the asked simplices up (a hash table for this round only).
    for (int kind = 0; kind < 2; ++kind)
      if (j - 1 <= top[kind]) level_of(kind, j - 1).simplices.reindex();
    std::vector<std::size_t> counts;
    const std::vector<std::byte> asked_here = comm.exchange(requests, counts);
    std::vector<std::vector<std::byte>> replies(ranks);
    agreed(comm, [&] {
      const std::byte* in = asked_here.data();
      std::uint32_t key[packed_words(kMaxDimension)];
      for (int r = 0; r < ranks; ++r)
        for (std::size_t n = counts[r] / (sizeof(std::uint32_t) * (words + 1)); n > 0; --n) {
          std::uint32_t kind;
          take(in, &kind, 1);
          take(in, key, words);
          const CellLevel& l = level_of(static_cast<int>(kind), j - 1);
          const std::uint32_t c = l.simplices.find(key);
          const std::uint32_t found = c != PackedKeyIndex::kAbsent;
          put(replies[r], &found, 1);
          if (!found) continue;
          const auto f = l.facets(c);
          const std::uint32_t head[] = {ids_of(static_cast<int>(kind), j - 1)[c], static_cast<std::uint32_t>(f.size()),
                                        l.boundary_facet.empty() ? CellLevel::kNone : l.boundary_facet[c]};
          put(replies[r], head, 3);
          put(replies[r], f.data(), f.size());
          if (j - 1 == 0) put(replies[r], (kind ? cc.boundary_vertices : cc.vertices).data() + std::size_t{c} * d, d);
        }
    });
    for (int kind = 0; kind < 2; ++kind)
      if (j - 1 <= top[kind]) level_of(kind, j - 1).simplices.release_index();
    const std::vector<std::byte> answers = comm.exchange(replies, counts);
    agreed(comm, [&] {
      const std::byte* in = answers.data();
      for (int r = 0; r < ranks; ++r) {
        const std::byte* q = requests[r].data();
        for (std::size_t n = requests[r].size() / (sizeof(std::uint32_t) * (words + 1)); n > 0; --n) {
          std::uint32_t kind, found, head[3];
          take(q, &kind, 1);
          const auto* key = reinterpret_cast<const std::uint32_t*>(q);
          q += sizeof(std::uint32_t) * words;
          take(in, &found, 1);
          if (!found) continue;
          take(in, head, 3);
          Halo& h = halo[kind][j - 1];
          h.keys.insert(h.keys.end(), key, key + words);
          h.ids.push_back(head[0]);
          h.facets.resize(h.facets.size() + head[1]);
          take(in, h.facets.data() + h.facets.size() - head[1], head[1]);
          h.facet_offsets.push_back(static_cast<std::uint32_t>(h.facets.size()));
          h.boundary_facet.push_back(head[2]);
          if (j - 1 == 0) {
            h.rows.resize(h.rows.size() + d);
            take(in, h.rows.data() + h.rows.size() - d, d);
          }
        }
      }
    });
    // Level j's keys have served (its cells' faces asked for, its halo's too), and level 0's after
    // the last round's look-ups: the assembly below reads none.
    for (int kind = 0; kind < 2; ++kind)
      if (j <= top[kind]) {
        release_keys(level_of(kind, j));
        if (j == 1) release_keys(level_of(kind, 0));  // (the last look-ups were this round's)
        std::vector<std::uint32_t>().swap(halo[kind][j].keys);
      }
  }

  // Each level in global order (this rank's cells merged with the others'), its facets and
  // boundary facets renumbered into the closure.
  CellClosure out;
  CellComplex& local = out.cells;
  local.ambient_dimension = d;
  local.manifold_dimension = m;
  const auto local_id = [&](int kind, int j, std::uint32_t g) {
    const std::vector<std::uint32_t>& ids = kind ? out.boundary_ids[j] : out.interior_ids[j];
    const auto at = std::lower_bound(ids.begin(), ids.end(), g);
    if (at == ids.end() || *at != g) throw std::logic_error("closure_for_writing: a face is missing");
    return static_cast<std::uint32_t>(at - ids.begin());
  };
  for (int j = 0; j <= m; ++j)
    for (int kind = 0; kind < 2; ++kind) {
      if (kind == 1 && j >= m) continue;
      CellLevel level;
      level.simplices = PackedKeyIndex::without_keys(0);
      level.facet_offsets.assign(1, 0);
      std::vector<std::uint32_t>& ids = (kind ? out.boundary_ids : out.interior_ids).emplace_back();
      if (j <= top[kind]) {
        const CellLevel& from = level_of(kind, j);
        const std::vector<std::uint32_t>& from_ids = ids_of(kind, j);
        const std::vector<std::uint8_t>& in_closure = mine[kind][j];
        const Halo& h = halo[kind][j];
        std::vector<std::uint32_t> order(h.ids.size());  // the halo by global id
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return h.ids[a] < h.ids[b]; });
        const bool with_bf = kind == 0 && j >= 1 && has_boundary;
        // (every array at its final size at once: grown cell by cell, each would be copied as it grows)
        std::size_t cells = h.ids.size(), incidences = h.facets.size();
        for (std::uint32_t c = 0; c < in_closure.size(); ++c)
          if (in_closure[c]) ++cells, incidences += from.facet_offsets[c + 1] - from.facet_offsets[c];
        ids.reserve(cells);
        level.facet_offsets.reserve(cells + 1);
        level.facet_ids.reserve(incidences);
        if (with_bf) level.boundary_facet.reserve(cells);
        if (j == 0) (kind ? local.boundary_vertices : local.vertices).reserve(cells * static_cast<std::size_t>(d));
        const auto append = [&](std::uint32_t g, std::span<const std::uint32_t> facets, std::uint32_t bf,
                                const double* row) {
          ids.push_back(g);
          for (const std::uint32_t f : facets) level.facet_ids.push_back(local_id(kind, j - 1, f));
          level.facet_offsets.push_back(static_cast<std::uint32_t>(level.facet_ids.size()));
          if (with_bf) level.boundary_facet.push_back(bf == CellLevel::kNone ? bf : local_id(1, j - 1, bf));
          if (row)
            (kind ? local.boundary_vertices : local.vertices)
                .insert((kind ? local.boundary_vertices : local.vertices).end(), row, row + d);
        };
        const PointArray& rows = kind ? cc.boundary_vertices : cc.vertices;
        std::size_t next = 0;  // in `order`
        const auto append_halo_below = [&](std::uint64_t g) {
          for (; next < order.size() && h.ids[order[next]] < g; ++next) {
            const std::uint32_t i = order[next];
            append(h.ids[i], {h.facets.data() + h.facet_offsets[i], h.facets.data() + h.facet_offsets[i + 1]},
                   h.boundary_facet[i], j == 0 ? h.rows.data() + std::size_t{i} * d : nullptr);
          }
        };
        for (std::uint32_t c = 0; c < in_closure.size(); ++c)
          if (in_closure[c]) {
            append_halo_below(from_ids[c]);
            append(from_ids[c], from.facets(c), from.boundary_facet.empty() ? CellLevel::kNone : from.boundary_facet[c],
                   j == 0 ? rows.data() + std::size_t{c} * d : nullptr);
          }
        append_halo_below(~std::uint64_t{0});
        level.simplices = PackedKeyIndex::without_keys(static_cast<std::uint32_t>(ids.size()));
        std::vector<std::uint8_t>().swap(mine[kind][j]);
        halo[kind][j] = Halo();
        if (j == 0) (kind ? cc.boundary_vertices : cc.vertices) = PointArray{};  // (copied: the topology needs none)
      }
      (kind ? local.boundary : local.interior).push_back(std::move(level));
    }
  release_all_but_incidences(part);  // (the levels above those of the file, if any)
  return out;
}

void release_all_but_incidences(CellComplexPart& part) {
  for (auto* levels : {&part.cells.interior, &part.cells.boundary})
    for (CellLevel& level : *levels) release_keys(level);
  part.cells.vertices = PointArray{};
  part.cells.boundary_vertices = PointArray{};
}

}  // namespace coxmesh
