// Thesis §1.2.2, Thm 1.2.15 (simple roots), Def. 1.2.11–1.2.13, Prop. 1.2.28.
#include "coxmesh/quality/root_system.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <unordered_set>

#include "coxmesh/lattice/simplex.h"  // InputError

namespace coxmesh::quality {

namespace {

using IntVector = std::vector<int>;  // a root in doubled coordinates (2·x is integral for every root)

int min_rank(Family f) {
  switch (f) {
    case Family::A:
      return 1;
    case Family::B:
    case Family::C:
      return 2;
    case Family::D:
      return 4;
    case Family::E:
      return 6;
    case Family::F:
      return 4;
    case Family::G:
      return 2;
  }
  return 0;
}

int max_rank(Family f) {
  switch (f) {
    case Family::E:
      return 8;
    case Family::F:
      return 4;
    case Family::G:
      return 2;
    default:
      return kMaxRank;
  }
}

std::string describe_ranks(Family f) {
  switch (f) {
    case Family::E:
      return "6, 7 or 8";
    case Family::F:
      return "4 only";
    case Family::G:
      return "2 only";
    default:
      return std::to_string(min_rank(f)) + ".." + std::to_string(kMaxRank);
  }
}

int ambient_dimension(Family f, int d) {
  switch (f) {
    case Family::A:
      return d + 1;
    case Family::E:
      return 8;
    case Family::G:
      return 3;
    default:
      return d;
  }
}

// Thm 1.2.15, every coordinate doubled: row i−1 holds 2·s_i.
std::vector<IntVector> doubled_simple_roots(Family f, int d) {
  const int n = ambient_dimension(f, d);
  std::vector<IntVector> s(d, IntVector(n, 0));
  auto chain = [&](int count) {  // s_i = e_i − e_{i+1}, i = 1..count
    for (int i = 0; i < count; ++i) s[i][i] = 2, s[i][i + 1] = -2;
  };
  switch (f) {
    case Family::A:
      chain(d);
      break;
    case Family::B:
      chain(d - 1);
      s[d - 1][d - 1] = 2;
      break;
    case Family::C:
      chain(d - 1);
      s[d - 1][d - 1] = 4;
      break;
    case Family::D:
      chain(d - 1);
      s[d - 1][d - 2] = 2, s[d - 1][d - 1] = 2;
      break;
    case Family::E:
      // s1 = ½(e1+e8) − ½(e2+…+e7), s2 = e1+e2, s3 = e2−e1, s_k = e_{k−1} − e_{k−2} (k = 4..8).
      s[0] = {1, -1, -1, -1, -1, -1, -1, 1};
      s[1][0] = 2, s[1][1] = 2;
      for (int k = 3; k <= d; ++k) s[k - 1][k - 2] = 2, s[k - 1][k - 3] = -2;
      break;
    case Family::F:
      // s1 = e2−e3, s2 = e3−e4, s3 = e4, s4 = ½(e1−e2−e3−e4).
      s[0] = {0, 2, -2, 0};
      s[1] = {0, 0, 2, -2};
      s[2] = {0, 0, 0, 2};
      s[3] = {1, -1, -1, -1};
      break;
    case Family::G:
      // s1 = e1−e2, s2 = −2e1+e2+e3.
      s[0] = {2, -2, 0};
      s[1] = {-4, 2, 2};
      break;
  }
  return s;
}

long dot(const IntVector& a, const IntVector& b) {
  long sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += static_cast<long>(a[k]) * b[k];
  return sum;
}

// n(s, r) = 2⟨r, s⟩/⟨r, r⟩, which must be an integer for a crystallographic system.
int cartan_integer(const IntVector& s, const IntVector& r) {
  const long num = 2 * dot(r, s), den = dot(r, r);
  if (num % den != 0) throw std::logic_error("root_system: non-integral Cartan integer");
  return static_cast<int>(num / den);
}

Eigen::MatrixXd to_matrix(const std::vector<IntVector>& rows, int n) {
  Eigen::MatrixXd m(rows.size(), n);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < n; ++k) m(i, k) = 0.5 * rows[i][k];
  return m;
}

std::vector<DiagramEdge> diagram_of(const std::vector<IntVector>& nodes, int first_label) {
  std::vector<DiagramEdge> edges;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      if (dot(nodes[i], nodes[j]) == 0) continue;
      const int p = cartan_integer(nodes[i], nodes[j]) * cartan_integer(nodes[j], nodes[i]);  // 4cos²φ
      const int m = p == 1 ? 3 : p == 2 ? 4 : p == 3 ? 6 : 0;
      edges.push_back({static_cast<int>(i) + first_label, static_cast<int>(j) + first_label, m});
    }
  return edges;
}

IntVector doubled(const Eigen::VectorXd& v) {
  IntVector out(v.size());
  for (Eigen::Index k = 0; k < v.size(); ++k) out[k] = static_cast<int>(std::lround(2 * v[k]));
  return out;
}

}  // namespace

std::string family_name(Family f) { return std::string(1, static_cast<char>('A' + static_cast<int>(f))); }

Family parse_family(std::string_view text) {
  if (text.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
    if (c >= 'A' && c <= 'G') return static_cast<Family>(c - 'A');
  }
  throw InputError("unknown root system type '" + std::string(text) + "' (expected one of A, B, C, D, E, F, G)");
}

std::vector<int> supported_ranks(Family f, int max_rank_wanted) {
  std::vector<int> out;
  for (int d = min_rank(f); d <= std::min(max_rank(f), max_rank_wanted); ++d) out.push_back(d);
  return out;
}

