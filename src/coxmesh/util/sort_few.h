// Sorting the short lists of one cell (its corners, its edges: a few tens of numbers), where
// std::sort's set-up costs more than the sort.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace coxmesh {

/// Sorts v ascending: by insertion when it is short, by std::sort otherwise.
template <class T>
void sort_few(std::vector<T>& v) {
  if (v.size() > 48) return std::sort(v.begin(), v.end());
  for (std::size_t i = 1; i < v.size(); ++i) {
    const T x = v[i];
    std::size_t j = i;
    for (; j > 0 && x < v[j - 1]; --j) v[j] = v[j - 1];
    v[j] = x;
  }
}

}  // namespace coxmesh
