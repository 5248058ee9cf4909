// Thesis §3.4: point location and barycentric coordinates in the Freudenthal–Kuhn triangulation
// under x = Λ·y + b, stated plainly. Portable C++; Triangulation uses it where the kernel of
// locate_kernel.cpp (the same results, shaped for the machine) is not used.
#include <array>
#include <cmath>
#include <numeric>
#include <utility>

#include "coxmesh/triangulation/locate_kernel.h"

namespace coxmesh::locate {

void lattice_coordinates_plain(const Triangulation& t, const double* x, double* z) {
  const int d = t.dimension();
  const double* b = t.offset().data();
  if (t.is_freudenthal()) {
    for (int i = 0; i < d; ++i) z[i] = x[i] - b[i];
    return;
  }
  const Eigen::MatrixXd& inverse = t.inverse();
  for (int i = 0; i < d; ++i) z[i] = 0;
  for (int j = 0; j < d; ++j) {  // (column by column: the kernel's order of the sums)
    const double u = x[j] - b[j];
    for (int i = 0; i < d; ++i) z[i] += inverse(i, j) * u;
  }
}

Simplex locate_plain(const Triangulation& t, const double* x) {
  const int d = t.dimension();
  std::array<double, kMaxDimension> z;
  lattice_coordinates_plain(t, x, z.data());
  Simplex s = kBlankSimplex;
  s.d = static_cast<std::uint8_t>(d);
  // y = ⌊z⌋ and the fractional parts z − y; a coordinate within the tolerance of an integer is
  // snapped to it (fraction 0), so points on lower-dimensional faces locate those faces.
  std::array<double, kMaxDimension + 1> frac{};  // frac[d] = 0
  for (int i = 0; i < d; ++i) {
    if (!(std::abs(z[i]) < kMaxLatticeCoordinate - 1)) throw_out_of_range(z.data(), d);
    double floor = std::floor(z[i]);
    frac[i] = z[i] - floor;
    if (frac[i] <= kTieTolerance)
      frac[i] = 0;
    else if (1 - frac[i] <= kTieTolerance)
      floor += 1, frac[i] = 0;
    s.y[i] = static_cast<std::int32_t>(floor);
  }
  // The indices 0..d by decreasing fractional part (equal ones by index), cut into blocks where
  // the fractional part drops by more than the tolerance.
  std::array<std::uint8_t, kMaxDimension + 1> order{};
  std::iota(order.begin(), order.begin() + d + 1, std::uint8_t{0});
  for (int p = 1; p <= d; ++p)  // (insertion sort: stable, no allocation)
    for (int q = p; q > 0 && frac[order[q - 1]] < frac[order[q]]; --q) std::swap(order[q - 1], order[q]);
  int block = 0;
  s.block[order[0]] = 0;
  for (int p = 1; p <= d; ++p) {
    if (frac[order[p - 1]] > frac[order[p]] + kTieTolerance) ++block;
    s.block[order[p]] = static_cast<std::uint8_t>(block);
  }
  s.k = static_cast<std::uint8_t>(block);
  return s;
}

}  // namespace coxmesh::locate
