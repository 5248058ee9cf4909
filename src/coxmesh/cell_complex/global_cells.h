// All cells of a complex in one numbering, as the topology computations see them: by dimension,
// and within dimension j the interior cells, then the boundary cells.
#pragma once

#include <cstddef>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh {

class GlobalCells {
 public:
  explicit GlobalCells(const CellComplex& cc) : cc_(cc) {
    const int m = cc.manifold_dimension;
    for (int j = 0; j <= m; ++j) {
      start_.push_back(count_);
      count_ += cc.interior[j].size();
      start_.push_back(count_);
      if (j < static_cast<int>(cc.boundary.size())) count_ += cc.boundary[j].size();
    }
    start_.push_back(count_);
  }

  std::size_t count() const { return count_; }
  /// First global id of level j of the given kind; its cells are numbered consecutively.
  std::size_t start(int j, bool boundary) const { return start_[2 * j + boundary]; }
  int manifold_dimension() const { return cc_.manifold_dimension; }
  const CellComplex& complex() const { return cc_; }

  /// Calls f(global id) for every facet of cell `local` of level j (j ≥ 1) of the given kind; an
  /// interior cell cut by the domain also has the boundary cell on its simplex as a facet.
  template <class F>
  void for_each_facet(int j, bool boundary, std::uint32_t local, F&& f) const {
    const CellLevel& level = boundary ? cc_.boundary[j] : cc_.interior[j];
    const std::size_t base = start(j - 1, boundary);
    for (std::uint32_t c : level.facets(local)) f(base + c);
    if (!boundary && !level.boundary_facet.empty() && level.boundary_facet[local] != CellLevel::kNone)
      f(start(j - 1, true) + level.boundary_facet[local]);
  }

  /// The same for a cell given by its global id.
  template <class F>
  void for_each_facet(std::size_t g, F&& f) const {
    std::size_t level = 0;
    while (start_[level + 1] <= g) ++level;  // (2(m + 1) levels: a short scan)
    const int j = static_cast<int>(level / 2);
    if (j > 0) for_each_facet(j, level % 2 == 1, static_cast<std::uint32_t>(g - start_[level]), f);
  }

  /// Dimension of a cell given by its global id.
  int dimension(std::size_t g) const {
    int j = 0;
    while (start_[2 * j + 2] <= g) ++j;
    return j;
  }

 private:
  const CellComplex& cc_;
  std::vector<std::size_t> start_;  // per level (j, kind) in order, then the total
  std::size_t count_ = 0;
};

}  // namespace coxmesh
