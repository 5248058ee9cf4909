// Faces and cofaces: worked examples computed with GUDHI, exact counts (thesis §3.5), and a brute-force
// enumeration of all simplices of a box from their vertex sets (independent of the encoding).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/util/fixed_dimension.h"

using namespace coxmesh;

namespace {

std::set<Simplex> faces(const Simplex& s, int k) {
  std::set<Simplex> out;
  FaceEnumerator e(s, k);
  for (Simplex f; e.next(f);) EXPECT_TRUE(out.insert(f).second) << "duplicate face " << f;
  return out;
}

// Through both APIs (copy out, and a view of the enumerator's own copy), which must agree.
std::set<Simplex> cofaces(const Simplex& s, int l) {
  std::set<Simplex> out;
  CofaceEnumerator e(s, l), view(s, l);
  for (Simplex f; e.next(f);) {
    EXPECT_TRUE(out.insert(f).second) << "duplicate coface " << f;
    const Simplex* g = view.next();
    EXPECT_TRUE(g && *g == f) << "the view API gives another coface than " << f;
  }
  EXPECT_EQ(view.next(), nullptr);
  return out;
}

std::set<Simplex> parse_all(std::initializer_list<const char*> texts) {
  std::set<Simplex> out;
  for (const char* t : texts) out.insert(parse_simplex(t));
  return out;
}

using VertexSet = std::vector<std::vector<int>>;  // sorted lattice points

VertexSet vertex_set(const Simplex& s) {
  VertexSet v(s.k + 1, std::vector<int>(s.d));
  for (int j = 0; j <= s.k; ++j)
    for (int i = 0; i < s.d; ++i) v[j][i] = s.vertex_coordinate(j, i);
  std::sort(v.begin(), v.end());
  return v;
}

// All simplices with minimal vertex in [lo, hi]^d, as vertex sets: strict chains
// y = v_0 < v_1 < … < v_k with v_k − y ∈ {0,1}^d (chains ∅ ⊂ A_1 ⊂ … ⊂ A_k ⊆ {0..d−1}).
void chains(int d, std::vector<int>& y, unsigned prev, VertexSet& cur, std::vector<VertexSet>& out) {
  {
    VertexSet sorted = cur;
    std::sort(sorted.begin(), sorted.end());
    out.push_back(sorted);
  }
  for (unsigned a = prev + 1; a < (1u << d); ++a) {
    if ((a & prev) != prev) continue;  // must be a strict superset
    std::vector<int> v = y;
    for (int i = 0; i < d; ++i) v[i] += (a >> i) & 1;
    cur.push_back(v);
    chains(d, y, a, cur, out);
    cur.pop_back();
  }
}

std::vector<VertexSet> all_simplices_in_box(int d, int lo, int hi) {
  std::vector<VertexSet> out;
  std::vector<int> y(d, lo);
  while (true) {
    VertexSet cur{y};
    chains(d, y, 0, cur, out);
    int i = 0;
    while (i < d && y[i] == hi) y[i++] = lo;
    if (i == d) break;
    ++y[i];
  }
  return out;
}

bool subset(const VertexSet& a, const VertexSet& b) { return std::includes(b.begin(), b.end(), a.begin(), a.end()); }

}  // namespace

TEST(Faces, WorkedExamplesComputedWithGudhi) {
  // (Every example here was produced by GUDHI's Coxeter_triangulation module.) The edges of the
  // two triangles at the origin of R².
  EXPECT_EQ(faces(parse_simplex("(0,0) [{0},{1},{2}]"), 1),
            parse_all({"(0,0) [{0},{1,2}]", "(0,0) [{0,1},{2}]", "(1,0) [{1},{0,2}]"}));
  EXPECT_EQ(faces(parse_simplex("(0,0) [{1},{0},{2}]"), 1),
            parse_all({"(0,0) [{1},{0,2}]", "(0,0) [{0,1},{2}]", "(0,1) [{0},{1,2}]"}));
  // The faces of every dimension of a tetrahedron of R³.
  const Simplex s = parse_simplex("(0,0,0) [{0},{1},{2},{3}]");
  EXPECT_EQ(faces(s, 1), parse_all({"(0,0,0) [{0},{1,2,3}]", "(0,0,0) [{0,1},{2,3}]", "(0,0,0) [{0,1,2},{3}]",
                                    "(1,0,0) [{1},{0,2,3}]", "(1,0,0) [{1,2},{0,3}]", "(1,1,0) [{2},{0,1,3}]"}));
  EXPECT_EQ(faces(s, 2), parse_all({"(0,0,0) [{0},{1},{2,3}]", "(0,0,0) [{0},{1,2},{3}]", "(0,0,0) [{0,1},{2},{3}]",
                                    "(1,0,0) [{1},{2},{0,3}]"}));
  EXPECT_EQ(faces(s, 3), parse_all({"(0,0,0) [{0},{1},{2},{3}]"}));
  EXPECT_THROW(FaceEnumerator(s, 4), InputError);
}

