// Manifolds with corners (several domain functions): every stratum traced; exact counts of corners
// and boundary strata, χ and Z/2 Betti numbers, the manifold-with-corners property (also at
// corners on lattice vertices), one result for any number of threads, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <set>

#include "coxmesh/cell_complex/betti.h"
#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/tracing/trace_strata.h"

using namespace coxmesh;

namespace {

struct Traced {
  CellComplex cc;
  TopologyReport topology;
  std::map<std::uint64_t, std::vector<std::size_t>> strata;  // domains → cells per dimension
  std::size_t corners = 0;
};

// The same complex, numbering included (keys, bitmasks, facets, points).
void expect_same_complex(const CellComplex& a, const CellComplex& b) {
  ASSERT_EQ(a.interior.size(), b.interior.size());
  for (std::size_t j = 0; j < a.interior.size(); ++j) {
    const CellLevel &x = a.interior[j], &y = b.interior[j];
    ASSERT_EQ(x.size(), y.size()) << j;
    if (x.size() > 0) {
      EXPECT_TRUE(
          std::equal(x.simplices.key(0), x.simplices.key(0) + x.size() * x.simplices.words(), y.simplices.key(0)));
    }
    EXPECT_EQ(x.domains, y.domains) << j;
    EXPECT_EQ(x.facet_ids, y.facet_ids) << j;
  }
  EXPECT_EQ(a.vertices, b.vertices);
}

// Through the whole pipeline, with 1 and 2 threads (the same result).
Traced trace(const Triangulation& t, FunctionPtr f, std::vector<FunctionPtr> domains,
             std::vector<std::vector<double>> seeds) {
  const auto run = [&](int threads) {
    MeshOptions o;
    o.seeds = seeds;
    o.trace.threads = threads;
    return mesh_manifold(
        t,
        [&] {
          return ManifoldFunctions{f, nullptr, domains};
        },
        o);
  };
  MeshReport one = run(1);
  const MeshReport two = run(2);
  EXPECT_EQ(one.status, TraceStatus::complete) << one.message;
  expect_same_complex(one.cells, two.cells);
  EXPECT_EQ(one.topology.betti, two.topology.betti);
  Traced out;
  out.cc = std::move(one.cells);
  out.topology = one.topology;
  for (const StratumCount& s : stratum_counts(out.cc)) {
    out.strata[s.domains] = s.cells;
    if (s.domains != 0 && s.dimension == 0) out.corners += s.cells[0];
  }
  EXPECT_TRUE(out.topology.is_manifold) << out.topology.manifold_problem;
  if (out.topology.closed) {
    EXPECT_EQ(out.topology.betti, betti_numbers_by_reduction(out.cc));
  }
  return out;
}

// χ of the (open) stratum: cells of even dimension minus cells of odd dimension.
long long stratum_euler(const std::vector<std::size_t>& cells) {
  long long chi = 0;
  for (std::size_t j = 0; j < cells.size(); ++j) chi += (j % 2 ? -1LL : 1LL) * static_cast<long long>(cells[j]);
  return chi;
}

// Number of strata of each dimension (the interior included).
std::map<int, int> strata_by_dimension(const Traced& r) {
  std::map<int, int> n;
  for (const auto& [domains, cells] : r.strata) ++n[static_cast<int>(cells.size()) - 1];
  return n;
}

// The link of every corner (a vertex cell on m domain boundaries) of a surface: one edge cell along
// each of its two faces, and one 2-cell holding both (a corner of a polygon, not a fold or a fan).
void expect_corner_links(const CellComplex& cc) {
  ASSERT_EQ(cc.manifold_dimension, 2);
  const CellLevel &v = cc.interior[0], &e = cc.interior[1], &f = cc.interior[2];
  std::map<std::uint32_t, std::vector<std::uint32_t>> edges_at;  // corner → its edge cells
  for (std::uint32_t c = 0; c < e.size(); ++c)
    for (std::uint32_t x : e.facets(c))
      if (std::popcount(v.domains[x]) == 2) edges_at[x].push_back(c);
  std::size_t corners = 0;
  for (std::uint32_t x = 0; x < v.size(); ++x) {
    if (std::popcount(v.domains[x]) != 2) continue;
    ++corners;
    const std::vector<std::uint32_t>& at = edges_at[x];
    ASSERT_EQ(at.size(), 2u) << "corner " << x;
    EXPECT_EQ(e.domains[at[0]] | e.domains[at[1]], v.domains[x]);
    EXPECT_EQ(std::popcount(e.domains[at[0]]), 1);
    EXPECT_EQ(std::popcount(e.domains[at[1]]), 1);
    int holding_both = 0;
    for (std::uint32_t c = 0; c < f.size(); ++c) {
      const auto facets = f.facets(c);
      const bool a = std::find(facets.begin(), facets.end(), at[0]) != facets.end();
      const bool b = std::find(facets.begin(), facets.end(), at[1]) != facets.end();
      holding_both += a && b;
    }
    EXPECT_EQ(holding_both, 1) << "corner " << x;
  }
  EXPECT_GT(corners, 0u);
}

FunctionPtr half_space(std::vector<double> normal, double c) { return half_space_domain(std::move(normal), c); }

// The octant x, y, z > 0 of the unit sphere: a disk bounded by three arcs meeting at three corners.
TEST(Strata, SphereOctantHasThreeCornersAndThreeArcs) {
  for (const Triangulation& t : {Triangulation::coxeter(3).with_longest_edge(0.15).rotated(3),
                                 Triangulation::freudenthal(3).scaled(0.1)}) {  // corners on lattice vertices
    const Traced r =
        trace(t, sphere(2, 3, 1.0), {half_space({-1, 0, 0}, 0), half_space({0, -1, 0}, 0), half_space({0, 0, -1}, 0)},
              {{0.577, 0.577, 0.577}});
    EXPECT_EQ(r.corners, 3u);
    EXPECT_EQ(r.strata.size(), 7u);  // interior, 3 arcs, 3 corners
    EXPECT_EQ((strata_by_dimension(r)), (std::map<int, int>{{0, 3}, {1, 3}, {2, 1}}));
    for (std::uint64_t face : {1u, 2u, 4u}) EXPECT_EQ(stratum_euler(r.strata.at(face)), -1) << face;  // open arcs
    for (std::uint64_t corner : {3u, 5u, 6u}) EXPECT_EQ(r.strata.at(corner), std::vector<std::size_t>{1});
    EXPECT_EQ(r.topology.euler_characteristic, 1);
    EXPECT_EQ(r.topology.betti, (std::vector<std::size_t>{1, 0, 0}));
    expect_corner_links(r.cc);
  }
}

// Degenerate corners: the plane z = 0 cut by x < 0, y < 0 and the unit disk, on the unshifted
// lattices: the corner (0, 0, 0) is a lattice vertex where F and two domain functions all vanish.
TEST(Strata, CornersOnLatticeVerticesStillMakeAManifoldWithCorners) {
  const FunctionPtr plane = make_function(3, 1, [](const double* x, double* v) { v[0] = x[2]; });
  const FunctionPtr disk =
      make_function(3, 1, [](const double* x, double* v) { v[0] = x[0] * x[0] + x[1] * x[1] - 1; });
  for (const Triangulation& t :
       {Triangulation::coxeter(3).with_longest_edge(0.1), Triangulation::freudenthal(3).scaled(0.125)}) {
    const Traced r = trace(t, plane, {half_space({1, 0, 0}, 0), half_space({0, 1, 0}, 0), disk}, {{-0.5, -0.5, 0}});
    EXPECT_EQ(r.corners, 3u);
    EXPECT_EQ((strata_by_dimension(r)), (std::map<int, int>{{0, 3}, {1, 3}, {2, 1}}));
    EXPECT_EQ(r.topology.euler_characteristic, 1);
    EXPECT_EQ(r.topology.betti, (std::vector<std::size_t>{1, 0, 0}));
    expect_corner_links(r.cc);
  }
}

// The torus (R = 1, r = 0.4) cut by x < 0.3 and z < 0.1: the two planes meet on the line
// x = 0.3, z = 0.1, which crosses the torus at 4 points, the corners.
TEST(Strata, TorusCutByTwoPlanes) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.08).rotated(5);
  const Traced r = trace(t, torus(1.0, 0.4), {half_space({1, 0, 0}, 0.3), half_space({0, 0, 1}, 0.1)}, {{-1.4, 0, 0}});
  EXPECT_EQ(r.corners, 4u);
  EXPECT_EQ((strata_by_dimension(r)), (std::map<int, int>{{0, 1}, {1, 2}, {2, 1}}));
  EXPECT_TRUE(r.topology.closed);
  expect_corner_links(r.cc);
  // x > 0 and y > 0 instead: the planes meet on the axis, off the torus. A quarter of the torus is
  // an annulus: no corner, two circles (one per plane).
  const Traced q = trace(t, torus(1.0, 0.4), {half_space({-1, 0, 0}, 0), half_space({0, -1, 0}, 0)}, {{0.99, 0.99, 0}});
  EXPECT_EQ(q.corners, 0u);
  EXPECT_EQ(q.strata.size(), 3u);
  for (std::uint64_t face : {1u, 2u}) EXPECT_EQ(stratum_euler(q.strata.at(face)), 0) << face;  // circles
  EXPECT_EQ(q.topology.euler_characteristic, 0);
  EXPECT_EQ(q.topology.betti, (std::vector<std::size_t>{1, 1, 0}));
}

