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
#include <vector>

#include "coxmesh/oracle/double_word.h"
#include "coxmesh/oracle/small_lu.h"

namespace coxmesh {

namespace {

constexpr int kMaxN = 32;

// Fraction-free Gauss–Jordan (Bareiss) on the augmented matrix a = [M | I] (n rows of 2n,
// row-major, integers): it ends with [D·I | D·M⁻¹], every division exact and no gcd ever taken.
// True iff M is non-singular and every row of M⁻¹ is lexicographically positive; then `lambda` =
// the first column of M⁻¹. Every intermediate entry is a minor of [M | I] (up to sign), so
// Hadamard's bound of its rows bounds them all.
template <class Z, class Ratio>
bool bareiss_lexicographic(int n, Z* a, double* lambda, Ratio ratio) {
  const int w = 2 * n;
  const auto at = [&](int r, int c) -> Z& { return a[r * w + c]; };
  Z prev = 1;
  for (int k = 0; k < n; ++k) {
    int p = k;
    while (p < n && at(p, k) == 0) ++p;
    if (p == n) return false;  // singular
    if (p != k)
      for (int j = 0; j < w; ++j) std::swap(at(p, j), at(k, j));
    for (int i = 0; i < n; ++i) {
      if (i == k) continue;
      for (int j = 0; j < w; ++j)
        if (j != k) at(i, j) = (at(k, k) * at(i, j) - at(i, k) * at(k, j)) / prev;
      at(i, k) = 0;
    }
    prev = at(k, k);
  }
  // Now a[r][r] = D for every r and a[r][n + c] = D·(M⁻¹)_rc.
  for (int r = 0; r < n; ++r) {
    int c = n;
    while (at(r, c) == 0) ++c;  // rows of an inverse are never zero
    if ((at(r, c) < 0) != (at(r, r) < 0)) return false;
  }
  for (int r = 0; r < n; ++r) lambda[r] = ratio(at(r, n), at(r, r));
  return true;
}

// Exact fallback. Each row of M is scaled by a power of two so that its entries are integers
// (a positive row scaling multiplies the columns of M⁻¹ by positive numbers, so signs and the
// first column are unchanged; row 0 is all ones). Small integers (values of F that are small
// integers or halves, as on the Freudenthal–Kuhn lattice) take 128-bit machine integers, when
// Hadamard's bound keeps every minor below 2⁶² and so every product below 2¹²⁴; the others
// arbitrary precision.
bool exact_solve(int n, const double* m, double* lambda) {
  std::array<long long, kMaxN * kMaxN> mant;  // entry (r, c) = mant · 2^shift, row-major
  std::array<int, kMaxN * kMaxN> shift;
  double bits = 0;  // log2 of Hadamard's bound of [M | I], rounded up
  for (int r = 0; r < n; ++r) {
    // Entry = odd integer × 2^e; scale the row by 2^{-min e}.
    int low = std::numeric_limits<int>::max(), top = 1;
    for (int c = 0; c < n; ++c) {
      const double v = m[c * n + r];
      mant[r * n + c] = 0;
      shift[r * n + c] = 0;
      if (v == 0) continue;
      int e;
      long long q = static_cast<long long>(std::ldexp(std::frexp(v, &e), 53));
      e -= 53;
      while ((q & 1) == 0) q /= 2, ++e;
      mant[r * n + c] = q;
      shift[r * n + c] = e;
      low = std::min(low, e);
    }
    for (int c = 0; c < n; ++c)
      if (mant[r * n + c] != 0) {
        shift[r * n + c] -= low;
        int length = 0;
        for (unsigned long long q = mant[r * n + c] < 0 ? -mant[r * n + c] : mant[r * n + c]; q; q >>= 1) ++length;
        top = std::max(top, length + shift[r * n + c]);  // |entry| < 2^top
      }
    bits += top + 0.5 * std::log2(n + 1.0);  // the row's norm < √(n + 1)·2^top (with its 1 of I)
  }
  if (bits <= 62) {
    __extension__ using Small = __int128;
    std::array<Small, kMaxN * 2 * kMaxN> a;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < 2 * n; ++c)
        a[r * 2 * n + c] =
            c < n ? static_cast<Small>(mant[r * n + c]) * (Small{1} << shift[r * n + c]) : Small{c - n == r ? 1 : 0};
    return bareiss_lexicographic(n, a.data(), lambda,
                                 [](Small p, Small q) { return static_cast<double>(p) / static_cast<double>(q); });
  }
  using Z = boost::multiprecision::cpp_int;
  thread_local std::vector<Z> a;  // kept: its entries keep their buffers from call to call
  if (a.size() < static_cast<std::size_t>(2 * n * n)) a.resize(2 * n * n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 2 * n; ++c) {
      Z& z = a[r * 2 * n + c];
      if (c >= n) {
        z = c - n == r ? 1 : 0;
        continue;
      }
      const long long q = mant[r * n + c];
      z = q < 0 ? -q : q;
      z <<= shift[r * n + c];
      if (q < 0) z = -z;
    }
  return bareiss_lexicographic(n, a.data(), lambda, [](Z p, Z q) {
    // λ_r = p/q ≥ 0 (p is 0 or of q's sign) needs no exact rounding: magnitudes shifted into the
    // range of doubles, no gcd taken.
    p = abs(p), q = abs(q);
    const int top = static_cast<int>(msb(q));
    if (top > 900) p >>= top - 900, q >>= top - 900;
    return static_cast<double>(p) / static_cast<double>(q);
  });
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

// The second filter, for what double precision leaves undecided: x = A⁻¹e₀ (the leading entries of
// the rows of A⁻¹) in double-word arithmetic. On degenerate input the undecided entries are mostly
// not zero but tiny, a few units of rounding of the largest (values of F that are rounding noise
// where the exact value is 0); 106 bits certify their signs. 1: every x_r certainly > 0 (then
// `first_column` = x), 0: some x_r certainly < 0, −1: undecided (a leading entry may be an exact
// zero, and only exact arithmetic can tell). The rows of A should be scaled to comparable sizes
// (the bound is not invariant under row scaling).
int double_word_first_column(int n, const double* a, double* first_column) {
  std::array<DoubleWord, kMaxN * kMaxN> lu;  // column-major
  std::array<int, kMaxN> perm;
  double smallest = 1;
  for (int i = 0; i < n * n; ++i) {
    lu[i] = {a[i], 0};
    if (a[i] != 0) smallest = std::min(smallest, std::abs(a[i]));
  }
  for (int r = 0; r < n; ++r) perm[r] = r;
  // Products of a few entries below 2⁻⁴⁰⁰ would reach the range where low words underflow and the
  // error bounds stop holding: exact arithmetic for those.
  if (smallest < 0x1p-400) return -1;
  const auto at = [&](int r, int c) -> DoubleWord& { return lu[c * n + r]; };
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(at(r, c).hi) > std::abs(at(p, c).hi)) p = r;
    if (at(p, c).hi == 0) return -1;
    if (p != c) {
      for (int j = 0; j < n; ++j) std::swap(at(p, j), at(c, j));
      std::swap(perm[p], perm[c]);
    }
    for (int r = c + 1; r < n; ++r) {
      const DoubleWord f = at(r, c) = at(r, c) / at(c, c);
      for (int j = c + 1; j < n; ++j) at(r, j) = at(r, j) - f * at(c, j);
    }
  }
  std::array<DoubleWord, kMaxN> x;
  for (int r = 0; r < n; ++r) {
    DoubleWord s{perm[r] == 0 ? 1.0 : 0.0, 0};
    for (int j = 0; j < r; ++j) s = s - at(r, j) * x[j];
    x[r] = s;
  }
  for (int r = n - 1; r >= 0; --r) {
    DoubleWord s = x[r];
    for (int j = r + 1; j < n; ++j) s = s - at(r, j) * x[j];
    x[r] = s / at(r, r);
  }
  // The bound of SmallLu::error_factor with the double-word unit: ‖x − x̂‖ ≤ 8n·u·K·‖x̂‖, K from the
  // high words (twice, for that and for K's own rounding), and an absolute term for underflow.
  double k_factor;
  {
    std::array<double, kMaxN> y;
    double norm_l = 0, norm_u = 0, inv_l = 0, inv_u = 0;
    for (int r = 0; r < n; ++r) {
      double s = 1, row = 1;
      for (int j = 0; j < r; ++j) s += std::abs(at(r, j).hi) * y[j], row += std::abs(at(r, j).hi);
      y[r] = s;
      inv_l = std::max(inv_l, s);
      norm_l = std::max(norm_l, row);
    }
    for (int r = n - 1; r >= 0; --r) {
      double s = 1, row = std::abs(at(r, r).hi);
      for (int j = r + 1; j < n; ++j) s += std::abs(at(r, j).hi) * y[j], row += std::abs(at(r, j).hi);
      y[r] = s / std::abs(at(r, r).hi);
      inv_u = std::max(inv_u, y[r]);
      norm_u = std::max(norm_u, row);
    }
    k_factor = 2 * norm_l * norm_u * inv_l * inv_u;
  }
  double size = 0;
  for (int r = 0; r < n; ++r) size = std::max(size, std::abs(x[r].hi));
  const double err = 8.0 * n * kDoubleWordUnit * k_factor * size + n * k_factor * 0x1p-900;
  bool positive = true;
  for (int r = 0; r < n; ++r) {
    if (x[r].hi < -err) return 0;
    positive &= x[r].hi > err;
  }
  if (!positive) return -1;
  for (int r = 0; r < n; ++r) first_column[r] = x[r].hi;
  return 1;
}

