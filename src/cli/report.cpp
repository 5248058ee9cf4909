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
  const std::size_t n = cc.interior.empty() ? 0 : cc.interior[0].size();
  const std::size_t nb = cc.boundary.empty() ? 0 : cc.boundary[0].size();
  os << "  traced simplices   " << n << " (" << nb << " on the boundary)\n"
     << "  cells by dimension " << number_list(topo.cells);
  if (nb) os << "  (boundary: " << number_list(topo.boundary_cells) << ")";
  os << "\n";
  if (topo.closed)
    os << "  Euler characteristic " << topo.euler_characteristic << ", Betti numbers (Z/2) " << number_list(topo.betti)
       << "\n  components         " << (topo.betti.empty() ? 0 : topo.betti[0]) << "\n";
  else
    os << "  topology           not computed: " << topo.manifold_problem << "\n";
  os << "  manifold check     " << (topo.is_manifold ? "passed" : "FAILED: " + topo.manifold_problem) << "\n";
}

}  // namespace coxmesh::cli
