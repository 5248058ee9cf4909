// Point clouds (thesis Ch. 4): samples of known manifolds, clean and noisy, traced through the
// point-cloud function and tube; the Z/2 Betti numbers and the manifold check must come out right,
// a non-orientable RP² ⊂ R⁴ must be flagged, and real samples nobody here made (CGAL's data) must
// give their known topology with the default parameters.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <new>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/point_reader.h"
#include "coxmesh/mesh/mesh_local_pca.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/local_pca_oracle.h"
#include "coxmesh/tracing/point_cloud_problem.h"
#include "point_samples.h"

using namespace coxmesh;
namespace fs = std::filesystem;

// Every allocation of this test program is counted: the point-cloud functions must not allocate
// when evaluated (they are called once per lattice vertex, millions of times). Not with
// AddressSanitizer, which has its own operator new.
#ifndef __SANITIZE_ADDRESS__
static std::atomic<std::size_t> allocations{0};
// (Not inlined: GCC would otherwise pair the malloc and free across the replacement operators.)
[[gnu::noinline]] void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace {

struct Outcome {
  PointCloudDiagnostics diagnostics;
  TopologyReport topology;
  std::size_t simplices = 0;
  TraceStatus status = TraceStatus::complete;
};

Outcome mesh(std::vector<double> points, int d, int m, const PointCloudOptions& options = {}, int threads = 1) {
  PointCloudProblem p = make_point_cloud_problem(std::move(points), d, m, options);
  const Triangulation t = Triangulation::coxeter(d).with_longest_edge(p.edge_length).with_offset(p.centre());
  TraceOptions to;
  to.skip_unusable_seeds = true;
  to.threads = threads;
  auto shared = threads > 1 ? ImplicitOracle::make_shared_values(t, p.function, p.domain) : nullptr;
  TraceResult r = trace_manifold(
      t, [&] { return std::make_unique<ImplicitOracle>(t, p.function, p.domain, shared); }, p.seeds, to);
  Outcome out;
  out.status = r.status;
  out.simplices = r.simplices.size();
  out.diagnostics = p.diagnostics;
  out.topology = analyze_topology(build_cell_complex(std::move(r)));
  return out;
}

struct Case {
  const char* name;
  std::size_t n;
  std::vector<std::size_t> betti;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name << " (" << c.n << " samples)"; }

class Synthetic : public ::testing::TestWithParam<std::tuple<Case, double, PointCloudFunction>> {};

TEST_P(Synthetic, RightTopology) {
  const auto& [c, noise, function] = GetParam();
  const test::Samples s = test::sample_manifold(c.name, c.n, noise);
  PointCloudOptions options;
  options.function = function;
  const Outcome o = mesh(s.points, s.d, s.m, options);
  EXPECT_EQ(o.status, TraceStatus::complete);
  EXPECT_TRUE(o.topology.is_manifold) << o.topology.manifold_problem;
  EXPECT_EQ(o.topology.betti, c.betti);
  EXPECT_FALSE(o.diagnostics.frames_inconsistent) << o.diagnostics.warning;
  EXPECT_TRUE(o.diagnostics.dimension_warning.empty()) << o.diagnostics.dimension_warning;
  EXPECT_GE(o.diagnostics.apparent_dimension, s.m);  // (more with curvature and noise)
  // (Around a closed space curve the frames carried along the tree meet again turned by the
  // holonomy of the normal bundle: a few edges there are frustrated, far fewer than flag it.)
  if (s.m >= 2 || s.d == 2) {
    EXPECT_EQ(o.diagnostics.frustrated_edges, 0u);
  }
  const bool with_boundary = std::string(c.name) == "patch";
  const bool has_boundary = !o.topology.boundary_cells.empty() && o.topology.boundary_cells[0] > 0;
  EXPECT_EQ(has_boundary, with_boundary);
}

// Noise 0.01 in every coordinate: about 1/4 of the sample spacing for surfaces (1/7 for S³, 2/3 for
// the trefoil knot, 1 for the circle; random samples of a curve also have gaps of ln(n) mean
// spacings, which the tube must span).
INSTANTIATE_TEST_SUITE_P(
    PointClouds, Synthetic,
    ::testing::Combine(::testing::Values(Case{"circle", 500, {1, 1}}, Case{"trefoil", 2000, {1, 1}},
                                         Case{"sphere", 2000, {1, 0, 1}}, Case{"torus", 2000, {1, 2, 1}},
                                         Case{"flat-torus", 2000, {1, 2, 1}}, Case{"s3", 2000, {1, 0, 0, 1}},
                                         Case{"two-spheres", 2000, {2, 0, 2}}, Case{"patch", 2000, {1, 0, 0}}),
                       ::testing::Values(0.0, 0.01), ::testing::Values(PointCloudFunction::blended)),
    [](const auto& info) {
      std::string name = std::get<0>(info.param).name;
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name + (std::get<1>(info.param) > 0 ? "_noisy" : "_clean");
    });

// The nearest-frame function on a few of them, and the denser noisy torus where both must hold.
INSTANTIATE_TEST_SUITE_P(Nearest, Synthetic,
                         ::testing::Combine(::testing::Values(Case{"sphere", 2000, {1, 0, 1}},
                                                              Case{"torus", 4000, {1, 2, 1}},
                                                              Case{"flat-torus", 2000, {1, 2, 1}}),
                                            ::testing::Values(0.0, 0.01),
                                            ::testing::Values(PointCloudFunction::nearest)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param).name;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name + (std::get<1>(info.param) > 0 ? "_noisy" : "_clean");
                         });

