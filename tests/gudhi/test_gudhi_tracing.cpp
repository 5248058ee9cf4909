// Cross-check of manifold tracing and of the cell complex against the reference implementation
// (GUDHI's Coxeter_triangulation module, thesis §4.2, §4.3, §4.4): on the same triangulation (GUDHI's Ã_d
// matrix, scaled, same offset, passed explicitly to coxmesh::Triangulation), the same manifold and
// the same seed, both must trace the SAME SET of k-simplices (and of boundary (k+1)-simplices), at the
// same points, and build cell complexes with the same cells (ambient simplices) in every dimension.
//
// GUDHI accepts λ in the closed [0,1] (floating point, column-pivoting QR); coxmesh decides with the
// exact lexicographic rule. The two agree whenever no lattice vertex lies on M̂, which the three
// configurations of thesis §4.4 and random offsets (fixed RNG seed) guarantee in practice.
//
// GUDHI is only called here; its simplices are converted to coxmesh::Simplex and compared as sorted
// vectors.
#include <gtest/gtest.h>

// GUDHI's headers are included as system headers (see tests/CMakeLists.txt): their warnings are not ours.
#include <gudhi/Coxeter_triangulation.h>
#include <gudhi/Coxeter_triangulation/Cell_complex/Cell_complex.h>
#include <gudhi/Functions/Cartesian_product.h>
#include <gudhi/Functions/Function_Sm_in_Rd.h>
#include <gudhi/Functions/Function_affine_plane_in_Rd.h>
#include <gudhi/Functions/Function_moment_curve_in_Rd.h>
#include <gudhi/Functions/Function_torus_in_R3.h>
#include <gudhi/Implicit_manifold_intersection_oracle.h>
#include <gudhi/Manifold_tracing.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"
#include "coxmesh/triangulation/triangulation.h"
#include "gudhi_interop.h"

namespace {

namespace gct = Gudhi::coxeter_triangulation;
using GTriangulation = gct::Coxeter_triangulation<>;
using GSimplex = GTriangulation::Simplex_handle;
using GMap = gct::Manifold_tracing<GTriangulation>::Out_simplex_map;
using GCellComplex = gct::Cell_complex<GMap>;
using coxmesh::Simplex;
using gudhi_interop::from_gudhi;

constexpr std::uint64_t kSeed = 0x7AC1E5EEDull;

// What one library produced: traced simplices with their points (sorted by simplex), and the
// ambient simplices of the cells of every dimension (sorted), interior and boundary.
struct Outcome {
  std::vector<std::pair<Simplex, std::vector<double>>> interior, boundary;
  std::vector<std::vector<Simplex>> interior_cells, boundary_cells;

  std::vector<Simplex> interior_simplices() const { return keys(interior); }
  std::vector<Simplex> boundary_simplices() const { return keys(boundary); }
  std::vector<std::size_t> cell_counts() const { return counts(interior_cells); }
  std::vector<std::size_t> boundary_cell_counts() const { return counts(boundary_cells); }

