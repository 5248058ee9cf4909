// The passes of coreductions in sweeps (betti_shrink.cpp, topology_distributed.cpp): each level's
// cells visited in storage order, passes in increasing dimension repeated until one settles
// nothing. Reading the facet lists in order, one byte per cell, costs several times less than a
// queue of scattered cells with coface lists, for the same cells left. Internal to the cell
// complex layer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace coxmesh {

/// `sizes[l]`: the number of cells of level l, in the order of the passes; `visit(l, a)` makes cell
/// a of level l's move and returns false once no later pass can delete it (it is gone, or stays).
/// A later pass visits only the cells that earlier ones left undecided.
template <class Visit>
void sweep_until_settled(const std::vector<std::uint32_t>& sizes, Visit&& visit) {
  std::vector<std::vector<std::uint32_t>> live(sizes.size());  // (per level)
  // (in the last pass: deleted, or found to stay)
  std::size_t settled = 1;
  for (bool first_pass = true; settled > 0; first_pass = false) {
    settled = 0;
    for (std::size_t l = 0; l < sizes.size(); ++l) {
      std::vector<std::uint32_t>& cells = live[l];
      const std::size_t before = first_pass ? sizes[l] : cells.size();
      if (first_pass) {
        for (std::uint32_t a = 0; a < sizes[l]; ++a)
          if (visit(l, a)) cells.push_back(a);
      } else {
        std::size_t kept = 0;
        for (std::uint32_t a : cells)
          if (visit(l, a)) cells[kept++] = a;
        cells.resize(kept);
      }
      settled += before - cells.size();
    }
  }
}

}  // namespace coxmesh
