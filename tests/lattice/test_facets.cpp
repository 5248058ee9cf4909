// facet_without and extra_vertex_index (the tracer's door-in/door-out step) against the generic
// face construction and the coface enumeration, on random simplices of every dimension.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"

using namespace coxmesh;

namespace {

// A random k-simplex: base in [−5, 5]^d, d in the last block, every block non-empty.
Simplex random_simplex(int d, int k, std::mt19937& rng) {
  std::vector<std::int32_t> y(d);
  for (auto& c : y) c = std::uniform_int_distribution<int>(-5, 5)(rng);
  std::vector<int> order(d);
  for (int i = 0; i < d; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<std::vector<int>> blocks(k + 1);
  blocks[k].push_back(d);
  for (int b = 0; b < k; ++b) blocks[b].push_back(order[b]);
  for (int i = k; i < d; ++i) blocks[std::uniform_int_distribution<int>(0, k)(rng)].push_back(order[i]);
  return Simplex::from_partition(y, blocks);
}

}  // namespace

TEST(Facets, FacetWithoutEqualsTheGenericFace) {
  std::mt19937 rng(7);
  for (int d = 1; d <= 9; ++d)
    for (int l = 1; l <= d; ++l)
      for (int trial = 0; trial < 20; ++trial) {
        const Simplex sigma = random_simplex(d, l, rng);
        for (int j = 0; j <= l; ++j) {
          int idx[kMaxDimension + 1];
          for (int h = 0, i = 0; i <= l; ++i)
            if (i != j) idx[h++] = i;
          EXPECT_EQ(facet_without(sigma, j), face_from_indices(sigma, idx, l - 1)) << sigma << " without " << j;
        }
      }
}

TEST(Facets, ExtraVertexOfEveryCofacet) {
  std::mt19937 rng(11);
  for (int d = 1; d <= 8; ++d)
    for (int k = 0; k < d; ++k)
      for (int trial = 0; trial < 10; ++trial) {
        const Simplex tau = random_simplex(d, k, rng);
        CofaceEnumerator cofacets(tau, k + 1);
        std::int32_t a[kMaxDimension], b[kMaxDimension];
        for (Simplex mu; cofacets.next(mu);) {
          const int e = extra_vertex_index(tau, mu);
          ASSERT_EQ(facet_without(mu, e), tau) << tau << " in " << mu;
          for (int j = 0; j <= k; ++j) {  // τ's vertices keep their order in μ
            tau.vertex(j, a);
            mu.vertex(j < e ? j : j + 1, b);
            EXPECT_TRUE(std::equal(a, a + d, b)) << tau << " vertex " << j << " in " << mu;
          }
        }
      }
}

// The assertion tiers (errors.h): a facet of a vertex is a broken precondition, caught where debug
// assertions are on (debug builds, and the paranoid sanitizer build of CI).
TEST(Assertions, BrokenPreconditionsAbortWhereChecked) {
#if !defined(NDEBUG) || defined(COXMESH_PARANOID)
  const Simplex vertex = parse_simplex("(0,0) [{0,1,2}]");
  EXPECT_DEATH(facet_without(vertex, 0), "assertion");
#else
  GTEST_SKIP() << "debug assertions are off in this build (NDEBUG)";
#endif
}
