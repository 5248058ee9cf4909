// Thesis §4.3: one lexicographic test per (simplex, stratum), with slack columns for the domains
// the stratum does not lie on.
#include "coxmesh/oracle/stratified_oracle.h"

#include <bit>
#include <cmath>
#include <sstream>

#include "coxmesh/oracle/transversality.h"

namespace coxmesh {

namespace {
constexpr int kMaxRows = 32;  // transversality.h's largest system
}

StratifiedOracle::StratifiedOracle(const Triangulation& triangulation, FunctionPtr f, std::vector<FunctionPtr> domains)
    : triangulation_(triangulation), f_(std::move(f)), domains_(std::move(domains)), vertices_(1) {
  d_ = triangulation_.dimension();
  check_manifold_function(f_, d_);
  k_ = f_->codimension();
  if (domains_.size() > static_cast<std::size_t>(kMaxDomains))
    throw InputError("at most " + std::to_string(kMaxDomains) + " domain functions, got " +
                     std::to_string(domains_.size()));
  for (const FunctionPtr& domain : domains_)
    if (!domain || domain->ambient_dimension() != d_ || domain->codimension() != 1)
      throw InputError("every domain function must map R^" + std::to_string(d_) + " to R");
  stride_ = k_ + static_cast<int>(domains_.size());
  vertices_ = PackedKeyIndex(d_);
}

std::uint32_t StratifiedOracle::vertex_values(const std::int32_t* v) {
  const auto [id, fresh] = vertices_.insert(reinterpret_cast<const std::uint32_t*>(v));
  const std::size_t at = static_cast<std::size_t>(id) * stride_;
  if (fresh) {
    values_.resize(at + stride_);
    double x[kMaxDimension];
    triangulation_.cartesian(v, x);
    f_->evaluate(x, values_.data() + at);
    for (std::size_t l = 0; l < domains_.size(); ++l) domains_[l]->evaluate(x, values_.data() + at + k_ + l);
    for (int i = 0; i < stride_; ++i)
      if (const double value = values_[at + i]; !std::isfinite(value)) {
        std::ostringstream os;
        os.precision(17);
        os << (i < k_ ? "the function" : "domain function " + std::to_string(i - k_ + 1)) << " is not finite (" << value
           << ") at (";
        for (int j = 0; j < d_; ++j) os << (j ? "," : "") << x[j];
        os << ")";
        vertices_.truncate(id);
        values_.resize(at);
        throw EvaluationError(os.str());
      }
  }
  return id;
}

bool StratifiedOracle::meets(const Simplex& nu, std::uint64_t stratum, double* point) {
  ++calls_;
  const int s = std::popcount(stratum), p = domain_count();
  const int corners = nu.k + 1;
  COXMESH_ASSERT(nu.k == k_ + s && (p == kMaxDomains || stratum >> p == 0));
  std::uint32_t ids[kMaxDimension + 1];
  std::int32_t v[kMaxDimension];
  for (int j = 0; j < corners; ++j) {
    nu.vertex(j, v);
    ids[j] = vertex_values(v);
  }
  const double* val[kMaxDimension + 1];  // (after all insertions: the table may move while it grows)
  for (int j = 0; j < corners; ++j) val[j] = values_.data() + static_cast<std::size_t>(ids[j]) * stride_;
  // Rows: 1, F, then the domains in order, each negated (D̂_l = −ε^{k+l} reads −D̂_l = ε^{k+l}).
  // A domain off the stratum with D < 0 at every vertex holds everywhere on ν (its slack is positive
  // whatever ε): left out. One with D ≥ 0 at every vertex excludes ν.
  int rows[kMaxDomains], slack[kMaxDomains], n_rows = 0, n_slack = 0;
  for (int l = 0; l < p; ++l) {
    bool all_negative = true, none_negative = true;
    for (int j = 0; j < corners; ++j) {
      const double x = val[j][k_ + l];
      all_negative &= x < 0, none_negative &= !(x < 0);
    }
    if (stratum >> l & 1) {
      rows[n_rows++] = l;
    } else if (!all_negative) {
      if (none_negative) return false;
      slack[n_slack] = n_rows;
      rows[n_rows++] = l;
      ++n_slack;
    }
  }
  const int n = corners + n_slack;
  if (n > kMaxRows)
    throw InputError("more than " + std::to_string(kMaxRows - 1) +
                     " equations and domain boundaries cross one simplex: too many domain functions for this "
                     "codimension");
  double m[kMaxRows * kMaxRows];  // column-major: the vertices of ν, then the slack columns
  for (int c = 0; c < n; ++c) {
    double* col = m + c * n;
    if (c < corners) {
      col[0] = 1.0;
      for (int i = 0; i < k_; ++i) col[1 + i] = val[c][i];
      for (int r = 0; r < n_rows; ++r) col[1 + k_ + r] = -val[c][k_ + rows[r]];
    } else {
      for (int r = 0; r < n; ++r) col[r] = 0.0;
      col[1 + k_ + slack[c - corners]] = -1.0;  // −D̂_l − t_l = ε^{k+l}
    }
  }
  double lambda[kMaxRows];
  if (!lexicographic_solve(n, m, lambda)) return false;
  double xs[(kMaxDimension + 1) * kMaxDimension];
  triangulation_.vertex_coordinates(nu, xs);
  for (int i = 0; i < d_; ++i) point[i] = 0;
  for (int j = 0; j < corners; ++j)
    for (int i = 0; i < d_; ++i) point[i] += lambda[j] * xs[j * d_ + i];
  return true;
}

}  // namespace coxmesh
