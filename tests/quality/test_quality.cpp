// Thesis §1.2 (Thm 1.2.15, Prop. 1.2.28–1.2.31) and Ch. 2. Root systems, alcoves, tiling,
// quality measures, Delaunay property and protection, against closed forms (thesis §2.4), classical
// facts (root counts, highest roots, |W|) and an independent exact computation in rational arithmetic.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <boost/multiprecision/cpp_int.hpp>
#include <boost/rational.hpp>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <set>

#include "coxmesh/lattice/simplex.h"  // InputError
#include "coxmesh/quality/measures.h"

using namespace coxmesh;
using namespace coxmesh::quality;

namespace {

// ---- Exact rationals (Boost.Rational over unbounded integers: no overflow) -------------------------

using Frac = boost::rational<boost::multiprecision::cpp_int>;
int sign(const Frac& x) { return x > 0 ? 1 : x < 0 ? -1 : 0; }
long double value(const Frac& x) { return boost::rational_cast<long double>(x); }

using FracMatrix = std::vector<std::vector<Frac>>;

// Gauss–Jordan inverse and determinant (the matrices are positive definite Gram matrices, d ≤ 8).
FracMatrix inverse(FracMatrix a, Frac& det) {
  const std::size_t n = a.size();
  FracMatrix inv(n, std::vector<Frac>(n));
  for (std::size_t i = 0; i < n; ++i) inv[i][i] = 1;
  det = 1;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t p = c;
    while (sign(a[p][c]) == 0) ++p;
    if (p != c) std::swap(a[p], a[c]), std::swap(inv[p], inv[c]), det = Frac(0) - det;
    const Frac pivot = a[c][c];
    det = det * pivot;
    for (std::size_t k = 0; k < n; ++k) a[c][k] = a[c][k] / pivot, inv[c][k] = inv[c][k] / pivot;
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c || sign(a[r][c]) == 0) continue;
      const Frac f = a[r][c];
      for (std::size_t k = 0; k < n; ++k) a[r][k] = a[r][k] - f * a[c][k], inv[r][k] = inv[r][k] - f * inv[c][k];
    }
  }
  return inv;
}

// ---- The test's own copy of Thm 1.2.15 and of the classical highest roots (Bourbaki) ---------------

// 2·s_i, rows, in the coordinates of Thm 1.2.15.
std::vector<std::vector<int>> doubled_simple_roots(Family f, int d) {
  std::vector<std::vector<int>> s;
  const int n = f == Family::A ? d + 1 : f == Family::E ? 8 : f == Family::G ? 3 : d;
  auto e = [&](std::initializer_list<std::pair<int, int>> entries) {  // (1-based index, doubled value)
    std::vector<int> v(n, 0);
    for (auto [i, x] : entries) v[i - 1] = x;
    s.push_back(v);
  };
  switch (f) {
    case Family::A:
      for (int i = 1; i <= d; ++i) e({{i, 2}, {i + 1, -2}});
      break;
    case Family::B:
    case Family::C:
    case Family::D:
      for (int i = 1; i < d; ++i) e({{i, 2}, {i + 1, -2}});
      if (f == Family::B) e({{d, 2}});
      if (f == Family::C) e({{d, 4}});
      if (f == Family::D) e({{d - 1, 2}, {d, 2}});
      break;
    case Family::E:
      e({{1, 1}, {2, -1}, {3, -1}, {4, -1}, {5, -1}, {6, -1}, {7, -1}, {8, 1}});
      e({{1, 2}, {2, 2}});
      for (int k = 3; k <= d; ++k) e({{k - 1, 2}, {k - 2, -2}});
      break;
    case Family::F:
      e({{2, 2}, {3, -2}});
      e({{3, 2}, {4, -2}});
      e({{4, 2}});
      e({{1, 1}, {2, -1}, {3, -1}, {4, -1}});
      break;
    case Family::G:
      e({{1, 2}, {2, -2}});
      e({{1, -4}, {2, 2}, {3, 2}});
      break;
  }
  return s;
}

std::vector<int> bourbaki_highest_root(Family f, int d) {
  switch (f) {
    case Family::A:
      return std::vector<int>(d, 1);
    case Family::B: {
      std::vector<int> c(d, 2);
      c[0] = 1;
      return c;
    }
    case Family::C: {
      std::vector<int> c(d, 2);
      c[d - 1] = 1;
      return c;
    }
    case Family::D: {
      std::vector<int> c(d, 2);
      c[0] = c[d - 2] = c[d - 1] = 1;
      return c;
    }
    case Family::E:
      if (d == 6) return {1, 2, 2, 3, 2, 1};
      if (d == 7) return {2, 2, 3, 4, 3, 2, 1};
      return {2, 3, 4, 6, 5, 4, 3, 2};
    case Family::F:
      return {2, 3, 4, 2};
    case Family::G:
      return {3, 2};
  }
  return {};
}

