// Gauss–Newton refinement of the output vertices onto M; see refine.h.
#include "coxmesh/mesh/refine.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/errors.h"
#include "coxmesh/util/parallel_for.h"
#include "coxmesh/util/stopwatch.h"

namespace coxmesh {

namespace {

// Fixed-capacity matrices: on the stack, no allocation per vertex (d ≤ 31, at most d rows).
constexpr int kMax = 32;
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMax, kMax>;
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMax, 1>;

struct Outcome {
  double before = 0, after = 0;  // max |F| at the vertex
  bool refined = true;
};

// At most kMax − 1 equations per vertex: F's k and one per domain of its stratum (k + |J| ≤ d).
class VertexRefiner {
 public:
  VertexRefiner(const RefineSet& functions, double longest_edge, const RefineOptions& options)
      : f_(*functions.f),
        d_(f_.ambient_dimension()),
        k_(f_.codimension()),
        limit_(options.max_move * longest_edge),
        step_(1e-5 * longest_edge),
        iterations_(options.iterations) {
    for (const FunctionPtr& domain : functions.domains) domains_.push_back(domain.get());
  }

  // Refines x (d coordinates) in place onto F = 0 and D_i = 0 for the bits i of `stratum`, keeping
  // D_l < 0 for the others.
  Outcome refine(double* x, std::uint64_t stratum) {
    on_.clear();
    for (std::size_t i = 0; i < domains_.size(); ++i)
      if (stratum >> i & 1) on_.push_back(domains_[i]);
    // (more equations than unknowns: not a generic stratum; r then keeps F's rows only, unmoved)
    const bool generic = k_ + static_cast<int>(on_.size()) <= d_;
    if (!generic) on_.clear();
    const int rows = k_ + static_cast<int>(on_.size());
    Outcome out;
    Vector r(rows), r_new(rows), y(rows);
    Matrix jac(rows, d_), gram(rows, rows);
    Eigen::Map<Eigen::VectorXd> point(x, d_);
    const Vector start = point;
    residual(x, r);
    out.before = r.head(k_).cwiseAbs().maxCoeff();
    if (!generic || !r.allFinite()) {
      out.after = out.before;
      out.refined = false;
      return out;
    }
    Vector current = start, trial(d_);
    double norm = r.norm();
    for (int it = 0; it < iterations_ && norm > 0; ++it) {
      for (int j = 0; j < d_; ++j) {  // central differences
        trial = current;
        trial[j] += step_;
        residual(trial.data(), r_new);
        jac.col(j) = r_new;
        trial[j] = current[j] - step_;
        residual(trial.data(), r_new);
        jac.col(j) = (jac.col(j) - r_new) / (2 * step_);
      }
      // The minimum-norm step J⁺r = Jᵀ(JJᵀ)⁻¹r (J has full row rank where 0 is a regular value).
      gram.noalias() = jac * jac.transpose();
      Eigen::LDLT<Matrix> ldlt(gram);
      if (ldlt.info() != Eigen::Success) break;
      y = ldlt.solve(r);
      trial = current - jac.transpose() * y;
      if (!trial.allFinite()) break;
      residual(trial.data(), r_new);
      const double norm_new = r_new.norm();
      if (!(norm_new < norm)) break;  // no further progress (rounding level reached)
      current = trial;
      r = r_new;
      norm = norm_new;
    }
    if ((current - start).norm() > limit_ || !stays_inside_the_others(start.data(), current.data(), stratum)) {
      out.refined = false;
      residual(start.data(), r);
      current = start;
    }
    point = current;
    out.after = r.head(k_).cwiseAbs().maxCoeff();
    return out;
  }

 private:
  void residual(const double* x, Vector& r) const {
    f_.evaluate(x, r.data());
    for (std::size_t i = 0; i < on_.size(); ++i) on_[i]->evaluate(x, r.data() + k_ + i);
  }

