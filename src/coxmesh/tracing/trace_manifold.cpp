// Thesis §4.3; spec §2.2 (tracing) and §2.3 (boundary). The one hot loop of coxmesh.
#include "coxmesh/tracing/trace_manifold.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/util/huge_page_allocator.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

namespace {

std::string point_text(std::span<const double> x) {
  std::ostringstream os;
  os.precision(10);
  os << "(";
  for (std::size_t i = 0; i < x.size(); ++i) os << (i ? "," : "") << x[i];
  os << ")";
  return os.str();
}

// What the walk knows of a tested k-simplex.
enum class Kind : std::uint8_t {
  miss,     // not transverse
  inside,   // transverse inside the domain: in S
  outside,  // transverse, D̂ ≥ 0 at its point: its cofacets cross the boundary
};
struct Found {
  Kind kind;
  std::uint32_t index;  // where the walk keeps the simplex (S id, or its point and D̂)
  int facet = -1;       // which facet of μ it is (the index of the vertex of μ it lacks)
};

// The lattice vertex w of a cofacet μ of τ not in τ, as 2 bits per coordinate of w − y(τ) ∈ {−1, 0, 1}
// (w and y(τ) are vertices of one simplex): with τ, it names μ exactly in 62 bits.
constexpr std::uint64_t kNoCofacet = ~std::uint64_t{0};  // "11" never occurs as a pair of bits
std::uint64_t cofacet_code(const std::int32_t* w, const std::uint32_t* tau_key, int d) {
  std::uint64_t code = 0;
  for (int i = 0; i < d; ++i)
    code |= static_cast<std::uint64_t>(w[i] - static_cast<std::int32_t>(tau_key[i]) + 1) << (2 * i);
  return code;
}

// The other transverse facet of a cofacet μ of τ ∈ S: M̂ ∩ μ is a segment between exactly two
// transverse facets of μ, τ and this one (spec §2.2). The oracle's door-in/door-out guess is
// tested first; without a guess, or when it is wrong, every facet is. `test` classifies a facet.
// μ is skipped (miss) when it is the cofacet τ was discovered through (`arrival`, a cofacet_code):
// its other transverse facet is τ's discoverer, already in S.
template <class Test>
Found other_transverse_facet(IntersectionOracle& oracle, bool pivots, const Simplex& tau, const std::uint32_t* tau_key,
                             std::uint64_t arrival, const Simplex& mu, Test&& test) {
  const int entry = extra_vertex_index(tau, mu);  // μ without its vertex `entry` is τ
  std::int32_t v[kMaxDimension];
  mu.vertex(entry, v);
  if (arrival != kNoCofacet && cofacet_code(v, tau_key, tau.d) == arrival) return {Kind::miss, 0};
  int guess = -1;
  if (pivots) {
    if (const int g = oracle.pivot_exit(v); g >= 0) {
      guess = g < entry ? g : g + 1;
      if (Found f = test(facet_without(mu, guess)); f.kind != Kind::miss) return f.facet = guess, f;
    }
  }
  for (int j = 0; j <= mu.k; ++j)
    if (j != entry && j != guess)
      if (Found f = test(facet_without(mu, j)); f.kind != Kind::miss) return f.facet = j, f;
  return {Kind::miss, 0};
}

// Tracing state: S lives in the result; every other tested k-simplex is remembered in `others_`
// (not transverse, or transverse outside the domain with its point), so the
// oracle sees each k-simplex at most once.
class Tracer {
 public:
  Tracer(const Triangulation& t, std::vector<IntersectionOracle*> oracles, const TraceOptions& options)
      : t_(t), oracle_(*oracles[0]), options_(options), d_(t.dimension()), k_(oracle_.codimension()),
        others_(packed_words(d_)) {
    result_.ambient_dimension = d_;
    result_.codimension = k_;
    result_.simplices = PackedKeyIndex(packed_words(d_));
    result_.boundary_simplices = PackedKeyIndex(packed_words(d_));
    for (IntersectionOracle* o : oracles) {
      const PackedKeyIndex empty(packed_words(d_));
      workers_.push_back(Worker{o, empty, {}, {}, {}, 0, {empty, empty}, {{0, 0}, {0, 0}}});
    }
  }

