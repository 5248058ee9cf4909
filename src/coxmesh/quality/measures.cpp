// Thesis §2.1 (measures), Def. 1.1.48, §2.3 and §2.5 (Delaunay property and protection).
#include "coxmesh/quality/measures.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "coxmesh/lattice/simplex.h"  // InputError

namespace coxmesh::quality {

namespace {

double factorial(int d) {
  double f = 1;
  for (int k = 2; k <= d; ++k) f *= k;
  return f;
}

// √(R² + x) − R without cancellation.
double sqrt_excess(double radius, double x) { return x / (std::sqrt(radius * radius + x) + radius); }

}  // namespace

SimplexMeasures measure_simplex(const Eigen::MatrixXd& vertices) {
  const int d = static_cast<int>(vertices.cols());
  if (d < 1 || vertices.rows() != d + 1)
    throw InputError("a d-simplex needs (d+1) x d vertex coordinates, got " + std::to_string(vertices.rows()) + "x" +
                     std::to_string(vertices.cols()));
  if (!vertices.allFinite()) throw InputError("a vertex coordinate is NaN or infinite");

  SimplexMeasures m;
  m.dimension = d;
  m.longest_edge = 0;
  m.shortest_edge = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= d; ++i)
    for (int j = i + 1; j <= d; ++j) {
      const double e = (vertices.row(i) - vertices.row(j)).norm();
      m.longest_edge = std::max(m.longest_edge, e);
      m.shortest_edge = std::min(m.shortest_edge, e);
    }

  // Edge matrix E (rows v_i − v_0): barycentric μ = E^{-T}(x − v_0), ∇λ_i = column i−1 of E^{-1}.
  const Eigen::MatrixXd e = vertices.bottomRows(d).rowwise() - vertices.row(0);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(e);
  if (m.shortest_edge <= 0 || !lu.isInvertible() || lu.rcond() < 1e-13)
    throw InputError("the simplex is degenerate (its vertices are affinely dependent)");
  const Eigen::MatrixXd inv = lu.inverse();

  m.heights.resize(d + 1);
  m.heights[0] = 1 / inv.rowwise().sum().norm();
  for (int i = 1; i <= d; ++i) m.heights[i] = 1 / inv.col(i - 1).norm();
  m.min_height = m.heights.minCoeff();

  const Eigen::VectorXd rhs = 0.5 * e.rowwise().squaredNorm();  // 2⟨c − v_0, e_i⟩ = |e_i|²
  const Eigen::VectorXd offset = lu.solve(rhs);
  m.circumcentre = vertices.row(0).transpose() + offset;
  m.circumradius = offset.norm();
  m.circumcentre_barycentric.resize(d + 1);
  const Eigen::VectorXd mu = inv.transpose() * offset;
  m.circumcentre_barycentric[0] = 1 - mu.sum();
  m.circumcentre_barycentric.tail(d) = mu;

  m.inradius = 1 / m.heights.cwiseInverse().sum();  // r·Σ|F_i| = d·vol and h_i = d·vol/|F_i|
  m.volume = std::abs(lu.determinant()) / factorial(d);

  const double L = m.longest_edge;
  m.edge_ratio = L / m.shortest_edge;
  m.thickness = m.min_height / L;
  m.thickness_normalized = m.thickness / d;
  m.radius_ratio = m.inradius / m.circumradius;
  m.fatness = m.volume / std::pow(L, d);
  m.aspect_ratio = m.min_height / m.circumradius;
  return m;
}