  // For every domain l the vertex does not lie on: D_l(to) < 0, the moved point inside it, or at
  // least no farther out than `from` (a vertex traced inside only by the symbolic perturbation,
  // from D_l = 0, may stay on D_l = 0).
  bool stays_inside_the_others(const double* from, const double* to, std::uint64_t stratum) const {
    for (std::size_t l = 0; l < domains_.size(); ++l) {
      if (stratum >> l & 1) continue;
      double after = 0, before = 0;
      domains_[l]->evaluate(to, &after);
      if (after < 0) continue;
      domains_[l]->evaluate(from, &before);
      if (!(after <= before)) return false;
    }
    return true;
  }

  const ImplicitFunction& f_;
  std::vector<const ImplicitFunction*> domains_, on_;
  const int d_, k_;
  const double limit_, step_;
  const int iterations_;
};

// Bit i: the vertex lies on D_i = 0 (see RefineSet).
std::uint64_t stratum_of(const CellComplex& cc, std::size_t v, std::size_t interior_vertices) {
  if (cc.stratified()) return cc.interior[0].domains[v];
  return v >= interior_vertices ? 1 : 0;
}

}  // namespace

RefinementReport refine_vertices(CellComplex& cc, double longest_edge, const RefineFunctions& make,
                                 const RefineOptions& options) {
  const auto t0 = Clock::now();
  const int d = cc.ambient_dimension;
  if (d > kMax - 1) throw InputError("refinement: d must be at most 31");
  const std::size_t n0 = cc.vertices.size() / std::max(d, 1), nb = cc.boundary_vertices.size() / std::max(d, 1);
  RefinementReport report;
  report.vertices = n0 + nb;
  const std::size_t n = n0 + nb;
  constexpr std::size_t kChunk = 2048;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const int workers =
      static_cast<int>(std::min<std::size_t>(resolve_threads(options.threads), std::max<std::size_t>(chunks, 1)));
  // Each worker its own functions (made here, in one thread).
  std::vector<RefineSet> functions;
  for (int w = 0; w < workers; ++w) functions.push_back(make());
  if (!functions[0].f || functions[0].f->ambient_dimension() != d)
    throw InputError("refinement: the function and the complex must live in the same R^d");
  std::uint64_t named = 0;  // the domains the vertices lie on
  for (std::size_t v = 0; v < n; ++v) named |= stratum_of(cc, v, n0);
  const std::size_t domains = functions[0].domains.size();
  if (domains < 64 && named >> domains != 0)
    throw InputError("refinement: a vertex lies on the boundary of domain " + std::to_string(std::bit_width(named)) +
                     ", but only " + std::to_string(domains) + " domain functions are given");
  for (const RefineSet& set : functions)
    for (const FunctionPtr& domain : set.domains)
      if (!domain || domain->ambient_dimension() != d || domain->codimension() != 1)
        throw InputError("refinement: every domain function must be a real function on the same R^d");
  std::vector<VertexRefiner> refiners;
  for (const RefineSet& set : functions) refiners.emplace_back(set, longest_edge, options);
  struct ChunkResult {
    double before = 0, after = 0;
    std::size_t not_refined = 0;
  };
  std::vector<ChunkResult> results(chunks);
  WorkerPool pool(workers);
  pool.run(chunks, [&](std::size_t c, int worker) {
    ChunkResult& res = results[c];
    for (std::size_t v = c * kChunk; v < std::min(n, (c + 1) * kChunk); ++v) {
      double* x = v >= n0 ? cc.boundary_vertices.data() + (v - n0) * d : cc.vertices.data() + v * d;
      const Outcome o = refiners[worker].refine(x, stratum_of(cc, v, n0));
      res.before = std::max(res.before, o.before);
      res.after = std::max(res.after, o.after);
      res.not_refined += o.refined ? 0 : 1;
    }
  });
  for (const ChunkResult& res : results) {
    report.max_abs_f_before = std::max(report.max_abs_f_before, res.before);
    report.max_abs_f_after = std::max(report.max_abs_f_after, res.after);
    report.not_refined += res.not_refined;
  }
  report.seconds = seconds_since(t0);
  return report;
}

}  // namespace coxmesh
