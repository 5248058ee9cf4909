// The complex as simplices (simplices.h) and the simplicial writers: fan counts, coherent
// orientation (every edge once in each direction), conforming tetrahedra, STL and Gmsh files read
// back.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

using namespace coxmesh;
namespace fs = std::filesystem;

namespace {

CellComplex trace(FunctionPtr f, FunctionPtr domain, double edge, std::vector<double> seed = {}) {
  const int d = f->ambient_dimension();
  const Triangulation t = Triangulation::coxeter(d).with_longest_edge(edge);
  ImplicitOracle oracle(t, f, domain);
  TraceResult r = trace_manifold(t, oracle, {seed.empty() ? f->seed() : seed});
  EXPECT_EQ(r.status, TraceStatus::complete);
  return build_cell_complex(std::move(r));
}

CellComplex sphere2() { return trace(sphere(2, 3, 1.0), nullptr, 0.3); }
CellComplex torus2() { return trace(torus(1.0, 0.4), nullptr, 0.15); }
CellComplex cap2() { return trace(sphere(2, 3, 1.0), ball_domain({1, 0, 0}, 0.9), 0.25); }

// The 3-ball {x4 = 0, |x| < 1} in R^4.
CellComplex ball3() {
  Eigen::MatrixXd n = Eigen::MatrixXd::Zero(4, 1);
  n(3, 0) = 1;
  const Triangulation t =
      Triangulation::coxeter(4).with_longest_edge(0.3).with_offset(Eigen::Vector4d(0.01, 0.02, 0.03, 0.0123));
  ImplicitOracle oracle(t, affine_plane(n, Eigen::VectorXd::Zero(4)), ball_domain({0, 0, 0, 0}, 1.0));
  return build_cell_complex(trace_manifold(t, oracle, {{0.1, 0.1, 0.1, 0.0}}));
}

using Directed = std::map<std::pair<std::uint32_t, std::uint32_t>, int>;

Directed directed_edges(const std::vector<std::uint32_t>& triangles) {
  Directed directed;
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int i = 0; i < 3; ++i) ++directed[{triangles[t + i], triangles[t + (i + 1) % 3]}];
  return directed;
}

// Every edge used once in each direction (closed surfaces) or once in one direction (the boundary).
void expect_coherent(const std::vector<std::uint32_t>& triangles, bool closed, const std::string& name) {
  const Directed directed = directed_edges(triangles);
  std::size_t lonely = 0;
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << name << ": edge " << e.first << "-" << e.second << " used twice in one direction";
    lonely += directed.count({e.second, e.first}) ? 0 : 1;
  }
  if (closed) {
    EXPECT_EQ(lonely, 0u) << name;
  } else {
    EXPECT_GT(lonely, 0u) << name;
  }
}

double enclosed_volume6(const std::vector<std::uint32_t>& triangles, const std::vector<double>& xs) {
  double volume = 0;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const double *a = &xs[3 * triangles[t]], *b = &xs[3 * triangles[t + 1]], *c = &xs[3 * triangles[t + 2]];
    volume +=
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return volume;
}

std::size_t fan_total(const CellComplex& cc) {
  const Ragged polygons = polygon_cycles(cc);
  std::size_t total = 0;
  for (std::uint32_t p = 0; p < polygons.size(); ++p)
    if (!polygons[p].empty()) total += polygons[p].size() - 2;
  return total;
}

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / ("coxmesh_test_simplices_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(Simplices, TriangleCountIsTheSumOfSidesMinusTwo) {
  const CellComplex sphere = sphere2(), torus = torus2();
  for (const CellComplex* cc : {&sphere, &torus}) {
    const std::vector<double> xs = vertex_coordinates(*cc);
    const Simplices s = simplicial_complex(*cc, xs);
    EXPECT_EQ(s.dimension, 2);
    EXPECT_EQ(s.skipped, 0u);
    EXPECT_EQ(s.interior_count(), fan_total(*cc));
    EXPECT_GT(s.interior_count(), cell_count(*cc, CellKind::interior, 2));  // some polygons have 4+ sides
    // No vertex added, and V − E + F of the triangles is χ: 2 and 0.
    std::uint32_t largest = 0;
    for (std::uint32_t v : s.interior) largest = std::max(largest, v);
    EXPECT_EQ(largest + 1, vertex_count(*cc));
    const long long chi = static_cast<long long>(vertex_count(*cc)) -
                          static_cast<long long>(directed_edges(s.interior).size() / 2) +
                          static_cast<long long>(s.interior_count());
    EXPECT_EQ(chi, cc == &sphere ? 2 : 0);
  }
}