int expected_root_count(Family f, int d) {
  switch (f) {
    case Family::A:
      return d * (d + 1);
    case Family::B:
    case Family::C:
      return 2 * d * d;
    case Family::D:
      return 2 * d * (d - 1);
    case Family::E:
      return d == 6 ? 72 : d == 7 ? 126 : 240;
    case Family::F:
      return 48;
    case Family::G:
      return 12;
  }
  return 0;
}

// Everything about the fundamental alcove, exactly (squares of lengths are rational).
struct ExactAlcove {
  int d = 0;
  Frac longest2, shortest2, min_height2, circumradius2, volume2, coroot_det;
  std::vector<Frac> heights2, barycentric;  // d+1 each
};

ExactAlcove exact_alcove(Family f, int d) {
  const auto s = doubled_simple_roots(f, d);
  const auto c = bourbaki_highest_root(f, d);
  FracMatrix gram(d, std::vector<Frac>(d)), coroot(d, std::vector<Frac>(d));
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) {
      long long dot = 0;
      for (std::size_t k = 0; k < s[i].size(); ++k) dot += s[i][k] * s[j][k];
      gram[i][j] = Frac(dot, 4);
    }
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) coroot[i][j] = Frac(4) * gram[i][j] / (gram[i][i] * gram[j][j]);
  ExactAlcove e;
  e.d = d;
  Frac unused;
  inverse(coroot, e.coroot_det);
  const FracMatrix coweights = inverse(gram, unused);  // Gram of the dual basis ω^∨
  FracMatrix m(d, std::vector<Frac>(d));               // Gram of v_1..v_d (v_0 = 0)
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) m[i][j] = coweights[i][j] / Frac(c[i] * c[j]);
  auto edge2 = [&](int i, int j) {  // vertices 0..d
    if (i == 0) return m[j - 1][j - 1];
    return m[i - 1][i - 1] + m[j - 1][j - 1] - Frac(2) * m[i - 1][j - 1];
  };
  e.longest2 = 0, e.shortest2 = edge2(0, 1);
  for (int i = 0; i <= d; ++i)
    for (int j = i + 1; j <= d; ++j) {
      const Frac x = edge2(i, j);
      if (sign(x - e.longest2) > 0) e.longest2 = x;
      if (sign(x - e.shortest2) < 0) e.shortest2 = x;
    }
  Frac det;
  const FracMatrix minv = inverse(m, det);
  Frac factorial = 1;
  for (int k = 2; k <= d; ++k) factorial = factorial * Frac(k);
  e.volume2 = det / (factorial * factorial);
  Frac grad0 = 0;
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) grad0 = grad0 + minv[i][j];
  e.heights2.push_back(Frac(1) / grad0);
  for (int i = 0; i < d; ++i) e.heights2.push_back(Frac(1) / minv[i][i]);
  e.min_height2 = e.heights2[0];
  for (const Frac& h : e.heights2)
    if (sign(h - e.min_height2) < 0) e.min_height2 = h;
  // Circumcentre c = Σ a_i v_i with 2⟨c, v_i⟩ = |v_i|²: a = ½·M^{-1}·diag(M).
  std::vector<Frac> a(d);
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) a[i] = a[i] + minv[i][j] * m[j][j] / Frac(2);
  e.circumradius2 = 0;
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) e.circumradius2 = e.circumradius2 + a[i] * m[i][j] * a[j];
  Frac rest = 1;
  for (const Frac& x : a) rest = rest - x;
  e.barycentric.push_back(rest);
  e.barycentric.insert(e.barycentric.end(), a.begin(), a.end());
  return e;
}

std::vector<std::pair<Family, int>> all_types_up_to(int max_d) {
  std::vector<std::pair<Family, int>> out;
  for (Family f : kAllFamilies)
    for (int d : supported_affine_ranks(f, max_d)) out.emplace_back(f, d);
  return out;
}

std::string name(Family f, int d) { return family_name(f) + std::to_string(d); }

void expect_rel(double actual, long double expected, double tol, const std::string& what) {
  EXPECT_LE(std::abs(actual - static_cast<double>(expected)), tol * std::max(1.0L, std::abs(expected)))
      << what << ": " << actual << " vs " << static_cast<double>(expected);
}

}  // namespace

