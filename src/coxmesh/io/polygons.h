// Geometry of a cell complex for the writers (thesis §4.2): the global vertex numbering, the
// cyclically ordered vertex list of every 2-cell, and the faces of every 3-cell. Plain arrays with
// 32-bit ids; nothing here depends on a file format.
//
// Numbering (used by every writer and documented in docs/formats.md):
//   * vertices: interior vertex cells 0 .. n0−1, then boundary vertex cells n0 .. n0+nb0−1;
//   * polygons: interior 2-cells 0 .. n2−1, then boundary 2-cells n2 .. n2+nb2−1.
// An interior 1-cell's ends are its interior vertex facets plus its boundary_facet (a boundary
// vertex) if any; a boundary 1-cell's ends are its boundary vertex facets. An interior 2-cell's
// edges are its interior 1-cell facets plus its boundary_facet (a boundary 1-cell); a boundary
// 2-cell's edges are its boundary 1-cell facets. 3-cells likewise, one level up.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh {

/// A list of lists of 32-bit ids in CSR form: list i is items[offsets[i] .. offsets[i+1]).
/// (Big blocks: util/huge_page_allocator.h.)
struct Ragged {
  HugeVector<std::uint32_t> offsets{0};
  HugeVector<std::uint32_t> items;

  std::uint32_t size() const { return static_cast<std::uint32_t>(offsets.size() - 1); }
  std::span<const std::uint32_t> operator[](std::uint32_t i) const {
    return {items.data() + offsets[i], items.data() + offsets[i + 1]};
  }
  void push(std::span<const std::uint32_t> list) {
    if (list.size() <= 8) {  // (most lists are a few ids: no call to copy them)
      for (std::uint32_t id : list) items.push_back(id);
    } else {
      items.insert(items.end(), list.begin(), list.end());
    }
    offsets.push_back(static_cast<std::uint32_t>(items.size()));
  }
};

enum class CellKind { interior, boundary };

/// The cells of dimension j of one kind, or nullptr when the complex has no such level
/// (interior: j ≤ m; boundary: j ≤ m − 1).
const CellLevel* cell_level(const CellComplex& cc, CellKind kind, int j);

/// Number of cells of dimension j of one kind (0 for a missing level).
std::uint32_t cell_count(const CellComplex& cc, CellKind kind, int j);

/// n0 + nb0: interior plus boundary vertex cells.
std::uint32_t vertex_count(const CellComplex& cc);

/// Coordinates in R^d of all vertices in the global numbering: (n0 + nb0) × d, row after row.
std::vector<double> vertex_coordinates(const CellComplex& cc);

/// The end points (global vertex ids) of every 1-cell of one kind; list c has 2 ids for a complete
/// cell, fewer for a cell at the edge of an incomplete trace (--max-simplices, --box).
Ragged edge_ends(const CellComplex& cc, CellKind kind);

/// The vertices (global ids) of every 2-cell, interior then boundary (global polygon numbering),
/// in cyclic order along the polygon's edges; consecutive vertices (and the last and the first)
/// are the two ends of one 1-cell. The list is empty when the edges do not close into one cycle
/// (a cell at the edge of an incomplete trace): writers skip such cells.
Ragged polygon_cycles(const CellComplex& cc);

/// polygon_cycles(cc), with the surface part oriented by orient_polygons: all 2-cells when m = 2,
/// the boundary 2-cells (the boundary surface) when m = 3. points3: n × 3 vertex coordinates used to
/// turn closed components outwards (may be null).
Ragged oriented_polygon_cycles(const CellComplex& cc, const double* points3);

/// The faces (global polygon ids) of every 3-cell of one kind; empty when the 3-cell is not
/// closed (fewer than four faces, a face empty in `polygons`, or an edge not in exactly two faces).
///   polygons: polygon_cycles(cc).
Ragged polyhedron_faces(const CellComplex& cc, CellKind kind, const Ragged& polygons);

/// The 3-cells of one kind one after the other, each with its faces, whether it is closed (as in
/// polyhedron_faces) and its corners: polyhedron_faces without its lists, for writers that use each
/// cell once. Cells are read in order and their polygons fetched a few cells ahead.
class PolyhedronCursor {
 public:
  /// points3: the vertices' coordinates (n × 3) the caller reads for each cell, fetched ahead too (may be null).
  /// complete: the complex comes from a complete trace, so that its 3-cells are convex polyhedra with
  /// all their faces. Then a cell is taken as closed when V − E + F = 2 (E: half the incidences), which
  /// a proper part of a convex polyhedron's boundary never satisfies, instead of counting every edge;
  /// only a cell that fails it is counted edge by edge. The answers are the same for such a complex.
  PolyhedronCursor(const CellComplex& cc, CellKind kind, const Ragged& polygons, const double* points3 = nullptr,
                   bool complete = false);
  std::uint32_t size() const { return level_ ? level_->size() : 0; }
  /// Moves to cell c (0 ≤ c < size(), best in increasing order); whether it is closed.
  bool load(std::uint32_t c);
  /// The faces of the cell (global polygon ids).
  std::span<const std::uint32_t> faces() const { return faces_; }
  /// When closed: its vertices (global ids), ascending, each once.
  std::span<const std::uint32_t> corners() const { return corners_; }
  /// When closed: the vertices of its faces' cycles counted face by face (the length of them all).
  std::size_t incidences() const { return incidences_; }

 private:
  bool closed_by_sorted_edges();

  const CellLevel* level_;
  CellKind kind_;
  const Ragged& polygons_;
  std::uint32_t n2_;
  bool as_listed_;  // (interior cells with no boundary face: their face ids as the level lists them)
  bool complete_;
  const double* points3_;
  std::span<const std::uint32_t> faces_;  // (the level's own list, or listed_faces_)
  std::vector<std::uint32_t> listed_faces_, corners_;
  std::size_t incidences_ = 0;
  std::vector<std::uint64_t> seen_, edges_;
  std::uint64_t loads_ = 0;
  // Bit j of once_[i] / twice_[i]: the edge between the corners numbered i ≤ j < 64 (as first met)
  // counted once / twice so far in the cell loaded.
  std::uint64_t once_[64], twice_[64];
};

/// Reverses polygons first .. last−1 so that two of them sharing an edge traverse it in opposite
/// directions (breadth-first over edge adjacency; edges in more than two of them are ignored). For
/// an orientable surface this is a consistent orientation. With `points3` (global vertex
/// coordinates, n × 3) each connected component is then flipped if its signed volume is negative,
/// so closed surfaces in R³ get outward normals. Empty lists are left alone.
///   edges: per polygon, the global ids (interior 1-cells, then boundary ones: edge_count in all)
///   of its edges in cycle order, edge i joining vertices i and i + 1.
void orient_polygons(Ragged& polygons, const Ragged& edges, std::uint32_t edge_count, std::uint32_t first,
                     std::uint32_t last, const double* points3 = nullptr);

}  // namespace coxmesh
