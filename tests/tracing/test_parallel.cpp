// Multi-threaded tracing gives the same result, order and bits included, for every thread count,
// equal to the sequential walk's; also when a limit or a box (a domain) truncates the walk.
// The cell complex built with several threads is identical too, cell numbering included, and
// equal to a plain reference construction (one coface inserted after the other). Shared vertex
// values store each vertex once however many threads ask for it at the same time.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <random>
#include <thread>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "expect_identical.h"

using namespace coxmesh;

namespace {

struct Case {
  std::string name;
  FunctionPtr f, domain;
  Triangulation t;
  std::vector<double> seed;
  std::size_t max_simplices = TraceOptions{}.max_simplices;
};

// The cell complex (thesis §4.2) the plain way: level j numbers the l-cofaces of level j − 1's cells in order of
// discovery; each cell's facets in increasing order.
struct ReferenceLevel {
  PackedKeyIndex simplices;
  std::vector<std::vector<std::uint32_t>> facets;
};
ReferenceLevel reference_level(const PackedKeyIndex& prev, int d, int l) {
  ReferenceLevel level{PackedKeyIndex(packed_words(d)), {}};
  for (std::uint32_t c = 0; c < prev.size(); ++c) {
    CofaceEnumerator cofaces(prev.simplex(c, d), l);
    for (Simplex nu; cofaces.next(nu);) {
      const auto [id, fresh] = level.simplices.insert(nu);
      if (fresh) level.facets.emplace_back();
      level.facets[id].push_back(c);
    }
  }
  return level;
}

}  // namespace

TEST(ParallelTracing, IdenticalForEveryThreadCount) {
  const std::vector<Case> cases = {
      {"S2 in R3", sphere(2, 3, 1.0), nullptr, Triangulation::coxeter(3).with_longest_edge(0.08), {}},
      {"torus, FK, vertices on M", torus(1.0, 0.5), nullptr, Triangulation::freudenthal(3).scaled(0.125), {}},
      {"S2 in R4", sphere(2, 4, 1.0), nullptr, Triangulation::coxeter(4).with_longest_edge(0.25).rotated(3), {}},
      {"flat torus cut",
       product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)),
       half_space_domain({1, 1, 0, 0}, 0.5),
       Triangulation::coxeter(4).with_longest_edge(0.3),
       {-1, 0, 1, 0}},
      {"limit", moment_curve(4), nullptr, Triangulation::coxeter(4).with_longest_edge(0.2), {}, 3000},
      {"box",
       sphere(2, 3, 1.0),
       box_domain(Box{{-2, -2, -0.3}, {2, 2, 2}}),
       Triangulation::coxeter(3).with_longest_edge(0.1),
       {}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::vector<std::vector<double>> seeds = {c.seed.empty() ? c.f->seed() : c.seed};
    ImplicitOracle oracle(c.t, c.f, c.domain);
    TraceOptions options;
    options.max_simplices = c.max_simplices;
    const TraceResult sequential = trace_manifold(c.t, oracle, seeds, options);
    EXPECT_GT(sequential.simplices.size(), 500u);
    for (int threads : {1, 2, 3, 4, 2}) {
      options.threads = threads;
      const TraceResult parallel = trace_manifold(
          c.t, [&] { return std::make_unique<ImplicitOracle>(c.t, c.f, c.domain); }, seeds, options);
      expect_identical(sequential, parallel, c.name + ", " + std::to_string(threads) + " threads");
      // Oracles sharing their vertex values: the same result, and F once per vertex in all.
      const auto shared = ImplicitOracle::make_shared_values(c.t, c.f, c.domain);
      const TraceResult sharing = trace_manifold(
          c.t, [&] { return std::make_unique<ImplicitOracle>(c.t, c.f, c.domain, shared); }, seeds, options);
      expect_identical(sequential, sharing, c.name + ", " + std::to_string(threads) + " threads sharing values");
      EXPECT_EQ(sharing.function_evaluations, sequential.function_evaluations) << threads << " threads";
      // Workers test again only what another worker tested (or they tested in an earlier level):
      // a simplex of S that a worker meets is found without the oracle (fails if the index of the
      // levels near the walk's front misses one of them).
      EXPECT_LE(sharing.oracle_calls, sequential.oracle_calls * 5 / 4) << threads << " threads";
    }
  }
}