TEST(Cofaces, WorkedExamplesComputedWithGudhi) {
  const Simplex v = parse_simplex("(0,0) [{0,1,2}]");  // the origin of R²: 6 edges, 6 triangles
  EXPECT_EQ(cofaces(v, 1), parse_all({"(0,0) [{0,1},{2}]", "(-1,-1) [{0,1},{2}]", "(0,0) [{1},{0,2}]",
                                      "(0,-1) [{1},{0,2}]", "(0,0) [{0},{1,2}]", "(-1,0) [{0},{1,2}]"}));
  EXPECT_EQ(cofaces(v, 2), parse_all({"(0,0) [{0},{1},{2}]", "(0,0) [{1},{0},{2}]", "(-1,-1) [{0},{1},{2}]",
                                      "(0,-1) [{1},{0},{2}]", "(-1,0) [{0},{1},{2}]", "(-1,-1) [{1},{0},{2}]"}));
  // The triangles on two edges at the origin.
  EXPECT_EQ(cofaces(parse_simplex("(0,0) [{0,1},{2}]"), 2), parse_all({"(0,0) [{0},{1},{2}]", "(0,0) [{1},{0},{2}]"}));
  EXPECT_EQ(cofaces(parse_simplex("(0,0) [{0},{1,2}]"), 2), parse_all({"(0,0) [{0},{1},{2}]", "(0,-1) [{1},{0},{2}]"}));
  // An edge of R³ and its cofaces of every dimension.
  const Simplex e = parse_simplex("(0,0,0) [{0,1},{2,3}]");
  EXPECT_EQ(cofaces(e, 2), parse_all({"(0,0,0) [{0},{1},{2,3}]", "(0,0,0) [{1},{0},{2,3}]", "(0,0,0) [{0,1},{2},{3}]",
                                      "(0,0,-1) [{2},{0,1},{3}]"}));
  EXPECT_EQ(cofaces(e, 3), parse_all({"(0,0,0) [{0},{1},{2},{3}]", "(0,0,0) [{1},{0},{2},{3}]",
                                      "(0,0,-1) [{2},{1},{0},{3}]", "(0,0,-1) [{2},{0},{1},{3}]"}));
  EXPECT_EQ(cofaces(e, 1), parse_all({"(0,0,0) [{0,1},{2,3}]"}));
}

TEST(Cofaces, GudhiUnitTestInDimension10) {
  // GUDHI's own unit test.
  const Simplex s = parse_simplex("(0,0,0,0,0,0,0,0,0,0) [{5},{2},{3,7},{4,9},{0,6,8},{1,10}]");
  EXPECT_EQ(s.dimension(), 5);
  EXPECT_EQ(faces(s, 4).size(), 6u);
  EXPECT_EQ(faces(s, 3).size(), 15u);
  const std::uint64_t expected[] = {1, 12, 54, 116, 120, 48};
  for (int l = 5; l <= 10; ++l) {
    EXPECT_EQ(cofaces(s, l).size(), expected[l - 5]) << "l = " << l;
    EXPECT_EQ(coface_count(s, l), expected[l - 5]);
  }
  EXPECT_TRUE(is_face_of(parse_simplex("(0,0,0,0,0,0,0,0,0,0) [{5},{0,1,2,3,4,6,7,8,9,10}]"), s));
  const Simplex c = parse_simplex("(0,-1,0,0,0,0,0,0,0,0) [{1},{5},{2},{3,7},{4,9},{0,6,8},{10}]");
  EXPECT_TRUE(is_face_of(s, c));
  EXPECT_FALSE(is_face_of(c, s));
}

