// Thesis §3.5 (cofaces of a permutahedral simplex).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// Enumerates the l-cofaces of a k-simplex τ (k ≤ l ≤ d), each exactly once (thesis §3.5):
/// every block ω_i is cut into c_i + 1 ordered sub-blocks with Σ c_i = l − k, then the result is
/// rotated so that d is in the last block again (the sub-blocks after d's move to the front and the
/// base vertex drops by their indicator). No allocation. The order is deterministic but otherwise
/// unspecified.
///
/// Cofacets (l = k + 1, the tracer's case) split one block in two and are walked in Gray-code
/// order, so consecutive cofacets differ in one index: O(1) work per cofacet.
/// Other l: constant work per coface beyond O(d) to write it out.
///
///   CofaceEnumerator cofacets(tau, tau.dimension() + 1);
///   while (const Simplex* mu = cofacets.next()) use(*mu);
class CofaceEnumerator {
 public:
  CofaceEnumerator() = default;
  CofaceEnumerator(const Simplex& tau, int l) { reset(tau, l); }
  /// Throws InputError unless dim τ ≤ l ≤ d.
  void reset(const Simplex& tau, int l);
  /// The next coface, or nullptr after the last: a view of the enumerator's own copy, valid until
  /// the next call (no copy; like dereferencing an iterator).
  const Simplex* next() {
    if (step_ == steps_) return next_block_or_general();
    gray_step();
    return &cur_;
  }
  /// Copies the next coface into `out`; false after the last.
  bool next(Simplex& out);

 private:
  const Simplex* next_block_or_general();
  void gray_step();
  bool start_split();
  bool next_general();
  bool first_composition();
  bool next_composition();
  void start_composition();
  void first_split(int b);
  bool next_split(int b);
  void build(Simplex& out) const;

  static constexpr int kN = kMaxDimension + 1;
  Simplex tau_;
  int l_ = 0;
  bool started_ = false, done_ = true;
  // Elements of τ's blocks, grouped by block: elems_[start_[b] .. start_[b+1]).
  // (The arrays below are written by reset() and the walks before they are read, and left
  // uninitialised here: an enumerator per simplex must be cheap to construct.)
  std::array<std::uint8_t, kN> elems_;
  std::array<int, kN + 1> start_;

  // Cofacets: block split_ is cut into two sub-blocks; its last element t stays on one side
  // (half_ = 0: the second sub-block, 1: the first) while the set S of the others on the far side
  // runs through the non-empty subsets of the block's first n − 1 elements in Gray-code order (step
  // step_ of steps_ = 2^(n−1) − 1). cur_ is the current coface (of either walk); an element entering or leaving
  // S has its label XORed with label_toggle_ and, after a rotation (y_toggle_ ≠ 0), its y toggled
  // between y and y − 1.
  Simplex cur_;
  std::uint32_t step_ = 0, steps_ = 0, y_toggle_ = 0;
  int split_ = 0, half_ = 0, first_ = 0;
  std::uint8_t label_toggle_ = 0;

  // Other l: cuts_[b] = c_b; label_[i] = sub-block (0..c_b) of element i within its block; base_[i]
  // = first coface label of i's block (Σ_{g<b} (c_g + 1)); count_[b] = uses per label in block b.
  std::array<int, kN> cuts_;
  std::array<std::uint8_t, kN> label_;
  std::array<std::uint8_t, kN> base_;
  std::array<std::array<std::uint8_t, kN>, kN> count_;  // rows 0..k set by first_split (1 KB)
};