// An oracle for which the walk's graph is not symmetric: the k-simplices in a ball of the lattice
// are transverse or not at random (by a hash of the simplex), so a cofacet often has three or more
// transverse facets, and the first one after τ leads to a simplex whose own walk need not lead back.
// The parallel walk then meets simplices of levels older than the previous one again; it must
// notice and give the sequential result all the same.
class ScatteredOracle : public IntersectionOracle {
 public:
  ScatteredOracle(int d, int k, int radius) : d_(d), k_(k), radius_(radius) {}
  int ambient_dimension() const override { return d_; }
  int codimension() const override { return k_; }
  Intersection intersect(const Simplex& tau, double* point) override {
    std::int32_t v[kMaxDimension];
    std::fill(point, point + d_, 0.0);
    for (int j = 0; j <= tau.k; ++j) {
      tau.vertex(j, v);
      std::int64_t norm2 = 0;
      for (int i = 0; i < d_; ++i) norm2 += std::int64_t{v[i]} * v[i], point[i] += v[i] / (tau.k + 1.0);
      if (norm2 > std::int64_t{radius_} * radius_) return {};
    }
    std::uint32_t key[packed_words(kMaxDimension)];
    pack(tau, key);
    return {hash_words(key, packed_words(d_)) % 3 != 0, -1};
  }

 private:
  int d_, k_, radius_;
};

TEST(ParallelTracing, IdenticalWhenTheWalkGraphIsNotSymmetric) {
  for (const auto& [d, k, radius] : {std::tuple{3, 1, 12}, std::tuple{4, 2, 5}}) {
    const Triangulation t = Triangulation::freudenthal(d);
    const std::vector<std::vector<double>> seeds = {std::vector<double>(d, 0.25)};
    ScatteredOracle oracle(d, k, radius);
    const TraceResult sequential = trace_manifold(t, oracle, seeds);
    EXPECT_GT(sequential.simplices.size(), 2000u);
    for (int threads : {2, 3, 4}) {
      TraceOptions options;
      options.threads = threads;
      const TraceResult parallel = trace_manifold(
          t, [&, d = d, k = k, radius = radius] { return std::make_unique<ScatteredOracle>(d, k, radius); }, seeds,
          options);  // (bindings copied: clang 14 cannot capture them)
      expect_identical(sequential, parallel,
                       std::to_string(d) + "/" + std::to_string(k) + ", " + std::to_string(threads) + " threads");
    }
  }
}

// Four threads ask for the same 40,000 vertices in different orders, while the table grows from
// its first size many times over: each vertex is evaluated exactly once, and every thread reads its
// values.
TEST(ParallelSharedValues, EveryVertexEvaluatedOnceWhileTheTableGrows) {
  constexpr int kVertices = 40'000, kThreads = 4;
  const auto vertex = [](int i, std::int32_t* v) {
    v[0] = i % 37 - 18, v[1] = i / 37 % 41 - 20, v[2] = i / (37 * 41) - 13;
  };
  const auto value = [](const std::int32_t* v, int j) { return v[0] * 1e6 + v[1] * 1e3 + v[2] + 0.5 * j; };
  SharedVertexValues shared(3, 2);
  std::vector<std::atomic<int>> evaluations(kVertices);
  std::vector<int> wrong(kThreads, 0), evaluated(kThreads, 0);
  std::vector<std::thread> threads;
  for (int w = 0; w < kThreads; ++w)
    threads.emplace_back([&, w] {
      std::vector<int> order(kVertices);
      for (int i = 0; i < kVertices; ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), std::mt19937(w));
      for (const int i : order) {
        std::int32_t v[3];
        vertex(i, v);
        double out[2];
        evaluated[w] +=
            shared.get(v, hash_words(reinterpret_cast<const std::uint32_t*>(v), 3), out, [&](double* stored) {
              evaluations[i].fetch_add(1);
              stored[0] = value(v, 0), stored[1] = value(v, 1);
            });
        wrong[w] += out[0] != value(v, 0) || out[1] != value(v, 1);
      }
    });
  for (std::thread& t : threads) t.join();
  int total = 0;
  for (int w = 0; w < kThreads; ++w) {
    EXPECT_EQ(wrong[w], 0) << "thread " << w;
    total += evaluated[w];
  }
  EXPECT_EQ(total, kVertices);
  for (int i = 0; i < kVertices; ++i) ASSERT_EQ(evaluations[i].load(), 1) << "vertex " << i;
}