 private:
  static std::vector<Simplex> keys(const std::vector<std::pair<Simplex, std::vector<double>>>& v) {
    std::vector<Simplex> out;
    for (const auto& [s, p] : v) out.push_back(s);
    return out;
  }
  static std::vector<std::size_t> counts(const std::vector<std::vector<Simplex>>& levels) {
    std::vector<std::size_t> out;
    for (const auto& l : levels) out.push_back(l.size());
    return out;
  }
};

bool by_simplex(const std::pair<Simplex, std::vector<double>>& a, const std::pair<Simplex, std::vector<double>>& b) {
  return a.first < b.first;
}

// ---- GUDHI ------------------------------------------------------------------------------------------

std::vector<std::pair<Simplex, std::vector<double>>> from_gudhi_map(const GMap& map) {
  std::vector<std::pair<Simplex, std::vector<double>>> out;
  for (const auto& [s, p] : map) out.emplace_back(from_gudhi(s), std::vector<double>(p.data(), p.data() + p.size()));
  std::sort(out.begin(), out.end(), by_simplex);
  return out;
}

std::vector<Simplex> from_gudhi_cells(const GCellComplex::Simplex_cell_map& map) {
  std::vector<Simplex> out;
  for (const auto& [s, cell] : map) out.push_back(from_gudhi(s));
  std::sort(out.begin(), out.end());
  return out;
}

// Domain = nullptr_t: no domain (GUDHI's default Constant_function(-1)).
template <class Function, class Domain = std::nullptr_t>
Outcome run_gudhi(const Eigen::MatrixXd& matrix, const Eigen::VectorXd& offset, const Function& f,
                  const std::vector<double>& seed, const Domain& domain = nullptr) {
  const int d = static_cast<int>(matrix.rows());
  const int m = d - static_cast<int>(f.cod_d());
  GTriangulation cox(d);
  cox.change_matrix(matrix);
  cox.change_offset(offset);
  const std::vector<Eigen::VectorXd> seeds{Eigen::Map<const Eigen::VectorXd>(seed.data(), d)};
  GMap interior, boundary;
  GCellComplex cc(m);
  if constexpr (std::is_same_v<Domain, std::nullptr_t>) {
    const auto oracle = gct::make_oracle(f);
    gct::manifold_tracing_algorithm(seeds, cox, oracle, interior);
    cc.construct_complex(interior);
  } else {
    const auto oracle = gct::make_oracle(f, domain);
    gct::manifold_tracing_algorithm(seeds, cox, oracle, interior, boundary);
    cc.construct_complex(interior, boundary);
  }
  Outcome o;
  o.interior = from_gudhi_map(interior);
  o.boundary = from_gudhi_map(boundary);
  for (int j = 0; j <= m; ++j) o.interior_cells.push_back(from_gudhi_cells(cc.interior_simplex_cell_map(j)));
  if constexpr (!std::is_same_v<Domain, std::nullptr_t>)
    for (int j = 0; j < m; ++j) o.boundary_cells.push_back(from_gudhi_cells(cc.boundary_simplex_cell_map(j)));
  else
    o.boundary_cells.assign(m, {});
  return o;
}

// ---- coxmesh ----------------------------------------------------------------------------------------

struct CoxmeshOutcome : Outcome {
  coxmesh::TopologyReport topology;
  std::uint64_t function_evaluations = 0;
};

std::vector<std::pair<Simplex, std::vector<double>>> from_index(const coxmesh::PackedKeyIndex& index,
                                                                const coxmesh::PointArray& points, int d) {
  std::vector<std::pair<Simplex, std::vector<double>>> out;
  for (std::uint32_t i = 0; i < index.size(); ++i)
    out.emplace_back(index.simplex(i, d), std::vector<double>(points.begin() + i * d, points.begin() + (i + 1) * d));
  std::sort(out.begin(), out.end(), by_simplex);
  return out;
}

std::vector<Simplex> from_level(const coxmesh::CellLevel& level, int d) {
  std::vector<Simplex> out;
  for (std::uint32_t c = 0; c < level.size(); ++c) out.push_back(level.simplices.simplex(c, d));
  std::sort(out.begin(), out.end());
  return out;
}

CoxmeshOutcome run_coxmesh(const Eigen::MatrixXd& matrix, const Eigen::VectorXd& offset, coxmesh::FunctionPtr f,
                           const std::vector<double>& seed, coxmesh::FunctionPtr domain = nullptr) {
  const coxmesh::Triangulation t(matrix, offset);
  const int d = t.dimension();
  coxmesh::ImplicitOracle oracle(t, std::move(f), std::move(domain));
  coxmesh::TraceResult r = coxmesh::trace_manifold(t, oracle, {seed});
  EXPECT_EQ(r.status, coxmesh::TraceStatus::complete) << r.message;
  CoxmeshOutcome o;
  o.function_evaluations = r.function_evaluations;
  o.interior = from_index(r.simplices, r.points, d);
  o.boundary = from_index(r.boundary_simplices, r.boundary_points, d);
  const coxmesh::CellComplex cc = coxmesh::build_cell_complex(std::move(r));
  for (const auto& level : cc.interior) o.interior_cells.push_back(from_level(level, d));
  for (const auto& level : cc.boundary) o.boundary_cells.push_back(from_level(level, d));
  o.topology = coxmesh::analyze_topology(cc);
  return o;
}

// ---- Comparison -------------------------------------------------------------------------------------

std::string list(const std::vector<std::size_t>& v) {
  std::ostringstream os;
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? "/" : "") << v[i];
  return os.str();
}