// Gray code: one element of the split block crosses to the other sub-block, which toggles its label
// (and, after a rotation, its y) between two values. cur_ is only read and written in the same
// 16-byte pieces, so that every load of it is served by a single earlier store (store-to-load
// forwarding): a narrow store followed by a wider load of the same bytes would stall until the
// store reaches the cache, on every cofacet.
inline void CofaceEnumerator::gray_step() {
  using Piece = std::uint32_t __attribute__((vector_size(16)));
  static constexpr Piece kLane[4] = {{~0u, 0, 0, 0}, {0, ~0u, 0, 0}, {0, 0, ~0u, 0}, {0, 0, 0, ~0u}};
  auto xor_word = [this](int w, std::uint32_t v) {  // cur_'s 4-byte word w ^= v
    unsigned char* p = reinterpret_cast<unsigned char*>(&cur_) + 16 * (w >> 2);
    Piece piece;
    std::memcpy(&piece, p, 16);
    piece ^= Piece{v, v, v, v} & kLane[w & 3];
    std::memcpy(p, &piece, 16);
  };
  const int i = elems_[first_ + std::countr_zero(++step_)];
  const std::uint32_t y = static_cast<std::uint32_t>(tau_.y[i]);
  if (y_toggle_) xor_word(i, y ^ (y - 1));  // only after a rotation; the same in a whole half
  const int byte = static_cast<int>(offsetof(Simplex, block)) + i;
  xor_word(byte >> 2, std::uint32_t{label_toggle_} << 8 * (byte & 3));
}

/// The cofacets of the simplex with packed key `key` (packed_words(d) words, simplex.h), as packed
/// keys, in the order of CofaceEnumerator(unpack(key, d), k + 1): for_each(emit) calls
/// emit(const std::uint32_t* cofacet, std::uint64_t hash) with a view of a working key, valid
/// during the call, and its hash_words. The same block splits in Gray-code order (thesis §3.5),
/// written straight into the packed form: one label byte (and, after a rotation, one y word)
/// changes per cofacet, with no Simplex to copy or pack, and the hash follows those words in O(1)
/// (hash_sum_update). For the cell complex, whose levels are cofacets of the level below (thesis
/// §4.2). The blocks are read once, in one pass over the labels, for count() and for_each() both.
/// kD ≠ 0 fixes d = kD at compile time (with_fixed_dimension, util/fixed_dimension.h), so that the loops over d and the
/// key's words unroll; kD = 0 reads d at run time.
template <int kD = 0>
class PackedCofacets {
 public:
  PackedCofacets(const std::uint32_t* key, int d) : key_(key), d_(kD != 0 ? kD : d), k_(label(dimension())) {
    // Every block 0..k has an element: zeroed by a pass over them (a loop over the blocks would
    // compile to a `rep stos`, slow to start for a few words).
    d = dimension();
    for (int i = 0; i <= d; ++i) members_[label(i)] = 0;
    for (int i = 0; i <= d; ++i) members_[label(i)] |= std::uint32_t{1} << i;
  }
  /// Σ 2^n − 2 over the blocks of n elements (a block splits into two ordered non-empty parts).
  std::size_t count() const {
    std::size_t count = 0;
    for (int b = 0; b <= k_; ++b) count += (std::size_t{1} << bit_count(members_[b])) - 2;
    return count;
  }
  template <class Emit>
  void for_each(Emit&& emit) const;

