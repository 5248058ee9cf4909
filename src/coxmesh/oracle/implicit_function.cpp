// Thesis §4.3 (manifolds given as zero sets), §4.4 (the example manifolds).
#include "coxmesh/oracle/implicit_function.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "coxmesh/errors.h"

namespace coxmesh {

void check_manifold_function(const FunctionPtr& f, int d) {
  if (!f) throw InputError("no implicit function given");
  if (f->ambient_dimension() != d)
    throw InputError("the function is defined on R^" + std::to_string(f->ambient_dimension()) +
                     " but the triangulation is of R^" + std::to_string(d));
  if (f->codimension() < 1 || f->codimension() > d)
    throw InputError("the number of equations must be between 1 and " + std::to_string(d));
}

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw InputError(what);
}
std::vector<double> to_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }
}  // namespace

FunctionPtr sphere(int m, int d, double radius, std::vector<double> center) {
  require(m >= 1 && d >= m + 1, "a sphere S^m needs 1 <= m < d");
  require(std::isfinite(radius) && radius > 0, "the radius must be finite and positive");
  if (center.empty()) center.assign(d, 0.0);
  require(static_cast<int>(center.size()) == d, "the centre must have d coordinates");
  std::vector<double> seed = center;
  seed[0] += radius;
  return make_function(
      d, d - m,
      [m, d, r2 = radius * radius, c = center](const double* x, double* f) {
        double s = 0;
        for (int i = 0; i <= m; ++i) s += (x[i] - c[i]) * (x[i] - c[i]);
        f[0] = s - r2;
        for (int i = m + 1; i < d; ++i) f[i - m] = x[i] - c[i];
      },
      seed);
}

FunctionPtr torus(double R, double r) {
  require(std::isfinite(R) && std::isfinite(r) && r > 0 && R > r, "a torus needs major radius > minor radius > 0");
  return make_function(3, 1,
                       [R, r](const double* x, double* f) {
                         const double q = std::sqrt(x[0] * x[0] + x[1] * x[1]) - R;
                         f[0] = q * q + x[2] * x[2] - r * r;
                       },
                       {R + r, 0, 0});
}

FunctionPtr affine_plane(const Eigen::MatrixXd& normals, const Eigen::VectorXd& point) {
  const int d = static_cast<int>(normals.rows()), k = static_cast<int>(normals.cols());
  require(point.size() == d, "the point of the affine plane must have d coordinates");
  require(normals.allFinite() && point.allFinite(), "the affine plane has a NaN or infinite entry");
  Eigen::FullPivLU<Eigen::MatrixXd> lu(normals);
  require(lu.rank() == k, "the normals of the affine plane must be linearly independent");
  Eigen::MatrixXd n = normals;
  n.colwise().normalize();
  return make_function(
      d, k,
      [n, p = point, d, k](const double* x, double* f) {
        for (int j = 0; j < k; ++j) {
          double s = 0;
          for (int i = 0; i < d; ++i) s += n(i, j) * (x[i] - p[i]);
          f[j] = s;
        }
      },
      to_vector(point));
}

FunctionPtr chair(double a, double b, double s) {
  // A seed on the positive z axis: (z² − a s²)² = b (z − s)²(z + s)², i.e. z² − a s² = √b (z² − s²).
  const double z0 = s * std::sqrt((a - std::sqrt(b)) / (1 - std::sqrt(b)));
  return make_function(3, 1,
                       [a, b, s](const double* p, double* f) {
                         const double x = p[0], y = p[1], z = p[2];
                         const double t = x * x + y * y + z * z - a * s * s;
                         f[0] = t * t - b * ((z - s) * (z - s) - 2 * x * x) * ((z + s) * (z + s) - 2 * y * y);
                       },
                       {0, 0, z0});
}

FunctionPtr iron() {
  return make_function(3, 1,
                       [](const double* p, double* f) {
                         const double x = p[0], y = p[1], z = p[2];
                         f[0] = -(std::pow(x, 6) + std::pow(y, 6) + std::pow(z, 6)) / 300. + x * y * y * z / 2.1 +
                                y * y + std::pow(z - 2, 4) - 1;
                       },
                       {std::pow(4500.0, 1.0 / 6), 0, 0});  // −x⁶/300 + 16 − 1 = 0
}

