// Thesis §4.2 (manifold tracing, with boundary): the walk, one simplex at a time, and the search
// for the simplices it starts from. The one hot loop of coxmesh.
#include "coxmesh/tracing/walk_sequential.h"

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/tracing/seed_search.h"
#include "coxmesh/util/fixed_dimension.h"

namespace coxmesh::walk {

SequentialWalk::SequentialWalk(const Triangulation& t, IntersectionOracle& oracle, const TraceOptions& options)
    : t_(t),
      oracle_(oracle),
      options_(options),
      d_(t.dimension()),
      k_(oracle.codimension()),
      settle_cofacets_(oracle.two_transverse_facets()),
      others_(packed_words(d_)),
      keep_cofacets_(options.keep_cofacets && oracle.two_transverse_facets() && oracle.codimension() < d_) {
  result_.ambient_dimension = d_;
  result_.codimension = k_;
  result_.simplices = PackedKeyIndex(packed_words(d_));
  result_.boundary_simplices = PackedKeyIndex(packed_words(d_));
  // The arrays that grow with S, in big blocks from the start (reserve_big_block says why).
  result_.simplices.reserve_key_block();
  for (auto* v : {&arrivals_, &settled_}) reserve_big_block(*v);
  reserve_big_block(result_.points), reserve_big_block(domain_values_);
  if (keep_cofacets_) {
    for (auto* v : {&cofacet_offsets_, &cofacet_facets_, &cofacet_places_}) reserve_big_block(*v);
    cofacet_offsets_.assign(1, 0);
  }
}

TraceResult SequentialWalk::finish() {
  result_.oracle_calls += calls_;
  // Each cofacet of S has all its facets in S among the kept ones (every incidence of S's cofacets
  // accounted for) when the walk went everywhere and met each cofacet's two transverse facets.
  if (keep_cofacets_ && result_.status == TraceStatus::complete && cofacet_facets_.size() == cofacets_met_) {
    WalkedCofacets& c = result_.cofacets;
    c.facet_offsets = std::move(cofacet_offsets_);
    c.facet_ids = std::move(cofacet_facets_);
    c.places = std::move(cofacet_places_);
  }
  return std::move(result_);
}

// The walk: for each τ of S in breadth-first order, for each cofacet μ of τ, the other transverse
// facet of μ is either a simplex inside the domain (appended to S if new: classify) or outside it
// (μ then crosses the boundary, at a point of S_∂).
void SequentialWalk::walk() {
  // The per-cofacet lattice work with d fixed at compile time (walk_common.h), for the common d.
  with_fixed_dimension<3, 4, 6, 9>(d_, [this](auto fixed_d) { walk_from_head<decltype(fixed_d)::value>(); });
}

template <int kD>
void SequentialWalk::walk_from_head() {
  // The cofacets μ of τ in a pipeline of four steps: μ is taken (and the oracle told that pivot_exit
  // will read its new vertex v); one cofacet later the oracle guesses μ's other transverse facet
  // (and its slot in S is fetched); two cofacets later still, the key that slot names is fetched;
  // one more, and μ is classified. Both look-ups are at random places of tables much bigger than
  // the caches: fetched ahead, they wait less (docs/benchmarks.md). The pipeline runs on from one τ
  // to the next, so that the first cofacets of a τ are fetched as far ahead as the others: only
  // the guesses wait for τ's last cofacet (the oracle guesses around one τ at a time), and the
  // classifications for a level's last τ (the next level is S's simplices found by then). The
  // oracle and S are asked the same things in the same order as by other_transverse_facet
  // (pivot_exit only reads values, of v, a vertex of every facet tested after it).
  constexpr std::uint32_t kGuessLag = 1, kFetchLag = 2, kTestLag = 1, kRing = 8;
  static_assert(kRing >= kGuessLag + kFetchLag + kTestLag + 2);
  PendingCofacet ring[kRing];
  std::uint32_t taken = 0, guessed = 0, fetched = 0, finished = 0;  // ring[i % kRing] for finished ≤ i < taken
  bool pivots = false;
  const auto advance = [&](std::uint32_t guess_lag, std::uint32_t fetch_lag, std::uint32_t test_lag) {
    if (taken - guessed > guess_lag) {
      PendingCofacet& p = ring[guessed++ % kRing];
      if (guess_other_facet<kD>(oracle_, pivots, p)) result_.simplices.prefetch(p.hash);  // (its slot in S)
    }
    if (guessed - fetched > fetch_lag) {
      const PendingCofacet& p = ring[fetched++ % kRing];
      if (p.guess >= 0) result_.simplices.prefetch_key(p.hash);  // (the key its slot names)
    }
    if (fetched - finished > test_lag) finish_cofacet<kD>(ring[finished++ % kRing]);
  };
  Simplex tau;
  CofaceEnumerator cofacets;
  for (;; ++head_) {
    if (head_ >= level_end_) {  // a breadth-first level starts: handed to the oracle at once
      while (finished < taken) advance(0, 0, 0);
      if (head_ >= result_.simplices.size() || !start_level()) return;
      oracle_.prefetch({result_.simplices.key(head_), std::size_t{level_end_ - head_} * packed_words(d_)});
    }
    tau = result_.simplices.simplex(head_, d_);
    pivots = oracle_.pivot_enter(tau);
    cofacets.reset(tau, k_ + 1);
    const ArrivalVertex<kD> arrival(result_.simplices.key(head_), arrivals_[head_], d_);
    const std::uint64_t settled = settled_[head_];
    std::uint32_t index = 0;
    while (const Simplex* mu = cofacets.next()) {
      if (index < 64 && (settled >> index & 1) != 0) {
        ++index;
        continue;
      }
      PendingCofacet& p = ring[taken % kRing];
      p.index = index++;
      p.tau = head_;
      if (take_cofacet<kD>(oracle_, pivots, tau, arrival, *mu, p)) ++taken, advance(kGuessLag, kFetchLag, kTestLag);
    }
    while (guessed < taken) advance(0, kFetchLag, kTestLag);
    cofacets_met_ += index;
  }
}

// Last step: the guess tested, then every other facet, then what the walk does with the one found.
template <int kD>
void SequentialWalk::finish_cofacet(const PendingCofacet& p) {
  const std::uint32_t known = result_.simplices.size();
  const Found f = classify_pending<kD>(
      p, [this](const Simplex& s, const std::uint32_t* key, std::uint64_t h) { return classify(s, key, h); },
      [this](const Simplex& s) { return classify<kD>(s); });
  if (keep_cofacets_ && (f.kind != Kind::inside || f.index > p.tau))
    keep_cofacet(p.tau, p.index, f.kind == Kind::inside ? f.index : kMiss);
  if (f.kind == Kind::miss) return;
  if (f.kind == Kind::outside) add_boundary(p.mu, p.tau, outside_.data() + f.index);
  if (f.kind != Kind::inside || f.index <= p.tau) return;
  if (settle_cofacets_)  // (the cofacet of arrival among them)
    settle<kD>(p.mu, f.facet, f.index);
  else if (f.index >= known)  // discovered now, through μ
    arrivals_[f.index] = arrival_code<kD>(p.mu, f.facet, result_.simplices.key(f.index), d_);
}

template <int kD>
void SequentialWalk::settle(const Simplex& mu, int facet, std::uint32_t id) {
  const std::uint64_t place = place_among_facet_cofacets<kD>(mu, facet);
  if (place < 64) settled_[id] |= std::uint64_t{1} << place;
}

// μ, met first from τ: its place among τ's cofacets, and τ and its other transverse facet if that is
// in S (from where the walk meets μ again, and passes it by: its id is bigger than τ's).
void SequentialWalk::keep_cofacet(std::uint32_t tau, std::uint32_t place, std::uint32_t other) {
  if (cofacet_places_.size() >= PackedKeyIndex::kMaxEntries) {  // (more than an index holds: not kept)
    keep_cofacets_ = false;
    cofacet_offsets_ = {}, cofacet_facets_ = {}, cofacet_places_ = {};
    return;
  }
  const std::uint32_t facets[2] = {tau, other};
  append_few(cofacet_places_, &place, 1);
  append_few(cofacet_facets_, facets, other != kMiss ? 2 : 1);
  const auto end = static_cast<std::uint32_t>(cofacet_facets_.size());
  append_few(cofacet_offsets_, &end, 1);
}

// The simplex limit is checked where a breadth-first level starts, in the sequential and the
// parallel walk alike, so a truncated result is also the same for every thread count.
bool SequentialWalk::start_level() {
  level_end_ = result_.simplices.size();
  if (result_.simplices.size() >= options_.max_simplices) {
    result_.status = TraceStatus::max_simplices_reached;
    return false;
  }
  if (options_.progress && result_.simplices.size() >= last_progress_ + options_.progress_interval) {
    last_progress_ = result_.simplices.size();
    options_.progress(last_progress_);
  }
  return true;
}

// Looks τ up in S, then among the other tested simplices; only if it is in neither is the oracle
// asked, and τ appended to S (inside the domain) or to the others.
template <int kD>
Found SequentialWalk::classify(const Simplex& tau) {
  std::uint32_t key[packed_words(kMaxDimension)];
  const std::uint64_t h = pack_hashed<kD>(tau, key);
  return classify(tau, key, h);
}

Found SequentialWalk::classify(const Simplex& tau, const std::uint32_t* key, std::uint64_t h) {
  std::size_t slot;  // where τ goes in S if it is new and inside
  if (std::uint32_t id = result_.simplices.find(key, h, slot); id != PackedKeyIndex::kAbsent) return {Kind::inside, id};
  if (std::uint32_t id = others_.find(key, h); id != PackedKeyIndex::kAbsent) {
    const std::uint32_t p = other_payload_[id];
    return p == kMiss ? Found{Kind::miss, 0} : Found{Kind::outside, p};
  }
  ++calls_;
  point_.resize(d_);
  const Intersection x = oracle_.intersect(tau, point_.data());
  std::uint32_t payload = kMiss;
  if (x.hit) {
    if (x.domain < 0) {
      const std::uint32_t id = result_.simplices.insert_at(slot, key, h);
      append_few(result_.points, point_.data(), static_cast<std::size_t>(d_));
      append_few(domain_values_, &x.domain, 1);
      append_few(arrivals_, &kNoCofacet, 1);  // set by the walk
      append_few(settled_, &kNoneSettled, 1);
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

// μ, a cofacet of S[inside], crosses the boundary; `outside` = point and D̂ of its other
// transverse facet.
void SequentialWalk::add_boundary(const Simplex& mu, std::uint32_t inside, const double* outside) {
  if (!result_.boundary_simplices.insert(mu).second) return;
  const double* p = result_.points.data() + static_cast<std::size_t>(inside) * d_;
  append_boundary_point(result_.boundary_points, p, domain_values_[inside], outside, d_);
}

void SequentialWalk::add_seed(std::span<const double> seed, bool must_succeed) {
  check_seed_dimension(seed, d_);
  const Simplex sigma = t_.locate(seed);
  // (generic_seed moves a seed off the lattice vertices, where it lies in (d+1)! simplices)
  SeedRings rings(sigma, d_);
  bool outside_hit = false;
  for (int r = 0; r <= options_.seed_search_rings && !rings.ring().empty(); ++r) {
    bool inside_hit = false;
    for (const Simplex& s : rings.ring()) {
      FaceEnumerator faces(s, k_);
      for (Simplex tau; faces.next(tau);) {
        const Found f = classify<0>(tau);
        inside_hit |= f.kind == Kind::inside;
        outside_hit |= f.kind == Kind::outside;
      }
    }
    if (inside_hit) return;
    rings.widen();
  }
  if (must_succeed) throw_seed_not_found(seed, outside_hit, options_.seed_search_rings);
}

}  // namespace coxmesh::walk
