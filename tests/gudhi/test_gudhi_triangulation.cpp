// Cross-check of the triangulation core against the reference implementation (GUDHI's
// Coxeter_triangulation module, thesis Ch. 3): point location in FK and Ã_d, faces and cofaces of
// every dimension, and the face test, on random inputs (point location in d = 2..20, faces and
// cofaces in d = 2..10, cofacets also in d = 20).
//
// GUDHI is only called here; its simplices (a vector of ints plus a vector of unsorted parts) are
// converted to coxmesh::Simplex and compared as sorted vectors.
//
// GUDHI quirk met here: under UBSan its Permutation_iterator copies an uninitialised bool
// (optim_3_ of a default-constructed end iterator) — "load of value …, which is not a valid value
// for type 'bool'"; sanitizer builds of this test need -fno-sanitize=bool. Harmless in practice.
#include <gtest/gtest.h>

// GUDHI's headers are included as system headers (see tests/CMakeLists.txt): their warnings are not ours.
#include <gudhi/Coxeter_triangulation.h>
#include <gudhi/Freudenthal_triangulation.h>
#include <gudhi/Permutahedral_representation.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/triangulation/triangulation.h"
#include "gudhi_interop.h"

namespace {

namespace gct = Gudhi::coxeter_triangulation;
using GSimplex = gct::Permutahedral_representation<std::vector<int>, std::vector<std::vector<std::size_t>>>;
using coxmesh::Simplex;
using gudhi_interop::from_gudhi;
using gudhi_interop::random_simplex;
using gudhi_interop::to_gudhi;

constexpr std::uint64_t kSeed = 0xC0DEC0FFEEull;
constexpr int kMinDim = 2, kMaxDim = 10;
// Point location is also checked beyond: coxmesh has unrolled kernels for d ≤ 12 and a generic one.
constexpr int kMaxLocateDim = 20;

// ---- Conversions ---------------------------------------------------------------------------------

std::string gudhi_text(const GSimplex& g) {
  std::ostringstream os;
  os << g;
  return os.str();
}

// ---- Random inputs -------------------------------------------------------------------------------

std::vector<double> random_point(std::mt19937_64& rng, int d, double r) {
  std::uniform_real_distribution<double> u(-r, r);
  std::vector<double> x(d);
  for (double& v : x) v = u(rng);
  return x;
}

Eigen::VectorXd random_offset(std::mt19937_64& rng, int d) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(d);
  for (int i = 0; i < d; ++i) b(i) = u(rng);
  return b;
}

template <class Range>
std::vector<Simplex> collect_gudhi(const Range& range) {
  std::vector<Simplex> out;
  for (const auto& g : range) out.push_back(from_gudhi(g));
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Simplex> collect_faces(const Simplex& s, int k) {
  std::vector<Simplex> out;
  coxmesh::FaceEnumerator faces(s, k);
  for (Simplex f; faces.next(f);) out.push_back(f);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Simplex> collect_cofaces(const Simplex& s, int l) {
  std::vector<Simplex> out;
  coxmesh::CofaceEnumerator cofaces(s, l);
  for (Simplex c; cofaces.next(c);) out.push_back(c);
  std::sort(out.begin(), out.end());
  return out;
}

// Compares the simplices located by GUDHI and by coxmesh for n random points in [-radius, radius]^d.
template <class GudhiTriangulation>
void expect_same_location(const GudhiTriangulation& gudhi, const coxmesh::Triangulation& ours, std::mt19937_64& rng,
                          int n, double radius, const std::string& what) {
  const int d = ours.dimension();
  int mismatches = 0;
  for (int t = 0; t < n; ++t) {
    const auto x = random_point(rng, d, radius);
    const GSimplex g = gudhi.locate_point(x);
    const Simplex theirs = from_gudhi(g);
    const Simplex mine = ours.locate(x);
    if (mine != theirs && ++mismatches <= 5) {
      ADD_FAILURE() << what << " d=" << d << ": point location differs\n  gudhi:   " << theirs
                    << "\n  coxmesh: " << mine;
    }
  }
  EXPECT_EQ(mismatches, 0) << what << " d=" << d;
}

}  // namespace

// ---- Point location --------------------------------------------------------------------------------

TEST(GudhiCrossCheck, LocateFreudenthal) {
  std::mt19937_64 rng(kSeed);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Freudenthal_triangulation<GSimplex> gudhi(d);
    expect_same_location(gudhi, coxmesh::Triangulation::freudenthal(d), rng, 5000, 10.0, "FK");
  }
}

