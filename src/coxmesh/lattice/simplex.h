// Thesis §3.3 (permutahedral representation). The one definition of the simplex encoding.
//
// A k-simplex of the Freudenthal–Kuhn triangulation of R^d is a pair (y, ω):
//   * y ∈ Z^d, its minimal vertex;
//   * ω = (ω_0, …, ω_k) an ordered partition of {0, …, d} into k+1 non-empty blocks, with the special
//     index d in the last block ω_k (canonical form; 0-based like GUDHI).
// With e_i the unit vectors and e_d := −(1, …, 1), the vertices are v_j = y + e(ω_0) + … + e(ω_{j−1}).
// Since d is in the last block, v_j = y + Σ_{i<d, block(i)<j} e_i: the vertex chain is componentwise
// increasing and every coordinate is y_i or y_i + 1.
//
// Encoding: the partition is stored as the map block[i] ∈ {0..k} for each i ∈ {0..d}. This form is
// canonical by construction (no sorting of blocks ever), and gives vertex coordinates in O(1):
//   v_j[i] = y[i] + (block[i] < j).
// Unused entries (index ≥ d for y, > d for block) are kept zero, so == is a plain member comparison.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <iosfwd>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "coxmesh/errors.h"

namespace coxmesh {

/// Largest supported ambient dimension: d+1 block labels fit in one 32-bit mask.
inline constexpr int kMaxDimension = 31;

/// Throws InputError unless 1 ≤ d ≤ kMaxDimension.
void check_dimension(int d);

/// Lattice coordinates are checked to stay within ±kMaxLatticeCoordinate, so that vertex, face and
/// coface arithmetic (which moves coordinates by ±1) can never overflow int32.
inline constexpr std::int32_t kMaxLatticeCoordinate = (1 << 30);

struct Simplex {
  std::array<std::int32_t, kMaxDimension> y{};          ///< minimal vertex, entries [0, d)
  std::array<std::uint8_t, kMaxDimension + 1> block{};  ///< block of each index, entries [0, d]
  std::uint8_t d = 0;                                   ///< ambient dimension
  std::uint8_t k = 0;                                   ///< simplex dimension (number of blocks − 1)

  int ambient_dimension() const { return d; }
  int dimension() const { return k; }

  /// Lattice coordinate i of vertex j (0 ≤ j ≤ k, 0 ≤ i < d).
  std::int32_t vertex_coordinate(int j, int i) const { return y[i] + (block[i] < j ? 1 : 0); }
  /// Writes the d lattice coordinates of vertex j.
  void vertex(int j, std::int32_t* out) const {
    for (int i = 0; i < d; ++i) out[i] = vertex_coordinate(j, i);
  }
  /// Number of elements of block j.
  int block_size(int j) const;
  /// The blocks as sorted lists (for printing and interchange).
  std::vector<std::vector<int>> partition() const;

  /// Builds a simplex from y and a list of blocks; throws InputError unless the blocks partition
  /// {0..d} and d is in the last block. Blocks need not be sorted.
  static Simplex from_partition(std::span<const std::int32_t> y, const std::vector<std::vector<int>>& blocks);
  /// The vertex y as a 0-simplex.
  static Simplex vertex_simplex(std::span<const std::int32_t> y);

