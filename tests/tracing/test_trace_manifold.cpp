// Tracing + cell complex: topology of the output over a catalogue of manifolds (with and without
// boundary, with and without lattice vertices on M), a brute-force cross-check of the traced set,
// one evaluation per lattice vertex, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <mutex>
#include <set>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/seeds.h"
#include "coxmesh/tracing/trace_manifold.h"

using namespace coxmesh;

namespace {

struct Case {
  std::string name;
  FunctionPtr f, domain;
  Triangulation t;
  long long euler;
  std::vector<std::size_t> betti;
  std::vector<std::vector<double>> seeds = {};
};

TopologyReport run(const Case& c, TraceResult* out = nullptr) {
  ImplicitOracle oracle(c.t, c.f, c.domain);
  std::vector<std::vector<double>> seeds = c.seeds;
  if (seeds.empty()) seeds.push_back(c.f->seed());
  TraceResult r = trace_manifold(c.t, oracle, seeds);
  EXPECT_EQ(r.status, TraceStatus::complete) << c.name << ": " << r.message;
  EXPECT_GT(r.simplices.size(), 0u) << c.name;
  if (out) {
    out->simplices = r.simplices;
    out->points = r.points;
  }
  CellComplex cc = build_cell_complex(std::move(r));
  TopologyReport topology = analyze_topology(cc);
  EXPECT_EQ(topology.betti, betti_numbers_by_reduction(cc)) << c.name << ": the fast Betti numbers differ";
  return topology;
}

Eigen::VectorXd offset(int d, double s) {
  Eigen::VectorXd b(d);
  for (int i = 0; i < d; ++i) b[i] = s * std::sin(1.7 * i + 0.3);
  return b;
}

std::vector<Case> catalogue() {
  std::vector<Case> cases;
  auto cox = [](int d, double edge) { return Triangulation::coxeter(d).with_longest_edge(edge); };
  // Spheres S^m ⊂ R^d, m ≤ 3, d ≤ 6: χ = 1 + (−1)^m, Betti 1, 0, …, 0, 1.
  for (int d = 2; d <= 6; ++d)
    for (int m = 1; m <= std::min(3, d - 1); ++m) {
      const double edge = d <= 3 ? 0.3 : (m == 3 ? 0.7 : 0.5);
      std::vector<std::size_t> betti(m + 1, 0);
      betti[0] = betti[m] = 1;
      std::string name = "S";  // (built stepwise: GCC 12 warns falsely on chained + here)
      name += std::to_string(m);
      name += " in R";
      name += std::to_string(d);
      cases.push_back(
          {name, sphere(m, d, 1.0), nullptr, cox(d, edge).with_offset(offset(d, 0.01)), m % 2 ? 0 : 2, betti});
    }
  cases.push_back({"torus", torus(1.0, 0.4), nullptr, cox(3, 0.15), 0, {1, 2, 1}});
  cases.push_back({"flat torus", product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), nullptr, cox(4, 0.5), 0, {1, 2, 1}});
  cases.push_back(
      {"S1 x S2 in R5", product(sphere(1, 2, 1.0), sphere(2, 3, 1.0)), nullptr, cox(5, 0.6), 0, {1, 1, 1, 1}});
  cases.push_back({"S2 rotated in R4",
                   linear_map(embed(sphere(2, 3, 1.0), 4), Triangulation::coxeter(4).rotated(9).matrix()),
                   nullptr,
                   cox(4, 0.5),
                   2,
                   {1, 0, 1}});
  cases.push_back({"chair", chair(), nullptr, cox(3, 0.1), -4, {1, 6, 1}});
  // With boundary: a cap of S², a cut flat torus (annulus × circle halves), a disk in R⁴, a curve.
  cases.push_back({"spherical cap", sphere(2, 3, 1.0), ball_domain({1, 0, 0}, 0.6), cox(3, 0.2), 1, {1, 0, 0}});
  cases.push_back({"flat torus cut",
                   product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)),
                   half_space_domain({1, 0, 0, 0}, 0.5),
                   cox(4, 0.5),
                   0,
                   {1, 1, 0},
                   {{-1, 0, 1, 0}}});
  cases.push_back({"disk in R4",
                   translate(affine_plane(Eigen::MatrixXd::Identity(4, 4).rightCols(2), Eigen::VectorXd::Zero(4)),
                             Eigen::VectorXd::Constant(4, 0.01)),
                   ball_domain({0, 0, 0, 0}, 1.0),
                   cox(4, 0.4),
                   1,
                   {1, 0, 0}});
  cases.push_back({"moment curve", moment_curve(4), ball_domain({0, 0, 0, 0}, 1.5), cox(4, 0.1), 1, {1, 0}});
  // Lattice vertices exactly on M, no offset: FK unit cubes and the unit sphere through (±1,0,0)…,
  // and Ã_2 circles through lattice vertices.
  cases.push_back(
      {"sphere through FK vertices", sphere(2, 3, 1.0), nullptr, Triangulation::freudenthal(3), 2, {1, 0, 1}});
  cases.push_back(
      {"sphere through FK vertices, fine", sphere(2, 3, 2.0), nullptr, Triangulation::freudenthal(3), 2, {1, 0, 1}});
  {
    const Triangulation t = Triangulation::coxeter(2);
    std::int32_t v[2] = {1, 0};
    double x[2];
    t.cartesian(v, x);
    cases.push_back({"circle through Coxeter vertices", sphere(1, 2, std::hypot(x[0], x[1])), nullptr, t, 0, {1, 1}});
    cases.push_back({"S2 through Coxeter vertices",
                     sphere(2, 3, 2 * Triangulation::coxeter(3).longest_edge()),
                     nullptr,
                     Triangulation::coxeter(3),
                     2,
                     {1, 0, 1}});
  }
  cases.push_back({"plane through vertices in R3",
                   affine_plane(Eigen::MatrixXd::Identity(3, 1), Eigen::VectorXd::Zero(3)),
                   ball_domain({0, 0, 0}, 2.0),
                   Triangulation::freudenthal(3).scaled(0.5),
                   1,
                   {1, 0, 0}});
  return cases;
}

}  // namespace