// Prints up to 5 simplices in one sorted vector and not in the other.
std::string difference(const std::vector<Simplex>& a, const std::vector<Simplex>& b) {
  std::vector<Simplex> only;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only));
  std::ostringstream os;
  os << only.size();
  for (std::size_t i = 0; i < only.size() && i < 5; ++i) os << "\n    " << only[i];
  return os.str();
}

void expect_same_simplices(const std::vector<Simplex>& gudhi, const std::vector<Simplex>& ours,
                           const std::string& what) {
  EXPECT_EQ(gudhi.size(), ours.size()) << what;
  EXPECT_TRUE(gudhi == ours) << what << ": only in GUDHI: " << difference(gudhi, ours)
                             << "\n  only in coxmesh: " << difference(ours, gudhi);
}

// Largest distance between the points of the same simplex (both lists sorted by simplex and equal).
double max_point_distance(const std::vector<std::pair<Simplex, std::vector<double>>>& a,
                          const std::vector<std::pair<Simplex, std::vector<double>>>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (!(a[i].first == b[i].first)) return INFINITY;
    double s = 0;
    for (std::size_t j = 0; j < a[i].second.size(); ++j) s += std::pow(a[i].second[j] - b[i].second[j], 2);
    worst = std::max(worst, std::sqrt(s));
  }
  return worst;
}

// The whole comparison; `scale` = the triangulation's scale, for the point tolerance.
void expect_agreement(const Outcome& gudhi, const CoxmeshOutcome& ours, double scale, const std::string& what) {
  ASSERT_FALSE(gudhi.interior.empty()) << what << ": GUDHI traced nothing (its seed simplex misses M̂)";
  expect_same_simplices(gudhi.interior_simplices(), ours.interior_simplices(), what + ", traced k-simplices");
  expect_same_simplices(gudhi.boundary_simplices(), ours.boundary_simplices(), what + ", boundary (k+1)-simplices");
  ASSERT_EQ(gudhi.interior_cells.size(), ours.interior_cells.size()) << what;
  ASSERT_EQ(gudhi.boundary_cells.size(), ours.boundary_cells.size()) << what;
  for (std::size_t j = 0; j < gudhi.interior_cells.size(); ++j)
    expect_same_simplices(gudhi.interior_cells[j], ours.interior_cells[j],
                          what + ", interior cells of dim " + std::to_string(j));
  for (std::size_t j = 0; j < gudhi.boundary_cells.size(); ++j)
    expect_same_simplices(gudhi.boundary_cells[j], ours.boundary_cells[j],
                          what + ", boundary cells of dim " + std::to_string(j));
  EXPECT_EQ(list(gudhi.cell_counts()), list(ours.topology.cells)) << what;
  EXPECT_EQ(list(gudhi.boundary_cell_counts()), list(ours.topology.boundary_cells)) << what;
  // Same points: both are Σ λ_j v_j of the PL interpolant (boundary: the point of μ where F̂ = D̂ = 0),
  // computed by different solvers, so equal up to rounding.
  EXPECT_LE(max_point_distance(gudhi.interior, ours.interior), 1e-9 * scale) << what;
  EXPECT_LE(max_point_distance(gudhi.boundary, ours.boundary), 1e-9 * scale) << what;
  EXPECT_TRUE(ours.topology.is_manifold) << what << ": " << ours.topology.manifold_problem;
  testing::Test::RecordProperty(what, static_cast<int>(ours.interior.size()));
}

Eigen::MatrixXd gudhi_matrix(int d, double scale) { return scale * GTriangulation(d).matrix(); }

Eigen::VectorXd random_offset(std::mt19937_64& rng, int d, double scale) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd b(d);
  for (int i = 0; i < d; ++i) b(i) = scale * u(rng);
  return b;
}

Eigen::VectorXd to_eigen(const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size()); }

}  // namespace

