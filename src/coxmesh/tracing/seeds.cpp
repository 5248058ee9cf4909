#include "coxmesh/tracing/seeds.h"

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace coxmesh {

std::optional<std::vector<double>> project_onto_manifold(const ImplicitFunction& f, std::vector<double> x,
                                                         double tolerance) {
  const int d = f.ambient_dimension(), k = f.codimension();
  Eigen::VectorXd fx(k), fp(k), fm(k);
  Eigen::MatrixXd jac(k, d);
  auto eval = [&](const std::vector<double>& p, Eigen::VectorXd& out) {
    f.evaluate(p.data(), out.data());
    return out.allFinite();
  };
  for (int iter = 0; iter < 100; ++iter) {
    if (!eval(x, fx)) return std::nullopt;
    double scale = 1;
    for (double v : x) scale = std::max(scale, std::abs(v));
    if (fx.norm() <= tolerance * scale) return x;
    for (int j = 0; j < d; ++j) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[j])), xj = x[j];
      x[j] = xj + h;
      const bool okp = eval(x, fp);
      x[j] = xj - h;
      const bool okm = eval(x, fm);
      x[j] = xj;
      if (!okp || !okm) return std::nullopt;
      jac.col(j) = (fp - fm) / (2 * h);
    }
    const Eigen::VectorXd step = jac.completeOrthogonalDecomposition().solve(fx);
    if (!step.allFinite()) return std::nullopt;
    for (int j = 0; j < d; ++j) x[j] -= step[j];
    if (step.norm() <= 1e-15 * scale) {
      if (!eval(x, fx)) return std::nullopt;
      return fx.norm() <= 1e-8 * scale ? std::optional(x) : std::nullopt;
    }
  }
  return std::nullopt;
}

std::vector<std::vector<double>> find_seeds(const ImplicitFunction& f, const ImplicitFunction* domain, const Box& box,
                                            int samples, std::uint64_t rng_seed) {
  const int d = f.ambient_dimension();
  std::mt19937_64 rng(rng_seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> seeds;
  std::vector<double> x(d);
  for (int s = 0; s < samples; ++s) {
    for (int i = 0; i < d; ++i) x[i] = box.lo[i] + u(rng) * (box.hi[i] - box.lo[i]);
    auto p = project_onto_manifold(f, x);
    if (!p || !box.contains(p->data())) continue;
    if (domain) {
      double dv;
      domain->evaluate(p->data(), &dv);
      if (!(dv < 0)) continue;
    }
    seeds.push_back(std::move(*p));
  }
  return seeds;
}

std::vector<double> generic_seed(const ImplicitFunction& f, const Triangulation& t, std::vector<double> x) {
  const int d = t.dimension();
  if (t.locate(x).k == d) return x;
  const double h = t.longest_edge();
  std::vector<double> moved = x;
  double norm = 0;
  for (int i = 0; i < d; ++i) norm += std::pow(std::sin(1.6180339887 * (i + 1) + 0.5), 2);
  for (int i = 0; i < d; ++i) moved[i] += 0.25 * h * std::sin(1.6180339887 * (i + 1) + 0.5) / std::sqrt(norm);
  const std::optional<std::vector<double>> p = project_onto_manifold(f, moved);
  if (!p) return x;
  double distance = 0;
  for (int i = 0; i < d; ++i) distance += ((*p)[i] - x[i]) * ((*p)[i] - x[i]);
  return std::sqrt(distance) <= h && t.locate(*p).k == d ? *p : x;
}

}  // namespace coxmesh
