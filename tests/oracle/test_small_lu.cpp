// SmallLu (oracle/small_lu.h), the oracle's LU with partial pivoting: solves of random well-
// conditioned systems against Gaussian elimination in long double, the columns of the inverse, the
// same bits as the textbook loops at every size, singular matrices reported, systems that need row
// exchanges, and the error bound it states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "coxmesh/oracle/small_lu.h"

using coxmesh::SmallLu;

namespace {

using Matrix = std::vector<double>;  // n × n, column-major like the oracle's

// x = M⁻¹b by Gauss–Jordan elimination in long double with full pivoting: the brute-force reference.
std::vector<double> reference_solve(int n, const Matrix& m, const std::vector<double>& b) {
  std::vector<std::vector<long double>> a(n, std::vector<long double>(n + 1));
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) a[r][c] = m[c * n + r];
    a[r][n] = b[r];
  }
  std::vector<int> column(n);
  for (int c = 0; c < n; ++c) column[c] = c;
  for (int k = 0; k < n; ++k) {
    int pr = k, pc = k;
    for (int r = k; r < n; ++r)
      for (int c = k; c < n; ++c)
        if (std::fabs(a[r][c]) > std::fabs(a[pr][pc])) pr = r, pc = c;
    std::swap(a[k], a[pr]);
    for (auto& row : a) std::swap(row[k], row[pc]);
    std::swap(column[k], column[pc]);
    for (int r = 0; r < n; ++r)
      if (r != k) {
        const long double f = a[r][k] / a[k][k];
        for (int c = k; c <= n; ++c) a[r][c] -= f * a[k][c];
      }
  }
  std::vector<double> x(n);
  for (int k = 0; k < n; ++k) x[column[k]] = static_cast<double>(a[k][n] / a[k][k]);
  return x;
}

// Diagonally dominant with random signs and a random row order: well conditioned, and partial
// pivoting must exchange rows to find the dominant entries.
Matrix well_conditioned(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = i;
  std::shuffle(rows.begin(), rows.end(), rng);
  Matrix m(n * n);
  for (double& x : m) x = u(rng);
  for (int c = 0; c < n; ++c) m[c * n + rows[c]] = (u(rng) < 0 ? -1 : 1) * (n + 1.0);
  return m;
}

double max_abs(const std::vector<double>& v) {
  double x = 0;
  for (double e : v) x = std::max(x, std::fabs(e));
  return x;
}

}  // namespace

TEST(SmallLu, SolvesRandomWellConditionedSystems) {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SmallLu lu;
  for (int n = 1; n <= SmallLu::kMaxN; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      const Matrix m = well_conditioned(n, rng);
      std::vector<double> b(n), x(n), e(n);
      for (double& v : b) v = u(rng);
      ASSERT_TRUE(lu.factor(n, m.data())) << n;
      EXPECT_EQ(lu.size(), n);
      lu.solve(b.data(), x.data());
      const std::vector<double> expected = reference_solve(n, m, b);
      const double bound = 8 * n * std::numeric_limits<double>::epsilon() / 2 * lu.error_factor() * max_abs(x);
      for (int i = 0; i < n; ++i) {
        ASSERT_NEAR(x[i], expected[i], 1e-12 * (1 + max_abs(expected))) << "n " << n << " trial " << trial;
        ASSERT_LE(std::fabs(x[i] - expected[i]), bound) << "the stated error bound, n " << n;
      }
      // The columns of the inverse: M · (M⁻¹e_c) = e_c.
      for (int c = 0; c < n; c += std::max(1, n / 4)) {
        lu.solve_unit(c, e.data());
        for (int r = 0; r < n; ++r) {
          double s = 0;
          for (int j = 0; j < n; ++j) s += m[j * n + r] * e[j];
          ASSERT_NEAR(s, r == c ? 1.0 : 0.0, 1e-12) << "n " << n << " column " << c;
        }
      }
    }
}

