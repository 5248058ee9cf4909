// Binary STL and Gmsh MSH 4.1 writers: the complex as simplices (simplices.h); see mesh_formats.h
// and docs/formats.md.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/number_text.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"

namespace coxmesh {

static_assert(std::endian::native == std::endian::little, "binary STL is little-endian");

namespace {

void flush_if_large(std::ostream& os, std::string& out) {
  if (out.size() > (1u << 20)) {
    os.write(out.data(), static_cast<std::streamsize>(out.size()));
    out.clear();
  }
}

void append_float(std::string& out, double x) {
  const float f = static_cast<float>(x);
  char bytes[4];
  std::memcpy(bytes, &f, 4);
  out.append(bytes, 4);
}

}  // namespace

WrittenCounts write_stl(std::ostream& os, const CellComplex& cc, const Projection& projection) {
  const int m = cc.manifold_dimension;
  if (m != 2 && m != 3)
    throw InputError("STL holds triangles, but this is a " + std::to_string(m) +
                     "-manifold: STL takes surfaces (and the boundary of 3-manifolds); use .msh, .vtu or .cxm");
  const std::vector<double> p3 = project_points(projection, vertex_coordinates(cc));
  const Simplices s = simplicial_complex(cc, p3);
  const std::vector<std::uint32_t>& triangles = m == 2 ? s.interior : s.boundary;
  WrittenCounts counts;
  counts.points = p3.size() / 3;
  counts.cells = triangles.size() / 3;
  counts.skipped = s.skipped;
  if (counts.cells > 0xFFFFFFFFu) throw InputError("STL: more than 2^32 - 1 triangles");
  std::string out(80, '\0');
  const char title[] = "binary STL written by coxmesh";
  std::memcpy(out.data(), title, sizeof title - 1);
  const std::uint32_t n = static_cast<std::uint32_t>(counts.cells);
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const double* a = &p3[3 * static_cast<std::size_t>(triangles[t])];
    const double* b = &p3[3 * static_cast<std::size_t>(triangles[t + 1])];
    const double* c = &p3[3 * static_cast<std::size_t>(triangles[t + 2])];
    // The unit normal (b − a) × (c − a): the right-hand rule of the oriented triangle.
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double normal[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (double& x : normal) x = length > 0 ? x / length : 0.0;
    for (double x : normal) append_float(out, x);
    for (const double* p : {a, b, c})
      for (int i = 0; i < 3; ++i) append_float(out, p[i]);
    out.append(2, '\0');  // attribute byte count
    flush_if_large(os, out);
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

WrittenCounts write_msh(std::ostream& os, const CellComplex& cc, const Projection& projection) {
  const int m = cc.manifold_dimension;
  if (m < 1 || m > 3)
    throw InputError("Gmsh .msh holds lines, triangles and tetrahedra, but this is a " + std::to_string(m) +
                     "-manifold: use .vtu or .cxm");
  const std::vector<double> p3 = project_points(projection, vertex_coordinates(cc));
  const Simplices s = simplicial_complex(cc, p3);
  const std::size_t nv = p3.size() / 3, ni = s.interior_count(), nb = s.boundary_count();
  WrittenCounts counts;
  counts.points = nv;
  counts.cells = ni + nb;
  counts.skipped = s.skipped;
  // Element types of Gmsh: 15 point, 1 line, 2 triangle, 4 tetrahedron (indexed by dimension).
  constexpr int kType[4] = {15, 1, 2, 4};
  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n";
  // One entity (dimension m, tag 1) holds every node; tags 1..n are the global vertex ids + 1.
  out += nv ? "1 " : "0 ";
  out += std::to_string(nv) + " " + std::to_string(nv ? 1 : 0) + " " + std::to_string(nv) + "\n";
  if (nv) {
    out += std::to_string(m) + " 1 0 " + std::to_string(nv) + "\n";
    for (std::size_t v = 1; v <= nv; ++v) {
      append_number(out, static_cast<unsigned long long>(v));
      out += '\n';
      flush_if_large(os, out);
    }
    for (std::size_t v = 0; v < nv; ++v) {
      for (int i = 0; i < 3; ++i) {
        if (i) out += ' ';
        append_number(out, p3[3 * v + i]);
      }
      out += '\n';
      flush_if_large(os, out);
    }
  }
  out += "$EndNodes\n$Elements\n";
  const int blocks = (ni ? 1 : 0) + (nb ? 1 : 0);
  out += std::to_string(blocks) + " " + std::to_string(ni + nb) + " " + std::to_string(ni + nb ? 1 : 0) + " " +
         std::to_string(ni + nb) + "\n";
  // The interior m-simplices (entity of dimension m, tag 1), then the boundary (dimension m − 1, tag 1).
  std::size_t tag = 0;
  auto block = [&](const std::vector<std::uint32_t>& ids, int dim) {
    if (ids.empty()) return;
    const std::size_t arity = static_cast<std::size_t>(dim) + 1;
    out += std::to_string(dim) + " 1 " + std::to_string(kType[dim]) + " " + std::to_string(ids.size() / arity) + "\n";
    for (std::size_t e = 0; e < ids.size(); e += arity) {
      append_number(out, static_cast<unsigned long long>(++tag));
      for (std::size_t i = 0; i < arity; ++i) {
        out += ' ';
        append_number(out, static_cast<unsigned long long>(ids[e + i]) + 1);
      }
      out += '\n';
      flush_if_large(os, out);
    }
  };
  block(s.interior, m);
  block(s.boundary, m - 1);
  out += "$EndElements\n";
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  return counts;
}

}  // namespace coxmesh
