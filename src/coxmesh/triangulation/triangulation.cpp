// Thesis §3.1–3.3; spec §1.3 (vertex coordinates), §1.7 (point location), §1.8 (Ã_d).
#include "coxmesh/triangulation/triangulation.h"
#include "coxmesh/util/parse_number.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

namespace coxmesh {

namespace {
constexpr double kTieTolerance = 1e-9;  // as GUDHI: fractional parts within this share a block

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
  if (identity_) {
    for (int i = 0; i < d_; ++i) y[i] = x[i] - offset_[i];
    return;
  }
  std::array<double, kMaxDimension> t;
  for (int j = 0; j < d_; ++j) t[j] = x[j] - offset_[j];
  // y = Λ^{-1}·t, eight (then four) rows at a time with the accumulators in registers, so that
  // independent rows overlap. Every y_i is summed in column order j = 0, 1, … (the rounding of a
  // plain column-by-column accumulation).
  const double* inv = inverse_.data();  // column-major
  const std::ptrdiff_t ld = d_;
  int i = 0;
  using Vec8 = Eigen::Matrix<double, 8, 1>;  // fixed-size: Eigen keeps it in vector registers
  using Vec4 = Eigen::Matrix<double, 4, 1>;
  for (; i + 8 <= d_; i += 8) {
    Vec8 a = Vec8::Zero();
    const double* col = inv + i;
    for (int j = 0; j < d_; ++j, col += ld) a.noalias() += Eigen::Map<const Vec8>(col) * t[j];
    Eigen::Map<Vec8>(y + i) = a;
  }
  for (; i + 4 <= d_; i += 4) {
    Vec4 a = Vec4::Zero();
    const double* col = inv + i;
    for (int j = 0; j < d_; ++j, col += ld) a.noalias() += Eigen::Map<const Vec4>(col) * t[j];
    Eigen::Map<Vec4>(y + i) = a;
  }
  for (; i < d_; ++i) {
    double a = 0;
    const double* col = inv + i;
    for (int j = 0; j < d_; ++j, col += ld) a += col[0] * t[j];
    y[i] = a;
  }
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

void Triangulation::vertex_coordinates(const Simplex& sigma, double* out) const {
  cartesian(sigma.y.data(), out);
  const double* m = matrix_.data();
  for (int j = 1; j <= sigma.k; ++j) {
    double* p = out + static_cast<std::ptrdiff_t>(j) * d_;
    const double* prev = p - d_;
    for (int i = 0; i < d_; ++i) p[i] = prev[i];
    for (int e = 0; e < d_; ++e)
      if (sigma.block[e] == j - 1) {
        const double* col = m + static_cast<std::ptrdiff_t>(e) * d_;
        for (int i = 0; i < d_; ++i) p[i] += col[i];
      }
  }
}

Simplex Triangulation::locate(std::span<const double> x) const {
  if (static_cast<int>(x.size()) != d_)
    throw InputError("the point has " + std::to_string(x.size()) + " coordinates, expected " + std::to_string(d_));
  for (double v : x)
    if (!std::isfinite(v)) throw InputError("the point has a NaN or infinite coordinate");
  return locate(x.data());
}

namespace {

// Point location in FK coordinates (spec §1.7): y = ⌊v⌋, then the indices ordered by decreasing
// fractional part, cut into blocks at strict drops. D > 0 fixes the dimension at compile time (small
// d: fully unrolled), D = 0 takes it at run time. z holds the d lattice coordinates and has room
// for kMaxDimension + 1 entries; it is overwritten with the fractional parts.
template <int D>
void locate_fk(double* z, int d_runtime, Simplex& s) {
  const int d = D > 0 ? D : d_runtime, n = d + 1;
  // Sort keys: the fractional part quantised to 26 bits, then 31 − index (ties by index).
  alignas(16) std::array<std::int32_t, kMaxDimension + 1> key, rank;
  for (int i = 0; i < d; ++i) {
    const double v = z[i];
    if (!(std::abs(v) < kMaxLatticeCoordinate - 1))
      throw InputError(std::isfinite(v) ? "the point is too far from the origin: lattice coordinate " + fmt(v) +
                                              " exceeds 2^30"
                                        : "the point has a NaN or infinite coordinate");
    // floor and round without libm calls or data-dependent branches (|v| < 2^30): truncate, step
    // down for negative non-integers; r is round(v) except at exact halves, which never snap.
    std::int64_t fi = static_cast<std::int64_t>(v);
    fi -= static_cast<double>(fi) > v ? 1 : 0;
    double f = static_cast<double>(fi);
    double frac = v - f;
    const double r = f + static_cast<double>(frac >= 0.5);
    if (std::abs(v - r) <= kTieTolerance) {  // on a lattice hyperplane: snap
      f = r;
      frac = 0;
    }
    s.y[i] = static_cast<std::int32_t>(f);
    z[i] = frac;
    key[i] = (static_cast<std::int32_t>(frac * 67108864.0) << 5) | (31 - i);
  }
  z[d] = 0;
  key[d] = 31 - d;
  // Ranks by counting larger keys: O(d²) branch-free comparisons that vectorise (4 per
  // instruction), instead of a comparison sort's mispredicted branches.
  const int padded = (n + 3) & ~3;
  for (int i = n; i < padded; ++i) key[i] = -1;
  for (int i = 0; i < padded; ++i) rank[i] = 0;
  for (int j = 0; j < n; ++j) {
    const std::int32_t kj = key[j];
    for (int i = 0; i < padded; ++i) rank[i] += key[i] < kj ? 1 : 0;
  }
  std::array<std::uint8_t, kMaxDimension + 1> order{};
  for (int i = 0; i < n; ++i) order[rank[i]] = static_cast<std::uint8_t>(i);
  // Exact order: fractional parts closer than 2^-26 may be swapped by the quantisation; an
  // insertion pass on the exact values repairs that (no work in the usual case).
  for (int p = 1; p < n; ++p) {
    const std::uint8_t e = order[p];
    const double ze = z[e];
    if (!(z[order[p - 1]] < ze)) continue;
    int q = p;
    for (; q > 0 && z[order[q - 1]] < ze; --q) order[q] = order[q - 1];
    order[q] = e;
  }
  // Strict drops (beyond the tolerance) start new blocks.
  int b = 0;
  s.block[order[0]] = 0;
  for (int p = 1; p < n; ++p) {
    b += z[order[p - 1]] > z[order[p]] + kTieTolerance ? 1 : 0;
    s.block[order[p]] = static_cast<std::uint8_t>(b);
  }
  s.k = static_cast<std::uint8_t>(b);
}

// locate() for a dimension fixed at compile time (D > 0: the small matrix–vector product and the
// kernel are fully unrolled) or given at run time (D = 0).
template <int D>
Simplex locate_impl(const Triangulation& t, const double* x) {
  const int d = D > 0 ? D : t.dimension();
  std::array<double, kMaxDimension + 1> z;
  if constexpr (D > 0) {
    const double* b = t.offset().data();
    if (t.is_freudenthal()) {
      for (int i = 0; i < D; ++i) z[i] = x[i] - b[i];
    } else {
      std::array<double, D> u;
      for (int j = 0; j < D; ++j) u[j] = x[j] - b[j];
      const double* inv = t.inverse().data();  // column-major; same summation order as below
      for (int i = 0; i < D; ++i) {
        double a = 0;
        for (int j = 0; j < D; ++j) a += inv[j * D + i] * u[j];
        z[i] = a;
      }
    }
  } else {
    t.lattice_coordinates(x, z.data());
  }
  Simplex s;
  s.d = static_cast<std::uint8_t>(d);
  locate_fk<D>(z.data(), d, s);
  return s;
}

}  // namespace

Simplex Triangulation::locate(const double* x) const {
  switch (d_) {
    case 1: return locate_impl<1>(*this, x);
    case 2: return locate_impl<2>(*this, x);
    case 3: return locate_impl<3>(*this, x);
    case 4: return locate_impl<4>(*this, x);
    case 5: return locate_impl<5>(*this, x);
    case 6: return locate_impl<6>(*this, x);
    case 7: return locate_impl<7>(*this, x);
    case 8: return locate_impl<8>(*this, x);
    case 9: return locate_impl<9>(*this, x);
    case 10: return locate_impl<10>(*this, x);
    case 11: return locate_impl<11>(*this, x);
    case 12: return locate_impl<12>(*this, x);
    default: return locate_impl<0>(*this, x);
  }
}

void Triangulation::barycentric(const Simplex& sigma, const double* x, double* lambda) const {
  std::array<double, kMaxDimension + 1> yf, zeta{};
  std::array<int, kMaxDimension + 1> count{};
  lattice_coordinates(x, yf.data());
  const int k = sigma.k;
  for (int i = 0; i < d_; ++i)
    if (sigma.block[i] < k) {
      zeta[sigma.block[i]] += yf[i] - sigma.y[i];
      ++count[sigma.block[i]];
    }
  for (int j = 0; j < k; ++j) zeta[j] /= count[j];  // blocks before the last hold an index < d
  zeta[k] = 0;
  lambda[0] = 1 - zeta[0];
  for (int j = 1; j <= k; ++j) lambda[j] = zeta[j - 1] - zeta[j];
}

double Triangulation::longest_edge() const {
  if (known_longest_edge_ > 0) return known_longest_edge_;
  if (d_ > 24)
    throw InputError("the longest edge of a general matrix is computed exhaustively, which needs d <= 24");
  // Edge vectors of the d-simplices are Λ·e_A for the non-empty A ⊆ {0..d−1}; walk them in Gray order.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(d_);
  std::vector<bool> in(d_, false);
  double best = 0;
  const std::uint64_t n = std::uint64_t{1} << d_;
  for (std::uint64_t t = 1; t < n; ++t) {
    const int bit = __builtin_ctzll(t);
    if (in[bit]) v -= matrix_.col(bit);
    else v += matrix_.col(bit);
    in[bit] = !in[bit];
    best = std::max(best, v.squaredNorm());
  }
  return std::sqrt(best);
}

Eigen::MatrixXd read_matrix_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the matrix file '" + path + "'");
  std::vector<std::vector<double>> rows;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (auto c = line.find('#'); c != std::string::npos) line.resize(c);
    std::istringstream ls(line);
    std::vector<double> row;
    std::string tok;
    while (ls >> tok) {
      const std::optional<double> v = parse_double(tok);
      if (!v)
        throw InputError("matrix file '" + path + "', line " + std::to_string(lineno) + ": '" + tok + "' is not a number");
      if (!std::isfinite(*v))
        throw InputError("matrix file '" + path + "', line " + std::to_string(lineno) + ": NaN or infinite entry");
      row.push_back(*v);
    }
    if (row.empty()) continue;
    if (!rows.empty() && row.size() != rows.front().size())
      throw InputError("matrix file '" + path + "', line " + std::to_string(lineno) + ": expected " +
                       std::to_string(rows.front().size()) + " numbers, got " + std::to_string(row.size()));
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError("matrix file '" + path + "' has no rows");
  if (rows.size() != rows.front().size())
    throw InputError("matrix file '" + path + "' is " + std::to_string(rows.size()) + "x" +
                     std::to_string(rows.front().size()) + ", expected a square matrix");
  const int d = static_cast<int>(rows.size());
  Eigen::MatrixXd m(d, d);
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) m(i, j) = rows[i][j];
  return m;
}

}  // namespace coxmesh
