// refine_vertices: the vertices land on M (and on ∂D at the boundary) to rounding, much closer to
// the exact manifold than before, without flipping a triangle; the limits are counted; the result
// does not depend on the thread count.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>

#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/mesh/refine.h"
#include "coxmesh/oracle/implicit_oracle.h"

using namespace coxmesh;

namespace {

CellComplex trace(const Triangulation& t, FunctionPtr f, FunctionPtr domain = nullptr,
                  std::uint64_t max_simplices = 0) {
  ImplicitOracle oracle(t, f, domain);
  TraceOptions options;
  if (max_simplices) options.max_simplices = max_simplices;
  return build_cell_complex(trace_manifold(t, oracle, {f->seed()}, options));
}

RefineFunctions same(FunctionPtr f, FunctionPtr domain = nullptr) {
  return [f, domain] { return RefineSet{f, domain ? std::vector<FunctionPtr>{domain} : std::vector<FunctionPtr>{}}; };
}

double max_abs(const ImplicitFunction& f, const PointArray& xs) {
  const int d = f.ambient_dimension();
  std::vector<double> value(f.codimension());
  double m = 0;
  for (std::size_t v = 0; v < xs.size() / d; ++v) {
    f.evaluate(&xs[v * d], value.data());
    for (double y : value) m = std::max(m, std::abs(y));
  }
  return m;
}

// The largest distance of a vertex to the exact manifold, by `distance`.
template <class Distance>
double max_distance(const CellComplex& cc, Distance distance) {
  const std::vector<double> xs = vertex_coordinates(cc);
  const int d = cc.ambient_dimension;
  double m = 0;
  for (std::size_t v = 0; v < xs.size() / d; ++v) m = std::max(m, distance(&xs[v * d]));
  return m;
}

// Signs of the triangles' normals against their centroid direction (the sphere's outside).
std::vector<int> outward_signs(const CellComplex& cc) {
  const std::vector<double> xs = vertex_coordinates(cc);
  const Simplices s = simplicial_complex(cc, xs);
  std::vector<int> signs;
  for (std::size_t t = 0; t < s.interior.size(); t += 3) {
    const double *a = &xs[3 * s.interior[t]], *b = &xs[3 * s.interior[t + 1]], *c = &xs[3 * s.interior[t + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double dot = n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]);
    const double area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    signs.push_back(area < 1e-12 ? 0 : dot > 0 ? 1 : -1);
  }
  return signs;
}

}  // namespace

TEST(Refine, SphereVerticesLandOnTheSphere) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.2);
  const FunctionPtr f = sphere(2, 3, 1.0);
  CellComplex cc = trace(t, f);
  const auto radius_error = [](const double* x) { return std::abs(std::hypot(x[0], x[1], x[2]) - 1); };
  const double before = max_distance(cc, radius_error), f_before = max_abs(*f, cc.vertices);
  const std::vector<int> signs = outward_signs(cc);
  const TopologyReport topology = analyze_topology(cc);
  const RefinementReport r = refine_vertices(cc, t.longest_edge(), same(f));
  EXPECT_EQ(r.vertices, vertex_count(cc));
  EXPECT_EQ(r.not_refined, 0u);
  EXPECT_EQ(r.max_abs_f_before, f_before);
  EXPECT_GT(r.max_abs_f_before, 1e-4);
  EXPECT_LE(r.max_abs_f_after, 1e-10 * r.max_abs_f_before);
  EXPECT_EQ(r.max_abs_f_after, max_abs(*f, cc.vertices));
  const double after = max_distance(cc, radius_error);
  EXPECT_LE(after, before / 10);
  EXPECT_LE(after, 1e-12);
  // The complex is the same; no triangle turned over.
  EXPECT_EQ(analyze_topology(cc).betti, topology.betti);
  const std::vector<int> signs_after = outward_signs(cc);
  ASSERT_EQ(signs_after.size(), signs.size());
  for (std::size_t i = 0; i < signs.size(); ++i)
    if (signs[i] != 0) {
      EXPECT_EQ(signs_after[i], signs[i]) << "triangle " << i;
    }
}