TEST(GudhiCrossCheck, LocateFreudenthalWithOffset) {
  std::mt19937_64 rng(kSeed + 1);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    const Eigen::VectorXd b = random_offset(rng, d);
    gct::Freudenthal_triangulation<GSimplex> gudhi(d, Eigen::MatrixXd::Identity(d, d), b);
    expect_same_location(gudhi, coxmesh::Triangulation::freudenthal(d).with_offset(b), rng, 5000, 10.0, "FK+offset");
  }
}

// Points on a dyadic grid hit lower-dimensional faces (ties between fractional parts, integer
// coordinates). FK arithmetic is exact there, so both must find the same minimal face.
TEST(GudhiCrossCheck, LocateFreudenthalDegenerate) {
  std::mt19937_64 rng(kSeed + 2);
  std::uniform_int_distribution<int> grid(-40, 40);
  std::vector<int> dims_seen(kMaxLocateDim + 1, 0);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Freudenthal_triangulation<GSimplex> gudhi(d);
    const auto ours = coxmesh::Triangulation::freudenthal(d);
    for (int t = 0; t < 2000; ++t) {
      std::vector<double> x(d);
      for (double& v : x) v = grid(rng) / 4.0;
      const Simplex theirs = from_gudhi(gudhi.locate_point(x));
      const Simplex mine = ours.locate(x);
      ASSERT_EQ(mine, theirs) << "FK dyadic point, d=" << d;
      ++dims_seen[mine.k];
    }
  }
  EXPECT_GT(dims_seen[0], 0);  // vertices were hit
  EXPECT_GT(dims_seen[2], 0);
}

// Near ties: fractional parts that differ by 1e-8..1e-7 (beyond the 1e-9 tolerance, so they are
// distinct blocks, but closer than the 2^-26 quantisation of coxmesh's sort keys, which must then
// be repaired exactly). Exact arithmetic in FK, so both must agree.
TEST(GudhiCrossCheck, LocateFreudenthalNearTies) {
  std::mt19937_64 rng(kSeed + 6);
  std::uniform_int_distribution<int> grid(-40, 40);
  std::uniform_real_distribution<double> eps(1e-8, 1e-7);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Freudenthal_triangulation<GSimplex> gudhi(d);
    const auto ours = coxmesh::Triangulation::freudenthal(d);
    for (int t = 0; t < 2000; ++t) {
      std::vector<double> x(d);
      for (double& v : x) v = grid(rng) / 4.0 + (rng() % 2 ? eps(rng) : 0.0) + (rng() % 2 ? 0.25 : 0.0);
      const Simplex theirs = from_gudhi(gudhi.locate_point(x));
      const Simplex mine = ours.locate(x);
      ASSERT_EQ(mine, theirs) << "FK near-tie point, d=" << d;
    }
  }
}

TEST(GudhiCrossCheck, LocateCoxeterWithGudhiMatrix) {
  std::mt19937_64 rng(kSeed + 3);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Coxeter_triangulation<GSimplex> gudhi(d);
    const coxmesh::Triangulation ours(gudhi.matrix(), gudhi.offset());
    expect_same_location(gudhi, ours, rng, 5000, 10.0, "Coxeter");
  }
}

TEST(GudhiCrossCheck, LocateCoxeterWithOffset) {
  std::mt19937_64 rng(kSeed + 4);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Coxeter_triangulation<GSimplex> gudhi(d);
    const Eigen::VectorXd b = random_offset(rng, d);
    gudhi.change_offset(b);
    const coxmesh::Triangulation ours(gudhi.matrix(), b);
    expect_same_location(gudhi, ours, rng, 5000, 10.0, "Coxeter+offset");
  }
}