TEST(PointCloud, NonOrientableIsFlagged) {
  // RP² and the Klein bottle in R⁴ are not orientable: no single-valued function R⁴ → R² has
  // them as its zero set (the zero set of such a function is orientable). The frames must say so,
  // clean or noisy.
  for (const char* name : {"rp2", "klein"}) {
    for (double noise : {0.0, 0.01}) {
      const test::Samples s = test::sample_manifold(name, 3000, noise);
      const Outcome o = mesh(s.points, s.d, s.m);
      EXPECT_TRUE(o.diagnostics.frames_inconsistent) << name << " " << noise;
      EXPECT_GT(o.diagnostics.frustrated_edges, o.diagnostics.compared_edges / 100);
      EXPECT_NE(o.diagnostics.warning.find("cannot be trusted"), std::string::npos);
      EXPECT_NE(o.diagnostics.warning.find(std::to_string(o.diagnostics.frustrated_edges)), std::string::npos);
      EXPECT_TRUE(o.topology.is_manifold);  // still a PL manifold: only its topology is wrong
      EXPECT_NE(o.topology.betti[2], 1u);   // RP² and the Klein bottle are closed: β₂ = 1 over Z/2
    }
  }
}

TEST(PointCloud, LowerDimensionalSamplesAreFlagged) {
  // Samples of a curve given as a surface (the default m = d − 1 for a space curve), of a surface in
  // R⁴ given as a 3-manifold: what is traced is a thin band or shell around them, a manifold of the
  // dimension asked for but with other Betti numbers, so the diagnostics must say so.
  struct Wrong {
    const char* name;
    int m;
  };
  // (Noise 0.001: a tenth of the trefoil's spacing.)
  for (const Wrong w : {Wrong{"trefoil", 2}, Wrong{"flat-torus", 3}, Wrong{"trefoil", 1}, Wrong{"sphere", 2}}) {
    for (double noise : {0.0, 0.001}) {
      const test::Samples s = test::sample_manifold(w.name, 1000, noise);
      const int m = w.m;
      const Outcome o = mesh(s.points, s.d, m);
      EXPECT_EQ(o.diagnostics.apparent_dimension, s.m) << w.name << " " << noise;
      if (m > s.m) {
        EXPECT_NE(o.diagnostics.dimension_warning.find("look " + std::to_string(s.m) + "-dimensional, not " +
                                                       std::to_string(m) + "-dimensional"),
                  std::string::npos)
            << w.name << ": " << o.diagnostics.dimension_warning;
      } else {
        EXPECT_TRUE(o.diagnostics.dimension_warning.empty()) << w.name << ": " << o.diagnostics.dimension_warning;
      }
    }
  }
}