// ---- Root systems ----------------------------------------------------------------------------------

TEST(RootSystem, CountsHighestRootsAndPositiveRoots) {
  for (Family f : kAllFamilies)
    for (int d : supported_ranks(f, 12)) {
      const RootSystem rs = make_root_system(f, d);
      const std::string n = name(f, d);
      ASSERT_EQ(rs.roots.rows(), expected_root_count(f, d)) << n;
      EXPECT_EQ(2 * rs.positive_count, rs.roots.rows()) << n;
      const auto c = bourbaki_highest_root(f, d);
      for (int i = 0; i < d; ++i) EXPECT_EQ(rs.highest_coefficients[i], c[i]) << n << " c_" << i + 1;
      // Every root is Σ coefficients·s_i; positive ones have non-negative coefficients; −R = R.
      EXPECT_TRUE((rs.coefficients.cast<double>() * rs.simple_roots).isApprox(rs.roots)) << n;
      EXPECT_GE(rs.coefficients.topRows(rs.positive_count).minCoeff(), 0) << n;
      EXPECT_TRUE(rs.roots.bottomRows(rs.positive_count).isApprox(-rs.roots.topRows(rs.positive_count))) << n;
      // The highest root is a long root (the maximum squared length) and has the largest height.
      EXPECT_NEAR(rs.highest_root.squaredNorm(), rs.roots.rowwise().squaredNorm().maxCoeff(), 1e-12) << n;
      // Closed under every reflection (not only the simple ones used to generate it); the doubled
      // coordinates of every root are integers.
      auto key = [](const Eigen::VectorXd& x) {
        std::vector<long> k(x.size());
        for (Eigen::Index i = 0; i < x.size(); ++i) k[i] = std::lround(2 * x[i]);
        return k;
      };
      std::set<std::vector<long>> all;
      for (int a = 0; a < rs.roots.rows(); ++a) all.insert(key(rs.roots.row(a).transpose()));
      EXPECT_EQ(all.size(), static_cast<std::size_t>(rs.roots.rows())) << n;
      for (int a = 0; a < rs.roots.rows(); a += 3) {
        const Eigen::VectorXd r = rs.roots.row(a).transpose();
        for (int b = 0; b < rs.roots.rows(); b += 5) {
          const Eigen::VectorXd x = rs.roots.row(b).transpose();
          EXPECT_TRUE(all.count(key(x - 2 * x.dot(r) / r.squaredNorm() * r))) << n;
        }
      }
    }
}

TEST(RootSystem, SimpleRootsAreThoseOfTheorem1215) {
  for (auto [f, d] : all_types_up_to(8)) {
    const auto s = doubled_simple_roots(f, d);
    const Eigen::MatrixXd m = simple_roots(f, d);
    for (int i = 0; i < d; ++i)
      for (std::size_t k = 0; k < s[i].size(); ++k) EXPECT_EQ(m(i, k), 0.5 * s[i][k]) << name(f, d);
  }
}

