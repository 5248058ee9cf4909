// Triangulation: the Ã_d closed form (thesis §3.1), point location examples computed with GUDHI, barycentric
// coordinates, vertex coordinates, longest edges, and input validation.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "coxmesh/lattice/faces.h"
#include "coxmesh/triangulation/triangulation.h"

using namespace coxmesh;

namespace {
Simplex locate(const Triangulation& t, std::vector<double> x) { return t.locate(x); }
std::string loc(const Triangulation& t, std::vector<double> x) { return to_string(t.locate(x)); }

// GUDHI's Eigen-computed Ã_d matrices (thesis §3.1), which differ from the sine form by row signs.
Eigen::MatrixXd gudhi_matrix(int d) {
  Eigen::MatrixXd m(d, d);
  if (d == 2)
    m << 0, 1.0000000000000002, 1.1547005383792517, -0.57735026918962584;
  else
    m << 0.38268343236508984, -0.38268343236509061, -0.92387953251128618, -0.70710678118654791, -0.70710678118654746,
        0.70710678118654757, 0.92387953251128729, -0.92387953251128718, 0.38268343236508989;
  return m;
}
}  // namespace

TEST(Coxeter, ClosedFormMatchesGudhiUpToRowSigns) {
  EXPECT_TRUE(Triangulation::coxeter(2).matrix().isApprox(gudhi_matrix(2), 1e-14));
  Eigen::MatrixXd c3 = Triangulation::coxeter(3).matrix();
  const Eigen::MatrixXd g3 = gudhi_matrix(3);
  for (int r = 0; r < 3; ++r) {
    const bool same = c3.row(r).isApprox(g3.row(r), 1e-13), flipped = c3.row(r).isApprox(-g3.row(r), 1e-13);
    EXPECT_TRUE(same || flipped) << "row " << r;
  }
  EXPECT_NEAR(c3(0, 0), -0.382683432365090, 1e-14);  // the sine formula's values
  EXPECT_NEAR(c3(1, 2), -0.707106781186548, 1e-14);
}

TEST(Coxeter, GramMatrixHeightsAndEdges) {
  for (int d = 1; d <= 31; ++d) {
    const Triangulation t = Triangulation::coxeter(d);
    const Eigen::MatrixXd& L = t.matrix();
    const Eigen::MatrixXd expected =
        2.0 * (Eigen::MatrixXd::Identity(d, d) - Eigen::MatrixXd::Constant(d, d, 1.0 / (d + 1)));
    ASSERT_TRUE((L.transpose() * L).isApprox(expected, 1e-11)) << "d=" << d;
    // Edges of the d-simplex (0, identity order): |v_i − v_j|² = 2q(d+1−q)/(d+1), q = |i−j|.
    std::vector<std::vector<int>> blocks;
    for (int i = 0; i <= d; ++i) blocks.push_back({i});
    const Simplex s = Simplex::from_partition(std::vector<std::int32_t>(d, 0), blocks);
    std::vector<double> xs((d + 1) * d);
    t.vertex_coordinates(s, xs.data());
    double longest = 0;
    for (int i = 0; i <= d; ++i)
      for (int j = i + 1; j <= d; ++j) {
        double e2 = 0;
        for (int c = 0; c < d; ++c) e2 += std::pow(xs[i * d + c] - xs[j * d + c], 2);
        const int q = j - i;
        EXPECT_NEAR(e2, 2.0 * q * (d + 1 - q) / (d + 1), 1e-10);
        longest = std::max(longest, std::sqrt(e2));
      }
    EXPECT_NEAR(t.longest_edge(), longest, 1e-12);
    if (d <= 16) {  // the exhaustive walk agrees with the closed form
      Triangulation general(t.matrix(), t.offset());
      EXPECT_NEAR(general.longest_edge(), longest, 1e-10);
    }
    // Every height is 1: h_i = 1/|∇λ_i|, with λ_{1..d}(x) = E^{-1}(x − v_0) and λ_0 = 1 − Σ λ_i.
    Eigen::MatrixXd E(d, d);
    for (int j = 1; j <= d; ++j)
      for (int c = 0; c < d; ++c) E(c, j - 1) = xs[j * d + c] - xs[c];
    const Eigen::MatrixXd G = E.inverse();
    EXPECT_NEAR(1.0 / G.colwise().sum().norm(), 1.0, 1e-10) << "d=" << d;
    for (int i = 0; i < d; ++i) EXPECT_NEAR(1.0 / G.row(i).norm(), 1.0, 1e-10) << "d=" << d << " i=" << i;
  }
}

