// The oracle's door-in/door-out guesses only save time: a trace with no guesses, or with wrong
// guesses, is identical (order and bits) to one with the implicit oracle's pivots; and with them
// the oracle is asked about little more than the traced simplices themselves.
#include <gtest/gtest.h>

#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
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
