#include "coxmesh/oracle/regularity.h"

#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace coxmesh {

namespace {

// Jacobian of the stacked functions at x by central differences; false where a value is not finite.
bool jacobian(std::span<const ImplicitFunction* const> functions, const Eigen::VectorXd& x, double step,
              Eigen::MatrixXd& j) {
  const int d = static_cast<int>(x.size());
  Eigen::VectorXd y = x;
  std::vector<double> plus, minus;
  int row = 0;
  for (const ImplicitFunction* f : functions) {
    const int k = f->codimension();
    plus.resize(k), minus.resize(k);
    for (int i = 0; i < d; ++i) {
      y[i] = x[i] + step;
      f->evaluate(y.data(), plus.data());
      y[i] = x[i] - step;
      f->evaluate(y.data(), minus.data());
      y[i] = x[i];
      for (int r = 0; r < k; ++r) {
        j(row + r, i) = (plus[r] - minus[r]) / (2 * step);
        if (!std::isfinite(j(row + r, i))) return false;
      }
    }
    row += k;
  }
  return true;
}

}  // namespace

double regularity(std::span<const ImplicitFunction* const> functions, const double* x, double h) {
  const int d = functions.front()->ambient_dimension();
  int k = 0;
  for (const ImplicitFunction* f : functions) k += f->codimension();
  if (k > d) return 0;
  const Eigen::VectorXd at = Eigen::Map<const Eigen::VectorXd>(x, d);
  Eigen::MatrixXd j(k, d), around(k, d);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (!jacobian(functions, at, h / 8, j)) return kNaN;
  Eigen::VectorXd scale = j.rowwise().norm();
  for (int i = 0; i < d; ++i)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::VectorXd q = at;
      q[i] += sign * 4 * h;
      if (!jacobian(functions, q, h / 8, around)) return kNaN;
      scale = scale.cwiseMax(around.rowwise().norm());
    }
  for (int r = 0; r < k; ++r) {
    if (scale[r] == 0) return 0;  // the equation is constant around x
    j.row(r) /= scale[r];
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(j).singularValues()[k - 1];
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
