// A .vtu mesh written by several processes (docs/distributed.md): each rank writes the cells it owns
// to NAME_<rank>.vtu, with their faces' vertices (cell_complex_distributed.h: closure_for_writing)
// and the point and cell data "global_id"; rank 0 then writes the manifest NAME.pvtu, which
// ParaView opens as one mesh read in parallel.
#pragma once

#include <string>

#include "coxmesh/cell_complex/cell_complex_distributed.h"
#include "coxmesh/io/write_mesh.h"

namespace coxmesh {

/// The name of rank r's piece of `path` (NAME.pvtu → NAME_<r>.vtu).
std::string vtu_piece_path(const std::string& path, int rank);

/// Throws InputError unless pieces can be written with these options: a projection that does not
/// depend on the points (not pca nor stereographic: each piece would get its own).
void check_vtu_pieces(const WriteOptions& options);

/// Rank `rank`'s piece of `path`, written atomically. `vertices`: the interior vertex cells of the
/// whole complex (boundary vertices are numbered after them, as in polygons.h).
WrittenCounts write_vtu_piece_file(const std::string& path, int rank, const CellClosure& closure,
                                   std::uint64_t vertices, const WriteOptions& options);

/// The manifest of `pieces` pieces of `path`, written atomically once the pieces are.
void write_pvtu_manifest_file(const std::string& path, int pieces, int d, const WriteOptions& options);

}  // namespace coxmesh