TEST(GudhiCrossCheck, LocateScaledCoxeterWithOffset) {
  std::mt19937_64 rng(kSeed + 5);
  for (int d = kMinDim; d <= kMaxLocateDim; ++d) {
    gct::Coxeter_triangulation<GSimplex> gudhi(d);
    const Eigen::MatrixXd m = 0.37 * gudhi.matrix();
    const Eigen::VectorXd b = random_offset(rng, d);
    gudhi.change_matrix(m);
    gudhi.change_offset(b);
    const coxmesh::Triangulation ours(m, b);
    expect_same_location(gudhi, ours, rng, 3000, 10.0, "scaled Coxeter+offset");
  }
}

// Our closed-form Ã_d matrix and GUDHI's Eigen-computed one differ by a reflection only (thesis §3.1):
// both satisfy Λᵀ·Λ = 2·(I − J/(d+1)).
TEST(GudhiCrossCheck, CoxeterMatrixGramMatchesGudhi) {
  for (int d = kMinDim; d <= kMaxDim; ++d) {
    gct::Coxeter_triangulation<GSimplex> gudhi(d);
    const Eigen::MatrixXd ours = coxmesh::Triangulation::coxeter(d).matrix();
    const Eigen::MatrixXd gram_gudhi = gudhi.matrix().transpose() * gudhi.matrix();
    const Eigen::MatrixXd gram_ours = ours.transpose() * ours;
    EXPECT_LT((gram_gudhi - gram_ours).cwiseAbs().maxCoeff(), 1e-12) << "d=" << d;
  }
}

// ---- Faces, cofaces, face test --------------------------------------------------------------------

TEST(GudhiCrossCheck, FacesOfEveryDimension) {
  std::mt19937_64 rng(kSeed + 10);
  for (int d = kMinDim; d <= kMaxDim; ++d) {
    std::uniform_int_distribution<int> dim(0, d);
    for (int t = 0; t < 150; ++t) {
      const Simplex s = random_simplex(rng, d, dim(rng));
      const GSimplex g = to_gudhi(s);
      ASSERT_EQ(from_gudhi(g), s);
      for (int k = 0; k <= s.k; ++k) {
        const auto theirs = collect_gudhi(g.face_range(k));
        const auto mine = collect_faces(s, k);
        ASSERT_EQ(mine, theirs) << "faces of dimension " << k << " of " << s << " (gudhi " << gudhi_text(g) << ")";
        for (const Simplex& f : mine) ASSERT_TRUE(coxmesh::is_face_of(f, s));
      }
    }
  }
}

TEST(GudhiCrossCheck, CofacesOfEveryDimension) {
  constexpr std::uint64_t kMaxCofaces = 20000;
  std::mt19937_64 rng(kSeed + 11);
  std::uint64_t compared = 0, skipped = 0;
  for (int d = kMinDim; d <= kMaxDim; ++d) {
    std::uniform_int_distribution<int> dim(0, d);
    const int trials = d <= 6 ? 120 : 60;
    for (int t = 0; t < trials; ++t) {
      const Simplex s = random_simplex(rng, d, dim(rng));
      const GSimplex g = to_gudhi(s);
      for (int l = s.k; l <= d; ++l) {
        const std::uint64_t n = coxmesh::coface_count(s, l);
        // Large coface sets are expensive in GUDHI; keep a few in small d only.
        if (n > kMaxCofaces || (n > 2000 && d >= 8 && t % 8 != 0)) {
          ++skipped;
          continue;
        }
        const auto mine = collect_cofaces(s, l);
        ASSERT_EQ(mine.size(), n) << "coface_count(" << s << ", " << l << ")";
        ASSERT_TRUE(std::adjacent_find(mine.begin(), mine.end()) == mine.end())
            << "duplicate " << l << "-coface of " << s;
        const auto theirs = collect_gudhi(g.coface_range(l));
        ASSERT_EQ(mine, theirs) << "cofaces of dimension " << l << " of " << s << " (gudhi " << gudhi_text(g) << ")";
        for (const Simplex& c : mine) ASSERT_TRUE(coxmesh::is_face_of(s, c));
        compared += n;
      }
    }
  }
  RecordProperty("cofaces_compared", std::to_string(compared));
  RecordProperty("coface_sets_skipped", std::to_string(skipped));
  EXPECT_GT(compared, 100000u);
}

