// Point-cloud readers: every format ends in one validated n × d array (see point_reader.h).
#include "coxmesh/io/point_reader.h"
#include "coxmesh/util/parse_number.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>
#include <string_view>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

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

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// Lines of text with their 1-based numbers; '#' comments cut off.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    return true;
  }
  std::size_t number() const { return number_; }
  std::size_t position() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, number_ = 0;
};

std::vector<std::string_view> split(std::string_view line, char separator) {
  std::vector<std::string_view> out;
  if (separator == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      std::size_t j = i;
      while (j < line.size() && !is_space(line[j])) ++j;
      if (j > i) out.push_back(line.substr(i, j - i));
      i = j;
    }
    return out;
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
  return out;
}

std::string where(std::size_t line) { return "line " + std::to_string(line); }

double checked(std::string_view token, const std::string& path, const std::string& place) {
  const std::optional<double> v = parse_double(token);
  if (!v) fail(path, place + ": '" + std::string(token) + "' is not a number");
  if (std::isnan(*v)) fail(path, place + ": NaN is not a coordinate");
  if (!std::isfinite(*v)) fail(path, place + ": infinite value '" + std::string(token) + "'");
  return *v;
}

// .xyz .txt .csv: rows of numbers.
PointSet read_rows(const std::string& path, std::string_view text, char separator, bool header_allowed,
                   bool xyz_normals, const PointReadOptions& options) {
  PointSet set;
  Lines lines(text);
  std::string_view line;
  std::size_t width = 0, first_line = 0;
  bool first = true;
  while (lines.next(line)) {
    const std::vector<std::string_view> tokens = split(line, separator);
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
    for (std::string_view t : tokens) set.points.push_back(checked(t, path, where(lines.number())));
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
      tokens = split(line, ' ');
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
    for (int t = 0; t < d; ++t) set.points.push_back(checked(tokens[t], path, where(lines.number())));
    if (normal)
      for (int t = 0; t < d; ++t) set.normals.push_back(checked(tokens[d + t], path, where(lines.number())));
  }
  if (nv == 0) fail(path, "no vertices in the file");
  return set;
}

// .ply
struct PlyProperty {
  std::string name, type, count_type;  // count_type non-empty for a list
};
struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

int ply_size(const std::string& type, const std::string& path) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  fail(path, "unknown PLY property type '" + type + "'");
}

double ply_value(const char* p, const std::string& type) {
  auto get = [p]<class T>(T) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  if (type == "char" || type == "int8") return get(std::int8_t{});
  if (type == "uchar" || type == "uint8") return get(std::uint8_t{});
  if (type == "short" || type == "int16") return get(std::int16_t{});
  if (type == "ushort" || type == "uint16") return get(std::uint16_t{});
  if (type == "int" || type == "int32") return get(std::int32_t{});
  if (type == "uint" || type == "uint32") return get(std::uint32_t{});
  if (type == "float" || type == "float32") return get(float{});
  return get(double{});
}

