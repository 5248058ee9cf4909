// The exact transversality rule against an independent rational-arithmetic reference, on
// degenerate matrices (exact zeros, repeated columns, vertices on M) where rounding would lie.
#include <gtest/gtest.h>

// GCC 12 reports a false maybe-uninitialized inside Boost.Multiprecision's cpp_int (clang has no
// such warning, and rejects the name).
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <boost/multiprecision/cpp_int.hpp>
#include <random>
#include <string>
#include <vector>

#include "coxmesh/oracle/double_word.h"
#include "coxmesh/oracle/transversality.h"

using coxmesh::lexicographic_solve;
using Q = boost::multiprecision::cpp_rational;

namespace {

// Reference: M^{-1} by Gauss–Jordan over Q; transverse iff every row is lexicographically positive.
bool reference(int n, const std::vector<double>& m, std::vector<double>& lambda) {
  std::vector<std::vector<Q>> a(n, std::vector<Q>(2 * n));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 2 * n; ++c) a[r][c] = c < n ? Q(m[c * n + r]) : Q(c - n == r ? 1 : 0);
  for (int c = 0; c < n; ++c) {
    int p = c;
    while (p < n && a[p][c] == 0) ++p;
    if (p == n) return false;
    std::swap(a[p], a[c]);
    const Q inv = 1 / a[c][c];
    for (auto& v : a[c]) v *= inv;
    for (int r = 0; r < n; ++r)
      if (r != c && a[r][c] != 0) {
        const Q f = a[r][c];
        for (int j = 0; j < 2 * n; ++j) a[r][j] -= f * a[c][j];
      }
  }
  for (int r = 0; r < n; ++r) {
    int c = n;
    while (a[r][c] == 0) ++c;
    if (a[r][c] < 0) return false;
  }
  lambda.resize(n);
  for (int r = 0; r < n; ++r) lambda[r] = static_cast<double>(a[r][n]);
  return true;
}

// lexicographic_solve on the n × n matrix m against the exact reference: the same answer and, for
// a transverse simplex, the same barycentric coordinates within `tolerance` (non-negative, summing
// to 1). Returns the answer.
bool expect_agrees_with_reference(int n, const std::vector<double>& m, double tolerance, const std::string& what) {
  std::vector<double> expected, got(n);
  const bool ref = reference(n, m, expected);
  EXPECT_EQ(lexicographic_solve(n, m.data(), got.data()), ref) << what;
  if (ref) {
    double sum = 0;
    for (int j = 0; j < n; ++j) {
      EXPECT_NEAR(got[j], expected[j], tolerance) << what;
      EXPECT_GE(got[j], 0.0) << what;
      sum += got[j];
    }
    EXPECT_NEAR(sum, 1.0, tolerance) << what;
  }
  return ref;
}

}  // namespace

TEST(Transversality, AgreesWithExactReferenceOnDegenerateMatrices) {
  std::mt19937_64 rng(11);
  int transverse = 0, total = 0;
  for (int n = 2; n <= 7; ++n) {
    for (int trial = 0; trial < 1000; ++trial) {
      // Small integers and halves: exact zeros, ties and singular matrices are frequent.
      std::vector<double> m(n * n);
      for (int c = 0; c < n; ++c) {
        m[c * n] = 1;
        for (int r = 1; r < n; ++r)
          m[c * n + r] = static_cast<double>(static_cast<int>(rng() % 5) - 2) / ((rng() % 2) ? 1 : 2);
      }
      if (trial % 3 == 0) {  // a vertex exactly on M
        const int c = static_cast<int>(rng() % n);
        for (int r = 1; r < n; ++r) m[c * n + r] = 0;
      }
      transverse +=
          expect_agrees_with_reference(n, m, 1e-12, "n=" + std::to_string(n) + " trial=" + std::to_string(trial));
      ++total;
    }
  }
  EXPECT_GT(transverse, total / 50);  // the sample exercises both answers
}

TEST(Transversality, EveryCofacetHasZeroOrTwoTransverseFacets) {
  // Facets of a (k+1)-simplex = drop one column of the (k+1) × (k+2) value table. With integer
  // values (many vertices on M, many ties) the rule must still give 0 or 2.
  std::mt19937_64 rng(5);
  for (int k = 1; k <= 5; ++k) {
    for (int trial = 0; trial < 2000; ++trial) {
      std::vector<std::vector<double>> values(k + 2, std::vector<double>(k));
      for (auto& col : values)
        for (auto& v : col) v = static_cast<double>(static_cast<int>(rng() % 3) - 1);
      int count = 0;
      for (int drop = 0; drop < k + 2; ++drop) {
        std::vector<double> m;
        for (int c = 0; c < k + 2; ++c) {
          if (c == drop) continue;
          m.push_back(1);
          m.insert(m.end(), values[c].begin(), values[c].end());
        }
        std::vector<double> lambda(k + 1);
        count += lexicographic_solve(k + 1, m.data(), lambda.data());
      }
      ASSERT_TRUE(count == 0 || count == 2) << "k=" << k << " trial=" << trial << " count=" << count;
    }
  }
}

