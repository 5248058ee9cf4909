// Projection of R^d points to R³ for the 3D formats; see projection.h.
#include "coxmesh/io/projection.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "coxmesh/io/number_rows.h"
#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

std::vector<double> read_projection_file(const std::string& path, int d) {
  const NumberRows rows = read_number_rows(path, "--project file '" + path + "'");
  if (rows.rows != 3 || rows.columns != static_cast<std::size_t>(d))
    throw InputError("--project " + path + ": expected d = " + std::to_string(d) +
                     " numbers in each of 3 rows, found " + std::to_string(rows.rows) + " rows of " +
                     std::to_string(rows.columns));
  return rows.values;
}

bool is_index_list(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789, ") == std::string::npos;
}

// The stereographic projection from a pole (given, or the best of 2d candidates) of the sphere
// around the points' centroid with their mean distance to it as radius.
Projection stereographic(int d, std::span<const double> points, std::span<const double> pole) {
  Projection p;
  p.d = d;
  p.stereographic = true;
  const std::size_t n = points.size() / std::max(d, 1);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(d);
  for (std::size_t v = 0; v < n; ++v)
    for (int i = 0; i < d; ++i) c[i] += points[v * d + i] / static_cast<double>(n);
  Eigen::VectorXd best(d);
  double radius = 0;
  auto distance = [&](std::size_t v, const Eigen::VectorXd& x) {
    double s = 0;
    for (int i = 0; i < d; ++i) s += (points[v * d + i] - x[i]) * (points[v * d + i] - x[i]);
    return std::sqrt(s);
  };
  if (!pole.empty()) {
    for (int i = 0; i < d; ++i) best[i] = pole[i];
    radius = (best - c).norm();
    double spread = 0;
    for (std::size_t v = 0; v < n; ++v) spread = std::max(spread, distance(v, c));
    if (!(radius > 1e-9 * spread) && n)
      throw InputError("--pole: the pole is the centroid of the points; give a point away from it");
    if (!(radius > 0)) radius = 1;  // (no points: only the spec is being checked)
  } else {
    for (std::size_t v = 0; v < n; ++v) radius += distance(v, c) / static_cast<double>(n);
    if (!(radius > 0)) radius = 1;
    // Of the candidates c ± r·e_i, the one whose nearest point is farthest: the projection
    // stretches the surroundings of the pole without bound.
    double farthest = -1;
    for (int i = 0; i < d; ++i)
      for (double sign : {1.0, -1.0}) {
        Eigen::VectorXd x = c;
        x[i] += sign * radius;
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t v = 0; v < n && nearest > farthest; ++v) nearest = std::min(nearest, distance(v, x));
        if (nearest > farthest) farthest = nearest, best = x;
      }
  }
  const Eigen::VectorXd normal = (best - c) / radius;
  // An orthonormal basis of normal⊥: the last d − 1 columns of the Householder Q of the normal.
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd(normal)).householderQ();
  p.matrix.assign(3 * static_cast<std::size_t>(d), 0.0);
  for (int r = 0; r < std::min(d - 1, 3); ++r)
    for (int i = 0; i < d; ++i) p.matrix[r * d + i] = q(i, r + 1);
  p.center.assign(best.data(), best.data() + d);
  p.sphere_center.assign(c.data(), c.data() + d);
  p.normal.assign(normal.data(), normal.data() + d);
  p.radius = radius;
  return p;
}

}  // namespace