TEST(Cofaces, VertexStarIsAPermutahedron) {
  // l-cofaces of a vertex = faces of dimension d − l of the permutahedron of order d+1 (thesis §3.5).
  const std::vector<std::vector<std::uint64_t>> expected = {{1, 2},
                                                            {1, 6, 6},
                                                            {1, 14, 36, 24},
                                                            {1, 30, 150, 240, 120},
                                                            {1, 62, 540, 1560, 1800, 720},
                                                            {1, 126, 1806, 8400, 16800, 15120, 5040}};
  for (int d = 1; d <= 6; ++d) {
    const Simplex v = Simplex::vertex_simplex(std::vector<std::int32_t>(d, 3));
    for (int l = 0; l <= d; ++l) {
      EXPECT_EQ(cofaces(v, l).size(), expected[d - 1][l]);
      EXPECT_EQ(coface_count(v, l), expected[d - 1][l]);
    }
  }
}

// The blocks of 0 … d, a new block starting at i wherever bit i − 1 of `cuts` is set: every
// composition of d + 1 (every simplex type) for cuts = 0 … 2^d − 1.
std::vector<std::vector<int>> blocks_cut_at(int d, unsigned cuts) {
  std::vector<std::vector<int>> blocks{{0}};
  for (int i = 1; i <= d; ++i) {
    if (cuts >> (i - 1) & 1)
      blocks.push_back({i});
    else
      blocks.back().push_back(i);
  }
  return blocks;
}

TEST(Cofaces, CountFormulaForEverySimplexTypeUpToDimension6) {
  // A type is the sequence of block sizes (a composition of d+1); check one simplex of each type
  // and every l, including the closed forms for cofacets and maximal cofaces.
  for (int d = 1; d <= 6; ++d) {
    for (unsigned cuts = 0; cuts < (1u << d); ++cuts) {
      std::vector<std::vector<int>> blocks = blocks_cut_at(d, cuts);
      const Simplex s = Simplex::from_partition(std::vector<std::int32_t>(d, -1), blocks);
      std::uint64_t facets_formula = 0, maximal_formula = 1;
      for (const auto& b : blocks) {
        facets_formula += (1u << b.size()) - 2;
        for (std::size_t f = 2; f <= b.size(); ++f) maximal_formula *= f;
      }
      for (int l = s.k; l <= d; ++l) {
        const auto found = cofaces(s, l);
        EXPECT_EQ(found.size(), coface_count(s, l)) << s << " l=" << l;
        for (const Simplex& c : found) EXPECT_TRUE(is_face_of(s, c)) << s << " not a face of " << c;
      }
      if (s.k < d) {
        EXPECT_EQ(coface_count(s, s.k + 1), facets_formula);
      }
      EXPECT_EQ(coface_count(s, d), maximal_formula);
    }
  }
}

// The packed walk must give CofaceEnumerator's cofacets in CofaceEnumerator's order: the cell
// complex numbers its cells by it.
void expect_packed_cofacets_as_enumerated(const Simplex& s) {
  const int d = s.d, words = packed_words(d);
  std::vector<std::uint32_t> expected, found, key(words);
  CofaceEnumerator e(s, s.k + 1);
  for (Simplex c; e.next(c);) {
    pack(c, key.data());
    expected.insert(expected.end(), key.begin(), key.end());
  }
  pack(s, key.data());
  // d read at run time, and fixed at compile time as the cell complex does for d = 2, 3, 4
  const auto check = [&](const auto& cofacets) {
    found.clear();
    cofacets.for_each([&](const std::uint32_t* c, std::uint64_t hash) {
      found.insert(found.end(), c, c + words);
      EXPECT_EQ(hash, hash_words(c, words));  // (kept up to date word by word)
    });
    EXPECT_EQ(found, expected) << s;
    EXPECT_EQ(cofacets.count(), expected.size() / words) << s;
  };
  check(PackedCofacets<0>(key.data(), d));
  with_fixed_dimension<2, 3, 4>(d,
                                [&](auto fixed_d) { check(PackedCofacets<decltype(fixed_d)::value>(key.data(), d)); });
}