FunctionPtr lemniscate_of_revolution(double a) {
  require(std::isfinite(a) && a > 0, "the lemniscate parameter must be positive");
  return make_function(3, 1,
                       [a](const double* p, double* f) {
                         const double x2 = p[0] * p[0], y2 = p[1] * p[1], z2 = p[2] * p[2];
                         const double t = x2 + y2 + z2;
                         f[0] = t * t - 2 * a * a * (x2 - y2 - z2);
                       },
                       {std::sqrt(2.0) * a, 0, 0});
}

FunctionPtr whitney_umbrella() {
  return make_function(3, 1, [](const double* p, double* f) { f[0] = p[0] * p[0] - p[1] * p[1] * p[2]; }, {1, 1, 1});
}

FunctionPtr moment_curve(int d) {
  require(d >= 2, "the moment curve needs d >= 2");
  std::vector<double> seed(d);  // t = 1/2, off the lattice vertex at the origin
  for (int i = 0; i < d; ++i) seed[i] = std::ldexp(1.0, -(i + 1));
  return make_function(
      d, d - 1,
      [d](const double* x, double* f) {
        for (int i = 1; i < d; ++i) f[i - 1] = x[i] - x[0] * x[i - 1];
      },
      seed);
}

FunctionPtr rotation_group_so3() {
  return make_function(9, 6,
                       [](const double* m, double* f) {
                         // Columns c_i = (m[i], m[3+i], m[6+i]); equations ⟨c_i, c_j⟩ − δ_ij for i ≤ j.
                         int e = 0;
                         for (int i = 0; i < 3; ++i)
                           for (int j = i; j < 3; ++j)
                             f[e++] = m[i] * m[j] + m[3 + i] * m[3 + j] + m[6 + i] * m[6 + j] - (i == j ? 1.0 : 0.0);
                       },
                       {1, 0, 0, 0, 1, 0, 0, 0, 1});
}

FunctionPtr product(FunctionPtr f, FunctionPtr g) {
  const int d1 = f->ambient_dimension(), d2 = g->ambient_dimension(), k1 = f->codimension(), k2 = g->codimension();
  std::vector<double> seed = f->seed(), s2 = g->seed();
  if (seed.empty() || s2.empty())
    seed.clear();
  else
    seed.insert(seed.end(), s2.begin(), s2.end());
  return make_function(
      d1 + d2, k1 + k2,
      [f, g, d1, k1](const double* x, double* v) {
        f->evaluate(x, v);
        g->evaluate(x + d1, v + k1);
      },
      seed);
}

FunctionPtr embed(FunctionPtr f, int d) {
  const int df = f->ambient_dimension(), kf = f->codimension();
  require(d >= df, "cannot embed a function of R^" + std::to_string(df) + " into R^" + std::to_string(d));
  std::vector<double> seed = f->seed();
  if (!seed.empty()) seed.resize(d, 0.0);
  return make_function(
      d, kf + d - df,
      [f, d, df, kf](const double* x, double* v) {
        f->evaluate(x, v);
        for (int i = df; i < d; ++i) v[kf + i - df] = x[i];
      },
      seed);
}

FunctionPtr linear_map(FunctionPtr f, const Eigen::MatrixXd& a) {
  const int d = f->ambient_dimension();
  require(a.rows() == d && a.cols() == d,
          "the linear map must be a " + std::to_string(d) + "x" + std::to_string(d) + " matrix");
  require(a.allFinite(), "the linear map has a NaN or infinite entry");
  Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  require(lu.isInvertible(), "the linear map must be invertible");
  const Eigen::MatrixXd inv = lu.inverse();  // factorised once
  std::vector<double> seed = f->seed();
  if (!seed.empty()) seed = to_vector(a * Eigen::Map<const Eigen::VectorXd>(seed.data(), d));
  return make_function(
      d, f->codimension(),
      [f, inv, d](const double* x, double* v) {
        double y[64];
        for (int i = 0; i < d; ++i) {
          double s = 0;
          for (int j = 0; j < d; ++j) s += inv(i, j) * x[j];
          y[i] = s;
        }
        f->evaluate(y, v);
      },
      seed);
}

