// Tests of the simplex value type: canonical form, text form, order, packing, hashing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <set>
#include <unordered_set>

#include "coxmesh/lattice/simplex.h"

using namespace coxmesh;

TEST(Simplex, TextRoundTrip) {
  for (const char* text : {"(0,0) [{0},{1},{2}]", "(3,-2,0) [{0,2},{1},{3}]", "(-5) [{0,1}]",
                           "(0,0,0,0,0,0,0,0,0,0) [{5},{2},{3,7},{4,9},{0,6,8},{1,10}]"}) {
    const Simplex s = parse_simplex(text);
    EXPECT_EQ(to_string(s), text);
    EXPECT_EQ(parse_simplex(to_string(s)), s);
  }
  // Whitespace is tolerated; the printed form is normalised.
  EXPECT_EQ(to_string(parse_simplex(" ( 1 , 2 )[ {0} ,{ 1,2 } ] ")), "(1,2) [{0},{1,2}]");
}

TEST(Simplex, VerticesFollowTheEncoding) {
  // A worked example computed with GUDHI: vertices of (0,0,0)[{0},{1},{2},{3}].
  const Simplex s = parse_simplex("(0,0,0) [{0},{1},{2},{3}]");
  const int expected[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.vertex_coordinate(j, i), expected[j][i]);
  EXPECT_EQ(s.dimension(), 3);
  EXPECT_EQ(s.block_size(0), 1);
}

TEST(Simplex, MalformedTextIsRejected) {
  for (const char* bad :
       {"", "(0,0)", "(0,0) [{0},{1},{2}", "(0,0) [{1,0},{2}]", "(0,0) [{0,1},{1,2}]", "(0,0) [{0},{2},{1}]",
        "(0,0) [{0},{1}]", "(0,0) [{0},{},{1,2}]", "(0,a) [{0,1,2}]", "(0,0) [{0,1,2}] x", "(0,0) [{0,1,3}]",
        "(0,99999999999) [{0,1,2}]", "(0,2000000000) [{0,1,2}]", "() [{0}]"}) {
    EXPECT_THROW(parse_simplex(bad), InputError) << bad;
  }
  // d too large.
  std::string big = "(";
  for (int i = 0; i < 32; ++i) big += (i ? ",0" : "0");
  big += ") [{0}]";
  EXPECT_THROW(parse_simplex(big), InputError);
}

TEST(Simplex, OrderIsTotalAndPutsCofacesFirst) {
  const Simplex edge = parse_simplex("(0,0) [{0,1},{2}]");
  const Simplex tri = parse_simplex("(0,0) [{0},{1},{2}]");
  EXPECT_LT(tri, edge);  // same y: more blocks first
  EXPECT_FALSE(edge < edge);
  EXPECT_LT(parse_simplex("(0,0) [{0},{1,2}]"), parse_simplex("(0,0) [{0,1},{2}]"));
  EXPECT_LT(parse_simplex("(0,0) [{0},{1,2}]"), parse_simplex("(0,0) [{1},{0,2}]"));
  EXPECT_LT(parse_simplex("(-1,5) [{0,1,2}]"), parse_simplex("(0,0) [{0,1,2}]"));
}

namespace {
Simplex random_simplex(std::mt19937_64& rng, int d) {
  std::vector<int> perm(d);
  for (int i = 0; i < d; ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  perm.push_back(d);
  std::vector<std::vector<int>> blocks{{perm[0]}};
  for (int i = 1; i <= d; ++i) {
    if (rng() % 2 && perm[i] != d)
      blocks.push_back({perm[i]});
    else
      blocks.back().push_back(perm[i]);
  }
  // d must end in the last block: move it there if the shuffle left it elsewhere (it is last).
  std::vector<std::int32_t> y(d);
  for (auto& v : y) v = static_cast<std::int32_t>(rng() % 11) - 5;
  return Simplex::from_partition(y, blocks);
}
}  // namespace

// Strict avalanche on structured keys (packed simplices near the origin: small y, labels ≤ d):
// flipping any bit of any word flips every bit of the hash about half the time. A hash that ignores
// a word, or a sum of the words times constants without the final mix (whose low bits see only the
// words' low bits), fails; so does one whose tag (the top 32 bits, the tables' home slot and tag)
// misses some input bits.
TEST(Simplex, HashAvalanchesOnStructuredKeys) {
  std::mt19937_64 rng(11);
  for (const int d : {3, 9, 31}) {
    const int words = packed_words(d);
    constexpr int kKeys = 300;
    std::vector<int> flips(static_cast<std::size_t>(words) * 32 * 64, 0);
    for (int t = 0; t < kKeys; ++t) {
      std::uint32_t w[packed_words(kMaxDimension)];
      pack(random_simplex(rng, d), w);
      const std::uint64_t h = hash_words(w, words);
      for (int bit = 0; bit < words * 32; ++bit) {
        w[bit / 32] ^= 1u << bit % 32;
        const std::uint64_t changed = h ^ hash_words(w, words);
        w[bit / 32] ^= 1u << bit % 32;
        for (int out = 0; out < 64; ++out) flips[static_cast<std::size_t>(bit) * 64 + out] += (changed >> out) & 1;
      }
    }
    int worst = kKeys / 2;
    for (const int f : flips) worst = std::abs(f - kKeys / 2) > std::abs(worst - kKeys / 2) ? f : worst;
    EXPECT_GT(worst, kKeys * 3 / 10) << "d = " << d;  // (7 standard deviations from a half)
    EXPECT_LT(worst, kKeys * 7 / 10) << "d = " << d;
  }
}

TEST(Simplex, PackRoundTripAndHashQuality) {
  std::mt19937_64 rng(7);
  std::unordered_set<std::uint64_t> hashes;
  std::set<Simplex> distinct;
  for (int t = 0; t < 20000; ++t) {
    const int d = 1 + static_cast<int>(rng() % kMaxDimension);
    const Simplex s = random_simplex(rng, d);
    std::uint32_t w[packed_words(kMaxDimension)];
    pack(s, w);
    EXPECT_EQ(unpack(w, d), s);
    EXPECT_EQ(hash_value(s), hash_words(w, packed_words(d)));
    if (distinct.insert(s).second) hashes.insert(hash_value(s));
  }
  EXPECT_EQ(hashes.size(), distinct.size());  // no 64-bit collision among distinct simplices
  // The hash depends on the partition, not only on y (GUDHI hashes only y).
  EXPECT_NE(hash_value(parse_simplex("(0,0) [{0},{1},{2}]")), hash_value(parse_simplex("(0,0) [{1},{0},{2}]")));
  EXPECT_EQ(packed_words(3) * 4, 16);
}

TEST(Simplex, DimensionLimits) {
  EXPECT_THROW(check_dimension(0), InputError);
  EXPECT_THROW(check_dimension(kMaxDimension + 1), InputError);
  EXPECT_NO_THROW(check_dimension(kMaxDimension));
}
