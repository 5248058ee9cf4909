// A .cxm file written by several processes (docs/distributed.md): each rank writes its part of the
// cell complex (cell_complex_distributed.h) to a piece NAME_<rank>.cxm, then rank 0 writes the
// manifest NAME.cxm, one JSON line naming the pieces (file names, in the manifest's directory):
//
//   {"format": "coxmesh-cxm-pieces", "version": 1, "pieces": ["NAME_0.cxm", ...], "info": {...}}
//
// A piece is laid out as a .cxm file (native_format.h), with "format": "coxmesh-cxm-piece" and,
// per level, "global_cells" (the level's size over all pieces); after each level's arrays come the
// global ids of its cells (cells × uint32), and its facet and boundary facet ids are global ids.
// read_native reads a manifest as the whole complex: the file that one process writes.
#pragma once

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex_distributed.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/native_format.h"

namespace coxmesh {

/// The name of rank r's piece of the manifest `path` (NAME.cxm → NAME_<r>.cxm).
std::string native_piece_path(const std::string& path, int rank);

void write_native_piece(std::ostream& os, const CellComplexPart& part);
/// Reads a piece (sizes and offsets checked; the assembled complex is checked by check_native).
CellComplexPart read_native_piece(std::istream& in, const std::string& name);

/// Writes the manifest of `pieces` pieces of `path` (the pieces' file names, relative to it).
void write_native_manifest(std::ostream& os, const std::string& path, int pieces, const NativeInfo& info);

/// Rank `rank`'s piece of `path`, written atomically (atomic_file.h).
void write_native_piece_file(const std::string& path, int rank, const CellComplexPart& part);
/// The manifest of `path` in `pieces` pieces, written atomically once the pieces are; returns the
/// counts that write_mesh returns for the whole complex, whose cells `counts` counts (a topology
/// report: the complex is not in one process).
WrittenCounts write_native_manifest_file(const std::string& path, int pieces, const TopologyReport& counts,
                                         const NativeInfo& info);

/// Whether the first line of `in` (rewound after) is a manifest; if so, the whole complex of its
/// pieces, each at its global id, checked as read_native checks a file.
bool read_native_manifest(std::istream& in, const std::string& name, NativeFile& out);

}  // namespace coxmesh