FunctionPtr translate(FunctionPtr f, const Eigen::VectorXd& b) {
  const int d = f->ambient_dimension();
  require(b.size() == d, "the translation must have d coordinates");
  require(b.allFinite(), "the translation has a NaN or infinite coordinate");
  std::vector<double> seed = f->seed();
  for (int i = 0; i < static_cast<int>(seed.size()); ++i) seed[i] += b[i];
  return make_function(
      d, f->codimension(),
      [f, b, d](const double* x, double* v) {
        double y[64];
        for (int i = 0; i < d; ++i) y[i] = x[i] - b[i];
        f->evaluate(y, v);
      },
      seed);
}

FunctionPtr negation(FunctionPtr f) {
  const int k = f->codimension();
  return make_function(
      f->ambient_dimension(), k,
      [f, k](const double* x, double* v) {
        f->evaluate(x, v);
        for (int i = 0; i < k; ++i) v[i] = -v[i];
      },
      f->seed());
}

FunctionPtr ball_domain(const std::vector<double>& center, double radius) {
  require(std::isfinite(radius) && radius > 0, "the domain radius must be finite and positive");
  const int d = static_cast<int>(center.size());
  return make_function(d, 1,
                       [c = center, r2 = radius * radius, d](const double* x, double* v) {
                         double s = 0;
                         for (int i = 0; i < d; ++i) s += (x[i] - c[i]) * (x[i] - c[i]);
                         v[0] = s - r2;
                       },
                       {});
}

FunctionPtr half_space_domain(const std::vector<double>& normal, double c) {
  const int d = static_cast<int>(normal.size());
  return make_function(d, 1,
                       [n = normal, c, d](const double* x, double* v) {
                         double s = -c;
                         for (int i = 0; i < d; ++i) s += n[i] * x[i];
                         v[0] = s;
                       },
                       {});
}

bool Box::contains(const double* x) const {
  for (std::size_t i = 0; i < lo.size(); ++i)
    if (!(x[i] >= lo[i] && x[i] <= hi[i])) return false;
  return true;
}

FunctionPtr box_domain(const Box& box) {
  const int d = static_cast<int>(box.lo.size());
  if (box.hi.size() != box.lo.size()) throw InputError("a box needs as many upper as lower bounds");
  for (int i = 0; i < d; ++i)
    if (!(box.lo[i] < box.hi[i]) || !std::isfinite(box.lo[i]) || !std::isfinite(box.hi[i]))
      throw InputError("a box needs finite bounds with lo < hi in every coordinate");
  return make_function(d, 1,
                       [box, d](const double* x, double* v) {
                         double s = -std::numeric_limits<double>::infinity();
                         for (int i = 0; i < d; ++i) s = std::max({s, box.lo[i] - x[i], x[i] - box.hi[i]});
                         v[0] = s;
                       },
                       {});
}

namespace {
// max(a, b), passing batches through to both (see domain_intersection).
class DomainIntersection final : public ImplicitFunction {
 public:
  DomainIntersection(FunctionPtr a, FunctionPtr b) : a_(std::move(a)), b_(std::move(b)) {}
  int ambient_dimension() const override { return a_->ambient_dimension(); }
  int codimension() const override { return 1; }
  void evaluate(const double* x, double* value) const override {
    double vb;
    a_->evaluate(x, value);
    b_->evaluate(x, &vb);
    value[0] = std::max(value[0], vb);
  }
  void evaluate_batch(const double* xs, int n, double* values) const override {
    std::vector<double> vb(n);
    a_->evaluate_batch(xs, n, values);
    b_->evaluate_batch(xs, n, vb.data());
    for (int i = 0; i < n; ++i) values[i] = std::max(values[i], vb[i]);
  }
  bool prefers_batches() const override { return a_->prefers_batches() || b_->prefers_batches(); }

 private:
  FunctionPtr a_, b_;
};
}  // namespace

FunctionPtr domain_intersection(FunctionPtr a, FunctionPtr b) {
  if (!a) return b;
  require(b && a->ambient_dimension() == b->ambient_dimension() && a->codimension() == 1 && b->codimension() == 1,
          "domains to intersect must both map R^d to R");
  return std::make_shared<DomainIntersection>(std::move(a), std::move(b));
}

}  // namespace coxmesh
