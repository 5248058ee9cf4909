// Thesis §3.4: the point-location kernel. The algorithm of locate_plain.cpp, shaped for the machine:
// the matrix–vector product and the sort in 16-byte vectors (GCC/Clang vector extensions), the
// dimension fixed at compile time up to 12, an AVX2 clone beyond (x86 only). Bitwise the same
// results as the plain version (tests/triangulation/test_locate_kernel.cpp).
#include "coxmesh/triangulation/locate_kernel.h"

#include <array>
#include <cmath>
#include <cstring>

namespace coxmesh::locate {

namespace {

// 16-byte vectors (GCC/Clang vector extensions, SSE2 on x86-64) for the point location kernels:
// branch-free and vectorised whatever the compiler's if-conversion does with floating-point
// comparisons, and every array is stored and loaded in the same 16-byte pieces (a wide load of
// narrower stores would stall until they reach the cache).
using V2d = double __attribute__((vector_size(16)));
using V2l = std::int64_t __attribute__((vector_size(16)));  // lane masks of V2d comparisons
using V2i = std::int32_t __attribute__((vector_size(8)));
using V4i = std::int32_t __attribute__((vector_size(16)));

V2d abs(V2d v) { return (V2d)((V2l)v & ~(V2l)V2d{-0.0, -0.0}); }

template <class V>
V load(const void* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
void store(void* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

// z = Λ^{-1}(x − b) for rows r .. r + 2C of the padded inverse (column-major, padded_rows(d) rows),
// with C vector accumulators in registers across the columns.
template <int C>
void lattice_rows(const double* inv, std::ptrdiff_t ld, const V2d* u, int d, int r, double* z) {
  V2d acc[C] = {};
  const double* col = inv + r;
#pragma GCC unroll 12  // completely for the compile-time dimensions (≤ 12)
  for (int j = 0; j < d; ++j, col += ld)
    for (int c = 0; c < C; ++c) acc[c] += load<V2d>(col + 2 * c) * u[j];
  for (int c = 0; c < C; ++c) store(z + r + 2 * c, acc[c]);
}

// The same with 32-byte vectors, for d > 12 (see locate_large): four rows per register.
using V4d = double __attribute__((vector_size(32)));
template <int C>
[[gnu::always_inline]] inline void lattice_rows_wide(const double* inv, std::ptrdiff_t ld, const double* u, int d,
                                                     int r, double* z) {
  V4d acc[C] = {};
  const double* col = inv + r;
  for (int j = 0; j < d; ++j, col += ld) {
    const V4d uj = {u[j], u[j], u[j], u[j]};
    for (int c = 0; c < C; ++c) {
      V4d m;  // (memcpy, not load<>: a 32-byte vector by value would change the ABI without AVX)
      std::memcpy(&m, col + 4 * c, sizeof m);
      acc[c] += m * uj;
    }
  }
  for (int c = 0; c < C; ++c) std::memcpy(z + r + 4 * c, &acc[c], sizeof acc[c]);
}

// z_i = Σ_j Λ^{-1}_ij (x_j − b_j), summed in column order j = 0, 1, … for every row (the rounding
// of a plain column-by-column accumulation), for i < padded_rows(d): z_d.. = 0. Twelve rows at a
// time (6 + 1 vector registers), so that independent rows overlap. D > 0 fixes d at compile time;
// D = 0 (d > 12) takes 16 rows at a time in 32-byte vectors: single instructions where compiled for
// AVX2 (locate_large), pairs of 16-byte ones otherwise. No FMA either way, and every row is summed
// in the same order, so the result is bitwise the same on every machine.
template <int D>
[[gnu::always_inline]] inline void lattice_kernel(const double* inv, const double* b, const double* x, int d_runtime,
                                                  double* z) {
  const int d = D > 0 ? D : d_runtime, rows = padded_rows(d);
  if constexpr (D == 0) {
    double u[kMaxDimension];
    for (int j = 0; j < d; ++j) u[j] = x[j] - b[j];
    int r = 0;
    for (; r + 16 <= rows; r += 16) lattice_rows_wide<4>(inv, rows, u, d, r, z);
    if (rows - r == 12) lattice_rows_wide<3>(inv, rows, u, d, r, z);
    if (rows - r == 8) lattice_rows_wide<2>(inv, rows, u, d, r, z);
    if (rows - r == 4) lattice_rows_wide<1>(inv, rows, u, d, r, z);
    return;
  }
  V2d u[kMaxDimension];
  for (int j = 0; j < d; ++j) u[j] = V2d{x[j] - b[j], x[j] - b[j]};
  int r = 0;
  for (; r + 12 <= rows; r += 12) lattice_rows<6>(inv, rows, u, d, r, z);
  if (rows - r == 8) lattice_rows<4>(inv, rows, u, d, r, z);
  if (rows - r == 4) lattice_rows<2>(inv, rows, u, d, r, z);
}

// f = ⌊v⌋ and the fractional part v − f, snapped (f = the nearest integer, fraction 0) within the
// tolerance of an integer; |v| < 2^30. Lanes out of that range (or NaN) are cleared in `ok` and
// computed as 0. No libm calls: truncate, step down for negative non-integers; round up when the
// fraction is at least 1/2 (exact halves never snap). Every difference here is exact.
inline void floor_and_fraction(V2d v, V2d& f, V2d& frac, V2l& ok) {
  const V2d one = {1, 1}, half = {0.5, 0.5}, tol = {kTieTolerance, kTieTolerance};
  const V2d limit = {kMaxLatticeCoordinate - 1, kMaxLatticeCoordinate - 1};
  const V2l in_range = abs(v) < limit;
  ok &= in_range;
  v = (V2d)((V2l)v & in_range);
  f = __builtin_convertvector(__builtin_convertvector(v, V2i), V2d);
  f -= (V2d)((V2l)one & (f > v));
  frac = v - f;
  const V2d up = (V2d)((V2l)one & (frac >= half));
  const V2l snap = abs(frac - up) <= tol;  // |v − round(v)|
  f += (V2d)((V2l)up & snap);
  frac = (V2d)((V2l)frac & ~snap);
}

// rank_i = #{j < n : key_j > key_i} for the 4C keys: O(n·C) branch-free vector comparisons with the
// keys and counts in registers, instead of a comparison sort's mispredicted branches.
template <int C>
void rank_groups(const std::int32_t* key, int n, std::int32_t* rank) {
  V4i k[C], r[C] = {};
  for (int c = 0; c < C; ++c) k[c] = load<V4i>(key + 4 * c);
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < C; ++c) r[c] += k[c] < key[j];  // true is −1
  for (int c = 0; c < C; ++c) store(rank + 4 * c, -r[c]);
}

template <int D>
void rank_keys(const std::int32_t* key, int n, std::int32_t* rank) {
  if constexpr (D > 0) {
    rank_groups<padded_rows(D) / 4>(key, n, rank);
  } else {
    switch (padded_rows(n - 1) / 4) {
      case 1:
        return rank_groups<1>(key, n, rank);
      case 2:
        return rank_groups<2>(key, n, rank);
      case 3:
        return rank_groups<3>(key, n, rank);
      case 4:
        return rank_groups<4>(key, n, rank);
      case 5:
        return rank_groups<5>(key, n, rank);
      case 6:
        return rank_groups<6>(key, n, rank);
      case 7:
        return rank_groups<7>(key, n, rank);
      default:
        return rank_groups<8>(key, n, rank);
    }
  }
}

// Point location in FK coordinates (thesis §3.4): y = ⌊v⌋, then the indices ordered by decreasing
// fractional part, cut into blocks at strict drops. D > 0 fixes the dimension at compile time (small
// d: fully unrolled), D = 0 takes it at run time. z holds the lattice coordinates, padded with
// zeros to padded_rows(d) entries.
template <int D>
void locate_fk(const double* z, int d_runtime, Simplex& s) {
  const int d = D > 0 ? D : d_runtime, n = d + 1, rows = padded_rows(d);
  // Sort keys: the fractional part quantised to 26 bits, then 31 − index (ties by index). Index d
  // and the padding (fraction 0, index ≥ d) come last.
  alignas(16) std::array<std::int32_t, kMaxDimension + 1> key, rank;
  alignas(16) std::array<double, kMaxDimension + 1> frac;
  V2l ok = {-1, -1};
  for (int i = 0; i < rows; i += 4) {
    V2d f0, f1, q0, q1;
    floor_and_fraction(load<V2d>(z + i), f0, q0, ok);
    floor_and_fraction(load<V2d>(z + i + 2), f1, q1, ok);
    store(frac.data() + i, q0);
    store(frac.data() + i + 2, q1);
    const V2d scale = {67108864.0, 67108864.0};
    const V4i q = __builtin_shufflevector(__builtin_convertvector(q0 * scale, V2i),
                                          __builtin_convertvector(q1 * scale, V2i), 0, 1, 2, 3);
    store(key.data() + i, (q << 5) | V4i{31 - i, 30 - i, 29 - i, 28 - i});
    // y (0 from index d on); the last group would reach past y, into the block labels.
    const V4i y =
        __builtin_shufflevector(__builtin_convertvector(f0, V2i), __builtin_convertvector(f1, V2i), 0, 1, 2, 3);
    if (i + 4 <= kMaxDimension)
      store(s.y.data() + i, y);
    else
      for (int l = 0; i + l < kMaxDimension; ++l) s.y[i + l] = y[l];
  }
  if (!(ok[0] & ok[1])) throw_out_of_range(z, d);
  rank_keys<D>(key.data(), n, rank.data());
  // Usual case: consecutive fractional parts in rank order drop by more than the tolerance, so the
  // order is exact and every index is a block of its own: the blocks are the ranks.
  std::array<double, kMaxDimension + 1> sorted;
  for (int i = 0; i < n; ++i) sorted[rank[i]] = frac[i];
  bool drops = true;
  for (int p = 1; p < n; ++p) drops &= sorted[p - 1] > sorted[p] + kTieTolerance;
  if (drops) {
    for (int i = 0; i < n; ++i) s.block[i] = static_cast<std::uint8_t>(rank[i]);
    s.k = static_cast<std::uint8_t>(d);
    return;
  }
  std::array<std::uint8_t, kMaxDimension + 1> order{};
  for (int i = 0; i < n; ++i) order[rank[i]] = static_cast<std::uint8_t>(i);
  // Exact order: fractional parts closer than 2^-26 may be swapped by the quantisation; an
  // insertion pass on the exact values repairs that.
  for (int p = 1; p < n; ++p) {
    const std::uint8_t e = order[p];
    const double fe = frac[e];
    if (!(frac[order[p - 1]] < fe)) continue;
    int q = p;
    for (; q > 0 && frac[order[q - 1]] < fe; --q) order[q] = order[q - 1];
    order[q] = e;
  }
  // Strict drops (beyond the tolerance) start new blocks.
  int b = 0;
  s.block[order[0]] = 0;
  for (int p = 1; p < n; ++p) {
    b += frac[order[p - 1]] > frac[order[p]] + kTieTolerance ? 1 : 0;
    s.block[order[p]] = static_cast<std::uint8_t>(b);
  }
  s.k = static_cast<std::uint8_t>(b);
}

// locate() for a dimension fixed at compile time (D > 0: the small matrix–vector product and the
// kernel are fully unrolled) or given at run time (D = 0).
template <int D>
Simplex locate_impl(const Triangulation& t, const double* padded_inverse, const double* x) {
  const int d = D > 0 ? D : t.dimension();
  alignas(16) std::array<double, kMaxDimension + 1> z;
  if (t.is_freudenthal()) {
    const double* b = t.offset().data();
    for (int i = 0; i < d; ++i) z[i] = x[i] - b[i];
    for (int i = d; i < padded_rows(d); ++i) z[i] = 0;
  } else {
    lattice_kernel<D>(padded_inverse, t.offset().data(), x, d, z.data());
  }
  Simplex s = kBlankSimplex;
  s.d = static_cast<std::uint8_t>(d);
  locate_fk<D>(z.data(), d, s);
  return s;
}

// d > 12: compiled for AVX2 and for the baseline, chosen once at load time (the matrix–vector
// product is most of the work there); everything it calls is inlined into each version. Only on
// x86, not under ThreadSanitizer (the load-time chooser, an ifunc resolver, would run before its
// runtime and crash) and not with clang (which refuses target_clones next to flatten).
#if defined(__SANITIZE_THREAD__) || defined(__clang__) || !(defined(__x86_64__) || defined(__i386__))
[[gnu::flatten]]
#else
[[gnu::target_clones("avx2", "default"), gnu::flatten]]
#endif
Simplex
locate_large(const Triangulation& t, const double* padded_inverse, const double* x) {
  return locate_impl<0>(t, padded_inverse, x);
}

}  // namespace

void lattice_coordinates_kernel(const double* padded_inverse, const double* offset, int d, const double* x, double* z) {
  lattice_kernel<0>(padded_inverse, offset, x, d, z);
}

Simplex locate_kernel(const Triangulation& t, const double* padded_inverse, const double* x) {
  switch (t.dimension()) {
    case 1:
      return locate_impl<1>(t, padded_inverse, x);
    case 2:
      return locate_impl<2>(t, padded_inverse, x);
    case 3:
      return locate_impl<3>(t, padded_inverse, x);
    case 4:
      return locate_impl<4>(t, padded_inverse, x);
    case 5:
      return locate_impl<5>(t, padded_inverse, x);
    case 6:
      return locate_impl<6>(t, padded_inverse, x);
    case 7:
      return locate_impl<7>(t, padded_inverse, x);
    case 8:
      return locate_impl<8>(t, padded_inverse, x);
    case 9:
      return locate_impl<9>(t, padded_inverse, x);
    case 10:
      return locate_impl<10>(t, padded_inverse, x);
    case 11:
      return locate_impl<11>(t, padded_inverse, x);
    case 12:
      return locate_impl<12>(t, padded_inverse, x);
    default:
      return locate_large(t, padded_inverse, x);
  }
}

}  // namespace coxmesh::locate
