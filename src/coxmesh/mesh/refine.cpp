// Gauss–Newton refinement of the output vertices onto M; see refine.h.
#include "coxmesh/mesh/refine.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "coxmesh/errors.h"
#include "coxmesh/util/parallel_for.h"

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

class VertexRefiner {
 public:
  VertexRefiner(const ImplicitFunction& f, const ImplicitFunction* domain, double longest_edge,
                const RefineOptions& options)
      : f_(f),
        domain_(domain),
        d_(f.ambient_dimension()),
        k_(f.codimension()),
        limit_(options.max_move * longest_edge),
        step_(1e-5 * longest_edge),
        iterations_(options.iterations) {}

  // Refines x (d coordinates) in place; `on_boundary`: the domain's equation D = 0 too.
  Outcome refine(double* x, bool on_boundary) {
    const int rows = k_ + (on_boundary && domain_ ? 1 : 0);
    Outcome out;
    Vector r(rows), r_new(rows), y(rows);
    Matrix jac(rows, d_), gram(rows, rows);
    Eigen::Map<Eigen::VectorXd> point(x, d_);
    const Vector start = point;
    residual(x, rows, r);
    out.before = r.head(k_).cwiseAbs().maxCoeff();
    if (!r.allFinite()) {
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
        residual(trial.data(), rows, r_new);
        jac.col(j) = r_new;
        trial[j] = current[j] - step_;
        residual(trial.data(), rows, r_new);
        jac.col(j) = (jac.col(j) - r_new) / (2 * step_);
      }
      // The minimum-norm step J⁺r = Jᵀ(JJᵀ)⁻¹r (J has full row rank where 0 is a regular value).
      gram.noalias() = jac * jac.transpose();
      Eigen::LDLT<Matrix> ldlt(gram);
      if (ldlt.info() != Eigen::Success) break;
      y = ldlt.solve(r);
      trial = current - jac.transpose() * y;
      if (!trial.allFinite()) break;
      residual(trial.data(), rows, r_new);
      const double norm_new = r_new.norm();
      if (!(norm_new < norm)) break;  // no further progress (rounding level reached)
      current = trial;
      r = r_new;
      norm = norm_new;
    }
    if ((current - start).norm() > limit_) {
      out.refined = false;
      residual(start.data(), rows, r);
      current = start;
    }
    point = current;
    out.after = r.head(k_).cwiseAbs().maxCoeff();
    return out;
  }

 private:
  void residual(const double* x, int rows, Vector& r) const {
    f_.evaluate(x, r.data());
    if (rows > k_) domain_->evaluate(x, r.data() + k_);
  }

  const ImplicitFunction& f_;
  const ImplicitFunction* domain_;
  const int d_, k_;
  const double limit_, step_;
  const int iterations_;
};

}  // namespace

RefinementReport refine_vertices(CellComplex& cc, double longest_edge, const RefineFunctions& make,
                                 const RefineOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
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
  std::vector<std::pair<FunctionPtr, FunctionPtr>> functions;
  for (int w = 0; w < workers; ++w) functions.push_back(make());
  if (!functions[0].first || functions[0].first->ambient_dimension() != d)
    throw InputError("refinement: the function and the complex must live in the same R^d");
  std::vector<VertexRefiner> refiners;
  for (const auto& fd : functions) refiners.emplace_back(*fd.first, fd.second.get(), longest_edge, options);
  struct ChunkResult {
    double before = 0, after = 0;
    std::size_t not_refined = 0;
  };
  std::vector<ChunkResult> results(chunks);
  WorkerPool pool(workers);
  pool.run(chunks, [&](std::size_t c, int worker) {
    ChunkResult& res = results[c];
    for (std::size_t v = c * kChunk; v < std::min(n, (c + 1) * kChunk); ++v) {
      const bool boundary = v >= n0;
      double* x = boundary ? cc.boundary_vertices.data() + (v - n0) * d : cc.vertices.data() + v * d;
      const Outcome o = refiners[worker].refine(x, boundary);
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
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace coxmesh
