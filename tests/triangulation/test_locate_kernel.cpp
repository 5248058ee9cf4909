// Point location (thesis §3.4): the machine kernel (locate_kernel.cpp) and the plain statement of
// the algorithm (locate_plain.cpp) give bitwise the same lattice coordinates, simplices and
// barycentric coordinates, on random points and on points of faces (ties of fractional parts,
// coordinates on or within the tolerance of integers), in every dimension.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "coxmesh/triangulation/locate_kernel.h"
#include "coxmesh/triangulation/triangulation.h"

using namespace coxmesh;

namespace {

bool same_bits(const double* a, const double* b, int n) { return std::memcmp(a, b, n * sizeof(double)) == 0; }

// Random points for T: uniform ones, and points whose lattice coordinates have repeated
// fractional parts, integer coordinates, or fractional parts within ~the tolerance of each other
// or of 0 and 1 (mapped to x = Λz + b, so after rounding: ties within the tolerance).
std::vector<std::vector<double>> sample_points(const Triangulation& t, int count, std::mt19937_64& rng) {
  const int d = t.dimension();
  std::uniform_real_distribution<double> unit(0, 1), wide(-50, 50);
  std::uniform_int_distribution<int> lattice(-20, 20);
  const double nudges[] = {0, 0, 1e-12, -1e-12, 5e-10, -5e-10, 1e-9, -1e-9, 2e-9, -2e-9};
  std::vector<std::vector<double>> points;
  for (int n = 0; n < count; ++n) {
    Eigen::VectorXd z(d);
    if (n % 3 == 0) {
      for (int i = 0; i < d; ++i) z[i] = wide(rng);
    } else {
      // A few fractional values (0 included), shared by several coordinates, some nudged.
      std::vector<double> values = {0.0, 1.0 - 1e-10, 1e-10};
      for (int v = 0; v < 1 + n % 4; ++v) values.push_back(unit(rng));
      values.push_back(values.back() + (n % 2 ? 1e-10 : 3e-9));
      std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
      std::uniform_int_distribution<std::size_t> nudge(0, std::size(nudges) - 1);
      for (int i = 0; i < d; ++i) z[i] = lattice(rng) + values[pick(rng)] + (n % 5 == 0 ? nudges[nudge(rng)] : 0.0);
    }
    const Eigen::VectorXd x = t.matrix() * z + t.offset();
    points.emplace_back(x.data(), x.data() + d);
  }
  return points;
}

std::vector<Triangulation> triangulations(int d) {
  Eigen::VectorXd offset(d);
  for (int i = 0; i < d; ++i) offset[i] = 0.1 * i - 0.35;
  return {Triangulation::freudenthal(d), Triangulation::coxeter(d), Triangulation::coxeter(d).scaled(0.3).rotated(7),
          Triangulation::freudenthal(d).with_offset(offset), Triangulation::coxeter(d).with_offset(offset)};
}

}  // namespace

TEST(LocateKernel, KernelAndPlainVersionAgreeBitwise) {
  std::mt19937_64 rng(2019);
  std::size_t faces = 0;  // points located on a proper face (a tie or an integer coordinate)
  for (int d = 1; d <= kMaxDimension; ++d) {
    for (const Triangulation& t : triangulations(d)) {
      Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(locate::padded_rows(d), d);
      padded.topRows(d) = t.inverse();
      for (const std::vector<double>& x : sample_points(t, d <= 12 ? 600 : 150, rng)) {
        const Simplex plain = locate::locate_plain(t, x.data());
        EXPECT_EQ(plain, t.locate(x)) << "d=" << d << " " << to_string(plain);
        faces += plain.k < d;
        double z_plain[kMaxDimension + 1], lambda_plain[kMaxDimension + 1], lambda[kMaxDimension + 1];
        locate::lattice_coordinates_plain(t, x.data(), z_plain);
        locate::barycentric_in_lattice(plain, d, z_plain, lambda_plain);
        t.barycentric(plain, x.data(), lambda);
        ASSERT_TRUE(same_bits(lambda, lambda_plain, plain.k + 1)) << "d=" << d;
#if defined(COXMESH_HAS_LOCATE_KERNEL)
        const Simplex kernel = locate::locate_kernel(t, padded.data(), x.data());
        ASSERT_EQ(kernel, plain) << "d=" << d << " " << to_string(kernel) << " vs " << to_string(plain);
        double z_kernel[kMaxDimension + 1], lambda_kernel[kMaxDimension + 1];
        locate::lattice_coordinates_kernel(padded.data(), t.offset().data(), d, x.data(), z_kernel);
        ASSERT_TRUE(same_bits(z_kernel, z_plain, d)) << "d=" << d;
        locate::barycentric_in_lattice(kernel, d, z_kernel, lambda_kernel);
        ASSERT_TRUE(same_bits(lambda_kernel, lambda_plain, kernel.k + 1)) << "d=" << d;
#endif
      }
    }
  }
  EXPECT_GT(faces, 10000u);  // the ties were exercised
}

TEST(LocateKernel, SameErrorsOutOfRange) {
  for (int d : {2, 5, 13}) {
    const Triangulation t = Triangulation::coxeter(d);
    Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(locate::padded_rows(d), d);
    padded.topRows(d) = t.inverse();
    for (double bad : {std::nan(""), 1e12, -1e12}) {
      std::vector<double> x(d, 0.5);
      x[d / 2] = bad;
      std::string plain, kernel;
      try {
        locate::locate_plain(t, x.data());
      } catch (const InputError& e) {
        plain = e.what();
      }
#if defined(COXMESH_HAS_LOCATE_KERNEL)
      try {
        locate::locate_kernel(t, padded.data(), x.data());
      } catch (const InputError& e) {
        kernel = e.what();
      }
      EXPECT_EQ(kernel, plain);
#endif
      EXPECT_FALSE(plain.empty()) << bad;
    }
  }
}