// λ = A⁻¹e₀ alone, with the O(n²) error bound of SmallLu::error_factor: 1 every λ_r certainly > 0,
// 0 some λ_r certainly < 0 (the lexicographic rule only looks further along a row whose leading
// entry is 0), −1 undecided.
int quick_first_column(int n, const SmallLu& lu, double* lambda) {
  constexpr double u = std::numeric_limits<double>::epsilon() / 2;
  const double factor = lu.error_factor();
  if (!(n * u * factor < 1e-6)) return -1;
  lu.solve_unit(0, lambda);
  double size = 0;
  for (int r = 0; r < n; ++r) size = std::max(size, std::abs(lambda[r]));
  const double err = 8.0 * n * u * factor * size;
  bool positive = true;
  for (int r = 0; r < n; ++r) {
    if (lambda[r] < -err) return 0;
    positive &= lambda[r] > err;
  }
  return positive ? 1 : -1;
}

// Is every row of A⁻¹ lexicographically positive? The filters from the cheapest on; exact
// arithmetic only for what none of them certifies. On true, `first_column` = A⁻¹e₀.
// `*factored`: true when that came from the factors of M as given, left in `lu`.
bool lexicographically_positive_inverse(int n, const double* original, double* first_column, SmallLu& lu,
                                        bool* factored) {
  if (lu.factor(n, original)) {  // most calls: λ alone, on M as given
    if (const int signs = quick_first_column(n, lu, first_column); signs >= 0) {
      if (factored) *factored = true;
      return signs == 1;
    }
  }
  // Rows scaled by powers of two to a largest entry in [1/2, 1): exact, and a positive row scaling
  // scales the columns of A⁻¹, so no sign changes; but the error bounds, which are not invariant
  // under it, get much tighter when the equations differ in scale. Row 0's factor is undone.
  // (A row is left as it is where scaling it down would round an entry into the subnormals.)
  std::array<double, kMaxN * kMaxN> scaled;
  double scale0 = 1;
  for (int r = 0; r < n; ++r) {
    double big = 0, small = std::numeric_limits<double>::infinity();
    for (int c = 0; c < n; ++c)
      if (const double v = std::abs(original[c * n + r]); v != 0) big = std::max(big, v), small = std::min(small, v);
    int e = 0;
    if (big > 0) std::frexp(big, &e);
    if (e > 0 && small < std::ldexp(std::numeric_limits<double>::min(), e)) e = 0;
    const double factor = std::ldexp(1.0, -e);  // a power of two: the products are exact
    if (r == 0) scale0 = factor;
    for (int c = 0; c < n; ++c) scaled[c * n + r] = original[c * n + r] * factor;
  }
  const double* a = scaled.data();
  int signs = -1;
  if (lu.factor(n, a)) {
    signs = quick_first_column(n, lu, first_column);
    if (signs < 0) signs = certified_row_signs(n, a, lu, first_column);  // the whole inverse
  }
  if (signs < 0) signs = double_word_first_column(n, a, first_column);
  if (signs < 0) return exact_solve(n, original, first_column);
  for (int r = 0; r < n; ++r) first_column[r] *= scale0;
  return signs == 1;
}