 private:
  int dimension() const { return kD != 0 ? kD : d_; }
  int label(int i) const { return static_cast<int>((key_[dimension() + (i >> 2)] >> 8 * (i & 3)) & 0xFFu); }
  // (std::popcount is a library call on baseline x86-64)
  static int bit_count(std::uint32_t x) {
    x -= (x >> 1) & 0x55555555u;
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    return static_cast<int>((((x + (x >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24);
  }

  const std::uint32_t* key_;
  int d_, k_;
  std::uint32_t members_[kMaxDimension + 1];  // per block, its elements as a bit set
};

template <int kD>
template <class Emit>
void PackedCofacets<kD>::for_each(Emit&& emit) const {
  const std::uint32_t* const key = key_;
  const int d = dimension(), k = k_, label_words = (d + 1 + 3) / 4;
  const std::uint32_t* labels = key + d;
  std::uint32_t cur[packed_words(kMaxDimension)];
  for (int i = 0; i < d + label_words; ++i) cur[i] = key[i];
  std::uint64_t sum = hash_sum(cur, d + label_words);  // of cur, kept with every word written
  const auto set = [&](int i, std::uint32_t word) {
    sum = hash_sum_update(sum, i, cur[i], word);
    cur[i] = word;
  };
  for (int b = k; b >= 0; --b) {
    std::uint8_t moving[kMaxDimension + 1];  // the block's elements but its last, increasing
    int n = 1;
    for (std::uint32_t rest = members_[b]; rest & (rest - 1); rest &= rest - 1)
      moving[n++ - 1] = static_cast<std::uint8_t>(std::countr_zero(rest));
    if (n < 2) continue;
    for (int half = 0; half < 2; ++half) {
      // As CofaceEnumerator::start_split: labels ≥ θ rise by one, the moving set gets label θ.
      const int theta = half == 0 ? b : b < k ? b + 1 : 0;
      const std::uint32_t toggle = static_cast<std::uint32_t>(theta ^ (b + (b >= theta)));
      const bool rotated = theta == 0 && half == 1;
      // Four labels (≤ 31) at a time: a byte ≥ θ gets its high bit from byte + 128 − θ; the zero
      // bytes after label d stay zero.
      const std::uint32_t below_theta = 0x01010101u * static_cast<std::uint32_t>(0x80 - theta);
      for (int w = 0; w < label_words; ++w) {
        const int used = std::min(4, d + 1 - 4 * w);
        const std::uint32_t in_use = used == 4 ? ~0u : (std::uint32_t{1} << 8 * used) - 1;
        set(d + w, labels[w] + ((((labels[w] + below_theta) & 0x80808080u) >> 7) & in_use));
      }
      const std::uint32_t steps = (std::uint32_t{1} << (n - 1)) - 1;
      for (std::uint32_t step = 1; step <= steps; ++step) {
        const int i = moving[std::countr_zero(step)];
        set(d + (i >> 2), cur[d + (i >> 2)] ^ toggle << 8 * (i & 3));
        if (rotated) set(i, cur[i] ^ key[i] ^ (key[i] - 1));  // y_i ↔ y_i − 1
        emit(static_cast<const std::uint32_t*>(cur), hash_finish(sum));
      }
      if (rotated)  // (y back for the blocks after)
        for (int j = 0; j + 1 < n; ++j) set(moving[j], key[moving[j]]);
    }
  }
}

/// The vertex that each cofacet of τ adds to τ's vertices, once per cofacet (thesis §3.5), in an
/// unspecified order: emit(const std::int32_t* v) with a view of d coordinates, valid during the
/// call. A cofacet splits a block ω_b of τ into a non-empty part A put first and the rest; its new
/// vertex is v_b + e(A) (e_d = −(1, …, 1)). The parts A of each block are taken in Gray-code order,
/// so one coordinate (all of them for d) changes per vertex: no cofacet is built. For the vertices
/// a walk will read around τ (the distributed walk fetches their values before a level).
template <class Emit>
void for_each_cofacet_vertex(const Simplex& tau, Emit&& emit) {
  const int d = tau.d, k = tau.k;
  std::uint32_t members[kMaxDimension + 1];  // per block, its elements as a bit set
  for (int b = 0; b <= k; ++b) members[b] = 0;
  for (int i = 0; i <= d; ++i) members[tau.block[i]] |= std::uint32_t{1} << i;
  std::int32_t v[kMaxDimension];
  for (int b = 0; b <= k; ++b) {
    std::uint8_t element[kMaxDimension + 1];
    int n = 0;
    for (std::uint32_t rest = members[b]; rest != 0; rest &= rest - 1)
      element[n++] = static_cast<std::uint8_t>(std::countr_zero(rest));
    if (n < 2) continue;
    tau.vertex(b, v);
    const auto move = [&](int i, std::int32_t step) {  // v += step · e_i
      if (i < d)
        v[i] += step;
      else
        for (int c = 0; c < d; ++c) v[c] -= step;
    };
    // Step s puts in or takes out element ctz(s): the parts are the Gray codes s ^ (s >> 1), every
    // non-empty subset once; the whole block (no cofacet) is skipped.
    const std::uint64_t all = (std::uint64_t{1} << n) - 1;
    std::uint64_t part = 0;
    for (std::uint64_t step = 1; step <= all; ++step) {
      const int t = std::countr_zero(step);
      move(element[t], (part >> t & 1) ? -1 : 1);
      part ^= std::uint64_t{1} << t;
      if (part != all) emit(static_cast<const std::int32_t*>(v));
    }
  }
}

/// The place of μ among the cofacets of its facet τ = μ without its vertex j, in the order of
/// CofaceEnumerator(τ, k + 1): the inverse of that enumeration (thesis §3.5). τ joins two
/// consecutive blocks of μ into its block ω_b, the first of them being the part A that μ puts first
/// (for j = 0, μ's last block, with d, then its block 0). ω_b's last element t gives the half (t ∉ A:
/// half 0, S = A; t ∈ A: half 1, S = ω_b ∖ A), and S, a Gray code over ω_b's other elements, the
/// step. O(d), nothing enumerated. For a walk that meets μ from one transverse facet and would meet
/// it again from the other (tracing/walk_sequential). kD as facet_without (faces.h).
template <int kD = 0>
std::uint64_t place_among_facet_cofacets(const Simplex& mu, int j) {
  const int d = kD != 0 ? kD : mu.d, top = mu.k;
  const int first = j == 0 ? top : j - 1, second = j == 0 ? 0 : j;  // μ's blocks that τ joins
  std::uint8_t size[kMaxDimension + 2];
  // (zeroed by a pass over the elements, as every block has one: a loop over the blocks compiles to
  // a `rep stos`, slow to start for a few bytes)
  for (int i = 0; i <= d; ++i) size[mu.block[i]] = 0;
  std::uint32_t a = 0, rest = 0;  // A, and ω_b ∖ A
  for (int i = 0; i <= d; ++i) {
    const int g = mu.block[i];
    ++size[g];
    a |= std::uint32_t{g == first} << i;
    rest |= std::uint32_t{g == second} << i;
  }
  std::uint64_t place = 0;  // the cofacets of τ's blocks after ω_b: μ's blocks after `second` (none for j = 0)
  for (int g = j == 0 ? top + 1 : j + 1; g <= top; ++g) place += (std::uint64_t{1} << size[g]) - 2;
  const std::uint32_t block = a | rest;
  const int t = 31 - std::countl_zero(block), n = size[first] + size[second];
  const bool half = (a >> t & 1) != 0;
  const std::uint32_t s = half ? rest : a;
  std::uint32_t gray = 0;  // S over ω_b's first n − 1 elements, increasing
  int bit = 0;
  for (std::uint32_t e = block & ~(std::uint32_t{1} << t); e != 0; e &= e - 1, ++bit)
    gray |= ((s >> std::countr_zero(e)) & 1) << bit;
  std::uint32_t step = gray;  // the step whose Gray code is S
  for (int shift = 1; shift < 32; shift <<= 1) step ^= step >> shift;
  return place + (half ? (std::uint64_t{1} << (n - 1)) - 1 : 0) + step - 1;
}

/// Number of l-cofaces of τ (thesis §3.5): Σ over cut vectors of Π_i a(n_i, c_i + 1), where
/// a(n, j) = j!·S(n, j) counts ordered partitions. Throws InputError only if the count, or a term
/// it needs, exceeds 64 bits (e.g. the 21! maximal cofaces of a vertex in d = 20); cofacet counts
/// are exact for every d ≤ kMaxDimension.
std::uint64_t coface_count(const Simplex& tau, int l);

}  // namespace coxmesh