TEST(RootSystem, CartanMatricesAndDiagrams) {
  const RootSystem g2 = make_root_system(Family::G, 2);
  EXPECT_EQ(g2.cartan(0, 1), -1);  // n(s1, s2) = 2⟨s1,s2⟩/⟨s2,s2⟩ = 2·(−3)/6
  EXPECT_EQ(g2.cartan(1, 0), -3);
  EXPECT_EQ(coxeter_diagram(g2), (std::vector<DiagramEdge>{{1, 2, 6}}));
  EXPECT_EQ(affine_coxeter_diagram(g2), (std::vector<DiagramEdge>{{0, 2, 3}, {1, 2, 6}}));
  EXPECT_EQ(coxeter_diagram(make_root_system(Family::F, 4)),
            (std::vector<DiagramEdge>{{1, 2, 3}, {2, 3, 4}, {3, 4, 3}}));
  EXPECT_EQ(coxeter_diagram(make_root_system(Family::B, 3)), (std::vector<DiagramEdge>{{1, 2, 3}, {2, 3, 4}}));
  EXPECT_EQ(affine_coxeter_diagram(make_root_system(Family::C, 3)),
            (std::vector<DiagramEdge>{{0, 1, 4}, {1, 2, 3}, {2, 3, 4}}));
  EXPECT_EQ(affine_coxeter_diagram(make_root_system(Family::A, 1)), (std::vector<DiagramEdge>{{0, 1, 0}}));  // ∞
  // E8 (Bourbaki numbering): 1-3-4-5-6-7-8 with 2 attached to 4; the extra node hangs off 8.
  EXPECT_EQ(affine_coxeter_diagram(make_root_system(Family::E, 8)),
            (std::vector<DiagramEdge>{
                {0, 8, 3}, {1, 3, 3}, {2, 4, 3}, {3, 4, 3}, {4, 5, 3}, {5, 6, 3}, {6, 7, 3}, {7, 8, 3}}));
  for (auto [f, d] : all_types_up_to(8)) {
    const RootSystem rs = make_root_system(f, d);
    EXPECT_EQ(coxeter_diagram(rs).size(), static_cast<std::size_t>(d - 1)) << name(f, d);  // a tree
    EXPECT_EQ(affine_coxeter_diagram(rs).size(), static_cast<std::size_t>(f == Family::A && d >= 2 ? d + 1 : d))
        << name(f, d);  // a cycle for Ã_d, a tree otherwise
    for (int i = 0; i < d; ++i) {
      EXPECT_EQ(rs.cartan(i, i), 2);
      for (int j = 0; j < d; ++j)
        if (i != j) {
          EXPECT_TRUE(rs.cartan(i, j) <= 0 && rs.cartan(i, j) >= -3 &&
                      (rs.cartan(i, j) == 0) == (rs.cartan(j, i) == 0));
        }
    }
  }
}

TEST(RootSystem, UnsupportedPairsThrowInputError) {
  const std::vector<std::pair<Family, int>> bad{{Family::A, 0}, {Family::B, 1}, {Family::C, 1},
                                                {Family::D, 3}, {Family::E, 5}, {Family::E, 9},
                                                {Family::F, 3}, {Family::G, 3}, {Family::A, 65}};
  for (auto [f, d] : bad) {
    EXPECT_THROW(make_root_system(f, d), InputError) << name(f, d);
    EXPECT_THROW(fundamental_alcove(f, d), InputError) << name(f, d);
  }
  EXPECT_NO_THROW(make_root_system(Family::B, 2));
  EXPECT_THROW(fundamental_alcove(Family::B, 2), InputError);  // B̃_2 = C̃_2
  EXPECT_THROW(parse_family("H"), InputError);
  EXPECT_EQ(parse_family("e"), Family::E);
}

// ---- Alcoves and tiling ----------------------------------------------------------------------------