TEST(PointCloud, ThreadsGiveTheSameResult) {
  // The functions are evaluated concurrently by the workers: same simplices, same topology.
  const test::Samples s = test::sample_manifold("torus", 3000, 0.01);
  const Outcome one = mesh(s.points, s.d, s.m, {}, 1), two = mesh(s.points, s.d, s.m, {}, 2);
  EXPECT_EQ(one.simplices, two.simplices);
  EXPECT_EQ(one.topology.cells, two.topology.cells);
  EXPECT_EQ(two.topology.betti, (std::vector<std::size_t>{1, 2, 1}));
}

TEST(PointCloud, PreparationThreadsGiveTheSameProblem) {
  // The spacing, the PCA and the edge checks run on the workers: every frame, count, seed and
  // function value must be bit for bit the same for any number of threads (noisy surfaces with
  // k = 1, a flat torus with k = 2 frames, and S³).
  const std::pair<const char*, std::size_t> cases[] = {{"torus", 3000}, {"flat-torus", 2000}, {"s3", 2000}};
  for (const auto& [name, n] : cases) {
    const test::Samples s = test::sample_manifold(name, n, 0.01);
    std::vector<PointCloudProblem> problems;
    for (int threads : {1, 2, 3, 8}) {
      PointCloudOptions options;
      options.threads = threads;
      problems.push_back(make_point_cloud_problem(s.points, s.d, s.m, options));
    }
    const SampleFrames& a = problems[0].model->frames;
    for (std::size_t i = 1; i < problems.size(); ++i) {
      const PointCloudProblem& p = problems[i];
      const SampleFrames& b = p.model->frames;
      EXPECT_EQ(p.diagnostics.spacing, problems[0].diagnostics.spacing) << name;
      EXPECT_EQ(b.centers, a.centers) << name;
      EXPECT_EQ(b.normals, a.normals) << name;
      EXPECT_EQ(b.flatness, a.flatness) << name;
      EXPECT_EQ(b.thickness, a.thickness) << name;
      EXPECT_EQ(b.within_radius, a.within_radius) << name;
      EXPECT_EQ(b.component, a.component) << name;
      EXPECT_EQ(b.mean_neighbours, a.mean_neighbours) << name;
      EXPECT_EQ(b.longest_gap, a.longest_gap) << name;
      EXPECT_EQ(b.graph_edges, a.graph_edges) << name;
      EXPECT_EQ(b.compared_edges, a.compared_edges) << name;
      EXPECT_EQ(b.frustrated_edges, a.frustrated_edges) << name;
      EXPECT_EQ(p.seeds, problems[0].seeds) << name;
      EXPECT_EQ(p.edge_length, problems[0].edge_length) << name;
      for (std::size_t j = 0; j < 200; ++j) {
        std::vector<double> x(s.points.begin() + j * s.d, s.points.begin() + (j + 1) * s.d);
        x[0] += 0.01 * static_cast<double>(j % 5);
        std::vector<double> u(s.d), v(s.d);
        problems[0].function->evaluate(x.data(), u.data());
        p.function->evaluate(x.data(), v.data());
        EXPECT_EQ(u, v) << name;
      }
    }
    EXPECT_GT(a.graph_edges, 0u);
  }
}

