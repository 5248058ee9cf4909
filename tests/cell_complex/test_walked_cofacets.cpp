// The cells of dimension 1 that the walk keeps (TraceOptions::keep_cofacets) make the same cell
// complex, numbering included, as the cofacets the complex enumerates itself: for 1, 2 and 3 walking
// threads, with and without a boundary, several components; a walk that cannot vouch for them (cut
// short, an oracle without the promise of two transverse facets, one that breaks it) keeps none.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/oracle/implicit_oracle.h"

using namespace coxmesh;

namespace {

TraceResult traced_with(const Triangulation& t, const FunctionPtr& f, const FunctionPtr& domain,
                        const std::vector<std::vector<double>>& seeds, int threads, TraceOptions options = {}) {
  options.keep_cofacets = true;
  options.threads = threads;
  return trace_manifold(
      t, [&] { return std::make_unique<ImplicitOracle>(t, f, domain); }, seeds, options);
}

void expect_same_complex(const CellComplex& a, const CellComplex& b, const std::string& what) {
  ASSERT_EQ(a.interior.size(), b.interior.size()) << what;
  ASSERT_EQ(a.boundary.size(), b.boundary.size()) << what;
  for (const auto& [x, y] : {std::pair{&a.interior, &b.interior}, std::pair{&a.boundary, &b.boundary}})
    for (std::size_t j = 0; j < x->size(); ++j) {
      const CellLevel &p = (*x)[j], &q = (*y)[j];
      const std::string level = what + " level " + std::to_string(j);
      ASSERT_EQ(p.size(), q.size()) << level;
      ASSERT_EQ(p.simplices.words(), q.simplices.words()) << level;
      const std::size_t words = static_cast<std::size_t>(p.simplices.words());
      EXPECT_TRUE(p.size() == 0 ||
                  std::equal(p.simplices.key(0), p.simplices.key(0) + p.size() * words, q.simplices.key(0)))
          << level;
      EXPECT_TRUE(p.facet_offsets == q.facet_offsets && p.facet_ids == q.facet_ids) << level;
      EXPECT_TRUE(p.boundary_facet == q.boundary_facet) << level;
    }
}

// The complex of `traced` as the walk's cofacets give it, and as the complex finds it alone.
void expect_walked_level_is_enumerated_level(const TraceResult& traced, const std::string& what) {
  TraceResult without = traced;
  without.cofacets = {};
  for (int threads : {1, 2})
    expect_same_complex(build_cell_complex(TraceResult(traced), threads),
                        build_cell_complex(TraceResult(without), threads),
                        what + " complex threads=" + std::to_string(threads));
}

}  // namespace

TEST(WalkedCofacets, TheSameComplexAsEnumerated) {
  // Two unit spheres of R³ apart: two components, walked from a seed each.
  const FunctionPtr two_spheres = make_function(3, 1, [](const double* x, double* v) {
    const double a = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1;
    const double b = (x[0] - 3) * (x[0] - 3) + x[1] * x[1] + x[2] * x[2] - 1;
    v[0] = a * b;
  });
  struct Case {
    std::string name;
    int d;
    double edge;
    FunctionPtr f, domain;
    std::vector<std::vector<double>> seeds;
  };
  const FunctionPtr circle = sphere(1, 2, 1.0);
  const Case cases[] = {
      {"S2", 3, 0.15, sphere(2, 3, 1.0), nullptr, {}},
      {"S2 cut by a plane", 3, 0.15, sphere(2, 3, 1.0), half_space_domain({-0.3, -0.2, 0.9}, 0.2), {}},
      {"S3 cut by a ball", 4, 0.35, sphere(3, 4, 1.0), ball_domain({0.5, 0, 0, 0}, 0.9), {}},
      {"circle in R5", 5, 0.2, sphere(1, 5, 1.0), nullptr, {}},
      {"torus in R3", 3, 0.12, torus(1.0, 0.4), nullptr, {}},
      {"flat torus in R4 cut by a box",
       4,
       0.3,
       product(circle, circle),
       box_domain({{-0.6, -2, -2, -2}, {2, 2, 2, 2}}),
       {}},
      {"two spheres", 3, 0.2, two_spheres, nullptr, {{1, 0, 0}, {4, 0, 0}}},
  };
  for (const Case& c : cases) {
    const Triangulation t = Triangulation::coxeter(c.d).with_longest_edge(c.edge);
    const auto seeds = c.seeds.empty() ? std::vector<std::vector<double>>{c.f->seed()} : c.seeds;
    const TraceResult one = traced_with(t, c.f, c.domain, seeds, 1);
    ASSERT_EQ(one.status, TraceStatus::complete) << c.name;
    ASSERT_FALSE(one.cofacets.empty()) << c.name;
    EXPECT_EQ(c.domain != nullptr, one.boundary_simplices.size() > 0) << c.name;
    expect_walked_level_is_enumerated_level(one, c.name);
    for (int threads : {2, 3}) {  // (the parallel walk keeps the same cofacets)
      const TraceResult many = traced_with(t, c.f, c.domain, seeds, threads);
      const std::string what = c.name + " walked by " + std::to_string(threads) + " threads";
      ASSERT_FALSE(many.cofacets.empty()) << what;
      EXPECT_TRUE(many.cofacets.places == one.cofacets.places &&
                  many.cofacets.facet_offsets == one.cofacets.facet_offsets &&
                  many.cofacets.facet_ids == one.cofacets.facet_ids)
          << what;
    }
  }
}

