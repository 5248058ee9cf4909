// Thesis §4.3; spec §2.2 (tracing) and §2.3 (boundary). The one hot loop of coxmesh.
#include "coxmesh/tracing/trace_manifold.h"

#include <cmath>
#include <sstream>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"

namespace coxmesh {

bool Box::contains(const double* x) const {
  for (std::size_t i = 0; i < lo.size(); ++i)
    if (!(x[i] >= lo[i] && x[i] <= hi[i])) return false;
  return true;
}

namespace {

std::string point_text(std::span<const double> x) {
  std::ostringstream os;
  os.precision(10);
  os << "(";
  for (std::size_t i = 0; i < x.size(); ++i) os << (i ? "," : "") << x[i];
  os << ")";
  return os.str();
}

// Tracing state: S lives in the result; every other tested k-simplex is remembered in `others_`
// (not transverse, outside the box, or transverse outside the domain with its point), so the
// oracle sees each k-simplex at most once.
class Tracer {
 public:
  Tracer(const Triangulation& t, IntersectionOracle& oracle, const TraceOptions& options)
      : t_(t), oracle_(oracle), options_(options), d_(t.dimension()), k_(oracle.codimension()),
        others_(packed_words(d_)) {
    result_.ambient_dimension = d_;
    result_.codimension = k_;
    result_.simplices = PackedKeyIndex(packed_words(d_));
    result_.boundary_simplices = PackedKeyIndex(packed_words(d_));
  }

  void add_seed(std::span<const double> seed, bool must_succeed);
  void walk();
  TraceResult finish() {
    result_.function_evaluations = oracle_.function_evaluations();
    return std::move(result_);
  }

 private:
  enum class Kind { miss, inside, outside };
  struct Found {
    Kind kind;
    std::uint32_t index;  // S id (inside) or outside-point index
  };
  static constexpr std::uint32_t kMiss = 0xFFFFFFFFu, kOutsideBox = 0xFFFFFFFEu;

  Found classify(const Simplex& tau);
  void add_boundary(const Simplex& mu, std::uint32_t inside, std::uint32_t outside);

