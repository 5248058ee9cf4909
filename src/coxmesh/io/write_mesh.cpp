// Choice of format and atomic writing of output files; see write_mesh.h.
#include "coxmesh/io/write_mesh.h"

#include <algorithm>
#include <filesystem>

#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

namespace {

struct FormatName {
  const char* name;
  MeshFormat format;
};
constexpr FormatName kNames[] = {{"vtu", MeshFormat::vtu},     {"off", MeshFormat::off}, {"noff", MeshFormat::noff},
                                 {"ply", MeshFormat::ply},     {"obj", MeshFormat::obj}, {"mesh", MeshFormat::medit},
                                 {"medit", MeshFormat::medit}, {"cxm", MeshFormat::cxm}, {"stl", MeshFormat::stl},
                                 {"msh", MeshFormat::msh}};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

MeshFormat parse_format(const std::string& name) {
  for (const FormatName& f : kNames)
    if (lower(name) == f.name) return f.format;
  throw InputError("unknown format '" + name + "' (known: vtu, off, noff, ply, obj, mesh, cxm, stl, msh)");
}

MeshFormat format_of_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext.size() > 1)
    for (const FormatName& f : kNames)
      if (lower(ext.substr(1)) == f.name) return f.format;
  throw InputError("cannot tell the format of '" + path +
                   "' from its extension: use .vtu, .off, .ply, .obj, .mesh, .cxm, .stl or .msh, or give --format");
}

const char* format_name(MeshFormat format) {
  for (const FormatName& f : kNames)
    if (f.format == format) return f.name;
  return "?";
}

void check_format(MeshFormat format, int d, int m, const WriteOptions& options) {
  if (format == MeshFormat::cxm && options.simplices)
    throw InputError("--simplices: the native format .cxm stores the cells themselves; write another format");
  if ((format == MeshFormat::off || format == MeshFormat::noff || format == MeshFormat::ply) && m < 2)
    throw InputError(std::string(format_name(format)) + " holds polygons, but this is a " + std::to_string(m) +
                     "-manifold: use .vtu, .obj, .mesh or .cxm");
  if (format == MeshFormat::obj && m < 1) throw InputError("obj holds lines and polygons, but this is a 0-manifold");
  if (format == MeshFormat::stl && m != 2 && m != 3)
    throw InputError("stl holds triangles, but this is a " + std::to_string(m) +
                     "-manifold: STL takes surfaces (and the boundary of 3-manifolds); use .msh, .vtu or .cxm");
  if (format == MeshFormat::stl && d != 3 && options.projection.empty())
    throw InputError("stl holds 3D triangles, but the points are in R^" + std::to_string(d) +
                     ": give --project (stereographic, pca or i,j,k)");
  if (format == MeshFormat::msh && (m < 1 || m > 3))
    throw InputError("msh holds lines, triangles and tetrahedra, but this is a " + std::to_string(m) +
                     "-manifold: use .vtu or .cxm");
  if (options.simplices && m > 3)
    throw InputError("--simplices: only curves, surfaces and 3-manifolds are split into simplices; this is a " +
                     std::to_string(m) + "-manifold");
}

// (The other writers take a boundary from the boundary levels, which a stratified complex leaves empty.)
void check_stratified_format(MeshFormat format, int m) {
  const bool polygons = format == MeshFormat::off || format == MeshFormat::noff || format == MeshFormat::ply ||
                        format == MeshFormat::obj || format == MeshFormat::stl;
  if (format != MeshFormat::vtu && format != MeshFormat::cxm && !(polygons && m == 2))
    throw InputError(std::string(format_name(format)) + " cannot hold this manifold with corners (several domains): " +
                     "use .vtu or .cxm" + (m == 2 ? ", .off, .ply, .obj or .stl" : ""));
}

WrittenCounts write_mesh(const std::string& path, MeshFormat format, const CellComplex& cc,
                         const WriteOptions& options) {
  const int d = cc.ambient_dimension, m = cc.manifold_dimension;
  check_format(format, d, m, options);
  if (cc.stratified()) check_stratified_format(format, m);
  if (format == MeshFormat::cxm) {
    write_file_atomically(path, [&](std::ostream& os) { write_native(os, cc, options.native); });
    std::size_t cells = 0;
    for (const auto* levels : {&cc.interior, &cc.boundary})
      for (const CellLevel& l : *levels) cells += l.size();
    return {vertex_count(cc), cells, 0};
  }
  // The projection is resolved first, so that a spec that does not fit d fails before the file exists.
  const bool n_dimensional =
      format == MeshFormat::noff || (format == MeshFormat::off && d != 3 && options.projection.empty());
  // (only "pca" and "stereographic" look at the points: no copy of them for the others)
  const bool fitted = !n_dimensional && (options.projection == "pca" || options.projection == "stereographic");
  const Projection projection =
      make_projection(options.projection, d, fitted ? vertex_coordinates(cc) : std::vector<double>{}, options.pole);
  WrittenCounts counts;
  write_file_atomically(path, [&](std::ostream& os) {
    switch (format) {
      case MeshFormat::vtu:
        counts = write_vtu(os, cc, projection, options.simplices, options.threads, options.native.complete);
        break;
      case MeshFormat::off:
      case MeshFormat::noff:
        counts = write_off(os, cc, projection, n_dimensional, options.simplices);
        break;
      case MeshFormat::ply:
        counts = write_ply(os, cc, projection, options.simplices);
        break;
      case MeshFormat::obj:
        counts = write_obj(os, cc, projection, options.simplices);
        break;
      case MeshFormat::medit:
        counts = write_medit(os, cc, projection);
        break;
      case MeshFormat::stl:
        counts = write_stl(os, cc, projection);
        break;
      case MeshFormat::msh:
        counts = write_msh(os, cc, projection);
        break;
      case MeshFormat::cxm:
        break;
    }
  });
  return counts;
}

}  // namespace coxmesh