// ---- The three worked configurations of GUDHI (thesis §4.4) ---------------------------------------------------------

TEST(GudhiTracing, SphereS2InR3_Spec) {
  const double r = 5.1111;
  const Eigen::MatrixXd a = gudhi_matrix(3, 1.0);
  const Eigen::VectorXd b = Eigen::VectorXd::Zero(3);
  const std::vector<double> seed{r, 0, 0};
  const Outcome g = run_gudhi(a, b, gct::Function_Sm_in_Rd(r, 2), seed);
  const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::sphere(2, 3, r), seed);
  EXPECT_EQ(g.interior.size(), 1118u);
  EXPECT_EQ(list(c.topology.cells), "1118/2820/1704");
  EXPECT_EQ(c.topology.euler_characteristic, 2);
  expect_agreement(g, c, 1.0, "S^2 r=5.1111 in R^3");
}

TEST(GudhiTracing, SphereS2InR3WithBallDomain_Spec) {
  const double r = 5.1111;
  const Eigen::MatrixXd a = gudhi_matrix(3, 1.0);
  const Eigen::VectorXd b = Eigen::VectorXd::Zero(3);
  const std::vector<double> seed{r, 0, 0};
  const Outcome g = run_gudhi(a, b, gct::Function_Sm_in_Rd(r, 2), seed, gct::Function_Sm_in_Rd(3.0, 2, to_eigen(seed)));
  const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::sphere(2, 3, r), seed, coxmesh::ball_domain(seed, 3.0));
  EXPECT_EQ(g.interior.size(), 96u);
  EXPECT_EQ(g.boundary.size(), 54u);
  EXPECT_EQ(list(c.topology.cells), "96/271/176");
  EXPECT_EQ(list(c.topology.boundary_cells), "54/54");
  EXPECT_EQ(c.topology.euler_characteristic, 1);
  expect_agreement(g, c, 1.0, "S^2 r=5.1111 in R^3, ball domain r=3");
}

TEST(GudhiTracing, CircleInR2WithOffset_Spec) {
  const Eigen::MatrixXd a = gudhi_matrix(2, 1.0);
  const Eigen::VectorXd b = (Eigen::VectorXd(2) << 0.1, 0.2).finished();
  const std::vector<double> seed{1, 0};
  const Outcome g = run_gudhi(a, b, gct::Function_Sm_in_Rd(1.0, 1), seed);
  const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::sphere(1, 2, 1.0), seed);
  expect_agreement(g, c, 1.0, "S^1 r=1 in R^2, offset (0.1,0.2)");
  EXPECT_EQ(list(c.topology.cells), "12/12");
  // GUDHI: the 12 simplices and their points.
  const std::vector<std::pair<std::string, std::vector<double>>> expected{
      {"(0,0) [{0},{1,2}]", {0.1, 0.811050152}},
      {"(0,0) [{0,1},{2}]", {0.638465284, 0.510883077}},
      {"(0,0) [{1},{0,2}]", {0.829426398, -0.221134528}},
      {"(0,-1) [{1},{0,2}]", {-0.596341343, 0.602032862}},
      {"(-1,0) [{0,1},{2}]", {0.282268674, -0.84946767}},
      {"(-1,0) [{1},{0,2}]", {0.129800846, -0.971906065}},
      {"(-1,-1) [{0},{1,2}]", {-0.9, -0.258333333}},
      {"(-1,-2) [{1},{0,2}]", {-0.917647781, -0.367161318}},
      {"(-2,-1) [{0,1},{2}]", {0.0648674022, -0.974984353}},
      {"(-2,-1) [{0},{1,2}]", {-0.9, -0.4022831}},
      {"(-2,-2) [{0,1},{2}]", {-0.913338743, -0.385051396}},
      {"(-2,0) [{0},{1,2}]", {0.1, -0.980335094}}};
  ASSERT_EQ(c.interior.size(), expected.size());
  for (const auto& [text, point] : expected) {
    const Simplex s = coxmesh::parse_simplex(text);
    const auto it = std::find_if(c.interior.begin(), c.interior.end(), [&](const auto& e) { return e.first == s; });
    ASSERT_NE(it, c.interior.end()) << text << " not traced";
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(it->second[i], point[i], 1e-8) << text;
  }
}