TEST(Alcove, VerticesAndFacetsMatchProposition1229) {
  for (auto [f, d] : all_types_up_to(8)) {
    const Alcove a = fundamental_alcove(f, d);
    const RootSystem rs = make_root_system(f, d);
    const std::string n = name(f, d);
    EXPECT_TRUE((a.basis * a.basis.transpose()).isIdentity(1e-13)) << n;
    for (int i = 0; i <= d; ++i) {
      const Eigen::VectorXd v = a.vertices.row(i).transpose();
      EXPECT_NEAR(v.dot(a.highest_root), i == 0 ? 0.0 : 1.0, 1e-13) << n;  // v_i ∈ H_{s̃,1} for i ≥ 1
      for (int j = 1; j <= d; ++j)
        EXPECT_NEAR(v.dot(a.simple_roots.row(j - 1)), i == j ? 1.0 / a.highest_coefficients[i - 1] : 0.0, 1e-13) << n;
    }
    // The open alcove lies strictly between H_{r,0} and H_{r,1} for every positive root r (thesis §1.2.4).
    const Eigen::VectorXd centre = a.vertices.colwise().mean().transpose();
    const Eigen::VectorXd values = rs.roots.topRows(rs.positive_count) * (a.basis.transpose() * centre);
    EXPECT_GT(values.minCoeff(), 0) << n;
    EXPECT_LT(values.maxCoeff(), 1) << n;
  }
  // C̃_d: 0, ½e_1, ½(e_1+e_2), … (thesis §1.2), in the unchanged coordinates.
  const Alcove c4 = fundamental_alcove(Family::C, 4);
  for (int i = 0; i <= 4; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(c4.vertices(i, k), k < i ? 0.5 : 0.0);
}

TEST(Alcove, NeighbourhoodsTileFaceToFace) {
  for (auto [f, d] : all_types_up_to(8)) {
    const Alcove a = fundamental_alcove(f, d);
    const AlcoveComplex c = generate_by_depth(a, 3);
    const TilingCheck t = check_tiling(a, c);
    EXPECT_TRUE(t.ok()) << name(f, d) << ": " << t.problem;
    std::size_t inner = 0;
    for (int depth : c.depth) inner += depth < 3;
    EXPECT_EQ(t.interior_alcoves, inner) << name(f, d);  // every alcove of depth < 3 has all its neighbours
    EXPECT_EQ(t.facets_checked, inner * (d + 1)) << name(f, d);
  }
}

TEST(Alcove, VertexStarsHaveOrderOfTheStabiliserAndCoverABall) {
  struct Case {
    Family f;
    int d, t;
    double expected;
  };
  // Star of v_0: |W|. Star of v_4 in Ẽ8: W(A1×A2×A5) = 2·6·720; of v_4 in Ẽ6: W(A2×A2×A2) = 216.
  const std::vector<Case> cases{{Family::A, 2, 0, weyl_group_order(Family::A, 2)},
                                {Family::A, 4, 0, weyl_group_order(Family::A, 4)},
                                {Family::B, 3, 0, weyl_group_order(Family::B, 3)},
                                {Family::C, 2, 0, weyl_group_order(Family::C, 2)},
                                {Family::C, 3, 0, weyl_group_order(Family::C, 3)},
                                {Family::D, 4, 0, weyl_group_order(Family::D, 4)},
                                {Family::F, 4, 0, weyl_group_order(Family::F, 4)},
                                {Family::G, 2, 0, weyl_group_order(Family::G, 2)},
                                {Family::E, 6, 4, 216},
                                {Family::E, 8, 4, 8640}};
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  for (const Case& k : cases) {
    const Alcove a = fundamental_alcove(k.f, k.d);
    const AlcoveComplex star = generate_vertex_star(a, k.t);
    const std::string n = name(k.f, k.d) + " star of v_" + std::to_string(k.t);
    EXPECT_EQ(static_cast<double>(star.alcove_count()), k.expected) << n;
    const TilingCheck t = check_tiling(a, star);
    EXPECT_TRUE(t.congruent && t.types_consistent && t.mirror_neighbours && t.face_to_face) << n << ": " << t.problem;
    // Points closer to v_t than its height are covered by exactly one alcove of the star.
    const double radius = 0.9 * measure_simplex(a.vertices).heights[k.t];
    for (int sample = 0; sample < (star.alcove_count() > 2000 ? 0 : 12); ++sample) {  // O(#alcoves·d³) each
      Eigen::VectorXd dir(k.d);
      for (int i = 0; i < k.d; ++i) dir[i] = normal(rng);
      const double r = radius * std::pow(std::uniform_real_distribution<double>(0.05, 1)(rng), 1.0 / k.d);
      const Eigen::VectorXd x = a.vertices.row(k.t).transpose() + r * dir.normalized();
      EXPECT_EQ(count_containing(star, x), 1) << n;
    }
  }
}

TEST(Alcove, BallGenerationCoversTheBall) {
  const Alcove a = fundamental_alcove(Family::G, 2);
  const SimplexMeasures m = measure_simplex(a.vertices);
  const Eigen::VectorXd centre = m.circumcentre;
  const double radius = 3 * m.longest_edge;
  const AlcoveComplex ball = generate_in_ball(a, centre, radius);
  EXPECT_TRUE(check_tiling(a, ball).ok());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int sample = 0; sample < 50; ++sample) {
    Eigen::Vector2d x(u(rng), u(rng));
    if (x.norm() > 1) continue;
    EXPECT_EQ(count_containing(ball, centre + (radius - m.longest_edge) * x), 1);
  }
  EXPECT_THROW(generate_in_ball(a, Eigen::VectorXd::Zero(3), 1.0), InputError);
  EXPECT_THROW(generate_vertex_star(a, 3), InputError);
  EXPECT_THROW(generate_vertex_star(fundamental_alcove(Family::E, 8), 0, 1000), InputError);
}

// ---- Measures --------------------------------------------------------------------------------------