TEST(Refine, TorusAndThreads) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.15);
  const FunctionPtr f = torus(1.0, 0.4);
  CellComplex one = trace(t, f), three = trace(t, f);
  const auto torus_error = [](const double* x) {
    return std::abs(std::hypot(std::hypot(x[0], x[1]) - 1.0, x[2]) - 0.4);
  };
  const double before = max_distance(one, torus_error);
  RefineOptions options;
  options.threads = 1;
  const RefinementReport r1 = refine_vertices(one, t.longest_edge(), same(f), options);
  options.threads = 3;
  const RefinementReport r3 = refine_vertices(three, t.longest_edge(), same(f), options);
  EXPECT_EQ(r1.not_refined, 0u);
  EXPECT_LE(r1.max_abs_f_after, 1e-10 * r1.max_abs_f_before);
  EXPECT_LE(max_distance(one, torus_error), before / 10);
  EXPECT_EQ(one.vertices, three.vertices);  // bitwise
  EXPECT_EQ(r1.max_abs_f_after, r3.max_abs_f_after);
}

TEST(Refine, BoundaryVerticesStayOnTheDomainsBoundary) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.2);
  const FunctionPtr f = sphere(2, 3, 1.0), domain = ball_domain({1, 0, 0}, 0.9);
  CellComplex cc = trace(t, f, domain);
  ASSERT_GT(cc.boundary_vertices.size(), 0u);
  const double d_before = max_abs(*domain, cc.boundary_vertices);
  const RefinementReport r = refine_vertices(cc, t.longest_edge(), same(f, domain));
  EXPECT_EQ(r.not_refined, 0u);
  EXPECT_LE(r.max_abs_f_after, 1e-12);
  EXPECT_GT(d_before, 1e-4);
  EXPECT_LE(max_abs(*domain, cc.boundary_vertices), 1e-12);
  EXPECT_LE(max_abs(*f, cc.boundary_vertices), 1e-12);
}

TEST(Refine, RotationGroupSO3) {
  // Part of SO(3) ⊂ R^9 (the walk stopped early: only the vertices matter here). The distance of a
  // matrix X to SO(3) is |Σ − I| for X = UΣVᵀ (X near a rotation).
  const Triangulation t = Triangulation::coxeter(9).with_longest_edge(0.8);
  const FunctionPtr f = rotation_group_so3();
  CellComplex cc = trace(t, f, nullptr, 3000);
  const auto so3_error = [](const double* x) {
    Eigen::MatrixXd m(3, 3);  // (dynamic size: GCC 12 warns falsely about the fixed-size SVD)
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = x[i];
    return (Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues() - Eigen::VectorXd::Ones(3)).norm();
  };
  const double before = max_distance(cc, so3_error);
  const RefinementReport r = refine_vertices(cc, t.longest_edge(), same(f));
  EXPECT_GT(r.vertices, 1000u);
  EXPECT_EQ(r.not_refined, 0u);
  EXPECT_LE(r.max_abs_f_after, 1e-10 * r.max_abs_f_before);
  EXPECT_LE(max_distance(cc, so3_error), before / 10);
}

TEST(Refine, VerticesThatWouldMoveTooFarStayAndAreCounted) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.2);
  const FunctionPtr f = sphere(2, 3, 1.0);
  CellComplex cc = trace(t, f);
  const auto original = cc.vertices;
  RefineOptions options;
  options.max_move = 1e-9;  // 2e-10: only vertices already on M (at lattice vertices) may move
  const RefinementReport r = refine_vertices(cc, t.longest_edge(), same(f), options);
  std::size_t far = 0;  // |F| = ||x|² − 1| > 1e-8: more than 2e-10 away from the sphere
  for (std::size_t v = 0; v < original.size() / 3; ++v) {
    const double* x = &original[3 * v];
    far += std::abs(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1) > 1e-8 ? 1 : 0;
    const double* y = &cc.vertices[3 * v];
    EXPECT_LE(std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]), 2e-10);
  }
  EXPECT_GT(far, r.vertices / 2);
  EXPECT_GE(r.not_refined, far);
  EXPECT_LT(r.not_refined, r.vertices);
}

TEST(Refine, MeshManifoldOption) {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.2);
  MeshOptions options;
  options.refine = true;
  const MeshReport r = mesh_manifold(
      t,
      [] {
        return ManifoldFunctions{sphere(2, 3, 1.0), nullptr};
      },
      options);
  ASSERT_TRUE(r.refinement.has_value());
  EXPECT_EQ(r.refinement->not_refined, 0u);
  EXPECT_LE(r.refinement->max_abs_f_after, 1e-12);
  options.refine = false;
  EXPECT_FALSE(mesh_manifold(
                   t,
                   [] {
                     return ManifoldFunctions{sphere(2, 3, 1.0), nullptr};
                   },
                   options)
                   .refinement.has_value());
}
