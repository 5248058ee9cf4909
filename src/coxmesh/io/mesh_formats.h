// Writers of the mesh file formats (VTU, OFF/nOFF, PLY, OBJ, medit, STL, Gmsh) on binary streams. Each takes
// the cell complex and the projection to R³ (projection.h); the exact content of every format is
// specified in docs/formats.md. Cells at the edge of an incomplete trace (open polygons, open
// polyhedra, edges with one end) are skipped and counted. Atomic files and the choice of format
// by extension are in write_mesh.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <span>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/io/projection.h"

namespace coxmesh {

/// What a writer wrote: points, cells (elements) and the incomplete cells it skipped.
struct WrittenCounts {
  std::size_t points = 0, cells = 0, skipped = 0;
};

/// VTK XML UnstructuredGrid (version 1.0, raw appended data with UInt64 block sizes). Cells: the
/// cells of dimension p = min(m, 3) (interior, and boundary ones when m ≥ 4), plus for m ≤ 3 the
/// boundary (m−1)-cells; types VTK_VERTEX, VTK_LINE, VTK_POLYGON, VTK_POLYHEDRON (faces and
/// faceoffsets arrays, faces oriented outwards). Points: all vertices, projected. Point data
/// "on_boundary" (UInt8) and, when the projection changes the points, "coordinates" (R^d, d
/// components); cell data "dimension" (UInt8) and "is_boundary" (UInt8). With `simplices`, polygons
/// are written as their fan triangles (VTK_TRIANGLE) and polyhedra as tetrahedra (VTK_TETRA), split
/// as in simplices.h. The 3-cells are put together on `threads` workers (0: all hardware threads);
/// the bytes are the same for any number. `complete`: the complex comes from a complete trace, so
/// that its 3-cells need not be checked edge by edge (PolyhedronCursor); the bytes are the same.
WrittenCounts write_vtu(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices = false,
                        int threads = 1, bool complete = false);

/// The ids that the cells and vertices of a piece have in the whole complex (a piece of a .pvtu,
/// written by one of several processes): per cell of each level, interior[j] and boundary[j] (its id
/// in its level, as in the .cxm file; read where they are, e.g. in a CellClosure), and per vertex
/// in the numbering of polygons.h.
struct VtuGlobalIds {
  std::vector<std::span<const std::uint32_t>> interior, boundary;
  std::vector<std::uint64_t> points;
};
/// write_vtu with point data and cell data "global_id" (UInt64): ids.points, and the id of the cell
/// each VTK cell comes from (a triangle or tetrahedron of --simplices: its cell's).
WrittenCounts write_vtu(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices,
                        const VtuGlobalIds& ids, int threads = 1);

/// OFF: "OFF" with 3D (projected) points, or, with `n_dimensional`, "nOFF" with the R^d points;
/// faces: every 2-cell (the polygonal 2-skeleton), consistently oriented when m = 2. Needs m ≥ 2
/// (throws InputError otherwise). With `simplices`, each polygon as its fan triangles (simplices.h).
WrittenCounts write_off(std::ostream& os, const CellComplex& cc, const Projection& projection, bool n_dimensional,
                        bool simplices = false);

/// PLY, binary little-endian: element vertex (double x, y, z) and element face (list uchar int
/// vertex_indices), the 2-cells as in write_off (`simplices`: fan triangles). Needs m ≥ 2.
WrittenCounts write_ply(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices = false);

/// Wavefront OBJ: "v x y z" lines, then "f" lines (1-based) for the 2-cells, or "l" lines for the
/// 1-cells when m = 1 (`simplices`: "f" lines of the fan triangles).
WrittenCounts write_obj(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices = false);

/// INRIA medit .mesh (MeshVersionFormatted 2, Dimension 3), 1-based indices, reference 0 for
/// interior and 1 for boundary elements: Vertices; Edges (m = 1: the 1-cells; m = 2: the boundary
/// 1-cells); Triangles (fans of the polygons: m = 2 the 2-cells, m = 3 the boundary 2-cells);
/// Tetrahedra (m ≥ 3: each 3-cell as the cone from its first vertex over the fan triangles of the
/// faces not containing it, positively oriented in the projected coordinates; simplices.h).
WrittenCounts write_medit(std::ostream& os, const CellComplex& cc, const Projection& projection);

/// Binary STL: an 80-byte header, the triangle count (UInt32), then per triangle the unit normal
/// (b − a) × (c − a) and the vertices a, b, c (Float32 × 3 each) and a zero UInt16. The triangles
/// of simplicial_complex (simplices.h): m = 2 the surface, m = 3 its boundary surface, in the
/// projected coordinates. Needs m = 2 or 3 (throws InputError otherwise).
WrittenCounts write_stl(std::ostream& os, const CellComplex& cc, const Projection& projection);

/// Gmsh MSH 4.1 ASCII: $MeshFormat, $Nodes (one entity block of dimension m; node tags 1..n =
/// global vertex id + 1; projected x y z), $Elements (the m-simplices of simplicial_complex as one
/// block of dimension m, then the boundary (m−1)-simplices as one block of dimension m − 1; types
/// 15 point, 1 line, 2 triangle, 4 tetrahedron; element tags 1, 2, … in that order). Needs
/// 1 ≤ m ≤ 3 (throws InputError otherwise).
WrittenCounts write_msh(std::ostream& os, const CellComplex& cc, const Projection& projection);

}  // namespace coxmesh
