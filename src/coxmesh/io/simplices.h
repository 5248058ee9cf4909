// The cell complex of a curve, surface or 3-manifold as simplices (edges, triangles, tetrahedra),
// for the formats and tools that only take simplices (STL, Gmsh, plot_trisurf). No vertex is added:
// the cells of the piecewise-linear approximation are convex (each is an affine plane of dimension
// m cut by an ambient simplex, thesis §4.2), so every polygon is split as the fan from one of its
// vertices and every 3-cell as the cone from one of its vertices over the fans of the faces that
// do not contain it (a pulling triangulation of a convex polytope). The fans start at the
// smallest global vertex id: two cells sharing a face then split it the same way, so the result is
// a simplicial complex (the cone's apex is the smallest vertex of its cell, hence of each face
// through it).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

/// Calls fn(a, b, c) for each triangle of the fan of a convex polygon (a cycle of global vertex
/// ids) from its smallest vertex, in the cycle's direction: a coherently oriented surface of
/// polygons gives a coherently oriented surface of triangles. Nothing for fewer than 3 vertices.
template <class Fn>
void for_each_fan_triangle(std::span<const std::uint32_t> cycle, Fn&& fn) {
  const std::size_t n = cycle.size();
  if (n < 3) return;
  const std::size_t s = static_cast<std::size_t>(std::min_element(cycle.begin(), cycle.end()) - cycle.begin());
  for (std::size_t i = 1; i + 1 < n; ++i) fn(cycle[s], cycle[(s + i) % n], cycle[(s + i + 1) % n]);
}

/// Number of triangles for_each_fan_triangle gives: sides − 2.
inline std::size_t fan_triangle_count(std::span<const std::uint32_t> cycle) {
  return cycle.size() >= 3 ? cycle.size() - 2 : 0;
}

/// Signed volume (times 6) of the tetrahedron a, b, c, e of `points3` (n × 3).
double tetrahedron_volume6(const double* points3, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t e);

/// Calls fn(a, b, c, e) for each tetrahedron of a closed 3-cell (`faces`: global polygon ids into
/// `polygons`): the cone from the cell's smallest vertex over the fan triangles of the faces not
/// containing it. With `points3` each tetrahedron is ordered to have positive volume there.
template <class Fn>
void for_each_cone_tetrahedron(std::span<const std::uint32_t> faces, const Ragged& polygons, const double* points3,
                               Fn&& fn) {
  std::uint32_t apex = 0xFFFFFFFFu;
  for (std::uint32_t f : faces)
    for (std::uint32_t v : polygons[f]) apex = std::min(apex, v);
  for (std::uint32_t f : faces) {
    const auto cycle = polygons[f];
    if (std::find(cycle.begin(), cycle.end(), apex) != cycle.end()) continue;
    for_each_fan_triangle(cycle, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (points3 && tetrahedron_volume6(points3, apex, a, b, c) < 0) std::swap(b, c);
      fn(apex, a, b, c);
    });
  }
}

/// The complex as simplices, vertices in the global numbering (polygons.h).
struct Simplices {
  int dimension = 0;                    ///< m: each interior simplex has m + 1 vertices
  std::vector<std::uint32_t> interior;  ///< the m-simplices, m + 1 ids each
  std::vector<std::uint32_t> boundary;  ///< the (m−1)-simplices of the boundary, m ids each
  std::size_t skipped = 0;              ///< open cells at the edge of an incomplete trace, not split
  std::size_t interior_count() const { return interior.size() / (dimension + 1); }
  std::size_t boundary_count() const { return dimension ? boundary.size() / dimension : 0; }
};

/// Splits the cells of dimension m (m ≤ 3) and of the boundary into simplices, oriented:
///   m = 1: edges head to tail along each curve (boundary: the end points);
///   m = 2: triangles of the polygons oriented by oriented_polygon_cycles (coherent where the
///          surface is orientable; closed components in R³ outward, i.e. along ∇F for a sphere
///          F = |x|² − r²); boundary edges in the direction of the triangle they bound;
///   m = 3: tetrahedra coherently oriented (two sharing a triangle induce opposite orientations on
///          it, where M is orientable), each connected component with positive volume in
///          `points3` (every tetrahedron positive when d = 3); boundary triangles from the
///          outward-oriented boundary surface.
/// points3: n × 3 projected vertex coordinates, or empty (no orientation by geometry).
///   Throws InputError for m > 3.
Simplices simplicial_complex(const CellComplex& cc, std::span<const double> points3);

}  // namespace coxmesh
