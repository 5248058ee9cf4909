// Local PCA, the neighbour graph, frame synchronisation along its minimum spanning tree (Hoppe et
// al. 1992 for normals; the Procrustes step for k-frames), and the frustrated-edge count.
#include "coxmesh/oracle/sample_frames.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parallel_for.h"
#include "coxmesh/util/union_find.h"

namespace coxmesh {

namespace {

constexpr int kMax = kMaxDimension;
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
constexpr std::size_t kBlock = 256;  // samples or edges per task of the workers
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;  // no heap for d ≤ 31

struct Edge {
  double weight;
  std::uint32_t a, b;
  bool operator<(const Edge& o) const {
    if (weight != o.weight) return weight < o.weight;
    return a != o.a ? a < o.a : b < o.b;
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

// det(U_iᵀU_j); for k = 1 the dot product itself.
double overlap_determinant(const double* ui, const double* uj, int k, int d) {
  if (k == 1) {
    double s = 0;
    for (int t = 0; t < d; ++t) s += ui[t] * uj[t];
    return s;
  }
  return overlap(ui, uj, k, d).determinant();
}

// Sorts by (weight, a, b) edges already ordered by (a, b): a stable radix sort on the weight's
// bits (mapped so that unsigned order is the order of the doubles), 11 bits a pass. The counts of
// every pass come from one read of the edges, and a pass whose digit is the same everywhere is skipped.
void sort_by_weight(std::vector<Edge>& edges) {
  auto key = [](double w) {
    std::uint64_t u;
    std::memcpy(&u, &w, sizeof u);
    return (u >> 63) ? ~u : u | (std::uint64_t{1} << 63);
  };
  constexpr int kBits = 11, kPasses = (64 + kBits - 1) / kBits;
  constexpr std::size_t kDigits = std::size_t{1} << kBits;
  std::vector<std::size_t> count(kPasses * kDigits, 0);
  for (const Edge& e : edges) {
    const std::uint64_t k = key(e.weight);
    for (int pass = 0; pass < kPasses; ++pass) ++count[pass * kDigits + ((k >> (pass * kBits)) & (kDigits - 1))];
  }
  std::unique_ptr<Edge[]> buffer;  // (not value-initialised: every slot is written before it is read)
  Edge* from = edges.data();
  for (int pass = 0; pass < kPasses; ++pass) {
    std::size_t* c = count.data() + pass * kDigits;
    if (std::any_of(c, c + kDigits, [&](std::size_t n) { return n == edges.size(); })) continue;
    if (!buffer) buffer.reset(new Edge[edges.size()]);
    Edge* to = from == edges.data() ? buffer.get() : edges.data();
    std::size_t start = 0;
    for (std::size_t b = 0; b < kDigits; ++b) start += std::exchange(c[b], start);
    const int shift = pass * kBits;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const Edge& e = from[i];
      to[c[(key(e.weight) >> shift) & (kDigits - 1)]++] = e;
    }
    from = to;
  }
  if (from != edges.data()) std::copy(from, from + edges.size(), edges.data());
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
  out.spread_dimension.resize(n);
  out.within_radius.resize(n);

  // Neighbourhoods and local PCA, in blocks of samples on the workers: each sample's results go
  // to its own slots, so they do not depend on the number of threads.
  const int cap = std::max({options.max_neighbours, options.min_neighbours, 1}) + 1;  // the sample itself too
  const int graph_cap = std::max(options.graph_neighbours, 0) + 1;
  std::vector<std::uint32_t> graph_ids(n * graph_cap, kNone);  // each sample's nearest (itself included)
  std::vector<std::uint32_t> neighbours(n);
  WorkerPool workers(std::max(options.threads, 1));
  std::vector<std::vector<std::uint32_t>> nb_of(workers.size(), std::vector<std::uint32_t>(std::max(cap, graph_cap)));
  std::vector<std::vector<double>> d2_of(workers.size(), std::vector<double>(std::max(cap, graph_cap)));
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  workers.run(blocks, [&](std::size_t block, int worker) {
    std::uint32_t* nb = nb_of[worker].data();
    double* nb_d2 = d2_of[worker].data();
    LocalSquare cov(d, d);
    LocalVector mean(d);
    for (std::size_t at = block * kBlock; at < std::min(n, (block + 1) * kBlock); ++at) {
      // In the tree's order: consecutive queries then search the same part of the tree.
      const std::size_t i = tree.sample_at(static_cast<std::uint32_t>(at));
      const double* p = tree.point(i);
      int count = tree.nearest_within(p, options.radius * options.radius, cap, nb, nb_d2);
      out.within_radius[i] = static_cast<std::uint16_t>(count - 1);
      if (count < options.min_neighbours + 1)
        count = tree.nearest_within(p, std::numeric_limits<double>::infinity(), options.min_neighbours + 1, nb, nb_d2);
      neighbours[i] = static_cast<std::uint32_t>(count - 1);
      local_scatter(tree, nb, count, mean, cov);
      Eigen::SelfAdjointEigenSolver<Square> eig(cov, Eigen::ComputeEigenvectors);  // reads the lower triangle
      double normal_part = 0;
      for (int j = 0; j < k; ++j) {  // eigenvalues ascend: the first k span the normal space
        normal_part += std::max(0.0, eig.eigenvalues()[j]);
        for (int t = 0; t < d; ++t) out.normals[(i * k + j) * d + t] = eig.eigenvectors()(t, j);
      }
      out.flatness[i] = normal_part / std::max(eig.eigenvalues().sum(), 1e-300);
      out.thickness[i] = std::sqrt(normal_part / count);
      int spread = 0;
      for (int j = 0; j < d; ++j) spread += eig.eigenvalues()[j] >= kSpreadFraction * eig.eigenvalues()[d - 1];
      out.spread_dimension[i] = static_cast<std::uint8_t>(spread);
      for (int t = 0; t < d; ++t) out.centers[i * d + t] = mean[t];
      // The graph joins the nearest graph_neighbours whatever the radius: joined only within it,
      // sparse stretches of a curve fell apart locally and the frames met again the long way round.
      int graph = std::min(count, graph_cap);
      if (graph < graph_cap)
        graph = tree.nearest_within(p, std::numeric_limits<double>::infinity(), graph_cap, nb, nb_d2);
      std::copy(nb, nb + graph, graph_ids.begin() + i * graph_cap);
    }
  });
  std::size_t total_neighbours = 0;
  for (std::uint32_t c : neighbours) total_neighbours += c;
  out.mean_neighbours = static_cast<double>(total_neighbours) / n;

  // The neighbour graph, each edge once, ordered by (a, b): bucketed by the smaller end, each
  // bucket's other ends sorted (a counting sort; sorting all the edges took a third of the time).
  std::vector<std::size_t> first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < graph_cap; ++j) {
      const std::uint32_t o = graph_ids[i * graph_cap + j];
      if (o != kNone && o != i) ++first[std::min<std::size_t>(i, o) + 1];
    }
  for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> other(first[n]);
  {
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < graph_cap; ++j) {
        const std::uint32_t o = graph_ids[i * graph_cap + j];
        if (o == kNone || o == i) continue;
        if (o > i)
          other[fill[i]++] = o;
        else
          other[fill[o]++] = static_cast<std::uint32_t>(i);
      }
  }
  std::vector<Edge> edges;
  edges.reserve(other.size());
  for (std::size_t a = 0; a < n; ++a) {
    std::sort(other.begin() + first[a], other.begin() + first[a + 1]);
    const auto end = std::unique(other.begin() + first[a], other.begin() + first[a + 1]);
    for (auto it = other.begin() + first[a]; it != end; ++it)
      edges.push_back({0.0, static_cast<std::uint32_t>(a), *it});
  }
  // Weighted 1 − |det(U_iᵀU_j)|: 0 when the normal spaces agree.
  workers.run((edges.size() + kBlock - 1) / kBlock, [&](std::size_t block, int) {
    for (std::size_t e = block * kBlock; e < std::min(edges.size(), (block + 1) * kBlock); ++e)
      edges[e].weight = 1 - std::abs(overlap_determinant(out.frame(edges[e].a), out.frame(edges[e].b), k, d));
  });
  out.graph_edges = edges.size();
  sort_by_weight(edges);

