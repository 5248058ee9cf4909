// Thesis §1.2.4 (Def. 1.2.24, Prop. 1.2.29–1.2.31), §2.3, §2.5.
#include "coxmesh/quality/alcove.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "coxmesh/lattice/simplex.h"  // InputError

namespace coxmesh::quality {

namespace {

using Key = std::vector<long long>;

// Orthonormal rows spanning the rows of `s` (classical Gram–Schmidt, applied twice for stability).
Eigen::MatrixXd gram_schmidt(const Eigen::MatrixXd& s) {
  Eigen::MatrixXd b = s;
  for (Eigen::Index k = 0; k < b.rows(); ++k) {
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index l = 0; l < k; ++l) b.row(k) -= b.row(k).dot(b.row(l)) * b.row(l);
    b.row(k).normalize();
  }
  return b;
}

// key_scale·⟨x, s_i⟩ for i = 1..d: integers at every vertex of the triangulation (see Alcove).
Key point_key(const Alcove& a, const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::VectorXd v = static_cast<double>(a.key_scale) * (a.simple_roots * x);
  Key key(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    key[i] = std::llround(v[i]);
    if (std::abs(v[i] - static_cast<double>(key[i])) > 1e-6)
      throw std::logic_error("alcove: a generated point is not a vertex of the triangulation");
  }
  return key;
}

std::vector<int> sorted(std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Breadth-first generation by facet reflections, tracking for each alcove g(F) the linear part Q of g
// (g(0) is its point of type 0): the point across facet j is g(σ_j(v_j)) = w_0 + Q·σ_j(v_j), and the
// new alcove is (g∘σ_j)(F), linear part Q·(I − 2 n̂_j n̂_jᵀ).
AlcoveComplex breadth_first(const Alcove& a, const std::vector<bool>& facet_allowed, int max_depth,
                            std::size_t max_alcoves,
                            const std::function<bool(const AlcoveComplex&, const std::vector<int>&)>& keep) {
  const int d = a.dimension;
  Eigen::MatrixXd unit(d + 1, d), mirror(d + 1, d);
  for (int j = 0; j <= d; ++j) {
    const Eigen::VectorXd n = a.facet_normals.row(j).transpose();
    const Eigen::VectorXd v = a.vertices.row(j).transpose();
    unit.row(j) = n.normalized().transpose();
    mirror.row(j) = (v - 2 * (v.dot(n) - a.facet_offsets[j]) / n.squaredNorm() * n).transpose();
  }

  AlcoveComplex out;
  out.dimension = d;
  std::map<Key, int> point_ids;
  std::map<std::vector<int>, int> alcove_ids;
  std::vector<Eigen::MatrixXd> linear;  // per alcove, released once it has been expanded

  auto add_point = [&](const Eigen::VectorXd& x, int type) {
    auto [it, fresh] = point_ids.emplace(point_key(a, x), static_cast<int>(out.point_type.size()));
    if (fresh) {
      out.points.insert(out.points.end(), x.data(), x.data() + d);
      out.point_type.push_back(type);
    }
    return it->second;
  };
  auto add_alcove = [&](const std::vector<int>& ids, int depth, Eigen::MatrixXd q) {
    if (!alcove_ids.emplace(sorted(ids), static_cast<int>(out.depth.size())).second) return;
    if (out.depth.size() >= max_alcoves)
      throw InputError("more than " + std::to_string(max_alcoves) + " alcoves would be generated");
    out.alcove_points.insert(out.alcove_points.end(), ids.begin(), ids.end());
    out.depth.push_back(depth);
    linear.push_back(std::move(q));
  };

  std::vector<int> first(d + 1);
  for (int t = 0; t <= d; ++t) first[t] = add_point(a.vertices.row(t).transpose(), t);
  add_alcove(first, 0, Eigen::MatrixXd::Identity(d, d));

  for (std::size_t k = 0; k < out.depth.size(); ++k) {
    if (out.depth[k] >= max_depth) continue;
    const std::vector<int> ids(out.alcove_points.begin() + k * (d + 1), out.alcove_points.begin() + (k + 1) * (d + 1));
    const Eigen::MatrixXd q = std::move(linear[k]);
    linear[k] = Eigen::MatrixXd();
    const Eigen::VectorXd w0 = out.point(ids[0]);
    for (int j = 0; j <= d; ++j) {
      if (!facet_allowed[j]) continue;
      std::vector<int> next = ids;
      next[j] = add_point(w0 + q * mirror.row(j).transpose(), j);
      if (alcove_ids.count(sorted(next)) || !keep(out, next)) continue;
      const Eigen::VectorXd qn = q * unit.row(j).transpose();
      add_alcove(next, out.depth[k] + 1, q - 2 * qn * unit.row(j));
    }
  }
  return out;
}

// Inverse of the edge matrix E (rows w_i − w_0, i = 1..d) of a simplex given by its vertex rows.
Eigen::MatrixXd inverse_edges(const Eigen::MatrixXd& w) {
  const Eigen::MatrixXd e = w.bottomRows(w.rows() - 1).rowwise() - w.row(0);
  return e.fullPivLu().inverse();
}

// Gradient of barycentric coordinate j (for inverse_edges E^{-1}): column j−1 of E^{-1}, and minus
// their sum for j = 0.
Eigen::VectorXd barycentric_gradient(const Eigen::MatrixXd& inv, int j) {
  return j == 0 ? Eigen::VectorXd(-inv.rowwise().sum()) : Eigen::VectorXd(inv.col(j - 1));
}

}  // namespace

void check_affine_type(Family f, int d) {
  if (f == Family::B && d == 2)
    throw InputError("there is no affine type B~2: B~_d needs d >= 3 (B~2 is C~2 up to similarity; use type C)");
  check_root_system(f, d);
}

std::vector<int> supported_affine_ranks(Family f, int max_rank) {
  std::vector<int> out = supported_ranks(f, max_rank);
  if (f == Family::B) std::erase(out, 2);
  return out;
}

Alcove fundamental_alcove(Family f, int d) {
  check_affine_type(f, d);
  return fundamental_alcove(make_root_system(f, d));
}

Alcove fundamental_alcove(const RootSystem& rs) {
  check_affine_type(rs.family, rs.rank);
  const int d = rs.rank;
  Alcove a;
  a.family = rs.family;
  a.dimension = d;
  a.basis = rs.ambient == d ? Eigen::MatrixXd::Identity(d, d) : gram_schmidt(rs.simple_roots);
  a.simple_roots = rs.simple_roots * a.basis.transpose();
  a.highest_root = a.basis * rs.highest_root;
  a.highest_coefficients = rs.highest_coefficients;
  const Eigen::MatrixXd coweights = a.simple_roots.fullPivLu().inverse();  // column i−1 = ω_i^∨
  a.vertices = Eigen::MatrixXd::Zero(d + 1, d);
  a.facet_normals.resize(d + 1, d);
  a.facet_offsets = Eigen::VectorXd::Zero(d + 1);
  a.facet_normals.row(0) = a.highest_root.transpose();
  a.facet_offsets[0] = 1;
  for (int i = 1; i <= d; ++i) {
    const int c = a.highest_coefficients[i - 1];
    a.vertices.row(i) = coweights.col(i - 1).transpose() / c;
    a.facet_normals.row(i) = a.simple_roots.row(i - 1);
    a.key_scale = std::lcm(a.key_scale, static_cast<long>(c));
  }
  return a;
}

Eigen::MatrixXd AlcoveComplex::alcove_vertices(std::size_t a) const {
  Eigen::MatrixXd w(dimension + 1, dimension);
  for (int t = 0; t <= dimension; ++t) w.row(t) = point(alcove_points[a * (dimension + 1) + t]).transpose();
  return w;
}

AlcoveComplex generate_by_depth(const Alcove& alcove, int depth) {
  if (depth < 0) throw InputError("the depth must be non-negative, got " + std::to_string(depth));
  return breadth_first(alcove, std::vector<bool>(alcove.dimension + 1, true), depth,
                       std::numeric_limits<std::size_t>::max(),
                       [](const AlcoveComplex&, const std::vector<int>&) { return true; });
}

AlcoveComplex generate_vertex_star(const Alcove& alcove, int t, std::size_t max_alcoves) {
  if (t < 0 || t > alcove.dimension)
    throw InputError("vertex type " + std::to_string(t) + " is outside 0.." + std::to_string(alcove.dimension));
  std::vector<bool> allowed(alcove.dimension + 1, true);
  allowed[t] = false;  // only facets through v_t
  return breadth_first(alcove, allowed, std::numeric_limits<int>::max(), max_alcoves,
                       [](const AlcoveComplex&, const std::vector<int>&) { return true; });
}

AlcoveComplex generate_in_ball(const Alcove& alcove, const Eigen::VectorXd& centre, double radius,
                               std::size_t max_alcoves) {
  if (centre.size() != alcove.dimension)
    throw InputError("the centre has " + std::to_string(centre.size()) + " coordinates, expected " +
                     std::to_string(alcove.dimension));
  if (!std::isfinite(radius) || radius < 0) throw InputError("the radius must be finite and non-negative");
  return breadth_first(alcove, std::vector<bool>(alcove.dimension + 1, true), std::numeric_limits<int>::max(),
                       max_alcoves, [&](const AlcoveComplex& c, const std::vector<int>& ids) {
                         for (int p : ids)
                           if ((c.point(p) - centre).norm() <= radius) return true;
                         return false;
                       });
}

TilingCheck check_tiling(const Alcove& alcove, const AlcoveComplex& complex, double tol) {
  const int d = complex.dimension;
  TilingCheck out;
  out.alcoves = complex.alcove_count();
  auto fail = [&](bool& flag, const std::string& what) {
    if (out.problem.empty()) out.problem = what;
    flag = false;
  };

  std::map<Key, int> point_ids;
  for (std::size_t p = 0; p < complex.point_count(); ++p) point_ids.emplace(point_key(alcove, complex.point(p)), p);
  std::map<std::vector<int>, std::size_t> alcove_ids;
  std::map<std::vector<int>, int> facet_count;
  auto ids_of = [&](std::size_t a) {
    return std::vector<int>(complex.alcove_points.begin() + a * (d + 1),
                            complex.alcove_points.begin() + (a + 1) * (d + 1));
  };
  for (std::size_t a = 0; a < complex.alcove_count(); ++a) {
    const std::vector<int> ids = ids_of(a);
    if (!alcove_ids.emplace(sorted(ids), a).second)
      fail(out.face_to_face, "alcove " + std::to_string(a) + " is listed twice");
    for (int j = 0; j <= d; ++j) {
      std::vector<int> facet = ids;
      facet.erase(facet.begin() + j);
      ++facet_count[sorted(facet)];
    }
  }

  const Eigen::MatrixXd reference = complex.alcove_vertices(0);
  for (std::size_t a = 0; a < complex.alcove_count(); ++a) {
    const std::vector<int> ids = ids_of(a);
    const Eigen::MatrixXd w = complex.alcove_vertices(a);
    const std::string name = "alcove " + std::to_string(a);
    for (int s = 0; s <= d; ++s) {
      if (complex.point_type[ids[s]] != s)
        fail(out.types_consistent, name + ": point of type " + std::to_string(s) + " has another type");
      for (int t = s + 1; t <= d; ++t)
        if (std::abs((w.row(s) - w.row(t)).norm() - (reference.row(s) - reference.row(t)).norm()) > tol)
          fail(out.congruent,
               name + ": edge " + std::to_string(s) + "-" + std::to_string(t) + " differs from alcove 0");
    }
    // Mirror images across the facets, by plain geometry.
    const Eigen::MatrixXd inv = inverse_edges(w);
    std::vector<std::vector<int>> neighbours;
    for (int j = 0; j <= d; ++j) {
      const Eigen::VectorXd g = barycentric_gradient(inv, j);
      const Eigen::VectorXd image = w.row(j).transpose() - 2 * g / g.squaredNorm();
      const auto it = point_ids.find(point_key(alcove, image));
      if (it == point_ids.end() || (complex.point(it->second) - image).norm() > tol) break;
      std::vector<int> next = ids;
      next[j] = it->second;
      const auto found = alcove_ids.find(sorted(next));
      if (found == alcove_ids.end()) break;
      if (ids_of(found->second) != next)
        fail(out.mirror_neighbours,
             name + ": the alcove across facet " + std::to_string(j) + " is not its mirror image");
      neighbours.push_back(next);
    }
    if (static_cast<int>(neighbours.size()) != d + 1) continue;
    ++out.interior_alcoves;
    for (int j = 0; j <= d; ++j) {
      std::vector<int> facet = ids;
      facet.erase(facet.begin() + j);
      ++out.facets_checked;
      if (facet_count[sorted(facet)] != 2)
        fail(out.face_to_face, name + ": facet " + std::to_string(j) + " lies in " +
                                   std::to_string(facet_count[sorted(facet)]) + " alcoves");
    }
  }
  return out;
}

int count_containing(const AlcoveComplex& complex, const Eigen::VectorXd& x, double tol) {
  int count = 0;
  for (std::size_t a = 0; a < complex.alcove_count(); ++a) {
    const Eigen::MatrixXd w = complex.alcove_vertices(a);
    const Eigen::MatrixXd inv = inverse_edges(w);
    const Eigen::VectorXd mu = inv.transpose() * (x - w.row(0).transpose());
    if (mu.minCoeff() > tol && 1 - mu.sum() > tol) ++count;
  }
  return count;
}

}  // namespace coxmesh::quality
