// The oracle's door-in/door-out guesses only save time: a trace with no guesses, or with wrong
// guesses, is identical (order and bits) to one with the implicit oracle's pivots; and with them
// the oracle is asked about little more than the traced simplices themselves.
#include <gtest/gtest.h>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/tracing/walk_common.h"
#include "expect_identical.h"

using namespace coxmesh;

namespace {

// Forwards intersect() and replaces the pivots: none at all, or always the same vertex (right in
// about 1 case out of k+1).
class GuessingOracle final : public IntersectionOracle {
 public:
  GuessingOracle(IntersectionOracle& inner, bool guess) : inner_(inner), guess_(guess) {}
  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  int codimension() const override { return inner_.codimension(); }
  bool has_domain() const override { return inner_.has_domain(); }
  std::uint64_t function_evaluations() const override { return inner_.function_evaluations(); }
  Intersection intersect(const Simplex& tau, double* point) override { return inner_.intersect(tau, point); }
  bool pivot_enter(const Simplex&) override { return guess_; }
  int pivot_exit(const std::int32_t*) override { return 0; }

 private:
  IntersectionOracle& inner_;
  bool guess_;
};

struct Case {
  std::string name;
  FunctionPtr f, domain;
  Triangulation t;
  bool generic;              // random offset: no lattice vertex on M
  std::vector<double> seed;  // empty: the function's own
};

}  // namespace

TEST(Pivoting, GuessesOnlySaveTime) {
  const Eigen::VectorXd b3 = Eigen::Vector3d(0.0123, 0.0456, 0.0789);
  std::vector<Case> cases;
  cases.push_back({"S2 in R3",
                   sphere(2, 3, 1.0),
                   nullptr,
                   Triangulation::coxeter(3).with_longest_edge(0.1).with_offset(b3),
                   true,
                   {}});
  cases.push_back(
      {"torus, FK, vertices on M", torus(1.0, 0.5), nullptr, Triangulation::freudenthal(3).scaled(0.125), false, {}});
  cases.push_back(
      {"S1 in R5", sphere(1, 5, 1.0), nullptr, Triangulation::coxeter(5).with_longest_edge(0.05).rotated(5), true, {}});
  cases.push_back(
      {"S3 in R6", sphere(3, 6, 1.0), nullptr, Triangulation::coxeter(6).with_longest_edge(0.6).rotated(2), true, {}});
  cases.push_back({"S2 in R4, FK, vertices on M",
                   sphere(2, 4, 1.0),
                   nullptr,
                   Triangulation::freudenthal(4).scaled(0.25),
                   false,
                   {}});
  cases.push_back({"flat torus cut",
                   product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)),
                   half_space_domain({1, 1, 0, 0}, 0.5),
                   Triangulation::coxeter(4).with_longest_edge(0.3).rotated(9),
                   true,
                   {-1, 0, 1, 0}});
  cases.push_back({"moment curve in a ball",
                   moment_curve(5),
                   ball_domain(std::vector<double>(5, 0.0), 1.2),
                   Triangulation::coxeter(5).with_longest_edge(0.05).rotated(4),
                   true,
                   {}});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::vector<std::vector<double>> seeds = {c.seed.empty() ? c.f->seed() : c.seed};
    ImplicitOracle oracle(c.t, c.f, c.domain);
    const TraceResult pivoting = trace_manifold(c.t, oracle, seeds);
    EXPECT_GT(pivoting.simplices.size(), 200u);
    if (c.domain) {
      EXPECT_GT(pivoting.boundary_simplices.size(), 0u);
    }
    for (bool guess : {false, true}) {
      ImplicitOracle inner(c.t, c.f, c.domain);
      GuessingOracle other(inner, guess);
      const TraceResult r = trace_manifold(c.t, other, seeds);
      expect_identical(pivoting, r, guess ? "wrong guesses" : "no guesses");
      // Every tested k-simplex costs one call; guesses spare the non-transverse facets.
      EXPECT_GT(r.oracle_calls, pivoting.oracle_calls);
    }
    // With a random offset the guesses are right but for rare near-ties: besides the search around
    // the seed, each oracle call is one discovered simplex (of S, or outside the domain).
    if (c.generic) {
      EXPECT_LE(pivoting.oracle_calls,
                pivoting.simplices.size() * 101 / 100 + 2 * pivoting.boundary_simplices.size() + 500)
          << pivoting.oracle_calls << " calls for " << pivoting.simplices.size() << " simplices";
    }
  }
}