// A vertex exactly on M (F(v_j) = 0: column j of M is e_0), the degenerate case that lattice
// vertices on M make common. With column j moved first, M = [[1, 1ᵀ], [0, G]] for the k × k matrix G
// of F at the other vertices, so M⁻¹ = [[1, −1ᵀG⁻¹], [0, G⁻¹]]: λ = e_j, row j of M⁻¹ is positive, and
// the other rows are (0, rows of G⁻¹). τ is transverse iff every row of G⁻¹ is lexicographically
// positive: a k × k question, decided by the same filters and, only if they cannot, exactly.
bool vertex_on_manifold(int n, const double* m, int j, double* lambda) {
  const int k = n - 1;
  std::array<double, kMaxN * kMaxN> g;  // column-major, k × k
  for (int c = 0, gc = 0; c < n; ++c) {
    if (c == j) continue;
    for (int r = 1; r < n; ++r) g[gc * k + (r - 1)] = m[c * n + r];
    ++gc;
  }
  std::array<double, kMaxN> unused;
  SmallLu lu;
  if (!lexicographically_positive_inverse(k, g.data(), unused.data(), lu, nullptr)) return false;
  for (int r = 0; r < n; ++r) lambda[r] = r == j ? 1.0 : 0.0;
  return true;
}

constexpr int kRejected = -2, kNoVertexOnManifold = -1;

