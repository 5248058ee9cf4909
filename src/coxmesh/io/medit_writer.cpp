// INRIA medit .mesh writer: polygons as triangle fans, 3-cells as tetrahedra; see mesh_formats.h.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/number_text.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

namespace {

using Element = std::array<std::uint32_t, 5>;  // up to 4 vertex ids (0-based) and the reference

double signed_volume(const double* p3, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = p3[3 * b + i] - p3[3 * a + i];
    v[i] = p3[3 * c + i] - p3[3 * a + i];
    w[i] = p3[3 * d + i] - p3[3 * a + i];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

void fan(std::span<const std::uint32_t> cycle, std::uint32_t ref, std::vector<Element>& triangles) {
  for (std::size_t i = 1; i + 1 < cycle.size(); ++i) triangles.push_back({cycle[0], cycle[i], cycle[i + 1], 0, ref});
}

// The cone from the polyhedron's first vertex over the fan triangles of the faces not containing it.
void tetrahedralize(std::span<const std::uint32_t> faces, const Ragged& polygons, const double* p3, std::uint32_t ref,
                    std::vector<Element>& tets) {
  const std::uint32_t apex = polygons[faces[0]][0];
  for (std::uint32_t f : faces) {
    const auto cycle = polygons[f];
    if (std::find(cycle.begin(), cycle.end(), apex) != cycle.end()) continue;
    for (std::size_t i = 1; i + 1 < cycle.size(); ++i) {
      Element t{apex, cycle[0], cycle[i], cycle[i + 1], ref};
      if (signed_volume(p3, t[0], t[1], t[2], t[3]) < 0) std::swap(t[2], t[3]);
      tets.push_back(t);
    }
  }
}

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
        fan(polygons[c], c >= n2 ? 1 : 0, triangles);
      } else {
        ++counts.skipped;
      }
    }
    if (m >= 3) {
      for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
        const Ragged faces = polyhedron_faces(cc, kind, polygons);
        for (std::uint32_t c = 0; c < faces.size(); ++c)
          if (!faces[c].empty()) {
            tetrahedralize(faces[c], polygons, p3.data(), kind == CellKind::boundary ? 1 : 0, tets);
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
