// Thesis §4.3: lexicographic transversality. Exactness matters: a wrong sign on a degenerate simplex
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
    q /= a[r][r];                                    // rejects a zero numerator over a negative)
    lambda[r] = static_cast<double>(q);
  }
  return true;
}

// The rows of A⁻¹ (A n × n, column-major, factored in `lu`), each judged lexicographically
// positive or not in floating point: 1 all positive, 0 one is not, −1 undecided (A ill-conditioned,
// or a row whose leading entries are too small to have a certain sign: the caller decides exactly).
// `first_column` receives A⁻¹'s first column.
int certified_row_signs(int n, const double* a, const SmallLu& lu, double* first_column) {
  double norm_a = 0;
  for (int r = 0; r < n; ++r) {
    double row = 0;
    for (int c = 0; c < n; ++c) row += std::abs(a[c * n + r]);
    norm_a = std::max(norm_a, row);
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
  const double cond = norm_a * norm_inv;
  if (!(cond < 1e10)) return -1;
  // Forward error bound of the computed inverse (generous constant): entries above it have a
  // certain sign; a row whose leading entries fall below it is undecided.
  const double err = 16.0 * n * std::numeric_limits<double>::epsilon() * cond * max_inv;
  for (int r = 0; r < n; ++r)
    if (std::abs(inv[r]) <= err) return -1;  // a leading entry may be an exact zero
  for (int r = 0; r < n; ++r) first_column[r] = inv[r];
  for (int r = 0; r < n; ++r)
    if (inv[r] < 0) return 0;
  return 1;
}

// A vertex exactly on M (F(v_j) = 0: column j of M is e_0), the degenerate case that lattice
// vertices on M make common. With column j moved first, M = [[1, 1ᵀ], [0, G]] for the k × k matrix G
// of F at the other vertices, so M⁻¹ = [[1, −1ᵀG⁻¹], [0, G⁻¹]]: λ = e_j, row j of M⁻¹ is positive, and
// the other rows are (0, rows of G⁻¹). τ is transverse iff every row of G⁻¹ is lexicographically
// positive: a k × k question, usually decided in floating point. −1: undecided.
int vertex_on_manifold(int n, const double* m, int j, double* lambda) {
  const int k = n - 1;
  std::array<double, kMaxN * kMaxN> g;  // column-major, k × k
  for (int c = 0, gc = 0; c < n; ++c) {
    if (c == j) continue;
    for (int r = 1; r < n; ++r) g[gc * k + (r - 1)] = m[c * n + r];
    ++gc;
  }
  SmallLu lu;
  if (!lu.factor(k, g.data())) return -1;
  std::array<double, kMaxN> unused;
  const int signs = certified_row_signs(k, g.data(), lu, unused.data());
  if (signs != 1) return signs;
  for (int r = 0; r < n; ++r) lambda[r] = r == j ? 1.0 : 0.0;
  return 1;
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
  // Vertices exactly on M: two make M singular (two columns e_0); one is decided on the smaller system.
  int on_manifold = -1;
  for (int c = 0; c < n; ++c) {
    bool zero = true;
    for (int r = 1; r < n && zero; ++r) zero = m[c * n + r] == 0;
    if (!zero) continue;
    if (on_manifold >= 0) return false;
    on_manifold = c;
  }
  if (on_manifold >= 0) {
    const int decided = vertex_on_manifold(n, m, on_manifold, lambda);
    return decided >= 0 ? decided == 1 : exact_solve(n, m, lambda);
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
  // Undecided: the whole inverse, and the lexicographic signs of its rows.
  const int signs = certified_row_signs(n, m, lu, lambda);
  return signs >= 0 ? signs == 1 : exact_solve(n, m, lambda);
}

}  // namespace coxmesh
