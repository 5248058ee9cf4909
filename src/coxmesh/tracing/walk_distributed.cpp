// Thesis §4.2 over several processes: the walk of one rank, level by level, and the seed search
// (every rank searches every seed, so all of them agree on what it found without a message).
#include "coxmesh/tracing/walk_distributed.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/tracing/seed_search.h"
#include "coxmesh/util/fixed_dimension.h"

namespace coxmesh::walk {

DistributedWalk::DistributedWalk(const Triangulation& t, IntersectionOracle& oracle, SharedVertexValues& values,
                                 const VertexEvaluator& evaluate, const TraceOptions& options, Communicator& comm)
    : t_(t),
      oracle_(oracle),
      values_(values),
      evaluate_(evaluate),
      options_(options),
      comm_(comm),
      d_(t.dimension()),
      k_(oracle.codimension()),
      words_(packed_words(d_)),
      rank_(comm.rank()),
      ranks_(comm.size()),
      mine_(words_),
      next_(words_),
      others_(words_),
      known_vertices_(d_),
      candidates_out_(ranks_),
      tested_out_(ranks_),
      handed_out_(ranks_),
      handed_values_out_(ranks_),
      point_(d_),
      last_owner_(d_, ranks_),
      vertex_owner_(d_, ranks_) {}

Found DistributedWalk::classify(const Simplex& tau) {
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  return classify(tau, key, hash_words(key, words_));
}

// As SequentialWalk::classify, with S split: this rank's part of S and of the next level are
// looked up, then everything else it tested; only then is the oracle asked.
Found DistributedWalk::classify(const Simplex& tau, const std::uint32_t* key, std::uint64_t h) {
  const int owner = last_owner_.of(tau.y.data());
  Slots slots;  // (where the test below inserts τ, found by these look-ups)
  if (owner == rank_) {
    if (const std::uint32_t id = mine_.find(key, h); id != PackedKeyIndex::kAbsent) return {Kind::inside, id};
    if (const std::uint32_t id = next_.find(key, h, slots.next); id != PackedKeyIndex::kAbsent)
      return {Kind::inside, id};
  }
  const std::uint32_t known = others_.find(key, h, slots.others);
  if (known != PackedKeyIndex::kAbsent) {
    const std::uint32_t p = other_payload_[known];
    if (p == kMiss) return {Kind::miss, 0};
    if (p == kRemoteInside) return {Kind::inside, 0};
    if (p != kUntested && p != kHanded) return {Kind::outside, p};
  }
  return test(key, h, tau, owner, known, slots);
}

// The oracle's answer on τ, kept where the walk will look for it. Each simplex tested is counted
// once in the whole job, by its owner: when it tests it, or when another rank reports it.
Found DistributedWalk::test(const std::uint32_t* key, std::uint64_t hash, const Simplex& tau, int owner,
                            std::uint32_t known, const Slots& slots) {
  if (handed_values_) load_handed_values();
  const bool owned = owner == rank_;
  if (owned && known == PackedKeyIndex::kAbsent) ++calls_;
  ++tests_;
  const Intersection x = oracle_.intersect(tau, point_.data());
  if (x.hit && x.domain < 0) {
    std::memcpy(fresh_key_, key, sizeof(std::uint32_t) * words_);
    if (owned) {
      const std::uint32_t id = next_.insert_at(slots.next, key, hash);  // (absent: classify looked)
      next_keys_.push_back(discovery_);
      next_arrivals_.push_back(kNoCofacet);
      next_data_.insert(next_data_.end(), point_.begin(), point_.end());
      next_data_.push_back(x.domain);
      fresh_ = Fresh::owned, fresh_at_ = id;
      return {Kind::inside, id};
    }
    if (known == PackedKeyIndex::kAbsent) {
      others_.insert_at(slots.others, key, hash);  // (classify looked, and τ is not ours)
      other_payload_.push_back(kRemoteInside);
    } else {  // (handed: its owner counts it)
      other_payload_[known] = kRemoteInside;
    }
    if (reporting_) {  // (in the seed search the owner tests it itself)
      std::vector<std::byte>& out = candidates_out_[owner];
      put(out, key, words_);
      put(out, &discovery_, 1);
      fresh_ = Fresh::remote, fresh_owner_ = owner, fresh_at_ = out.size();
      put(out, &kNoCofacet, 1);
      put(out, point_.data(), d_);
      put(out, &x.domain, 1);
      ++candidates_sent_;
    }
    return {Kind::inside, 0};
  }
  std::uint32_t payload = kMiss;
  if (x.hit) {
    payload = static_cast<std::uint32_t>(outside_.size());
    outside_.insert(outside_.end(), point_.begin(), point_.end());
    outside_.push_back(x.domain);
  }
  if (known == PackedKeyIndex::kAbsent) {
    others_.insert_at(slots.others, key, hash);
    other_payload_.push_back(payload);
    if (!owned && reporting_) put(tested_out_[owner], key, words_);
  } else {
    other_payload_[known] = payload;
  }
  return payload == kMiss ? Found{Kind::miss, 0} : Found{Kind::outside, payload};
}

// What the sequential walk records for a simplex discovered through μ.
void DistributedWalk::set_fresh_arrival(std::uint64_t arrival) {
  if (fresh_ == Fresh::owned) next_arrivals_[fresh_at_] = arrival;
  if (fresh_ == Fresh::remote) std::memcpy(candidates_out_[fresh_owner_].data() + fresh_at_, &arrival, sizeof arrival);
}

// SequentialWalk::walk on this rank's part of one level, in the order of their global ids, with
// its pipeline: the tables here are as far beyond the caches as S is there. The per-cofacet lattice
// work with d fixed at compile time for the common d, as there (walk_common.h).
void DistributedWalk::walk_level() {
  with_fixed_dimension<3, 4, 6, 9>(d_, [this](auto fixed_d) { walk_level<decltype(fixed_d)::value>(); });
}

template <int kD>
void DistributedWalk::walk_level() {
  Simplex tau;
  CofaceEnumerator cofacets;
  CofacetPipeline pipeline;
  for (std::uint32_t i = level_begin_; i < level_end_; ++i) {
    tau = mine_.simplex(i, d_);
    const bool pivots = oracle_.pivot_enter(tau);
    const ArrivalVertex<kD> arrival(mine_.key(i), arrivals_[i], d_);
    cofacets.reset(tau, k_ + 1);
    pipeline.run(
        cofacets,
        [&](const Simplex& mu, PendingCofacet& p) { return take_cofacet<kD>(oracle_, pivots, tau, arrival, mu, p); },
        [&](PendingCofacet& p) {
          if (guess_other_facet<kD>(oracle_, pivots, p)) fetch_slots(p);
        },
        [&](const PendingCofacet& p) { finish_cofacet<kD>(i, p); });
  }
}

// The slots where classify() will look the guess up.
void DistributedWalk::fetch_slots(const PendingCofacet& p) {
  if (last_owner_.of(p.facet.y.data()) == rank_) mine_.prefetch(p.hash), next_.prefetch(p.hash);
  others_.prefetch(p.hash);
}

template <int kD>
void DistributedWalk::finish_cofacet(std::uint32_t i, const PendingCofacet& p) {
  const Simplex& mu = p.mu;
  discovery_ = std::uint64_t{global_ids_[i]} << 32 | p.index;
  if (p.guess >= 0)  // (a guess this rank knows the answer of is classified here)
    if (const int owner = last_owner_.of<kD>(p.facet.y.data()); owner != rank_) {
      std::size_t slot;
      const std::uint32_t known = others_.find(p.key, p.hash, slot);
      if (known == PackedKeyIndex::kAbsent) {
        others_.insert_at(slot, p.key, p.hash);
        other_payload_.push_back(kHanded);
        return hand_over(p, owner, false);
      }
      if (other_payload_[known] == kHanded) return hand_over(p, owner, true);
    }
  fresh_ = Fresh::no;
  const Found f = classify_pending<kD>(
      p, [this](const Simplex& s, const std::uint32_t* key, std::uint64_t h) { return classify(s, key, h); },
      [this](const Simplex& s) { return classify(s); });
  if (f.kind == Kind::outside) {
    std::uint32_t key[packed_words(kMaxDimension)];
    pack(mu, key);
    boundary_keys_.push_back(discovery_);
    boundary_simplices_.insert(boundary_simplices_.end(), key, key + words_);
    append_boundary_point(boundary_points_, points_.data() + static_cast<std::size_t>(i) * d_, domain_values_[i],
                          outside_.data() + f.index, d_);
  } else if (f.kind == Kind::inside && fresh_ != Fresh::no) {
    set_fresh_arrival(arrival_code<kD>(mu, f.facet, fresh_key_, d_));
  }
}

// μ to the owner of its guessed facet, which settles it as finish_cofacet does (settle_handed):
// μ, the discovery, which vertex of μ is not τ's and which facet is the guess, and the values of
// μ's vertices that the owner does not own (all fetched here for this level; it has its own). A
// guess handed `again` goes with the value of μ's vertex outside it alone: when the guess is not in
// S, its owner has tested it, so it has the values of its vertices.
void DistributedWalk::hand_over(const PendingCofacet& p, int owner, bool again) {
  std::vector<std::byte>& out = handed_out_[owner];
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(p.mu, key);
  put(out, key, words_);
  put(out, &discovery_, 1);
  const std::uint32_t which =
      static_cast<std::uint32_t>(p.entry) | static_cast<std::uint32_t>(p.guess) << 8 | (again ? 1u : 0u) << 16;
  put(out, &which, 1);
  put(out, &p.hash, 1);
  std::vector<std::byte>& values_out = handed_values_out_[owner];
  std::int32_t v[kMaxDimension];
  double values[kMaxDimension + 1];
  for (int j = 0; j <= k_ + 1; ++j) {
    if (again && j != p.guess) continue;
    p.mu.vertex(j, v);
    if (vertex_owner_.of(v) == owner) continue;
    values_.get(v, hash_words(reinterpret_cast<const std::uint32_t*>(v), d_), values,
                [](double*) { throw std::logic_error("a vertex value missing from its level's"); });
    put(values_out, values, values_.stride());
  }
}

// The handed cofacets of other ranks' τ (hand_over's records from `in` to `end`), settled here as
// finish_cofacet settles this rank's: what they find for other ranks goes with the tests reported.
void DistributedWalk::settle_handed(const std::byte* in, const std::byte* const end, const std::byte* values) {
  const std::size_t record = sizeof(std::uint32_t) * (words_ + 1) + 2 * sizeof(std::uint64_t);
  const std::size_t vertex_values = sizeof(double) * values_.stride();
  const std::size_t n = static_cast<std::size_t>(end - in) / record;
  constexpr std::size_t kAhead = 8;  // (the guess's slots fetched ahead: its hash is in the record)
  const auto prefetch = [&](std::size_t i) {
    std::uint64_t h;
    std::memcpy(&h, in + i * record + record - sizeof h, sizeof h);
    mine_.prefetch(h), next_.prefetch(h), others_.prefetch(h);
  };
  for (std::size_t i = 0; i < std::min(n, kAhead); ++i) prefetch(i);
  PendingCofacet p;
  std::uint32_t key[packed_words(kMaxDimension)];
  std::int32_t v[kMaxDimension];
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) prefetch(i + kAhead);
    const std::byte* at = in + i * record;
    take(at, key, words_);
    take(at, &discovery_, 1);
    std::uint32_t which;
    take(at, &which, 1);
    take(at, &p.hash, 1);
    p.mu = handed_mu_ = unpack(key, d_);
    p.entry = static_cast<int>(which & 0xFF), p.guess = static_cast<int>(which >> 8 & 0xFF);
    handed_again_ = (which >> 16) != 0, handed_guess_ = p.guess;
    handed_values_ = values;
    for (int j = 0; j <= k_ + 1; ++j)
      if (!(handed_again_ && j != p.guess) && (p.mu.vertex(j, v), vertex_owner_.of(v) != rank_))
        values += vertex_values;
    p.facet = facet_without(p.mu, p.guess);
    pack(p.facet, p.key);
    fresh_ = Fresh::no;
    const Found f = classify_pending(
        p, [this](const Simplex& s, const std::uint32_t* k, std::uint64_t h) { return classify(s, k, h); },
        [this](const Simplex& s) { return classify(s); });
    if (f.kind == Kind::outside) {
      // τ's point and D̂ again (τ is in S: the oracle finds what it found then), for the boundary's.
      if (handed_values_) load_handed_values();
      double tau_point[kMaxDimension];
      const double tau_domain = oracle_.intersect(facet_without(p.mu, p.entry), tau_point).domain;
      boundary_keys_.push_back(discovery_);
      boundary_simplices_.insert(boundary_simplices_.end(), key, key + words_);
      append_boundary_point(boundary_points_, tau_point, tau_domain, outside_.data() + f.index, d_);
    } else if (f.kind == Kind::inside && fresh_ != Fresh::no) {
      set_fresh_arrival(arrival_code(p.mu, f.facet, fresh_key_, d_));
    } else if (f.kind == Kind::inside) {
      // Met before, from a τ walked later than this one maybe: the smallest discovery wins.
      const Simplex facet = facet_without(p.mu, f.facet);
      std::uint32_t facet_key[packed_words(kMaxDimension)];
      const std::uint64_t h = pack_hashed<0>(facet, facet_key);
      const std::uint64_t arrival = arrival_code(p.mu, f.facet, facet_key, d_);
      const int owner = last_owner_.of(facet.y.data());
      if (owner == rank_) {
        if (const std::uint32_t id = next_.find(facet_key, h);
            id != PackedKeyIndex::kAbsent && discovery_ < next_keys_[id])
          next_keys_[id] = discovery_, next_arrivals_[id] = arrival;
      } else {  // (its owner holds it already, with its point: this one is not read)
        std::vector<std::byte>& out = candidates_out_[owner];
        put(out, facet_key, words_);
        put(out, &discovery_, 1);
        put(out, &arrival, 1);
        out.resize(out.size() + sizeof(double) * (d_ + 1));
      }
    }
    handed_values_ = nullptr;
  }
}