// A solid cube: the 3-plane w = 0 of R^4 cut by |x|, |y|, |z| < 1/2 (six domains): 8 corners,
// 12 edges, 6 faces, a 3-ball.
TEST(Strata, CubeIsABallWithEightCornersTwelveEdgesSixFaces) {
  const FunctionPtr hyperplane = make_function(4, 1, [](const double* x, double* v) { v[0] = x[3]; });
  std::vector<FunctionPtr> faces;
  for (int i = 0; i < 3; ++i)
    for (double s : {1.0, -1.0}) {
      std::vector<double> n(4, 0.0);
      n[i] = s;
      faces.push_back(half_space(n, 0.5));
    }
  const Traced r =
      trace(Triangulation::coxeter(4).with_longest_edge(0.2).rotated(1), hyperplane, faces, {{0, 0, 0, 0}});
  EXPECT_EQ(r.corners, 8u);
  EXPECT_EQ((strata_by_dimension(r)), (std::map<int, int>{{0, 8}, {1, 12}, {2, 6}, {3, 1}}));
  for (const auto& [domains, cells] : r.strata)
    EXPECT_EQ(stratum_euler(cells), static_cast<long long>(cells.size() % 2 ? 1 : -1)) << domains;  // open cells
  EXPECT_EQ(r.topology.euler_characteristic, 1);
  EXPECT_EQ(r.topology.betti, (std::vector<std::size_t>{1, 0, 0, 0}));
}

