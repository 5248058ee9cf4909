// Files of number rows (--matrix, --project FILE) and the --project spec. Input: one byte choosing
// the mode and the dimension, then the file content (written to a private temporary file).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "coxmesh/io/number_rows.h"
#include "coxmesh/io/projection.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/triangulation/triangulation.h"

using namespace coxmesh;

namespace {

// One file per fuzzing process, in the system's temporary directory, removed at exit.
const std::string& scratch_file() {
  static const std::string path = [] {
    std::string p = (std::filesystem::temp_directory_path() / "coxmesh-fuzz-XXXXXX").string();
    const int fd = mkstemp(p.data());
    if (fd < 0) std::abort();
    close(fd);
    std::atexit([] { std::remove(scratch_file().c_str()); });
    return p;
  }();
  return path;
}

const std::vector<double> kPoints = {0, 0,  0, 0, 0,   0, 1, 0.5, -2, 3, 0.25, 1, -1, 2, 0.75, -0.5,  4,  1,
                                     2, -3, 1, 0, 0.5, 2, 1, 1,   1,  1, 1,    1, -1, 0, 2,    0.125, -3, 5};  // 6 × 6

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int mode = data[0] & 3, d = 1 + (data[0] >> 2) % 6;
  const std::string content(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (mode == 3) {  // the spec as text: indices, "pca", "" (never a path of this machine)
      // (a NUL would cut the name when the file is opened; no command-line argument holds one)
      std::error_code ec;
      if (content.find('\0') != std::string::npos || (!content.empty() && std::filesystem::exists(content, ec)))
        return 0;
      std::vector<double> points(kPoints.begin(), kPoints.begin() + 6 * d);
      const Projection p = make_projection(content, d, points);
      project_points(p, points);
      return 0;
    }
    {
      std::ofstream out(scratch_file(), std::ios::binary | std::ios::trunc);
      out << content;
    }
    if (mode == 0) {  // rows as points: their principal axes
      const NumberRows rows = read_number_rows(scratch_file(), "fuzz rows");
      if (rows.rows * rows.columns != rows.values.size()) std::abort();
      if (rows.columns <= static_cast<std::size_t>(kMaxDimension)) {
        const int n = static_cast<int>(rows.columns);
        const Projection p = make_projection("pca", n, rows.values);
        project_points(p, rows.values);
      }
    } else if (mode == 1) {  // a matrix: the linear part of a triangulation
      const Eigen::MatrixXd m = read_matrix_file(scratch_file());
      if (m.rows() <= kMaxDimension) {
        const Triangulation t(m, Eigen::VectorXd::Zero(m.rows()));
        t.locate(std::vector<double>(m.rows(), 0.3));
      }
    } else {  // a projection matrix file for points of R^d
      std::vector<double> points(kPoints.begin(), kPoints.begin() + 6 * d);
      const Projection p = make_projection(scratch_file(), d, points);
      project_points(p, points);
    }
  } catch (const InputError&) {
  }
  return 0;
}
