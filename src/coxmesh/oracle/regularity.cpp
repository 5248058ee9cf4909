#include "coxmesh/oracle/regularity.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace coxmesh {

namespace {

// The Jacobians (central differences of step h/8) of the stacked functions at x and at the 2d points
// x ± 4h·e_i: all their (2d + 1)·2d evaluation points in one batch per function (a function written
// in Python pays its call once). jacobians[p] is k × d; false where a value is not finite.
bool jacobians(std::span<const ImplicitFunction* const> functions, const double* x, double h,
               std::vector<Eigen::MatrixXd>& out) {
  const int d = functions.front()->ambient_dimension();
  const double step = h / 8;
  const int centres = 2 * d + 1, per_centre = 2 * d;
  std::vector<double> points(static_cast<std::size_t>(centres) * per_centre * d);
  for (int c = 0; c < centres; ++c)
    for (int q = 0; q < per_centre; ++q) {
      double* p = points.data() + (static_cast<std::size_t>(c) * per_centre + q) * d;
      std::copy(x, x + d, p);
      if (c > 0) p[(c - 1) / 2] += ((c - 1) % 2 ? 4 * h : -4 * h);
      p[q / 2] += q % 2 ? step : -step;
    }
  int k = 0;
  for (const ImplicitFunction* f : functions) k += f->codimension();
  out.assign(centres, Eigen::MatrixXd(k, d));
  int row = 0;
  std::vector<double> values;
  for (const ImplicitFunction* f : functions) {
    const int kf = f->codimension();
    values.resize(static_cast<std::size_t>(centres) * per_centre * kf);
    f->evaluate_batch(points.data(), centres * per_centre, values.data());
    for (int c = 0; c < centres; ++c)
      for (int i = 0; i < d; ++i)
        for (int r = 0; r < kf; ++r) {
          const double minus = values[(static_cast<std::size_t>(c) * per_centre + 2 * i) * kf + r];
          const double plus = values[(static_cast<std::size_t>(c) * per_centre + 2 * i + 1) * kf + r];
          out[c](row + r, i) = (plus - minus) / (2 * step);
          if (!std::isfinite(out[c](row + r, i))) return false;
        }
    row += kf;
  }
  return true;
}

}  // namespace

double regularity(std::span<const ImplicitFunction* const> functions, const double* x, double h) {
  const int d = functions.front()->ambient_dimension();
  int k = 0;
  for (const ImplicitFunction* f : functions) k += f->codimension();
  if (k > d) return 0;
  std::vector<Eigen::MatrixXd> j;
  if (!jacobians(functions, x, h, j)) return std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd scale = j[0].rowwise().norm();
  for (std::size_t c = 1; c < j.size(); ++c) scale = scale.cwiseMax(j[c].rowwise().norm());
  for (int r = 0; r < k; ++r) {
    if (scale[r] == 0) return 0;  // the equation is constant around x
    j[0].row(r) /= scale[r];
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(j[0]).singularValues()[k - 1];
}

bool singular_on(std::span<const ImplicitFunction* const> functions, std::span<const double> points, double h,
                 int samples, double threshold) {
  const std::size_t d = static_cast<std::size_t>(functions.front()->ambient_dimension());
  const std::size_t n = points.size() / d;
  if (n == 0) return false;
  const std::size_t tested = std::min<std::size_t>(n, static_cast<std::size_t>(samples));
  std::size_t finite = 0, singular = 0;
  for (std::size_t s = 0; s < tested; ++s) {
    const double r = regularity(functions, points.data() + (s * n / tested) * d, h);
    if (std::isnan(r)) continue;
    ++finite;
    singular += r < threshold;
  }
  return finite > 0 && 4 * singular > finite;
}

}  // namespace coxmesh