TEST(Measures, RegularSimplexClosedForms) {
  for (int d = 1; d <= 10; ++d) {
    // The regular simplex with unit edges: e_i/√2 in R^{d+1}, expressed in d coordinates.
    Eigen::MatrixXd v = Eigen::MatrixXd::Identity(d + 1, d + 1) / std::sqrt(2.0);
    Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(d + 1, d);  // orthonormal basis of Σx = 0
    for (int k = 0; k < d; ++k) {
      for (int i = 0; i <= k; ++i) basis(i, k) = 1;
      basis(k + 1, k) = -(k + 1);
      basis.col(k).normalize();
    }
    const SimplexMeasures m = measure_simplex(v * basis), r = regular_simplex_measures(d);
    EXPECT_NEAR(m.longest_edge, 1, 1e-13);
    EXPECT_NEAR(m.min_height, r.min_height, 1e-13);
    EXPECT_NEAR(m.circumradius, r.circumradius, 1e-13);
    EXPECT_NEAR(m.inradius, r.inradius, 1e-13);
    EXPECT_NEAR(m.volume / r.volume, 1, 1e-12);
    EXPECT_NEAR(m.radius_ratio, 1.0 / d, 1e-13);
    const RelativeMeasures rel = relative_to_regular(m);
    EXPECT_NEAR(rel.thickness, 1, 1e-12);
    EXPECT_NEAR(rel.radius_ratio, 1, 1e-12);
    EXPECT_NEAR(rel.fatness, 1, 1e-12);
    EXPECT_NEAR(rel.aspect_ratio, 1, 1e-12);
  }
  EXPECT_THROW(measure_simplex(Eigen::MatrixXd::Zero(3, 2)), InputError);  // degenerate
  EXPECT_THROW(measure_simplex(Eigen::MatrixXd::Zero(3, 3)), InputError);  // wrong shape
}

TEST(Measures, AtildeClosedFormsUpToDimension50) {
  for (int d = 1; d <= 50; ++d) {
    const Alcove a = fundamental_alcove(Family::A, d);
    const SimplexMeasures m = measure_simplex(a.vertices);
    const long double D = d;
    const std::string n = name(Family::A, d);
    for (int i = 0; i <= d; ++i)
      for (int j = i + 1; j <= d; ++j) {
        const long double q = j - i;
        expect_rel((a.vertices.row(i) - a.vertices.row(j)).squaredNorm(), q * (D + 1 - q) / (D + 1), 1e-12,
                   n + " edge");
      }
    const long double L2 = std::floor((D + 1) / 2) * std::ceil((D + 1) / 2) / (D + 1);
    const long double R2 = D * (D + 2) / (12 * (D + 1));
    expect_rel(m.longest_edge, std::sqrt(L2), 1e-12, n + " L");
    for (int i = 0; i <= d; ++i) expect_rel(m.heights[i], 1 / std::sqrt(2.0L), 1e-12, n + " h");
    expect_rel(m.circumradius, std::sqrt(R2), 1e-12, n + " R");
    expect_rel(m.inradius, 1 / (std::sqrt(2.0L) * (D + 1)), 1e-12, n + " r");
    expect_rel(m.volume / static_cast<double>(1 / (std::tgamma(D + 1) * std::sqrt(D + 1))), 1, 1e-12, n + " vol");
    expect_rel(m.radius_ratio, std::sqrt(6 / (D * (D + 1) * (D + 2))), 1e-12, n + " r/R");
    expect_rel(m.aspect_ratio, std::sqrt(6 * (D + 1) / (D * (D + 2))), 1e-12, n + " h/R");
    expect_rel(m.thickness, d % 2 ? std::sqrt(2 / (D + 1)) : std::sqrt(2 * (D + 1) / (D * (D + 2))), 1e-12, n + " h/L");
    if (d % 2) expect_rel(relative_to_regular(m).thickness, 2 * std::sqrt(D) / (D + 1), 1e-12, n + " h/L rel");
    for (int i = 0; i <= d; ++i) EXPECT_NEAR(m.circumcentre_barycentric[i], 1.0 / (d + 1), 1e-12) << n;  // barycentre
    // Protection (thesis §2.4): δ = √((d²+2d+24)/(12(d+1))) − √((d²+2d)/(12(d+1))).
    const DelaunayResult del = delaunay_by_circumcentre(m);
    ASSERT_EQ(del.status, DelaunayStatus::yes) << n;
    const long double delta =
        std::sqrt((D * D + 2 * D + 24) / (12 * (D + 1))) - std::sqrt((D * D + 2 * D) / (12 * (D + 1)));
    expect_rel(*del.protection, delta / std::sqrt(L2), 1e-12, n + " δ/L");
    if (d <= 12) {  // the direct check on the depth-2 neighbourhood gives the same protection
      const DelaunayResult direct = delaunay_direct(generate_by_depth(a, 2));
      EXPECT_EQ(direct.status, DelaunayStatus::yes) << n;
      expect_rel(*direct.protection, delta / std::sqrt(L2), 1e-12, n + " δ/L direct");
    }
    if (d >= 10) {  // Θ(1/d²): d²·δ/L → 4√3 ≈ 6.93 from below
      EXPECT_GT(D * D * delta / std::sqrt(L2), 5.5) << n;
      EXPECT_LT(D * D * delta / std::sqrt(L2), 4 * std::sqrt(3.0)) << n;
    }
  }
  // The values listed in thesis §2.4.
  const double listed[] = {0.577350, 0.342371, 0.239146, 0.169844, 0.129757, 0.100324, 0.080930, 0.065856, 0.055105};
  for (int d = 2; d <= 10; ++d)
    EXPECT_NEAR(*coxeter_quality(Family::A, d, 0).delaunay.protection, listed[d - 2], 6e-7) << d;
}

