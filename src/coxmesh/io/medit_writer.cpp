// INRIA medit .mesh writer: polygons as triangle fans, 3-cells as tetrahedra (simplices.h); see mesh_formats.h.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/number_text.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"

namespace coxmesh {

namespace {

using Element = std::array<std::uint32_t, 5>;  // up to 4 vertex ids (0-based) and the reference

void append_section(std::string& out, const char* name, const std::vector<Element>& elements, int arity) {
  if (elements.empty()) return;
  out += std::string(name) + "\n";
  append_number(out, static_cast<unsigned long long>(elements.size()));
  out += '\n';
  for (const Element& e : elements) {
    for (int i = 0; i < arity; ++i) {
      append_number(out, static_cast<unsigned long long>(e[i]) + 1);
      out += ' ';
    }
    append_number(out, static_cast<unsigned long long>(e[4]));
    out += '\n';
  }
}

}  // namespace

WrittenCounts write_medit(std::ostream& os, const CellComplex& cc, const Projection& projection) {
  const int m = cc.manifold_dimension;
  const std::vector<double> p3 = project_points(projection, vertex_coordinates(cc));
  const std::uint32_t n0 = cell_count(cc, CellKind::interior, 0), nv = vertex_count(cc);
  WrittenCounts counts;
  counts.points = nv;
  std::vector<Element> edges, triangles, tets;
  auto add_edges = [&](CellKind kind, std::uint32_t ref) {
    const Ragged ends = edge_ends(cc, kind);
    for (std::uint32_t c = 0; c < ends.size(); ++c)
      if (ends[c].size() == 2) {
        edges.push_back({ends[c][0], ends[c][1], 0, 0, ref});
      } else {
        ++counts.skipped;
      }
  };
  if (m == 1) add_edges(CellKind::interior, 0);
  if (m == 2) add_edges(CellKind::boundary, 1);
  if (m >= 2) {
    const Ragged polygons = oriented_polygon_cycles(cc, p3.data());
    const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2);
    for (std::uint32_t c = m == 2 ? 0 : n2; m <= 3 && c < polygons.size(); ++c) {
      if (!polygons[c].empty()) {
        const std::uint32_t ref = c >= n2 ? 1 : 0;
        for_each_fan_triangle(polygons[c], [&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
          triangles.push_back({a, b, t, 0, ref});
        });
      } else {
        ++counts.skipped;
      }
    }
    if (m >= 3) {
      for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
        const Ragged faces = polyhedron_faces(cc, kind, polygons);
        for (std::uint32_t c = 0; c < faces.size(); ++c)
          if (!faces[c].empty()) {
            const std::uint32_t ref = kind == CellKind::boundary ? 1 : 0;
            for_each_cone_tetrahedron(faces[c], polygons, p3.data(),
                                      [&](std::uint32_t a, std::uint32_t b, std::uint32_t t, std::uint32_t e) {
                                        tets.push_back({a, b, t, e, ref});
                                      });
          } else {
            ++counts.skipped;
          }
      }
    }
  }
  counts.cells = edges.size() + triangles.size() + tets.size();

  std::string out = "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n";
  append_number(out, static_cast<unsigned long long>(nv));
  out += '\n';
  for (std::uint32_t v = 0; v < nv; ++v) {
    for (int i = 0; i < 3; ++i) {
      append_number(out, p3[3 * v + i]);
      out += ' ';
    }
    out += v < n0 ? "0\n" : "1\n";
  }
  append_section(out, "\nEdges", edges, 2);
  append_section(out, "\nTriangles", triangles, 3);
  append_section(out, "\nTetrahedra", tets, 4);
  out += "\nEnd\n";
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

}  // namespace coxmesh
