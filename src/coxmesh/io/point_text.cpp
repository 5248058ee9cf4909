// .xyz .txt .csv (rows of numbers) and .off (the vertices of OFF meshes): the text formats of
// read_points.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/io/point_formats.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh::point_files {

// .xyz .txt .csv: rows of numbers.
PointSet read_rows(const std::string& path, std::string_view text, char separator, bool header_allowed,
                   bool xyz_normals, const PointReadOptions& options) {
  PointSet set;
  Lines lines(text);
  std::string_view line;
  std::size_t width = 0, first_line = 0;
  bool first = true;
  std::vector<std::string_view> tokens;
  while (lines.next(line)) {
    split_into(line, separator, tokens);
    if (tokens.empty()) continue;
    if (first && header_allowed &&
        std::any_of(tokens.begin(), tokens.end(), [](std::string_view t) { return !parse_double(t); })) {
      first = false;  // a header line of column names
      continue;
    }
    first = false;
    if (width == 0) {
      width = tokens.size();
      first_line = lines.number();
    } else if (tokens.size() != width) {
      fail(path, where(lines.number()) + " has " + std::to_string(tokens.size()) + " numbers, " + where(first_line) +
                     " has " + std::to_string(width));
    }
    for (std::string_view t : tokens) {
      const std::optional<double> v = parse_double(t);  // (the message's place only when it fails)
      set.points.push_back(v && std::isfinite(*v) ? *v : checked(t, path, where(lines.number())));
    }
  }
  if (width == 0) fail(path, "no points in the file");
  const bool with_normals = xyz_normals && width == 6 && options.dimension != 6;
  set.dimension = static_cast<int>(with_normals ? 3 : width);
  if (with_normals) {
    std::vector<double> coords, normals;
    for (std::size_t i = 0; i < set.points.size(); i += 6) {
      coords.insert(coords.end(), set.points.begin() + i, set.points.begin() + i + 3);
      normals.insert(normals.end(), set.points.begin() + i + 3, set.points.begin() + i + 6);
    }
    set.points = std::move(coords);
    set.normals = std::move(normals);
  }
  return set;
}

// .off: [ST][C][N][n]OFF, then (n: d), then counts nv nf ne, then nv vertex lines.
PointSet read_off(const std::string& path, std::string_view text) {
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  auto next_tokens = [&]() {
    while (lines.next(line)) {
      split_into(line, ' ', tokens);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  if (!next_tokens()) fail(path, "empty file: expected an OFF header");
  std::string_view key = tokens[0];
  if (key.size() < 3 || key.substr(key.size() - 3) != "OFF")
    fail(path, "line 1: expected OFF, NOFF, COFF or nOFF, found '" + std::string(key) + "'");
  // Prefixes in their fixed order: ST (texture coordinates) and C (colour) only add numbers after
  // the coordinates, which are ignored; N adds a normal; n announces the dimension.
  std::string_view prefix = key.substr(0, key.size() - 3);
  auto take_prefix = [&prefix](std::string_view p) {
    if (!prefix.starts_with(p)) return false;
    prefix.remove_prefix(p.size());
    return true;
  };
  take_prefix("ST");
  take_prefix("C");
  const bool normal = take_prefix("N");
  const bool given_dim = take_prefix("n");
  if (!prefix.empty()) fail(path, "line 1: unsupported OFF variant '" + std::string(key) + "'");
  std::vector<std::string_view> rest(tokens.begin() + 1, tokens.end());
  auto take = [&](const char* what) -> long long {
    while (rest.empty()) {
      if (!next_tokens()) fail(path, std::string("the header ends before the ") + what);
      rest = tokens;
    }
    const std::optional<double> v = parse_double(rest.front());
    if (!v || *v < 0 || *v != std::floor(*v) || *v > 1e15)
      fail(path, where(lines.number()) + ": the " + what + " '" + std::string(rest.front()) + "' is not a count");
    rest.erase(rest.begin());
    return static_cast<long long>(*v);
  };
  int d = 3;
  if (given_dim) {
    const long long dim = take("dimension");
    if (dim < 1 || dim > kMaxDimension)
      fail(path, "dimension " + std::to_string(dim) + " is outside 1.." + std::to_string(kMaxDimension));
    d = static_cast<int>(dim);
  }
  const long long nv = take("vertex count");
  take("face count");
  if (!rest.empty()) take("edge count");
  // Each vertex takes at least 2 bytes per coordinate ("0 "): more announced than the file holds.
  if (static_cast<double>(nv) * 2 * d > static_cast<double>(text.size() - std::min(text.size(), lines.position())))
    fail(path, "the header announces " + std::to_string(nv) + " vertices, more than the file can hold");
  PointSet set;
  set.dimension = d;
  set.points.reserve(nv * d);
  for (long long v = 0; v < nv; ++v) {
    if (!next_tokens())
      fail(path, "the file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    const std::size_t need = d * (normal ? 2 : 1);
    if (tokens.size() < need)
      fail(path, where(lines.number()) + ": a vertex needs " + std::to_string(need) + " numbers, found " +
                     std::to_string(tokens.size()));
    auto number = [&](std::string_view token) {  // (the message's place only when it fails)
      const std::optional<double> v = parse_double(token);
      return v && std::isfinite(*v) ? *v : checked(token, path, where(lines.number()));
    };
    for (int t = 0; t < d; ++t) set.points.push_back(number(tokens[t]));
    if (normal)
      for (int t = 0; t < d; ++t) set.normals.push_back(number(tokens[d + t]));
  }
  if (nv == 0) fail(path, "no vertices in the file");
  return set;
}

}  // namespace coxmesh::point_files