TEST(Locate, FreudenthalExamples) {
  const Triangulation t3 = Triangulation::freudenthal(3);
  EXPECT_EQ(loc(t3, {3, -1, 0}), "(3,-1,0) [{0,1,2,3}]");
  EXPECT_EQ(loc(t3, {3.5, -1.5, 0.5}), "(3,-2,0) [{0,1,2},{3}]");
  EXPECT_EQ(loc(t3, {3.5, -1.8, 0.5}), "(3,-2,0) [{0,2},{1},{3}]");
  EXPECT_EQ(loc(t3, {3.5, -1.8, 0.3}), "(3,-2,0) [{0},{2},{1},{3}]");
  EXPECT_EQ(locate(t3.scaled(0.5), {3.5, -1.8, 0.3}).dimension(), 2);  // GUDHI's scale 2 = our 1/2
  const Triangulation t2 = Triangulation::freudenthal(2);
  EXPECT_EQ(loc(t2, {0.3, 0.7}), "(0,0) [{1},{0},{2}]");
  EXPECT_EQ(loc(t2, {0.7, 0.3}), "(0,0) [{0},{1},{2}]");
  EXPECT_EQ(loc(t2, {0.5, 0.5}), "(0,0) [{0,1},{2}]");
  EXPECT_EQ(loc(t2, {1.0, 0.25}), "(1,0) [{1},{0,2}]");
  EXPECT_EQ(loc(t2, {-0.2, 1.5}), "(-1,1) [{0},{1},{2}]");
}

TEST(Locate, CoxeterExamplesWithGudhiMatrix) {
  const Triangulation t2(gudhi_matrix(2), Eigen::VectorXd::Zero(2));
  const Simplex s = locate(t2, {0.3, 0.7});
  EXPECT_EQ(to_string(s), "(0,0) [{0},{1},{2}]");
  std::vector<double> xs(6);
  t2.vertex_coordinates(s, xs.data());
  const double expected[] = {0, 0, 0, 1.1547005, 1.0, 0.5773503};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(xs[i], expected[i], 1e-7);
  EXPECT_EQ(loc(t2, {0.7, 0.3}), "(0,0) [{1},{0},{2}]");
  // (1.0, 0.25) has lattice coordinate y_1 = 1/1.0000000000000002: on the hyperplane y_1 = 1 up to
  // rounding. GUDHI reports the triangle (0,0)[{1},{0},{2}]; coxmesh snaps and reports its edge.
  EXPECT_EQ(loc(t2, {1.0, 0.25}), "(0,1) [{0},{1,2}]");
  EXPECT_TRUE(is_face_of(locate(t2, {1.0, 0.25}), parse_simplex("(0,0) [{1},{0},{2}]")));
  EXPECT_EQ(loc(t2, {-0.2, 1.5}), "(1,-1) [{1},{0},{2}]");
  const Triangulation t3(gudhi_matrix(3), Eigen::VectorXd::Zero(3));
  EXPECT_EQ(loc(t3, {0, 0, 0}), "(0,0,0) [{0,1,2,3}]");
  EXPECT_EQ(loc(t3, {0.1, 0.2, 0.3}), "(0,-1,0) [{1},{0},{2},{3}]");
  EXPECT_EQ(loc(t3, {1, -2, 0.5}), "(1,0,-1) [{1},{0},{2},{3}]");
}

TEST(Locate, PointsLieInTheirSimplexWithPositiveBarycentricCoordinates) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int d = 1; d <= 12; ++d) {
    const Triangulation t = Triangulation::coxeter(d).rotated(d).scaled(0.7).with_offset(Eigen::VectorXd::Random(d));
    std::vector<double> x(d), lambda(d + 1), xs((d + 1) * d);
    for (int trial = 0; trial < 300; ++trial) {
      for (auto& v : x) v = u(rng);
      const Simplex s = t.locate(x);
      t.barycentric(s, x.data(), lambda.data());
      t.vertex_coordinates(s, xs.data());
      std::vector<double> back(d, 0.0);
      double sum = 0;
      for (int j = 0; j <= s.k; ++j) {
        EXPECT_GT(lambda[j], 0.0);
        sum += lambda[j];
        for (int i = 0; i < d; ++i) back[i] += lambda[j] * xs[j * d + i];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
      for (int i = 0; i < d; ++i) EXPECT_NEAR(back[i], x[i], 1e-9);
    }
  }
}

TEST(Locate, LowerDimensionalFacesAreFound) {
  // The barycentre of any face of a located simplex locates exactly that face.
  const Triangulation t = Triangulation::coxeter(4).scaled(1.3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> x(4);
    for (auto& v : x) v = u(rng);
    const Simplex s = t.locate(x);
    for (int k = 0; k <= s.k; ++k) {
      FaceEnumerator faces(s, k);
      for (Simplex f; faces.next(f);) {
        std::vector<double> xs((k + 1) * 4), c(4, 0.0);
        t.vertex_coordinates(f, xs.data());
        for (int j = 0; j <= k; ++j)
          for (int i = 0; i < 4; ++i) c[i] += xs[j * 4 + i] / (k + 1);
        EXPECT_EQ(t.locate(c), f);
      }
    }
  }
}

