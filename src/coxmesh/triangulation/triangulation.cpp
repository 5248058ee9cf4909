// Thesis §3.1 (FK and Ã_d), §3.3 (vertex coordinates), §3.4 (point location: the algorithm in
// locate_plain.cpp, the kernel used on x86 in locate_kernel.cpp).
#include "coxmesh/triangulation/triangulation.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "coxmesh/triangulation/locate_kernel.h"
#include "coxmesh/util/fixed_dimension.h"

namespace coxmesh {

namespace {
std::string fmt(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}
}  // namespace

Triangulation::Triangulation(const Eigen::MatrixXd& matrix, const Eigen::VectorXd& offset) {
  if (matrix.rows() != matrix.cols())
    throw InputError("the matrix must be square, got " + std::to_string(matrix.rows()) + "x" +
                     std::to_string(matrix.cols()));
  d_ = static_cast<int>(matrix.rows());
  check_dimension(d_);
  if (offset.size() != d_)
    throw InputError("the offset has " + std::to_string(offset.size()) + " coordinates, expected " +
                     std::to_string(d_));
  if (!matrix.allFinite()) throw InputError("the matrix has a NaN or infinite entry");
  if (!offset.allFinite()) throw InputError("the offset has a NaN or infinite coordinate");
  matrix_ = matrix;
  offset_ = offset;
  identity_ = matrix_.isIdentity(0.0);
  factorize();
}

void Triangulation::factorize() {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(matrix_);
  const auto& sv = svd.singularValues();
  const double rcond = sv(0) > 0 ? sv(d_ - 1) / sv(0) : 0.0;
  if (!(rcond > 1e-12))
    throw InputError("the matrix is singular or too ill-conditioned (reciprocal condition number " + fmt(rcond) + ")");
  inverse_ = matrix_.fullPivLu().inverse();
  padded_inverse_ = Eigen::MatrixXd::Zero(locate::padded_rows(d_), d_);
  padded_inverse_.topRows(d_) = inverse_;
}

Triangulation Triangulation::freudenthal(int d) {
  check_dimension(d);
  Triangulation t(Eigen::MatrixXd::Identity(d, d), Eigen::VectorXd::Zero(d));
  t.known_longest_edge_ = std::sqrt(static_cast<double>(d));
  return t;
}

Triangulation Triangulation::coxeter(int d) {
  check_dimension(d);
  const double n = d + 1;
  Eigen::MatrixXd qt(d, d);  // Qᵀ scaled row-wise by μ_q^{-1/2}
  for (int q = 1; q <= d; ++q) {
    const double mu = 1.0 - std::cos(q * std::numbers::pi / n);
    for (int j = 1; j <= d; ++j)
      qt(q - 1, j - 1) = std::sqrt(2.0 / n) * std::sin(j * q * std::numbers::pi / n) / std::sqrt(mu);
  }
  // Right-multiply by L^{-1} (1 on the diagonal, −1 just below): column j becomes col_j − col_{j+1}.
  Eigen::MatrixXd lambda(d, d);
  for (int j = 0; j < d; ++j) {
    lambda.col(j) = qt.col(j);
    if (j + 1 < d) lambda.col(j) -= qt.col(j + 1);
  }
  Triangulation t(lambda, Eigen::VectorXd::Zero(d));
  t.known_longest_edge_ = std::sqrt(2.0 * std::floor(n / 2) * std::ceil(n / 2) / n);
  return t;
}

Triangulation Triangulation::scaled(double s) const {
  if (!std::isfinite(s) || s <= 0) throw InputError("the scale must be finite and positive, got " + fmt(s));
  Triangulation t(s * matrix_, offset_);
  t.known_longest_edge_ = s * known_longest_edge_;
  return t;
}

Triangulation Triangulation::with_longest_edge(double h) const {
  if (!std::isfinite(h) || h <= 0) throw InputError("the edge length must be finite and positive, got " + fmt(h));
  return scaled(h / longest_edge());
}

Triangulation Triangulation::with_offset(const Eigen::VectorXd& offset) const {
  Triangulation t(matrix_, offset);
  t.known_longest_edge_ = known_longest_edge_;
  return t;
}

Triangulation Triangulation::rotated(std::uint64_t seed) const {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd g(d_, d_);
  for (int j = 0; j < d_; ++j)
    for (int i = 0; i < d_; ++i) g(i, j) = normal(rng);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(g);
  Eigen::MatrixXd q = qr.householderQ();
  // Fix the signs so that O is Haar-distributed (R with a positive diagonal).
  const Eigen::MatrixXd& r = qr.matrixQR();
  for (int j = 0; j < d_; ++j)
    if (r(j, j) < 0) q.col(j) = -q.col(j);
  Triangulation t(q * matrix_, q * offset_);
  t.known_longest_edge_ = known_longest_edge_;
  return t;
}

void Triangulation::lattice_coordinates(const double* x, double* y) const {
#if defined(COXMESH_USE_LOCATE_KERNEL)
  if (!identity_) {
    alignas(16) std::array<double, kMaxDimension + 1> z;  // (with the kernel's padding)
    locate::lattice_coordinates_kernel(padded_inverse_.data(), offset_.data(), d_, x, z.data());
    std::copy_n(z.data(), d_, y);
    return;
  }
#endif
  locate::lattice_coordinates_plain(*this, x, y);
}

void Triangulation::cartesian(const std::int32_t* v, double* x) const {
  for (int i = 0; i < d_; ++i) x[i] = offset_[i];
  const double* m = matrix_.data();
  for (int j = 0; j < d_; ++j) {
    const double t = v[j];
    const double* col = m + static_cast<std::ptrdiff_t>(j) * d_;
    for (int i = 0; i < d_; ++i) x[i] += col[i] * t;
  }
}

namespace {

// Triangulation::vertex_coordinates for d = D (D = 0: d at run time). Loops of constant length for
// the common d: the ends of loops of varying length cost more than their few additions (SO(3) ⊂ R⁹,
// once per oracle hit). The same operations in the same order: the same bits.
template <int D>
void vertex_coordinates_n(int d_runtime, const double* m, const double* offset, const Simplex& sigma, double* out) {
  const int d = D ? D : d_runtime;
  for (int i = 0; i < d; ++i) out[i] = offset[i];  // Λ·y + b, as cartesian()
  for (int j = 0; j < d; ++j) {
    const double t = sigma.y[j];
    const double* col = m + static_cast<std::ptrdiff_t>(j) * d;
    for (int i = 0; i < d; ++i) out[i] += col[i] * t;
  }
  // v_j = v_{j-1} + the columns e of block j − 1, added in increasing e. The columns are sorted by
  // block first (stably: the same sums, the same bits); testing each column against each block
  // was a branch per pair, mispredicted as often as not.
  std::array<int, kMaxDimension + 2> end{};  // end[b]: one past block b's columns in `order`
  std::array<int, kMaxDimension> order;
  for (int e = 0; e < d; ++e) ++end[sigma.block[e] + 1];
  for (int b = 1; b <= sigma.k + 1; ++b) end[b] += end[b - 1];
  for (int e = 0; e < d; ++e) order[end[sigma.block[e]]++] = e;
  for (int j = 1; j <= sigma.k; ++j) {
    double* p = out + static_cast<std::ptrdiff_t>(j) * d;
    const double* prev = p - d;
    for (int i = 0; i < d; ++i) p[i] = prev[i];
    for (int at = j == 1 ? 0 : end[j - 2]; at < end[j - 1]; ++at) {
      const double* col = m + static_cast<std::ptrdiff_t>(order[at]) * d;
      for (int i = 0; i < d; ++i) p[i] += col[i];
    }
  }
}

}  // namespace

void Triangulation::vertex_coordinates(const Simplex& sigma, double* out) const {
  const double *m = matrix_.data(), *b = offset_.data();
  with_fixed_dimension<3, 4, 6, 9>(
      d_, [&](auto fixed_d) { vertex_coordinates_n<decltype(fixed_d)::value>(d_, m, b, sigma, out); });
}

Simplex Triangulation::locate(std::span<const double> x) const {
  if (static_cast<int>(x.size()) != d_)
    throw InputError("the point has " + std::to_string(x.size()) + " coordinates, expected " + std::to_string(d_));
  for (double v : x)
    if (!std::isfinite(v)) throw InputError("the point has a NaN or infinite coordinate");
  return locate(x.data());
}

// Thesis §3.4 (locate_kernel.h): the kernel on x86, the plain statement of the algorithm elsewhere.
Simplex Triangulation::locate(const double* x) const {
#if defined(COXMESH_USE_LOCATE_KERNEL)
  return locate::locate_kernel(*this, padded_inverse_.data(), x);
#else
  return locate::locate_plain(*this, x);
#endif
}

[[noreturn]] void locate::throw_out_of_range(const double* z, int d) {
  for (int i = 0; i < d; ++i)
    if (!(std::abs(z[i]) < kMaxLatticeCoordinate - 1) && std::isfinite(z[i]))
      throw InputError("the point is too far from the origin: lattice coordinate " + fmt(z[i]) + " exceeds 2^30");
  throw InputError("the point has a NaN or infinite coordinate");
}

void Triangulation::barycentric(const Simplex& sigma, const double* x, double* lambda) const {
  std::array<double, kMaxDimension + 1> z;
  lattice_coordinates(x, z.data());
  locate::barycentric_in_lattice(sigma, d_, z.data(), lambda);
}

double Triangulation::longest_edge() const {
  if (known_longest_edge_ > 0) return known_longest_edge_;
  if (d_ > 24) throw InputError("the longest edge of a general matrix is computed exhaustively, which needs d <= 24");
  // Edge vectors of the d-simplices are Λ·e_A for the non-empty A ⊆ {0..d−1}; walk them in Gray order.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(d_);
  std::vector<bool> in(d_, false);
  double best = 0;
  const std::uint64_t n = std::uint64_t{1} << d_;
  for (std::uint64_t t = 1; t < n; ++t) {
    const int bit = __builtin_ctzll(t);
    if (in[bit])
      v -= matrix_.col(bit);
    else
      v += matrix_.col(bit);
    in[bit] = !in[bit];
    best = std::max(best, v.squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace coxmesh
