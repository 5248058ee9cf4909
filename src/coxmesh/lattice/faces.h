// Thesis §3.5 (faces of a permutahedral simplex).
#pragma once

#include <algorithm>
#include <array>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// The k-face of σ (dimension l) spanned by the vertices i_0 < … < i_k (thesis §3.5): the base moves
/// to v_{i_0}; consecutive blocks between chosen vertices merge; the blocks after i_k and before
/// i_0 merge into the last block (which holds d, so the result is canonical). O(d).
/// `indices` has k+1 entries; preconditions (checked by the caller): increasing and ≤ l.
Simplex face_from_indices(const Simplex& sigma, const int* indices, int k);

/// True iff τ is a face of σ (every vertex of τ is a vertex of σ, thesis §3.5). O(d·(dim τ + 1)).
bool is_face_of(const Simplex& tau, const Simplex& sigma);

/// The facet of σ opposite its vertex j (0 ≤ j ≤ dim σ, dim σ ≥ 1): face_from_indices with every
/// index but j, in one pass. O(d). kD ≠ 0: σ.d = kD, fixed at compile time so that the loops unroll
/// (the walk's per-cofacet work, util/fixed_dimension.h); kD = 0 reads d at run time.
template <int kD = 0>
inline Simplex facet_without(const Simplex& sigma, int j) {
  // Dropping v_j merges blocks j−1 and j; dropping v_0 moves the base to v_1 and block 0 into the
  // last block (which holds d, so the result stays canonical).
  const int l = sigma.k, d = kD != 0 ? kD : sigma.d;
  COXMESH_DEBUG_ASSERT(l >= 1 && j >= 0 && j <= l);
  Simplex f = sigma;
  f.k = static_cast<std::uint8_t>(l - 1);
  if (j == 0) {
    for (int i = 0; i < d; ++i) f.y[i] += sigma.block[i] == 0 ? 1 : 0;
    for (int i = 0; i <= d; ++i)
      f.block[i] = static_cast<std::uint8_t>(sigma.block[i] == 0 ? l - 1 : sigma.block[i] - 1);
  } else {
    for (int i = 0; i <= d; ++i) f.block[i] = static_cast<std::uint8_t>(sigma.block[i] - (sigma.block[i] >= j ? 1 : 0));
  }
  return f;
}

/// For a facet τ of μ: the index in μ's vertex order of the vertex of μ not in τ. Vertex i of τ is
/// vertex i of μ below that index and vertex i + 1 from it on. O(d). kD as facet_without.
template <int kD = 0>
inline int extra_vertex_index(const Simplex& tau, const Simplex& mu) {
  COXMESH_DEBUG_ASSERT(mu.k == tau.k + 1 && mu.d == tau.d && (kD == 0 || tau.d == kD));
  COXMESH_PARANOID_ASSERT(is_face_of(tau, mu));
  // Same base vertex: μ splits a block b of τ in two and its new vertex comes right after v_b, so
  // b is the smallest τ-block of an index whose block number changed. Otherwise the split put
  // the part without d in front and the new vertex is μ's base. (Branch-free over the indices.)
  const int d = kD != 0 ? kD : tau.d;
  std::int32_t moved = 0;
  for (int i = 0; i < d; ++i) moved |= tau.y[i] ^ mu.y[i];
  if (moved != 0) return 0;
  int b = tau.k + 1;
  for (int i = 0; i <= d; ++i) b = std::min(b, tau.block[i] != mu.block[i] ? int{tau.block[i]} : b);
  return b + 1;
}

/// For packed keys (simplex.h) τ of dimension l − 1 and σ of dimension l ≥ 1, both of the form pack()
/// writes (is_packed_simplex): the j with τ = facet_without(σ, j), or −1 when τ is not a facet of σ.
/// The facet test on the words, O(d), with no unpack: for checking the incidences of a file.
int packed_facet_index(const std::uint32_t* tau, const std::uint32_t* sigma, int d);

/// Enumerates the k-faces of a simplex in lexicographic order of their vertex indices.
/// No allocation: reset() and next() work on fixed-size state.
///
///   FaceEnumerator faces(sigma, 1);
///   for (Simplex f; faces.next(f);) use(f);
class FaceEnumerator {
 public:
  FaceEnumerator() = default;
  FaceEnumerator(const Simplex& sigma, int k) { reset(sigma, k); }
  /// Throws InputError unless 0 ≤ k ≤ dim σ.
  void reset(const Simplex& sigma, int k);
  bool next(Simplex& out);

 private:
  Simplex sigma_;
  std::array<int, kMaxDimension + 1> idx_{};
  int k_ = 0;
  bool started_ = false, done_ = true;
};

/// Index j of the vertex v of σ (v = v_j), or −1 if v is not a vertex of σ. O(d).
int vertex_index(const Simplex& sigma, const std::int32_t* v);

}  // namespace coxmesh
