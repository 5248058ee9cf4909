#include "coxmesh/io/number_rows.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh {

namespace {

// A token quoted for a one-line message: control bytes shown as '?', cut at 40 bytes.
std::string shown(const std::string& token) {
  std::string out(1, '\'');
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out.push_back(c < 0x20 || c == 0x7f ? '?' : static_cast<char>(c));
  }
  if (token.size() > 40) out.append(3, '.');
  out.push_back('\'');
  return out;
}

}  // namespace

NumberRows read_number_rows(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(what + " is a directory");
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the " + what);
  NumberRows out;
  std::string line;
  for (std::size_t lineno = 1; std::getline(in, line); ++lineno) {
    if (const auto c = line.find('#'); c != std::string::npos) line.resize(c);
    const auto fail = [&](const std::string& why) {
      throw InputError(what + ", line " + std::to_string(lineno) + ": " + why);
    };
    std::size_t columns = 0;
    for (std::size_t i = 0; i < line.size();) {
      const auto separator = [&line](std::size_t at) {
        return line[at] == ',' || std::isspace(static_cast<unsigned char>(line[at])) != 0;
      };
      while (i < line.size() && separator(i)) ++i;
      if (i == line.size()) break;
      std::size_t j = i;
      while (j < line.size() && !separator(j)) ++j;
      const std::string token = line.substr(i, j - i);
      const std::optional<double> v = parse_double(token);
      if (!v) fail(shown(token) + " is not a number");
      if (!std::isfinite(*v)) fail("NaN or infinite entry " + shown(token));
      out.values.push_back(*v);
      ++columns;
      i = j;
    }
    if (columns == 0) continue;
    if (out.rows > 0 && columns != out.columns)
      fail("expected " + std::to_string(out.columns) + " numbers, got " + std::to_string(columns));
    out.columns = columns;
    ++out.rows;
  }
  if (out.rows == 0) throw InputError(what + " has no rows of numbers");
  return out;
}

Eigen::MatrixXd read_matrix_file(const std::string& path) {
  const std::string what = "matrix file '" + path + "'";
  const NumberRows rows = read_number_rows(path, what);
  if (rows.rows != rows.columns)
    throw InputError(what + " is " + std::to_string(rows.rows) + "x" + std::to_string(rows.columns) +
                     ", expected a square matrix");
  const int d = static_cast<int>(rows.rows);
  Eigen::MatrixXd m(d, d);
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) m(i, j) = rows.values[static_cast<std::size_t>(i) * d + j];
  return m;
}

}  // namespace coxmesh
