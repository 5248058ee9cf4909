// refine_vertices on a manifold with corners: each vertex lands on M and on the boundary of the
// domains of its stratum, inside the others; the corners land on the exact corners; the complex and
// its topology stay; the result does not depend on the thread count.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/mesh/mesh_manifold.h"

using namespace coxmesh;

namespace {

// The part x > c_0, y > c_1, z > c_2 of the unit sphere, D_i = c_i − x_i (c = 0: the octant),
// traced with or without refinement.
MeshReport octant(double edge, bool refine, int threads, std::array<double, 3> c = {0, 0, 0},
                  const Triangulation* triangulation = nullptr) {
  MeshOptions options;
  options.seeds = {{0.577, 0.577, 0.577}};
  options.refine = refine;
  options.trace.threads = threads;
  return mesh_manifold(
      triangulation ? *triangulation : Triangulation::coxeter(3).with_longest_edge(edge).rotated(3),
      [c] {
        return ManifoldFunctions{sphere(2, 3, 1.0),
                                 nullptr,
                                 {half_space_domain({-1, 0, 0}, -c[0]), half_space_domain({0, -1, 0}, -c[1]),
                                  half_space_domain({0, 0, -1}, -c[2])}};
      },
      options);
}

// Distance of x to the closed octant patch: its nearest point is x/|x| with the negative
// coordinates of x set to 0 first (the patch's nearest boundary arc or corner).
double distance_to_patch(const double* x) {
  double q[3], norm = 0;
  for (int i = 0; i < 3; ++i) q[i] = std::max(x[i], 0.0), norm += q[i] * q[i];
  norm = std::sqrt(norm);
  return std::hypot(x[0] - q[0] / norm, x[1] - q[1] / norm, x[2] - q[2] / norm);
}

double max_vertex_distance(const CellComplex& cc) {
  double m = 0;
  for (std::size_t v = 0; v < cc.vertices.size() / 3; ++v) m = std::max(m, distance_to_patch(&cc.vertices[3 * v]));
  return m;
}

}  // namespace

TEST(RefineCorners, SphereOctantVerticesLandOnTheirStrata) {
  const MeshReport plain = octant(0.1, false, 1), refined = octant(0.1, true, 1);
  ASSERT_TRUE(refined.refinement.has_value());
  const RefinementReport& r = *refined.refinement;
  const CellComplex& cc = refined.cells;
  ASSERT_TRUE(cc.stratified());
  EXPECT_EQ(r.vertices, cc.vertices.size() / 3);
  EXPECT_EQ(r.not_refined, 0u);
  EXPECT_GT(r.max_abs_f_before, 1e-4);
  EXPECT_LE(r.max_abs_f_after, 1e-10 * r.max_abs_f_before);
  std::size_t corners = 0;
  for (std::size_t v = 0; v < r.vertices; ++v) {
    const double* x = &cc.vertices[3 * v];
    const std::uint64_t stratum = cc.interior[0].domains[v];
    EXPECT_LE(std::abs(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1), 1e-10 * r.max_abs_f_before) << v;
    for (int i = 0; i < 3; ++i) {
      if (stratum >> i & 1) {
        EXPECT_LE(std::abs(x[i]), 1e-10) << v << " on D_" << i + 1;
      } else {
        EXPECT_GT(x[i], 0) << v << " inside D_" << i + 1;
      }
    }
    if (std::popcount(stratum) == 2) {  // the corner where x_i is 1 and the two others vanish
      ++corners;
      const int one = std::countr_zero(~stratum & 7);
      EXPECT_NEAR(x[one], 1.0, 1e-10) << v;
    }
  }
  EXPECT_EQ(corners, 3u);
  // The vertices much closer to the exact patch (the triangles between them still sag, O(h²)); the
  // same complex, strata and topology.
  const double before = max_vertex_distance(plain.cells), after = max_vertex_distance(cc);
  EXPECT_GT(before, 1e-4);
  EXPECT_LE(after, before / 10);
  EXPECT_EQ(cc.interior[0].domains, plain.cells.interior[0].domains);
  ASSERT_EQ(cc.interior.size(), plain.cells.interior.size());
  for (std::size_t j = 0; j < cc.interior.size(); ++j)
    EXPECT_EQ(cc.interior[j].facet_ids, plain.cells.interior[j].facet_ids);
  EXPECT_EQ(refined.topology.betti, plain.topology.betti);
  EXPECT_EQ(refined.topology.euler_characteristic, 1);
}

