// Manifolds with corners (several domain functions): every stratum traced, exact counts of
// corners and boundary strata, topology, the manifold-with-corners property, degenerate corners.
#include <gtest/gtest.h>

#include <bit>
#include <map>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/tracing/trace_strata.h"

using namespace coxmesh;

namespace {

struct Traced {
  CellComplex cc;
  TopologyReport topology;
  std::map<std::uint64_t, std::vector<std::size_t>> strata;  // domains → cells per dimension
  std::size_t corners = 0;
};

Traced trace(const Triangulation& t, FunctionPtr f, std::vector<FunctionPtr> domains,
             std::vector<std::vector<double>> seeds) {
  StratifiedOracle oracle(t, f, std::move(domains));
  StrataTraceResult r = trace_strata(t, oracle, seeds);
  EXPECT_EQ(r.status, TraceStatus::complete) << r.message;
  Traced out;
  out.cc = build_stratified_cell_complex(std::move(r));
  out.topology = analyze_topology(out.cc);
  for (const StratumCount& s : stratum_counts(out.cc)) {
    out.strata[s.domains] = s.cells;
    if (s.domains != 0 && s.dimension == 0) out.corners += s.cells[0];
  }
  if (out.topology.closed) {
    EXPECT_EQ(out.topology.betti, betti_numbers_by_reduction(out.cc));
  }
  return out;
}

FunctionPtr half_space(std::vector<double> normal, double c) { return half_space_domain(std::move(normal), c); }

TEST(Strata, DebugEdges) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.2);
  Traced r = trace(t, sphere(2, 3, 1.0), {half_space({-1, 0, 0}, -0.1), half_space({0, -1, 0}, -0.1)},
                   {{0.7, 0.7, 0.1}});
  const CellLevel& edges = r.cc.interior[1];
  for (std::uint32_t e = 0; e < edges.size(); ++e)
    if (edges.facets(e).size() != 2) {
      std::cout << "edge " << unpack(edges.simplices.key(e), 3) << " domains " << edges.domains[e] << ":";
      for (std::uint32_t v : edges.facets(e))
        std::cout << " " << unpack(r.cc.interior[0].simplices.key(v), 3) << "/" << r.cc.interior[0].domains[v];
      std::cout << "\n";
      StratifiedOracle o(t, sphere(2, 3, 1.0), {half_space({-1, 0, 0}, -0.1), half_space({0, -1, 0}, -0.1)});
      const Simplex mu = unpack(edges.simplices.key(e), 3);
      double p[3];
      for (int j = 0; j <= mu.k; ++j) std::cout << " facet " << j << ": " << o.meets(facet_without(mu, j), 0, p);
      for (int l = 0; l < 2; ++l) std::cout << " domain " << l << ": " << o.meets(mu, 1u << l, p);
      std::cout << "\n";
    }
  std::cout << "vertex cells " << r.cc.interior[0].size() << "\n";
  EXPECT_TRUE(r.topology.is_manifold) << r.topology.manifold_problem;
}

}  // namespace
