// Point-cloud files: the format by the extension, then one validated n × d array (see
// point_reader.h); the readers of the formats are in point_text.cpp, point_ply.cpp, point_npy.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>

#include "coxmesh/errors.h"
#include "coxmesh/io/point_formats.h"
#include "coxmesh/io/point_reader.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh {

namespace point_files {

void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

void split_into(std::string_view line, char separator, std::vector<std::string_view>& out) {
  out.clear();
  if (separator == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      std::size_t j = i;
      while (j < line.size() && !is_space(line[j])) ++j;
      if (j > i) out.push_back(line.substr(i, j - i));
      i = j;
    }
    return;
  }
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = std::min(line.find(separator, start), line.size());
    std::string_view field = line.substr(start, end - start);
    while (!field.empty() && is_space(field.front())) field.remove_prefix(1);
    while (!field.empty() && is_space(field.back())) field.remove_suffix(1);
    out.push_back(field);
    if (end == line.size()) break;
    start = end + 1;
  }
  if (out.size() == 1 && out[0].empty()) out.clear();  // a blank line
}

std::vector<std::string_view> split(std::string_view line, char separator) {
  std::vector<std::string_view> out;
  split_into(line, separator, out);
  return out;
}

double checked(std::string_view token, const std::string& path, const std::string& place) {
  const std::optional<double> v = parse_double(token);
  if (!v) fail(path, place + ": '" + std::string(token) + "' is not a number");
  if (std::isnan(*v)) fail(path, place + ": NaN is not a coordinate");
  if (!std::isfinite(*v)) fail(path, place + ": infinite value '" + std::string(token) + "'");
  return *v;
}

}  // namespace point_files

namespace {

namespace fs = std::filesystem;
using point_files::fail;

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(path, "is a directory, not a point file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) fail(path, "cannot read the file");
  return std::move(s).str();
}

}  // namespace

std::size_t remove_duplicate_points(PointSet& set) {
  const int d = set.dimension;
  const std::size_t n = set.size();
  auto row = [&](std::size_t i) { return set.points.data() + i * d; };
  // Each row against the earlier rows of its hash (an open-addressing table: sorting the rows to
  // find equal neighbours cost more); equal as numbers, so −0 and 0 hash alike, and a later copy of
  // a row is dropped.
  auto hash = [&](std::size_t i) {
    std::uint64_t h = 0x9E3779B97F4A7C15u;
    for (int t = 0; t < d; ++t) {
      const double v = row(i)[t] == 0 ? 0.0 : row(i)[t];
      std::uint64_t u;
      std::memcpy(&u, &v, sizeof u);
      h = (h ^ u) * 0xFF51AFD7ED558CCDu;
      h ^= h >> 32;
    }
    return h;
  };
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  constexpr std::size_t kEmpty = ~std::size_t{0};
  std::vector<std::size_t> table(size, kEmpty);
  std::vector<char> drop(n, 0);
  std::size_t removed = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t slot = hash(i) & (size - 1);; slot = (slot + 1) & (size - 1)) {
      if (table[slot] == kEmpty) {
        table[slot] = i;
        break;
      }
      if (std::equal(row(i), row(i) + d, row(table[slot]))) {
        drop[i] = 1, ++removed;
        break;
      }
    }
  if (!removed) return 0;
  std::size_t out = 0;
  const bool normals = !set.normals.empty();
  for (std::size_t i = 0; i < n; ++i) {
    if (drop[i]) continue;
    std::copy(row(i), row(i) + d, set.points.data() + out * d);
    if (normals) std::copy(set.normals.data() + i * d, set.normals.data() + (i + 1) * d, set.normals.data() + out * d);
    ++out;
  }
  set.points.resize(out * d);
  if (normals) set.normals.resize(out * d);
  return removed;
}

PointSet point_set_from_rows(std::vector<double> points, int d, std::vector<double> normals) {
  if (d < 1 || d > kMaxDimension)
    throw InputError("points of R^" + std::to_string(d) + ": d must be between 1 and " + std::to_string(kMaxDimension));
  if (points.empty() || points.size() % d != 0) throw InputError("the samples must be an (n, d) array with n >= 1");
  if (!normals.empty() && normals.size() != points.size())
    throw InputError("the normals must be an array of the samples' shape");
  for (double v : points)
    if (!std::isfinite(v)) throw InputError("the samples contain NaN or infinite coordinates");
  for (double v : normals)
    if (!std::isfinite(v)) throw InputError("the normals contain NaN or infinite values");
  PointSet set;
  set.dimension = d;
  set.points = std::move(points);
  set.normals = std::move(normals);
  set.format = "array";
  set.duplicates = remove_duplicate_points(set);
  return set;
}

PointSet read_points(const std::string& path, const PointReadOptions& options) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(path, "is a directory, not a point file");
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const char* known[] = {".xyz", ".txt", ".csv", ".off", ".ply", ".npy"};
  if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return ext == k; }) == std::end(known))
    fail(path, "unknown point file extension '" + ext + "' (use .xyz, .txt, .csv, .off, .ply or .npy)");
  const std::string text = read_file(path);
  PointSet set;
  if (ext == ".xyz" || ext == ".txt")
    set = point_files::read_rows(path, text, ' ', false, ext == ".xyz", options);
  else if (ext == ".csv")
    set = point_files::read_rows(path, text, ',', true, false, options);
  else if (ext == ".off")
    set = point_files::read_off(path, text);
  else if (ext == ".ply")
    set = point_files::read_ply(path, text);
  else
    set = point_files::read_npy(path, text);
  set.format = ext.substr(1);
  if (set.dimension < 1 || set.dimension > kMaxDimension)
    fail(path,
         "points of R^" + std::to_string(set.dimension) + ": d must be between 1 and " + std::to_string(kMaxDimension));
  if (options.dimension && set.dimension != options.dimension)
    fail(path,
         "the points are in R^" + std::to_string(set.dimension) + ", expected R^" + std::to_string(options.dimension));
  for (double v : set.normals)
    if (!std::isfinite(v)) fail(path, "the normals contain NaN or infinite values");
  set.duplicates = remove_duplicate_points(set);
  return set;
}

}  // namespace coxmesh
