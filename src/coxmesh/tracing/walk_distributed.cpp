// Thesis §4.2 over several processes: the walk of one rank, level by level, and the seed search
// (every rank searches every seed, so all of them agree on what it found without a message).
#include "coxmesh/tracing/walk_distributed.h"

#include <cstring>

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
      settle_cofacets_(oracle.two_transverse_facets()),
      next_(words_),
      others_(words_),
      known_vertices_(d_),
      candidates_out_(ranks_),
      tested_out_(ranks_),
      point_(d_),
      last_owner_(d_, ranks_) {}

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
    if (const std::uint32_t id = mine_.find(key, h); id != PackedKeyIndex::kAbsent)
      return held_ = Held::mine, Found{Kind::inside, id};
    if (const std::uint32_t id = next_.find(key, h, slots.next); id != PackedKeyIndex::kAbsent)
      return held_ = Held::next, Found{Kind::inside, id};
  }
  const std::uint32_t known = others_.find(key, h, slots.others);
  if (known != PackedKeyIndex::kAbsent) {
    const std::uint32_t p = other_payload_[known];
    if (p == kMiss) return {Kind::miss, 0};
    if (p == kRemoteInside) return held_ = Held::remote, Found{Kind::inside, 0};
    if (p != kUntested) return {Kind::outside, p};
  }
  return test(key, h, tau, owner, known, slots);
}

// The oracle's answer on τ, kept where the walk will look for it. Each simplex tested is counted
// once in the whole job, by its owner: when it tests it, or when another rank reports it.
Found DistributedWalk::test(const std::uint32_t* key, std::uint64_t hash, const Simplex& tau, int owner,
                            std::uint32_t known, const Slots& slots) {
  const bool owned = owner == rank_;
  if (owned && known == PackedKeyIndex::kAbsent) ++calls_;
  ++tests_;
  const Intersection x = oracle_.intersect(tau, point_.data());
  if (x.hit && x.domain < 0) {
    if (owned) {
      const std::uint32_t id = next_.insert_at(slots.next, key, hash);  // (absent: classify looked)
      next_keys_.push_back(discovery_);
      next_settled_.push_back(kNoneSettled);
      next_data_.insert(next_data_.end(), point_.begin(), point_.end());
      next_data_.push_back(x.domain);
      fresh_ = Fresh::owned, fresh_at_ = id, held_ = Held::next;
      return {Kind::inside, id};
    }
    others_.insert_at(slots.others, key, hash);  // (absent: classify looked, and τ is not ours)
    other_payload_.push_back(kRemoteInside);
    if (reporting_) {  // (in the seed search the owner tests it itself)
      std::vector<std::byte>& out = candidates_out_[owner];
      put(out, key, words_);
      put(out, &discovery_, 1);
      fresh_ = Fresh::remote, fresh_owner_ = owner, fresh_at_ = out.size();
      put(out, &kNoneSettled, 1);
      put(out, point_.data(), d_);
      put(out, &x.domain, 1);
      ++candidates_sent_;
    }
    held_ = Held::remote;
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

// μ, walked from S[i] to its facet f (inside), settled there as SequentialWalk::settle does: where
// this rank keeps that facet (its part of S, if walked after S[i], or of the next level), or in the
// message that hands a new one to its owner. A facet that another rank owns and this one had met
// before is not marked: the owner walks μ once more.
template <int kD>
void DistributedWalk::settle(std::uint32_t i, const PendingCofacet& p, const Found& f) {
  if (!settle_cofacets_ && fresh_ == Fresh::no) return;  // (then only the cofacet of arrival)
  const std::uint64_t place = place_among_facet_cofacets<kD>(p.mu, f.facet);
  if (place >= 64) return;
  const std::uint64_t bit = std::uint64_t{1} << place;
  if (fresh_ == Fresh::remote) {
    std::byte* at = candidates_out_[fresh_owner_].data() + fresh_at_;
    std::uint64_t settled;
    std::memcpy(&settled, at, sizeof settled);
    settled |= bit;
    std::memcpy(at, &settled, sizeof settled);
  } else if (held_ == Held::next) {
    next_settled_[f.index] |= bit;
  } else if (held_ == Held::mine && f.index > i) {  // (ids here increase with the global ones)
    settled_[f.index] |= bit;
  }
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
  const ArrivalVertex<kD> no_arrival = ArrivalVertex<kD>::none();  // (settled_ has it)
  for (std::uint32_t i = level_begin_; i < level_end_; ++i) {
    tau = mine_.simplex(i, d_);
    const bool pivots = oracle_.pivot_enter(tau);
    const std::uint64_t settled = settled_[i];
    cofacets.reset(tau, k_ + 1);
    pipeline.run(
        cofacets,
        [&](const Simplex& mu, PendingCofacet& p) {
          return (p.index >= 64 || (settled >> p.index & 1) == 0) &&
                 take_cofacet<kD>(oracle_, pivots, tau, no_arrival, mu, p);
        },
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
  } else if (f.kind == Kind::inside) {
    settle<kD>(i, p, f);
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
