// Local PCA, the neighbour graph, frame synchronisation along its minimum spanning tree (Hoppe et
// al. 1992 for normals; the Procrustes step for k-frames), and the frustrated-edge count.
#include "coxmesh/oracle/sample_frames.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

constexpr int kMax = kMaxDimension;
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;  // no heap for d ≤ 31

struct Edge {
  double weight;
  std::uint32_t a, b;
  bool operator<(const Edge& o) const {
    if (weight != o.weight) return weight < o.weight;
    return a != o.a ? a < o.a : b < o.b;
  }
};

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[std::max(a, b)] = std::min(a, b);
    return true;
  }
};

// A = U_iᵀ U_j (k × k) from the row-stored frames.
Square overlap(const double* ui, const double* uj, int k, int d) {
  Square a(k, k);
  for (int r = 0; r < k; ++r)
    for (int c = 0; c < k; ++c) {
      double s = 0;
      for (int t = 0; t < d; ++t) s += ui[r * d + t] * uj[c * d + t];
      a(r, c) = s;
    }
  return a;
}

// The orthogonal factor W Vᵀ of A = W Σ Vᵀ: the rotation (or reflection) nearest to A.
Square polar(const Square& a) {
  Eigen::JacobiSVD<Square> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

}  // namespace

SampleFrames estimate_frames(const SampleTree& tree, int m, const FrameOptions& options) {
  const int d = tree.dimension(), k = d - m;
  const std::size_t n = tree.size();
  if (m < 1 || k < 1)
    throw InputError("the manifold dimension m must be between 1 and d − 1 = " + std::to_string(d - 1));
  if (!(options.radius > 0)) throw InputError("the neighbourhood radius must be positive");
  if (!options.reference_normals.empty() && (k != 1 || options.reference_normals.size() != n * d))
    throw InputError("given normals need codimension 1 and one normal of R^" + std::to_string(d) + " per sample");
  SampleFrames out;
  out.d = d;
  out.k = k;
  out.centers.resize(n * d);
  out.normals.resize(n * k * d);
  out.flatness.resize(n);
  out.thickness.resize(n);
  out.within_radius.resize(n);

  // Neighbourhoods and local PCA.
  const int cap = std::max({options.max_neighbours, options.min_neighbours, 1}) + 1;  // the sample itself too
  std::vector<std::uint32_t> nb(cap);
  std::vector<double> nb_d2(cap);
  std::vector<Edge> edges;
  edges.reserve(n * options.graph_neighbours);
  std::size_t total_neighbours = 0;
  LocalSquare cov(d, d);
  LocalVector mean(d);
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = tree.point(i);
    int count = tree.nearest_within(p, options.radius * options.radius, cap, nb.data(), nb_d2.data());
    out.within_radius[i] = static_cast<std::uint16_t>(count - 1);
    if (count < options.min_neighbours + 1)
      count = tree.nearest_within(p, std::numeric_limits<double>::infinity(), options.min_neighbours + 1, nb.data(),
                                  nb_d2.data());
    total_neighbours += count - 1;
    local_scatter(tree, nb.data(), count, mean, cov);
    Eigen::SelfAdjointEigenSolver<Square> eig(cov, Eigen::ComputeEigenvectors);  // reads the lower triangle
    double normal_part = 0;
    for (int j = 0; j < k; ++j) {  // eigenvalues ascend: the first k span the normal space
      normal_part += std::max(0.0, eig.eigenvalues()[j]);
      for (int t = 0; t < d; ++t) out.normals[(i * k + j) * d + t] = eig.eigenvectors()(t, j);
    }
    out.flatness[i] = normal_part / std::max(eig.eigenvalues().sum(), 1e-300);
    out.thickness[i] = std::sqrt(normal_part / count);
    for (int t = 0; t < d; ++t) out.centers[i * d + t] = mean[t];
    // The graph joins the nearest graph_neighbours whatever the radius: joined only within it,
    // sparse stretches of a curve fell apart locally and the frames met again the long way round.
    int graph = std::min(count, options.graph_neighbours + 1);
    if (graph < options.graph_neighbours + 1)
      graph = tree.nearest_within(p, std::numeric_limits<double>::infinity(), options.graph_neighbours + 1, nb.data(),
                                  nb_d2.data());
    for (int j = 0; j < graph; ++j)
      if (nb[j] != i)
        edges.push_back({0.0, static_cast<std::uint32_t>(std::min<std::size_t>(i, nb[j])),
                         static_cast<std::uint32_t>(std::max<std::size_t>(i, nb[j]))});
  }
  out.mean_neighbours = static_cast<double>(total_neighbours) / n;

  // The neighbour graph (each edge once), weighted 1 − |det(U_iᵀU_j)|: 0 when the normal spaces agree.
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  edges.erase(
      std::unique(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.a == y.a && x.b == y.b; }),
      edges.end());
  for (Edge& e : edges) e.weight = 1 - std::abs(overlap(out.frame(e.a), out.frame(e.b), k, d).determinant());
  out.graph_edges = edges.size();
  std::sort(edges.begin(), edges.end());

  // The largest gap: the longest edge of a Euclidean minimum spanning forest of the graph restricted
  // to samples with at least m + 1 others within the radius (so that outliers do not count). M
  // passes through such a gap at about half its length from every sample.
  {
    std::vector<Edge> by_length;
    for (const Edge& e : edges)
      if (out.within_radius[e.a] > m && out.within_radius[e.b] > m) {
        double s = 0;
        for (int t = 0; t < d; ++t)
          s += (tree.point(e.a)[t] - tree.point(e.b)[t]) * (tree.point(e.a)[t] - tree.point(e.b)[t]);
        by_length.push_back({s, e.a, e.b});
      }
    std::sort(by_length.begin(), by_length.end());
    UnionFind gaps(n);
    for (const Edge& e : by_length)
      if (gaps.unite(e.a, e.b)) out.longest_gap = std::max(out.longest_gap, std::sqrt(e.weight));
  }

  // Kruskal: the minimum spanning forest, and the components.
  UnionFind uf(n);
  std::vector<std::vector<std::uint32_t>> tree_adjacent(n);
  for (const Edge& e : edges)
    if (uf.unite(e.a, e.b)) {
      tree_adjacent[e.a].push_back(e.b);
      tree_adjacent[e.b].push_back(e.a);
    }
  out.component.assign(n, 0);
  std::vector<std::uint32_t> id_of_root(n, 0xFFFFFFFFu);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = uf.find(static_cast<std::uint32_t>(i));
    if (id_of_root[r] == 0xFFFFFFFFu) id_of_root[r] = out.components++;
    out.component[i] = id_of_root[r];
  }

  // Orientation.
  if (!options.reference_normals.empty()) {
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0;
      for (int t = 0; t < d; ++t) s += out.normals[i * d + t] * options.reference_normals[i * d + t];
      if (s < 0)
        for (int t = 0; t < d; ++t) out.normals[i * d + t] = -out.normals[i * d + t];
    }
  } else {
    // Breadth-first from the first sample of each component; a child's frame is turned onto its
    // parent's (already final) frame.
    std::vector<char> seen(n, 0);
    std::vector<std::uint32_t> queue;
    queue.reserve(n);
    for (std::size_t root = 0; root < n; ++root) {
      if (seen[root]) continue;
      seen[root] = 1;
      queue.assign(1, static_cast<std::uint32_t>(root));
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t p = queue[head];
        for (std::uint32_t c : tree_adjacent[p]) {
          if (seen[c]) continue;
          seen[c] = 1;
          queue.push_back(c);
          double* uc = out.normals.data() + static_cast<std::size_t>(c) * k * d;
          if (k == 1) {
            if (overlap(uc, out.frame(p), 1, d)(0, 0) < 0)
              for (int t = 0; t < d; ++t) uc[t] = -uc[t];
            continue;
          }
          const Square r = polar(overlap(uc, out.frame(p), k, d));  // U_c ← U_c·R: rows F_c ← Rᵀ·F_c
          Square rows(k, d);
          for (int a = 0; a < k; ++a)
            for (int t = 0; t < d; ++t) {
              double s = 0;
              for (int b = 0; b < k; ++b) s += r(b, a) * uc[b * d + t];
              rows(a, t) = s;
            }
          for (int a = 0; a < k; ++a)
            for (int t = 0; t < d; ++t) uc[a * d + t] = rows(a, t);
        }
      }
    }
  }

  // Frustration: edges between comparable normal spaces (all principal angles ≤ 45°) whose frames
  // do not agree: a reflection (det < 0), or a rotation by more than 60° (‖R − I‖₂ = 2 sin(θ/2) > 1).
  const double cos45 = std::sqrt(0.5);
  for (const Edge& e : edges) {
    const Square a = overlap(out.frame(e.a), out.frame(e.b), k, d);
    if (k == 1) {
      if (std::abs(a(0, 0)) < cos45) continue;
      ++out.compared_edges;
      if (a(0, 0) < 0) ++out.frustrated_edges;
      continue;
    }
    Eigen::JacobiSVD<Square> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (svd.singularValues().minCoeff() < cos45) continue;
    ++out.compared_edges;
    const Square r = svd.matrixU() * svd.matrixV().transpose();
    if (r.determinant() < 0) {
      ++out.frustrated_edges;
      continue;
    }
    const Square diff = r - Square::Identity(k, k);
    if (Eigen::JacobiSVD<Square>(diff).singularValues()[0] > 1) ++out.frustrated_edges;
  }
  return out;
}

}  // namespace coxmesh
