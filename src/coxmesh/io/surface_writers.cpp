// OFF / nOFF, PLY and OBJ writers: the polygonal 2-skeleton (surfaces); see mesh_formats.h.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/number_text.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"

// GCC 12 reports a false -Wrestrict in std::string::append once the number formatting is inlined
// into the face loops.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace coxmesh {

static_assert(std::endian::native == std::endian::little, "the PLY writer declares binary_little_endian");

namespace {

void require_polygons(const CellComplex& cc, const char* format) {
  if (cc.manifold_dimension < 2)
    throw InputError(std::string(format) + " holds polygons, but this is a " + std::to_string(cc.manifold_dimension) +
                     "-manifold: use .vtu, .obj, .mesh or .cxm");
}

// Points (n × dim) as text lines, with an optional prefix ("v ").
void append_points(std::string& out, std::span<const double> xs, int dim, const char* prefix) {
  for (std::size_t v = 0; v < xs.size() / dim; ++v) {
    out += prefix;
    for (int i = 0; i < dim; ++i) {
      if (i) out += ' ';
      append_number(out, xs[v * dim + i]);
    }
    out += '\n';
  }
}

// Calls fn(vertex ids) for each face written: every non-empty polygon, or (simplices) each of its
// fan triangles. Returns the number of faces.
template <class Fn>
std::size_t for_each_face(const Ragged& polygons, bool simplices, Fn&& fn) {
  std::size_t faces = 0;
  for (std::uint32_t c = 0; c < polygons.size(); ++c) {
    if (polygons[c].empty()) continue;
    if (!simplices) {
      fn(polygons[c]);
      ++faces;
      continue;
    }
    for_each_fan_triangle(polygons[c], [&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
      const std::uint32_t ids[3] = {a, b, t};
      fn(std::span<const std::uint32_t>(ids));
      ++faces;
    });
  }
  return faces;
}

std::size_t open_polygons(const Ragged& polygons) {
  std::size_t open = 0;
  for (std::uint32_t c = 0; c < polygons.size(); ++c) open += polygons[c].empty() ? 1 : 0;
  return open;
}

std::size_t face_count(const Ragged& polygons, bool simplices) {
  return for_each_face(polygons, simplices, [](std::span<const std::uint32_t>) {});
}

void flush_if_large(std::ostream& os, std::string& out) {
  if (out.size() > (1u << 20)) {
    os.write(out.data(), static_cast<std::streamsize>(out.size()));
    out.clear();
  }
}

}  // namespace

WrittenCounts write_off(std::ostream& os, const CellComplex& cc, const Projection& projection, bool n_dimensional,
                        bool simplices) {
  require_polygons(cc, "OFF");
  const int d = cc.ambient_dimension;
  const std::vector<double> xs = vertex_coordinates(cc);
  const std::vector<double> p3 = project_points(projection, xs);
  const Ragged polygons = oriented_polygon_cycles(cc, n_dimensional ? nullptr : p3.data());
  WrittenCounts counts;
  counts.points = xs.size() / d;
  counts.cells = face_count(polygons, simplices);
  counts.skipped = open_polygons(polygons);
  std::string out = n_dimensional ? "nOFF\n" + std::to_string(d) + "\n" : "OFF\n";
  out += std::to_string(counts.points) + " " + std::to_string(counts.cells) + " 0\n";
  append_points(out, n_dimensional ? xs : p3, n_dimensional ? d : 3, "");
  for_each_face(polygons, simplices, [&](std::span<const std::uint32_t> face) {
    append_number(out, static_cast<unsigned long long>(face.size()));
    for (std::uint32_t v : face) {
      out += ' ';
      append_number(out, static_cast<unsigned long long>(v));
    }
    out += '\n';
    flush_if_large(os, out);
  });
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

WrittenCounts write_ply(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices) {
  require_polygons(cc, "PLY");
  const ProjectedVertices projected(projection, cc);
  const std::span<const double> p3 = projected.points();
  const Ragged polygons = oriented_polygon_cycles(cc, p3.data());
  WrittenCounts counts;
  counts.points = p3.size() / 3;
  if (counts.points > 0x7FFFFFFFu) throw InputError("PLY: more than 2^31 - 1 vertices");
  counts.cells = face_count(polygons, simplices);
  counts.skipped = open_polygons(polygons);
  const std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by coxmesh\nelement vertex " +
                             std::to_string(counts.points) +
                             "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                             std::to_string(counts.cells) + "\nproperty list uchar int vertex_indices\nend_header\n";
  os.write(header.data(), static_cast<std::streamsize>(header.size()));
  os.write(reinterpret_cast<const char*>(p3.data()), static_cast<std::streamsize>(p3.size() * sizeof(double)));
  // Faces into a fixed buffer (a face takes at most 1 + 4 · 255 bytes), written out when nearly full.
  constexpr std::size_t kBuffer = std::size_t{1} << 20, kLargestFace = 1 + 4 * 255;
  std::vector<char> buffer(kBuffer);
  std::size_t used = 0;
  for_each_face(polygons, simplices, [&](std::span<const std::uint32_t> cycle) {
    if (cycle.size() > 255) throw InputError("PLY: a polygon has more than 255 vertices");
    if (used + kLargestFace > kBuffer) {
      os.write(buffer.data(), static_cast<std::streamsize>(used));
      used = 0;
    }
    buffer[used++] = static_cast<char>(cycle.size());
    for (std::uint32_t v : cycle) {
      const std::int32_t i = static_cast<std::int32_t>(v);
      std::memcpy(buffer.data() + used, &i, 4);
      used += 4;
    }
  });
  os.write(buffer.data(), static_cast<std::streamsize>(used));
  return counts;
}

WrittenCounts write_obj(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices) {
  if (cc.manifold_dimension < 1)
    throw InputError("OBJ holds lines and polygons, but this is a 0-manifold: use .vtu or .cxm");
  const ProjectedVertices projected(projection, cc);
  const std::span<const double> p3 = projected.points();
  WrittenCounts counts;
  counts.points = p3.size() / 3;
  std::string out = "# written by coxmesh\n";
  append_points(out, p3, 3, "v ");
  auto element = [&](char tag, std::span<const std::uint32_t> ids) {
    out += tag;
    for (std::uint32_t v : ids) {
      out += ' ';
      append_number(out, static_cast<unsigned long long>(v) + 1);
    }
    out += '\n';
    ++counts.cells;
    flush_if_large(os, out);
  };
  if (cc.manifold_dimension == 1) {
    const Ragged ends = edge_ends(cc, CellKind::interior);
    for (std::uint32_t c = 0; c < ends.size(); ++c)
      if (ends[c].size() == 2) {
        element('l', ends[c]);
      } else {
        ++counts.skipped;
      }
  } else {
    const Ragged polygons = oriented_polygon_cycles(cc, p3.data());
    for_each_face(polygons, simplices, [&](std::span<const std::uint32_t> face) { element('f', face); });
    counts.skipped = open_polygons(polygons);
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

}  // namespace coxmesh
