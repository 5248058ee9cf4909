// Thesis §3.5: cofaces by splitting blocks, then re-canonicalising.
#include "coxmesh/lattice/cofaces.h"

#include <bit>
#include <cstddef>
#include <cstring>
#include <string>

namespace coxmesh {

namespace {
// Simplices are copied in the 16-byte pieces gray_step() uses (see there).
using Piece = std::uint32_t __attribute__((vector_size(16)));
static_assert(sizeof(Simplex) % sizeof(Piece) == 0 && offsetof(Simplex, y) == 0);
void copy_pieces(Simplex& dst, const Simplex& src) {
  for (std::size_t p = 0; p < sizeof(Simplex); p += sizeof(Piece)) {
    Piece v;
    std::memcpy(&v, reinterpret_cast<const unsigned char*>(&src) + p, sizeof(Piece));
    std::memcpy(reinterpret_cast<unsigned char*>(&dst) + p, &v, sizeof(Piece));
  }
}
}  // namespace

void CofaceEnumerator::reset(const Simplex& tau, int l) {
  if (l < tau.k || l > tau.d)
    throw InputError("coface dimension " + std::to_string(l) + " is outside " + std::to_string(tau.k) + ".." +
                     std::to_string(tau.d));
  tau_ = tau;
  l_ = l;
  const int k = tau.k, d = tau.d;
  // Bucket the elements by block (counting sort keeps each block increasing).
  std::array<int, kN + 1> fill;
  for (int b = 0; b <= k + 1; ++b) start_[b] = 0;
  for (int i = 0; i <= d; ++i) ++start_[tau.block[i] + 1];
  for (int b = 0; b <= k; ++b) fill[b] = start_[b], start_[b + 1] += start_[b];
  for (int i = 0; i <= d; ++i) elems_[fill[tau.block[i]]++] = static_cast<std::uint8_t>(i);
  started_ = false;
  done_ = false;
  step_ = steps_ = 0;
  split_ = k + 1;
  half_ = 1;
}

// The next half of a block split, for the blocks b = k, k−1, …, 0 with at least two elements. With
// t the block's last element (d for b = k) and S ≠ ∅ the elements on the other side:
//   * half 0, t after S: the block's labels become b (S) and b + 1, the later blocks' rise by one;
//   * half 1, b < k, t before S: b and b + 1 (S), the later blocks' rise by one;
//   * half 1, b = k, d before S: S comes first after the rotation (label 0, y − 1), every other
//     label rises by one.
// That is: labels g ≥ θ rise by one, S gets label θ; θ = b, b + 1 and 0 respectively.
bool CofaceEnumerator::start_split() {
  const int k = tau_.k, d = tau_.d;
  if (half_ == 0) {
    half_ = 1;
  } else {
    do --split_;
    while (split_ >= 0 && start_[split_ + 1] - start_[split_] < 2);
    if (split_ < 0) {
      done_ = true;
      return false;
    }
    half_ = 0;
  }
  const int b = split_, n = start_[b + 1] - start_[b];
  const int theta = half_ == 0 ? b : b < k ? b + 1 : 0;
  first_ = start_[b];
  steps_ = (std::uint32_t{1} << (n - 1)) - 1;
  step_ = 0;
  label_toggle_ = static_cast<std::uint8_t>(theta ^ (b + (b >= theta)));
  y_toggle_ = theta == 0 && half_ == 1 ? ~0u : 0u;
  cur_ = tau_;
  cur_.k = static_cast<std::uint8_t>(k + 1);
  for (int i = 0; i <= d; ++i) cur_.block[i] = static_cast<std::uint8_t>(tau_.block[i] + (tau_.block[i] >= theta));
  return true;
}

// Cut vectors (c_0..c_k), 0 ≤ c_b < n_b, Σ c_b = l − k, in lexicographic order. The smallest one
// puts every cut as far back as possible.
bool CofaceEnumerator::first_composition() {
  int rest = l_ - tau_.k;
  for (int b = tau_.k; b >= 0; --b) {
    const int cap = start_[b + 1] - start_[b] - 1;
    cuts_[b] = rest < cap ? rest : cap;
    rest -= cuts_[b];
  }
  return rest == 0;
}

bool CofaceEnumerator::next_composition() {
  int suffix = 0;
  for (int b = tau_.k; b >= 0; --b) {
    if (b < tau_.k && suffix >= 1 && cuts_[b] < start_[b + 1] - start_[b] - 1) {
      ++cuts_[b];
      int rest = suffix - 1;
      for (int g = tau_.k; g > b; --g) {
        const int cap = start_[g + 1] - start_[g] - 1;
        cuts_[g] = rest < cap ? rest : cap;
        rest -= cuts_[g];
      }
      return true;
    }
    suffix += cuts_[b];
  }
  return false;
}

// Ordered partitions of block b into cuts_[b]+1 sub-blocks, as surjective label sequences (over
// the block's elements in increasing order) in lexicographic order. The labels' use counts live in
// count_[b].
void CofaceEnumerator::first_split(int b) {
  const int n = start_[b + 1] - start_[b], c = cuts_[b];
  const std::uint8_t* el = elems_.data() + start_[b];
  auto& cnt = count_[b];
  for (int p = 0; p < n; ++p) label_[el[p]] = static_cast<std::uint8_t>(p < n - c ? 0 : p - (n - c) + 1);
  cnt[0] = static_cast<std::uint8_t>(n - c);
  for (int v = 1; v <= c; ++v) cnt[v] = 1;
}

// A new cut vector: first splits of every block, and the label offsets of the blocks.
void CofaceEnumerator::start_composition() {
  const int k = tau_.k;
  int offset = 0;
  for (int b = 0; b <= k; ++b) {
    first_split(b);
    for (int p = start_[b]; p < start_[b + 1]; ++p) base_[elems_[p]] = static_cast<std::uint8_t>(offset);
    offset += cuts_[b] + 1;
  }
}

bool CofaceEnumerator::next_split(int b) {
  const int c = cuts_[b];
  if (c == 0) return false;  // one sub-block: a single split (all labels 0, never modified)
  const int n = start_[b + 1] - start_[b];
  const std::uint8_t* el = elems_.data() + start_[b];
  std::uint8_t* lab = label_.data();
  auto& cnt = count_[b];
  if (c == 1) {
    // Two sub-blocks: binary counting, which is lexicographic order; every
    // sequence is surjective except all ones (all zeros cannot follow 0…01). Amortised O(1).
    int ones = cnt[1], pos = n - 1;
    while (lab[el[pos]] == 1) {  // stops: a surjective sequence has a 0
      lab[el[pos--]] = 0;
      --ones;
    }
    lab[el[pos]] = 1;
    ++ones;
    cnt[1] = static_cast<std::uint8_t>(ones);
    cnt[0] = static_cast<std::uint8_t>(n - ones);
    return ones < n;
  }
  int uncovered = 0;  // the current sequence is surjective
  for (int pos = n - 1; pos >= 0; --pos) {
    if (--cnt[lab[el[pos]]] == 0) ++uncovered;
    for (int v = lab[el[pos]] + 1; v <= c; ++v) {
      if (cnt[v]++ == 0) --uncovered;
      if (uncovered <= n - 1 - pos) {
        lab[el[pos]] = static_cast<std::uint8_t>(v);
        // Smallest completion: label 0 while there is room, else the smallest unused label.
        for (int q = pos + 1; q < n; ++q) {
          int w = 0;
          if (uncovered >= n - q)
            while (cnt[w] != 0) ++w;
          lab[el[q]] = static_cast<std::uint8_t>(w);
          if (cnt[w]++ == 0) --uncovered;
        }
        return true;
      }
      if (--cnt[v] == 0) ++uncovered;
    }
  }
  return false;
}

// Writes the coface for the current cuts and splits. Element i gets the label base_i + λ_i (its
// block's sub-blocks are base_b .. base_b + c_b; the last block's base is l − c_k). Rotating d's
// sub-block (label l − c_k + λ_d) to the end adds s = c_k − λ_d to every label, except for the
// sub-blocks after d's in the last block (λ > λ_d), which come first (λ − λ_d − 1) and lower the
// base vertex by their indicator. One branch-free pass over the elements; τ's zero tails are
// copied with it.
void CofaceEnumerator::build(Simplex& out) const {
  const int k = tau_.k, d = tau_.d;
  out = tau_;
  out.k = static_cast<std::uint8_t>(l_);
  const int lambda_d = label_[d], shift = cuts_[k] - lambda_d;
  for (int i = 0; i < d; ++i) {
    const int lambda = label_[i];
    const int before = (tau_.block[i] == k) & (lambda > lambda_d);
    const int rotated = base_[i] + lambda + shift;
    out.block[i] = static_cast<std::uint8_t>(before ? lambda - lambda_d - 1 : rotated);
    out.y[i] = tau_.y[i] - before;
  }
  out.block[d] = static_cast<std::uint8_t>(l_);
}

// The current split is exhausted: the next one, or the general walk for l > k + 1.
const Simplex* CofaceEnumerator::next_block_or_general() {
  if (done_) return nullptr;
  if (l_ != tau_.k + 1) return next_general() ? &cur_ : nullptr;
  if (!start_split()) return nullptr;
  gray_step();
  return &cur_;
}

bool CofaceEnumerator::next(Simplex& out) {
  const Simplex* mu = next();
  if (mu) copy_pieces(out, *mu);
  return mu != nullptr;
}

// Other l: the general walk over cut vectors and splits writes each coface into cur_.
bool CofaceEnumerator::next_general() {
  const int k = tau_.k;
  if (!started_) {
    started_ = true;
    first_composition();
    start_composition();
    build(cur_);
    return true;
  }
  for (int b = k; b >= 0; --b) {
    if (cuts_[b] != 0 && next_split(b)) {
      // Blocks without a cut keep their single split (all labels 0) and need no reset.
      for (int g = b + 1; g <= k; ++g)
        if (cuts_[g] != 0) first_split(g);
      build(cur_);
      return true;
    }
  }
  if (next_composition()) {
    start_composition();
    build(cur_);
    return true;
  }
  done_ = true;
  return false;
}

namespace {
// Saturating arithmetic: table entries and partial sums that do not fit (e.g. a(21, 21) = 21! for
// d = 20) are marked, and only throw if the requested count actually uses them.
constexpr std::uint64_t kSaturated = ~std::uint64_t{0};
std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  return a == kSaturated || b == kSaturated || __builtin_mul_overflow(a, b, &r) ? kSaturated : r;
}
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  return a == kSaturated || b == kSaturated || __builtin_add_overflow(a, b, &r) ? kSaturated : r;
}
}  // namespace