TEST(Simplices, SurfacesAreCoherentlyOrientedAndOutward) {
  const CellComplex sphere = sphere2(), torus = torus2(), cap = cap2();
  for (const CellComplex* cc : {&sphere, &torus}) {
    const std::vector<double> xs = vertex_coordinates(*cc);
    const Simplices s = simplicial_complex(*cc, xs);
    expect_coherent(s.interior, true, cc == &sphere ? "sphere" : "torus");
    EXPECT_GT(enclosed_volume6(s.interior, xs), 0);  // outward: along ∇F for F = |x|² − 1
  }
  // Sphere: every normal points away from the centre (F's gradient direction).
  const std::vector<double> xs = vertex_coordinates(sphere);
  const Simplices s = simplicial_complex(sphere, xs);
  for (std::size_t t = 0; t < s.interior.size(); t += 3) {
    const double *a = &xs[3 * s.interior[t]], *b = &xs[3 * s.interior[t + 1]], *c = &xs[3 * s.interior[t + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    EXPECT_GT(n[0] * a[0] + n[1] * a[1] + n[2] * a[2], 0) << "triangle " << t / 3;
  }
  // A cap: coherent inside, and each boundary edge runs the way its triangle runs along it.
  const std::vector<double> cx = vertex_coordinates(cap);
  const Simplices c = simplicial_complex(cap, cx);
  expect_coherent(c.interior, false, "cap");
  const Directed directed = directed_edges(c.interior);
  ASSERT_GT(c.boundary_count(), 0u);
  for (std::size_t e = 0; e < c.boundary.size(); e += 2) {
    EXPECT_EQ(directed.count({c.boundary[e], c.boundary[e + 1]}), 1u);
    EXPECT_EQ(directed.count({c.boundary[e + 1], c.boundary[e]}), 0u);
  }
}

TEST(Simplices, CurveEdgesRunHeadToTail) {
  const CellComplex circle = trace(sphere(1, 2, 1.0), nullptr, 0.2);
  const Simplices s = simplicial_complex(circle, {});
  ASSERT_EQ(s.dimension, 1);
  ASSERT_EQ(s.interior_count(), cell_count(circle, CellKind::interior, 1));
  std::map<std::uint32_t, int> out, in;
  for (std::size_t e = 0; e < s.interior.size(); e += 2) ++out[s.interior[e]], ++in[s.interior[e + 1]];
  for (std::uint32_t v = 0; v < vertex_count(circle); ++v) {
    EXPECT_EQ(out[v], 1) << v;
    EXPECT_EQ(in[v], 1) << v;
  }
}

TEST(Simplices, TetrahedraAreConformingPositiveAndAddNoVertex) {
  const CellComplex cc = ball3();
  const Projection p = make_projection("1,2,3", 4, {});
  const std::vector<double> p3 = project_points(p, vertex_coordinates(cc));
  const Simplices s = simplicial_complex(cc, p3);
  ASSERT_EQ(s.dimension, 3);
  ASSERT_GT(s.interior_count(), 0u);
  // Each triangle of a tetrahedron lies in exactly two tetrahedra, or in one and in the boundary.
  std::map<std::array<std::uint32_t, 3>, int> faces;
  double volume = 0;
  for (std::size_t t = 0; t < s.interior.size(); t += 4) {
    const double v6 =
        tetrahedron_volume6(p3.data(), s.interior[t], s.interior[t + 1], s.interior[t + 2], s.interior[t + 3]);
    EXPECT_GT(v6, 0);
    volume += v6 / 6;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::uint32_t, 3> f;
      int k = 0;
      for (int i = 0; i < 4; ++i)
        if (i != skip) f[k++] = s.interior[t + i];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  std::map<std::array<std::uint32_t, 3>, int> boundary;
  for (std::size_t t = 0; t < s.boundary.size(); t += 3) {
    std::array<std::uint32_t, 3> f{s.boundary[t], s.boundary[t + 1], s.boundary[t + 2]};
    std::sort(f.begin(), f.end());
    ++boundary[f];
  }
  for (const auto& [f, n] : faces) EXPECT_EQ(n + boundary.count(f), 2) << f[0] << " " << f[1] << " " << f[2];
  for (const auto& [f, n] : boundary) EXPECT_EQ(faces.count(f), 1u);
  EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI, 0.3);
  // The boundary surface is closed and outward.
  expect_coherent(s.boundary, true, "boundary of the ball");
  EXPECT_GT(enclosed_volume6(s.boundary, p3), 0);
}

TEST(Simplices, FourManifoldsAreRefused) {
  const CellComplex cc = trace(sphere(4, 5, 1.0), nullptr, 0.9);
  EXPECT_THROW(simplicial_complex(cc, {}), InputError);
  const fs::path dir = temp_dir();
  WriteOptions options;
  options.simplices = true;
  EXPECT_THROW(write_mesh((dir / "s.vtu").string(), MeshFormat::vtu, cc, options), InputError);
  EXPECT_THROW(write_mesh((dir / "s.msh").string(), MeshFormat::msh, cc), InputError);
  EXPECT_FALSE(fs::exists(dir / "s.vtu"));
  fs::remove_all(dir);
}

TEST(Writers, StlReadBack) {
  const fs::path dir = temp_dir();
  const CellComplex cc = torus2();
  const WrittenCounts n = write_mesh((dir / "t.stl").string(), MeshFormat::stl, cc);
  const std::string bytes = read_bytes(dir / "t.stl");
  const std::vector<double> xs = vertex_coordinates(cc);
  const Simplices s = simplicial_complex(cc, xs);
  ASSERT_GE(bytes.size(), 84u);
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, s.interior_count());
  EXPECT_EQ(n.cells, count);
  ASSERT_EQ(bytes.size(), 84u + 50u * count);
  for (std::uint32_t t = 0; t < count; ++t) {
    float r[12];
    std::memcpy(r, bytes.data() + 84 + 50 * t, sizeof r);
    // The vertices are the (float) points of the oriented triangle; the normal its right-hand normal.
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(r[3 + 3 * k + i], static_cast<float>(xs[3 * s.interior[3 * t + k] + i]));
    // (from the double coordinates: rounding to float turns the normals of thin triangles)
    const double *a = &xs[3 * s.interior[3 * t]], *b = &xs[3 * s.interior[3 * t + 1]],
                 *c = &xs[3 * s.interior[3 * t + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    EXPECT_NEAR(r[0] * r[0] + r[1] * r[1] + r[2] * r[2], 1.0, 1e-5);
    EXPECT_GT((r[0] * w[0] + r[1] * w[1] + r[2] * w[2]) / len, 1 - 1e-5);
  }
  // A curve, and points in R^4 without a projection: refused before the file exists.
  EXPECT_THROW(write_mesh((dir / "c.stl").string(), MeshFormat::stl, trace(sphere(1, 2, 1.0), nullptr, 0.2)),
               InputError);
  EXPECT_THROW(write_mesh((dir / "f.stl").string(), MeshFormat::stl,
                          trace(product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), nullptr, 0.5)),
               InputError);
  EXPECT_FALSE(fs::exists(dir / "c.stl"));
  EXPECT_FALSE(fs::exists(dir / "f.stl"));
  EXPECT_EQ(format_of_path("a.STL"), MeshFormat::stl);
  EXPECT_EQ(parse_format("msh"), MeshFormat::msh);
  fs::remove_all(dir);
}

// A Gmsh MSH 4.1 ASCII file parsed back: node coordinates, element blocks with their types.
TEST(Writers, GmshReadBack) {
  const fs::path dir = temp_dir();
  struct Expect {
    CellComplex cc;
    int type, boundary_type;
  };
  std::vector<Expect> cases;
  cases.push_back({cap2(), 2, 1});
  cases.push_back({trace(sphere(1, 2, 1.0), nullptr, 0.2), 1, 15});
  cases.push_back({ball3(), 4, 2});
  for (const Expect& e : cases) {
    const CellComplex& cc = e.cc;
    const int m = cc.manifold_dimension;
    write_mesh((dir / "a.msh").string(), MeshFormat::msh, cc);
    std::istringstream in(read_bytes(dir / "a.msh"));
    const std::vector<double> xs = vertex_coordinates(cc);
    const Projection p = make_projection("", cc.ambient_dimension, {});
    const std::vector<double> p3 = project_points(p, xs);
    const Simplices s = simplicial_complex(cc, p3);
    std::string word;
    in >> word;
    EXPECT_EQ(word, "$MeshFormat");
    double version;
    int binary, size;
    in >> version >> binary >> size >> word;
    EXPECT_EQ(version, 4.1);
    EXPECT_EQ(binary, 0);
    EXPECT_EQ(word, "$EndMeshFormat");
    in >> word;
    EXPECT_EQ(word, "$Nodes");
    std::size_t blocks, nodes, lo, hi;
    in >> blocks >> nodes >> lo >> hi;
    EXPECT_EQ(blocks, 1u);
    EXPECT_EQ(nodes, vertex_count(cc));
    EXPECT_EQ(lo, 1u);
    EXPECT_EQ(hi, nodes);
    int dim, tag, parametric;
    std::size_t in_block;
    in >> dim >> tag >> parametric >> in_block;
    EXPECT_EQ(dim, m);
    EXPECT_EQ(in_block, nodes);
    for (std::size_t v = 0; v < nodes; ++v) {
      std::size_t t;
      in >> t;
      ASSERT_EQ(t, v + 1);
    }
    for (std::size_t v = 0; v < nodes; ++v)
      for (int i = 0; i < 3; ++i) {
        double x;
        in >> x;
        ASSERT_EQ(x, p3[3 * v + i]);
      }
    in >> word;
    EXPECT_EQ(word, "$EndNodes");
    in >> word;
    EXPECT_EQ(word, "$Elements");
    std::size_t elements;
    in >> blocks >> elements >> lo >> hi;
    EXPECT_EQ(blocks, s.boundary.empty() ? 1u : 2u);
    EXPECT_EQ(elements, s.interior_count() + s.boundary_count());
    std::size_t next = 1;
    for (std::size_t b = 0; b < blocks; ++b) {
      int type;
      std::size_t n;
      in >> dim >> tag >> type >> n;
      EXPECT_EQ(dim, b == 0 ? m : m - 1);
      EXPECT_EQ(type, b == 0 ? e.type : e.boundary_type);
      const std::vector<std::uint32_t>& ids = b == 0 ? s.interior : s.boundary;
      const std::size_t arity = static_cast<std::size_t>(dim) + 1;
      ASSERT_EQ(n, ids.size() / arity);
      for (std::size_t k = 0; k < n; ++k) {
        std::size_t t;
        in >> t;
        ASSERT_EQ(t, next++);
        for (std::size_t i = 0; i < arity; ++i) {
          std::size_t v;
          in >> v;
          ASSERT_EQ(v, ids[k * arity + i] + 1u);
        }
      }
    }
    in >> word;
    EXPECT_EQ(word, "$EndElements");
  }
  fs::remove_all(dir);
}

// --simplices in the polygon formats: the same fan triangles.
TEST(Writers, SimplicesOptionWritesTriangles) {
  const fs::path dir = temp_dir();
  const CellComplex cc = torus2();
  WriteOptions options;
  options.simplices = true;
  const WrittenCounts n = write_mesh((dir / "t.off").string(), MeshFormat::off, cc, options);
  EXPECT_EQ(n.cells, fan_total(cc));
  std::istringstream in(read_bytes(dir / "t.off"));
  std::string word;
  std::size_t nv, nf, ne;
  in >> word >> nv >> nf >> ne;
  EXPECT_EQ(nf, fan_total(cc));
  double x;
  for (std::size_t i = 0; i < 3 * nv; ++i) in >> x;
  std::vector<std::uint32_t> triangles;
  for (std::size_t f = 0; f < nf; ++f) {
    int k;
    in >> k;
    ASSERT_EQ(k, 3);
    for (int i = 0; i < 3; ++i) triangles.push_back(0), in >> triangles.back();
  }
  expect_coherent(triangles, true, "torus OFF");
  EXPECT_EQ(write_mesh((dir / "t.obj").string(), MeshFormat::obj, cc, options).cells, fan_total(cc));
  EXPECT_EQ(write_mesh((dir / "t.ply").string(), MeshFormat::ply, cc, options).cells, fan_total(cc));
  EXPECT_EQ(write_mesh((dir / "t.vtu").string(), MeshFormat::vtu, cc, options).cells, fan_total(cc));
  EXPECT_EQ(write_mesh((dir / "t.vtu").string(), MeshFormat::vtu, cc).cells, cell_count(cc, CellKind::interior, 2));
  EXPECT_THROW(write_mesh((dir / "t.cxm").string(), MeshFormat::cxm, cc, options), InputError);
  fs::remove_all(dir);
}

// ---- Stereographic projection -------------------------------------------------------------------

TEST(Stereographic, MapsTheSphereFromItsPole) {
  // Points of the unit sphere around (1, 2, 3), pole its north pole: |image| = ρ / (1 − z), ρ the
  // distance to the axis (the basis of the plane is any orthonormal one).
  std::vector<double> pts;
  for (int i = 0; i < 200; ++i) {
    const double z = std::cos(0.1 + 3.0 * i / 200), a = 2.399963 * i, rho = std::sqrt(1 - z * z);
    pts.insert(pts.end(), {1 + rho * std::cos(a), 2 + rho * std::sin(a), 3 + z});
  }
  // The centroid of these points is not (1, 2, 3): give the pole so that the sphere is the unit one.
  std::vector<double> centred = pts;
  const std::vector<double> antipodes = [&] {  // add the antipodes: the centroid is then the centre
    std::vector<double> a;
    for (std::size_t v = 0; v < pts.size(); v += 3) a.insert(a.end(), {2 - pts[v], 4 - pts[v + 1], 6 - pts[v + 2]});
    return a;
  }();
  centred.insert(centred.end(), antipodes.begin(), antipodes.end());
  const std::vector<double> pole{1, 2, 4};
  const Projection p = make_projection("stereographic", 3, centred, pole);
  EXPECT_TRUE(p.stereographic);
  EXPECT_TRUE(p.changes_points);
  EXPECT_NEAR(p.radius, 1.0, 1e-12);
  const std::vector<double> image = project_points(p, pts);
  for (std::size_t v = 0; v < pts.size() / 3; ++v) {
    const double x = pts[3 * v] - 1, y = pts[3 * v + 1] - 2, z = pts[3 * v + 2] - 3;
    EXPECT_NEAR(std::hypot(image[3 * v], image[3 * v + 1]), std::hypot(x, y) / (1 - z), 1e-9);
    EXPECT_EQ(image[3 * v + 2], 0.0);  // R^2, padded
  }
  // Errors: a pole of the wrong size, a pole without stereographic, a pole at the centroid, a
  // point on the pole's side.
  EXPECT_THROW(make_projection("stereographic", 3, centred, std::vector<double>{1, 2}), InputError);
  EXPECT_THROW(make_projection("pca", 3, centred, pole), InputError);
  EXPECT_THROW(make_projection("stereographic", 3, centred, std::vector<double>{1, 2, 3}), InputError);
  const std::vector<double> beyond{1, 2, 5};
  EXPECT_THROW(project_points(p, beyond), InputError);
}

TEST(Stereographic, DefaultPoleIsAwayFromThePoints) {
  // A circle in the plane z = 0 of R^3: the candidates ±r·e_3 are the farthest from it.
  std::vector<double> pts;
  for (int i = 0; i < 64; ++i) pts.insert(pts.end(), {std::cos(i * M_PI / 32), std::sin(i * M_PI / 32), 0.0});
  const Projection p = make_projection("stereographic", 3, pts);
  EXPECT_NEAR(std::abs(p.center[2]), 1.0, 1e-12);
  EXPECT_NEAR(std::hypot(p.center[0], p.center[1]), 0.0, 1e-12);
}

namespace {

// Whether the closed segment pq meets the closed triangle abc (points of R^3), for segments not
// in the triangle's plane.
bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b, const double* c) {
  auto sub = [](const double* x, const double* y) {
    return std::array<double, 3>{x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  };
  auto det = [](const std::array<double, 3>& u, const std::array<double, 3>& v, const std::array<double, 3>& w) {
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
  };
  const double sp = det(sub(b, a), sub(c, a), sub(p, a)), sq = det(sub(b, a), sub(c, a), sub(q, a));
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || sp == sq) return false;
  // The crossing point's side of each edge, seen along pq.
  const double u = det(sub(b, p), sub(c, p), sub(q, p)), v = det(sub(c, p), sub(a, p), sub(q, p)),
               w = det(sub(a, p), sub(b, p), sub(q, p));
  return (u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0);
}

}  // namespace

TEST(Stereographic, FlatTorusInR4BecomesAnEmbeddedTorus) {
  // The Clifford torus S^1 × S^1 (radii 1, 1) lies on the sphere of radius √2: projected from R^4
  // to R^3 it is an ordinary torus. Brute force: two triangles with no common vertex do not meet.
  const CellComplex cc = trace(product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), nullptr, 0.5);
  const std::vector<double> xs = vertex_coordinates(cc);
  EXPECT_NEAR(make_projection("stereographic", 4, xs).radius, std::sqrt(2.0), 0.05);  // the default pole's sphere
  // A pole in general position on that sphere: from the default one (on an axis) the mesh's
  // vertices in a coordinate hyperplane through it (the torus passes through lattice vertices)
  // land in one plane, where the segment–triangle test below cannot decide.
  std::vector<double> pole{0.9, 0.3, 0.2, 0.25};
  const double length = std::sqrt(pole[0] * pole[0] + pole[1] * pole[1] + pole[2] * pole[2] + pole[3] * pole[3]);
  for (double& x : pole) x *= std::sqrt(2.0) / length;
  const Projection p = make_projection("stereographic", 4, xs, pole);
  const std::vector<double> p3 = project_points(p, xs);
  const Simplices s = simplicial_complex(cc, p3);
  const std::size_t n = s.interior_count();
  ASSERT_GT(n, 50u);
  expect_coherent(s.interior, true, "projected flat torus");
  // Triangles of coincident vertices (where M passes through a lattice vertex) are points or
  // segments: left out.
  std::vector<bool> degenerate(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double *a = &p3[3 * s.interior[3 * i]], *b = &p3[3 * s.interior[3 * i + 1]],
                 *c = &p3[3 * s.interior[3 * i + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    degenerate[i] = std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]) < 1e-10;
  }
  std::size_t crossings = 0, pairs = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::uint32_t* t = &s.interior[3 * i];
      const std::uint32_t* u = &s.interior[3 * j];
      // (vertices of different ids may coincide too: they touch there)
      bool shared = degenerate[i] || degenerate[j];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const double* x = &p3[3 * static_cast<std::size_t>(t[a])];
          const double* y = &p3[3 * static_cast<std::size_t>(u[b])];
          shared = shared || std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]) < 1e-9;
        }
      if (shared) continue;
      ++pairs;
      auto x = [&](std::uint32_t v) { return &p3[3 * static_cast<std::size_t>(v)]; };
      bool meet = false;
      for (int e = 0; e < 3 && !meet; ++e) {
        meet = segment_meets_triangle(x(t[e]), x(t[(e + 1) % 3]), x(u[0]), x(u[1]), x(u[2])) ||
               segment_meets_triangle(x(u[e]), x(u[(e + 1) % 3]), x(t[0]), x(t[1]), x(t[2]));
      }
      crossings += meet ? 1 : 0;
    }
  EXPECT_GT(pairs, n * (n - 1) / 4);
  EXPECT_EQ(crossings, 0u);
  // The first three coordinates instead squash it: it crosses itself.
  const std::vector<double> squashed = project_points(make_projection("", 4, xs), xs);
  std::size_t squashed_crossings = 0;
  for (std::size_t i = 0; i < n && squashed_crossings == 0; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::uint32_t* t = &s.interior[3 * i];
      const std::uint32_t* u = &s.interior[3 * j];
      bool shared = false;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shared = shared || t[a] == u[b];
      auto x = [&](std::uint32_t v) { return &squashed[3 * static_cast<std::size_t>(v)]; };
      if (!shared && segment_meets_triangle(x(t[0]), x(t[1]), x(u[0]), x(u[1]), x(u[2]))) ++squashed_crossings;
    }
  EXPECT_GT(squashed_crossings, 0u);
}

