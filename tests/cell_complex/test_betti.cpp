// Z/2 Betti numbers: the fast computation (collapses and coreductions, then a reduction of what is
// left) against the reference reduction of the whole boundary matrix and against known answers, on
// simplicial complexes written out by hand (non-orientable surfaces, several components, a
// pinched pair of spheres, a complex that is not a manifold) and on traced ones (SO(3) ≅ RP³,
// manifolds with boundary, a truncated run).
#include <gtest/gtest.h>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/oracle/expression_function.h"
#include "simplicial_complexes.h"

using namespace coxmesh;
using namespace coxmesh::hand_written;

namespace {

void expect_betti(const CellComplex& cc, const std::vector<std::size_t>& expected, bool manifold) {
  const TopologyReport report = analyze_topology(cc);
  EXPECT_TRUE(report.closed) << report.manifold_problem;
  EXPECT_EQ(report.is_manifold, manifold) << report.manifold_problem;
  EXPECT_EQ(report.betti, expected);
  EXPECT_EQ(betti_numbers_by_reduction(cc), expected);
  EXPECT_EQ(betti_numbers(cc, false), expected);  // (without the top cells' shortcut)
}

}  // namespace

TEST(Betti, HandWrittenComplexes) {
  {
    SCOPED_TRACE("spheres");
    for (int m = 1; m <= 4; ++m) {
      std::vector<std::size_t> betti(m + 1, 0);
      betti[0] = betti[m] = 1;
      expect_betti(simplicial_complex(sphere_boundary(m, 0)), betti, true);
    }
  }
  {
    SCOPED_TRACE("torus");
    expect_betti(simplicial_complex(glued_grid(false)), {1, 2, 1}, true);
  }
  {
    SCOPED_TRACE("Klein bottle");
    const CellComplex cc = simplicial_complex(glued_grid(true));
    EXPECT_EQ(cc.interior[0].size(), 9u);
    EXPECT_EQ(cc.interior[1].size(), 27u);
    EXPECT_EQ(cc.interior[2].size(), 18u);
    expect_betti(cc, {1, 2, 1}, true);  // (over Z/2 as the torus; χ = 0)
  }
  {
    SCOPED_TRACE("projective plane");
    expect_betti(simplicial_complex(kProjectivePlane), {1, 1, 1}, true);
  }
  {
    SCOPED_TRACE("three components: two 2-spheres and RP²");
    std::vector<Simplex_> rp2 = kProjectivePlane;
    for (Simplex_& s : rp2)
      for (int& v : s) v += 100;
    expect_betti(simplicial_complex(join(join(sphere_boundary(2, 0), sphere_boundary(2, 10)), rp2)), {3, 1, 3}, true);
  }
  {
    SCOPED_TRACE("two 2-spheres sharing a vertex (passes the counting check; one top cell removed for both)");
    expect_betti(simplicial_complex(join(sphere_boundary(2, 0), sphere_boundary(2, 3))), {1, 0, 2}, true);
  }
  {
    SCOPED_TRACE("three triangles on one edge: not a manifold");
    expect_betti(simplicial_complex({{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}), {1, 0, 0}, false);
  }
  {
    SCOPED_TRACE("three 2-spheres glued along a common circle: not a manifold (β₂ = 2)");
    // The suspension of a triangle by three apexes: each pair of cones is a sphere.
    std::vector<Simplex_> top;
    for (int apex : {10, 11, 12})
      for (int i = 0; i < 3; ++i) top.push_back({apex, i, (i + 1) % 3});
    expect_betti(simplicial_complex(top), {1, 0, 2}, false);
  }
}

// On traced complexes: the catalogue of the tracing tests compares the fast numbers with known
// ones; here with the reference reduction, where the answers are less obvious.
TEST(Betti, TracedComplexesAgreeWithTheReference) {
  struct Case {
    const char* name;
    FunctionPtr f, domain;
    Triangulation t;
  };
  const Case cases[] = {
      // (too coarse for RP³'s homology: Betti numbers 1 2 2 1 and 1 21 21 1, a harder test)
      {"SO(3), coarse", rotation_group_so3(), nullptr, Triangulation::coxeter(9).with_longest_edge(2.0)},
      {"SO(3), coarser", rotation_group_so3(), nullptr, Triangulation::coxeter(9).with_longest_edge(2.4)},
      {"S3 in R4 cut by a slab", sphere(3, 4, 1.0), half_space_domain({0.3, 0.1, 0.9, 0.2}, 0.4),
       Triangulation::coxeter(4).with_longest_edge(0.35)},
      {"torus cut in two tubes", torus(1.0, 0.4), half_space_domain({0.1, 1, 0.05}, 0.3),
       Triangulation::coxeter(3).with_longest_edge(0.1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const MeshReport mesh = mesh_manifold(c.t, [&] { return ManifoldFunctions{c.f, c.domain}; }, {});
    const CellComplex& cc = mesh.cells;
    const TopologyReport& report = mesh.topology;
    ASSERT_TRUE(report.is_manifold) << report.manifold_problem;
    EXPECT_EQ(report.betti, betti_numbers_by_reduction(cc));
    EXPECT_EQ(betti_numbers(cc, false), report.betti);
  }
}

TEST(Betti, RotationGroupIsTheRealProjectiveSpace) {  // SO(3) ≅ RP³: Z/2 Betti numbers 1 1 1 1
  const Triangulation t = Triangulation::coxeter(9).with_longest_edge(1.6);
  const FunctionPtr so3 = rotation_group_so3();
  const TopologyReport report = mesh_manifold(t, [&] { return ManifoldFunctions{so3, nullptr}; }, {}).topology;
  EXPECT_TRUE(report.is_manifold) << report.manifold_problem;
  EXPECT_EQ(report.betti, (std::vector<std::size_t>{1, 1, 1, 1}));
}

// Manifolds of dimension 3 and 4, where only the (m−1)-skeleton is reduced after coreductions:
// closed with cells left for the final reduction (T³) or none (S³), two components, with boundary,
// a closed component beside one with boundary, with corners, S⁴, S² × S², and a truncated run.
TEST(Betti, ThreeManifoldsAgreeWithTheReference) {
  struct Case {
    const char* name;
    FunctionPtr f, domain;
    Triangulation t;
    std::vector<std::vector<double>> seeds;
    std::vector<std::size_t> betti;
    std::vector<FunctionPtr> domains = {};
  };
  const Case cases[] = {
      {"T3 in R6",
       expression_function("x1^2+x2^2-1; x3^2+x4^2-1; x5^2+x6^2-1", 6),
       nullptr,
       Triangulation::coxeter(6).with_longest_edge(1.3),
       {},
       {1, 3, 3, 1}},
      {"S3 in R4", sphere(3, 4, 1.0), nullptr, Triangulation::coxeter(4).with_longest_edge(0.4), {}, {1, 0, 0, 1}},
      {"two 3-spheres",
       expression_function("(x^2+y^2+z^2+w^2-1)*((x-3)^2+y^2+z^2+w^2-1)", 4),
       nullptr,
       Triangulation::coxeter(4).with_longest_edge(0.4),
       {{1, 0, 0, 0}, {4, 0, 0, 0}},
       {2, 0, 0, 2}},
      {"T3 in R6 cut by a ball",
       expression_function("x1^2+x2^2-1; x3^2+x4^2-1; x5^2+x6^2-1", 6),
       ball_domain({1, 0, 1, 0, 1, 0}, 0.9),
       Triangulation::coxeter(6).with_longest_edge(0.6),
       {{1, 0, 1, 0, 1, 0}},
       {1, 0, 0, 0}},
      {"a 3-sphere beside one cut in two",
       expression_function("(x^2+y^2+z^2+w^2-1)*((x-3)^2+y^2+z^2+w^2-1)", 4),
       half_space_domain({1, 0.1, 0.05, 0.02}, 3.2),
       Triangulation::coxeter(4).with_longest_edge(0.4),
       {{1, 0, 0, 0}, {2, 0, 0, 0}},
       {2, 0, 0, 1}},
      {"S3 in R4 cut by three half-spaces (corners)",
       sphere(3, 4, 1.0),
       nullptr,
       Triangulation::coxeter(4).with_longest_edge(0.3),
       {{-0.5, -0.5, -0.5, 0.5}},
       {1, 0, 0, 0},
       {half_space_domain({1, 0, 0, 0}, 0), half_space_domain({0, 1, 0, 0}, 0), half_space_domain({0, 0, 1, 0}, 0)}},
      {"S4 in R5", sphere(4, 5, 1.0), nullptr, Triangulation::coxeter(5).with_longest_edge(0.7), {}, {1, 0, 0, 0, 1}},
      {"S2 x S2 in R6 (β_2 from the reduction of the 3-skeleton)",
       expression_function("x1^2+x2^2+x3^2-1; x4^2+x5^2+x6^2-1", 6),
       nullptr,
       Triangulation::coxeter(6).with_longest_edge(1.3),
       {},
       {1, 0, 2, 0, 1}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MeshOptions options;
    options.seeds = c.seeds;
    const MeshReport mesh = mesh_manifold(
        c.t,
        [&] {
          return ManifoldFunctions{c.f, c.domain, c.domains};
        },
        options);
    const CellComplex& cc = mesh.cells;
    const TopologyReport& report = mesh.topology;
    ASSERT_TRUE(report.is_manifold) << report.manifold_problem;
    EXPECT_EQ(report.betti, c.betti);
    EXPECT_EQ(betti_numbers_by_reduction(cc), report.betti);
    EXPECT_EQ(betti_numbers(cc, false), report.betti);
  }
  {
    SCOPED_TRACE("truncated T3 in R6: open, no Betti numbers");
    MeshOptions options;
    options.trace.max_simplices = 2000;
    const FunctionPtr t3 = expression_function("x1^2+x2^2-1; x3^2+x4^2-1; x5^2+x6^2-1", 6);
    const MeshReport mesh = mesh_manifold(
        Triangulation::coxeter(6).with_longest_edge(1.3),
        [&] {
          return ManifoldFunctions{t3, nullptr};
        },
        options);
    EXPECT_NE(mesh.status, TraceStatus::complete);
    EXPECT_FALSE(mesh.topology.closed);
    EXPECT_TRUE(mesh.topology.betti.empty());
  }
}

// The closedness check (∂∂ = 0 on fingerprints of the boundaries) finds a cell whose boundary
// does not close, on every level and kind: a facet swapped for another cell of its level, of an
// interior 2- or 3-cell, of a boundary 2-cell, and the boundary facet of interior cells cut by the
// domain.
TEST(Betti, NoneForACellWhoseBoundaryDoesNotClose) {
  const MeshReport mesh =
      mesh_manifold(Triangulation::coxeter(4).with_longest_edge(0.5),
                    [] {
                      return ManifoldFunctions{sphere(3, 4, 1.0), half_space_domain({0.3, 0.1, 0.9, 0.2}, 0.4)};
                    },
                    {});
  ASSERT_TRUE(mesh.topology.is_manifold) << mesh.topology.manifold_problem;
  const auto swapped = [](std::uint32_t id, std::uint32_t count) { return id + 1 < count ? id + 1 : id - 1; };
  const auto expect_open = [&](const CellComplex& cc, int j, const std::string& what) {
    SCOPED_TRACE(what);
    const TopologyReport report = analyze_topology(cc);
    EXPECT_FALSE(report.closed);
    EXPECT_TRUE(report.betti.empty());
    EXPECT_NE(report.manifold_problem.find("a " + std::to_string(j) + "-cell is not closed"), std::string::npos)
        << report.manifold_problem;
  };
  for (int j : {2, 3}) {
    CellComplex cc = mesh.cells;
    CellLevel& level = cc.interior[j];
    std::uint32_t& facet = level.facet_ids[level.facet_offsets[level.size() / 2]];
    facet = swapped(facet, cc.interior[j - 1].size());
    expect_open(cc, j, "a facet of an interior " + std::to_string(j) + "-cell");
  }
  {
    CellComplex cc = mesh.cells;
    std::uint32_t& facet = cc.boundary[2].facet_ids[0];
    facet = swapped(facet, cc.boundary[1].size());
    expect_open(cc, 3, "a facet of a boundary 2-cell (found first as a face of the interior 3-cell it closes)");
  }
  for (int j : {2, 3}) {
    CellComplex cc = mesh.cells;
    IndexArray& boundary_facet = cc.interior[j].boundary_facet;
    const auto cut = std::find_if(boundary_facet.begin(), boundary_facet.end(),
                                  [](std::uint32_t f) { return f != CellLevel::kNone; });
    ASSERT_NE(cut, boundary_facet.end());
    *cut = swapped(*cut, cc.boundary[j - 1].size());
    expect_open(cc, j, "the boundary facet of an interior " + std::to_string(j) + "-cell");
  }
}
