#include "coxmesh/tracing/seeds.h"

#include <Eigen/Dense>
#include <algorithm>
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

namespace {

// When no point of M is found in the box, F may simply not be finite there (0/0, 1/0, the logarithm
// of a negative number): say that instead.
void check_finite_somewhere(const ImplicitFunction& f, const Box& box) {
  const int d = f.ambient_dimension();
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> x(d), value(f.codimension());
  std::string example;
  for (int sample = 0; sample < 64; ++sample) {
    for (int i = 0; i < d; ++i) x[i] = box.lo[i] + unit(random) * (box.hi[i] - box.lo[i]);
    f.evaluate(x.data(), value.data());
    if (std::all_of(value.begin(), value.end(), [](double v) { return std::isfinite(v); })) return;
    if (example.empty()) {
      std::ostringstream at;
      at << "(";
      for (int i = 0; i < d; ++i) at << (i ? "," : "") << x[i];
      example = at.str() + ")";
    }
  }
  throw InputError("F is not finite at any of 64 points sampled in the box (e.g. at " + example +
                   "): check it for divisions by zero and logarithms or roots of negative numbers");
}

}  // namespace

SeedChoice choose_seeds(const ImplicitFunction& f, const ImplicitFunction* domain,
                        const std::vector<std::vector<double>>& given, bool automatic, const Box& box,
                        const Triangulation& t) {
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
      check_finite_somewhere(f, box);
      std::ostringstream box_text;
      for (int i = 0; i < d; ++i) box_text << (i ? " x [" : "[") << box.lo[i] << "," << box.hi[i] << "]";
      throw InputError("no point of the manifold found in the box " + box_text.str() +
                       (domain ? " inside the domain" : "") + ": give a larger box or a seed");
    }
    choice.skip_unusable = true;
    choice.seeds.insert(choice.seeds.end(), found.begin(), found.end());
  }
  for (auto& seed : choice.seeds) seed = generic_seed(f, t, std::move(seed));
  return choice;
}

}  // namespace coxmesh