TEST(TraceManifold, TopologyOfTheCatalogue) {
  for (const Case& c : catalogue()) {
    SCOPED_TRACE(c.name);
    const TopologyReport r = run(c);
    EXPECT_TRUE(r.is_manifold) << r.manifold_problem;
    EXPECT_EQ(r.euler_characteristic, c.euler);
    EXPECT_EQ(r.betti, c.betti);
    const int m = static_cast<int>(c.betti.size()) - 1;
    for (int j = 0; j <= m; ++j) EXPECT_GT(r.cells[j], 0u) << "no cell of dimension " << j;
    if (c.domain) {
      EXPECT_GT(r.boundary_cells[0], 0u);
    }
  }
}

TEST(TraceManifold, TracedSetEqualsBruteForceOverABox) {
  // Every k-simplex with its minimal vertex in a box around M, tested one by one, against tracing.
  struct Small {
    FunctionPtr f;
    Triangulation t;
    int lo, hi;
  };
  const std::vector<Small> cases = {
      {sphere(1, 2, 1.0), Triangulation::coxeter(2).scaled(0.4).with_offset(offset(2, 0.03)), -5, 5},
      {sphere(2, 3, 1.0), Triangulation::coxeter(3).scaled(0.6).with_offset(offset(3, 0.02)), -4, 4},
      {sphere(2, 3, 1.0), Triangulation::freudenthal(3), -2, 2},  // vertices on M
      {product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), Triangulation::coxeter(4).scaled(1.1), -3, 3},
  };
  for (const Small& c : cases) {
    const int d = c.t.dimension(), k = c.f->codimension();
    // The walk's F records every point it is evaluated at.
    std::vector<std::vector<double>> evaluated;
    const FunctionPtr f = c.f;
    const FunctionPtr recorded = make_function(
        d, k,
        [f, d, &evaluated](const double* x, double* v) {
          evaluated.emplace_back(x, x + d);
          f->evaluate(x, v);
        },
        f->seed());
    ImplicitOracle traced_oracle(c.t, recorded);
    const TraceResult r = trace_manifold(c.t, traced_oracle, {c.f->seed()});
    std::set<Simplex> traced;
    for (std::uint32_t i = 0; i < r.simplices.size(); ++i) traced.insert(r.simplices.simplex(i, d));
    // One F evaluation per lattice vertex the walk touched: as many evaluations as distinct
    // points, and every vertex of every traced simplex among them.
    const std::set<std::vector<double>> distinct(evaluated.begin(), evaluated.end());
    EXPECT_EQ(evaluated.size(), distinct.size()) << "a lattice vertex evaluated twice, d=" << d;
    EXPECT_EQ(traced_oracle.function_evaluations(), distinct.size());
    std::int32_t v[kMaxDimension];
    std::vector<double> x(d);
    for (const Simplex& s : traced)
      for (int j = 0; j <= s.k; ++j) {
        s.vertex(j, v);
        c.t.cartesian(v, x.data());
        ASSERT_TRUE(distinct.count(x)) << "a vertex of a traced simplex was never evaluated, d=" << d;
      }

    ImplicitOracle oracle(c.t, c.f);
    std::set<Simplex> brute;
    std::vector<std::int32_t> y(d, c.lo);
    std::vector<double> p(d);
    while (true) {
      // All k-simplices with minimal vertex y: the k-faces of the (k)-cofaces of the vertex y that keep y.
      CofaceEnumerator cofaces(Simplex::vertex_simplex(y), k);
      for (Simplex s; cofaces.next(s);)
        if (std::equal(y.begin(), y.end(), s.y.begin()) && oracle.intersect(s, p.data()).hit) brute.insert(s);
      int i = 0;
      while (i < d && y[i] == c.hi) y[i++] = c.lo;
      if (i == d) break;
      ++y[i];
    }
    EXPECT_EQ(traced, brute) << "d=" << d;
    // The brute force evaluated F at every vertex of the box once; the walk, near M, at fewer.
    EXPECT_LT(traced_oracle.function_evaluations(), oracle.function_evaluations());
  }
}