  void add_seed(std::span<const double> seed, bool must_succeed);
  void walk();
  bool stopped() const { return result_.status == TraceStatus::max_simplices_reached; }
  TraceResult finish() {
    for (const Worker& w : workers_) {
      result_.function_evaluations += w.oracle->function_evaluations();
      result_.oracle_calls += w.calls;
    }
    return std::move(result_);
  }

 private:
  static constexpr std::uint32_t kMiss = 0xFFFFFFFFu;

  Found classify(const Simplex& tau);
  void add_boundary(const Simplex& mu, std::uint32_t inside, const double* outside);
  bool start_level();  // false when the simplex limit stops the walk

  // ---- Parallel walk (level-synchronous) ----
  // What one chunk of a level discovered, in encounter order: inside simplices (key, hash, point,
  // D̂) and boundary simplices (key, point). Merged in chunk order, so the result is deterministic.
  struct alignas(64) ChunkOutput {
    std::vector<std::uint32_t> inside_keys, boundary_keys;
    std::vector<std::uint64_t> inside_hashes, inside_arrivals;
    std::vector<double> inside_data, boundary_points;
    void clear() {
      inside_keys.clear(), boundary_keys.clear(), inside_hashes.clear(), inside_arrivals.clear(), inside_data.clear(),
          boundary_points.clear();
    }
  };
  // A worker's oracle and its memory of the simplices it tested in the current level that were not
  // in S: workers share nothing but S, which no one modifies during a level.
  struct alignas(64) Worker {
    IntersectionOracle* oracle;
    PackedKeyIndex tested;
    std::vector<std::uint32_t> payload;  // kMiss or index into data
    std::vector<std::uint32_t> output_in;  // per tested simplex inside: the first chunk that output it
    std::vector<double> data;            // (d + 1) per transverse simplex: point, D̂
    std::uint64_t calls;
    // The simplices of S that a level's walk can meet: its own and the previous level's (a
    // neighbour of a simplex of level L is in level L − 1, L or L + 1). Two small indexes of
    // ids [near_range[i].first, near_range[i].second) of S instead of S's big one, whose lookups
    // missed the caches; one pair per worker, built by the worker itself: lookups of lines that
    // another core wrote last cost several times a local read.
    PackedKeyIndex near[2];
    std::pair<std::uint32_t, std::uint32_t> near_range[2];
  };
  // Which chunks of a level are left: worker w starts at the front of its own contiguous share, so
  // it keeps to one region of the manifold (its caches, its memory of tested simplices); a worker
  // out of chunks takes the last chunk of the largest remaining share.
  class ChunkClaims {
   public:
    void reset(std::size_t chunks, std::size_t workers) {
      shares_.clear();
      for (std::size_t w = 0; w < workers; ++w) shares_.push_back({chunks * w / workers, chunks * (w + 1) / workers});
    }
    bool claim(std::size_t share, std::size_t& chunk) {
      std::lock_guard<std::mutex> lock(mutex_);
      auto& [front, back] = shares_[share];
      if (front < back) return chunk = front++, true;
      std::size_t largest = 0;
      for (std::size_t w = 1; w < shares_.size(); ++w)
        if (shares_[w].second - shares_[w].first > shares_[largest].second - shares_[largest].first) largest = w;
      if (shares_[largest].first == shares_[largest].second) return false;
      return chunk = --shares_[largest].second, true;
    }

   private:
    std::mutex mutex_;
    std::vector<std::pair<std::size_t, std::size_t>> shares_;  // [front, back) per worker
  };
  bool walk_parallel();
  void walk_sequential();
  // What a parallel walk changes, to undo it when it has to be redone sequentially.
  struct Mark {
    std::uint32_t head, simplices, boundary_simplices;
    std::size_t last_progress;
    TraceStatus status;
  };
  Mark mark() const;
  void undo(const Mark& m);
  void open_windows(Worker& worker) const;
  static std::uint32_t find_near(const Worker& worker, const std::uint32_t* key, std::uint64_t hash);
  void process_chunk(std::uint32_t chunk, std::uint32_t begin, std::uint32_t end, Worker& worker, ChunkOutput& out);
  const std::uint32_t* source_key(const std::vector<ChunkOutput>& outputs, std::uint64_t source) const {
    return outputs[source >> 32].inside_keys.data() + static_cast<std::uint32_t>(source) * packed_words(d_);
  }
  void fill(std::uint32_t begin, std::uint32_t end);
  void fill_pending();
  Found classify_in_level(const Simplex& tau, std::uint32_t chunk, Worker& worker, ChunkOutput& out);
  void merge(std::size_t n_chunks);

