// .npy point files for read_points: a float64 or float32 array of shape (n, d), C order.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/io/point_formats.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh::point_files {

// .npy: magic, version, header length, a Python dict literal, then the data.
PointSet read_npy(const std::string& path, std::string_view text) {
  if (text.size() < 10 || text.substr(0, 6) != "\x93NUMPY") fail(path, "not a NumPy .npy file (bad magic)");
  const int major = static_cast<unsigned char>(text[6]);
  std::size_t header_len = 0, start = 0;
  if (major == 1) {
    header_len = static_cast<unsigned char>(text[8]) | static_cast<unsigned char>(text[9]) << 8;
    start = 10;
  } else if (major == 2 || major == 3) {
    if (text.size() < 12) fail(path, "truncated .npy header");
    for (int b = 0; b < 4; ++b)
      header_len |= static_cast<std::size_t>(static_cast<unsigned char>(text[8 + b])) << (8 * b);
    start = 12;
  } else {
    fail(path, "unsupported .npy version " + std::to_string(major));
  }
  if (start + header_len > text.size()) fail(path, "truncated .npy header");
  const std::string header(text.substr(start, header_len));
  auto value_of = [&](const std::string& key) {
    const std::size_t k = header.find("'" + key + "'");
    if (k == std::string::npos) fail(path, ".npy header lacks '" + key + "'");
    std::size_t v = header.find(':', k);
    if (v == std::string::npos) fail(path, "malformed .npy header");
    ++v;
    while (v < header.size() && header[v] == ' ') ++v;
    return v;
  };
  std::size_t v = value_of("descr");
  const std::size_t close = header.find(header[v], v + 1);
  const std::string descr = header.substr(v + 1, close - v - 1);
  if (descr != "<f8" && descr != "<f4" && descr != "=f8" && descr != "=f4")
    fail(path, "the array's type is '" + descr + "'; only float64 ('<f8') and float32 ('<f4') are read");
  const std::size_t item = descr.back() == '8' ? 8 : 4;
  v = value_of("fortran_order");
  if (header.compare(v, 4, "True") == 0) fail(path, "Fortran-order arrays are not read: save the array in C order");
  v = value_of("shape");
  const std::size_t open = header.find('(', v), end = header.find(')', v);
  if (open == std::string::npos || end == std::string::npos) fail(path, "malformed shape in the .npy header");
  std::vector<long long> shape;
  for (std::string_view t : split(std::string_view(header).substr(open + 1, end - open - 1), ',')) {
    if (t.empty()) continue;
    const std::optional<double> s = parse_double(t);
    if (!s || *s < 0 || *s != std::floor(*s) || *s > 1e15) fail(path, "malformed shape in the .npy header");
    shape.push_back(static_cast<long long>(*s));
  }
  if (shape.size() != 2)
    fail(path, "the array must have shape (n, d), found " + std::to_string(shape.size()) + " dimensions");
  if (shape[1] < 1 || shape[1] > kMaxDimension)
    fail(path, "d = " + std::to_string(shape[1]) + " is outside 1.." + std::to_string(kMaxDimension));
  const std::size_t data = start + header_len;
  const double bytes = static_cast<double>(shape[0]) * shape[1] * item;
  if (bytes != static_cast<double>(text.size() - data))
    fail(path, "the header announces " + std::to_string(shape[0]) + " x " + std::to_string(shape[1]) +
                   " values, the file holds " + std::to_string((text.size() - data) / item));
  if (shape[0] == 0) fail(path, "no points in the file");
  PointSet set;
  set.dimension = static_cast<int>(shape[1]);
  set.points.resize(shape[0] * shape[1]);
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const double x =
        item == 8 ? ply_value(text.data() + data + 8 * i, "double") : ply_value(text.data() + data + 4 * i, "float");
    if (!std::isfinite(x))
      fail(path, "point " + std::to_string(i / shape[1]) + ": " + (std::isnan(x) ? "NaN" : "an infinite value") +
                     " in the coordinates");
    set.points[i] = x;
  }
  return set;
}

}  // namespace coxmesh::point_files
