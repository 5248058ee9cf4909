// Output files: the format chosen by name or by extension, validated before any file is touched,
// and written atomically (atomic_file.h) by the writer of that format (mesh_formats.h,
// native_format.h).
#pragma once

#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/native_format.h"

namespace coxmesh {

enum class MeshFormat { vtu, off, noff, ply, obj, medit, cxm, stl, msh };

/// The format of a name: vtu, off, noff, ply, obj, mesh (or medit), cxm, stl, msh. Throws InputError
/// listing the known names.
MeshFormat parse_format(const std::string& name);

/// The format of a file name's extension (.vtu .off .ply .obj .mesh .cxm .stl .msh, any case). Throws
/// InputError for other extensions.
MeshFormat format_of_path(const std::string& path);

/// The canonical name of a format ("vtu", "off", …).
const char* format_name(MeshFormat format);

struct WriteOptions {
  std::string projection;    ///< --project: "", "i,j,k", "pca", "stereographic" or a matrix file (projection.h)
  std::vector<double> pole;  ///< --pole of "stereographic" (empty: chosen from the points)
  NativeInfo native;         ///< context stored in .cxm files
  /// --simplices: polygons and polyhedra as triangles and tetrahedra (simplices.h) in VTU, OFF,
  /// PLY and OBJ; medit, STL and Gmsh are simplicial anyway, and .cxm stores the cells (refused).
  bool simplices = false;
  /// --threads: workers that put a VTU file's 3-cells together (0: all hardware threads); the
  /// file is the same for any number.
  int threads = 1;
};

/// Whether `format` can hold an m-manifold in R^d with these options (the checks write_mesh makes
/// first, for a front end to make before tracing). Throws InputError saying why not.
void check_format(MeshFormat format, int d, int m, const WriteOptions& options);
/// Throws InputError unless the format can hold a manifold with corners (a stratified complex):
/// .vtu and .cxm always (they mark the strata), the polygon formats for surfaces. write_mesh checks it.
void check_stratified_format(MeshFormat format, int m);

/// Writes the complex to `path` in `format`, atomically. `.off` writes OFF when the points are in
/// R³ (d = 3, or a --project given) and nOFF otherwise. The projection and the format's needs (m ≥ 2
/// for OFF and PLY; STL: m = 2 or 3 and 3D points, i.e. d = 3 or a --project given; Gmsh:
/// 1 ≤ m ≤ 3) are checked before the file is created.
///   Throws InputError (bad projection, format unable to hold the complex, unwritable path); on
///   error an existing file at `path` is left untouched.
WrittenCounts write_mesh(const std::string& path, MeshFormat format, const CellComplex& cc,
                         const WriteOptions& options = {});

}  // namespace coxmesh
