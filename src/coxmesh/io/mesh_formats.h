// Writers of the mesh file formats (VTU, OFF/nOFF, PLY, OBJ, medit) on binary streams. Each takes
// the cell complex and the projection to R³ (projection.h); the exact content of every format is
// specified in docs/formats.md. Cells at the edge of an incomplete trace (open polygons, open
// polyhedra, edges with one end) are skipped and counted. Atomic files and the choice of format
// by extension are in write_mesh.h.
#pragma once

#include <cstddef>
#include <ostream>

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
/// components); cell data "dimension" (UInt8) and "is_boundary" (UInt8).
WrittenCounts write_vtu(std::ostream& os, const CellComplex& cc, const Projection& projection);

/// OFF: "OFF" with 3D (projected) points, or, with `n_dimensional`, "nOFF" with the R^d points;
/// faces: every 2-cell (the polygonal 2-skeleton), consistently oriented when m = 2. Needs m ≥ 2
/// (throws InputError otherwise).
WrittenCounts write_off(std::ostream& os, const CellComplex& cc, const Projection& projection, bool n_dimensional);

/// PLY, binary little-endian: element vertex (double x, y, z) and element face (list uchar int
/// vertex_indices), the 2-cells as in write_off. Needs m ≥ 2.
WrittenCounts write_ply(std::ostream& os, const CellComplex& cc, const Projection& projection);

/// Wavefront OBJ: "v x y z" lines, then "f" lines (1-based) for the 2-cells, or "l" lines for the
/// 1-cells when m = 1.
WrittenCounts write_obj(std::ostream& os, const CellComplex& cc, const Projection& projection);

/// INRIA medit .mesh (MeshVersionFormatted 2, Dimension 3), 1-based indices, reference 0 for
/// interior and 1 for boundary elements: Vertices; Edges (m = 1: the 1-cells; m = 2: the boundary
/// 1-cells); Triangles (fans of the polygons: m = 2 the 2-cells, m = 3 the boundary 2-cells);
/// Tetrahedra (m ≥ 3: each 3-cell as the cone from its first vertex over the fan triangles of the
/// faces not containing it, positively oriented in the projected coordinates).
WrittenCounts write_medit(std::ostream& os, const CellComplex& cc, const Projection& projection);

}  // namespace coxmesh
