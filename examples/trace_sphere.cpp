// Meshes the unit 2-sphere in R^4 (embedded, codimension 2) and prints the topology of the result.
#include <iostream>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

int main() {
  using namespace coxmesh;
  const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.3);
  FunctionPtr f = sphere(/*m=*/2, /*d=*/4, /*radius=*/1.0);
  ImplicitOracle oracle(t, f);
  TraceResult traced = trace_manifold(t, oracle, {f->seed()});
  std::cout << traced.simplices.size() << " triangles of R^4 meet the sphere; " << oracle.function_evaluations()
            << " evaluations of F\n";
  const CellComplex cells = build_cell_complex(std::move(traced));
  const TopologyReport topo = analyze_topology(cells);
  std::cout << "cells: " << topo.cells[0] << " vertices, " << topo.cells[1] << " edges, " << topo.cells[2]
            << " polygons; Euler characteristic " << topo.euler_characteristic << "; Betti " << topo.betti[0] << " "
            << topo.betti[1] << " " << topo.betti[2] << "; manifold: " << (topo.is_manifold ? "yes" : "no") << "\n";
}