// The exact tests of lexicographic_solve before any solve, for n = N (N = 0: n at run time; loops
// of constant length unroll): kRejected, or the column of the one vertex exactly on M, or
// kNoVertexOnManifold.
template <int N>
int screen(int n_runtime, const double* m) {
  const int n = N ? N : n_runtime;
  // Exact quick rejection: if some F_i is > 0 at every vertex (or < 0 at every vertex), then
  // Σ λ_j F_i(v_j) = ε^i has no solution with λ ≥ 0, Σ λ = 1 for small ε > 0.
  for (int i = 1; i < n; ++i) {
    bool all_pos = true, all_neg = true;
    for (int j = 0; j < n; ++j) {
      all_pos &= m[j * n + i] > 0;
      all_neg &= m[j * n + i] < 0;
    }
    if (all_pos || all_neg) return kRejected;
  }
  // Vertices exactly on M: two make M singular (two columns e_0); one is decided on the smaller system.
  int on_manifold = kNoVertexOnManifold;
  for (int c = 0; c < n; ++c) {
    bool zero = true;
    for (int r = 1; r < n; ++r) zero &= m[c * n + r] == 0;
    if (!zero) continue;
    if (on_manifold >= 0) return kRejected;
    on_manifold = c;
  }
  return on_manifold;
}

}  // namespace

bool lexicographic_solve(int n, const double* m, double* lambda, SmallLu* lu, bool* factored) {
  if (factored) *factored = false;
  if (n == 2) {
    // M = [[1, 1], [f0, f1]]: exact in floating point. Transverse iff one value is > 0 and the
    // other ≤ 0 (zero counts as negative); the sign of f1 − f0 is exact.
    const double f0 = m[1], f1 = m[3];
    if ((f0 > 0) == (f1 > 0)) return false;
    lambda[0] = f1 / (f1 - f0);
    lambda[1] = -f0 / (f1 - f0);
    return true;
  }
  const int on_manifold = with_small_size(n, [&]<int N>() { return screen<N>(n, m); });
  if (on_manifold == kRejected) return false;
  if (on_manifold >= 0) return vertex_on_manifold(n, m, on_manifold, lambda);
  if (lu) return lexicographically_positive_inverse(n, m, lambda, *lu, factored);
  SmallLu own;
  return lexicographically_positive_inverse(n, m, lambda, own, nullptr);
}

}  // namespace coxmesh