// Through lattice vertices the ratio test of the guess ties (λ_τ = e_j when vertex j of τ is on M):
// the lexicographic ratio test must still find the other transverse facet that the exact rule
// picks, but for rare rounding. Brute force: every facet of every cofacet of the traced simplices.
TEST(Pivoting, GuessesAreRightThroughLatticeVertices) {
  struct Degenerate {
    std::string name;
    FunctionPtr f;
    Triangulation t;
    std::vector<double> seed;
  };
  Eigen::MatrixXd normals = Eigen::MatrixXd::Zero(5, 3);
  for (int j = 0; j < 3; ++j) normals(2 + j, j) = 1;
  const std::vector<Degenerate> cases = {
      {"moment curve in R^8 through the origin", moment_curve(8), Triangulation::coxeter(8).with_longest_edge(0.15),
       moment_curve(8)->seed()},
      {"plane in R^5 through the origin",
       affine_plane(normals, Eigen::VectorXd::Zero(5)),
       Triangulation::coxeter(5).with_longest_edge(0.3),
       {0.05, 0.07, 0, 0, 0}},
      {"torus, FK, vertices on M", torus(1.0, 0.5), Triangulation::freudenthal(3).scaled(0.125),
       torus(1.0, 0.5)->seed()},
  };
  for (const Degenerate& c : cases) {
    SCOPED_TRACE(c.name);
    ImplicitOracle oracle(c.t, c.f);
    TraceOptions options;
    options.max_simplices = 3000;
    const TraceResult traced = trace_manifold(c.t, oracle, {c.seed}, options);
    const int d = c.t.dimension(), k = c.f->codimension();
    ImplicitOracle check(c.t, c.f);
    std::vector<double> point(d);
    int through_vertex = 0, wrong = 0;
    CofaceEnumerator cofacets;
    for (std::uint32_t i = 0; i < traced.simplices.size(); ++i) {
      const Simplex tau = unpack(traced.simplices.key(i), d);
      bool on_vertex = false;
      std::int32_t v[kMaxDimension];
      for (int j = 0; j <= k; ++j) {
        tau.vertex(j, v);
        double x[kMaxDimension], fx[kMaxDimension];
        c.t.cartesian(v, x);
        c.f->evaluate(x, fx);
        bool zero = true;
        for (int e = 0; e < k; ++e) zero &= fx[e] == 0;
        on_vertex |= zero;
      }
      ASSERT_TRUE(check.pivot_enter(tau));
      cofacets.reset(tau, k + 1);
      while (const Simplex* mu = cofacets.next()) {
        const int entry = extra_vertex_index(tau, *mu);
        int other = -1, transverse = 0;
        for (int j = 0; j <= k + 1; ++j)
          if (j != entry && check.intersect(facet_without(*mu, j), point.data()).hit) other = j, ++transverse;
        ASSERT_EQ(transverse, 1);
        mu->vertex(entry, v);
        const int g = check.pivot_exit(v);
        const int guess = g < 0 ? -1 : (g < entry ? g : g + 1);
        through_vertex += on_vertex;
        wrong += on_vertex && guess != other;
      }
    }
    EXPECT_GT(through_vertex, 20);
    // (Before the lexicographic ratio test: 40 of 72 and 96 of 300 wrong.)
    EXPECT_LE(wrong * 20, through_vertex) << wrong << " wrong of " << through_vertex;
  }
}