TEST(Triangulation, VertexCoordinatesMatchLatticeVertices) {
  const Triangulation t = Triangulation::coxeter(5).rotated(1).with_offset(Eigen::VectorXd::Constant(5, 0.25));
  const Simplex s = parse_simplex("(1,-2,3,0,7) [{4},{0,2},{1},{3,5}]");
  std::vector<double> xs(4 * 5), x(5);
  t.vertex_coordinates(s, xs.data());
  std::int32_t v[5];
  for (int j = 0; j <= 3; ++j) {
    s.vertex(j, v);
    t.cartesian(v, x.data());
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(xs[j * 5 + i], x[i], 1e-12);
  }
}

// The oracle's intersection points are sums over these coordinates: each vertex must be its
// predecessor plus the columns of its block, added in increasing column order, bit for bit.
TEST(Triangulation, VertexCoordinatesAddEachBlockInColumnOrder) {
  const int d = 9;
  const Triangulation t = Triangulation::coxeter(d).rotated(3).with_longest_edge(1.1);
  const Eigen::MatrixXd& m = t.matrix();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-4, 4);
  int multi_column_blocks = 0;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> x(d);
    for (auto& v : x) v = u(rng);
    FaceEnumerator faces(t.locate(x), 1 + trial % (d - 1));
    for (Simplex f; faces.next(f);) {
      std::vector<double> xs((f.k + 1) * d);
      t.vertex_coordinates(f, xs.data());
      std::int32_t v[kMaxDimension];
      f.vertex(0, v);
      std::vector<double> expected(d);
      t.cartesian(v, expected.data());
      for (int i = 0; i < d; ++i) ASSERT_EQ(xs[i], expected[i]);
      for (int j = 1; j <= f.k; ++j) {
        int columns = 0;
        for (int e = 0; e < d; ++e)
          if (f.block[e] == j - 1) {
            ++columns;
            for (int i = 0; i < d; ++i) expected[i] += m(i, e);
          }
        multi_column_blocks += columns > 1;
        for (int i = 0; i < d; ++i) ASSERT_EQ(xs[j * d + i], expected[i]) << "vertex " << j;
      }
    }
  }
  EXPECT_GT(multi_column_blocks, 100);
}

TEST(Triangulation, RotationIsDeterministicAndOrthogonal) {
  const Triangulation a = Triangulation::coxeter(6).rotated(42), b = Triangulation::coxeter(6).rotated(42);
  EXPECT_EQ(a.matrix(), b.matrix());
  const Eigen::MatrixXd g0 = Triangulation::coxeter(6).matrix().transpose() * Triangulation::coxeter(6).matrix();
  EXPECT_TRUE((a.matrix().transpose() * a.matrix()).isApprox(g0, 1e-12));
  EXPECT_FALSE(a.matrix().isApprox(Triangulation::coxeter(6).rotated(43).matrix()));
  EXPECT_NEAR(Triangulation::coxeter(6).with_longest_edge(0.1).longest_edge(), 0.1, 1e-15);
}

TEST(Triangulation, BadInputIsRejected) {
  EXPECT_THROW(Triangulation(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Zero(2)), InputError);
  EXPECT_THROW(Triangulation(Eigen::MatrixXd::Identity(2, 3), Eigen::VectorXd::Zero(2)), InputError);
  EXPECT_THROW(Triangulation(Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(3)), InputError);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Identity(2, 2);
  nan(0, 1) = std::nan("");
  EXPECT_THROW(Triangulation(nan, Eigen::VectorXd::Zero(2)), InputError);
  EXPECT_THROW(Triangulation::coxeter(32), InputError);
  EXPECT_THROW(Triangulation::coxeter(0), InputError);
  const Triangulation t = Triangulation::coxeter(3);
  EXPECT_THROW(locate(t, {1, 2}), InputError);
  EXPECT_THROW(locate(t, {1, std::nan(""), 2}), InputError);
  EXPECT_THROW(locate(t, {1, INFINITY, 2}), InputError);
  EXPECT_THROW(locate(t, {1e10, 0, 0}), InputError);  // lattice coordinate beyond 2^30
  EXPECT_THROW(t.scaled(0), InputError);
  EXPECT_THROW(t.scaled(-1), InputError);
  EXPECT_THROW(t.with_longest_edge(std::nan("")), InputError);
  const Triangulation wide(Eigen::MatrixXd::Random(25, 25), Eigen::VectorXd::Zero(25));  // a valid triangulation,
  EXPECT_THROW(wide.longest_edge(), InputError);  // but 2^25 candidate edges are too many to search
}