// The vertex star is a permutahedron: the coface counts of thesis §3.5 for a vertex, against GUDHI.
TEST(GudhiCrossCheck, VertexStarCounts) {
  for (int d = kMinDim; d <= 6; ++d) {
    const std::vector<std::int32_t> y(d, 0);
    const Simplex v = Simplex::vertex_simplex(y);
    const GSimplex g = to_gudhi(v);
    for (int l = 0; l <= d; ++l) {
      std::uint64_t n_gudhi = 0;
      for (const auto& c : g.coface_range(l)) {
        (void)c;
        ++n_gudhi;
      }
      EXPECT_EQ(coxmesh::coface_count(v, l), n_gudhi) << "d=" << d << " l=" << l;
    }
  }
}

TEST(GudhiCrossCheck, FaceTest) {
  std::mt19937_64 rng(kSeed + 12);
  int positives = 0, negatives = 0;
  for (int d = kMinDim; d <= kMaxDim; ++d) {
    std::uniform_int_distribution<int> dim(0, d);
    for (int t = 0; t < 300; ++t) {
      const Simplex sigma = random_simplex(rng, d, dim(rng));
      // A true face (random vertex subset) and a perturbed one (random y shift, random partition).
      std::uniform_int_distribution<int> fdim(0, sigma.k);
      const int k = fdim(rng);
      std::vector<int> idx(sigma.k + 1);
      std::iota(idx.begin(), idx.end(), 0);
      std::shuffle(idx.begin(), idx.end(), rng);
      idx.resize(k + 1);
      std::sort(idx.begin(), idx.end());
      const Simplex face = coxmesh::face_from_indices(sigma, idx.data(), k);
      Simplex other = random_simplex(rng, d, k);
      for (int i = 0; i < d; ++i) other.y[i] = sigma.y[i] + static_cast<int>(rng() % 2);
      for (const Simplex& tau : {face, other}) {
        const bool theirs = to_gudhi(tau).is_face_of(to_gudhi(sigma));
        const bool mine = coxmesh::is_face_of(tau, sigma);
        ASSERT_EQ(mine, theirs) << tau << " face of " << sigma;
        (mine ? positives : negatives)++;
      }
    }
  }
  EXPECT_GT(positives, 1000);
  EXPECT_GT(negatives, 100);
}

// Beyond the d = 2..10 sweep: cofacets in d = 20 (where (d+1)! no longer fits in 64 bits, which
// coface_count must not trip over when it only needs small entries) and the Σ(2^{n_i} − 2) formula.
TEST(GudhiCrossCheck, CofacetsInDimension20) {
  std::mt19937_64 rng(kSeed + 13);
  constexpr int d = 20;
  for (int t = 0; t < 40; ++t) {
    const int k = 10 + t % 10;
    const Simplex s = random_simplex(rng, d, k);
    std::uint64_t formula = 0;
    for (int b = 0; b <= k; ++b) formula += (std::uint64_t{1} << s.block_size(b)) - 2;
    ASSERT_EQ(coxmesh::coface_count(s, k + 1), formula) << s;
    const auto mine = collect_cofaces(s, k + 1);
    ASSERT_EQ(mine.size(), formula) << s;
    ASSERT_EQ(mine, collect_gudhi(to_gudhi(s).coface_range(k + 1))) << s;
  }
  // A vertex: 2^{d+1} − 2 cofacets even in d = 31; its (d+1)! maximal cofaces overflow from d = 20.
  const Simplex v31 = Simplex::vertex_simplex(std::vector<std::int32_t>(31, 0));
  EXPECT_EQ(coxmesh::coface_count(v31, 1), (std::uint64_t{1} << 32) - 2);
  const Simplex v20 = Simplex::vertex_simplex(std::vector<std::int32_t>(20, 0));
  EXPECT_EQ(coxmesh::coface_count(v20, 1), (std::uint64_t{1} << 21) - 2);
  EXPECT_THROW((void)coxmesh::coface_count(v20, 20), coxmesh::InputError);
  const Simplex v19 = Simplex::vertex_simplex(std::vector<std::int32_t>(19, 0));
  EXPECT_EQ(coxmesh::coface_count(v19, 19), 2432902008176640000ull);  // 20!
}