// ---- Random offsets -------------------------------------------------------------------------------------

struct SphereCase {
  int m, d;
  double radius, scale;
};

class GudhiTracingSphere : public testing::TestWithParam<SphereCase> {};

TEST_P(GudhiTracingSphere, RandomOffset) {
  const SphereCase p = GetParam();
  std::mt19937_64 rng(kSeed + 100 * p.d + p.m);
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(p.d, p.scale);
    std::vector<double> seed(p.d, 0.0);
    seed[0] = p.radius;
    // GUDHI only tests the k-faces of the simplex located at the seed (thesis §4.2): at coarse
    // scales in high codimension it may trace nothing. Like the thesis' experiment programs, draw
    // another offset then (coxmesh, which searches around the seed, would trace either way).
    Eigen::VectorXd b;
    Outcome g;
    for (int attempt = 0; attempt < 20 && g.interior.empty(); ++attempt) {
      b = random_offset(rng, p.d, p.scale);
      g = run_gudhi(a, b, gct::Function_Sm_in_Rd(p.radius, p.m, p.d), seed);
    }
    const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::sphere(p.m, p.d, p.radius), seed);
    const std::string what =
        "S^" + std::to_string(p.m) + " in R^" + std::to_string(p.d) + ", trial " + std::to_string(trial);
    expect_agreement(g, c, p.scale, what);
    EXPECT_EQ(c.topology.euler_characteristic, p.m % 2 == 0 ? 2 : 0) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Spheres, GudhiTracingSphere,
                         testing::Values(SphereCase{1, 2, 1.0, 0.05}, SphereCase{1, 3, 1.0, 0.05},
                                         SphereCase{2, 3, 1.0, 0.14}, SphereCase{1, 4, 1.0, 0.05},
                                         SphereCase{2, 4, 1.0, 0.22}, SphereCase{3, 4, 1.0, 0.37},
                                         SphereCase{1, 5, 1.0, 0.05}, SphereCase{2, 5, 1.0, 0.3},
                                         SphereCase{3, 5, 1.0, 0.55}, SphereCase{1, 6, 1.0, 0.05},
                                         SphereCase{2, 6, 1.0, 0.4}, SphereCase{3, 6, 1.0, 0.65}),
                         [](const testing::TestParamInfo<SphereCase>& info) {
                           std::ostringstream os;  // (not operator+: GCC 12 warns falsely, -Wrestrict)
                           os << "S" << info.param.m << "inR" << info.param.d;
                           return os.str();
                         });

TEST(GudhiTracing, TorusInR3RandomOffset) {
  std::mt19937_64 rng(kSeed + 7);
  const double major = 1.0, minor = 0.4, scale = 0.1;
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(3, scale);
    const Eigen::VectorXd b = random_offset(rng, 3, scale);
    const std::vector<double> seed{major + minor, 0, 0};
    // GUDHI's Function_torus_in_R3(R, r) is z² + (√(x²+y²) − r)² − R²: r is the major radius.
    const Outcome g = run_gudhi(a, b, gct::Function_torus_in_R3(minor, major), seed);
    const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::torus(major, minor), seed);
    expect_agreement(g, c, scale, "torus in R^3, trial " + std::to_string(trial));
    EXPECT_EQ(c.topology.euler_characteristic, 0);
    EXPECT_EQ(list(c.topology.betti), "1/2/1");
  }
}

TEST(GudhiTracing, FlatTorusInR4RandomOffset) {
  std::mt19937_64 rng(kSeed + 8);
  const double r = 1.0, scale = 0.25;
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(4, scale);
    const Eigen::VectorXd b = random_offset(rng, 4, scale);
    const std::vector<double> seed{r, 0, r, 0};
    const auto circle = gct::Function_Sm_in_Rd(r, 1);
    const Outcome g = run_gudhi(a, b, gct::make_product_function(circle, circle), seed);
    const CoxmeshOutcome c =
        run_coxmesh(a, b, coxmesh::product(coxmesh::sphere(1, 2, r), coxmesh::sphere(1, 2, r)), seed);
    expect_agreement(g, c, scale, "flat torus in R^4, trial " + std::to_string(trial));
    EXPECT_EQ(c.topology.euler_characteristic, 0);
    EXPECT_EQ(list(c.topology.betti), "1/2/1");
  }
}

