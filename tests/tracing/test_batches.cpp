// Functions that prefer batches (e.g. Python callables) are evaluated a breadth-first level at a
// time through ImplicitOracle::prefetch: the trace is identical, F is still evaluated exactly once
// per lattice vertex, and almost every evaluation comes from a batch.
#include <gtest/gtest.h>

#include <array>
#include <set>

#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "expect_identical.h"

using namespace coxmesh;

namespace {

// Forwards to a built-in function and records every point it is evaluated at.
class RecordingFunction final : public ImplicitFunction {
 public:
  RecordingFunction(FunctionPtr inner, bool batches) : inner_(std::move(inner)), batches_(batches) {}
  int ambient_dimension() const override { return inner_->ambient_dimension(); }
  int codimension() const override { return inner_->codimension(); }
  std::vector<double> seed() const override { return inner_->seed(); }
  bool prefers_batches() const override { return batches_; }
  void evaluate(const double* x, double* value) const override {
    record(x);
    inner_->evaluate(x, value);
  }
  void evaluate_batch(const double* xs, int n, double* values) const override {
    ++batch_calls;
    batch_points += n;
    for (int i = 0; i < n; ++i) {
      record(xs + i * ambient_dimension());
      inner_->evaluate(xs + i * ambient_dimension(), values + i * codimension());
    }
  }

  mutable std::size_t batch_calls = 0, batch_points = 0, points = 0;
  mutable std::set<std::vector<double>> distinct;

 private:
  void record(const double* x) const {
    ++points;
    distinct.insert(std::vector<double>(x, x + ambient_dimension()));
  }
  FunctionPtr inner_;
  bool batches_;
};

struct Case {
  std::string name;
  FunctionPtr f, domain;
  Triangulation t;
  std::vector<double> seed;  // empty: the function's own
};

}  // namespace

TEST(Batches, SameTraceSameEvaluations) {
  const Eigen::VectorXd b3 = Eigen::Vector3d(0.0123, 0.0456, 0.0789);
  std::vector<Case> cases;
  cases.push_back(
      {"S2 in R3", sphere(2, 3, 1.0), nullptr, Triangulation::coxeter(3).with_longest_edge(0.1).with_offset(b3), {}});
  cases.push_back(
      {"torus, FK, vertices on M", torus(1.0, 0.5), nullptr, Triangulation::freudenthal(3).scaled(0.125), {}});
  cases.push_back(
      {"S1 in R5", sphere(1, 5, 1.0), nullptr, Triangulation::coxeter(5).with_longest_edge(0.05).rotated(5), {}});
  cases.push_back({"flat torus cut",
                   product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)),
                   half_space_domain({1, 1, 0, 0}, 0.5),
                   Triangulation::coxeter(4).with_longest_edge(0.3).rotated(9),
                   {-1, 0, 1, 0}});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::vector<std::vector<double>> seeds = {c.seed.empty() ? c.f->seed() : c.seed};
    std::array<std::shared_ptr<RecordingFunction>, 2> f, domain;
    std::array<TraceResult, 2> r;
    for (int batches : {0, 1}) {
      f[batches] = std::make_shared<RecordingFunction>(c.f, batches);
      if (c.domain) domain[batches] = std::make_shared<RecordingFunction>(c.domain, batches);
      ImplicitOracle oracle(c.t, f[batches], domain[batches]);
      r[batches] = trace_manifold(c.t, oracle, seeds);
    }
    expect_identical(r[0], r[1], "with and without batches");
    EXPECT_GT(r[1].simplices.size(), 200u);
    EXPECT_EQ(r[0].function_evaluations, r[1].function_evaluations);
    for (int batches : {0, 1}) {
      EXPECT_EQ(f[batches]->points, r[batches].function_evaluations);
      EXPECT_EQ(f[batches]->distinct.size(), f[batches]->points) << "a vertex evaluated twice";
    }
    EXPECT_EQ(f[0]->distinct, f[1]->distinct);
    EXPECT_EQ(f[0]->batch_calls, 0u);
    // All but the vertices met while searching around the seed come in batches, one per level
    // (a curve's levels hold two simplices: small batches).
    EXPECT_GT(f[1]->batch_points, f[1]->points * 9 / 10);
    if (r[1].manifold_dimension() >= 2) {
      EXPECT_LT(f[1]->batch_calls * 10, f[1]->batch_points);
    }
    if (c.domain) {
      EXPECT_GT(r[1].boundary_simplices.size(), 0u);
      EXPECT_EQ(domain[1]->distinct, f[1]->distinct);
      EXPECT_EQ(domain[1]->batch_points, f[1]->batch_points);
    }
  }
}

// A failure inside a batch leaves the oracle's cache as it was and reaches the caller.
TEST(Batches, ErrorsPropagate) {
  auto f = make_function(3, 1, [](const double* x, double* v) {
    v[0] = x[2] > 0.5 ? std::nan("") : x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1;
  });
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1);
  for (bool batches : {false, true}) {
    ImplicitOracle oracle(t, std::make_shared<RecordingFunction>(f, batches));
    EXPECT_THROW(trace_manifold(t, oracle, {{1.0, 0.0, 0.0}}), EvaluationError);
  }
}