  // The largest gap: the longest edge of a Euclidean minimum spanning forest of the graph restricted
  // to samples with at least m + 1 others within the radius (so that outliers do not count). M
  // passes through such a gap at about half its length from every sample.
  {
    std::vector<Edge> restricted;  // weight: the squared length
    restricted.reserve(edges.size());
    std::vector<double> shortest(n, std::numeric_limits<double>::infinity());
    for (const Edge& e : edges)
      if (out.within_radius[e.a] > m && out.within_radius[e.b] > m) {
        double s = 0;
        for (int t = 0; t < d; ++t)
          s += (tree.point(e.a)[t] - tree.point(e.b)[t]) * (tree.point(e.a)[t] - tree.point(e.b)[t]);
        restricted.push_back({s, e.a, e.b});
        shortest[e.a] = std::min(shortest[e.a], s);
        shortest[e.b] = std::min(shortest[e.b], s);
      }
    // Every sample's forest edges are at least as long as its shortest edge, so the longest edge
    // is at least the longest of those: the shorter edges only join components, in any order, and
    // Kruskal needs the rest sorted (a fraction of the edges).
    double at_least = 0;
    for (double s : shortest)
      if (s < std::numeric_limits<double>::infinity()) at_least = std::max(at_least, s);
    UnionFind gaps(n);
    std::vector<Edge> longer;
    for (const Edge& e : restricted)
      if (e.weight < at_least)
        gaps.unite(e.a, e.b);
      else
        longer.push_back(e);
    sort_by_weight(longer);
    for (const Edge& e : longer)
      if (gaps.unite(e.a, e.b)) out.longest_gap = std::max(out.longest_gap, std::sqrt(e.weight));
  }