TEST(WalkedCofacets, NoneFromAWalkCutShort) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.15);
  const FunctionPtr f = sphere(2, 3, 1.0);
  for (int threads : {1, 2}) {
    TraceOptions options;
    options.max_simplices = 200;
    const TraceResult traced = traced_with(t, f, nullptr, {f->seed()}, threads, options);
    ASSERT_EQ(traced.status, TraceStatus::max_simplices_reached);
    EXPECT_TRUE(traced.cofacets.empty()) << threads << " threads";
  }
}

namespace {

// An implicit oracle that promises two transverse facets per cofacet and breaks the promise: it calls
// some simplices that miss M̂ transverse (at their first vertex), so cofacets have three of them.
class BrokenPromise final : public IntersectionOracle {
 public:
  BrokenPromise(const Triangulation& t, FunctionPtr f) : t_(t), inner_(t, std::move(f)) {}
  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  int codimension() const override { return inner_.codimension(); }
  bool two_transverse_facets() const override { return true; }
  Intersection intersect(const Simplex& tau, double* point) override {
    const Intersection x = inner_.intersect(tau, point);
    std::int32_t v[kMaxDimension];
    tau.vertex(0, v);
    if (x.hit || (v[0] + 3 * v[1] + 7 * v[2]) % 11 != 0) return x;
    std::vector<double> xs(static_cast<std::size_t>((tau.k + 1) * tau.d));
    t_.vertex_coordinates(tau, xs.data());
    std::copy_n(xs.begin(), tau.d, point);
    return {true, -1};
  }

 private:
  const Triangulation& t_;
  ImplicitOracle inner_;
};

}  // namespace

TEST(WalkedCofacets, NoneFromAnOracleThatBreaksItsPromise) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.15);
  const FunctionPtr f = sphere(2, 3, 1.0);
  BrokenPromise broken(t, f);
  TraceOptions options;
  options.keep_cofacets = true;
  options.max_simplices = 100'000;
  const TraceResult traced = trace_manifold(t, broken, {f->seed()}, options);
  ASSERT_EQ(traced.status, TraceStatus::complete);
  EXPECT_TRUE(traced.cofacets.empty());
  // Without the promise, nothing is kept either.
  ImplicitOracle honest(t, f);
  class NoPromise final : public IntersectionOracle {
   public:
    explicit NoPromise(IntersectionOracle& o) : o_(o) {}
    int ambient_dimension() const override { return o_.ambient_dimension(); }
    int codimension() const override { return o_.codimension(); }
    Intersection intersect(const Simplex& tau, double* point) override { return o_.intersect(tau, point); }

   private:
    IntersectionOracle& o_;
  } no_promise(honest);
  EXPECT_TRUE(trace_manifold(t, no_promise, {f->seed()}, options).cofacets.empty());
}
