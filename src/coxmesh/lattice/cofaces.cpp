// Thesis §3; spec §1.5: cofaces by splitting blocks, then re-canonicalising.
#include "coxmesh/lattice/cofaces.h"

#include <string>

namespace coxmesh {

void CofaceEnumerator::reset(const Simplex& tau, int l) {
  if (l < tau.k || l > tau.d)
    throw InputError("coface dimension " + std::to_string(l) + " is outside " + std::to_string(tau.k) + ".." +
                     std::to_string(tau.d));
  tau_ = tau;
  l_ = l;
  const int k = tau.k, d = tau.d;
  // Bucket the elements by block (counting sort keeps each block increasing).
  start_.fill(0);
  for (int i = 0; i <= d; ++i) ++start_[tau.block[i] + 1];
  for (int b = 0; b <= k; ++b) start_[b + 1] += start_[b];
  std::array<int, kN + 1> fill = start_;
  for (int i = 0; i <= d; ++i) elems_[fill[tau.block[i]]++] = static_cast<std::uint8_t>(i);
  started_ = false;
  done_ = false;
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

// Ordered partitions of block b into cuts_[b]+1 sub-blocks, as surjective label sequences in
// lexicographic order. The labels' use counts live in count_[b].
void CofaceEnumerator::first_split(int b) {
  const int n = start_[b + 1] - start_[b], c = cuts_[b];
  std::uint8_t* lab = label_.data() + start_[b];
  auto& cnt = count_[b];
  // One pass (blocks are short: a memset call per block would cost more than the stores).
  for (int p = 0; p < n; ++p) lab[p] = static_cast<std::uint8_t>(p < n - c ? 0 : p - (n - c) + 1);
  cnt[0] = static_cast<std::uint8_t>(n - c);
  for (int v = 1; v <= c; ++v) cnt[v] = 1;
}

bool CofaceEnumerator::next_split(int b) {
  const int c = cuts_[b];
  if (c == 0) return false;  // one sub-block: a single split (all labels 0, never modified)
  const int n = start_[b + 1] - start_[b];
  std::uint8_t* lab = label_.data() + start_[b];
  auto& cnt = count_[b];
  if (c == 1) {
    // Two sub-blocks (every cofacet): binary counting, which is lexicographic order; every
    // sequence is surjective except all ones (all zeros cannot follow 0…01). Amortised O(1).
    int ones = cnt[1], pos = n - 1;
    while (lab[pos] == 1) {  // stops: a surjective sequence has a 0
      lab[pos--] = 0;
      --ones;
    }
    lab[pos] = 1;
    ++ones;
    cnt[1] = static_cast<std::uint8_t>(ones);
    cnt[0] = static_cast<std::uint8_t>(n - ones);
    return ones < n;
  }
  int uncovered = 0;  // the current sequence is surjective
  for (int pos = n - 1; pos >= 0; --pos) {
    if (--cnt[lab[pos]] == 0) ++uncovered;
    for (int v = lab[pos] + 1; v <= c; ++v) {
      if (cnt[v]++ == 0) --uncovered;
      if (uncovered <= n - 1 - pos) {
        lab[pos] = static_cast<std::uint8_t>(v);
        // Smallest completion: label 0 while there is room, else the smallest unused label.
        for (int q = pos + 1; q < n; ++q) {
          int w = 0;
          if (uncovered >= n - q)
            while (cnt[w] != 0) ++w;
          lab[q] = static_cast<std::uint8_t>(w);
          if (cnt[w]++ == 0) --uncovered;
        }
        return true;
      }
      if (--cnt[v] == 0) ++uncovered;
    }
  }
  return false;
}

// Writes the coface for the current cuts and splits. Block b's sub-blocks get the labels
// offset_b .. offset_b + c_b (offset_b = Σ_{g<b} (c_g + 1), so offset_k = l − c_k). Rotating d's
// sub-block (label offset_k + λ_d) to the end maps a label x to x + s with s = c_k − λ_d, except
// for the sub-blocks after d's in the last block (λ > λ_d), which come first (λ − λ_d − 1) and lower
// the base vertex by their indicator. Only the last block can contain those, so y changes there
// only. O(d), branch-light; τ's zero tails are copied with it.
void CofaceEnumerator::build(Simplex& out) const {
  const int k = tau_.k, d = tau_.d;
  out = tau_;
  out.k = static_cast<std::uint8_t>(l_);
  const int lambda_d = label_[d];  // d is the last element of the last block
  int offset = cuts_[k] - lambda_d;
  for (int b = 0; b < k; ++b) {
    for (int p = start_[b]; p < start_[b + 1]; ++p)
      out.block[elems_[p]] = static_cast<std::uint8_t>(offset + label_[p]);
    offset += cuts_[b] + 1;
  }
  for (int p = start_[k]; p < d; ++p) {  // the last block without d itself
    const int e = elems_[p], lambda = label_[p];
    const bool before = lambda > lambda_d;
    out.block[e] = static_cast<std::uint8_t>(before ? lambda - lambda_d - 1 : offset + lambda);
    out.y[e] -= before ? 1 : 0;
  }
  out.block[d] = static_cast<std::uint8_t>(l_);
}

bool CofaceEnumerator::next(Simplex& out) {
  if (done_) return false;
  const int k = tau_.k;
  if (!started_) {
    started_ = true;
    first_composition();
    for (int b = 0; b <= k; ++b) first_split(b);
    build(out);
    return true;
  }
  for (int b = k; b >= 0; --b) {
    if (cuts_[b] != 0 && next_split(b)) {
      // Blocks without a cut keep their single split (all labels 0) and need no reset.
      for (int g = b + 1; g <= k; ++g)
        if (cuts_[g] != 0) first_split(g);
      build(out);
      return true;
    }
  }
  if (next_composition()) {
    for (int b = 0; b <= k; ++b) first_split(b);
    build(out);
    return true;
  }
  done_ = true;
  return false;
}

namespace {
std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_mul_overflow(a, b, &r)) throw InputError("coface count overflows 64 bits");
  return r;
}
std::uint64_t checked_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_add_overflow(a, b, &r)) throw InputError("coface count overflows 64 bits");
  return r;
}
// Saturating arithmetic for the table of ordered partition counts: entries that do not fit (e.g.
// a(21, 21) = 21! for d = 20) are marked, and only throw if a count actually uses them.
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
        for (int c = 0; c <= n - 1 && s + c <= l - k; ++c) {
          if (a[n][c + 1] == kSaturated) throw InputError("coface count overflows 64 bits");
          next[s + c] = checked_add(next[s + c], checked_mul(ways[s], a[n][c + 1]));
        }
    ways = next;
  }
  return ways[l - k];
}

}  // namespace coxmesh
