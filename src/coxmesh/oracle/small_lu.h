// Dense LU with partial pivoting for the oracle's small systems (n ≤ 32): fixed-size storage, no
// allocation, column-major like the matrices the oracle builds. Hand-written because it is the
// innermost loop of tracing and Eigen's dynamic-size LU allocates and dispatches per call.
#pragma once

#include <array>
#include <cmath>
#include <utility>

namespace coxmesh {

class SmallLu {
 public:
  static constexpr int kMaxN = 32;

  /// Factors the n × n column-major matrix m as P·M = L·U. False when a pivot is exactly zero
  /// (M singular in floating point; the caller decides exactly).
  bool factor(int n, const double* m) {
    n_ = n;
    for (int i = 0; i < n * n; ++i) lu_[i] = m[i];
    for (int r = 0; r < n; ++r) perm_[r] = r;
    for (int c = 0; c < n; ++c) {
      int p = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(at(r, c)) > std::abs(at(p, c))) p = r;
      if (at(p, c) == 0) return false;
      if (p != c) {
        for (int j = 0; j < n; ++j) std::swap(at(p, j), at(c, j));
        std::swap(perm_[p], perm_[c]);
      }
      for (int r = c + 1; r < n; ++r) {
        const double f = at(r, c) /= at(c, c);
        for (int j = c + 1; j < n; ++j) at(r, j) -= f * at(c, j);
      }
    }
    return true;
  }

  int size() const { return n_; }

  /// x = M⁻¹·b (b and x may not alias).
  void solve(const double* b, double* x) const {
    for (int r = 0; r < n_; ++r) {
      double s = b[perm_[r]];
      for (int j = 0; j < r; ++j) s -= at(r, j) * x[j];
      x[r] = s;
    }
    back_substitute(x);
  }

  /// x = M⁻¹·e_c, the column c of the inverse.
  void solve_unit(int c, double* x) const {
    for (int r = 0; r < n_; ++r) {
      double s = perm_[r] == c ? 1.0 : 0.0;
      for (int j = 0; j < r; ++j) s -= at(r, j) * x[j];
      x[r] = s;
    }
    back_substitute(x);
  }

  /// x = row r of M⁻¹ (Mᵀx = e_r: with P·M = L·U, Uᵀ then Lᵀ, then the permutation).
  void solve_transposed_unit(int r, double* x) const {
    std::array<double, kMaxN> y;
    for (int i = 0; i < n_; ++i) {
      double s = i == r ? 1.0 : 0.0;
      for (int j = 0; j < i; ++j) s -= at(j, i) * y[j];
      y[i] = s / at(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      double s = y[i];
      for (int j = i + 1; j < n_; ++j) s -= at(j, i) * y[j];
      y[i] = s;
    }
    for (int i = 0; i < n_; ++i) x[perm_[i]] = y[i];
  }

  /// A computed solution x̂ of M·x = b satisfies ‖x − x̂‖_∞ ≤ 8n·u·K·‖x̂‖_∞ (u = unit roundoff), with
  /// K = this factor = ‖|L|‖·‖|U|‖·‖⟨L⟩⁻¹‖·‖⟨U⟩⁻¹‖ (∞-norms): the backward error γ_3n·|L||U| of
  /// the solve (Higham, Thm 9.4) times a bound of ‖M⁻¹‖, where |T⁻¹| ≤ ⟨T⟩⁻¹ entrywise for the
  /// comparison matrix ⟨T⟩ of a triangular T and ‖⟨T⟩⁻¹‖_∞ = max ⟨T⟩⁻¹·(1, …, 1). O(n²).
  double error_factor() const {
    std::array<double, kMaxN> x;
    double norm_l = 0, norm_u = 0, inv_l = 0, inv_u = 0;
    for (int r = 0; r < n_; ++r) {  // L has a unit diagonal
      double s = 1, row = 1;
      for (int j = 0; j < r; ++j) s += std::abs(at(r, j)) * x[j], row += std::abs(at(r, j));
      x[r] = s;
      inv_l = std::max(inv_l, s);
      norm_l = std::max(norm_l, row);
    }
    for (int r = n_ - 1; r >= 0; --r) {
      double s = 1, row = std::abs(at(r, r));
      for (int j = r + 1; j < n_; ++j) s += std::abs(at(r, j)) * x[j], row += std::abs(at(r, j));
      x[r] = s / std::abs(at(r, r));
      inv_u = std::max(inv_u, x[r]);
      norm_u = std::max(norm_u, row);
    }
    return norm_l * norm_u * inv_l * inv_u;
  }

 private:
  double& at(int r, int c) { return lu_[c * n_ + r]; }
  double at(int r, int c) const { return lu_[c * n_ + r]; }
  void back_substitute(double* x) const {
    for (int r = n_ - 1; r >= 0; --r) {
      double s = x[r];
      for (int j = r + 1; j < n_; ++j) s -= at(r, j) * x[j];
      x[r] = s / at(r, r);
    }
  }

  int n_ = 0;
  std::array<double, kMaxN * kMaxN> lu_;
  std::array<int, kMaxN> perm_;
};

}  // namespace coxmesh
