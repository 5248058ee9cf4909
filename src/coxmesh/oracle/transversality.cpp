// Spec §3: lexicographic transversality. Exactness matters: a wrong sign on a degenerate simplex
// would give a (k+1)-simplex 1 or 3 transverse facets and a non-manifold output.
#include "coxmesh/oracle/transversality.h"

// GCC 12 reports a false maybe-uninitialized inside Boost.Multiprecision's cpp_int (clang has no
// such warning, and rejects the name).
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <array>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <limits>
#include <utility>

#include "coxmesh/oracle/small_lu.h"

namespace coxmesh {

namespace {

constexpr int kMaxN = 32;

// Exact fallback. Each row of M is scaled by a power of two so that its entries are integers
// (a positive row scaling multiplies the columns of M^{-1} by positive numbers, so signs and the
// first column are unchanged; row 0 is all ones). Fraction-free Gauss–Jordan (Bareiss) on [M | I]
// ends with [D·I | D·M^{-1}]: every division is exact and no gcd is ever taken.
bool exact_solve(int n, const double* m, double* lambda) {
  using Z = boost::multiprecision::cpp_int;
  std::array<std::array<Z, 2 * kMaxN>, kMaxN> a;  // row-major augmented matrix
  for (int r = 0; r < n; ++r) {
    // Entry = odd integer × 2^e; scale the row by 2^{-min e}.
    std::array<long long, kMaxN> mant{};
    std::array<int, kMaxN> expo{};
    int low = std::numeric_limits<int>::max();
    for (int c = 0; c < n; ++c) {
      const double v = m[c * n + r];
      if (v == 0) continue;
      int e;
      long long q = static_cast<long long>(std::ldexp(std::frexp(v, &e), 53));
      e -= 53;
      while ((q & 1) == 0) q /= 2, ++e;
      mant[c] = q;
      expo[c] = e;
      low = std::min(low, e);
    }
    for (int c = 0; c < n; ++c) {
      a[r][c] = Z(mant[c] < 0 ? -mant[c] : mant[c]) << (mant[c] == 0 ? 0 : expo[c] - low);
      if (mant[c] < 0) a[r][c] = -a[r][c];
    }
    for (int c = n; c < 2 * n; ++c) a[r][c] = (c - n == r) ? 1 : 0;
  }
  Z prev = 1;
  for (int k = 0; k < n; ++k) {
    int p = k;
    while (p < n && a[p][k] == 0) ++p;
    if (p == n) return false;  // singular
    if (p != k) std::swap(a[p], a[k]);
    for (int i = 0; i < n; ++i) {
      if (i == k) continue;
      for (int j = 0; j < 2 * n; ++j)
        if (j != k) a[i][j] = (a[k][k] * a[i][j] - a[i][k] * a[k][j]) / prev;
      a[i][k] = 0;
    }
    prev = a[k][k];
  }
  // Now a[r][r] = D for every r and a[r][n + c] = D·(M^{-1})_{rc}.
  for (int r = 0; r < n; ++r) {
    int c = n;
    while (a[r][c] == 0) ++c;  // rows of an inverse are never zero
    if ((a[r][c] < 0) != (a[r][r] < 0)) return false;
  }
  for (int r = 0; r < n; ++r) {
    boost::multiprecision::cpp_rational q(a[r][n]);  // (not the two-argument constructor: Boost 1.74
    q /= a[r][r];                                     // rejects a zero numerator over a negative)
    lambda[r] = static_cast<double>(q);
  }
  return true;
}

}  // namespace

bool lexicographic_solve(int n, const double* m, double* lambda) {
  if (n == 2) {
    // M = [[1, 1], [f0, f1]]: exact in floating point. Transverse iff one value is > 0 and the
    // other ≤ 0 (zero counts as negative); the sign of f1 − f0 is exact.
    const double f0 = m[1], f1 = m[3];
    if ((f0 > 0) == (f1 > 0)) return false;
    lambda[0] = f1 / (f1 - f0);
    lambda[1] = -f0 / (f1 - f0);
    return true;
  }
  // Exact quick rejection: if some F_i is > 0 at every vertex (or < 0 at every vertex), then
  // Σ λ_j F_i(v_j) = ε^i has no solution with λ ≥ 0, Σ λ = 1 for small ε > 0.
  for (int i = 1; i < n; ++i) {
    bool all_pos = true, all_neg = true;
    for (int j = 0; j < n; ++j) {
      all_pos &= m[j * n + i] > 0;
      all_neg &= m[j * n + i] < 0;
    }
    if (all_pos || all_neg) return false;
  }
  SmallLu lu;
  if (!lu.factor(n, m)) return exact_solve(n, m, lambda);
  // Usually λ = M⁻¹·e₀ alone decides: a certainly negative λ_j rejects, all certainly positive
  // accept (the lexicographic rule only looks further along a row whose leading entry is 0).
  constexpr double u = std::numeric_limits<double>::epsilon() / 2;
  const double factor = lu.error_factor();
  if (n * u * factor < 1e-6) {
    lu.solve_unit(0, lambda);
    double size = 0;
    for (int r = 0; r < n; ++r) size = std::max(size, std::abs(lambda[r]));
    const double err = 8.0 * n * u * factor * size;
    bool positive = true;
    for (int r = 0; r < n; ++r) {
      if (lambda[r] < -err) return false;
      positive &= lambda[r] > err;
    }
    if (positive) return true;
  }
  // Undecided: the whole inverse, column by column, and the lexicographic signs of its rows.
  double norm_m = 0;
  for (int r = 0; r < n; ++r) {
    double row = 0;
    for (int c = 0; c < n; ++c) row += std::abs(m[c * n + r]);
    norm_m = std::max(norm_m, row);
  }
  std::array<double, kMaxN * kMaxN> inv;  // column-major
  for (int c = 0; c < n; ++c) lu.solve_unit(c, inv.data() + c * n);
  double norm_inv = 0, max_inv = 0;
  for (int r = 0; r < n; ++r) {
    double row = 0;
    for (int c = 0; c < n; ++c) {
      row += std::abs(inv[c * n + r]);
      max_inv = std::max(max_inv, std::abs(inv[c * n + r]));
    }
    norm_inv = std::max(norm_inv, row);
  }
  const double cond = norm_m * norm_inv;
  if (!(cond < 1e10)) return exact_solve(n, m, lambda);
  // Forward error bound of the computed inverse (generous constant): entries above it have a
  // certain sign; a row whose leading entries fall below it is decided exactly.
  const double err = 16.0 * n * std::numeric_limits<double>::epsilon() * cond * max_inv;
  bool transverse = true;
  for (int r = 0; r < n && transverse; ++r) {
    int c = 0;
    while (c < n && std::abs(inv[c * n + r]) <= err) ++c;
    if (c > 0) return exact_solve(n, m, lambda);  // a leading entry may be an exact zero
    transverse = inv[r] > 0;
  }
  if (!transverse) return false;
  for (int r = 0; r < n; ++r) lambda[r] = inv[r];
  return true;
}

}  // namespace coxmesh
