// Disjoint sets of 0..n−1 (union–find with path halving); the root of a set is its smallest
// member, so results do not depend on the order of the unions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh {

struct UnionFind {
  HugeVector<std::uint32_t> parent;  // (big blocks: huge_page_allocator.h)

  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  /// Joins the sets of a and b; false when they were one set already.
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[std::max(a, b)] = std::min(a, b);
    return true;
  }
};

}  // namespace coxmesh