TEST(Measures, CtildeClosedFormsUpToDimension50) {
  for (int d = 2; d <= 50; ++d) {
    const SimplexMeasures m = measure_simplex(fundamental_alcove(Family::C, d).vertices);
    const long double D = d;
    const std::string n = name(Family::C, d);
    expect_rel(m.longest_edge, std::sqrt(D) / 2, 1e-12, n + " L");
    expect_rel(m.shortest_edge, 0.5L, 1e-12, n + " l");
    expect_rel(m.min_height, std::sqrt(2.0L) / 4, 1e-12, n + " h");
    expect_rel(m.circumradius, std::sqrt(D) / 4, 1e-12, n + " R");
    expect_rel(m.volume * std::ldexp(std::tgamma(D + 1), d), 1, 1e-12, n + " vol");
    expect_rel(m.thickness, 1 / std::sqrt(2 * D), 1e-12, n + " h/L");
    expect_rel(m.aspect_ratio, std::sqrt(2 / D), 1e-12, n + " h/R");
    expect_rel(m.fatness * std::tgamma(D + 1) * std::pow(D, D / 2), 1, 1e-12, n + " vol/L^d");
    EXPECT_EQ(delaunay_by_circumcentre(m).status, DelaunayStatus::degenerate) << n;  // c = midpoint of v_0 v_d
  }
}