// The values of the vertices of the handed cofacet being settled that this rank does not own,
// before its first test.
void DistributedWalk::load_handed_values() {
  const int stride = values_.stride();
  const std::byte* in = handed_values_;
  handed_values_ = nullptr;
  double scratch[kMaxDimension + 1];
  std::int32_t v[kMaxDimension];
  for (int j = 0; j <= k_ + 1; ++j) {
    if (handed_again_ && j != handed_guess_) continue;
    handed_mu_.vertex(j, v);
    if (vertex_owner_.of(v) == rank_) continue;
    const auto* key = reinterpret_cast<const std::uint32_t*>(v);
    const std::uint64_t h = hash_words(key, d_);
    values_.get(v, h, scratch, [&](double* values) { std::memcpy(values, in, sizeof(double) * stride); });
    known_vertices_.insert(key, h);  // (not asked for again)
    in += sizeof(double) * stride;
  }
}

// As SequentialWalk::start_level, on |S| over all ranks; progress is shown by rank 0.
bool DistributedWalk::start_level() {
  if (global_size_ >= options_.max_simplices) return stopped_ = true, false;
  if (rank_ == 0 && options_.progress && global_size_ >= last_progress_ + options_.progress_interval) {
    last_progress_ = global_size_;
    options_.progress(last_progress_);
  }
  return true;
}

