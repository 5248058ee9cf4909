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