// ---- Manifolds with boundary, random offsets ------------------------------------------------------------

TEST(GudhiTracing, SphereInR3WithBallDomainRandomOffset) {
  std::mt19937_64 rng(kSeed + 9);
  const double r = 1.0, scale = 0.08;
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(3, scale);
    const Eigen::VectorXd b = random_offset(rng, 3, scale);
    const std::vector<double> seed{r, 0, 0};
    const Outcome g =
        run_gudhi(a, b, gct::Function_Sm_in_Rd(r, 2), seed, gct::Function_Sm_in_Rd(0.7, 2, to_eigen(seed)));
    const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::sphere(2, 3, r), seed, coxmesh::ball_domain(seed, 0.7));
    expect_agreement(g, c, scale, "S^2 in R^3 cut by a ball, trial " + std::to_string(trial));
    EXPECT_FALSE(c.boundary.empty());
    EXPECT_EQ(c.topology.euler_characteristic, 1);  // a disk
  }
}

TEST(GudhiTracing, FlatTorusInR4CutByHyperplaneRandomOffset) {
  std::mt19937_64 rng(kSeed + 10);
  const double r = 1.0, scale = 0.25;
  // Half-space ⟨n, x⟩ < ⟨n, p⟩ with a unit normal n; GUDHI's affine plane normalises its normal and
  // evaluates nᵀ(x − p).
  Eigen::VectorXd n(4);
  n << 0.3, -0.2, 0.9, 0.25;
  n.normalize();
  const Eigen::VectorXd p = (Eigen::VectorXd(4) << 0.1, 0.2, 0.3, 0.4).finished();
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(4, scale);
    const Eigen::VectorXd b = random_offset(rng, 4, scale);
    const std::vector<double> seed{-r, 0, 0, r};  // ⟨n, seed⟩ < ⟨n, p⟩: inside
    const auto circle = gct::Function_Sm_in_Rd(r, 1);
    const Outcome g = run_gudhi(a, b, gct::make_product_function(circle, circle), seed,
                                gct::Function_affine_plane_in_Rd(Eigen::MatrixXd(n), p));
    const CoxmeshOutcome c = run_coxmesh(a, b, coxmesh::product(coxmesh::sphere(1, 2, r), coxmesh::sphere(1, 2, r)),
                                         seed, coxmesh::half_space_domain({n[0], n[1], n[2], n[3]}, n.dot(p)));
    expect_agreement(g, c, scale, "flat torus in R^4 cut by a hyperplane, trial " + std::to_string(trial));
    EXPECT_FALSE(c.boundary.empty());
  }
}

TEST(GudhiTracing, MomentCurveInR6InBallRandomOffset) {
  std::mt19937_64 rng(kSeed + 11);
  const int d = 6;
  const double scale = 0.02;
  for (int trial = 0; trial < 2; ++trial) {
    const Eigen::MatrixXd a = gudhi_matrix(d, scale);
    const Eigen::VectorXd b = random_offset(rng, d, scale);
    const coxmesh::FunctionPtr f = coxmesh::moment_curve(d);
    const std::vector<double> seed = f->seed();  // t = 1/2
    const std::vector<double> centre(d, 0.0);
    const Outcome g = run_gudhi(a, b, gct::Function_moment_curve_in_Rd(1.0, d), seed,
                                gct::Function_Sm_in_Rd(1.2, d - 1, Eigen::VectorXd::Zero(d)));
    const CoxmeshOutcome c = run_coxmesh(a, b, f, seed, coxmesh::ball_domain(centre, 1.2));
    expect_agreement(g, c, scale, "moment curve in R^6 inside a ball, trial " + std::to_string(trial));
    EXPECT_EQ(c.boundary.size(), 2u);  // an arc: two end points
    EXPECT_EQ(c.topology.euler_characteristic, 1);
  }
}
