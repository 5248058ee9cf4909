// OFF / nOFF, PLY and OBJ writers: the polygonal 2-skeleton (surfaces); see mesh_formats.h.
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/number_text.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

static_assert(std::endian::native == std::endian::little, "the PLY writer declares binary_little_endian");

namespace {

void require_polygons(const CellComplex& cc, const char* format) {
  if (cc.manifold_dimension < 2)
    throw InputError(std::string(format) + " holds polygons, but this is a " + std::to_string(cc.manifold_dimension) +
                     "-manifold: use .vtu, .obj, .mesh or .cxm");
}

// Points (n × dim) as text lines, with an optional prefix ("v ").
void append_points(std::string& out, const std::vector<double>& xs, int dim, const char* prefix) {
  for (std::size_t v = 0; v < xs.size() / dim; ++v) {
    out += prefix;
    for (int i = 0; i < dim; ++i) {
      if (i) out += ' ';
      append_number(out, xs[v * dim + i]);
    }
    out += '\n';
  }
}

void flush_if_large(std::ostream& os, std::string& out) {
  if (out.size() > (1u << 20)) {
    os.write(out.data(), static_cast<std::streamsize>(out.size()));
    out.clear();
  }
}

}  // namespace

WrittenCounts write_off(std::ostream& os, const CellComplex& cc, const Projection& projection, bool n_dimensional) {
  require_polygons(cc, "OFF");
  const int d = cc.ambient_dimension;
  const std::vector<double> xs = vertex_coordinates(cc);
  const std::vector<double> p3 = project_points(projection, xs);
  const Ragged polygons = oriented_polygon_cycles(cc, n_dimensional ? nullptr : p3.data());
  WrittenCounts counts;
  counts.points = xs.size() / d;
  for (std::uint32_t c = 0; c < polygons.size(); ++c) (polygons[c].empty() ? counts.skipped : counts.cells) += 1;
  std::string out = n_dimensional ? "nOFF\n" + std::to_string(d) + "\n" : "OFF\n";
  out += std::to_string(counts.points) + " " + std::to_string(counts.cells) + " 0\n";
  append_points(out, n_dimensional ? xs : p3, n_dimensional ? d : 3, "");
  for (std::uint32_t c = 0; c < polygons.size(); ++c) {
    if (polygons[c].empty()) continue;
    append_number(out, static_cast<unsigned long long>(polygons[c].size()));
    for (std::uint32_t v : polygons[c]) {
      out += ' ';
      append_number(out, static_cast<unsigned long long>(v));
    }
    out += '\n';
    flush_if_large(os, out);
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

WrittenCounts write_ply(std::ostream& os, const CellComplex& cc, const Projection& projection) {
  require_polygons(cc, "PLY");
  const std::vector<double> p3 = project_points(projection, vertex_coordinates(cc));
  const Ragged polygons = oriented_polygon_cycles(cc, p3.data());
  WrittenCounts counts;
  counts.points = p3.size() / 3;
  if (counts.points > 0x7FFFFFFFu) throw InputError("PLY: more than 2^31 - 1 vertices");
  for (std::uint32_t c = 0; c < polygons.size(); ++c) (polygons[c].empty() ? counts.skipped : counts.cells) += 1;
  const std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by coxmesh\nelement vertex " +
                             std::to_string(counts.points) +
                             "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                             std::to_string(counts.cells) + "\nproperty list uchar int vertex_indices\nend_header\n";
  os.write(header.data(), static_cast<std::streamsize>(header.size()));
  os.write(reinterpret_cast<const char*>(p3.data()), static_cast<std::streamsize>(p3.size() * sizeof(double)));
  std::string out;
  for (std::uint32_t c = 0; c < polygons.size(); ++c) {
    const auto cycle = polygons[c];
    if (cycle.empty()) continue;
    if (cycle.size() > 255) throw InputError("PLY: a polygon has more than 255 vertices");
    out += static_cast<char>(cycle.size());
    for (std::uint32_t v : cycle) {
      const std::int32_t i = static_cast<std::int32_t>(v);
      out.append(reinterpret_cast<const char*>(&i), 4);
    }
    flush_if_large(os, out);
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

WrittenCounts write_obj(std::ostream& os, const CellComplex& cc, const Projection& projection) {
  if (cc.manifold_dimension < 1)
    throw InputError("OBJ holds lines and polygons, but this is a 0-manifold: use .vtu or .cxm");
  const std::vector<double> p3 = project_points(projection, vertex_coordinates(cc));
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
    for (std::uint32_t c = 0; c < polygons.size(); ++c)
      if (!polygons[c].empty()) {
        element('f', polygons[c]);
      } else {
        ++counts.skipped;
      }
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

}  // namespace coxmesh