  const Triangulation& t_;
  IntersectionOracle& oracle_;
  const TraceOptions& options_;
  const int d_, k_;
  TraceResult result_;
  std::vector<double> domain_values_;  // D̂ at each point of S
  PackedKeyIndex others_;
  std::vector<std::uint32_t> other_payload_;  // kMiss, kOutsideBox or index into outside_
  std::vector<double> outside_;               // (d + 1) per transverse simplex outside: point, D̂
  std::uint32_t head_ = 0;                    // S[head_..] is the breadth-first queue
  std::vector<double> point_;
};

Tracer::Found Tracer::classify(const Simplex& tau) {
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  const std::uint64_t h = hash_words(key, packed_words(d_));
  if (std::uint32_t id = result_.simplices.find(key, h); id != PackedKeyIndex::kAbsent) return {Kind::inside, id};
  if (std::uint32_t id = others_.find(key, h); id != PackedKeyIndex::kAbsent) {
    const std::uint32_t p = other_payload_[id];
    return p >= kOutsideBox ? Found{Kind::miss, 0} : Found{Kind::outside, p};
  }
  ++result_.oracle_calls;
  point_.resize(d_);
  const Intersection x = oracle_.intersect(tau, point_.data());
  std::uint32_t payload = kMiss;
  if (x.hit) {
    if (options_.box && !options_.box->contains(point_.data())) {
      payload = kOutsideBox;
      result_.status = TraceStatus::box_reached;
    } else if (x.domain < 0) {
      const std::uint32_t id = result_.simplices.insert(key, h).first;
      result_.points.insert(result_.points.end(), point_.begin(), point_.end());
      domain_values_.push_back(x.domain);
      return {Kind::inside, id};
    } else {
      payload = static_cast<std::uint32_t>(outside_.size() / (d_ + 1));
      outside_.insert(outside_.end(), point_.begin(), point_.end());
      outside_.push_back(x.domain);
    }
  }
  others_.insert(key, h);
  other_payload_.push_back(payload);
  return payload >= kOutsideBox ? Found{Kind::miss, 0} : Found{Kind::outside, payload};
}

// μ ∩ M̂ is the segment between the points of its two transverse facets; D̂ is linear on it, so the
// boundary point is where it crosses 0.
void Tracer::add_boundary(const Simplex& mu, std::uint32_t inside, std::uint32_t outside) {
  if (!result_.boundary_simplices.insert(mu).second) return;
  const double* p = result_.points.data() + static_cast<std::size_t>(inside) * d_;
  const double* q = outside_.data() + static_cast<std::size_t>(outside) * (d_ + 1);
  const double dp = domain_values_[inside], dq = q[d_];
  const double t = dp / (dp - dq);  // dp < 0 ≤ dq
  for (int i = 0; i < d_; ++i) result_.boundary_points.push_back(p[i] + t * (q[i] - p[i]));
}

void Tracer::walk() {
  Simplex tau, mu, facet;
  CofaceEnumerator cofacets;
  FaceEnumerator facets;
  for (; head_ < result_.simplices.size(); ++head_) {
    if (result_.simplices.size() >= options_.max_simplices) {
      result_.status = TraceStatus::max_simplices_reached;
      return;
    }
    tau = result_.simplices.simplex(head_, d_);
    cofacets.reset(tau, k_ + 1);
    while (cofacets.next(mu)) {
      facets.reset(mu, k_);
      while (facets.next(facet)) {
        if (facet == tau) continue;
        const Found f = classify(facet);
        if (f.kind == Kind::outside) add_boundary(mu, head_, f.index);
      }
    }
  }
}

void Tracer::add_seed(std::span<const double> seed, bool must_succeed) {
  if (static_cast<int>(seed.size()) != d_)
    throw InputError("the seed " + point_text(seed) + " has " + std::to_string(seed.size()) +
                     " coordinates, expected " + std::to_string(d_));
  const Simplex sigma = t_.locate(seed);
  // Ring 0: the d-simplices containing the seed; ring r+1: their neighbours across facets.
  PackedKeyIndex seen(packed_words(d_));
  std::vector<Simplex> ring, next;
  CofaceEnumerator cofaces(sigma, d_);
  for (Simplex s; cofaces.next(s);)
    if (seen.insert(s).second) ring.push_back(s);
  bool outside_hit = false;
  for (int r = 0; r <= options_.seed_search_rings && !ring.empty(); ++r) {
    bool inside_hit = false;
    for (const Simplex& s : ring) {
      FaceEnumerator faces(s, k_);
      for (Simplex tau; faces.next(tau);) {
        const Found f = classify(tau);
        inside_hit |= f.kind == Kind::inside;
        outside_hit |= f.kind == Kind::outside;
      }
    }
    if (inside_hit) return;
    next.clear();
    for (const Simplex& s : ring) {
      FaceEnumerator faces(s, d_ - 1);
      for (Simplex f; faces.next(f);) {
        CofaceEnumerator across(f, d_);
        for (Simplex n; across.next(n);)
          if (seen.insert(n).second) next.push_back(n);
      }
    }
    ring.swap(next);
  }
  if (!must_succeed) return;
  if (outside_hit)
    throw SeedError("the seed " + point_text(seed) + " is outside the domain: the manifold near it has D >= 0");
  throw SeedError("no simplex within " + std::to_string(options_.seed_search_rings) + " rings of the seed " +
                  point_text(seed) +
                  " meets the manifold: the seed is too far from it, or the triangulation is too coarse for it");
}

}  // namespace

TraceResult trace_manifold(const Triangulation& triangulation, IntersectionOracle& oracle,
                           const std::vector<std::vector<double>>& seeds, const TraceOptions& options) {
  const int d = triangulation.dimension();
  if (oracle.ambient_dimension() != d)
    throw InputError("the oracle works in R^" + std::to_string(oracle.ambient_dimension()) +
                     " but the triangulation is of R^" + std::to_string(d));
  if (options.box && (static_cast<int>(options.box->lo.size()) != d || static_cast<int>(options.box->hi.size()) != d))
    throw InputError("the box must have " + std::to_string(d) + " coordinates per corner");
  if (seeds.empty()) throw SeedError("no seed given");
  Tracer tracer(triangulation, oracle, options);
  for (const auto& seed : seeds) {
    tracer.add_seed(seed, !options.skip_unusable_seeds);
    tracer.walk();
  }
  TraceResult result = tracer.finish();
  if (result.status == TraceStatus::max_simplices_reached)
    result.message = "stopped at the limit of " + std::to_string(options.max_simplices) +
                     " simplices; the manifold may be unbounded (give a domain or a box) or the scale too fine";
  else if (result.status == TraceStatus::box_reached)
    result.message = "the manifold leaves the bounding box; the output is cut there";
  return result;
}

}  // namespace coxmesh
