// Dense LU with partial pivoting for the oracle's small systems (n ≤ 32): fixed-size storage, no
// allocation, column-major like the matrices the oracle builds. Hand-written because it is the
// innermost loop of tracing and Eigen's dynamic-size LU allocates and dispatches per call. The sizes
// n = 3 to 9 (codimensions 2 to 8) get loops of constant length, unrolled (`unroll 9`): without
// loops of varying length whose ends the processor mispredicts, consecutive solves overlap (a
// solve of n = 7 took 130 ns, 32–36 ns unrolled, in a loop of solves). The same operations in the
// same order: the results are the same bits.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

// GCC unrolls the loops of constant length; clang (the fuzz build) takes the same pragma as a
// request and fails the build where its optimizer cannot honour it, so it gets none.
#if defined(__clang__)
#define COXMESH_UNROLL_9
#else
#define COXMESH_UNROLL_9 _Pragma("GCC unroll 9")
#endif

namespace coxmesh {

// body.template operator()<N>() with N = n for the sizes unrolled, N = 0 (n known at run time) otherwise.
template <class Body>
decltype(auto) with_small_size(int n, Body&& body) {
  switch (n) {
    case 3:
      return body.template operator()<3>();
    case 4:
      return body.template operator()<4>();
    case 5:
      return body.template operator()<5>();
    case 6:
      return body.template operator()<6>();
    case 7:
      return body.template operator()<7>();
    case 8:
      return body.template operator()<8>();
    case 9:
      return body.template operator()<9>();
    default:
      return body.template operator()<0>();
  }
}

class SmallLu {
 public:
  static constexpr int kMaxN = 32;

  /// Factors the n × n column-major matrix m as P·M = L·U. False when a pivot is exactly zero
  /// (M singular in floating point; the caller decides exactly).
  bool factor(int n, const double* m) {
    n_ = n;
    return with_small_size(n_, [&]<int N>() { return factor_n<N>(m); });
  }

  int size() const { return n_; }

  /// The factors in n·n doubles and the n row indices of P, and back: a factorization kept for later.
  /// (Copies of constant length for the unrolled sizes: no call to memcpy.)
  void save(double* factors, int* rows) const {
    with_small_size(n_, [&]<int N>() {
      std::copy_n(lu_.data(), N ? N * N : n_ * n_, factors);
      std::copy_n(perm_.data(), N ? N : n_, rows);
    });
  }
  void restore(int n, const double* factors, const int* rows) {
    n_ = n;
    with_small_size(n_, [&]<int N>() {
      std::copy_n(factors, N ? N * N : n_ * n_, lu_.data());
      std::copy_n(rows, N ? N : n_, perm_.data());
    });
  }

  /// x = M⁻¹·b (b and x may not alias).
  void solve(const double* b, double* x) const {
    with_small_size(n_, [&]<int N>() {
      forward_substitute<N>(b, x);
      back_substitute<N>(x);
    });
  }

  /// Keeps the reciprocals of U's diagonal for solve_guess (after factor or restore).
  void keep_reciprocals() {
    for (int r = 0; r < n_; ++r) reciprocal_[r] = 1.0 / at<0>(r, r);
  }
  /// As solve, with U's diagonal divided out by the reciprocals keep_reciprocals() kept: no division
  /// on the chain from row to row, and results a few ulps from solve's. Only for guesses that an
  /// exact rule checks (ImplicitOracle::pivot_exit).
  void solve_guess(const double* b, double* x) const {
    with_small_size(n_, [&]<int N>() {
      forward_substitute<N>(b, x);
      back_substitute<N, true>(x);
    });
  }

  /// x = M⁻¹·e_c, the column c of the inverse.
  void solve_unit(int c, double* x) const {
    with_small_size(n_, [&]<int N>() {
      const int n = N ? N : n_;
      COXMESH_UNROLL_9
      for (int r = 0; r < n; ++r) {
        double s = perm_[r] == c ? 1.0 : 0.0;
        COXMESH_UNROLL_9
        for (int j = 0; j < r; ++j) s -= at<N>(r, j) * x[j];
        x[r] = s;
      }
      back_substitute<N>(x);
    });
  }