  friend bool operator==(const Simplex&, const Simplex&) = default;
};

static_assert(std::is_trivially_copyable_v<Simplex>);

/// The zero simplex, defined out of line. Hot paths start a result with `Simplex s = kBlankSimplex;`:
/// copying an opaque constant takes ten vector moves, where zeroing a value-initialised Simplex
/// compiles to a `rep stos` that is slow to start for 160 bytes.
extern const Simplex kBlankSimplex;
static_assert(sizeof(Simplex) == 160, "y (31 int32) + block (32 bytes) + d + k, padded");

/// Total order: y lexicographically, then more blocks first (a face sorts after its cofaces, as in
/// GUDHI's Simplex_comparator), then the sorted blocks lexicographically.
bool operator<(const Simplex& a, const Simplex& b);

// ---- Packed form: the compact key stored in hash sets and output maps --------------------------
// d words for y, then the d+1 block labels as bytes, 4 per word. For d = 3 that is 16 bytes.
constexpr int packed_words(int d) { return d + (d + 1 + 3) / 4; }
// (inline, as the other helpers of the walk's and the cell complex's loops: called per cofacet)
// kD ≠ 0: s.d = kD fixed at compile time, so that the loops unroll (the walk's per-cofacet keys).
template <int kD = 0>
inline void pack(const Simplex& s, std::uint32_t* out) {
  const int d = kD != 0 ? kD : s.d;
  for (int i = 0; i < d; ++i) out[i] = static_cast<std::uint32_t>(s.y[i]);
  std::uint32_t* labels = out + d;
  const int nwords = (d + 1 + 3) / 4;
  for (int w = 0; w < nwords; ++w) {
    std::uint32_t word;
    std::memcpy(&word, s.block.data() + 4 * w, 4);  // unused labels are zero, so this is canonical
    labels[w] = word;
  }
}
inline Simplex unpack(const std::uint32_t* words, int d) {
  Simplex s = kBlankSimplex;
  s.d = static_cast<std::uint8_t>(d);
  for (int i = 0; i < d; ++i) s.y[i] = static_cast<std::int32_t>(words[i]);
  std::memcpy(s.block.data(), words + d, 4 * ((d + 1 + 3) / 4));
  s.k = s.block[d];
  return s;
}
/// Whether `words` is the packed form of a simplex of dimension k in R^d, as pack() writes it: the
/// block labels of 0..d use each of 0..k, d's is k (the last block), the label bytes after d are
/// zero, and every coordinate is within ±kMaxLatticeCoordinate. O(d), on the words (no unpack), for
/// keys read from a file.
bool is_packed_simplex(const std::uint32_t* words, int d, int k);

/// Strong 64-bit hash of packed words, in two steps: a sum of the words times odd constants, one
/// per position (hash_sum), then an avalanche of the sum (hash_finish). The sum is linear in each
/// word, so a key that differs from the last one in a word or two is hashed in O(1)
/// (hash_sum_update: the cofacet walk of the cell complex changes one or two words per cofacet);
/// the avalanche makes every bit of the result, the table's tag above all, depend on every bit of
/// every word (tests/lattice/test_simplex.cpp).
namespace hash_detail {
constexpr std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
inline constexpr auto kWordFactors = [] {
  std::array<std::uint64_t, 64> f{};
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = splitmix(i) | 1;
  return f;
}();
static_assert(packed_words(kMaxDimension) <= 64);
}  // namespace hash_detail
inline std::uint64_t hash_sum(const std::uint32_t* w, int n) {
  std::uint64_t sum = static_cast<std::uint64_t>(n) * 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < n; ++i) sum += w[i] * hash_detail::kWordFactors[i];
  return sum;
}
/// The sum after word i changed from `from` to `to`.
inline std::uint64_t hash_sum_update(std::uint64_t sum, int i, std::uint32_t from, std::uint32_t to) {
  return sum + (std::uint64_t{to} - from) * hash_detail::kWordFactors[i];
}
inline std::uint64_t hash_finish(std::uint64_t sum) {
  sum ^= sum >> 32;
  sum *= 0xBF58476D1CE4E5B9ull;
  sum ^= sum >> 29;
  sum *= 0xFF51AFD7ED558CCDull;
  sum ^= sum >> 32;
  return sum;
}
inline std::uint64_t hash_words(const std::uint32_t* w, int n) { return hash_finish(hash_sum(w, n)); }

/// Hash of the whole simplex (vertex and partition); equal simplices hash equal.
std::uint64_t hash_value(const Simplex& s);

struct SimplexHash {
  std::size_t operator()(const Simplex& s) const { return static_cast<std::size_t>(hash_value(s)); }
};

// ---- Text form: "(y_0,...,y_{d-1}) [{..},{..},...]" --------------------------------------------
std::string to_string(const Simplex& s);
std::ostream& operator<<(std::ostream& os, const Simplex& s);
/// Parses the text form; throws InputError (with the reason) on malformed text, unsorted or
/// overlapping blocks, missing indices, d not in the last block, coordinates out of range.
Simplex parse_simplex(std::string_view text);

/// Throws InputError if a coordinate of y is outside ±kMaxLatticeCoordinate.
void check_lattice_range(std::span<const std::int32_t> y);

}  // namespace coxmesh
