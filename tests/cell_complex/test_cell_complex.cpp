// The cell complex (thesis §4.2): the pipelined construction that build_cell_complex runs gives, for
// 1, 2 and 3 workers, exactly the levels of the plain construction (cells, numbering, facets), with
// and without a boundary.
#include <gtest/gtest.h>

#include <algorithm>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/next_level.h"
#include "coxmesh/oracle/implicit_oracle.h"

using namespace coxmesh;

namespace {

void expect_same_level(const CellLevel& plain, const CellLevel& level, const std::string& what) {
  ASSERT_EQ(plain.size(), level.size()) << what;
  const int words = plain.simplices.words();
  for (std::uint32_t c = 0; c < plain.size(); ++c) {
    ASSERT_TRUE(std::equal(plain.simplices.key(c), plain.simplices.key(c) + words, level.simplices.key(c))) << what;
    const auto a = plain.facets(c), b = level.facets(c);
    ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << what << " cell " << c;
  }
}

}  // namespace

TEST(CellComplex, PipelinedLevelsAreThePlainOnes) {
  struct Case {
    int m, d;
    double edge;
    FunctionPtr domain;
  };
  const Case cases[] = {{2, 3, 0.15, nullptr},
                        {2, 3, 0.15, half_space_domain({-0.3, -0.2, 0.9}, 0.2)},
                        {3, 4, 0.35, ball_domain({0.5, 0, 0, 0}, 0.9)},
                        {1, 5, 0.2, nullptr}};
  for (const Case& c : cases) {
    const Triangulation t = Triangulation::coxeter(c.d).with_longest_edge(c.edge);
    const FunctionPtr f = sphere(c.m, c.d, 1.0);
    ImplicitOracle oracle(t, f, c.domain);
    const TraceResult traced = trace_manifold(t, oracle, {f->seed()});
    const int k = c.d - c.m;
    for (int threads : {1, 2, 3}) {
      const CellComplex cc = build_cell_complex(TraceResult(traced), threads);
      const std::string what = "m=" + std::to_string(c.m) + " d=" + std::to_string(c.d) +
                               (c.domain ? " with boundary" : "") + " threads=" + std::to_string(threads);
      for (int j = 1; j <= c.m; ++j)
        expect_same_level(cells::next_level_plain(cc.interior[j - 1], c.d, k + j), cc.interior[j],
                          what + " interior level " + std::to_string(j));
      if (c.domain) {
        ASSERT_GT(cc.boundary[0].size(), 0u) << what;
        for (int j = 1; j <= c.m - 1; ++j)
          expect_same_level(cells::next_level_plain(cc.boundary[j - 1], c.d, k + 1 + j), cc.boundary[j],
                            what + " boundary level " + std::to_string(j));
      }
    }
  }
}

// Without keys, a complex keeps everything but them: the same cell counts, facets, boundary facets
// and vertices, level by level, and the levels hold no key (their words are gone).
TEST(CellComplex, WithoutKeysTheSameCells) {
  for (const FunctionPtr& domain : {FunctionPtr{}, ball_domain({0.5, 0, 0, 0}, 0.9)}) {
    const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.35);
    const FunctionPtr f = sphere(3, 4, 1.0);
    ImplicitOracle oracle(t, f, domain);
    const TraceResult traced = trace_manifold(t, oracle, {f->seed()});
    for (int threads : {1, 2}) {
      const CellComplex with = build_cell_complex(TraceResult(traced), threads);
      const CellComplex without = build_cell_complex(TraceResult(traced), threads, false);
      const std::string what =
          std::string(domain ? "with" : "without") + " boundary, threads=" + std::to_string(threads);
      EXPECT_TRUE(with.vertices == without.vertices && with.boundary_vertices == without.boundary_vertices) << what;
      ASSERT_EQ(with.interior.size(), without.interior.size()) << what;
      ASSERT_EQ(with.boundary.size(), without.boundary.size()) << what;
      for (const auto& [a, b] :
           {std::pair{&with.interior, &without.interior}, std::pair{&with.boundary, &without.boundary}})
        for (std::size_t j = 0; j < a->size(); ++j) {
          const CellLevel &x = (*a)[j], &y = (*b)[j];
          EXPECT_EQ(y.simplices.words(), 0) << what << " level " << j;
          EXPECT_TRUE(x.size() == y.size() && x.facet_offsets == y.facet_offsets && x.facet_ids == y.facet_ids &&
                      x.boundary_facet == y.boundary_facet)
              << what << " level " << j;
        }
      EXPECT_TRUE(!domain || without.boundary[0].size() > 0) << what;
    }
  }
}