Projection make_projection(const std::string& spec, int d, std::span<const double> points,
                           std::span<const double> pole) {
  if (!pole.empty() && spec != "stereographic")
    throw InputError("--pole is the pole of --project stereographic; it does not apply to --project " +
                     (spec.empty() ? std::string("1,2,3") : spec));
  if (!pole.empty() && static_cast<int>(pole.size()) != d)
    throw InputError("--pole has " + std::to_string(pole.size()) + " coordinates, expected d = " + std::to_string(d));
  for (double x : pole)
    if (!std::isfinite(x)) throw InputError("--pole must be finite");
  if (spec == "stereographic") {
    if (d < 2) throw InputError("--project stereographic needs d >= 2");
    return stereographic(d, points, pole);
  }
  Projection p;
  p.d = d;
  p.matrix.assign(3 * static_cast<std::size_t>(d), 0.0);
  p.center.assign(d, 0.0);
  if (spec.empty() || is_index_list(spec)) {
    std::vector<int> index;
    if (spec.empty()) {
      for (int i = 0; i < std::min(d, 3); ++i) index.push_back(i + 1);
    } else {
      std::istringstream in(spec);
      for (std::string token; std::getline(in, token, ',');) {
        token.erase(0, token.find_first_not_of(' '));
        token.erase(token.find_last_not_of(' ') + 1);
        if (token.empty() || token.size() > 3 || token.find(' ') != std::string::npos)
          throw InputError("--project " + spec + ": '" + token + "' is not a coordinate index 1.." + std::to_string(d));
        const long i = std::stol(token);
        if (i < 1 || i > d)
          throw InputError("--project " + spec + ": coordinate " + token + " is outside 1.." + std::to_string(d) +
                           " (the points are in R^" + std::to_string(d) + ")");
        index.push_back(static_cast<int>(i));
      }
      if (index.empty() || index.size() > 3)
        throw InputError("--project " + spec + ": give 1 to 3 coordinate indices, e.g. 1,2,3");
    }
    for (std::size_t r = 0; r < index.size(); ++r) p.matrix[r * d + index[r] - 1] = 1.0;
    p.changes_points = !(d == 3 && index == std::vector<int>{1, 2, 3});
    return p;
  }
  if (spec == "pca") {
    const std::size_t n = points.size() / std::max(d, 1);
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> x(points.data(), n, d);
    Eigen::VectorXd mean = n ? Eigen::VectorXd(x.colwise().mean().transpose()) : Eigen::VectorXd::Zero(d);
    Eigen::MatrixXd centred = x.rowwise() - mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(centred.transpose() * centred);
    for (int r = 0; r < std::min(d, 3); ++r) {
      Eigen::VectorXd axis = eig.eigenvectors().col(d - 1 - r);  // eigenvalues ascend
      Eigen::Index big = 0;
      axis.cwiseAbs().maxCoeff(&big);
      if (axis[big] < 0) axis = -axis;
      for (int i = 0; i < d; ++i) p.matrix[r * d + i] = axis[i];
    }
    for (int i = 0; i < d; ++i) p.center[i] = mean[i];
    return p;
  }
  p.matrix = read_projection_file(spec, d);
  return p;
}

namespace {

// The image of each of the n points of R^d in `points` into out[0 .. 3n).
void project_rows(const Projection& p, std::span<const double> points, double* out) {
  const int d = p.d;
  const std::size_t n = points.size() / d;
  std::vector<double> x(d);
  for (std::size_t v = 0; v < n; ++v) {
    for (int i = 0; i < d; ++i) x[i] = points[v * d + i] - p.center[i];
    double scale = 1;
    if (p.stereographic) {  // the line from the pole through x meets the hyperplane at pole + (r/s)(x − pole)
      double s = 0;
      for (int i = 0; i < d; ++i) s -= p.normal[i] * x[i];
      if (!(s > 1e-12 * p.radius))
        throw InputError(
            "--project stereographic: a vertex lies on the pole's side of its tangent hyperplane and has "
            "no image; give another --pole");
      scale = p.radius / s;
    }
    for (int r = 0; r < 3; ++r) {
      double s = 0;
      for (int i = 0; i < d; ++i) s += p.matrix[r * d + i] * x[i];
      out[3 * v + r] = scale * s;
    }
  }
}

}  // namespace

std::vector<double> project_points(const Projection& p, std::span<const double> points) {
  std::vector<double> out(3 * (points.size() / p.d));
  project_rows(p, points, out.data());
  return out;
}

ProjectedVertices::ProjectedVertices(const Projection& p, const CellComplex& cc) {
  const auto negative_zero = [](double x) { return x == 0 && std::signbit(x); };
  if (!p.changes_points && cc.boundary_vertices.empty() && std::ranges::none_of(cc.vertices, negative_zero)) {
    own_ = cc.vertices;
    return;
  }
  // (written in full below: no zeros first, and no copy of the vertices in the global numbering)
  const std::size_t interior = cc.vertices.size() / p.d, boundary = cc.boundary_vertices.size() / p.d;
  copy_ = PointArray(3 * (interior + boundary));
  project_rows(p, cc.vertices, copy_.data());
  project_rows(p, cc.boundary_vertices, copy_.data() + 3 * interior);
}

}  // namespace coxmesh
