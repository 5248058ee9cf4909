// Projection of R^d points to R³ for the 3D formats; see projection.h.
#include "coxmesh/io/projection.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
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

}  // namespace

Projection make_projection(const std::string& spec, int d, std::span<const double> points) {
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

std::vector<double> project_points(const Projection& p, std::span<const double> points) {
  const int d = p.d;
  const std::size_t n = points.size() / d;
  std::vector<double> out(3 * n);
  std::vector<double> x(d);
  for (std::size_t v = 0; v < n; ++v) {
    for (int i = 0; i < d; ++i) x[i] = points[v * d + i] - p.center[i];
    for (int r = 0; r < 3; ++r) {
      double s = 0;
      for (int i = 0; i < d; ++i) s += p.matrix[r * d + i] * x[i];
      out[3 * v + r] = s;
    }
  }
  return out;
}

}  // namespace coxmesh