TEST(Cofaces, PackedCofacetsInEnumeratorOrderForEveryTypeUpToDimension7) {
  for (int d = 1; d <= 7; ++d)
    for (unsigned cuts = 0; cuts + 1 < (1u << d); ++cuts) {  // (the last type, k = d, has no cofacets)
      // Every composition of d + 1 into blocks (d's block last), the others in several orders.
      std::vector<std::vector<int>> blocks = blocks_cut_at(d, cuts);
      std::vector<std::int32_t> y(d);
      for (int i = 0; i < d; ++i) y[i] = (i % 3 == 0 ? -1 : 1) * (i + 1) * 1000 - (i % 2);
      for (std::size_t r = 0; r < blocks.size(); ++r) {
        expect_packed_cofacets_as_enumerated(Simplex::from_partition(y, blocks));
        if (blocks.size() >= 3) std::rotate(blocks.begin(), blocks.begin() + 1, blocks.end() - 1);
      }
    }
}

TEST(Cofaces, PackedCofacetsInEnumeratorOrderUpToTheLargestDimension) {
  std::mt19937 rng(3);
  for (int d : {8, 9, 12, 16, 20, 31})
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<std::int32_t> y(d);
      for (auto& c : y) c = std::uniform_int_distribution<int>(-kMaxLatticeCoordinate + 1, kMaxLatticeCoordinate)(rng);
      std::vector<int> order(d);
      for (int i = 0; i < d; ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), rng);
      // (k near d: a block of n elements has 2^n − 2 cofacets)
      const int k = d - std::uniform_int_distribution<int>(1, 6)(rng);
      std::vector<std::vector<int>> blocks(k + 1);
      blocks[k].push_back(d);
      for (int b = 0; b < k; ++b) blocks[b].push_back(order[b]);
      for (int i = k; i < d; ++i) blocks[std::uniform_int_distribution<int>(0, k)(rng)].push_back(order[i]);
      expect_packed_cofacets_as_enumerated(Simplex::from_partition(y, blocks));
    }
}

// for_each_cofacet_vertex gives, once per cofacet, the vertex it adds to τ: the same list as the
// cofacets of CofaceEnumerator, up to order. And place_among_facet_cofacets finds each cofacet's
// place in the enumeration from the cofacet alone and the index of the vertex it adds (with d fixed
// at compile time too, where the walk fixes it).
void expect_cofacet_vertices_as_enumerated(const Simplex& s) {
  const int d = s.d;
  std::vector<std::vector<std::int32_t>> expected, found;
  CofaceEnumerator e(s, s.k + 1);
  std::vector<std::int32_t> v(d);
  std::uint64_t place = 0;
  for (Simplex c; e.next(c); ++place) {
    const int j = extra_vertex_index(s, c);
    c.vertex(j, v.data());
    expected.push_back(v);
    EXPECT_EQ(place_among_facet_cofacets(c, j), place) << s << ", cofacet " << c;
    with_fixed_dimension<3, 4, 6, 9>(d, [&](auto fixed_d) {
      EXPECT_EQ(place_among_facet_cofacets<decltype(fixed_d)::value>(c, j), place) << s << ", cofacet " << c;
    });
  }
  for_each_cofacet_vertex(s, [&](const std::int32_t* w) { found.emplace_back(w, w + d); });
  std::sort(expected.begin(), expected.end());
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected) << s;
}

TEST(Cofaces, CofacetVerticesForEveryTypeUpToDimension7) {
  for (int d = 1; d <= 7; ++d)
    for (unsigned cuts = 0; cuts < (1u << d); ++cuts) {
      std::vector<std::vector<int>> blocks = blocks_cut_at(d, cuts);
      std::vector<std::int32_t> y(d);
      for (int i = 0; i < d; ++i) y[i] = (i % 3 == 0 ? -1 : 1) * (i + 1) * 7 - (i % 2);
      if (cuts + 1 == (1u << d)) {  // k = d: no cofacet, no vertex
        int emitted = 0;
        for_each_cofacet_vertex(Simplex::from_partition(y, blocks), [&](const std::int32_t*) { ++emitted; });
        EXPECT_EQ(emitted, 0);
        continue;
      }
      for (std::size_t r = 0; r < blocks.size(); ++r) {
        expect_cofacet_vertices_as_enumerated(Simplex::from_partition(y, blocks));
        if (blocks.size() >= 3) std::rotate(blocks.begin(), blocks.begin() + 1, blocks.end() - 1);
      }
    }
}