  // Kruskal: the minimum spanning forest, and the components. Each sample's tree neighbours in the
  // order Kruskal joined them, in one array (a vector per sample was an allocation per sample).
  UnionFind uf(n);
  std::vector<std::uint32_t> tree_edges;  // a, b of each joining edge
  tree_edges.reserve(2 * n);
  for (const Edge& e : edges)
    if (uf.unite(e.a, e.b)) tree_edges.insert(tree_edges.end(), {e.a, e.b});
  std::vector<std::uint32_t> adjacent_first(n + 1, 0), adjacent(tree_edges.size());
  for (std::uint32_t v : tree_edges) ++adjacent_first[v + 1];
  for (std::size_t i = 0; i < n; ++i) adjacent_first[i + 1] += adjacent_first[i];
  {
    std::vector<std::uint32_t> fill(adjacent_first.begin(), adjacent_first.end() - 1);
    for (std::size_t e = 0; e < tree_edges.size(); e += 2) {
      adjacent[fill[tree_edges[e]]++] = tree_edges[e + 1];
      adjacent[fill[tree_edges[e + 1]]++] = tree_edges[e];
    }
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
        for (std::uint32_t j = adjacent_first[p]; j < adjacent_first[p + 1]; ++j) {
          const std::uint32_t c = adjacent[j];
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
  const std::size_t edge_blocks = (edges.size() + kBlock - 1) / kBlock;
  std::vector<std::size_t> compared(edge_blocks, 0), frustrated(edge_blocks, 0);
  workers.run(edge_blocks, [&](std::size_t block, int) {
    for (std::size_t i = block * kBlock; i < std::min(edges.size(), (block + 1) * kBlock); ++i) {
      const Edge& e = edges[i];
      if (k == 1) {
        const double a = overlap_determinant(out.frame(e.a), out.frame(e.b), 1, d);
        if (std::abs(a) < cos45) continue;
        ++compared[block];
        if (a < 0) ++frustrated[block];
        continue;
      }
      const Square a = overlap(out.frame(e.a), out.frame(e.b), k, d);
      Eigen::JacobiSVD<Square> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
      if (svd.singularValues().minCoeff() < cos45) continue;
      ++compared[block];
      const Square r = svd.matrixU() * svd.matrixV().transpose();
      if (r.determinant() < 0) {
        ++frustrated[block];
        continue;
      }
      const Square diff = r - Square::Identity(k, k);
      if (Eigen::JacobiSVD<Square>(diff).singularValues()[0] > 1) ++frustrated[block];
    }
  });
  for (std::size_t b = 0; b < edge_blocks; ++b) {
    out.compared_edges += compared[b];
    out.frustrated_edges += frustrated[b];
  }
  return out;
}

}  // namespace coxmesh