TEST(TraceManifold, OneEvaluationPerLatticeVertex) {
  // A counting F: the oracle must never evaluate the same point twice.
  auto seen = std::make_shared<std::map<std::vector<double>, int>>();
  auto mutex = std::make_shared<std::mutex>();
  FunctionPtr s = sphere(2, 4, 1.0);
  FunctionPtr counted = make_function(
      4, 2,
      [s, seen, mutex](const double* x, double* v) {
        std::lock_guard<std::mutex> lock(*mutex);
        ++(*seen)[std::vector<double>(x, x + 4)];
        s->evaluate(x, v);
      },
      s->seed());
  const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.4).with_offset(offset(4, 0.01));
  ImplicitOracle oracle(t, counted);
  const TraceResult r = trace_manifold(t, oracle, {counted->seed()});
  EXPECT_GT(r.simplices.size(), 100u);
  for (const auto& [x, n] : *seen) ASSERT_EQ(n, 1);
  EXPECT_EQ(oracle.function_evaluations(), seen->size());
  EXPECT_GT(r.oracle_calls, oracle.function_evaluations());  // the cache is what saves work
}

TEST(TraceManifold, PointsLieOnTheirSimplicesAndNearM) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1);
  FunctionPtr f = torus(1.0, 0.4);
  ImplicitOracle oracle(t, f);
  const TraceResult r = trace_manifold(t, oracle, {f->seed()});
  for (std::uint32_t i = 0; i < r.simplices.size(); ++i) {
    const Simplex s = r.simplices.simplex(i, 3);
    const double* p = r.points.data() + 3 * i;
    double lambda[2];
    t.barycentric(s, p, lambda);
    EXPECT_GE(lambda[0], -1e-12);
    EXPECT_GE(lambda[1], -1e-12);
    EXPECT_NEAR(lambda[0] + lambda[1], 1.0, 1e-12);
    double v;
    f->evaluate(p, &v);
    EXPECT_LT(std::abs(v), 0.01);  // O(h²) from M
  }
}