TEST(Cofaces, CofacetVerticesUpToTheLargestDimension) {
  std::mt19937 rng(5);
  for (int d : {8, 12, 20, 31})
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<std::int32_t> y(d);
      for (auto& c : y) c = std::uniform_int_distribution<int>(-1000, 1000)(rng);
      std::vector<int> order(d);
      for (int i = 0; i < d; ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), rng);
      const int k = d - std::uniform_int_distribution<int>(1, 6)(rng);  // (blocks of a few elements)
      std::vector<std::vector<int>> blocks(k + 1);
      blocks[k].push_back(d);
      for (int b = 0; b < k; ++b) blocks[b].push_back(order[b]);
      for (int i = k; i < d; ++i) blocks[std::uniform_int_distribution<int>(0, k)(rng)].push_back(order[i]);
      expect_cofacet_vertices_as_enumerated(Simplex::from_partition(y, blocks));
    }
}

TEST(FacesCofaces, BruteForceOnABoxUpToDimension4) {
  for (int d = 1; d <= 4; ++d) {
    // Simplices with minimal vertex in [-1, 1]^d; queries with minimal vertex 0 have all their
    // cofaces (minimal vertex ≥ −1) and faces (≤ +1) inside.
    const std::vector<VertexSet> all = all_simplices_in_box(d, -1, 1);
    std::map<VertexSet, int> index;
    for (std::size_t i = 0; i < all.size(); ++i) index[all[i]] = static_cast<int>(i);
    ASSERT_EQ(index.size(), all.size());
    int checked = 0;
    for (const VertexSet& vs : all) {
      if (vs.front() != std::vector<int>(d, 0)) continue;
      // Encode the chain: y = v_0, block[i] = step at which coordinate i rises, else the last block.
      const int k = static_cast<int>(vs.size()) - 1;
      std::vector<std::vector<int>> blocks(k + 1);
      for (int i = 0; i < d; ++i) {
        int step = k;
        for (int j = 1; j <= k; ++j)
          if (vs[j][i] > vs[j - 1][i]) step = j - 1;
        blocks[step].push_back(i);
      }
      blocks[k].push_back(d);
      const Simplex s = Simplex::from_partition(std::vector<std::int32_t>(d, 0), blocks);
      ASSERT_EQ(vertex_set(s), vs);
      for (int l = 0; l <= d; ++l) {
        std::set<VertexSet> expect_faces, expect_cofaces, got_faces, got_cofaces;
        for (const VertexSet& other : all) {
          if (static_cast<int>(other.size()) != l + 1) continue;
          if (l <= k && subset(other, vs)) expect_faces.insert(other);
          if (l >= k && subset(vs, other)) expect_cofaces.insert(other);
        }
        if (l <= k)
          for (const Simplex& f : faces(s, l)) got_faces.insert(vertex_set(f));
        if (l >= k)
          for (const Simplex& c : cofaces(s, l)) got_cofaces.insert(vertex_set(c));
        EXPECT_EQ(got_faces, expect_faces) << s << " l=" << l;
        EXPECT_EQ(got_cofaces, expect_cofaces) << s << " l=" << l;
      }
      ++checked;
    }
    // k-simplices per lattice point: Σ_k k!·S(d+1, k+1) (ordered partitions with d last).
    const int per_point[] = {0, 2, 6, 26, 150};
    EXPECT_EQ(checked, per_point[d]);
  }
}

TEST(FacesCofaces, FaceTestAgainstVertexSets) {
  const Simplex s = parse_simplex("(0,0,0) [{1},{0},{2},{3}]");
  for (int k = 0; k <= 3; ++k)
    for (const Simplex& f : faces(s, k)) {
      EXPECT_TRUE(is_face_of(f, s));
      EXPECT_TRUE(subset(vertex_set(f), vertex_set(s)));
    }
  EXPECT_FALSE(is_face_of(parse_simplex("(0,0,0) [{0},{1,2,3}]"), s));
  EXPECT_FALSE(is_face_of(parse_simplex("(0,0,0) [{0,1,2,3}]"), parse_simplex("(1,0,0) [{0,1,2,3}]")));
  // y + (1,…,1) is never a vertex of a simplex based at y.
  EXPECT_FALSE(is_face_of(parse_simplex("(1,1,1) [{0,1,2,3}]"), parse_simplex("(0,0,0) [{0,1},{2,3}]")));
  EXPECT_TRUE(is_face_of(parse_simplex("(1,1,1) [{0,1,2,3}]"), parse_simplex("(0,0,0) [{0,1,2},{3}]")));
}

