#include "coxmesh/oracle/presets.h"

#include <cmath>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

const std::vector<PresetInfo>& preset_catalogue() {
  static const std::vector<PresetInfo> catalogue = {
      {"torus", "torus in R^3, --radius R (1) and --minor-radius r (0.4)", {"--radius", "--minor-radius"}},
      {"sphere", "S^m of --radius (1) in R^--dim (m+1), --m (2), --center", {"--m", "--dim", "--radius", "--center"}},
      {"flat-torus",
       "S^1 x S^1 in R^4, circles of --radius (1) and --minor-radius (1)",
       {"--radius", "--minor-radius"}},
      {"chair", "the chair surface in R^3", {}},
      {"iron", "the iron surface in R^3", {}},
      {"lemniscate", "lemniscate of revolution in R^3, --radius a (1)", {"--radius"}},
      {"whitney-umbrella", "Whitney umbrella x^2 = y^2 z in R^3, inside the ball of --radius (2)", {"--radius"}},
      {"moment-curve",
       "moment curve (t, t^2, ..., t^d) in R^--dim (3), inside the ball of --radius (1.5)",
       {"--dim", "--radius"}},
      {"so3", "the rotation group SO(3) in R^9 (M^T M = I)", {}},
      {"plane",
       "the plane x_m = ... = x_{d-1} = 0 in R^--dim, --m (2), inside the ball of --radius (1) around --center",
       {"--m", "--dim", "--radius", "--center"}},
  };
  return catalogue;
}

Preset make_preset(const std::string& name, const PresetParameters& p) {
  auto center_or_origin = [&](int d) {
    if (!p.center.empty() && static_cast<int>(p.center.size()) != d)
      throw InputError("--center has " + std::to_string(p.center.size()) + " coordinates, expected " +
                       std::to_string(d));
    return p.center.empty() ? std::vector<double>(d, 0.0) : p.center;
  };
  if (name == "torus") {
    const double R = p.radius.value_or(1.0), r = p.minor_radius.value_or(0.4);
    return {torus(R, r), nullptr, r / 4, R + r};
  }
  if (name == "sphere") {
    const int d = p.dim.value_or(p.m + 1);
    const double r = p.radius.value_or(1.0);
    return {sphere(p.m, d, r, center_or_origin(d)), nullptr, r / 5, r};
  }
  if (name == "flat-torus") {
    const double r1 = p.radius.value_or(1.0), r2 = p.minor_radius.value_or(1.0);
    return {product(sphere(1, 2, r1), sphere(1, 2, r2)), nullptr, std::min(r1, r2) / 4, std::max(r1, r2)};
  }
  if (name == "chair") return {chair(), nullptr, 0.1, 1.5};
  if (name == "iron") return {iron(), nullptr, 0.25, 4.5};
  if (name == "lemniscate") {
    const double a = p.radius.value_or(1.0);
    return {lemniscate_of_revolution(a), nullptr, a / 10, 1.5 * a};
  }
  if (name == "whitney-umbrella") {
    const double r = p.radius.value_or(2.0);
    return {whitney_umbrella(), ball_domain({0, 0, 0}, r), r / 10, r};
  }
  if (name == "moment-curve") {
    const int d = p.dim.value_or(3);
    const double r = p.radius.value_or(1.5);
    return {moment_curve(d), ball_domain(std::vector<double>(d, 0.0), r), r / 10, r};
  }
  if (name == "so3") return {rotation_group_so3(), nullptr, 0.5, 1.5};
  if (name == "plane") {
    const int d = p.dim.value_or(3);
    if (p.m < 1 || p.m >= d) throw InputError("--m must be between 1 and d-1 for the plane");
    Eigen::MatrixXd n = Eigen::MatrixXd::Zero(d, d - p.m);
    for (int j = 0; j < d - p.m; ++j) n(p.m + j, j) = 1;
    const double r = p.radius.value_or(1.0);
    return {affine_plane(n, Eigen::VectorXd::Zero(d)), ball_domain(center_or_origin(d), r), r / 5, r};
  }
  std::string names;
  for (const auto& info : preset_catalogue()) names += (names.empty() ? "" : ", ") + info.name;
  throw InputError("unknown preset '" + name + "' (known: " + names + ")");
}

}  // namespace coxmesh