TEST(Transversality, WorkedExampleOfTheThesis) {
  // Thesis §4.3: F = x² + y² − 1 on the segment (0,0)–(2,0): values −1, 3 → λ = (3/4, 1/4).
  const double m[] = {1, -1, 1, 3};
  double lambda[2];
  ASSERT_TRUE(lexicographic_solve(2, m, lambda));
  EXPECT_DOUBLE_EQ(lambda[0], 0.75);
  EXPECT_DOUBLE_EQ(lambda[1], 0.25);
  // Zero counts as negative: a vertex on M belongs to the side F ≤ 0.
  const double on[] = {1, 0, 1, 3}, both_on[] = {1, 0, 1, 0}, neg_zero[] = {1, -2, 1, 0};
  ASSERT_TRUE(lexicographic_solve(2, on, lambda));
  EXPECT_EQ(lambda[0], 1.0);
  EXPECT_EQ(lambda[1], 0.0);
  EXPECT_FALSE(lexicographic_solve(2, both_on, lambda));
  EXPECT_FALSE(lexicographic_solve(2, neg_zero, lambda));
}

TEST(Transversality, AgreesWithExactReferenceOnRoundingNoise) {
  // Lattice vertices near M give values of F that are rounding noise (a few units of 2⁻⁵⁵) where
  // the exact value is 0, so the leading entries of M⁻¹ are tiny but not zero: what the
  // double-word filter decides. Some vertices exactly on M, some noise of noise.
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(-1, 1);
  int transverse = 0, total = 0;
  for (int n = 3; n <= 7; ++n) {
    for (int trial = 0; trial < 150; ++trial) {
      std::vector<double> m(n * n);
      for (int c = 0; c < n; ++c) {
        m[c * n] = 1;
        for (int r = 1; r < n; ++r) {
          const int kind = static_cast<int>(rng() % 4);
          const double noise = std::ldexp(static_cast<double>(static_cast<int>(rng() % 7) - 3), -55);
          m[c * n + r] = kind == 0 ? noise : kind == 1 ? noise * std::ldexp(unit(rng), -50) : unit(rng);
        }
      }
      if (trial % 4 == 0) {
        const int c = static_cast<int>(rng() % n);
        for (int r = 1; r < n; ++r) m[c * n + r] = 0;
      }
      transverse +=
          expect_agrees_with_reference(n, m, 1e-9, "n=" + std::to_string(n) + " trial=" + std::to_string(trial));
      ++total;
    }
  }
  EXPECT_GT(transverse, total / 50);
}

TEST(DoubleWord, EveryOperationWithinItsUnit) {
  using coxmesh::DoubleWord;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.5, 1);
  const auto random_word = [&] {
    // hi + lo with |lo| ≤ ulp(hi)/2, at exponents −40..40, either sign.
    const double hi = std::ldexp(unit(rng), static_cast<int>(rng() % 81) - 40) * ((rng() & 1) ? 1 : -1);
    const double lo = hi * std::ldexp(unit(rng), -54) * ((rng() & 1) ? 1 : -1);
    const double s = hi + lo;
    return DoubleWord{s, lo - (s - hi)};
  };
  const auto exact = [](DoubleWord x) { return Q(x.hi) + Q(x.lo); };
  const auto within = [](const Q& got, const Q& want) {
    return abs(got - want) <= Q(coxmesh::kDoubleWordUnit) * abs(want);
  };
  for (int trial = 0; trial < 20000; ++trial) {
    const DoubleWord x = random_word(), y = random_word();
    ASSERT_TRUE(within(exact(x + y), exact(x) + exact(y))) << trial;
    ASSERT_TRUE(within(exact(x - y), exact(x) - exact(y))) << trial;
    ASSERT_TRUE(within(exact(x * y), exact(x) * exact(y))) << trial;
    ASSERT_TRUE(within(exact(x / y), exact(x) / exact(y))) << trial;
  }
  // Cancellation: x + (−x·(1 + 2⁻⁹⁰)) keeps the tiny difference.
  const DoubleWord x{1.0, 0x1p-60}, y{-1.0, -0x1p-60 - 0x1p-90};
  EXPECT_EQ(exact(x + y), Q(-0x1p-90));
}