// S³ ⊂ R^4 cut by the box |x_i| < 0.55 (eight domains). The sphere lies outside the box along the
// axes and inside it near the 16 diagonals (±1/2, …, ±1/2): 16 solid tetrahedra, one per seed,
// each bounded by 4 faces. Corners: three coordinates ±0.55 and the fourth ±0.304, 4·8·2 = 64 of
// them, on 32 sets of three domains; 24 pairs of domains meet in 4 arcs each; each of the 8
// faces holds 8 triangles.
TEST(Strata, ThreeSphereCutByABox) {
  std::vector<FunctionPtr> faces;
  for (int i = 0; i < 4; ++i)
    for (double s : {1.0, -1.0}) {
      std::vector<double> n(4, 0.0);
      n[i] = s;
      faces.push_back(half_space(n, 0.55));
    }
  std::vector<std::vector<double>> seeds;
  for (int signs = 0; signs < 16; ++signs) {
    seeds.emplace_back();
    for (int i = 0; i < 4; ++i) seeds.back().push_back(signs >> i & 1 ? -0.5 : 0.5);
  }
  const Traced r = trace(Triangulation::coxeter(4).with_longest_edge(0.12).rotated(2), sphere(3, 4, 1.0), faces, seeds);
  EXPECT_EQ(r.corners, 64u);
  EXPECT_EQ((strata_by_dimension(r)), (std::map<int, int>{{0, 32}, {1, 24}, {2, 8}, {3, 1}}));
  for (const auto& [domains, cells] : r.strata) {
    const long long expected = cells.size() == 1 ? 2 : cells.size() == 2 ? -4 : cells.size() == 3 ? 8 : -16;
    EXPECT_EQ(stratum_euler(cells), expected) << domains;  // 2 corners, 4 open arcs, 8 open triangles, 16 open balls
  }
  EXPECT_EQ(r.topology.euler_characteristic, 16);
  EXPECT_EQ(r.topology.betti, (std::vector<std::size_t>{16, 0, 0, 0}));
}