TEST(PointCloud, TubeReusesTheNearestSampleOfTheFunction) {
  // The tube takes the nearest sample's distance from the function's query at the same point when
  // there is one: the values must be those of a query of its own and of a brute-force search.
  for (const char* name : {"torus", "s3"}) {
    const test::Samples s = test::sample_manifold(name, 2000, 0.01);
    for (PointCloudFunction function : {PointCloudFunction::blended, PointCloudFunction::nearest}) {
      PointCloudOptions options;
      options.function = function;
      const PointCloudProblem p = make_point_cloud_problem(s.points, s.d, s.m, options);
      const PointCloudProblem other = make_point_cloud_problem(test::sample_manifold(name, 500).points, s.d, s.m);
      std::vector<double> x(s.d), value(s.d);
      for (std::size_t i = 0; i < 300; ++i) {
        for (int t = 0; t < s.d; ++t) x[t] = s.points[i * s.d + t] * (1 + 0.2 * ((i % 9) - 4.0) / 4);
        double alone, after_function, after_other;
        p.domain->evaluate(x.data(), &alone);
        p.function->evaluate(x.data(), value.data());
        p.domain->evaluate(x.data(), &after_function);
        other.function->evaluate(x.data(), value.data());  // another model's memo must not be used
        p.domain->evaluate(x.data(), &after_other);
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < s.size(); ++j) {
          double d2 = 0;
          for (int t = 0; t < s.d; ++t) d2 += (x[t] - s.points[j * s.d + t]) * (x[t] - s.points[j * s.d + t]);
          best = std::min(best, d2);
        }
        EXPECT_EQ(after_function, alone) << name;
        EXPECT_EQ(after_other, alone) << name;
        EXPECT_NEAR(alone, std::sqrt(best) - p.diagnostics.tube_radius, 1e-12) << name;
      }
    }
  }
}

TEST(PointCloud, DefaultsFollowTheSpacing) {
  const test::Samples s = test::sample_manifold("sphere", 2000);
  PointCloudProblem p = make_point_cloud_problem(s.points, 3, 2);
  const PointCloudDiagnostics& g = p.diagnostics;
  EXPECT_GT(g.spacing, 0.02);  // 2000 random points on the unit sphere: about 0.037
  EXPECT_LT(g.spacing, 0.06);
  EXPECT_LT(g.thickness, 0.5 * g.spacing);  // clean samples: the coarser edge lengths
  EXPECT_GT(g.curvature_radius, 0.8);       // the unit sphere's radius, from the thickness
  EXPECT_LT(g.curvature_radius, 1.25);
  EXPECT_DOUBLE_EQ(g.curvature_radius, g.radius * g.radius / (7 * g.thickness));
  EXPECT_DOUBLE_EQ(g.edge_length, g.curvature_radius / 5);  // dense for its curvature: 5.5 spacings
  EXPECT_GT(g.edge_length, 2.5 * g.spacing);
  EXPECT_LT(g.edge_length, 6 * g.spacing);
  EXPECT_DOUBLE_EQ(g.radius, 5 * g.spacing);
  EXPECT_DOUBLE_EQ(g.tube_radius, 3 * g.edge_length);
  EXPECT_EQ(g.components, 1u);
  EXPECT_FALSE(p.seeds.empty());
  // F vanishes near the samples and changes sign across the sphere.
  double in[3] = {0.9, 0, 0}, out[3] = {1.1, 0, 0}, vin, vout;
  p.function->evaluate(in, &vin);
  p.function->evaluate(out, &vout);
  EXPECT_LT(vin * vout, 0);
  double far[3] = {5, 5, 5}, dv;
  p.domain->evaluate(far, &dv);
  EXPECT_GT(dv, 0);  // outside the tube
  EXPECT_EQ(make_point_cloud_problem(test::sample_manifold("two-spheres", 2000).points, 3, 2).diagnostics.components,
            2u);
  // Denser: a fifth of the radius of curvature is more than 6 spacings, the longest edge.
  const PointCloudDiagnostics dense =
      make_point_cloud_problem(test::sample_manifold("sphere", 10000).points, 3, 2).diagnostics;
  EXPECT_GT(dense.curvature_radius / 5, 6 * dense.spacing);
  EXPECT_DOUBLE_EQ(dense.edge_length, 6 * dense.spacing);
  // Sparser for its curvature: 2.5 spacings at least.
  const PointCloudDiagnostics sparse =
      make_point_cloud_problem(test::sample_manifold("torus", 1000).points, 3, 2).diagnostics;
  EXPECT_LT(sparse.thickness, 0.5 * sparse.spacing);
  EXPECT_LT(sparse.curvature_radius / 5, 2.5 * sparse.spacing);
  EXPECT_DOUBLE_EQ(sparse.edge_length, 2.5 * sparse.spacing);
  // Noise of about a spacing: the finer edge length of 2 spacings.
  const PointCloudDiagnostics noisy =
      make_point_cloud_problem(test::sample_manifold("sphere", 2000, 0.04).points, 3, 2).diagnostics;
  EXPECT_GT(noisy.thickness, 0.5 * noisy.spacing);
  EXPECT_DOUBLE_EQ(noisy.edge_length, 2 * noisy.spacing);
  // Noise beyond a spacing: edges of 2 thicknesses, a blend up to 1.5 times wider than 2 thicknesses.
  const PointCloudDiagnostics noisier =
      make_point_cloud_problem(test::sample_manifold("sphere", 2000, 0.1).points, 3, 2).diagnostics;
  EXPECT_GT(noisier.thickness, noisier.spacing);
  EXPECT_DOUBLE_EQ(noisier.edge_length, 2 * noisier.thickness);
  EXPECT_DOUBLE_EQ(noisier.blend_width, 2 * noisier.thickness * std::min(noisier.thickness / noisier.spacing, 1.5));
}