// The walks' pipeline (take_cofacet, guess_other_facet, classify_pending) asks the oracle and the
// tables what other_transverse_facet asks, in the same order, and finds what it finds: for every
// cofacet of every traced simplex, with the oracle's guesses, none, and wrong ones, each cofacet
// once taken as τ's arrival.
TEST(Pivoting, PipelineAsksAsOtherTransverseFacet) {
  const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.3).rotated(9);
  const FunctionPtr f = product(sphere(1, 2, 1.0), sphere(1, 2, 1.0));
  ImplicitOracle traced_by(t, f);
  TraceOptions options;
  options.max_simplices = 400;
  const TraceResult traced = trace_manifold(t, traced_by, {{-1, 0, 1, 0}}, options);
  const int d = t.dimension(), k = f->codimension();
  ImplicitOracle implicit(t, f);
  std::vector<double> point(d);
  // (inside: in S; outside, at index 7: transverse but not in S; else a miss)
  const auto classifier = [&](std::vector<std::uint32_t>& asked) {
    return [&](const Simplex& s) {
      std::uint32_t key[packed_words(kMaxDimension)];
      pack(s, key);
      asked.insert(asked.end(), key, key + packed_words(d));
      if (const std::uint32_t id = traced.simplices.find(key); id != PackedKeyIndex::kAbsent)
        return walk::Found{walk::Kind::inside, id};
      return implicit.intersect(s, point.data()).hit ? walk::Found{walk::Kind::outside, 7}
                                                     : walk::Found{walk::Kind::miss, 0};
    };
  };
  int compared = 0, guessed = 0;
  for (int mode = 0; mode < 3; ++mode) {  // the oracle's guesses, none, wrong ones
    GuessingOracle guessing(implicit, mode == 2);
    IntersectionOracle& oracle = mode == 0 ? static_cast<IntersectionOracle&>(implicit) : guessing;
    CofaceEnumerator cofacets;
    for (std::uint32_t i = 0; i < traced.simplices.size(); ++i) {
      const Simplex tau = unpack(traced.simplices.key(i), d);
      const std::uint32_t* tau_key = traced.simplices.key(i);
      for (int arrival_at = 0; arrival_at <= 1; ++arrival_at) {
        std::uint64_t arrival = walk::kNoCofacet;
        if (arrival_at) {  // (the first cofacet)
          cofacets.reset(tau, k + 1);
          const Simplex* mu = cofacets.next();
          std::int32_t v[kMaxDimension];
          mu->vertex(extra_vertex_index(tau, *mu), v);
          arrival = walk::cofacet_code(v, tau_key, d);
        }
        const bool pivots = oracle.pivot_enter(tau);
        cofacets.reset(tau, k + 1);
        while (const Simplex* mu = cofacets.next()) {
          SCOPED_TRACE(std::to_string(mode) + " " + std::to_string(i));
          std::vector<std::uint32_t> asked_one, asked_pipeline;
          const walk::Found one =
              walk::other_transverse_facet(oracle, pivots, tau, tau_key, arrival, *mu, classifier(asked_one));
          walk::PendingCofacet p;
          walk::Found piped{walk::Kind::miss, 0, walk::kArrival};  // (what take_cofacet passes by)
          if (walk::take_cofacet(oracle, pivots, tau, walk::ArrivalVertex<>(tau_key, arrival, tau.d), *mu, p)) {
            if (walk::guess_other_facet(oracle, pivots, p)) {
              ++guessed;
              std::uint32_t key[packed_words(kMaxDimension)];
              pack(p.facet, key);
              EXPECT_TRUE(std::equal(key, key + packed_words(d), p.key));
              EXPECT_EQ(p.hash, hash_words(key, packed_words(d)));
            }
            const auto classify = classifier(asked_pipeline);
            piped = walk::classify_pending(
                p, [&](const Simplex& s, const std::uint32_t*, std::uint64_t) { return classify(s); }, classify);
          }
          EXPECT_EQ(asked_pipeline, asked_one);
          EXPECT_EQ(piped.kind, one.kind);
          EXPECT_EQ(piped.index, one.index);
          EXPECT_EQ(piped.facet, one.facet);
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 3 * 2 * 400 * 3);
  EXPECT_GT(guessed, 400);
}

// pivot_enter(τ) reuses the factors of M(τ) that intersect(τ) kept when the sequential walk found τ:
// nearly every simplex of S, and the guesses are those of factors computed again (the same bits).
// Out of the walk's order, the oracle factors again.
TEST(Pivoting, KeptFactorsGiveTheSameGuesses) {
  const struct {
    std::string name;
    FunctionPtr f, domain;
    Triangulation t;
    std::vector<double> seed;
  } cases[] = {
      {"S2 in R3 (k = 1: F at the ends)", sphere(2, 3, 1.0), nullptr,
       Triangulation::coxeter(3).with_longest_edge(0.1).rotated(3), sphere(2, 3, 1.0)->seed()},
      {"S3 in R6", sphere(3, 6, 1.0), nullptr, Triangulation::coxeter(6).with_longest_edge(0.6).rotated(2),
       sphere(3, 6, 1.0)->seed()},
      {"flat torus cut", product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), half_space_domain({1, 1, 0, 0}, 0.5),
       Triangulation::coxeter(4).with_longest_edge(0.3).rotated(9), std::vector<double>{-1, 0, 1, 0}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    ImplicitOracle walked(c.t, c.f, c.domain);
    const TraceResult traced = trace_manifold(c.t, walked, {c.seed});
    const std::uint32_t n = traced.simplices.size();
    EXPECT_GT(n, 1000u);
    EXPECT_GE(walked.factorizations_reused() * 100, n * 99ull);
    EXPECT_LE(walked.factorizations_reused(), n);
    // The walk's calls, simplex by simplex (kept), against an oracle entered out of order (factors again).
    const int d = c.t.dimension(), k = c.f->codimension();
    ImplicitOracle kept(c.t, c.f, c.domain), again(c.t, c.f, c.domain);
    ASSERT_TRUE(again.pivot_enter(unpack(traced.simplices.key(n - 1), d)));  // (switches its queue off)
    std::vector<double> point(d);
    CofaceEnumerator cofacets;
    int compared = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const Simplex tau = unpack(traced.simplices.key(i), d);
      ASSERT_TRUE(kept.intersect(tau, point.data()).hit);
      ASSERT_EQ(kept.pivot_enter(tau), again.pivot_enter(tau));
      cofacets.reset(tau, k + 1);
      while (const Simplex* mu = cofacets.next()) {
        std::int32_t v[kMaxDimension];
        mu->vertex(extra_vertex_index(tau, *mu), v);
        ASSERT_EQ(kept.pivot_exit(v), again.pivot_exit(v)) << i;
        ++compared;
      }
    }
    EXPECT_GE(kept.factorizations_reused() * 100, n * 99ull);
    EXPECT_EQ(again.factorizations_reused(), 0u);
    EXPECT_GT(compared, 5000);
  }
}
