// Thesis §4.2 with many threads: the walk of walk_sequential.cpp, a breadth-first level at a time.
// A level's simplices are walked in chunks by the sequential walk's loop (process_chunk), whose
// classify writes discoveries to the chunk's buffer instead of S (classify_in_level); the buffers
// are appended to S in chunk order (merge), which gives S the sequential walk's order.
#include "coxmesh/tracing/walk_parallel.h"

#include <algorithm>
#include <atomic>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/util/huge_page_allocator.h"
#include "coxmesh/util/linear_probe.h"

namespace coxmesh::walk {

ParallelWalk::ParallelWalk(SequentialWalk& walk, const std::vector<IntersectionOracle*>& oracles)
    : s_(walk), d_(walk.d_), k_(walk.k_) {
  for (IntersectionOracle* o : oracles) {
    const PackedKeyIndex empty(packed_words(d_));
    workers_.push_back(Worker{o, empty, {}, {}, {}, {}, 0, {empty, empty}, {{0, 0}, {0, 0}}});
  }
}

std::uint64_t ParallelWalk::oracle_calls() const {
  std::uint64_t calls = 0;
  for (const Worker& w : workers_) calls += w.calls;
  return calls;
}

// The parallel walk appends its levels to S without indexing them (its workers look simplices up
// in the indexes of two levels), and S is indexed at the end, and whenever it has grown fourfold
// since it last was (so a walk gone astray wastes at most that much; every fourfold, not twofold:
// each indexing grows the table into fresh memory, whose page faults are much of its time). A simplex met
// twice shows up there; only an oracle for which the walk's graph is not symmetric (a cofacet with
// more than two transverse facets) can cause that, and the walk is then redone sequentially, so
// the result is the same for every thread count in every case.
void ParallelWalk::walk() {
  const Mark before = mark();
  if (walk_levels() && s_.result_.simplices.index_appended() == PackedKeyIndex::kAbsent) return;
  undo(before);
  s_.walk();
}

ParallelWalk::Mark ParallelWalk::mark() const {
  return {s_.head_,          s_.result_.simplices.size(), s_.result_.boundary_simplices.size(),
          s_.last_progress_, s_.result_.status,           s_.cofacet_places_.size(),
          s_.cofacets_met_};
}

void ParallelWalk::undo(const Mark& m) {
  const std::size_t n = m.simplices, b = m.boundary_simplices;
  s_.head_ = s_.level_end_ = m.head;
  pending_ = {0, 0};
  s_.result_.simplices.truncate(static_cast<std::uint32_t>(n));
  s_.result_.points.resize(n * d_);
  s_.domain_values_.resize(n);
  s_.arrivals_.resize(n);
  s_.settled_.resize(n);
  s_.result_.boundary_simplices.truncate(static_cast<std::uint32_t>(b));
  s_.result_.boundary_points.resize(b * d_);
  s_.last_progress_ = m.last_progress;
  s_.result_.status = m.status;
  if (s_.keep_cofacets_) {
    s_.cofacet_places_.resize(m.kept_cofacets);
    s_.cofacet_offsets_.resize(m.kept_cofacets + 1);
    s_.cofacet_facets_.resize(s_.cofacet_offsets_.back());
    s_.cofacets_met_ = m.cofacets_met;
  }
}

// False when S, indexed on the way, holds a simplex twice (see walk).
bool ParallelWalk::walk_levels() {
  level_ = {s_.head_, s_.head_};
  while (s_.head_ < s_.result_.simplices.size()) {
    if (!s_.start_level()) return fill_pending(), true;
    const std::uint32_t begin = s_.head_, end = s_.level_end_;
    previous_level_ = level_;
    level_ = {begin, end};
    // About 32 chunks per worker: the last chunk of a level, which the other workers wait for, is
    // short (8 per worker left a third of a millisecond per level of imbalance). Each worker keeps to
    // its own share of consecutive chunks anyway. The result does not depend on the chunking.
    const std::uint32_t chunk = std::clamp<std::uint32_t>((end - begin) / (32 * workers_.size()), 16, 4096);
    const std::size_t n = (end - begin + chunk - 1) / chunk;
    std::vector<ChunkOutput>& outputs = chunks_[current_];
    if (outputs.size() < n) outputs.resize(n);
    for (Worker& w : workers_)
      w.tested.clear(), w.payload.clear(), w.output_in.clear(), w.output_row.clear(), w.data.clear();
    if (!pool_) pool_ = std::make_unique<WorkerPool>(static_cast<int>(workers_.size()));
    claims_.reset(n, workers_.size());
    pool_->run(workers_.size(), [&](std::size_t share, int worker) {
      open_windows(workers_[worker]);
      for (std::size_t c; claims_.claim(share, c);) {
        outputs[c].clear();
        const std::uint32_t a = begin + static_cast<std::uint32_t>(c) * chunk, b = std::min(end, a + chunk);
        fill(a, b);
        process_chunk(static_cast<std::uint32_t>(c), a, b, workers_[worker], outputs[c]);
      }
    });
    pending_ = {0, 0};  // (the workers copied the level in)
    merge(n);
    if (s_.keep_cofacets_) keep_cofacets(n);
    s_.head_ = end;
    if (4 * s_.result_.simplices.unindexed() > 3 * s_.result_.simplices.size()) {
      fill_pending();
      if (s_.result_.simplices.index_appended() != PackedKeyIndex::kAbsent) return false;
    }
  }
  return true;
}

// SequentialWalk::walk on the simplices [begin, end) of S, with classify_in_level for classify.
void ParallelWalk::process_chunk(std::uint32_t chunk, std::uint32_t begin, std::uint32_t end, Worker& worker,
                                 ChunkOutput& out) {
  const int words = packed_words(d_);
  Simplex tau;
  CofaceEnumerator cofacets;
  std::uint32_t mu_key[packed_words(kMaxDimension)];
  for (std::uint32_t id = begin; id < end; ++id) {
    const std::uint32_t* tau_key = s_.result_.simplices.key(id);
    tau = unpack(tau_key, d_);
    const bool pivots = worker.oracle->pivot_enter(tau);
    cofacets.reset(tau, k_ + 1);
    const std::uint64_t settled = std::atomic_ref<std::uint64_t>(s_.settled_[id]).load(std::memory_order_relaxed);
    std::uint32_t place = 0;  // μ's among τ's cofacets
    for (const Simplex* cofacet; (cofacet = cofacets.next()) != nullptr; ++place) {
      if (place < 64 && (settled >> place & 1) != 0) continue;
      const Simplex& mu = *cofacet;
      const std::size_t known = out.inside_arrivals.size();
      std::uint64_t other = kMiss;
      const Found f =
          other_transverse_facet(*worker.oracle, pivots, tau, tau_key, s_.arrivals_[id], mu,
                                 [&](const Simplex& s) { return classify_in_level(s, chunk, worker, out, other); });
      if (s_.keep_cofacets_ && f.facet != kArrival && (f.kind != Kind::inside || other > id))  // (a row: > id)
        out.kept.push_back({id, place, f.kind == Kind::inside ? other : kMiss});
      if (s_.settle_cofacets_ && f.kind == Kind::inside && other > id)  // (the cofacet of arrival among them)
        settle(mu, f.facet, other, out);
      else if (f.kind == Kind::inside && out.inside_arrivals.size() > known)  // first found now, through μ
        out.inside_arrivals.back() =
            arrival_code(mu, f.facet, out.inside_keys.data() + out.inside_keys.size() - words, d_);
      if (f.kind != Kind::outside) continue;
      // μ crosses the boundary (see SequentialWalk::add_boundary; duplicates are dropped by the merge)
      const double* p = s_.result_.points.data() + static_cast<std::size_t>(id) * d_;
      pack(mu, mu_key);
      out.boundary_keys.insert(out.boundary_keys.end(), mu_key, mu_key + words);
      append_boundary_point(out.boundary_points, p, s_.domain_values_[id], worker.data.data() + f.index, d_);
    }
    out.cofacets_met += place;
  }
}

// SequentialWalk::settle for a level: μ was walked to its facet `facet`, `other` (as
// ChunkOutput::KeptCofacet::other), a simplex of the next level (marked by the merge) or a later
// one of this level (marked now: the worker walking it may pass μ by or not, and finds the same).
void ParallelWalk::settle(const Simplex& mu, int facet, std::uint64_t other, ChunkOutput& out) {
  const std::uint64_t place = place_among_facet_cofacets(mu, facet);
  if (place >= 64) return;
  if ((other & ChunkOutput::kRow) != 0)
    out.settled.push_back({other, static_cast<std::uint32_t>(place)});
  else
    std::atomic_ref<std::uint64_t>(s_.settled_[other]).fetch_or(std::uint64_t{1} << place, std::memory_order_relaxed);
}

// SequentialWalk::classify for a level: S is read-only during a level, so discoveries go to `out`.
// The merge keeps the first occurrence in chunk order, so a new simplex is output by each chunk of
// the worker that meets it before every chunk that output it so far (chunks are taken in no fixed
// order).
Found ParallelWalk::classify_in_level(const Simplex& tau, std::uint32_t chunk, Worker& worker, ChunkOutput& out,
                                      std::uint64_t& other) {
  const int words = packed_words(d_);
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  const std::uint64_t h = hash_words(key, words);
  // (a simplex of an older level, which only a degenerate oracle could show, would be tested again
  // and output: see walk)
  if (std::uint32_t id = find_near(worker, key, h); id != PackedKeyIndex::kAbsent) {
    other = id;
    return {Kind::inside, id};
  }
  // (no structured binding: clang 14 cannot capture one in a lambda)
  const std::pair<std::uint32_t, bool> inserted = worker.tested.insert(key, h);
  const std::uint32_t id = inserted.first;
  const bool fresh = inserted.second;
  const auto output = [&](const double* found) {
    out.inside_keys.insert(out.inside_keys.end(), key, key + words);
    out.inside_hashes.push_back(h);
    out.inside_arrivals.push_back(kNoCofacet);  // set by process_chunk
    out.inside_data.insert(out.inside_data.end(), found, found + d_ + 1);
    worker.output_in[id] = chunk;
    worker.output_row[id] = static_cast<std::uint32_t>(out.inside_hashes.size() - 1);
  };
  if (fresh) {
    worker.output_in.push_back(kMiss);
    worker.output_row.push_back(0);
    ++worker.calls;
    double found[kMaxDimension + 1];  // point, D̂
    const Intersection x = worker.oracle->intersect(tau, found);
    found[d_] = x.domain;
    std::uint32_t payload = kMiss;
    if (x.hit) {
      payload = static_cast<std::uint32_t>(worker.data.size());
      worker.data.insert(worker.data.end(), found, found + d_ + 1);
      if (x.domain < 0) output(found);
    }
    worker.payload.push_back(payload);
  }
  const std::uint32_t p = worker.payload[id];
  if (p == kMiss) return {Kind::miss, 0};
  if (worker.data[p + d_] >= 0) return {Kind::outside, p};
  if (chunk < worker.output_in[id]) output(worker.data.data() + p);
  other = ChunkOutput::kRow | std::uint64_t{worker.output_in[id]} << 32 | worker.output_row[id];
  return {Kind::inside, p};
}

// Makes the worker's indexes those of the current and the previous level (at the first level of a
// walk the previous one is empty: S before this walk is not next to it). A worker that sat out a
// level (the others took all its chunks) builds both.
void ParallelWalk::open_windows(Worker& worker) const {
  if (worker.near_range[0] == level_) return;
  const auto build = [&](int i, std::pair<std::uint32_t, std::uint32_t> range) {
    worker.near[i].clear();
    worker.near[i].reserve(range.second - range.first);
    for (std::uint32_t id = range.first; id < range.second; ++id)  // (a level not copied into S yet: see fill)
      worker.near[i].insert(range == pending_ ? source_key(chunks_[current_ ^ 1], sources_[id - range.first])
                                              : s_.result_.simplices.key(id));
    worker.near_range[i] = range;
  };
  if (worker.near_range[0] == previous_level_) {
    std::swap(worker.near[0], worker.near[1]);
    std::swap(worker.near_range[0], worker.near_range[1]);
  } else {
    build(1, previous_level_);
  }
  build(0, level_);
}

inline std::uint32_t ParallelWalk::find_near(const Worker& worker, const std::uint32_t* key, std::uint64_t hash) {
  for (int i = 0; i < 2; ++i)
    if (const std::uint32_t id = worker.near[i].find(key, hash); id != PackedKeyIndex::kAbsent)
      return worker.near_range[i].first + id;
  return PackedKeyIndex::kAbsent;
}

// Appends the level's discoveries to S in chunk order (the first occurrence of a simplex wins, as in
// the sequential walk). The workers found none of them in the current or the previous level, so
// they are only deduplicated among themselves, in a small table of hash tags that reads a key only
// when tags match (half the outputs were written by another core: every line read is a transfer),
// and appended to S unindexed. S's arrays grow here; each simplex is copied in by the worker that
// takes it in the next level (fill), so that the copying and its page faults are shared; their
// settled cofacets are marked here.
void ParallelWalk::merge(std::size_t n_chunks) {
  std::vector<ChunkOutput>& outputs = chunks_[current_];
  const int words = packed_words(d_);
  std::size_t rows = 0;
  for (std::size_t c = 0; c < n_chunks; ++c) rows += outputs[c].inside_hashes.size();
  std::size_t capacity = 16;
  while (capacity < 2 * rows) capacity *= 2;  // load ≤ 1/2
  const LinearProbe probe(capacity);
  firsts_.assign(capacity, 0);
  sources_.clear();
  const std::uint32_t first = s_.result_.simplices.size();
  for (std::size_t c = 0; c < n_chunks; ++c) {
    ChunkOutput& out = outputs[c];
    out.inside_ids.resize(out.inside_hashes.size());
    for (std::size_t r = 0; r < out.inside_hashes.size(); ++r) {
      const std::uint32_t tag = LinearProbe::tag_of(out.inside_hashes[r]);
      const std::uint32_t* key = out.inside_keys.data() + r * words;
      const std::size_t s = probe.find(
          tag, [&](std::size_t i) { return firsts_[i]; },
          [&](std::uint32_t payload) {  // output by an earlier chunk
            return std::equal(key, key + words, source_key(outputs, sources_[payload - 1]));
          });
      if (firsts_[s] == 0) {
        firsts_[s] = LinearProbe::entry(out.inside_hashes[r], static_cast<std::uint32_t>(sources_.size() + 1));
        sources_.push_back(c << 32 | r);
      }
      out.inside_ids[r] = first + LinearProbe::payload(firsts_[s]) - 1;
    }
  }
  TraceResult& result = s_.result_;
  const std::uint32_t added = static_cast<std::uint32_t>(sources_.size());
  const std::uint32_t appended_at = result.simplices.append_unindexed(added);
  COXMESH_ASSERT(appended_at == first);
  const std::size_t size = std::size_t{first} + added;
  grow_with_headroom(result.points, size * d_);
  grow_with_headroom(s_.domain_values_, size);
  grow_with_headroom(s_.arrivals_, size);
  grow_with_headroom(s_.settled_, size);
  std::fill(s_.settled_.data() + first, s_.settled_.data() + size, kNoneSettled);
  for (std::size_t c = 0; c < n_chunks; ++c)
    for (const ChunkOutput::Settled& m : outputs[c].settled) {
      const std::uint32_t id = outputs[m.row >> 32 & 0x7FFFFFFFu].inside_ids[static_cast<std::uint32_t>(m.row)];
      s_.settled_[id] |= std::uint64_t{1} << m.place;
    }
  pending_ = {first, first + added};
  for (std::size_t c = 0; c < n_chunks; ++c) {
    const ChunkOutput& out = outputs[c];
    for (std::size_t r = 0; r * words < out.boundary_keys.size(); ++r)
      if (result.boundary_simplices.insert(out.boundary_keys.data() + r * words).second) {
        const double* p = out.boundary_points.data() + r * d_;
        result.boundary_points.insert(result.boundary_points.end(), p, p + d_);
      }
  }
  current_ ^= 1;  // the next level keeps these outputs to copy from
}

// The level's kept cofacets in chunk order (the sequential walk's), their other facets named by ids.
void ParallelWalk::keep_cofacets(std::size_t n_chunks) {
  const std::vector<ChunkOutput>& outputs = chunks_[current_ ^ 1];  // (merge has turned the buffers)
  for (std::size_t c = 0; c < n_chunks && s_.keep_cofacets_; ++c) {
    for (const ChunkOutput::KeptCofacet& k : outputs[c].kept) {
      const std::uint32_t other =
          (k.other & ChunkOutput::kRow) == 0
              ? static_cast<std::uint32_t>(k.other)
              : outputs[k.other >> 32 & 0x7FFFFFFFu].inside_ids[static_cast<std::uint32_t>(k.other)];
      s_.keep_cofacet(k.tau, k.place, other);
    }
    s_.cofacets_met_ += outputs[c].cofacets_met;
  }
}

// Copies the simplices of S with ids in [begin, end) that the last merge appended in from the
// outputs they came from. Workers call it on disjoint ranges at once.
void ParallelWalk::fill(std::uint32_t begin, std::uint32_t end) {
  begin = std::max(begin, pending_.first), end = std::min(end, pending_.second);
  const std::vector<ChunkOutput>& outputs = chunks_[current_ ^ 1];
  const int words = packed_words(d_);
  for (std::uint32_t id = begin; id < end; ++id) {
    const std::uint64_t source = sources_[id - pending_.first];
    const ChunkOutput& out = outputs[source >> 32];
    const std::size_t r = static_cast<std::uint32_t>(source);
    s_.result_.simplices.set_appended(id, out.inside_keys.data() + r * words, out.inside_hashes[r]);
    const double* p = out.inside_data.data() + r * (d_ + 1);
    std::copy_n(p, d_, s_.result_.points.data() + static_cast<std::size_t>(id) * d_);
    s_.domain_values_[id] = p[d_];
    s_.arrivals_[id] = out.inside_arrivals[r];
  }
}

void ParallelWalk::fill_pending() {
  fill(pending_.first, pending_.second);
  pending_ = {0, 0};
}

}  // namespace coxmesh::walk