#ifndef __SANITIZE_ADDRESS__
TEST(PointCloud, EvaluationAllocatesNothing) {
  for (const char* name : {"torus", "flat-torus", "s3"}) {
    const test::Samples s = test::sample_manifold(name, 2000, 0.01);
    for (PointCloudFunction function : {PointCloudFunction::blended, PointCloudFunction::nearest}) {
      PointCloudOptions options;
      options.function = function;
      const PointCloudProblem p = make_point_cloud_problem(s.points, s.d, s.m, options);
      std::vector<double> x(s.d), value(s.d);
      const std::size_t before = allocations;
      for (std::size_t i = 0; i < 1000; ++i) {
        for (int t = 0; t < s.d; ++t) x[t] = s.points[i * s.d + t] * (1 + 0.05 * ((i % 7) - 3.0));  // near and far
        p.function->evaluate(x.data(), value.data());
        p.domain->evaluate(x.data(), value.data());
      }
      EXPECT_EQ(allocations - before, 0u) << name;
    }
  }
}
#endif

TEST(PointCloud, OutliersAreNotSeeds) {
  // 20 samples scattered in the box around a sphere: they must not seed little sheets of their own.
  test::Samples s = test::sample_manifold("sphere", 2000, 0.01);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> box(-2, 2);
  for (int i = 0; i < 20 * 3; ++i) s.points.push_back(box(rng));
  const Outcome o = mesh(s.points, 3, 2);
  EXPECT_EQ(o.topology.betti, (std::vector<std::size_t>{1, 0, 1}));
  EXPECT_GE(o.diagnostics.isolated_samples, 15u);
  EXPECT_LE(o.diagnostics.isolated_samples, 20u);
}