void DistributedWalk::walk() {
  std::vector<std::int32_t> vertices;
  std::int32_t v[kMaxDimension];
  while (level_global_size_ > 0) {
    std::exception_ptr failure;
    bool go = false;
    try {
      go = start_level();
    } catch (...) {
      failure = std::current_exception();
    }
    agree(failure);
    if (!go) return;
    // The level's vertex values: τ's vertices and the one each cofacet adds (every vertex a test
    // of the level can read).
    vertices.clear();
    for (std::uint32_t i = level_begin_; i < level_end_; ++i) {
      const Simplex tau = mine_.simplex(i, d_);
      for (int j = 0; j <= k_; ++j) tau.vertex(j, v), vertices.insert(vertices.end(), v, v + d_);
      for_each_cofacet_vertex(tau, [&](const std::int32_t* w) { vertices.insert(vertices.end(), w, w + d_); });
    }
    fetch_vertex_values(vertices);
    try {
      walk_level();
    } catch (...) {
      failure = std::current_exception();
    }
    agree(failure);
    exchange_candidates();
    append_level();
    ++levels_;
  }
}

// SequentialWalk::add_seed on every rank: each tests the faces of the rings that it owns (the
// values of the rings' vertices fetched first) and keeps those of S, keyed by the order of the
// tests of one process; the ranks agree on what the ring met.
void DistributedWalk::add_seed(std::span<const double> seed, bool must_succeed) {
  check_seed_dimension(seed, d_);
  const Simplex sigma = t_.locate(seed);
  SeedRings rings(sigma, d_);
  bool inside_hit = false, outside_hit = false;
  std::uint64_t tests = 0;
  std::vector<std::int32_t> vertices;
  std::vector<std::uint64_t> level_keys;              // every rank's run of keys of the ring's simplices of S
  std::vector<std::size_t> run_begin(ranks_ + 1, 0);  // (rank r's from run_begin[r])
  reporting_ = false;
  for (int r = 0; r <= options_.seed_search_rings && !rings.ring().empty(); ++r) {
    const std::vector<Simplex>& ring = rings.ring();
    vertices.resize(ring.size() * (d_ + 1) * d_);
    for (std::size_t i = 0; i < ring.size(); ++i)
      for (int j = 0; j <= d_; ++j) ring[i].vertex(j, vertices.data() + (i * (d_ + 1) + j) * d_);
    std::exception_ptr failure = push_vertex_values(vertices);
    if (!failure) {  // (else nothing is tested: every rank throws below)
      try {
        for (const Simplex& s : ring) {
          FaceEnumerator faces(s, k_);
          for (Simplex tau; faces.next(tau);) {
            discovery_ = tests++;
            if (last_owner_.of(tau.y.data()) != rank_) continue;  // (its owner tests it)
            const Found f = classify(tau);
            inside_hit |= f.kind == Kind::inside;
            outside_hit |= f.kind == Kind::outside;
          }
        }
      } catch (...) {
        failure = std::current_exception();
      }
    }
    // The ring's verdict is that of all its faces, each tested by its owner; it goes with the keys
    // of the simplices of S found (the next level, if the ring met S), so that the ranks meet once
    // per ring (a sum, then a gather of the level's keys, had cost a quarter of a seed's meetings).
    std::vector<std::uint32_t> order;
    std::vector<std::uint64_t> words = {failure ? 1u : 0u, inside_hit ? 1u : 0u, outside_hit ? 1u : 0u};
    if (!failure) {
      const std::vector<std::uint64_t> keys = next_keys_in_order(order);
      words.insert(words.end(), keys.begin(), keys.end());
    }
    std::vector<std::byte> mine;
    put(mine, words.data(), words.size());
    std::vector<std::size_t> counts;
    const std::vector<std::byte> gathered = comm_.all_gather(mine, counts);
    words.resize(gathered.size() / sizeof(std::uint64_t));
    const std::byte* in = gathered.data();
    take(in, words.data(), words.size());
    std::uint64_t found[3] = {0, 0, 0};
    for (int r = 0, at = 0; r < ranks_; at += static_cast<int>(counts[r++] / sizeof(std::uint64_t))) {
      for (int i = 0; i < 3; ++i) found[i] |= words[at + i];
      level_keys.insert(level_keys.end(), words.begin() + at + 3,
                        words.begin() + at + static_cast<int>(counts[r] / sizeof(std::uint64_t)));
      run_begin[r + 1] = level_keys.size();
    }
    if (found[0] != 0) agree(failure);
    inside_hit = found[1] != 0, outside_hit = found[2] != 0;
    if (inside_hit) {
      join_level(order, level_keys, run_begin);
      break;
    }
    level_keys.clear();  // (none: no rank found a simplex of S)
    rings.widen();
  }
  reporting_ = true;
  if (!inside_hit) join_level({}, {}, std::vector<std::size_t>(ranks_ + 1, 0));  // (an empty level)
  if (!inside_hit && must_succeed) throw_seed_not_found(seed, outside_hit, options_.seed_search_rings);
}

}  // namespace coxmesh::walk