  const Triangulation& t_;
  IntersectionOracle& oracle_;  // the first worker's; seeds and the sequential walk use it
  const TraceOptions& options_;
  const int d_, k_;
  TraceResult result_;
  UninitializedHugeVector<double> domain_values_;    // D̂ at each point of S
  UninitializedHugeVector<std::uint64_t> arrivals_;  // per simplex of S: the cofacet it was discovered through
  PackedKeyIndex others_;
  std::vector<std::uint32_t> other_payload_;  // kMiss or index into outside_
  std::vector<double> outside_;               // (d + 1) per transverse simplex outside: point, D̂
  std::uint32_t head_ = 0;                    // S[head_..] is the breadth-first queue
  std::uint32_t level_end_ = 0;               // end of the current breadth-first level
  std::size_t last_progress_ = 0;
  std::vector<double> point_;
  std::vector<Worker> workers_;
  // The chunks' outputs of the last two levels: the merge appends level L + 1 to S without copying
  // it, and the workers of level L + 1 copy each simplex in when they take its chunk (`fill`).
  std::vector<ChunkOutput> chunks_[2];
  int current_ = 0;                          // which of chunks_ the level being walked writes
  std::vector<std::uint64_t> sources_;       // per simplex of S from `pending_.first`: chunk << 32 | row
  std::pair<std::uint32_t, std::uint32_t> pending_{0, 0};  // ids of S appended and not copied in yet
  ChunkClaims claims_;
  std::pair<std::uint32_t, std::uint32_t> level_, previous_level_;  // ids of S (parallel walk)
  std::vector<std::uint64_t> firsts_;  // the merge's hash table: tag << 32 | 1 + index into sources_
  std::unique_ptr<WorkerPool> pool_;  // started by the first parallel level
};

Found Tracer::classify(const Simplex& tau) {
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  const std::uint64_t h = hash_words(key, packed_words(d_));
  std::size_t slot;  // where τ goes in S if it is new and inside
  if (std::uint32_t id = result_.simplices.find(key, h, slot); id != PackedKeyIndex::kAbsent) return {Kind::inside, id};
  if (std::uint32_t id = others_.find(key, h); id != PackedKeyIndex::kAbsent) {
    const std::uint32_t p = other_payload_[id];
    return p == kMiss ? Found{Kind::miss, 0} : Found{Kind::outside, p};
  }
  ++workers_[0].calls;
  point_.resize(d_);
  const Intersection x = oracle_.intersect(tau, point_.data());
  std::uint32_t payload = kMiss;
  if (x.hit) {
    if (x.domain < 0) {
      const std::uint32_t id = result_.simplices.insert_at(slot, key, h);
      result_.points.insert(result_.points.end(), point_.begin(), point_.end());
      domain_values_.push_back(x.domain);
      arrivals_.push_back(kNoCofacet);  // set by the walk
      return {Kind::inside, id};
    } else {
      payload = static_cast<std::uint32_t>(outside_.size());
      outside_.insert(outside_.end(), point_.begin(), point_.end());
      outside_.push_back(x.domain);
    }
  }
  others_.insert(key, h);
  other_payload_.push_back(payload);
  return payload == kMiss ? Found{Kind::miss, 0} : Found{Kind::outside, payload};
}

// μ ∩ M̂ is the segment between the points of its two transverse facets; D̂ is linear on it, so the
// boundary point is where it crosses 0. `outside` = point and D̂ of the facet outside the domain.
void Tracer::add_boundary(const Simplex& mu, std::uint32_t inside, const double* outside) {
  if (!result_.boundary_simplices.insert(mu).second) return;
  const double* p = result_.points.data() + static_cast<std::size_t>(inside) * d_;
  const double dp = domain_values_[inside], dq = outside[d_];
  const double t = dp / (dp - dq);  // dp < 0 ≤ dq
  for (int i = 0; i < d_; ++i) result_.boundary_points.push_back(p[i] + t * (outside[i] - p[i]));
}

// The simplex limit is checked where a breadth-first level starts, in the sequential and the
// parallel walk alike, so a truncated result is also the same for every thread count.
bool Tracer::start_level() {
  level_end_ = result_.simplices.size();
  if (result_.simplices.size() >= options_.max_simplices) {
    result_.status = TraceStatus::max_simplices_reached;
    return false;
  }
  if (options_.progress && result_.simplices.size() >= last_progress_ + 65536) {
    last_progress_ = result_.simplices.size();
    options_.progress(last_progress_);
  }
  return true;
}

// The parallel walk appends its levels to S without indexing them (its workers look simplices up
// in the indexes of two levels), and S is indexed at the end, and whenever it has grown fourfold
// since it last was (so a walk gone astray wastes at most that much; every fourfold, not twofold:
// each indexing grows the table into fresh memory, 30 % of its time on S^2 in R^3). A simplex met
// twice shows up there; only an oracle for which the walk's graph is not symmetric (a cofacet with
// more than two transverse facets) can cause that, and the walk is then redone sequentially, so
// the result is the same for every thread count in every case.
void Tracer::walk() {
  if (workers_.size() == 1) return walk_sequential();
  const Mark before = mark();
  if (walk_parallel() && result_.simplices.index_appended() == PackedKeyIndex::kAbsent) return;
  undo(before);
  walk_sequential();
}

Tracer::Mark Tracer::mark() const {
  return {head_, result_.simplices.size(), result_.boundary_simplices.size(), last_progress_, result_.status};
}

void Tracer::undo(const Mark& m) {
  const std::size_t n = m.simplices, b = m.boundary_simplices;
  head_ = level_end_ = m.head;
  pending_ = {0, 0};
  result_.simplices.truncate(static_cast<std::uint32_t>(n));
  result_.points.resize(n * d_);
  domain_values_.resize(n);
  arrivals_.resize(n);
  result_.boundary_simplices.truncate(static_cast<std::uint32_t>(b));
  result_.boundary_points.resize(b * d_);
  last_progress_ = m.last_progress;
  result_.status = m.status;
}

void Tracer::walk_sequential() {
  Simplex tau;
  CofaceEnumerator cofacets;
  std::int32_t v[kMaxDimension];
  for (; head_ < result_.simplices.size(); ++head_) {
    if (head_ >= level_end_ && !start_level()) return;
    tau = result_.simplices.simplex(head_, d_);
    const bool pivots = oracle_.pivot_enter(tau);
    cofacets.reset(tau, k_ + 1);
    while (const Simplex* cofacet = cofacets.next()) {
      const Simplex& mu = *cofacet;
      const std::uint32_t known = result_.simplices.size();
      // (τ's key is fetched per cofacet: classify appends to S, which may move the keys)
      const Found f = other_transverse_facet(oracle_, pivots, tau, result_.simplices.key(head_), arrivals_[head_], mu,
                                             [this](const Simplex& s) { return classify(s); });
      if (f.kind == Kind::outside) add_boundary(mu, head_, outside_.data() + f.index);
      if (f.kind == Kind::inside && f.index >= known) {  // discovered now, through μ
        mu.vertex(f.facet, v);
        arrivals_[f.index] = cofacet_code(v, result_.simplices.key(f.index), d_);
      }
    }
  }
}

// Makes the worker's indexes those of the current and the previous level (at the first level of a
// walk the previous one is empty: S before this walk is not next to it). A worker that sat out a
// level (the others took all its chunks) builds both.
void Tracer::open_windows(Worker& worker) const {
  if (worker.near_range[0] == level_) return;
  const auto build = [&](int i, std::pair<std::uint32_t, std::uint32_t> range) {
    worker.near[i].clear();
    worker.near[i].reserve(range.second - range.first);
    for (std::uint32_t id = range.first; id < range.second; ++id)  // (a level not copied into S yet: see fill)
      worker.near[i].insert(range == pending_ ? source_key(chunks_[current_ ^ 1], sources_[id - range.first])
                                              : result_.simplices.key(id));
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

std::uint32_t Tracer::find_near(const Worker& worker, const std::uint32_t* key, std::uint64_t hash) {
  for (int i = 0; i < 2; ++i)
    if (const std::uint32_t id = worker.near[i].find(key, hash); id != PackedKeyIndex::kAbsent)
      return worker.near_range[i].first + id;
  return PackedKeyIndex::kAbsent;
}

// False when S, indexed on the way, holds a simplex twice (see walk).
bool Tracer::walk_parallel() {
  level_ = {head_, head_};
  while (head_ < result_.simplices.size()) {
    if (!start_level()) return fill_pending(), true;
    const std::uint32_t begin = head_, end = level_end_;
    previous_level_ = level_;
    level_ = {begin, end};
    // About 32 chunks per worker: the last chunk of a level, which the other workers wait for, is
    // short (8 per worker left a third of a millisecond per level of imbalance). Each worker keeps to
    // its own share of consecutive chunks anyway. The result does not depend on the chunking.
    const std::uint32_t chunk = std::clamp<std::uint32_t>((end - begin) / (32 * workers_.size()), 16, 4096);
    const std::size_t n = (end - begin + chunk - 1) / chunk;
    std::vector<ChunkOutput>& outputs = chunks_[current_];
    if (outputs.size() < n) outputs.resize(n);
    for (Worker& w : workers_) w.tested.clear(), w.payload.clear(), w.output_in.clear(), w.data.clear();
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
    head_ = end;
    if (4 * result_.simplices.unindexed() > 3 * result_.simplices.size()) {
      fill_pending();
      if (result_.simplices.index_appended() != PackedKeyIndex::kAbsent) return false;
    }
  }
  return true;
}

// The parallel classify: S is read-only during a level, so discoveries go to `out`. The merge keeps
// the first occurrence in chunk order, so a new simplex is output by each chunk of the worker that
// meets it before every chunk that output it so far (chunks are taken in no fixed order).
Found Tracer::classify_in_level(const Simplex& tau, std::uint32_t chunk, Worker& worker, ChunkOutput& out) {
  const int words = packed_words(d_);
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  const std::uint64_t h = hash_words(key, words);
  // (a simplex of an older level, which only a degenerate oracle could show, would be tested again
  // and output: see walk)
  if (std::uint32_t id = find_near(worker, key, h); id != PackedKeyIndex::kAbsent) return {Kind::inside, id};
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
  };
  if (fresh) {
    worker.output_in.push_back(kMiss);
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
  return {Kind::inside, p};
}

void Tracer::process_chunk(std::uint32_t chunk, std::uint32_t begin, std::uint32_t end, Worker& worker, ChunkOutput& out) {
  const int words = packed_words(d_);
  Simplex tau;
  CofaceEnumerator cofacets;
  std::uint32_t mu_key[packed_words(kMaxDimension)];
  std::int32_t v[kMaxDimension];
  for (std::uint32_t id = begin; id < end; ++id) {
    const std::uint32_t* tau_key = result_.simplices.key(id);
    tau = unpack(tau_key, d_);
    const bool pivots = worker.oracle->pivot_enter(tau);
    cofacets.reset(tau, k_ + 1);
    while (const Simplex* cofacet = cofacets.next()) {
      const Simplex& mu = *cofacet;
      const std::size_t known = out.inside_arrivals.size();
      const Found f = other_transverse_facet(*worker.oracle, pivots, tau, tau_key, arrivals_[id], mu,
                                             [&](const Simplex& s) { return classify_in_level(s, chunk, worker, out); });
      if (f.kind == Kind::inside && out.inside_arrivals.size() > known) {  // first found now, through μ
        mu.vertex(f.facet, v);
        out.inside_arrivals.back() = cofacet_code(v, out.inside_keys.data() + out.inside_keys.size() - words, d_);
      }
      if (f.kind != Kind::outside) continue;
      // μ crosses the boundary (see add_boundary)
      const double* q = worker.data.data() + f.index;
      const double* p = result_.points.data() + static_cast<std::size_t>(id) * d_;
      const double dp = domain_values_[id], t = dp / (dp - q[d_]);
      pack(mu, mu_key);
      out.boundary_keys.insert(out.boundary_keys.end(), mu_key, mu_key + words);
      for (int i = 0; i < d_; ++i) out.boundary_points.push_back(p[i] + t * (q[i] - p[i]));
    }
  }
}

// Appends the level's discoveries to S in chunk order (the first occurrence of a simplex wins, as in
// the sequential walk). The workers found none of them in the current or the previous level, so
// they are only deduplicated among themselves, in a small table of hash tags that reads a key only
// when tags match (half the outputs were written by another core: every line read is a transfer),
// and appended to S unindexed. S's arrays grow here; each simplex is copied in by the worker that
// takes it in the next level (fill), so that the copying and its page faults are shared.
void Tracer::merge(std::size_t n_chunks) {
  const std::vector<ChunkOutput>& outputs = chunks_[current_];
  const int words = packed_words(d_);
  std::size_t rows = 0;
  for (std::size_t c = 0; c < n_chunks; ++c) rows += outputs[c].inside_hashes.size();
  int bits = 4;
  while ((std::size_t{1} << bits) < 2 * rows) ++bits;  // load ≤ 1/2
  const std::size_t mask = (std::size_t{1} << bits) - 1;
  firsts_.assign(mask + 1, 0);
  sources_.clear();
  for (std::size_t c = 0; c < n_chunks; ++c) {
    const ChunkOutput& out = outputs[c];
    for (std::size_t r = 0; r < out.inside_hashes.size(); ++r) {
      const std::uint32_t tag = static_cast<std::uint32_t>(out.inside_hashes[r] >> 32);
      const std::uint32_t* key = out.inside_keys.data() + r * words;
      for (std::size_t s = tag >> (32 - bits);; s = (s + 1) & mask) {
        const std::uint64_t slot = firsts_[s];
        if (slot == 0) {
          firsts_[s] = std::uint64_t{tag} << 32 | (sources_.size() + 1);
          sources_.push_back(c << 32 | r);
          break;
        }
        if (slot >> 32 == tag &&
            std::equal(key, key + words, source_key(outputs, sources_[static_cast<std::uint32_t>(slot) - 1])))
          break;  // output by an earlier chunk
      }
    }
  }
  const std::uint32_t added = static_cast<std::uint32_t>(sources_.size());
  const std::uint32_t first = result_.simplices.append_unindexed(added);
  const std::size_t size = std::size_t{first} + added;
  grow_with_headroom(result_.points, size * d_);
  grow_with_headroom(domain_values_, size);
  grow_with_headroom(arrivals_, size);
  pending_ = {first, first + added};
  for (std::size_t c = 0; c < n_chunks; ++c) {
    const ChunkOutput& out = outputs[c];
    for (std::size_t r = 0; r * words < out.boundary_keys.size(); ++r)
      if (result_.boundary_simplices.insert(out.boundary_keys.data() + r * words).second) {
        const double* p = out.boundary_points.data() + r * d_;
        result_.boundary_points.insert(result_.boundary_points.end(), p, p + d_);
      }
  }
  current_ ^= 1;  // the next level keeps these outputs to copy from
}

// Copies the simplices of S with ids in [begin, end) that the last merge appended in from the
// outputs they came from. Workers call it on disjoint ranges at once.
void Tracer::fill(std::uint32_t begin, std::uint32_t end) {
  begin = std::max(begin, pending_.first), end = std::min(end, pending_.second);
  const std::vector<ChunkOutput>& outputs = chunks_[current_ ^ 1];
  const int words = packed_words(d_);
  for (std::uint32_t id = begin; id < end; ++id) {
    const std::uint64_t source = sources_[id - pending_.first];
    const ChunkOutput& out = outputs[source >> 32];
    const std::size_t r = static_cast<std::uint32_t>(source);
    result_.simplices.set_appended(id, out.inside_keys.data() + r * words, out.inside_hashes[r]);
    const double* p = out.inside_data.data() + r * (d_ + 1);
    std::copy_n(p, d_, result_.points.data() + static_cast<std::size_t>(id) * d_);
    domain_values_[id] = p[d_];
    arrivals_[id] = out.inside_arrivals[r];
  }
}

void Tracer::fill_pending() {
  fill(pending_.first, pending_.second);
  pending_ = {0, 0};
}

void Tracer::add_seed(std::span<const double> seed, bool must_succeed) {
  if (static_cast<int>(seed.size()) != d_)
    throw InputError("the seed " + point_text(seed) + " has " + std::to_string(seed.size()) +
                     " coordinates, expected " + std::to_string(d_));
  const Simplex sigma = t_.locate(seed);
  // Ring 0: the d-simplices containing the seed, at most 720 of them (a seed on a lattice vertex
  // lies in (d+1)! of them, 3.6 million for d = 9: see generic_seed); ring r+1: the neighbours of
  // ring r across facets.
  PackedKeyIndex seen(packed_words(d_));
  std::vector<Simplex> ring, next;
  CofaceEnumerator cofaces(sigma, d_);
  for (Simplex s; ring.size() < 720 && cofaces.next(s);)
    if (seen.insert(s).second) ring.push_back(s);
  bool outside_hit = false;
  for (int r = 0; r <= options_.seed_search_rings && !ring.empty(); ++r) {
    bool inside_hit = false;
    for (const Simplex& s : ring) {
      FaceEnumerator faces(s, k_);
      for (Simplex tau; faces.next(tau);) {
        const Found f = classify(tau);
        inside_hit |= f.kind == Kind::inside;
        outside_hit |= f.kind == Kind::outside;
      }
    }
    if (inside_hit) return;
    next.clear();
    for (const Simplex& s : ring) {
      FaceEnumerator faces(s, d_ - 1);
      for (Simplex f; faces.next(f);) {
        CofaceEnumerator across(f, d_);
        for (Simplex n; across.next(n);)
          if (seen.insert(n).second) next.push_back(n);
      }
    }
    ring.swap(next);
  }
  if (!must_succeed) return;
  if (outside_hit)
    throw SeedError("the seed " + point_text(seed) + " is outside the domain: the manifold near it has D >= 0");
  throw SeedError("no simplex within " + std::to_string(options_.seed_search_rings) + " rings of the seed " +
                  point_text(seed) +
                  " meets the manifold: the seed is too far from it, or the triangulation is too coarse for it");
}

}  // namespace

namespace {

TraceResult run_tracer(const Triangulation& triangulation, std::vector<IntersectionOracle*> oracles,
                       const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  const int d = triangulation.dimension();
  for (IntersectionOracle* o : oracles)
    if (o->ambient_dimension() != d)
      throw InputError("the oracle works in R^" + std::to_string(o->ambient_dimension()) +
                       " but the triangulation is of R^" + std::to_string(d));
  if (seeds.empty()) throw SeedError("no seed given");
  Tracer tracer(triangulation, std::move(oracles), options);
  for (const auto& seed : seeds) {
    // Past the limit, no more seeds: each would add its simplices and a level of walk (thousands
    // of automatic seeds took S far past the limit).
    if (tracer.stopped()) break;
    tracer.add_seed(seed, !options.skip_unusable_seeds);
    tracer.walk();
  }
  TraceResult result = tracer.finish();
  if (result.status == TraceStatus::max_simplices_reached)
    result.message = "stopped at the limit of " + std::to_string(options.max_simplices) +
                     " simplices; the manifold may be unbounded (give a domain or a box) or the scale too fine";
  return result;
}

}  // namespace

TraceResult trace_manifold(const Triangulation& triangulation, IntersectionOracle& oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  return run_tracer(triangulation, {&oracle}, seeds, options);
}

TraceResult trace_manifold(const Triangulation& triangulation, const OracleFactory& make_oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  const int workers = resolve_threads(options.threads);
  std::vector<std::unique_ptr<IntersectionOracle>> owned;
  std::vector<IntersectionOracle*> oracles;
  for (int w = 0; w < workers; ++w) {
    owned.push_back(make_oracle());
    if (!owned.back()) throw InputError("the oracle factory returned no oracle");
    oracles.push_back(owned.back().get());
  }
  return run_tracer(triangulation, std::move(oracles), seeds, options);
}

}  // namespace coxmesh