TEST(Measures, LowDimensionalShapes) {
  auto angles = [](const Eigen::MatrixXd& v) {  // of a triangle, sorted, in degrees
    std::vector<double> out;
    for (int i = 0; i < 3; ++i) {
      const Eigen::VectorXd a = v.row((i + 1) % 3) - v.row(i), b = v.row((i + 2) % 3) - v.row(i);
      out.push_back(std::acos(a.dot(b) / (a.norm() * b.norm())) * 180 / std::numbers::pi);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto g2 = angles(fundamental_alcove(Family::G, 2).vertices);
  EXPECT_NEAR(g2[0], 30, 1e-10);
  EXPECT_NEAR(g2[1], 60, 1e-10);
  EXPECT_NEAR(g2[2], 90, 1e-10);
  const auto c2 = angles(fundamental_alcove(Family::C, 2).vertices);
  EXPECT_NEAR(c2[0], 45, 1e-10);
  EXPECT_NEAR(c2[1], 45, 1e-10);
  EXPECT_NEAR(c2[2], 90, 1e-10);
  const auto a2 = angles(fundamental_alcove(Family::A, 2).vertices);
  EXPECT_NEAR(a2[0], 60, 1e-10);
  EXPECT_NEAR(a2[2], 60, 1e-10);
  // Ã3: the BCC tetrahedron, four edges √3/2 and two edges 1 (in this normalisation, exactly).
  const Eigen::MatrixXd a3 = fundamental_alcove(Family::A, 3).vertices;
  std::vector<double> edges;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) edges.push_back((a3.row(i) - a3.row(j)).norm());
  std::sort(edges.begin(), edges.end());
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(edges[k], std::sqrt(3.0) / 2, 1e-14);
  EXPECT_NEAR(edges[4], 1, 1e-14);
  EXPECT_NEAR(edges[5], 1, 1e-14);
  // ... and its two unit edges are opposite (disjoint), as in the BCC lattice.
  int shared = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (std::abs((a3.row(i) - a3.row(j)).norm() - 1) < 1e-12) shared += (1 << i) | (1 << j);
  EXPECT_EQ(shared, 15);
}

// ---- Independent exact computation -----------------------------------------------------------------

TEST(Exact, RationalComputationAgreesWithDoublesForEveryType) {
  for (auto [f, d] : all_types_up_to(8)) {
    const std::string n = name(f, d);
    const ExactAlcove e = exact_alcove(f, d);
    const CoxeterQuality q = coxeter_quality(f, d, 0);
    const SimplexMeasures& m = q.measures;
    expect_rel(m.longest_edge * m.longest_edge, value(e.longest2), 1e-12, n + " L²");
    expect_rel(m.shortest_edge * m.shortest_edge, value(e.shortest2), 1e-12, n + " l²");
    expect_rel(m.min_height * m.min_height, value(e.min_height2), 1e-12, n + " h²");
    expect_rel(m.circumradius * m.circumradius, value(e.circumradius2), 1e-12, n + " R²");
    expect_rel(m.volume * m.volume / static_cast<double>(value(e.volume2)), 1, 1e-12, n + " vol²");
    for (int i = 0; i <= d; ++i) {
      expect_rel(m.heights[i] * m.heights[i], value(e.heights2[i]), 1e-12, n + " h_i²");
      EXPECT_NEAR(m.circumcentre_barycentric[i], static_cast<double>(value(e.barycentric[i])), 1e-12) << n;
    }
    // Delaunay status, decided exactly by the signs of the barycentric coordinates.
    int lowest = 1;
    for (const Frac& x : e.barycentric) lowest = std::min(lowest, sign(x));
    const DelaunayStatus exact = lowest > 0    ? DelaunayStatus::yes
                                 : lowest == 0 ? DelaunayStatus::degenerate
                                               : DelaunayStatus::no;
    EXPECT_EQ(q.delaunay.status, exact) << n;
    if (exact == DelaunayStatus::yes) {
      long double delta = 1e300L;
      const long double R = std::sqrt(value(e.circumradius2));
      for (int j = 0; j <= d; ++j)
        delta = std::min(delta, std::sqrt(value(e.circumradius2 + Frac(4) * e.heights2[j] * e.barycentric[j])) - R);
      expect_rel(*q.delaunay.protection, delta / std::sqrt(value(e.longest2)), 1e-12, n + " δ/L");
    }
    // vol(alcove)·|W| = covolume of the coroot lattice, exactly.
    const Frac w = Frac(static_cast<long long>(weyl_group_order(f, d)));
    EXPECT_TRUE(e.volume2 * w * w == e.coroot_det) << n;
  }
  // Ẽ8: the coroot lattice is the unimodular E8 lattice, so vol = 1/|W(E8)| = 1/696729600 exactly.
  const ExactAlcove e8 = exact_alcove(Family::E, 8);
  EXPECT_TRUE(e8.volume2 == Frac(1) / Frac(696729600LL * 696729600LL));
  EXPECT_NEAR(coxeter_quality(Family::E, 8, 0).measures.volume * 696729600.0, 1, 1e-12);
}

// ---- Delaunay property -----------------------------------------------------------------------------

TEST(Delaunay, CriterionAndDirectCheckAgreeForEveryTypeUpToDimension8) {
  int delaunay = 0, not_delaunay = 0;
  for (auto [f, d] : all_types_up_to(8)) {
    const std::string n = name(f, d);
    const CoxeterQuality q = coxeter_quality(f, d, 2);
    ASSERT_TRUE(q.delaunay_direct) << n;
    EXPECT_EQ(q.delaunay.status, q.delaunay_direct->status) << n;
    EXPECT_EQ(q.delaunay.protection.has_value(), q.delaunay_direct->protection.has_value()) << n;
    if (q.delaunay.protection) {
      EXPECT_NEAR(*q.delaunay.protection, *q.delaunay_direct->protection, 1e-12) << n;
    }
    // A larger neighbourhood (depth 3) finds no closer vertex: the nearest ones are the mirror images.
    if (d <= 6) {
      const DelaunayResult deeper = delaunay_direct(generate_by_depth(fundamental_alcove(f, d), 3));
      EXPECT_EQ(deeper.status, q.delaunay.status) << n;
      if (q.delaunay.protection) {
        EXPECT_NEAR(*deeper.protection, *q.delaunay.protection, 1e-12) << n;
      }
    }
    const DelaunayStatus expected = f == Family::A                                         ? DelaunayStatus::yes
                                    : (f == Family::C || f == Family::F || f == Family::G) ? DelaunayStatus::degenerate
                                                                                           : DelaunayStatus::no;
    EXPECT_EQ(q.delaunay.status, expected) << n;
    (q.delaunay.status == DelaunayStatus::no ? not_delaunay : delaunay)++;
  }
  EXPECT_GT(delaunay, 0);
  EXPECT_GT(not_delaunay, 0);  // the thesis: not all Coxeter triangulations are Delaunay
}