TEST(PointCloud, CloseSheetsKeepShortEdges) {
  // Two flat squares 0.2 apart (13 spacings): flat samples would allow the longest edge, 6
  // spacings, which joins them through hundreds of handles; half the feature size (the empty balls
  // between them, radius 0.1) keeps about 3.3.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> side(-1, 1);
  std::vector<double> points;
  for (double z : {0.0, 0.2})
    for (int i = 0; i < 4000; ++i) points.insert(points.end(), {side(rng), side(rng), z});
  const Outcome o = mesh(points, 3, 2);
  EXPECT_NEAR(o.diagnostics.feature_size, 0.1, 0.01);
  EXPECT_DOUBLE_EQ(o.diagnostics.edge_length, o.diagnostics.feature_size / 2);
  EXPECT_EQ(o.topology.betti, (std::vector<std::size_t>{2, 0, 0}));
  // One square alone: nothing nearby, the longest edge.
  points.resize(points.size() / 2);
  const Outcome alone = mesh(points, 3, 2);
  EXPECT_DOUBLE_EQ(alone.diagnostics.edge_length, 6 * alone.diagnostics.spacing);
  EXPECT_EQ(alone.topology.betti, (std::vector<std::size_t>{1, 0, 0}));
}

TEST(PointCloud, SeedsLieNearTheSurface) {
  // Noise of two spacings: farthest-point sampling picks the samples pushed furthest out (3-4σ),
  // which can be beyond the rings a seed's search looks through; moved onto F's zero set along
  // their normals, the seeds are within the noise of the sphere.
  const double sigma = 0.03;
  const test::Samples s = test::sample_manifold("sphere", 20000, sigma);
  const PointCloudProblem p = make_point_cloud_problem(s.points, 3, 2);
  ASSERT_EQ(p.seeds.size(), 8u);
  double farthest_sample = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    farthest_sample =
        std::max(farthest_sample, std::abs(std::hypot(s.points[3 * i], s.points[3 * i + 1], s.points[3 * i + 2]) - 1));
  EXPECT_GT(farthest_sample, 3 * sigma);
  for (const auto& seed : p.seeds) EXPECT_LT(std::abs(std::hypot(seed[0], seed[1], seed[2]) - 1), sigma);
}

TEST(PointCloud, GivenNormalsOrient) {
  test::Samples s = test::sample_manifold("sphere", 2000);
  PointCloudOptions options;
  options.normals = s.points;  // the outward normal of the unit sphere is the point itself
  const Outcome o = mesh(s.points, 3, 2, options);
  EXPECT_TRUE(o.diagnostics.used_given_normals);
  EXPECT_EQ(o.topology.betti, (std::vector<std::size_t>{1, 0, 1}));
}

TEST(PointCloud, BadInput) {
  const std::vector<double> three = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_THROW(make_point_cloud_problem(three, 3, 2), InputError);                                        // n < m + 2
  EXPECT_THROW(make_point_cloud_problem(test::sample_manifold("sphere", 100).points, 3, 3), InputError);  // m = d
  EXPECT_THROW(make_point_cloud_problem(test::sample_manifold("sphere", 100).points, 3, 0), InputError);
  std::vector<double> nan = test::sample_manifold("sphere", 100).points;
  nan[5] = std::nan("");
  EXPECT_THROW(make_point_cloud_problem(nan, 3, 2), InputError);
  PointCloudOptions bad;
  bad.edge_length = -1;
  EXPECT_THROW(make_point_cloud_problem(test::sample_manifold("sphere", 100).points, 3, 2, bad), InputError);
  const std::vector<double> same(30, 1.0);  // ten copies of one point
  EXPECT_THROW(make_point_cloud_problem(same, 3, 2), InputError);
}

// ---- Real samples: CGAL's data set (Debian libcgal-demo), extracted at test time ---------------

fs::path cgal_data() {
  const char* env = std::getenv("COXMESH_CGAL_DATA");
  const fs::path archive = env ? env : "/usr/share/doc/libcgal-dev/data.tar.gz";
  if (!fs::exists(archive)) return {};
  const fs::path dir = fs::path(COXMESH_TEST_BINARY_DIR) / "cgal_data";  // the build directory
  if (fs::exists(dir / "data/points_3/sphere_20k.xyz")) return dir / "data";
  // Extract to a private directory, then rename: tests running in parallel never see half a file.
  const fs::path tmp = dir.parent_path() / ("cgal_data.tmp." + std::to_string(::getpid()));
  fs::create_directories(tmp);
  const std::string cmd =
      "tar -xzf '" + archive.string() + "' -C '" + tmp.string() +
      "' data/meshes/bunny00.off data/meshes/knot1.off data/points_3/kitten.xyz data/points_3/sphere_20k.xyz";
  if (std::system(cmd.c_str()) != 0) {  // the archive is there but unreadable or without the files: a failure
    fs::remove_all(tmp);
    ADD_FAILURE() << "cannot extract the samples from " << archive;
  }
  std::error_code ec;
  fs::rename(tmp, dir, ec);
  if (ec) fs::remove_all(tmp);  // another test got there first
  return dir / "data";
}

