#include "coxmesh/tracing/seeds.h"

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <sstream>

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

SeedChoice choose_seeds(const ImplicitFunction& f, const ImplicitFunction* domain,
                        const std::vector<std::vector<double>>& given, bool automatic, const Box& box) {
  const int d = f.ambient_dimension();
  SeedChoice choice;
  for (const std::vector<double>& x : given) {
    if (static_cast<int>(x.size()) != d)
      throw InputError("a seed has " + std::to_string(x.size()) + " coordinates, expected " + std::to_string(d));
    choice.seeds.push_back(project_onto_manifold(f, x).value_or(x));
  }
  if (choice.seeds.empty() && !f.seed().empty()) choice.seeds.push_back(f.seed());
  if (automatic || choice.seeds.empty()) {
    auto found = find_seeds(f, domain, box);
    choice.automatic = found.size();
    if (choice.seeds.empty() && found.empty()) {
      std::ostringstream box_text;
      for (int i = 0; i < d; ++i) box_text << (i ? " x [" : "[") << box.lo[i] << "," << box.hi[i] << "]";
      throw InputError("no point of the manifold found in the box " + box_text.str() +
                       (domain ? " inside the domain" : "") + ": give a larger box or a seed");
    }
    choice.skip_unusable = true;
    choice.seeds.insert(choice.seeds.end(), found.begin(), found.end());
  }
  return choice;
}

}  // namespace coxmesh