std::uint64_t coface_count(const Simplex& tau, int l) {
  const int d = tau.d, k = tau.k;
  if (l < k || l > d) return 0;
  // a[n][j] = j!·S(n, j), the number of ordered partitions of n elements into j blocks,
  // by a(n, j) = j·(a(n−1, j−1) + a(n−1, j)).
  std::array<std::array<std::uint64_t, kMaxDimension + 2>, kMaxDimension + 2> a{};
  a[0][0] = 1;
  for (int n = 1; n <= d + 1; ++n)
    for (int j = 1; j <= n; ++j) a[n][j] = saturating_mul(j, saturating_add(a[n - 1][j - 1], a[n - 1][j]));
  // Knapsack over blocks: ways[s] = number of ways to place s cuts in the blocks seen so far.
  std::array<std::uint64_t, kMaxDimension + 2> ways{}, next{};
  ways[0] = 1;
  for (int b = 0; b <= k; ++b) {
    const int n = tau.block_size(b);
    next.fill(0);
    for (int s = 0; s <= l - k; ++s)
      if (ways[s])
        for (int c = 0; c <= n - 1 && s + c <= l - k; ++c)
          next[s + c] = saturating_add(next[s + c], saturating_mul(ways[s], a[n][c + 1]));
    ways = next;
  }
  // Saturation propagates, so only a count that really needs a too large term is rejected.
  if (ways[l - k] == kSaturated) throw InputError("coface count overflows 64 bits");
  return ways[l - k];
}

}  // namespace coxmesh