TEST(Simplices, TetrahedraOfS3InR4AreCoherent) {
  // S³ projected to its first three coordinates folds over itself, so the sign of a tetrahedron's
  // volume there says nothing: the orientation comes from the neighbours. Every triangle lies in two
  // tetrahedra, which induce opposite orientations on it.
  const CellComplex cc = trace(sphere(3, 4, 1.0), nullptr, 0.6);
  const std::vector<double> p3 = project_points(make_projection("1,2,3", 4, {}), vertex_coordinates(cc));
  const Simplices s = simplicial_complex(cc, p3);
  ASSERT_GT(s.interior_count(), 100u);
  std::map<std::array<std::uint32_t, 3>, std::vector<bool>> induced;
  std::size_t negative = 0;
  for (std::size_t t = 0; t < s.interior.size(); t += 4) {
    negative +=
        tetrahedron_volume6(p3.data(), s.interior[t], s.interior[t + 1], s.interior[t + 2], s.interior[t + 3]) < 0 ? 1
                                                                                                                   : 0;
    for (int i = 0; i < 4; ++i) {
      std::array<std::uint32_t, 3> f;
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) f[k++] = s.interior[t + j];
      bool odd = i % 2 == 1;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b + 1 < 3; ++b)
          if (f[b] > f[b + 1]) std::swap(f[b], f[b + 1]), odd = !odd;
      induced[f].push_back(odd);
    }
  }
  for (const auto& [f, o] : induced) {
    ASSERT_EQ(o.size(), 2u);
    EXPECT_NE(o[0], o[1]) << f[0] << " " << f[1] << " " << f[2];
  }
  EXPECT_GT(negative, s.interior_count() / 10);  // the fold: many tetrahedra are negative there
}
