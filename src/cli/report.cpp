// The topology report shared by trace and check; see report.h.
#include "report.h"

#include <sys/resource.h>

namespace coxmesh::cli {

std::string number_list(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ' ';
    s += std::to_string(v[i]);
  }
  return s;
}

long long peak_memory_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<long long>(usage.ru_maxrss) * 1024;
}

void print_topology(std::ostream& os, const CellComplex& cc, const TopologyReport& topo) {
  const std::size_t n = topo.cells.empty() ? 0 : topo.cells[0];
  const std::size_t nb = topo.boundary_cells.empty() ? 0 : topo.boundary_cells[0];
  os << "  traced simplices   " << n << " (" << nb << " on the boundary)\n"
     << "  cells by dimension " << number_list(topo.cells);
  if (nb) os << "  (boundary: " << number_list(topo.boundary_cells) << ")";
  os << "\n";
  if (cc.stratified()) {
    os << "  strata             ";
    std::size_t corners = 0;
    for (const StratumCount& s : stratum_counts(cc)) {
      os << (s.domains ? "" : "interior ") << "{";
      for (int i = 0, first = 1; i < 64; ++i)
        if (s.domains >> i & 1) os << (first ? "" : ",") << i + 1, first = 0;
      os << "}: " << number_list(s.cells) << "; ";
      if (s.domains && s.dimension == 0) corners += s.cells[0];
    }
    os << corners << " corners\n";
  }
  if (topo.closed)
    os << "  Euler characteristic " << topo.euler_characteristic << ", Betti numbers (Z/2) " << number_list(topo.betti)
       << "\n  components         " << (topo.betti.empty() ? 0 : topo.betti[0]) << "\n";
  else
    os << "  topology           not computed: " << topo.manifold_problem << "\n";
  os << "  manifold check     " << (topo.is_manifold ? "passed" : "FAILED: " + topo.manifold_problem) << "\n";
}

}  // namespace coxmesh::cli
