// Shared by the GUDHI cross-checks and the benchmarks: conversions between GUDHI's
// Permutahedral_representation and coxmesh::Simplex, and random simplices.
#pragma once

#include <gudhi/Permutahedral_representation.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "coxmesh/lattice/simplex.h"

namespace gudhi_interop {

/// GUDHI's default simplex type (Freudenthal_triangulation<>::Simplex_handle).
using GudhiSimplex =
    Gudhi::coxeter_triangulation::Permutahedral_representation<std::vector<int>, std::vector<std::vector<std::size_t>>>;

template <class G>
coxmesh::Simplex from_gudhi(const G& g) {
  std::vector<std::int32_t> y(g.vertex().begin(), g.vertex().end());
  std::vector<std::vector<int>> blocks;
  for (const auto& part : g.partition()) {
    std::vector<int> b(part.begin(), part.end());
    std::sort(b.begin(), b.end());  // GUDHI's parts are not sorted in general
    blocks.push_back(std::move(b));
  }
  return coxmesh::Simplex::from_partition(y, blocks);
}

inline GudhiSimplex to_gudhi(const coxmesh::Simplex& s) {
  GudhiSimplex g;
  g.vertex().assign(s.y.begin(), s.y.begin() + s.d);
  for (const auto& b : s.partition()) g.partition().emplace_back(b.begin(), b.end());
  return g;
}

/// A random k-simplex: y uniform in [-coord, coord]^d and a random ordered partition of {0..d}
/// into k+1 blocks with d in the last block.
inline coxmesh::Simplex random_simplex(std::mt19937_64& rng, int d, int k, int coord = 5) {
  std::vector<int> perm(d + 1);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<int> label(d + 1);
  std::uniform_int_distribution<int> any_block(0, k);
  for (int j = 0; j <= d; ++j) label[perm[j]] = j <= k ? j : any_block(rng);
  const int last = label[d];
  for (int& b : label) b = b == last ? k : (b == k ? last : b);  // swap labels: d's block goes last
  std::vector<std::vector<int>> blocks(k + 1);
  for (int i = 0; i <= d; ++i) blocks[label[i]].push_back(i);
  std::uniform_int_distribution<std::int32_t> coordinate(-coord, coord);
  std::vector<std::int32_t> y(d);
  for (auto& v : y) v = coordinate(rng);
  return coxmesh::Simplex::from_partition(y, blocks);
}

}  // namespace gudhi_interop
