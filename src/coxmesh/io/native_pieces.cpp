// The .cxm pieces of several processes and their manifest; see native_pieces.h.
#include "coxmesh/io/native_pieces.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/polygons.h"

namespace coxmesh {

namespace {

constexpr const char* kPieceMagic = "coxmesh-cxm-piece";
constexpr const char* kManifestMagic = "coxmesh-cxm-pieces";

template <class T>
void write_array(std::ostream& os, const T* data, std::size_t n) {
  if (n) os.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
}

template <class V>
void read_array(std::istream& in, V& v, std::size_t n, const std::string& name) {
  v.resize(n);
  if (n) in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(v[0])));
  if (!in) throw InputError(name + ": truncated piece");
}

// The header line, padded as in a .cxm file so that the arrays start at a multiple of 8.
void write_header(std::ostream& os, const nlohmann::json& h) {
  std::string line = h.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  line.append((8 - (line.size() + 1) % 8) % 8, ' ');
  line += '\n';
  os.write(line.data(), static_cast<std::streamsize>(line.size()));
}

nlohmann::json read_header(std::istream& in) {
  std::string line;
  for (char c; in.get(c) && c != '\n' && line.size() <= (16u << 20);) line += c;
  return nlohmann::json::parse(line, nullptr, false);
}

}  // namespace

std::string native_piece_path(const std::string& path, int rank) {
  std::filesystem::path p(path);
  const std::string stem = p.stem().string() + "_" + std::to_string(rank) + p.extension().string();
  return (p.parent_path() / stem).string();
}

void write_native_piece(std::ostream& os, const CellComplexPart& part) {
  const CellComplex& cc = part.cells;
  const int d = cc.ambient_dimension;
  nlohmann::json h;
  h["format"] = kPieceMagic;
  h["version"] = 1;
  h["ambient_dimension"] = d;
  h["manifold_dimension"] = cc.manifold_dimension;
  h["key_words"] = packed_words(d);
  for (int kind = 0; kind < 2; ++kind) {
    const auto& levels = kind ? cc.boundary : cc.interior;
    nlohmann::json& list = h[kind ? "boundary" : "interior"] = nlohmann::json::array();
    for (std::size_t j = 0; j < levels.size(); ++j)
      list.push_back({{"cells", levels[j].size()},
                      {"facet_entries", levels[j].facet_ids.size()},
                      {"boundary_facet", !levels[j].boundary_facet.empty()},
                      {"global_cells", (kind ? part.boundary_sizes : part.interior_sizes)[j]}});
  }
  write_header(os, h);
  for (int kind = 0; kind < 2; ++kind) {
    const auto& levels = kind ? cc.boundary : cc.interior;
    for (std::size_t j = 0; j < levels.size(); ++j) {
      const CellLevel& l = levels[j];
      if (l.size()) write_array(os, l.simplices.key(0), std::size_t{l.size()} * l.simplices.words());
      write_array(os, l.facet_offsets.data(), l.facet_offsets.size());
      write_array(os, l.facet_ids.data(), l.facet_ids.size());
      write_array(os, l.boundary_facet.data(), l.boundary_facet.size());
      const std::vector<std::uint32_t>& ids = (kind ? part.boundary_ids : part.interior_ids)[j];
      write_array(os, ids.data(), ids.size());
    }
  }
  write_array(os, cc.vertices.data(), cc.vertices.size());
  write_array(os, cc.boundary_vertices.data(), cc.boundary_vertices.size());
}