// Brute force: every (simplex, stratum) of the lattice around the octant of the sphere, each face of
// every d-simplex within [−1.5, 1.5]³ with every set of domains of the right size, asked to a fresh
// oracle: exactly the vertex cells the walk found.
TEST(Strata, WalkFindsEveryVertexCellOfTheBruteForce) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.3).rotated(7);
  const FunctionPtr f = sphere(2, 3, 1.0);
  const std::vector<FunctionPtr> domains = {half_space({-1, 0, 0}, 0), half_space({0, -1, 0}, 0),
                                            half_space({0, 0, -1}, 0)};
  StratifiedOracle walked(t, f, domains);
  const StrataTraceResult r = trace_strata(t, walked, {{0.577, 0.577, 0.577}});
  std::set<std::vector<std::uint32_t>> traced;
  for (std::uint32_t c = 0; c < r.vertex_cells.size(); ++c)
    traced.emplace(r.vertex_cells.key(c), r.vertex_cells.key(c) + stratum_key_words(3));

  StratifiedOracle fresh(t, f, domains);
  std::set<std::vector<std::uint32_t>> found;
  PackedKeyIndex seen(packed_words(3));
  std::vector<Simplex> queue;
  const auto inside_box = [&](const Simplex& s) {
    double xs[4 * 3];
    t.vertex_coordinates(s, xs);
    return std::all_of(xs, xs + 12, [](double x) { return std::abs(x) <= 1.5; });
  };
  CofaceEnumerator start(t.locate(std::vector<double>{0.1, 0.2, 0.3}), 3);
  for (Simplex s; start.next(s);)
    if (seen.insert(s).second) queue.push_back(s);
  double point[3];
  std::uint32_t key[stratum_key_words(3)];
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const Simplex sigma = queue[q];
    for (int dim = 1; dim <= 3; ++dim) {  // k = 1: strata of 0, 1, 2 domains
      FaceEnumerator faces(sigma, dim);
      for (Simplex nu; faces.next(nu);)
        for (std::uint64_t stratum = 0; stratum < 8; ++stratum)
          if (std::popcount(stratum) == dim - 1 && fresh.meets(nu, stratum, point)) {
            pack_stratum_key(nu, stratum, key);
            found.emplace(key, key + stratum_key_words(3));
          }
    }
    FaceEnumerator facets(sigma, 2);
    for (Simplex facet; facets.next(facet);) {
      CofaceEnumerator across(facet, 3);
      for (Simplex n; across.next(n);)
        if (inside_box(n) && seen.insert(n).second) queue.push_back(n);
    }
  }
  EXPECT_GT(queue.size(), 1000u);
  EXPECT_GT(traced.size(), 50u);
  EXPECT_EQ(found.size(), traced.size());
  EXPECT_TRUE(found == traced);
}

TEST(Strata, BadInput) {
  const Triangulation t = Triangulation::coxeter(3);
  EXPECT_THROW(StratifiedOracle(t, sphere(2, 3, 1.0), std::vector<FunctionPtr>(65, half_space({1, 0, 0}, 0))),
               InputError);
  EXPECT_THROW(StratifiedOracle(t, sphere(2, 3, 1.0), {half_space({1, 0}, 0)}), InputError);
  EXPECT_THROW(StratifiedOracle(t, sphere(2, 3, 1.0), {nullptr}), InputError);
  StratifiedOracle oracle(t.with_longest_edge(0.2), sphere(2, 3, 1.0),
                          {half_space({1, 0, 0}, 0), half_space({0, 1, 0}, 0)});
  EXPECT_THROW(trace_strata(t.with_longest_edge(0.2), oracle, {{5, 5, 5}}), SeedError);
}

}  // namespace
