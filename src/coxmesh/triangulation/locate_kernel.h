// Thesis §3.4 (point location, barycentric coordinates), twice: as the plain statement of the
// algorithm (locate_plain.cpp, portable C++) and as the machine kernel that Triangulation uses on
// x86 (locate_kernel.cpp: GCC/Clang vector extensions, an AVX2 clone for d > 12). The two give
// bitwise the same simplices and lattice coordinates (tests/triangulation/test_locate_kernel.cpp).
// Internal to the triangulation layer (not installed); triangulation.h is the public interface.
#pragma once

#include <array>
#include <cstdint>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/triangulation/triangulation.h"

#if defined(__GNUC__)  // GCC and Clang: the kernel compiles
#define COXMESH_HAS_LOCATE_KERNEL 1
// Triangulation::locate and lattice_coordinates use it on x86 (-DCOXMESH_PORTABLE_LOCATE: the plain
// version there too, to try the portable path).
#if (defined(__x86_64__) || defined(__i386__)) && !defined(COXMESH_PORTABLE_LOCATE)
#define COXMESH_USE_LOCATE_KERNEL 1
#endif
#endif

namespace coxmesh::locate {

constexpr double kTieTolerance = 1e-9;  // as GUDHI: fractional parts within this share a block

/// Rows of Λ^{-1} as the kernel stores it: a multiple of 4 above d, rows d.. zero.
constexpr int padded_rows(int d) { return (d + 4) & ~3; }

/// The plain algorithm. z = Λ^{-1}(x − b) (d values), summed for each row in column order.
void lattice_coordinates_plain(const Triangulation& t, const double* x, double* z);
/// The simplex of T containing x: z = Λ^{-1}(x − b), y = ⌊z⌋, and the indices 0..d ordered by
/// decreasing fractional part, cut into blocks where it drops by more than the tolerance.
Simplex locate_plain(const Triangulation& t, const double* x);
/// Throws InputError for the lattice coordinates z[0..d) of a point out of range (or NaN / Inf).
[[noreturn]] void throw_out_of_range(const double* z, int d);

/// Barycentric coordinates (dim σ + 1 values) in σ of the point with lattice coordinates z[0..d).
/// With ζ_j the mean of z_i − y_i over the block j of σ (ζ_k = 0): λ_0 = 1 − ζ_0, λ_j = ζ_{j−1} − ζ_j.
inline void barycentric_in_lattice(const Simplex& sigma, int d, const double* z, double* lambda) {
  std::array<double, kMaxDimension + 1> zeta{};
  std::array<int, kMaxDimension + 1> count{};
  const int k = sigma.k;
  for (int i = 0; i < d; ++i)
    if (sigma.block[i] < k) {
      zeta[sigma.block[i]] += z[i] - sigma.y[i];
      ++count[sigma.block[i]];
    }
  for (int j = 0; j < k; ++j) zeta[j] /= count[j];  // blocks before the last hold an index < d
  zeta[k] = 0;
  lambda[0] = 1 - zeta[0];
  for (int j = 1; j <= k; ++j) lambda[j] = zeta[j - 1] - zeta[j];
}

#if defined(COXMESH_HAS_LOCATE_KERNEL)
/// The kernel: the same results. padded_inverse = Λ^{-1} padded to padded_rows(d) rows
/// (column-major); z has room for padded_rows(d) values (the padding comes out 0).
void lattice_coordinates_kernel(const double* padded_inverse, const double* offset, int d, const double* x, double* z);
Simplex locate_kernel(const Triangulation& t, const double* padded_inverse, const double* x);
#endif

}  // namespace coxmesh::locate