  /// x = row r of M⁻¹ (Mᵀx = e_r: with P·M = L·U, Uᵀ then Lᵀ, then the permutation).
  void solve_transposed_unit(int r, double* x) const {
    std::array<double, kMaxN> y;
    for (int i = 0; i < n_; ++i) {
      double s = i == r ? 1.0 : 0.0;
      for (int j = 0; j < i; ++j) s -= at<0>(j, i) * y[j];
      y[i] = s / at<0>(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      double s = y[i];
      for (int j = i + 1; j < n_; ++j) s -= at<0>(j, i) * y[j];
      y[i] = s;
    }
    for (int i = 0; i < n_; ++i) x[perm_[i]] = y[i];
  }

  /// A computed solution x̂ of M·x = b satisfies ‖x − x̂‖_∞ ≤ 8n·u·K·‖x̂‖_∞ (u = unit roundoff), with
  /// K = this factor = ‖|L|‖·‖|U|‖·‖⟨L⟩⁻¹‖·‖⟨U⟩⁻¹‖ (∞-norms): the backward error γ_3n·|L||U| of
  /// the solve (Higham, Thm 9.4) times a bound of ‖M⁻¹‖, where |T⁻¹| ≤ ⟨T⟩⁻¹ entrywise for the
  /// comparison matrix ⟨T⟩ of a triangular T and ‖⟨T⟩⁻¹‖_∞ = max ⟨T⟩⁻¹·(1, …, 1). O(n²).
  double error_factor() const {
    return with_small_size(n_, [&]<int N>() {
      const int n = N ? N : n_;
      std::array<double, kMaxN> x;
      double norm_l = 0, norm_u = 0, inv_l = 0, inv_u = 0;
      COXMESH_UNROLL_9
      for (int r = 0; r < n; ++r) {  // L has a unit diagonal
        double s = 1, row = 1;
        COXMESH_UNROLL_9
        for (int j = 0; j < r; ++j) s += std::abs(at<N>(r, j)) * x[j], row += std::abs(at<N>(r, j));
        x[r] = s;
        inv_l = std::max(inv_l, s);
        norm_l = std::max(norm_l, row);
      }
      COXMESH_UNROLL_9
      for (int r = n - 1; r >= 0; --r) {
        double s = 1, row = std::abs(at<N>(r, r));
        COXMESH_UNROLL_9
        for (int j = r + 1; j < n; ++j) s += std::abs(at<N>(r, j)) * x[j], row += std::abs(at<N>(r, j));
        x[r] = s / std::abs(at<N>(r, r));
        inv_u = std::max(inv_u, x[r]);
        norm_u = std::max(norm_u, row);
      }
      return norm_l * norm_u * inv_l * inv_u;
    });
  }

 private:
  template <int N>
  double& at(int r, int c) {
    return lu_[c * (N ? N : n_) + r];
  }
  template <int N>
  double at(int r, int c) const {
    return lu_[c * (N ? N : n_) + r];
  }

  template <int N>
  bool factor_n(const double* m) {
    const int n = N ? N : n_;
    for (int i = 0; i < n * n; ++i) lu_[i] = m[i];
    for (int r = 0; r < n; ++r) perm_[r] = r;
    COXMESH_UNROLL_9
    for (int c = 0; c < n; ++c) {
      int p = c;
      COXMESH_UNROLL_9
      for (int r = c + 1; r < n; ++r)
        if (std::abs(at<N>(r, c)) > std::abs(at<N>(p, c))) p = r;
      if (at<N>(p, c) == 0) return false;
      if (p != c) {
        COXMESH_UNROLL_9
        for (int j = 0; j < n; ++j) std::swap(at<N>(p, j), at<N>(c, j));
        std::swap(perm_[p], perm_[c]);
      }
      COXMESH_UNROLL_9
      for (int r = c + 1; r < n; ++r) {
        const double f = at<N>(r, c) /= at<N>(c, c);
        COXMESH_UNROLL_9
        for (int j = c + 1; j < n; ++j) at<N>(r, j) -= f * at<N>(c, j);
      }
    }
    return true;
  }

  // x = L⁻¹·P·b.
  template <int N>
  void forward_substitute(const double* b, double* x) const {
    COXMESH_UNROLL_9
    for (int r = 0; r < (N ? N : n_); ++r) {
      double s = b[perm_[r]];
      COXMESH_UNROLL_9
      for (int j = 0; j < r; ++j) s -= at<N>(r, j) * x[j];
      x[r] = s;
    }
  }
  // x = U⁻¹·x, dividing by U's diagonal, or multiplying by its kept reciprocals.
  template <int N, bool kReciprocals = false>
  void back_substitute(double* x) const {
    COXMESH_UNROLL_9
    for (int r = (N ? N : n_) - 1; r >= 0; --r) {
      double s = x[r];
      COXMESH_UNROLL_9
      for (int j = r + 1; j < (N ? N : n_); ++j) s -= at<N>(r, j) * x[j];
      x[r] = kReciprocals ? s * reciprocal_[r] : s / at<N>(r, r);
    }
  }

  int n_ = 0;
  std::array<double, kMaxN * kMaxN> lu_;
  std::array<int, kMaxN> perm_;
  std::array<double, kMaxN> reciprocal_;  // (keep_reciprocals)
};

}  // namespace coxmesh

#undef COXMESH_UNROLL_9
