// Thesis §4.2: what the sequential walk (walk_sequential.cpp) and its level-synchronous parallel
// variant (walk_parallel.cpp) share: how a tested k-simplex is classified, how the walk finds the
// other transverse facet of a cofacet, how it names the cofacet a simplex was discovered through,
// and where a cofacet crosses the domain's boundary. Internal to tracing (not installed).
#pragma once

#include <cstdint>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/oracle/intersection_oracle.h"

namespace coxmesh::walk {

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
// Found::facet of a miss: μ is the cofacet τ was discovered through (other_transverse_facet).
constexpr int kArrival = -2;

// The per-cofacet lattice work below takes kD ≠ 0 when every simplex has d = kD, fixed at compile
// time so that its loops over d and over the packed words unroll (the sequential walk picks kD once,
// with_fixed_dimension, util/fixed_dimension.h); kD = 0 reads d at run time (other d, and the
// parallel and distributed walks).
template <int kD>
int dimension_of(const Simplex& s) {
  return kD != 0 ? kD : s.d;
}
template <int kD>
void vertex_of(const Simplex& s, int j, std::int32_t* out) {  // Simplex::vertex
  for (int i = 0; i < dimension_of<kD>(s); ++i) out[i] = s.vertex_coordinate(j, i);
}
// pack(s, key), and returns hash_words of the key.
template <int kD>
std::uint64_t pack_hashed(const Simplex& s, std::uint32_t* key) {
  pack<kD>(s, key);
  return hash_words(key, packed_words(dimension_of<kD>(s)));
}

// The payload of a tested simplex that is not transverse (otherwise: where its point and D̂ are).
constexpr std::uint32_t kMiss = 0xFFFFFFFFu;

// The lattice vertex w of a cofacet μ of τ not in τ, as 2 bits per coordinate of w − y(τ) ∈ {−1, 0, 1}
// (w and y(τ) are vertices of one simplex): with τ, it names μ exactly in 62 bits.
constexpr std::uint64_t kNoCofacet = ~std::uint64_t{0};  // "11" never occurs as a pair of bits
// The settled cofacets of a simplex just found: none (SequentialWalk::settled_).
constexpr std::uint64_t kNoneSettled = 0;
inline std::uint64_t cofacet_code(const std::int32_t* w, const std::uint32_t* tau_key, int d) {
  std::uint64_t code = 0;
  for (int i = 0; i < d; ++i)
    code |= static_cast<std::uint64_t>(w[i] - static_cast<std::int32_t>(tau_key[i]) + 1) << (2 * i);
  return code;
}

// The code of the cofacet μ seen from its facet without vertex `facet` (packed: `facet_key`): what
// the walk records for a simplex discovered through μ.
template <int kD = 0>
std::uint64_t arrival_code(const Simplex& mu, int facet, const std::uint32_t* facet_key, int d) {
  std::int32_t v[kMaxDimension];
  vertex_of<kD>(mu, facet, v);
  return cofacet_code(v, facet_key, kD != 0 ? kD : d);
}

// The other transverse facet of a cofacet μ of τ ∈ S: M̂ ∩ μ is a segment between exactly two
// transverse facets of μ, τ and this one (thesis §4.2). The oracle's door-in/door-out guess is
// tested first; without a guess, or when it is wrong, every facet is. `test` classifies a facet.
// μ is skipped (miss) when it is the cofacet τ was discovered through (`arrival`, a cofacet_code):
// its other transverse facet is τ's discoverer, already in S.
template <class Test>
Found other_transverse_facet(IntersectionOracle& oracle, bool pivots, const Simplex& tau, const std::uint32_t* tau_key,
                             std::uint64_t arrival, const Simplex& mu, Test&& test) {
  const int entry = extra_vertex_index(tau, mu);  // μ without its vertex `entry` is τ
  std::int32_t v[kMaxDimension];
  mu.vertex(entry, v);
  if (arrival != kNoCofacet && cofacet_code(v, tau_key, tau.d) == arrival) return {Kind::miss, 0, kArrival};
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

// A cofacet μ of τ in the walks' pipeline of three steps (SequentialWalk::walk says why): taken,
// then its other transverse facet guessed by the oracle (packed and hashed, so that the caller can
// fetch the facet's slots), then classified. The oracle and the tables are asked the same things in
// the same order as by other_transverse_facet.
struct PendingCofacet {
  Simplex mu, facet;  // (facet: μ without its vertex `guess`, when guess ≥ 0)
  int entry = 0, guess = -1;
  std::uint32_t index = 0;        // μ's place among τ's cofacets
  std::uint32_t tau = 0;          // (the sequential walk: τ's id in S)
  std::int32_t v[kMaxDimension];  // μ's vertex `entry`, not in τ
  std::uint32_t key[packed_words(kMaxDimension)];
  std::uint64_t hash = 0;
};

// The vertex w of τ's arrival cofacet not in τ, decoded once per τ: per cofacet, comparing its new
// vertex with w costs less than encoding it (cofacet_code).
template <int kD = 0>
class ArrivalVertex {
 public:
  ArrivalVertex(const std::uint32_t* tau_key, std::uint64_t arrival, int d)
      : d_(kD != 0 ? kD : d), none_(arrival == kNoCofacet) {
    if (none_) return;
    for (int i = 0; i < dimension(); ++i)
      w_[i] = static_cast<std::int32_t>(tau_key[i]) + static_cast<std::int32_t>(arrival >> (2 * i) & 3) - 1;
  }
  static ArrivalVertex none() { return ArrivalVertex(nullptr, kNoCofacet, kD != 0 ? kD : 1); }
  bool is(const std::int32_t* v) const {
    if (none_) return false;
    std::int32_t diff = 0;
    for (int i = 0; i < dimension(); ++i) diff |= v[i] ^ w_[i];
    return diff == 0;
  }

 private:
  int dimension() const { return kD != 0 ? kD : d_; }

  int d_;
  bool none_;
  std::int32_t w_[kMaxDimension];
};

// First step: false when μ is τ's arrival (see other_transverse_facet).
template <int kD = 0>
bool take_cofacet(IntersectionOracle& oracle, bool pivots, const Simplex& tau, const ArrivalVertex<kD>& arrival,
                  const Simplex& mu, PendingCofacet& p) {
  p.entry = extra_vertex_index<kD>(tau, mu);
  vertex_of<kD>(mu, p.entry, p.v);
  if (arrival.is(p.v)) return false;
  p.mu = mu;
  if (pivots) oracle.prefetch_pivot(p.v);
  return true;
}

// Second step: false when the oracle makes no guess.
template <int kD = 0>
bool guess_other_facet(IntersectionOracle& oracle, bool pivots, PendingCofacet& p) {
  p.guess = -1;
  if (!pivots) return false;
  const int g = oracle.pivot_exit(p.v);
  if (g < 0) return false;
  p.guess = g < p.entry ? g : g + 1;
  p.facet = facet_without<kD>(p.mu, p.guess);
  p.hash = pack_hashed<kD>(p.facet, p.key);
  return true;
}

// Last step: the guess tested (`classify_keyed(facet, key, hash)`), then every other facet
// (`classify(facet)`), as other_transverse_facet.
template <int kD = 0, class ClassifyKeyed, class Classify>
Found classify_pending(const PendingCofacet& p, ClassifyKeyed&& classify_keyed, Classify&& classify) {
  if (p.guess >= 0)
    if (Found f = classify_keyed(p.facet, p.key, p.hash); f.kind != Kind::miss) return f.facet = p.guess, f;
  for (int j = 0; j <= p.mu.k; ++j)
    if (j != p.entry && j != p.guess)
      if (Found f = classify(facet_without<kD>(p.mu, j)); f.kind != Kind::miss) return f.facet = j, f;
  return {Kind::miss, 0};
}

// Drives the cofacets of one τ through the three steps above, each cofacet guessed one cofacet after
// it is taken and classified two after that (SequentialWalk::walk says why): take(μ, p) → bool (as
// take_cofacet), guess(p), finish(p). Kept by the walk across its simplices: the ring of pending
// cofacets is not built again per τ.
class CofacetPipeline {
 public:
  template <class Take, class Guess, class Finish>
  void run(CofaceEnumerator& cofacets, Take&& take, Guess&& guess, Finish&& finish) {
    int taken = 0, guessed = 0, finished = 0;  // ring_[i % kRing] for finished ≤ i < taken
    const auto advance = [&](int guess_lag, int test_lag) {
      if (taken - guessed > guess_lag) guess(ring_[guessed++ % kRing]);
      if (guessed - finished > test_lag) finish(ring_[finished++ % kRing]);
    };
    std::uint32_t index = 0;
    while (const Simplex* mu = cofacets.next()) {
      PendingCofacet& p = ring_[taken % kRing];
      p.index = index++;
      if (take(*mu, p)) ++taken, advance(kGuessLag, kTestLag);
    }
    while (finished < taken) advance(0, 0);
  }

 private:
  static constexpr int kGuessLag = 1, kTestLag = 2, kRing = kGuessLag + kTestLag + 1;
  PendingCofacet ring_[kRing];
};

// A cofacet μ with one transverse facet inside the domain (point p, D̂ = dp < 0) and one outside
// (q[0..d), D̂ = q[d] ≥ 0): μ ∩ M̂ is the segment pq and D̂ is linear on it, so μ ∩ M̂ ∩ ∂D̂ is the
// point where D̂ crosses 0. Appends its d coordinates to `out`.
template <class Points>
void append_boundary_point(Points& out, const double* p, double dp, const double* q, int d) {
  const double t = dp / (dp - q[d]);  // dp < 0 ≤ q[d]
  for (int i = 0; i < d; ++i) out.push_back(p[i] + t * (q[i] - p[i]));
}

}  // namespace coxmesh::walk
