// The .vtu pieces of several processes and their .pvtu manifest; see vtu_pieces.h.
#include "coxmesh/io/vtu_pieces.h"

#include <filesystem>

#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

std::string vtu_piece_path(const std::string& path, int rank) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "_" + std::to_string(rank) + ".vtu")).string();
}

void check_vtu_pieces(const WriteOptions& options) {
  if (options.projection == "pca" || options.projection == "stereographic")
    throw InputError("--project " + options.projection +
                     " depends on the points, which no process has all of: give coordinates (--project i,j,k) or a "
                     "matrix file, or write .cxm pieces and convert them");
}

WrittenCounts write_vtu_piece_file(const std::string& path, int rank, const CellClosure& closure,
                                   std::uint64_t vertices, const WriteOptions& options) {
  check_vtu_pieces(options);
  const CellComplex& cc = closure.cells;
  VtuGlobalIds ids;
  for (const std::vector<std::uint32_t>& level : closure.interior_ids) ids.interior.emplace_back(level);
  for (const std::vector<std::uint32_t>& level : closure.boundary_ids) ids.boundary.emplace_back(level);
  for (const std::uint32_t g : closure.interior_ids[0]) ids.points.push_back(g);
  if (!closure.boundary_ids.empty())
    for (const std::uint32_t g : closure.boundary_ids[0]) ids.points.push_back(vertices + g);
  const Projection projection = make_projection(options.projection, cc.ambient_dimension, {}, options.pole);
  WrittenCounts counts;
  write_file_atomically(vtu_piece_path(path, rank),
                        [&](std::ostream& os) { counts = write_vtu(os, cc, projection, options.simplices, ids); });
  return counts;
}

void write_pvtu_manifest_file(const std::string& path, int pieces, int d, const WriteOptions& options) {
  const bool coordinates = make_projection(options.projection, d, {}, options.pole).changes_points;
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PUnstructuredGrid GhostLevel=\"0\">\n"
      "    <PPointData>\n"
      "      <PDataArray type=\"UInt8\" Name=\"on_boundary\"/>\n";
  if (coordinates)
    xml +=
        "      <PDataArray type=\"Float64\" Name=\"coordinates\" NumberOfComponents=\"" + std::to_string(d) + "\"/>\n";
  xml +=
      "      <PDataArray type=\"UInt64\" Name=\"global_id\"/>\n"
      "    </PPointData>\n"
      "    <PCellData>\n"
      "      <PDataArray type=\"UInt8\" Name=\"dimension\"/>\n"
      "      <PDataArray type=\"UInt8\" Name=\"is_boundary\"/>\n"
      "      <PDataArray type=\"UInt64\" Name=\"domains\"/>\n"
      "      <PDataArray type=\"UInt64\" Name=\"global_id\"/>\n"
      "    </PCellData>\n"
      "    <PPoints>\n"
      "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n";
  for (int r = 0; r < pieces; ++r)
    xml += "    <Piece Source=\"" + std::filesystem::path(vtu_piece_path(path, r)).filename().string() + "\"/>\n";
  xml += "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomically(path, [&](std::ostream& os) { os << xml; });
}

}  // namespace coxmesh
