// What every walk's seed search shares (the sequential, distributed and stratified walks): the
// rings of d-simplices it widens through, and how a seed is named in messages. Internal to tracing.
#pragma once

#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "coxmesh/errors.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/lattice/packed_index.h"
#include "coxmesh/lattice/simplex.h"

namespace coxmesh::walk {

/// Ring 0: the d-simplices containing the seed's simplex σ, at most kFirstRing of them (a seed on a
/// lattice vertex lies in (d+1)! of them, 3.6 million for d = 9); ring r + 1: the neighbours of
/// ring r across facets, none met twice.
class SeedRings {
 public:
  static constexpr std::size_t kFirstRing = 720;

  SeedRings(const Simplex& sigma, int d) : d_(d), seen_(packed_words(d)) {
    CofaceEnumerator cofaces(sigma, d);
    for (Simplex s; ring_.size() < kFirstRing && cofaces.next(s);)
      if (seen_.insert(s).second) ring_.push_back(s);
  }

  const std::vector<Simplex>& ring() const { return ring_; }

  void widen() {
    next_.clear();
    for (const Simplex& s : ring_) {
      FaceEnumerator faces(s, d_ - 1);
      for (Simplex f; faces.next(f);) {
        CofaceEnumerator across(f, d_);
        for (Simplex n; across.next(n);)
          if (seen_.insert(n).second) next_.push_back(n);
      }
    }
    ring_.swap(next_);
  }

 private:
  int d_;
  PackedKeyIndex seen_;
  std::vector<Simplex> ring_, next_;
};

/// "(x1,...,xd)" with 10 significant digits, for messages about a seed.
inline std::string point_text(std::span<const double> x) {
  std::ostringstream os;
  os.precision(10);
  os << "(";
  for (std::size_t i = 0; i < x.size(); ++i) os << (i ? "," : "") << x[i];
  os << ")";
  return os.str();
}

/// Throws InputError unless the seed has d coordinates.
inline void check_seed_dimension(std::span<const double> seed, int d) {
  if (static_cast<int>(seed.size()) != d)
    throw InputError("the seed " + point_text(seed) + " has " + std::to_string(seed.size()) +
                     " coordinates, expected " + std::to_string(d));
}

/// The seed search of the one-domain walks found nothing: the seed's component lies outside the
/// domain (a transverse simplex was met, outside), or no simplex within `rings` meets M.
[[noreturn]] inline void throw_seed_not_found(std::span<const double> seed, bool outside_hit, int rings) {
  if (outside_hit)
    throw SeedError("the seed " + point_text(seed) + " is outside the domain: the manifold near it has D >= 0");
  throw SeedError("no simplex within " + std::to_string(rings) + " rings of the seed " + point_text(seed) +
                  " meets the manifold: the seed is too far from it, or the triangulation is too coarse for it");
}

}  // namespace coxmesh::walk