CellComplexPart read_native_piece(std::istream& in, const std::string& name) {
  const nlohmann::json h = read_header(in);
  // (Comparisons, not value(): a field of another type would throw outside the checks below.)
  if (!h.is_object() || !h.contains("format") || h["format"] != kPieceMagic || !h.contains("version") ||
      h["version"] != 1)
    throw InputError(name + ": not a piece of a .cxm file");
  CellComplexPart part;
  CellComplex& cc = part.cells;
  try {
    const int d = h.at("ambient_dimension").get<int>(), m = h.at("manifold_dimension").get<int>();
    if (d < 1 || d > kMaxDimension || m < 0 || m >= d || h.at("key_words").get<int>() != packed_words(d))
      throw InputError(name + ": inconsistent dimensions in the header");
    cc.ambient_dimension = d;
    cc.manifold_dimension = m;
    const int words = packed_words(d);
    for (int kind = 0; kind < 2; ++kind) {
      const auto& list = h.at(kind ? "boundary" : "interior");
      if (list.size() != static_cast<std::size_t>(kind ? m : m + 1))
        throw InputError(name + ": the header must list m + 1 interior and m boundary levels");
      for (std::size_t j = 0; j < list.size(); ++j) {
        const auto n = list[j].at("cells").get<std::uint64_t>(), f = list[j].at("facet_entries").get<std::uint64_t>();
        const auto global = list[j].at("global_cells").get<std::uint64_t>();
        if (n > global || global >= PackedKeyIndex::kAbsent || f >= (std::uint64_t{1} << 32))
          throw InputError(name + ": too many cells in a level");
        CellLevel level;
        // (keys only: the assembled complex is checked as a whole, repeated keys included)
        UninitializedHugeVector<std::uint32_t> keys;
        read_array(in, keys, n * words, name);
        level.simplices = PackedKeyIndex::from_keys(words, std::move(keys));
        read_array(in, level.facet_offsets, n + 1, name);
        read_array(in, level.facet_ids, f, name);
        if (list[j].at("boundary_facet").get<bool>()) read_array(in, level.boundary_facet, n, name);
        if (level.facet_offsets[0] != 0 || level.facet_offsets[n] != f)
          throw InputError(name + ": facet offsets do not match the facet count");
        for (std::uint64_t c = 0; c < n; ++c)
          if (level.facet_offsets[c] > level.facet_offsets[c + 1])
            throw InputError(name + ": facet offsets are not increasing");
        std::vector<std::uint32_t> ids;
        read_array(in, ids, n, name);
        (kind ? cc.boundary : cc.interior).push_back(std::move(level));
        (kind ? part.boundary_ids : part.interior_ids).push_back(std::move(ids));
        (kind ? part.boundary_sizes : part.interior_sizes).push_back(global);
      }
    }
    read_array(in, cc.vertices, std::size_t{cc.interior[0].size()} * d, name);
    if (m >= 1) read_array(in, cc.boundary_vertices, std::size_t{cc.boundary[0].size()} * d, name);
    if (in.peek() != std::char_traits<char>::eof()) throw InputError(name + ": trailing bytes after the arrays");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name + ": bad header: " + e.what());
  }
  return part;
}

void write_native_manifest(std::ostream& os, const std::string& path, int pieces, const NativeInfo& info) {
  nlohmann::json h;
  h["format"] = kManifestMagic;
  h["version"] = 1;
  h["pieces"] = nlohmann::json::array();
  for (int r = 0; r < pieces; ++r)
    h["pieces"].push_back(std::filesystem::path(native_piece_path(path, r)).filename().string());
  h["info"] = {{"source", info.source},   {"complete", info.complete},
               {"message", info.message}, {"matrix", info.matrix},
               {"offset", info.offset},   {"function_evaluations", info.function_evaluations}};
  os << h.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

void write_native_piece_file(const std::string& path, int rank, const CellComplexPart& part) {
  write_file_atomically(native_piece_path(path, rank), [&](std::ostream& os) { write_native_piece(os, part); });
}

WrittenCounts write_native_manifest_file(const std::string& path, int pieces, const TopologyReport& counts,
                                         const NativeInfo& info) {
  write_file_atomically(path, [&](std::ostream& os) { write_native_manifest(os, path, pieces, info); });
  std::size_t cells = 0;
  for (const auto* levels : {&counts.cells, &counts.boundary_cells})
    for (const std::size_t n : *levels) cells += n;
  const std::size_t points =
      (counts.cells.empty() ? 0 : counts.cells[0]) + (counts.boundary_cells.empty() ? 0 : counts.boundary_cells[0]);
  return {points, cells, 0};
}

bool read_native_manifest(std::istream& in, const std::string& name, NativeFile& out) {
  const std::streampos start = in.tellg();
  const nlohmann::json h = read_header(in);
  if (!h.is_object() || !h.contains("format") || h["format"] != kManifestMagic) {
    in.clear();
    in.seekg(start);
    return false;
  }
  std::vector<CellComplexPart> parts;
  NativeInfo info;
  try {
    if (h.value("version", 0) != 1) throw InputError(name + ": unsupported manifest version");
    const std::filesystem::path dir = std::filesystem::path(name).parent_path();
    for (const auto& piece : h.at("pieces")) {
      const std::string file = piece.get<std::string>();
      if (file.empty() || std::filesystem::path(file).filename() != file)
        throw InputError(name + ": a piece is not a file name in the manifest's directory");
      const std::string path = (dir / file).string();
      std::ifstream pin(path, std::ios::binary);
      if (!pin) throw InputError(name + ": cannot open its piece " + path);
      parts.push_back(read_native_piece(pin, path));
    }
    const auto& i = h.at("info");
    info.source = i.value("source", "");
    info.complete = i.value("complete", true);
    info.message = i.value("message", "");
    info.matrix = i.value("matrix", std::vector<double>{});
    info.offset = i.value("offset", std::vector<double>{});
    info.function_evaluations = i.value("function_evaluations", std::uint64_t{0});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name + ": bad manifest: " + e.what());
  }
  // The checks of read_native, on the complex that one process would have written (in memory:
  // writing it out and reading it back cost a copy of the file and a second reading).
  try {
    out.cells = assemble_cell_complex(std::move(parts));
  } catch (const InputError& e) {
    throw InputError(name + ": " + e.what());
  }
  check_native(out.cells, name);
  out.info = std::move(info);
  return true;
}

}  // namespace coxmesh