TEST(ParallelTracing, ErrorsFromWorkersReachTheCaller) {
  FunctionPtr bad = make_function(
      3, 1, [](const double* x, double* v) { v[0] = x[0] > 0.7 ? NAN : x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1; },
      std::vector<double>{0, 0, 1});
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1);
  TraceOptions options;
  options.threads = 2;
  EXPECT_THROW(trace_manifold(
                   t, [&] { return std::make_unique<ImplicitOracle>(t, bad); }, {bad->seed()}, options),
               EvaluationError);
  const auto shared = ImplicitOracle::make_shared_values(t, bad);
  EXPECT_THROW(
      trace_manifold(
          t, [&] { return std::make_unique<ImplicitOracle>(t, bad, nullptr, shared); }, {bad->seed()}, options),
      EvaluationError);
  EXPECT_THROW(ImplicitOracle(t, bad, half_space_domain({1, 0, 0}, 0), shared),
               InputError);  // 2 values per vertex, not 1
}

TEST(ParallelCellComplex, IdenticalForEveryThreadCount) {
  struct Complex {
    std::string name;
    FunctionPtr f, domain;
    Triangulation t;
    std::vector<double> seed;
  };
  const std::vector<Complex> cases = {
      {"S2 in R3", sphere(2, 3, 1.0), nullptr, Triangulation::coxeter(3).with_longest_edge(0.05), {}},
      {"S3 in R5", sphere(3, 5, 1.0), nullptr, Triangulation::coxeter(5).with_longest_edge(0.5).rotated(1), {}},
      {"flat torus cut",
       product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)),
       half_space_domain({1, 1, 0, 0}, 0.5),
       Triangulation::coxeter(4).with_longest_edge(0.25),
       {-1, 0, 1, 0}},
  };
  auto same_level = [](const CellLevel& a, const CellLevel& b) {
    if (a.size() != b.size() || a.facet_offsets != b.facet_offsets || a.facet_ids != b.facet_ids ||
        a.boundary_facet != b.boundary_facet)
      return false;
    for (std::uint32_t c = 0; c < a.size(); ++c)
      if (!std::equal(a.simplices.key(c), a.simplices.key(c) + a.simplices.words(), b.simplices.key(c))) return false;
    return true;
  };
  for (const Complex& c : cases) {
    SCOPED_TRACE(c.name);
    ImplicitOracle oracle(c.t, c.f, c.domain);
    const TraceResult traced = trace_manifold(c.t, oracle, {c.seed.empty() ? c.f->seed() : c.seed});
    const CellComplex one = build_cell_complex(TraceResult(traced), 1);
    std::size_t cells = 0;
    for (const CellLevel& l : one.interior) cells += l.size();
    EXPECT_GT(cells, 20000u);  // several batches of the parallel construction
    const int d = c.t.dimension(), k = c.f->codimension();
    for (const auto* levels : {&one.interior, &one.boundary}) {
      const int first = levels == &one.interior ? k : k + 1;  // dimension of the level-0 simplices
      for (std::size_t j = 1; j < levels->size(); ++j) {
        const ReferenceLevel ref = reference_level((*levels)[j - 1].simplices, d, first + static_cast<int>(j));
        const CellLevel& got = (*levels)[j];
        ASSERT_EQ(got.size(), ref.simplices.size()) << j;
        for (std::uint32_t cell = 0; cell < got.size(); ++cell) {
          ASSERT_TRUE(std::equal(got.simplices.key(cell), got.simplices.key(cell) + got.simplices.words(),
                                 ref.simplices.key(cell)))
              << "level " << j << " cell " << cell;
          const auto facets = got.facets(cell);
          ASSERT_TRUE(std::equal(facets.begin(), facets.end(), ref.facets[cell].begin(), ref.facets[cell].end()))
              << "level " << j << " cell " << cell;
        }
      }
    }
    for (int threads : {2, 3, 4}) {
      const CellComplex many = build_cell_complex(TraceResult(traced), threads);
      ASSERT_EQ(one.interior.size(), many.interior.size());
      ASSERT_EQ(one.boundary.size(), many.boundary.size());
      for (std::size_t j = 0; j < one.interior.size(); ++j)
        EXPECT_TRUE(same_level(one.interior[j], many.interior[j])) << j;
      for (std::size_t j = 0; j < one.boundary.size(); ++j)
        EXPECT_TRUE(same_level(one.boundary[j], many.boundary[j])) << j;
      EXPECT_EQ(one.vertices, many.vertices);
      EXPECT_EQ(one.boundary_vertices, many.boundary_vertices);
    }
  }
}
