// .ply point files for read_points: the vertex element's coordinates and normals, ascii or
// binary little-endian.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/io/point_formats.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh::point_files {

namespace {

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

}  // namespace

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
    std::vector<std::string_view> t;  // (one vector for every line)
    for (const PlyElement& e : elements) {
      for (long long i = 0; i < e.count; ++i) {
        do {
          if (!lines.next(line)) fail(path, "the file ends inside the " + e.name + " element");
          split_into(line, ' ', t);
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

}  // namespace coxmesh::point_files
