// Thesis §3.5 (faces and the face test).
#include "coxmesh/lattice/faces.h"

#include <algorithm>
#include <bit>
#include <string>

namespace coxmesh {

Simplex face_from_indices(const Simplex& sigma, const int* indices, int k) {
  const int l = sigma.k, d = sigma.d;
  COXMESH_DEBUG_ASSERT(k >= 0 && k <= l && indices[0] >= 0 && indices[k] <= l);
  for (int h = 1; h <= k; ++h) COXMESH_PARANOID_ASSERT(indices[h - 1] < indices[h]);
  // New block of each old block b: blocks i_{h-1} ≤ b < i_h form block h−1; the rest wrap into k.
  std::array<std::uint8_t, kMaxDimension + 1> relabel;
  for (int b = 0; b <= l; ++b) relabel[b] = static_cast<std::uint8_t>(k);
  for (int h = 1; h <= k; ++h)
    for (int b = indices[h - 1]; b < indices[h]; ++b) relabel[b] = static_cast<std::uint8_t>(h - 1);
  Simplex f = kBlankSimplex;
  f.d = sigma.d;
  f.k = static_cast<std::uint8_t>(k);
  const int i0 = indices[0];
  for (int i = 0; i < d; ++i) f.y[i] = sigma.y[i] + (sigma.block[i] < i0 ? 1 : 0);
  for (int i = 0; i <= d; ++i) f.block[i] = relabel[sigma.block[i]];
  return f;
}

namespace {

// kD > 0: the loops over d unrolled for this d (the common small dimensions; `check` of T³ ⊂ R⁶,
// 17.5 M incidences, took 4 % less CPU); 0: any d.
template <int kD>
int facet_index(const std::uint32_t* tau, const std::uint32_t* sigma, int runtime_d) {
  const int d = kD > 0 ? kD : runtime_d;
  // Labels are bytes in memory order (pack() copies them so); four to a word, read a word at a time
  // below where every byte gets the same operation (labels ≤ 31: no carry crosses a byte).
  const auto* ls = reinterpret_cast<const unsigned char*>(sigma + d);
  const auto* lt = reinterpret_cast<const unsigned char*>(tau + d);
  const int l = ls[d], label_words = (d + 1 + 3) / 4;
  if (l < 1 || lt[d] != l - 1) return -1;
  bool same_base = true;
  for (int i = 0; i < d; ++i) same_base &= tau[i] == sigma[i];
  bool same = true;
  if (!same_base) {
    // Only facet_without(σ, 0) moves the base, to v_1 = y + e(ω_0); block 0 joins the last block
    // (label l − 1) and the other labels drop by one. The label bytes after d stay zero.
    for (int i = 0; i < d; ++i) same &= tau[i] == sigma[i] + (ls[i] == 0 ? 1u : 0u);
    for (int w = 0; w < label_words; ++w) {
      const int used = std::min(4, d + 1 - 4 * w);
      const std::uint32_t ones = 0x01010101u & (used == 4 ? ~0u : (std::uint32_t{1} << 8 * used) - 1);
      const std::uint32_t zero = ((0x80808080u - sigma[d + w]) & 0x80808080u) >> 7 & ones;  // 1 in each 0 label
      same &= tau[d + w] == sigma[d + w] + zero * static_cast<std::uint32_t>(l) - ones;
    }
    return same ? 0 : -1;
  }
  // facet_without(σ, j), j ≥ 1, merges blocks j − 1 and j: exactly the labels ≥ j drop by one, so j
  // is the smallest label of σ that changed (d's always does).
  std::uint32_t changed = 0;
  for (int i = 0; i <= d; ++i) changed |= std::uint32_t{lt[i] != ls[i]} << (ls[i] & 31);
  const int j = std::countr_zero(changed);
  if (j < 1) return -1;
  // A label ≥ j gets its high bit from label + 128 − j; the zero bytes after d stay zero.
  const std::uint32_t below_j = 0x01010101u * static_cast<std::uint32_t>(0x80 - j);
  for (int w = 0; w < label_words; ++w)
    same &= tau[d + w] == sigma[d + w] - (((sigma[d + w] + below_j) & 0x80808080u) >> 7);
  return same ? j : -1;
}

}  // namespace

int packed_facet_index(const std::uint32_t* tau, const std::uint32_t* sigma, int d) {
  switch (d) {
    case 2:
      return facet_index<2>(tau, sigma, d);
    case 3:
      return facet_index<3>(tau, sigma, d);
    case 4:
      return facet_index<4>(tau, sigma, d);
    case 5:
      return facet_index<5>(tau, sigma, d);
    case 6:
      return facet_index<6>(tau, sigma, d);
    default:
      return facet_index<0>(tau, sigma, d);
  }
}

void FaceEnumerator::reset(const Simplex& sigma, int k) {
  if (k < 0 || k > sigma.k)
    throw InputError("face dimension " + std::to_string(k) + " is outside 0.." + std::to_string(sigma.k));
  sigma_ = sigma;
  k_ = k;
  started_ = false;
  done_ = false;
}

bool FaceEnumerator::next(Simplex& out) {
  if (done_) return false;
  const int l = sigma_.k;
  if (!started_) {
    for (int h = 0; h <= k_; ++h) idx_[h] = h;
    started_ = true;
  } else {
    // Next combination of k+1 indices out of l+1, lexicographically.
    int h = k_;
    while (h >= 0 && idx_[h] == l - k_ + h) --h;
    if (h < 0) {
      done_ = true;
      return false;
    }
    ++idx_[h];
    for (int g = h + 1; g <= k_; ++g) idx_[g] = idx_[g - 1] + 1;
  }
  out = face_from_indices(sigma_, idx_.data(), k_);
  return true;
}

int vertex_index(const Simplex& sigma, const std::int32_t* v) {
  // v = v_j iff v − y is the indicator of {i < d : block(i) < j}. j is one more than the largest
  // block of a raised coordinate, and no lowered-or-equal coordinate may sit in a block below j.
  int j = 0;
  for (int i = 0; i < sigma.d; ++i) {
    const std::int32_t diff = v[i] - sigma.y[i];
    if (diff == 1) {
      if (sigma.block[i] + 1 > j) j = sigma.block[i] + 1;
      if (j > sigma.k) return -1;  // a coordinate in the last block never rises
    } else if (diff != 0) {
      return -1;
    }
  }
  for (int i = 0; i < sigma.d; ++i)
    if (v[i] == sigma.y[i] && sigma.block[i] < j) return -1;
  return j;
}

bool is_face_of(const Simplex& tau, const Simplex& sigma) {
  if (tau.d != sigma.d || tau.k > sigma.k) return false;
  std::array<std::int32_t, kMaxDimension> v;
  for (int j = 0; j <= tau.k; ++j) {
    tau.vertex(j, v.data());
    if (vertex_index(sigma, v.data()) < 0) return false;
  }
  return true;
}

}  // namespace coxmesh