// Planes off the sphere's centre (projecting radially onto the sphere would leave them): the
// vertices of each stratum land on its planes, the corners at (c_i, c_j, √(1 − c_i² − c_j²)).
TEST(RefineCorners, FacesOffTheCentreKeepTheirVertices) {
  const std::array<double, 3> c = {0.3, 0.2, 0.1};
  const MeshReport refined = octant(0.1, true, 1, c);
  const CellComplex& cc = refined.cells;
  EXPECT_EQ(refined.refinement->not_refined, 0u);
  std::size_t corners = 0;
  for (std::size_t v = 0; v < cc.vertices.size() / 3; ++v) {
    const double* x = &cc.vertices[3 * v];
    const std::uint64_t stratum = cc.interior[0].domains[v];
    EXPECT_LE(std::abs(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1), 1e-12) << v;
    for (int i = 0; i < 3; ++i) {
      if (stratum >> i & 1) {
        EXPECT_LE(std::abs(x[i] - c[i]), 1e-10) << v << " on D_" << i + 1;
      } else {
        EXPECT_GT(x[i], c[i]) << v << " inside D_" << i + 1;
      }
    }
    if (std::popcount(stratum) == 2) {
      ++corners;
      const int free = std::countr_zero(~stratum & 7);
      EXPECT_NEAR(x[free], std::sqrt(1 - c[(free + 1) % 3] * c[(free + 1) % 3] - c[(free + 2) % 3] * c[(free + 2) % 3]),
                  1e-10)
          << v;
    }
  }
  EXPECT_EQ(corners, 3u);
}

TEST(RefineCorners, SameResultForOneAndTwoThreads) {
  // (more than one chunk of vertices: both workers refine some)
  const MeshReport one = octant(0.03, true, 1), two = octant(0.03, true, 2);
  ASSERT_GT(one.cells.vertices.size() / 3, 4096u);
  EXPECT_EQ(one.cells.vertices, two.cells.vertices);  // bitwise
  EXPECT_EQ(one.refinement->max_abs_f_after, two.refinement->max_abs_f_after);
  EXPECT_EQ(one.refinement->not_refined, two.refinement->not_refined);
  EXPECT_LE(max_vertex_distance(one.cells), 1e-12);
}

// A vertex whose step would leave another domain stays where it was and is counted. The vertices
// lie inside the unit ball (F is convex: the chords cross 0 before it); a fourth domain
// |x|² < 1 − 10⁻⁶ holds most of them but no point of the sphere.
TEST(RefineCorners, StepsLeavingAnotherDomainAreRefused) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.1).rotated(3);
  CellComplex cc = octant(0.1, false, 1).cells;
  const PointArray original = cc.vertices;
  const RefinementReport r = refine_vertices(cc, t.longest_edge(), [] {
    const FunctionPtr ball = make_function(
        3, 1, [](const double* x, double* v) { v[0] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - (1 - 1e-6); });
    return RefineSet{
        sphere(2, 3, 1.0),
        {half_space_domain({-1, 0, 0}, 0), half_space_domain({0, -1, 0}, 0), half_space_domain({0, 0, -1}, 0), ball}};
  });
  std::size_t inside = 0;  // those stay, bitwise; a vertex already outside may move back towards it
  for (std::size_t v = 0; v < original.size() / 3; ++v) {
    const double* x = &original[3 * v];
    if (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] >= 1 - 1e-6) continue;
    ++inside;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(cc.vertices[3 * v + i], x[i]) << v;
  }
  EXPECT_GT(inside, r.vertices / 2);
  EXPECT_GE(r.not_refined, inside);
  EXPECT_EQ(r.max_abs_f_after, r.max_abs_f_before);
}

// Freudenthal–Kuhn at scale 1/10 has lattice vertices all over the planes x_i = 0: vertices traced
// inside a domain only by the symbolic perturbation start on its boundary, and may stay on it.
TEST(RefineCorners, VerticesOnAPlaneOnlyByThePerturbationAreRefinedToo) {
  const Triangulation t = Triangulation::freudenthal(3).scaled(0.1);
  const MeshReport r = octant(0, true, 1, {0, 0, 0}, &t);
  std::size_t on_a_plane = 0;
  for (std::size_t v = 0; v < r.cells.vertices.size() / 3; ++v) {
    const double* x = &r.cells.vertices[3 * v];
    const std::uint64_t stratum = r.cells.interior[0].domains[v];
    for (int i = 0; i < 3; ++i) on_a_plane += !(stratum >> i & 1) && x[i] == 0 ? 1 : 0;
  }
  EXPECT_GT(on_a_plane, 0u);
  EXPECT_EQ(r.refinement->not_refined, 0u);
  EXPECT_LE(r.refinement->max_abs_f_after, 1e-12);
}

// A stratum naming a domain that is not given: one clear error.
TEST(RefineCorners, MissingDomainFunctionsAreAnError) {
  CellComplex cc = octant(0.2, false, 1).cells;
  EXPECT_THROW(refine_vertices(cc, 0.2,
                               [] {
                                 return RefineSet{sphere(2, 3, 1.0), {half_space_domain({-1, 0, 0}, 0)}};
                               }),
               InputError);
}
