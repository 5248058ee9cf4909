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
  for (int v = 0; v <= c; ++v) cnt[v] = 0;
  for (int p = 0; p < n; ++p) {
    lab[p] = static_cast<std::uint8_t>(p < n - c ? 0 : p - (n - c) + 1);
    ++cnt[lab[p]];
  }
}

bool CofaceEnumerator::next_split(int b) {
  const int n = start_[b + 1] - start_[b], c = cuts_[b];
  std::uint8_t* lab = label_.data() + start_[b];
  auto& cnt = count_[b];
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

void CofaceEnumerator::build(Simplex& out) const {
  const int k = tau_.k, d = tau_.d;
  out.d = tau_.d;
  out.k = static_cast<std::uint8_t>(l_);
  int offset = 0;
  for (int b = 0; b <= k; ++b) {
    for (int p = start_[b]; p < start_[b + 1]; ++p)
      out.block[elems_[p]] = static_cast<std::uint8_t>(offset + label_[p]);
    offset += cuts_[b] + 1;
  }
  // Rotate so that d's sub-block u is last: the sub-blocks after u come first, and the base vertex
  // drops by their indicator (they precede y in the cyclic vertex order).
  const int u = out.block[d];
  for (int i = 0; i < d; ++i) {
    const int nb = out.block[i];
    out.y[i] = tau_.y[i] - (nb > u ? 1 : 0);
    out.block[i] = static_cast<std::uint8_t>(nb > u ? nb - u - 1 : nb + l_ - u);
  }
  out.block[d] = static_cast<std::uint8_t>(l_);
  for (int i = d; i < kMaxDimension; ++i) out.y[i] = 0;
  for (int i = d + 1; i <= kMaxDimension; ++i) out.block[i] = 0;
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
    if (next_split(b)) {
      for (int g = b + 1; g <= k; ++g) first_split(g);
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
}  // namespace

std::uint64_t coface_count(const Simplex& tau, int l) {
  const int d = tau.d, k = tau.k;
  if (l < k || l > d) return 0;
  // a[n][j] = j!·S(n, j), the number of ordered partitions of n elements into j blocks,
  // by a(n, j) = j·(a(n−1, j−1) + a(n−1, j)).
  std::array<std::array<std::uint64_t, kMaxDimension + 2>, kMaxDimension + 2> a{};
  a[0][0] = 1;
  for (int n = 1; n <= d + 1; ++n)
    for (int j = 1; j <= n; ++j) a[n][j] = checked_mul(j, checked_add(a[n - 1][j - 1], a[n - 1][j]));
  // Knapsack over blocks: ways[s] = number of ways to place s cuts in the blocks seen so far.
  std::array<std::uint64_t, kMaxDimension + 2> ways{}, next{};
  ways[0] = 1;
  for (int b = 0; b <= k; ++b) {
    const int n = tau.block_size(b);
    next.fill(0);
    for (int s = 0; s <= l - k; ++s)
      if (ways[s])
        for (int c = 0; c <= n - 1 && s + c <= l - k; ++c)
          next[s + c] = checked_add(next[s + c], checked_mul(ways[s], a[n][c + 1]));
    ways = next;
  }
  return ways[l - k];
}

}  // namespace coxmesh