TEST(TraceManifold, BadInputGivesClearErrors) {
  const Triangulation t3 = Triangulation::coxeter(3).with_longest_edge(0.2);
  FunctionPtr s2 = sphere(2, 3, 1.0);
  {  // seed far from M
    ImplicitOracle oracle(t3, s2);
    EXPECT_THROW(trace_manifold(t3, oracle, {{5, 5, 5}}), SeedError);
  }
  {  // seed exactly on a lattice vertex that lies on M
    const Triangulation fk = Triangulation::freudenthal(3);
    ImplicitOracle oracle(fk, s2);
    const TraceResult r = trace_manifold(fk, oracle, {{1, 0, 0}});
    EXPECT_GT(r.simplices.size(), 0u);
  }
  {  // a scale far too coarse for a small sphere: no simplex meets M̂
    const Triangulation coarse = Triangulation::coxeter(3).scaled(100).with_offset(offset(3, 5));
    FunctionPtr tiny = sphere(2, 3, 0.01);
    ImplicitOracle oracle(coarse, tiny);
    EXPECT_THROW(trace_manifold(coarse, oracle, {tiny->seed()}), SeedError);
  }
  {  // unbounded manifold without domain: stops at the limit with a message
    const Triangulation t4 = Triangulation::coxeter(4).with_longest_edge(0.5);
    FunctionPtr curve = moment_curve(4);
    ImplicitOracle oracle(t4, curve);
    TraceOptions options;
    options.max_simplices = 2000;
    const TraceResult r = trace_manifold(t4, oracle, {curve->seed()}, options);
    EXPECT_EQ(r.status, TraceStatus::max_simplices_reached);
    EXPECT_NE(r.message.find("unbounded"), std::string::npos);
    EXPECT_GE(r.simplices.size(), 2000u);
  }
  {  // the limit holds across seeds: with many seeds, S stops one level past it, not a level per seed
    const Triangulation t4 = Triangulation::coxeter(4).with_longest_edge(0.05);
    FunctionPtr s3 = sphere(3, 4, 1.0);
    ImplicitOracle oracle(t4, s3);
    std::vector<std::vector<double>> seeds;
    for (int i = 0; i < 400; ++i) {  // points of S^3, spread out
      const double a = 0.1 * i, b = 0.37 * i;
      seeds.push_back({std::cos(a) * std::cos(b), std::cos(a) * std::sin(b), std::sin(a) * std::cos(2 * b),
                       std::sin(a) * std::sin(2 * b)});
    }
    TraceOptions options;
    options.max_simplices = 100;
    const TraceResult r = trace_manifold(t4, oracle, seeds, options);
    EXPECT_EQ(r.status, TraceStatus::max_simplices_reached);
    EXPECT_LT(r.simplices.size(), 2000u);
  }
  {  // a box is a domain: the half sphere it cuts out is a closed disk (χ = 1, Betti 1 0 0)
    ImplicitOracle oracle(t3, s2, box_domain(Box{{0, -2, -2}, {2, 2, 2}}));
    TraceResult r = trace_manifold(t3, oracle, {s2->seed()});
    EXPECT_EQ(r.status, TraceStatus::complete);
    EXPECT_GT(r.boundary_simplices.size(), 0u);
    for (std::uint32_t i = 0; i < r.simplices.size(); ++i) EXPECT_GE(r.points[3 * i], 0.0);
    const TopologyReport topo = analyze_topology(build_cell_complex(std::move(r)));
    EXPECT_TRUE(topo.is_manifold) << topo.manifold_problem;
    EXPECT_EQ(topo.betti, (std::vector<std::size_t>{1, 0, 0}));
  }
  {  // a walk stopped by the limit is open at its front: no Betti numbers, never wrong ones
    ImplicitOracle oracle(t3, s2);
    TraceOptions options;
    options.max_simplices = 100;
    TraceResult r = trace_manifold(t3, oracle, {s2->seed()}, options);
    EXPECT_EQ(r.status, TraceStatus::max_simplices_reached);
    const TopologyReport topo = analyze_topology(build_cell_complex(std::move(r)));
    EXPECT_FALSE(topo.closed);
    EXPECT_FALSE(topo.is_manifold);
    EXPECT_TRUE(topo.betti.empty());
  }
  {  // a polygon whose edges do not close up (one edge swapped for another): no Betti numbers either
    ImplicitOracle oracle(t3, s2);
    CellComplex cc = build_cell_complex(trace_manifold(t3, oracle, {s2->seed()}));
    ASSERT_TRUE(analyze_topology(cc).closed);
    CellLevel& faces = cc.interior[2];
    const std::uint32_t first = faces.facet_ids[faces.facet_offsets[0]];
    faces.facet_ids[faces.facet_offsets[0]] = first == 0 ? 1 : first - 1;
    const TopologyReport topo = analyze_topology(cc);
    EXPECT_FALSE(topo.closed);
    EXPECT_TRUE(topo.betti.empty());
    EXPECT_NE(topo.manifold_problem.find("not closed"), std::string::npos) << topo.manifold_problem;
  }
  // Dimension mismatches.
  EXPECT_THROW(ImplicitOracle(Triangulation::coxeter(4), s2), InputError);
  EXPECT_THROW(ImplicitOracle(t3, s2, ball_domain({0, 0}, 1.0)), InputError);
  {
    ImplicitOracle oracle(t3, s2);
    EXPECT_THROW(trace_manifold(t3, oracle, {{1, 0}}), InputError);
    EXPECT_THROW(trace_manifold(t3, oracle, {{1, NAN, 0}}), InputError);
    EXPECT_THROW(trace_manifold(t3, oracle, {}), SeedError);
  }
  {  // NaN from F names the point
    FunctionPtr bad = make_function(
        3, 1, [](const double* x, double* v) { v[0] = x[0] > 0.5 ? NAN : x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1; },
        std::vector<double>{0, 0, 1});
    ImplicitOracle oracle(t3, bad);
    try {
      trace_manifold(t3, oracle, {bad->seed()});
      FAIL() << "expected an EvaluationError";
    } catch (const EvaluationError& e) {
      EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("("), std::string::npos);
    }
  }
  {  // seed outside the domain
    ImplicitOracle oracle(t3, s2, ball_domain({-1, 0, 0}, 0.5));
    EXPECT_THROW(trace_manifold(t3, oracle, {s2->seed()}), SeedError);
  }
}

