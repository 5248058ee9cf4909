// Thesis §4.2 (tracing, with boundary) for several domain functions: a breadth-first walk over
// the vertex cells of all strata.
#include "coxmesh/tracing/trace_strata.h"

#include <bit>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/tracing/seed_search.h"

namespace coxmesh {

namespace {

class StrataWalk {
 public:
  StrataWalk(const Triangulation& t, StratifiedOracle& oracle, const TraceOptions& options)
      : t_(t),
        oracle_(oracle),
        options_(options),
        d_(t.dimension()),
        k_(oracle.codimension()),
        m_(d_ - k_),
        p_(oracle.domain_count()),
        tested_(stratum_key_words(d_)) {
    result_.ambient_dimension = d_;
    result_.codimension = k_;
    result_.domain_count = p_;
    result_.vertex_cells = PackedKeyIndex(stratum_key_words(d_));
    point_.resize(d_);
  }

  void add_seed(std::span<const double> seed, bool must_succeed);
  void walk();
  bool stopped() const { return result_.status == TraceStatus::max_simplices_reached; }
  StrataTraceResult finish() {
    result_.oracle_calls = oracle_.calls();
    result_.function_evaluations = oracle_.function_evaluations();
    return std::move(result_);
  }

 private:
  // Tests (ν, J) once; a hit becomes a vertex cell (queued by being appended). True on a hit.
  bool test(const Simplex& nu, std::uint64_t stratum) {
    std::uint32_t key[stratum_key_words(kMaxDimension)];
    pack_stratum_key(nu, stratum, key);
    const std::uint64_t h = hash_words(key, stratum_key_words(d_));
    if (result_.vertex_cells.find(key, h) != PackedKeyIndex::kAbsent) return true;
    if (tested_.find(key, h) != PackedKeyIndex::kAbsent) return false;
    if (oracle_.meets(nu, stratum, point_.data())) {
      result_.vertex_cells.insert(key, h);
      result_.points.insert(result_.points.end(), point_.begin(), point_.end());
      return true;
    }
    tested_.insert(key, h);
    return false;
  }
  // The possible ends of the edge cell (J, μ), μ of dimension k + |J| + 1. The perturbation is
  // generic, so the edge has 0 or 2 ends: the search stops at the second (the first being the
  // vertex the walk came from, when the edge exists).
  void visit_edge(const Simplex& mu, std::uint64_t stratum) {
    int ends = 0;
    for (int j = 0; j <= mu.k && ends < 2; ++j) ends += test(facet_without(mu, j), stratum);
    if (std::popcount(stratum) + 1 > m_) return;
    for (int l = 0; l < p_ && ends < 2; ++l)
      if (!(stratum >> l & 1)) ends += test(mu, stratum | std::uint64_t{1} << l);
  }

  const Triangulation& t_;
  StratifiedOracle& oracle_;
  const TraceOptions& options_;
  const int d_, k_, m_, p_;
  StrataTraceResult result_;
  PackedKeyIndex tested_;  // (ν, J) tested and missed
  std::uint32_t head_ = 0;
  std::vector<double> point_;
};

void StrataWalk::walk() {
  CofaceEnumerator cofacets;
  for (; head_ < result_.vertex_cells.size(); ++head_) {
    if (result_.vertex_cells.size() >= options_.max_simplices) {
      result_.status = TraceStatus::max_simplices_reached;
      return;
    }
    if (options_.progress && options_.progress_interval > 0 && head_ > 0 && head_ % options_.progress_interval == 0)
      options_.progress(head_);
    const std::uint32_t* key = result_.vertex_cells.key(head_);
    const Simplex nu = unpack(key, d_);
    const std::uint64_t stratum = stratum_of_key(key, d_);
    if (nu.k < d_) {
      cofacets.reset(nu, nu.k + 1);
      while (const Simplex* mu = cofacets.next()) visit_edge(*mu, stratum);
    }
    for (int i = 0; i < p_; ++i)
      if (stratum >> i & 1) visit_edge(nu, stratum & ~(std::uint64_t{1} << i));
  }
}

void StrataWalk::add_seed(std::span<const double> seed, bool must_succeed) {
  walk::check_seed_dimension(seed, d_);
  const Simplex sigma = t_.locate(seed);
  walk::SeedRings rings(sigma, d_);
  for (int r = 0; r <= options_.seed_search_rings && !rings.ring().empty(); ++r) {
    bool hit = false;
    for (const Simplex& s : rings.ring()) {
      FaceEnumerator faces(s, k_);
      for (Simplex tau; faces.next(tau);) hit |= test(tau, 0);
      if (k_ < d_) {
        faces.reset(s, k_ + 1);
        for (Simplex mu; faces.next(mu);)
          for (int l = 0; l < p_; ++l) hit |= test(mu, std::uint64_t{1} << l);
      }
    }
    if (hit) return;
    rings.widen();
  }
  if (must_succeed)
    throw SeedError("no simplex within " + std::to_string(options_.seed_search_rings) + " rings of the seed " +
                    walk::point_text(seed) + " meets the manifold inside the domains");
}

}  // namespace

StrataTraceResult trace_strata(const Triangulation& triangulation, StratifiedOracle& oracle,
                               const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  if (oracle.ambient_dimension() != triangulation.dimension())
    throw InputError("the oracle works in R^" + std::to_string(oracle.ambient_dimension()) +
                     " but the triangulation is of R^" + std::to_string(triangulation.dimension()));
  if (seeds.empty()) throw SeedError("no seed given");
  StrataWalk walk(triangulation, oracle, options);
  for (const auto& seed : seeds) {
    if (walk.stopped()) break;
    walk.add_seed(seed, !options.skip_unusable_seeds);
    walk.walk();
  }
  StrataTraceResult result = walk.finish();
  if (result.status == TraceStatus::max_simplices_reached)
    result.message = "stopped at the limit of " + std::to_string(options.max_simplices) +
                     " vertex cells; the manifold may be unbounded (give a domain or a box) or the scale too fine";
  return result;
}

}  // namespace coxmesh
