// The native file format `.cxm`: one file holding a whole cell complex in any dimension — every
// cell of every level with its facets and boundary facet, the ambient simplex of each cell
// (packed key), the vertex coordinates in R^d, d and m — so that a traced result can be reloaded
// exactly, re-exported and re-checked. Layout (also in docs/formats.md):
//
//   line 1   a JSON object (UTF-8), padded with spaces so that the '\n' ending it is the last
//            byte before an offset that is a multiple of 8;
//   then     little-endian binary arrays, back to back, in this order:
//              for each level, interior j = 0..m then boundary j = 0..m−1:
//                keys            cells × key_words  uint32   (pack(), simplex.h)
//                facet_offsets   cells + 1          uint32
//                facet_ids       facet_entries      uint32
//                boundary_facet  cells              uint32   (only when the level's flag is set)
//                domains         cells              uint64   (only when the level's flag is set)
//              vertices           n0 × d             float64
//              boundary_vertices  nb0 × d            float64
//
// Header keys: "format": "coxmesh-cxm", "version": 2, "ambient_dimension", "manifold_dimension",
// "domains" (the domain functions of a stratified complex, cell_complex.h; 0 otherwise),
// "key_words" (packed_words(d), or stratum_key_words(d) when stratified), "interior" and
// "boundary": one object per level {"cells", "facet_entries", "boundary_facet": bool,
// "domains": bool (the interior levels of a stratified complex)}, "vertices" (n0),
// "boundary_vertices" (nb0), and "info" (NativeInfo below). Version 1 (no "domains") still reads.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh {

/// Context stored next to the cells (header key "info"); every field is optional.
struct NativeInfo {
  std::string source;                      ///< how the manifold was given, e.g. "function x^2+y^2+z^2-1"
  bool complete = true;                    ///< false when a limit stopped the trace
  std::string message;                     ///< why it stopped (empty when complete)
  std::vector<double> matrix, offset;      ///< the ambient triangulation x = Λ·y + b: Λ (d × d, row-major) and b
  std::uint64_t function_evaluations = 0;  ///< (oracle calls are not stored: they vary with threads)
};

struct NativeFile {
  CellComplex cells;
  NativeInfo info;
};

/// Writes the complex in the .cxm layout above to a binary stream. Little-endian hosts only
/// (checked at compile time).
void write_native(std::ostream& os, const CellComplex& cc, const NativeInfo& info = {});

/// Reads a .cxm file and rebuilds the complex exactly: every cell keeps its id, and every array
/// equals the written one. The levels' keys come without a hash table, as from build_cell_complex
/// (reindex() before find()). Validates everything (header, sizes against the file size, then
/// check_native).
///   Throws InputError naming the file for anything wrong.
NativeFile read_native(const std::string& path);
/// The same from a stream; `name` is used in error messages.
NativeFile read_native(std::istream& in, const std::string& name);

/// The checks of read_native on a complex in memory (e.g. assembled from the pieces of several
/// processes): the levels' shapes, every key the canonical form of a simplex of its level's
/// dimension (and stratum), no key twice in a level, CSR offsets, facet ids in range, every
/// incidence one of the face relation with no facet twice, boundary facets on the same simplex,
/// finite coordinates. Throws InputError naming `name` for the first thing wrong.
void check_native(const CellComplex& cc, const std::string& name);

}  // namespace coxmesh