PointSet read_ply(const std::string& path, std::string_view text) {
  static_assert(std::endian::native == std::endian::little, "binary PLY reading assumes a little-endian machine");
  Lines lines(text);
  std::string_view line;
  if (!lines.next(line) || split(line, ' ').empty() || split(line, ' ')[0] != "ply")
    fail(path, "line 1: not a PLY file (no 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (lines.next(line)) {
    const std::vector<std::string_view> t = split(line, ' ');
    if (t.empty()) continue;
    if (t[0] == "end_header") {
      ended = true;
      break;
    }
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format" && t.size() >= 2) {
      format = t[1];
    } else if (t[0] == "element" && t.size() == 3) {
      const std::optional<double> c = parse_double(t[2]);
      if (!c || *c < 0 || *c != std::floor(*c) || *c > 1e15)
        fail(path, where(lines.number()) + ": bad element count '" + std::string(t[2]) + "'");
      elements.push_back({std::string(t[1]), static_cast<long long>(*c), {}});
    } else if (t[0] == "property" && !elements.empty() && t.size() == 3) {
      elements.back().properties.push_back({std::string(t[2]), std::string(t[1]), ""});
      ply_size(elements.back().properties.back().type, path);
    } else if (t[0] == "property" && !elements.empty() && t.size() == 5 && t[1] == "list") {
      elements.back().properties.push_back({std::string(t[4]), std::string(t[3]), std::string(t[2])});
      ply_size(elements.back().properties.back().type, path);
      ply_size(elements.back().properties.back().count_type, path);
    } else {
      fail(path, where(lines.number()) + ": unexpected PLY header line '" + std::string(line) + "'");
    }
  }
  if (!ended) fail(path, "the PLY header has no end_header");
  if (format == "binary_big_endian")
    fail(path, "big-endian binary PLY is not supported (convert it to ascii or little-endian)");
  if (format != "ascii" && format != "binary_little_endian") fail(path, "unknown PLY format '" + format + "'");
  const bool binary = format == "binary_little_endian";
  const auto vertex =
      std::find_if(elements.begin(), elements.end(), [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex == elements.end()) fail(path, "no vertex element in the PLY header");
  int xyz[3] = {-1, -1, -1}, nxyz[3] = {-1, -1, -1};
  std::size_t vertex_bytes = 0;
  for (std::size_t i = 0; i < vertex->properties.size(); ++i) {
    const PlyProperty& p = vertex->properties[i];
    if (!p.count_type.empty()) fail(path, "list property '" + p.name + "' in the vertex element is not supported");
    vertex_bytes += ply_size(p.type, path);
    static const char* names[] = {"x", "y", "z"};
    static const char* nnames[] = {"nx", "ny", "nz"};
    for (int a = 0; a < 3; ++a) {
      if (p.name == names[a]) xyz[a] = static_cast<int>(i);
      if (p.name == nnames[a]) nxyz[a] = static_cast<int>(i);
    }
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) fail(path, "the vertex element lacks x, y or z");
  const bool normals = nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0;
  const std::size_t body = lines.position();
  const std::size_t available = text.size() - std::min(text.size(), body);
  const double least = binary ? static_cast<double>(vertex_bytes) : 2.0 * vertex->properties.size();
  if (static_cast<double>(vertex->count) * least > static_cast<double>(available))
    fail(path, "the header announces " + std::to_string(vertex->count) + " vertices, more than the file can hold");
  if (vertex->count == 0) fail(path, "no vertices in the file");

  PointSet set;
  set.dimension = 3;
  set.points.reserve(vertex->count * 3);
  std::vector<double> row(vertex->properties.size());
  auto keep = [&](const std::string& place) {
    for (int a = 0; a < 3; ++a) {
      const double v = row[xyz[a]];
      if (!std::isfinite(v))
        fail(path, place + ": " + (std::isnan(v) ? "NaN" : "an infinite value") + " in the coordinates");
      set.points.push_back(v);
    }
    if (normals)
      for (int a = 0; a < 3; ++a) set.normals.push_back(row[nxyz[a]]);
  };
  if (!binary) {
    for (const PlyElement& e : elements) {
      for (long long i = 0; i < e.count; ++i) {
        std::vector<std::string_view> t;
        do {
          if (!lines.next(line)) fail(path, "the file ends inside the " + e.name + " element");
          t = split(line, ' ');
        } while (t.empty());
        if (&e != &*vertex) continue;
        if (t.size() != row.size())
          fail(path, where(lines.number()) + ": a vertex has " + std::to_string(t.size()) +
                         " values, the header declares " + std::to_string(row.size()));
        for (std::size_t j = 0; j < t.size(); ++j) {
          const std::optional<double> v = parse_double(t[j]);
          if (!v) fail(path, where(lines.number()) + ": '" + std::string(t[j]) + "' is not a number");
          row[j] = *v;
        }
        keep(where(lines.number()));
      }
      if (&e == &*vertex) break;  // faces and anything after: not needed
    }
    return set;
  }
  std::size_t pos = body;
  auto need = [&](std::size_t bytes, const std::string& what) {
    if (pos + bytes > text.size()) fail(path, "the file ends inside the " + what + " element");
  };
  for (const PlyElement& e : elements) {
    for (long long i = 0; i < e.count; ++i) {
      for (std::size_t j = 0; j < e.properties.size(); ++j) {
        const PlyProperty& p = e.properties[j];
        if (!p.count_type.empty()) {
          need(ply_size(p.count_type, path), e.name);
          const double c = ply_value(text.data() + pos, p.count_type);
          pos += ply_size(p.count_type, path);
          if (c < 0) fail(path, "negative list length in the " + e.name + " element");
          need(static_cast<std::size_t>(c) * ply_size(p.type, path), e.name);
          pos += static_cast<std::size_t>(c) * ply_size(p.type, path);
          continue;
        }
        need(ply_size(p.type, path), e.name);
        if (&e == &*vertex) row[j] = ply_value(text.data() + pos, p.type);
        pos += ply_size(p.type, path);
      }
      if (&e == &*vertex) keep("vertex " + std::to_string(i));
    }
    if (&e == &*vertex) break;
  }
  return set;
}

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

}  // namespace

std::size_t remove_duplicate_points(PointSet& set) {
  const int d = set.dimension;
  const std::size_t n = set.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto row = [&](std::size_t i) { return set.points.data() + i * d; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(row(a), row(a) + d, row(b), row(b) + d);
  });
  std::vector<char> drop(n, 0);
  std::size_t removed = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (std::equal(row(order[i]), row(order[i]) + d, row(order[i - 1]))) drop[order[i]] = 1, ++removed;
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
    set = read_rows(path, text, ' ', false, ext == ".xyz", options);
  else if (ext == ".csv")
    set = read_rows(path, text, ',', true, false, options);
  else if (ext == ".off")
    set = read_off(path, text);
  else if (ext == ".ply")
    set = read_ply(path, text);
  else
    set = read_npy(path, text);
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
