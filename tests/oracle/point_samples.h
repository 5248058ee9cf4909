// Samples of test manifolds for the point-cloud tests, from fixed generator seeds, with optional
// Gaussian noise of standard deviation `noise` in every coordinate.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace coxmesh::test {

struct Samples {
  int d = 3, m = 2;
  std::vector<double> points;  // n × d
  std::size_t size() const { return points.size() / d; }
};

/// "circle" (S¹ ⊂ R²), "trefoil" (the trefoil knot ⊂ R³: (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)),
/// "sphere" (S² ⊂ R³), "torus" (radii 1, 0.4, area-uniform), "flat-torus" (S¹ × S¹ ⊂ R⁴), "s3"
/// (S³ ⊂ R⁴), "two-spheres" (unit spheres centred 3 apart), "patch" (the saddle z = 0.2(x² − y²)
/// over the unit disc: a disc with boundary), "rp2" (the Veronese-type RP² ⊂ R⁴:
/// (x, y, z) ∈ S² ↦ (xy, xz, y² − z², 2yz)), "klein" (the Klein bottle ⊂ R⁴:
/// (u, v) ↦ ((1 + 0.4 cos v) cos u, (1 + 0.4 cos v) sin u, 0.4 sin v cos(u/2), 0.4 sin v sin(u/2))).
inline Samples sample_manifold(const std::string& name, std::size_t n, double noise = 0, std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  std::uniform_real_distribution<double> uniform(0, 1);
  const double pi = std::acos(-1.0);
  Samples s;
  auto push = [&](std::initializer_list<double> p) {
    for (double v : p) s.points.push_back(v + noise * gauss(rng));
  };
  auto on_sphere = [&](int dim, double* x) {
    double r = 0;
    for (int i = 0; i < dim; ++i) {
      x[i] = gauss(rng);
      r += x[i] * x[i];
    }
    for (int i = 0; i < dim; ++i) x[i] /= std::sqrt(r);
  };
  if (name == "flat-torus" || name == "s3" || name == "rp2" || name == "klein") s.d = 4;
  if (name == "s3") s.m = 3;
  if (name == "circle") s.d = 2;
  if (name == "circle" || name == "trefoil") s.m = 1;
  for (std::size_t i = 0; i < n; ++i) {
    double x[4];
    if (name == "circle") {
      const double t = 2 * pi * uniform(rng);
      push({std::cos(t), std::sin(t)});
    } else if (name == "trefoil") {
      const double t = 2 * pi * uniform(rng);
      push({std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)});
    } else if (name == "sphere" || name == "two-spheres") {
      on_sphere(3, x);
      const double c = name == "two-spheres" && i % 2 ? 3.0 : 0.0;
      push({x[0] + c, x[1], x[2]});
    } else if (name == "torus") {
      double a, b;
      do {  // area element ∝ 1 + 0.4 cos b: rejection
        a = 2 * pi * uniform(rng);
        b = 2 * pi * uniform(rng);
      } while (uniform(rng) * 1.4 > 1 + 0.4 * std::cos(b));
      push({(1 + 0.4 * std::cos(b)) * std::cos(a), (1 + 0.4 * std::cos(b)) * std::sin(a), 0.4 * std::sin(b)});
    } else if (name == "flat-torus") {
      const double a = 2 * pi * uniform(rng), b = 2 * pi * uniform(rng);
      push({std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    } else if (name == "s3") {
      on_sphere(4, x);
      push({x[0], x[1], x[2], x[3]});
    } else if (name == "patch") {
      const double r = std::sqrt(uniform(rng)), t = 2 * pi * uniform(rng), u = r * std::cos(t), v = r * std::sin(t);
      push({u, v, 0.2 * (u * u - v * v)});
    } else if (name == "klein") {
      const double u = 2 * pi * uniform(rng), v = 2 * pi * uniform(rng), r = 1 + 0.4 * std::cos(v);
      push(
          {r * std::cos(u), r * std::sin(u), 0.4 * std::sin(v) * std::cos(u / 2), 0.4 * std::sin(v) * std::sin(u / 2)});
    } else if (name == "rp2") {
      on_sphere(3, x);
      push({x[0] * x[1], x[0] * x[2], x[1] * x[1] - x[2] * x[2], 2 * x[1] * x[2]});
    }
  }
  return s;
}

}  // namespace coxmesh::test
