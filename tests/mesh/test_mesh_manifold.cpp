// mesh_manifold: the one-call pipeline gives what its steps give by hand, bounds the walk by the box
// as a domain, reports no topology for an open complex, and says when 0 is not a regular value.
#include <gtest/gtest.h>

#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/implicit_oracle.h"

using namespace coxmesh;

namespace {

ManifoldMaker maker(FunctionPtr f, FunctionPtr domain = nullptr) {
  return [f, domain] { return ManifoldFunctions{f, domain}; };
}

}  // namespace

TEST(MeshManifold, EqualsItsStepsByHand) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.15);
  const FunctionPtr f = torus(1.0, 0.4);
  MeshOptions options;
  options.seeds = {f->seed()};
  const MeshReport r = mesh_manifold(t, maker(f), options);
  ImplicitOracle oracle(t, f);
  const CellComplex by_hand = build_cell_complex(trace_manifold(t, oracle, {f->seed()}));
  for (int j = 0; j <= 2; ++j) EXPECT_EQ(r.cells.interior[j].size(), by_hand.interior[j].size());
  EXPECT_EQ(r.topology.betti, (std::vector<std::size_t>{1, 2, 1}));
  EXPECT_EQ(r.function_evaluations, oracle.function_evaluations());
  EXPECT_TRUE(r.warnings.empty());
  // Any number of threads, one worker's functions each: the same complex.
  options.trace.threads = 2;
  const MeshReport two = mesh_manifold(t, maker(f), options);
  EXPECT_EQ(two.cells.interior[2].size(), r.cells.interior[2].size());
  EXPECT_EQ(two.function_evaluations, r.function_evaluations);
}

TEST(MeshManifold, TheBoxIsADomainAndALimitLeavesNoTopology) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1);
  const FunctionPtr genus2 = expression_function("(x*(x-1)^2*(x-2)+y^2)^2+z^2-0.01");
  MeshOptions options;  // automatic seeds in the default box [-2, 2]^3, which the surface leaves
  options.bounded_by_box = true;
  const MeshReport cut = mesh_manifold(t, maker(genus2), options);
  EXPECT_TRUE(cut.topology.is_manifold) << cut.topology.manifold_problem;
  EXPECT_EQ(cut.topology.betti, (std::vector<std::size_t>{1, 4, 0}));
  options.bounded_by_box = false;
  options.seeds = {{0, 0.1, 0}};
  EXPECT_EQ(mesh_manifold(t, maker(genus2), options).topology.betti, (std::vector<std::size_t>{1, 4, 1}));
  options.trace.max_simplices = 200;
  const MeshReport stopped = mesh_manifold(t, maker(genus2), options);
  EXPECT_EQ(stopped.status, TraceStatus::max_simplices_reached);
  EXPECT_FALSE(stopped.topology.closed);
  EXPECT_TRUE(stopped.topology.betti.empty());
  // The memory limit stops it too, and says so.
  options.trace.max_simplices = 20'000'000;
  options.max_memory = 300 * estimated_bytes_per_simplex(2);
  const MeshReport small = mesh_manifold(t, maker(genus2), options);
  EXPECT_EQ(small.status, TraceStatus::max_simplices_reached);
  EXPECT_NE(small.message.find("memory limit"), std::string::npos) << small.message;
}

TEST(MeshManifold, SaysWhenZeroIsNotARegularValue) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1);
  MeshOptions options;
  options.bounded_by_box = true;
  const MeshReport square = mesh_manifold(t, maker(expression_function("(x^2+y^2+z^2-1)^2")), options);
  ASSERT_EQ(square.warnings.size(), 1u);
  EXPECT_NE(square.warnings[0].find("singular"), std::string::npos);
  const FunctionPtr s2 = sphere(2, 3, 1.0);
  const MeshReport tangent = mesh_manifold(t, maker(s2, s2), options);
  EXPECT_FALSE(tangent.warnings.empty());
  EXPECT_THROW(mesh_manifold(t, maker(expression_function("x^2+y^2+z^2-1; 2*x^2+2*y^2+2*z^2-2")), options), InputError);
}

// Work done while the topology is computed (writing a file, in the command line) sees the final
// mesh, and the report is the one computed without it, for one and for two threads.
TEST(MeshManifold, WorkWhileTheTopologyIsComputed) {
  const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.45);
  const ManifoldMaker make = [] { return ManifoldFunctions{sphere(3, 4, 1.0), nullptr}; };
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    MeshOptions options;
    options.trace.threads = threads;
    const MeshReport plain = mesh_manifold(t, make, options);
    std::size_t seen_cells = 0;
    const MeshReport with = mesh_manifold(t, make, options, [&](const MeshReport& r) {
      for (const CellLevel& level : r.cells.interior) seen_cells += level.size();
    });
    std::size_t cells = 0;
    for (const CellLevel& level : plain.cells.interior) cells += level.size();
    EXPECT_EQ(seen_cells, cells);
    EXPECT_EQ(with.topology.betti, plain.topology.betti);
    EXPECT_EQ(with.topology.betti, (std::vector<std::size_t>{1, 0, 0, 1}));
    EXPECT_EQ(with.topology.is_manifold, plain.topology.is_manifold);
    // An error in that work reaches the caller once the topology's thread has finished.
    EXPECT_THROW(mesh_manifold(t, make, options, [](const MeshReport&) { throw InputError("cannot write"); }),
                 InputError);
  }
}
