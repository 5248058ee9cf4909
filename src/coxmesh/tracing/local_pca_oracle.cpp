// The local-PCA oracle of the thesis prototype (thesis Ch. 4) and the defect count.
#include "coxmesh/tracing/local_pca_oracle.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/lattice/packed_index.h"

namespace coxmesh {

namespace {

constexpr int kMax = kMaxDimension;
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;  // k + 1 ≤ d ≤ kMax
// The same cap on a neighbourhood as the frames of the per-vertex functions (sample_frames.h).
constexpr int kMaxNeighbours = 64;

}  // namespace

LocalPcaOracle::LocalPcaOracle(const Triangulation& triangulation, std::shared_ptr<const SampleModel> model, int m,
                               double radius, FunctionPtr domain)
    : t_(triangulation),
      model_(std::move(model)),
      domain_(std::move(domain)),
      d_(triangulation.dimension()),
      k_(d_ - m),
      m_(m),
      radius2_(radius * radius) {
  if (!model_ || model_->tree->dimension() != d_)
    throw InputError("the samples and the triangulation must live in the same R^d");
  if (m < 1 || m >= d_) throw InputError("the manifold dimension m must be between 1 and d − 1");
  if (!(radius > 0)) throw InputError("the neighbourhood radius must be positive");
  if (domain_ && (domain_->ambient_dimension() != d_ || domain_->codimension() != 1))
    throw InputError("the domain must be one function of R^" + std::to_string(d_));
  vertices_.resize(static_cast<std::size_t>(d_ + 1) * d_);
  const int cap = std::max(kMaxNeighbours, m + 2);
  index_.resize(cap);
  distance2_.resize(cap);
}

// GCC 12 reports Eigen's eigenvector storage (fixed maximum size, dynamic size) as maybe
// uninitialised after the solver has written it: a false positive of the inlined solver.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
Intersection LocalPcaOracle::intersect(const Simplex& tau, double* point) {
  ++evaluations_;
  const SampleTree& tree = *model_->tree;
  const int d = d_, k = k_;
  t_.vertex_coordinates(tau, vertices_.data());
  double b[kMax];
  for (int t = 0; t < d; ++t) {
    double s = 0;
    for (int j = 0; j <= k; ++j) s += vertices_[j * d + t];
    b[t] = s / (k + 1);
  }
  // The neighbourhood of b: within the radius, or the m + 2 nearest when fewer (a plane's worth
  // and one more, so that the PCA is defined).
  int count = tree.nearest_within(b, radius2_, static_cast<int>(index_.size()), index_.data(), distance2_.data());
  if (count < m_ + 2)
    count = tree.nearest_within(b, std::numeric_limits<double>::infinity(), m_ + 2, index_.data(), distance2_.data());
  LocalVector mean(d);
  LocalSquare cov(d, d);
  local_scatter(tree, index_.data(), count, mean, cov);
  Eigen::SelfAdjointEigenSolver<Square> eig(cov, Eigen::ComputeEigenvectors);  // reads the lower triangle
  const double* q = tree.point(index_[0]);                                     // nearest first

  // A = [1 … 1; F_τ(v_0) … F_τ(v_k)], F_τ(x) = Uᵀ(x − q); the first k eigenvectors span U. The
  // solution λ does not depend on the basis chosen for U, so the frames need no orientation.
  Square a(k + 1, k + 1);
  for (int j = 0; j <= k; ++j) {
    a(0, j) = 1;
    for (int r = 0; r < k; ++r) {
      double s = 0;
      for (int t = 0; t < d; ++t) s += eig.eigenvectors()(t, r) * (vertices_[j * d + t] - q[t]);
      a(r + 1, j) = s;
    }
  }
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> e0(k + 1);
  e0.setZero();
  e0[0] = 1;
  Eigen::FullPivLU<Square> lu(a);
  Intersection out;
  if (!lu.isInvertible()) return out;  // F_τ degenerate on τ: no transverse crossing
  const auto lambda = lu.solve(e0).eval();
  for (int j = 0; j <= k; ++j)
    if (!(lambda[j] >= 0)) return out;
  for (int t = 0; t < d; ++t) {
    double s = 0;
    for (int j = 0; j <= k; ++j) s += lambda[j] * vertices_[j * d + t];
    point[t] = s;
  }
  out.hit = true;
  if (domain_) domain_->evaluate(point, &out.domain);
  return out;
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

std::size_t count_defects(const TraceResult& traced, IntersectionOracle& oracle) {
  const int d = traced.ambient_dimension, k = traced.codimension;
  PackedKeyIndex seen_cofacets(packed_words(d)), tested(packed_words(d));
  std::vector<char> hit;  // by id in `tested`
  double point[kMaxDimension];
  std::size_t defects = 0;
  for (std::uint32_t id = 0; id < traced.simplices.size(); ++id) {
    CofaceEnumerator cofacets(traced.simplices.simplex(id, d), k + 1);
    while (const Simplex* mu = cofacets.next()) {
      if (!seen_cofacets.insert(*mu).second) continue;
      int crossed = 0;
      for (int j = 0; j <= k + 1; ++j) {
        const Simplex facet = facet_without(*mu, j);
        const auto [fid, is_new] = tested.insert(facet);
        if (is_new) hit.push_back(oracle.intersect(facet, point).hit ? 1 : 0);
        crossed += hit[fid];
      }
      if (crossed % 2) ++defects;
    }
  }
  return defects;
}

}  // namespace coxmesh