void expect_topology(const std::string& file, std::vector<std::size_t> betti) {
  const fs::path data = cgal_data();
  if (data.empty()) GTEST_SKIP() << "CGAL's sample data (Debian package libcgal-demo) is not installed";
  const PointSet set = read_points((data / file).string());
  const Outcome o = mesh(set.points, 3, 2);
  EXPECT_TRUE(o.topology.is_manifold) << o.topology.manifold_problem;
  EXPECT_EQ(o.topology.betti, betti) << file;
  EXPECT_FALSE(o.diagnostics.frames_inconsistent) << o.diagnostics.warning;
  EXPECT_TRUE(o.diagnostics.dimension_warning.empty()) << o.diagnostics.dimension_warning;
  EXPECT_TRUE(o.topology.boundary_cells.empty() || o.topology.boundary_cells[0] == 0);
}

TEST(RealSamples, BunnyIsASphere) { expect_topology("meshes/bunny00.off", {1, 0, 1}); }
TEST(RealSamples, KnotIsATorus) { expect_topology("meshes/knot1.off", {1, 2, 1}); }
// The kitten's tail meets its back: a handle (genus 1).
TEST(RealSamples, KittenHasOneHandle) { expect_topology("points_3/kitten.xyz", {1, 2, 1}); }
// A noisy sphere: the samples lie within ±0.15 of the unit sphere, noise 1.3 times their spacing.
TEST(RealSamples, NoisySphere) { expect_topology("points_3/sphere_20k.xyz", {1, 0, 1}); }

}  // namespace

// The thesis prototype's per-simplex oracle (local PCA around each simplex's barycentre) against the
// per-vertex function on the same torus samples and triangulation, its defects counted by the same
// function: the per-vertex function has none (the exact rule makes M̂ a manifold whatever the
// values), the local-PCA oracle traces something and its count is the same on a second run.
TEST(LocalPca, DefectsAgainstPerVertexFunction) {
  const test::Samples s = test::sample_manifold("torus", 2000);
  const PointCloudProblem p = make_point_cloud_problem(s.points, s.d, s.m);
  const Triangulation t = Triangulation::coxeter(s.d).with_longest_edge(p.edge_length).with_offset(p.centre());

  const LocalPcaResult a = mesh_local_pca(t, p), b = mesh_local_pca(t, p);
  EXPECT_EQ(a.status, TraceStatus::complete);
  EXPECT_GT(a.cells.interior[0].size(), 100u);
  EXPECT_EQ(a.cells.interior[0].size(), b.cells.interior[0].size());
  EXPECT_EQ(a.defects, b.defects);
  EXPECT_GT(a.defects, 0u);  // (4,576 measured: facets of one cofacet answered by different planes)
  EXPECT_EQ(a.topology.betti, b.topology.betti);

  ImplicitOracle oracle(t, p.function, p.domain);
  TraceOptions options;
  options.skip_unusable_seeds = true;
  const TraceResult r = trace_manifold(t, oracle, p.seeds, options);
  EXPECT_GT(r.simplices.size(), 100u);
  EXPECT_EQ(count_defects(r, oracle), 0u);
  std::cout << "torus, 2000 samples: local-pca " << a.cells.interior[0].size() << " simplices, " << a.defects
            << " defects; per-vertex " << r.simplices.size() << " simplices, 0 defects\n";
}