// The facet test and the key check on packed words agree with the face relation of unpacked
// simplices: every facet of σ is found at its index, and no other simplex of dimension l − 1 near σ
// (the facets of σ's neighbours through its facets, and σ's faces moved by one) is taken for one.
TEST(PackedFaces, FacetIndexAgreesWithTheFaceTest) {
  std::mt19937 rng(5);
  std::size_t facets = 0, others = 0;
  for (int d = 1; d <= 9; ++d)
    for (unsigned cuts = 1; cuts < (1u << d); cuts += (d > 6 ? 37 : 1)) {  // (at least two blocks: l ≥ 1)
      std::vector<std::vector<int>> blocks = blocks_cut_at(d, cuts);
      std::vector<std::int32_t> y(d);
      for (auto& c : y) c = std::uniform_int_distribution<int>(-5, 5)(rng);
      if (blocks.size() >= 3) std::rotate(blocks.begin(), blocks.begin() + 1, blocks.end() - 1);
      const Simplex sigma = Simplex::from_partition(y, blocks);
      const int words = packed_words(d);
      std::vector<std::uint32_t> ks(words), kt(words);
      pack(sigma, ks.data());
      ASSERT_TRUE(is_packed_simplex(ks.data(), d, sigma.k)) << sigma;
      EXPECT_FALSE(is_packed_simplex(ks.data(), d, sigma.k - 1)) << sigma;
      std::set<Simplex> candidates;
      for (int j = 0; j <= sigma.k; ++j) {
        const Simplex f = facet_without(sigma, j);
        pack(f, kt.data());
        ASSERT_TRUE(is_packed_simplex(kt.data(), d, f.k)) << f;
        EXPECT_EQ(packed_facet_index(kt.data(), ks.data(), d), j) << f << " of " << sigma;
        ++facets;
        for (const Simplex& c : cofaces(f, f.k + 1))
          for (int i = 0; i <= c.k; ++i) candidates.insert(facet_without(c, i));
        for (int i = 0; i < d; ++i) {  // (moved faces: some coordinates one off)
          Simplex g = f;
          g.y[i] += i % 2 ? 1 : -1;
          candidates.insert(g);
        }
      }
      for (const Simplex& c : candidates) {
        pack(c, kt.data());
        const int j = packed_facet_index(kt.data(), ks.data(), d);
        EXPECT_EQ(j >= 0, is_face_of(c, sigma)) << c << " and " << sigma;
        if (j >= 0) {
          EXPECT_EQ(facet_without(sigma, j), c);
        }
        others += j < 0;
      }
    }
  EXPECT_GT(facets, 500u);
  EXPECT_GT(others, 10000u);
}

TEST(PackedFaces, KeyCheckRefusesWhatPackNeverWrites) {
  const Simplex s = parse_simplex("(4,-2,7,0,1) [{1,3},{0},{2,4,5}]");  // d = 5, k = 2: two label words
  std::vector<std::uint32_t> key(packed_words(5));
  pack(s, key.data());
  ASSERT_TRUE(is_packed_simplex(key.data(), 5, 2));
  const auto with_label = [&](int i, unsigned char label) {
    std::vector<std::uint32_t> k = key;
    reinterpret_cast<unsigned char*>(k.data() + 5)[i] = label;
    return k;
  };
  EXPECT_FALSE(is_packed_simplex(with_label(0, 3).data(), 5, 2));  // a label beyond k
  EXPECT_FALSE(is_packed_simplex(with_label(5, 1).data(), 5, 2));  // d not in the last block
  EXPECT_FALSE(is_packed_simplex(with_label(0, 2).data(), 5, 2));  // block 1 ({0}) left empty
  EXPECT_FALSE(is_packed_simplex(with_label(6, 1).data(), 5, 2));  // label bytes after d
  EXPECT_FALSE(is_packed_simplex(with_label(7, 1).data(), 5, 2));
  for (const std::int64_t y : {std::int64_t{kMaxLatticeCoordinate} + 1, -std::int64_t{kMaxLatticeCoordinate} - 1}) {
    std::vector<std::uint32_t> k = key;
    k[3] = static_cast<std::uint32_t>(y);
    EXPECT_FALSE(is_packed_simplex(k.data(), 5, 2)) << y;
  }
  key[3] = static_cast<std::uint32_t>(-kMaxLatticeCoordinate);
  EXPECT_TRUE(is_packed_simplex(key.data(), 5, 2));
  EXPECT_FALSE(is_packed_simplex(key.data(), 0, 0));
}