TEST(Seeds, ProjectionAndAutomaticSeedingFindEveryComponent) {
  FunctionPtr s2 = sphere(2, 3, 1.0);
  const auto p = project_onto_manifold(*s2, {0.3, 0.4, 0.2});
  ASSERT_TRUE(p.has_value());
  double v;
  s2->evaluate(p->data(), &v);
  EXPECT_NEAR(v, 0.0, 1e-12);
  // Two disjoint spheres: automatic seeds in a box find both components (β0 = 2).
  FunctionPtr two = make_function(3, 1, [](const double* x, double* f) {
    const double a = (x[0] - 2) * (x[0] - 2) + x[1] * x[1] + x[2] * x[2] - 1;
    const double b = (x[0] + 2) * (x[0] + 2) + x[1] * x[1] + x[2] * x[2] - 1;
    f[0] = a * b;
  });
  const Box box{{-4, -2, -2}, {4, 2, 2}};
  const auto seeds = find_seeds(*two, nullptr, box, 500);
  ASSERT_FALSE(seeds.empty());
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.25).with_offset(offset(3, 0.01));
  ImplicitOracle oracle(t, two);
  TraceOptions options;
  options.skip_unusable_seeds = true;
  TraceResult r = trace_manifold(t, oracle, seeds, options);
  const TopologyReport topo = analyze_topology(build_cell_complex(std::move(r)));
  EXPECT_EQ(topo.betti, (std::vector<std::size_t>{2, 0, 2}));
  EXPECT_EQ(topo.euler_characteristic, 4);
  EXPECT_FALSE(
      project_onto_manifold(
          *make_function(2, 1, [](const double* x, double* f) { f[0] = x[0] * x[0] + x[1] * x[1] + 1; }), {0.5, 0.5})
          .has_value());
}
