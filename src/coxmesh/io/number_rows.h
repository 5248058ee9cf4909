// Text files of numbers, one row per line: the matrix of a triangulation (--matrix), a projection
// to R³ (--project), points to locate.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace coxmesh {

/// rows × columns numbers, row after row.
struct NumberRows {
  std::vector<double> values;
  std::size_t rows = 0, columns = 0;
};

/// Reads rows of numbers separated by whitespace or commas; '#' starts a comment; blank lines are
/// skipped. Every number must be finite and every row as long as the first. `what` names the file in
/// messages (e.g. "matrix file 'm.txt'").
///   Throws InputError: the file cannot be opened or is a directory, a token is not a number, NaN or
///   Inf, rows of different lengths, no rows at all.
NumberRows read_number_rows(const std::string& path, const std::string& what);

/// A d × d matrix from a file of d rows of d numbers (the linear part of a triangulation).
///   Throws InputError as read_number_rows, and when the matrix is not square.
Eigen::MatrixXd read_matrix_file(const std::string& path);

}  // namespace coxmesh