// The textbook loops, operation by operation: the fixed sizes of SmallLu (unrolled) must give the
// same bits, or the oracle's answers, and so the meshes, would change with the code's shape.
struct TextbookLu {
  int n;
  Matrix lu;
  std::vector<int> perm;
  double& at(int r, int c) { return lu[c * n + r]; }
  TextbookLu(int size, const Matrix& m) : n(size), lu(m), perm(size) {
    for (int r = 0; r < n; ++r) perm[r] = r;
    for (int c = 0; c < n; ++c) {
      int p = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(at(r, c)) > std::abs(at(p, c))) p = r;
      for (int j = 0; j < n; ++j) std::swap(at(p, j), at(c, j));
      std::swap(perm[p], perm[c]);
      for (int r = c + 1; r < n; ++r) {
        const double f = at(r, c) /= at(c, c);
        for (int j = c + 1; j < n; ++j) at(r, j) -= f * at(c, j);
      }
    }
  }
  std::vector<double> solve(const std::vector<double>& b) {
    std::vector<double> x(n);
    for (int r = 0; r < n; ++r) {
      double s = b[perm[r]];
      for (int j = 0; j < r; ++j) s -= at(r, j) * x[j];
      x[r] = s;
    }
    for (int r = n - 1; r >= 0; --r) {
      double s = x[r];
      for (int j = r + 1; j < n; ++j) s -= at(r, j) * x[j];
      x[r] = s / at(r, r);
    }
    return x;
  }
};

TEST(SmallLu, FixedSizesGiveTheBitsOfTheTextbookLoops) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SmallLu lu;
  for (int n = 1; n <= 12; ++n)
    for (int trial = 0; trial < 50; ++trial) {
      Matrix m(n * n);
      for (double& v : m) v = u(rng);  // not dominant: rounding everywhere
      std::vector<double> b(n), x(n);
      for (double& v : b) v = u(rng);
      ASSERT_TRUE(lu.factor(n, m.data()));
      TextbookLu reference(n, m);
      lu.solve(b.data(), x.data());
      const std::vector<double> expected = reference.solve(b);
      for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], expected[i]) << "n " << n << " trial " << trial;
      std::vector<double> unit(n, 0.0);
      unit[n - 1] = 1;
      lu.solve_unit(n - 1, x.data());
      const std::vector<double> column = reference.solve(unit);
      for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], column[i]) << "n " << n << " trial " << trial;
    }
}

TEST(SmallLu, NeedsRowExchanges) {
  // A zero first pivot: without pivoting the factorisation would divide by 0.
  const Matrix swap = {0, 1, 1, 0};  // [[0, 1], [1, 0]]
  SmallLu lu;
  ASSERT_TRUE(lu.factor(2, swap.data()));
  double b[2] = {3, 5}, x[2];
  lu.solve(b, x);
  EXPECT_EQ(x[0], 5.0);
  EXPECT_EQ(x[1], 3.0);
  // A tiny first pivot: without pivoting the multiplier 1e20 destroys the answer; with it, exact.
  const Matrix tiny = {1e-20, 1, 1, 1};  // [[1e-20, 1], [1, 1]]
  ASSERT_TRUE(lu.factor(2, tiny.data()));
  double c[2] = {1, 2};
  lu.solve(c, x);
  EXPECT_NEAR(x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[1], 1.0, 1e-15);
  // A permutation of order 3 (every row moves) times a diagonal.
  const Matrix cycle = {0, 0, 3, 2, 0, 0, 0, 5, 0};  // rows: (0 2 0), (0 0 5), (3 0 0)
  ASSERT_TRUE(lu.factor(3, cycle.data()));
  double d[3] = {4, 10, 9}, y[3];
  lu.solve(d, y);
  EXPECT_EQ(y[0], 3.0);
  EXPECT_EQ(y[1], 2.0);
  EXPECT_EQ(y[2], 2.0);
}

TEST(SmallLu, ReportsSingularMatrices) {
  SmallLu lu;
  const Matrix zero(9, 0.0);
  EXPECT_FALSE(lu.factor(3, zero.data()));
  const Matrix equal_columns = {1, 2, 3, 1, 2, 3, 0, 1, 0};
  EXPECT_FALSE(lu.factor(3, equal_columns.data()));
  // A column twice another, with multipliers exact in binary: the second pivot is exactly 0.
  const Matrix dependent = {1, 2, 4, 2, 4, 8, 1, 0, 3};
  EXPECT_FALSE(lu.factor(3, dependent.data()));
  // Singular only in a later column, after pivoting rows.
  const Matrix late = {0, 1, 0, 1, 0, 0, 0, 2, 0};  // rank 2: the last row is zero
  EXPECT_FALSE(lu.factor(3, late.data()));
  // Nearly singular but not exactly: factors (the caller decides such cases exactly).
  const Matrix nearly = {1, 1, 1, 1 + 1e-15};
  EXPECT_TRUE(lu.factor(2, nearly.data()));
  // A 32 × 32 matrix with one zero column.
  std::mt19937_64 rng(7);
  Matrix big = well_conditioned(SmallLu::kMaxN, rng);
  std::fill_n(big.begin() + 17 * SmallLu::kMaxN, SmallLu::kMaxN, 0.0);
  EXPECT_FALSE(lu.factor(SmallLu::kMaxN, big.data()));
}