SimplexMeasures regular_simplex_measures(int d) {
  if (d < 1) throw InputError("the dimension must be at least 1, got " + std::to_string(d));
  SimplexMeasures m;
  m.dimension = d;
  m.longest_edge = m.shortest_edge = m.edge_ratio = 1;
  m.min_height = std::sqrt((d + 1.0) / (2.0 * d));
  m.heights = Eigen::VectorXd::Constant(d + 1, m.min_height);
  m.circumcentre_barycentric = Eigen::VectorXd::Constant(d + 1, 1.0 / (d + 1));
  m.circumradius = std::sqrt(d / (2.0 * (d + 1)));
  m.inradius = 1 / std::sqrt(2.0 * d * (d + 1));
  m.volume = std::sqrt(d + 1.0) / (factorial(d) * std::pow(2.0, d / 2.0));
  m.thickness = m.min_height;
  m.thickness_normalized = m.min_height / d;
  m.radius_ratio = m.inradius / m.circumradius;
  m.fatness = m.volume;
  m.aspect_ratio = m.min_height / m.circumradius;
  return m;
}

RelativeMeasures relative_to_regular(const SimplexMeasures& m) {
  const SimplexMeasures r = regular_simplex_measures(m.dimension);
  return {m.thickness / r.thickness, m.radius_ratio / r.radius_ratio, m.fatness / r.fatness,
          m.aspect_ratio / r.aspect_ratio};
}

std::string to_string(DelaunayStatus s) {
  switch (s) {
    case DelaunayStatus::yes:
      return "yes";
    case DelaunayStatus::degenerate:
      return "degenerate";
    case DelaunayStatus::no:
      return "no";
  }
  return "?";
}

DelaunayResult delaunay_by_circumcentre(const SimplexMeasures& m, double tol) {
  const double lowest = m.circumcentre_barycentric.minCoeff();
  if (lowest < -tol) return {DelaunayStatus::no, std::nullopt};
  if (lowest <= tol) return {DelaunayStatus::degenerate, 0.0};
  double delta = std::numeric_limits<double>::infinity();
  for (int j = 0; j <= m.dimension; ++j) {
    const double h = m.heights[j];
    delta = std::min(delta, sqrt_excess(m.circumradius, 4 * h * h * m.circumcentre_barycentric[j]));
  }
  return {DelaunayStatus::yes, delta / m.longest_edge};
}

DelaunayResult delaunay_direct(const AlcoveComplex& complex, double tol) {
  const int max_depth = complex.depth.empty() ? 0 : *std::max_element(complex.depth.begin(), complex.depth.end());
  if (max_depth < 1) throw InputError("the direct Delaunay check needs a neighbourhood of depth at least 1");
  const int d = complex.dimension;
  double lowest = std::numeric_limits<double>::infinity();  // min (|q − c| − R)/L
  for (std::size_t a = 0; a < complex.alcove_count(); ++a) {
    if (complex.depth[a] >= max_depth) continue;
    const SimplexMeasures m = measure_simplex(complex.alcove_vertices(a));
    const int* own = complex.alcove_points.data() + a * (d + 1);
    for (std::size_t p = 0; p < complex.point_count(); ++p) {
      if (std::find(own, own + d + 1, static_cast<int>(p)) != own + d + 1) continue;
      const double gap = (complex.point(p) - m.circumcentre).norm() - m.circumradius;
      lowest = std::min(lowest, gap / m.longest_edge);
    }
  }
  if (lowest < -tol) return {DelaunayStatus::no, std::nullopt};
  if (lowest <= tol) return {DelaunayStatus::degenerate, 0.0};
  return {DelaunayStatus::yes, lowest};
}

CoxeterQuality coxeter_quality(Family f, int d, int direct_depth) {
  if (direct_depth < 0) throw InputError("the neighbourhood depth must be non-negative");
  const Alcove alcove = fundamental_alcove(f, d);
  CoxeterQuality q;
  q.family = f;
  q.dimension = d;
  q.measures = measure_simplex(alcove.vertices);
  q.relative = relative_to_regular(q.measures);
  q.delaunay = delaunay_by_circumcentre(q.measures);
  if (direct_depth > 0) q.delaunay_direct = delaunay_direct(generate_by_depth(alcove, direct_depth));
  return q;
}

}  // namespace coxmesh::quality