void check_root_system(Family f, int d) {
  if (d < min_rank(f) || d > max_rank(f))
    throw InputError("there is no root system of type " + family_name(f) + " and rank " + std::to_string(d) +
                     " (type " + family_name(f) + " supports d = " + describe_ranks(f) + ")");
}

Eigen::MatrixXd simple_roots(Family f, int d) {
  check_root_system(f, d);
  return to_matrix(doubled_simple_roots(f, d), ambient_dimension(f, d));
}

RootSystem make_root_system(Family f, int d) {
  check_root_system(f, d);
  const int n = ambient_dimension(f, d);
  const std::vector<IntVector> simple = doubled_simple_roots(f, d);

  // Cartan integers from the vectors of Thm 1.2.15, exactly: cartan(i, j) = n(s_i, s_j).
  Eigen::MatrixXi cartan(d, d);
  std::vector<std::vector<int>> touching(d);  // i with cartan(i, j) ≠ 0, for each j
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) {
      cartan(i, j) = cartan_integer(simple[i], simple[j]);
      if (cartan(i, j) != 0) touching[j].push_back(i);
    }

  // Closure under the simple reflections σ_{s_j}(r) = r − n(r, s_j)·s_j, breadth first, in coordinates
  // on the simple roots (r = Σ c_i s_i gives n(r, s_j) = Σ_i c_i·n(s_i, s_j), and σ_{s_j} changes c_j only).
  struct Entry {
    IntVector coeff;
    int height;
  };
  struct Hash {
    std::size_t operator()(const IntVector& v) const {
      std::size_t h = 1469598103934665603ull;
      for (int x : v) h = (h ^ static_cast<std::size_t>(x + 1024)) * 1099511628211ull;
      return h;
    }
  };
  std::unordered_set<IntVector, Hash> seen;
  std::deque<Entry> queue;
  for (int j = 0; j < d; ++j) {
    IntVector coeff(d, 0);
    coeff[j] = 1;
    seen.insert(coeff);
    queue.push_back({coeff, 1});
  }
  std::vector<Entry> positive;
  std::size_t total = 0;
  while (!queue.empty()) {
    Entry e = std::move(queue.front());
    queue.pop_front();
    for (int j = 0; j < d; ++j) {
      int pairing = 0;
      for (int i : touching[j]) pairing += e.coeff[i] * cartan(i, j);
      if (pairing == 0) continue;
      Entry image = e;
      image.coeff[j] -= pairing;
      image.height -= pairing;
      if (seen.insert(image.coeff).second) queue.push_back(std::move(image));
    }
    const bool nonneg = std::all_of(e.coeff.begin(), e.coeff.end(), [](int x) { return x >= 0; });
    const bool nonpos = std::all_of(e.coeff.begin(), e.coeff.end(), [](int x) { return x <= 0; });
    if (!nonneg && !nonpos) throw std::logic_error("root_system: a root with mixed signs");
    if (nonneg) positive.push_back(std::move(e));
    ++total;
  }
  const Eigen::MatrixXd S = to_matrix(simple, n);
  std::sort(positive.begin(), positive.end(), [](const Entry& a, const Entry& b) {
    return a.height != b.height ? a.height < b.height : a.coeff < b.coeff;
  });
  if (2 * positive.size() != total) throw std::logic_error("root_system: R ≠ R⁺ ∪ −R⁺");

  RootSystem rs;
  rs.family = f;
  rs.rank = d;
  rs.ambient = n;
  rs.simple_roots = S;
  rs.positive_count = static_cast<int>(positive.size());
  rs.coefficients.resize(total, d);
  for (int p = 0; p < rs.positive_count; ++p)
    for (int sign = 0; sign < 2; ++sign) {
      const int row = p + sign * rs.positive_count;
      const int m = sign ? -1 : 1;
      for (int i = 0; i < d; ++i) rs.coefficients(row, i) = m * positive[p].coeff[i];
    }
  rs.roots = rs.coefficients.cast<double>() * S;  // half-integers: exact

  // Highest root: the maximum for the partial order of Def. 1.2.11 (it has the largest height).
  const Entry& top = positive.back();
  for (const Entry& e : positive)
    for (int i = 0; i < d; ++i)
      if (e.coeff[i] > top.coeff[i]) throw std::logic_error("root_system: no highest root");
  rs.highest_coefficients = Eigen::Map<const Eigen::VectorXi>(top.coeff.data(), d);
  rs.highest_root = rs.roots.row(rs.positive_count - 1).transpose();

  rs.cartan = cartan;
  return rs;
}

std::vector<DiagramEdge> coxeter_diagram(const RootSystem& rs) {
  std::vector<IntVector> nodes;
  for (int i = 0; i < rs.rank; ++i) nodes.push_back(doubled(rs.simple_roots.row(i).transpose()));
  return diagram_of(nodes, 1);
}

std::vector<DiagramEdge> affine_coxeter_diagram(const RootSystem& rs) {
  std::vector<IntVector> nodes{doubled(-rs.highest_root)};
  for (int i = 0; i < rs.rank; ++i) nodes.push_back(doubled(rs.simple_roots.row(i).transpose()));
  return diagram_of(nodes, 0);
}

double weyl_group_order(Family f, int d) {
  check_root_system(f, d);
  double factorial = 1;
  for (int k = 2; k <= d; ++k) factorial *= k;
  switch (f) {
    case Family::A:
      return factorial * (d + 1);
    case Family::B:
    case Family::C:
      return std::ldexp(factorial, d);
    case Family::D:
      return std::ldexp(factorial, d - 1);
    case Family::E:
      return d == 6 ? 51840.0 : d == 7 ? 2903040.0 : 696729600.0;
    case Family::F:
      return 1152.0;
    case Family::G:
      return 12.0;
  }
  return 0;
}

}  // namespace coxmesh::quality
