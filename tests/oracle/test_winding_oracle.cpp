// The winding oracle (tracing/normal_winding_oracle.h): surfaces in R⁴ whose normal bundle is not
// orientable, which no per-vertex function can mesh, from samples with fixed generator seeds, clean
// and noisy. Every tetrahedron next to the trace must see an even number of hit facets, the cell
// complex must pass the manifold check, and the Z/2 Betti numbers must be those of RP² (1 1 1,
// χ = 1) and of the Klein bottle (1 2 1, χ = 0), the same for any number of threads.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "coxmesh/mesh/mesh_winding.h"
#include "coxmesh/tracing/normal_winding_oracle.h"
#include "point_samples.h"

using namespace coxmesh;

namespace {

struct Outcome {
  PointCloudDiagnostics diagnostics;
  WindingMeshResult result;
};

Outcome mesh(const test::Samples& s, int threads = 1) {
  PointCloudOptions po;
  po.threads = threads;
  PointCloudProblem p = make_point_cloud_problem(s.points, s.d, s.m, po);
  const Triangulation t = Triangulation::coxeter(s.d).with_longest_edge(p.edge_length);
  TraceOptions to;
  to.threads = threads;
  return {p.diagnostics, mesh_normal_winding(t, p, to)};
}

struct Case {
  const char* name;
  std::size_t n;
  double noise;
  std::vector<std::size_t> betti;
};

class NonOrientable : public ::testing::TestWithParam<Case> {};

TEST_P(NonOrientable, RightTopology) {
  const Case& c = GetParam();
  const Outcome o = mesh(test::sample_manifold(c.name, c.n, c.noise));
  EXPECT_TRUE(o.diagnostics.frames_inconsistent);
  EXPECT_EQ(o.result.status, TraceStatus::complete);
  EXPECT_EQ(o.result.odd_tetrahedra, 0u);
  EXPECT_TRUE(o.result.topology.is_manifold) << o.result.topology.manifold_problem;
  EXPECT_EQ(o.result.topology.betti, c.betti);
  std::cout << c.name << " " << c.n << " noise " << c.noise << ": uncertain " << o.result.uncertain_triangles
            << ", trace " << o.result.trace_seconds << " s\n";
}

INSTANTIATE_TEST_SUITE_P(PointClouds, NonOrientable,
                         ::testing::Values(Case{"rp2", 2000, 0, {1, 1, 1}}, Case{"rp2", 2000, 0.01, {1, 1, 1}},
                                           Case{"rp2", 10000, 0, {1, 1, 1}}, Case{"klein", 2000, 0, {1, 2, 1}},
                                           Case{"klein", 2000, 0.01, {1, 2, 1}}, Case{"klein", 10000, 0.01, {1, 2, 1}}),
                         [](const auto& info) {
                           return std::string(info.param.name) + "_" + std::to_string(info.param.n) +
                                  (info.param.noise > 0 ? "_noisy" : "_clean");
                         });

}  // namespace
