// The native .cxm format: JSON header line, then little-endian arrays; see native_format.h.
#include "coxmesh/io/native_format.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "coxmesh/io/native_pieces.h"
#include "coxmesh/lattice/faces.h"

namespace coxmesh {

static_assert(std::endian::native == std::endian::little, "the .cxm reader and writer assume a little-endian host");

namespace {

constexpr const char* kMagic = "coxmesh-cxm";
constexpr int kVersion = 2;  // 2: manifolds with corners (domain bitmasks); version 1 files still read

template <class T>
void write_array(std::ostream& os, const T* data, std::size_t n) {
  if (n) os.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
}

nlohmann::json level_json(const CellLevel& level) {
  return {{"cells", level.size()},
          {"facet_entries", level.facet_ids.size()},
          {"boundary_facet", !level.boundary_facet.empty()},
          {"domains", !level.domains.empty()}};
}

struct Reader {
  std::istream& in;
  const std::string& name;

  [[noreturn]] void fail(const std::string& why) const { throw InputError(name + ": " + why); }

  template <class T>
  UninitializedHugeVector<T> array(std::size_t n, const char* what) {
    UninitializedHugeVector<T> v(n);
    if (n) in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in) fail(std::string("truncated file (reading ") + what + ")");
    return v;
  }
};

// A header number that must be an integer in 0..max. get<>() alone would convert a float with a
// cast (undefined behaviour when out of range, e.g. a count written as 3e69) and wrap integers.
std::uint64_t header_integer(const nlohmann::json& v, std::uint64_t max, const Reader& r, const char* what) {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > max)
    r.fail(std::string("bad header: ") + what + " is not an integer in range");
  return v.get<std::uint64_t>();
}

// Checks that a packed key is the canonical form of a simplex of dimension k in R^d.
bool valid_key(const std::uint32_t* key, int d, int k) {
  const Simplex s = unpack(key, d);
  if (s.k != k) return false;
  std::uint32_t seen = 0;
  for (int i = 0; i <= d; ++i) {
    if (s.block[i] > k) return false;
    seen |= 1u << s.block[i];
  }
  if (seen != (k == 31 ? 0xFFFFFFFFu : (1u << (k + 1)) - 1)) return false;
  for (int i = d + 1; i < 4 * ((d + 1 + 3) / 4); ++i)
    if (s.block[i] != 0) return false;
  for (int i = 0; i < d; ++i)
    if (s.y[i] > kMaxLatticeCoordinate || s.y[i] < -kMaxLatticeCoordinate) return false;
  return true;
}

// A facet of a cell (J, σ) is (J, a facet of σ) or, in a stratified complex, (J ∪ {i}, σ).
bool is_stratified_facet(const CellLevel& below, std::uint32_t f, const CellLevel& level, std::uint32_t c, int d) {
  const Simplex face = below.simplices.simplex(f, d), cell = level.simplices.simplex(c, d);
  if (level.domains.empty()) return is_face_of(face, cell);
  const std::uint64_t mine = level.domains[c], theirs = below.domains[f];
  if (theirs == mine) return is_face_of(face, cell);
  return (theirs & mine) == mine && std::popcount(theirs ^ mine) == 1 && face == cell;
}

}  // namespace

void write_native(std::ostream& os, const CellComplex& cc, const NativeInfo& info) {
  const int d = cc.ambient_dimension, m = cc.manifold_dimension;
  nlohmann::json h;
  h["format"] = kMagic;
  h["version"] = kVersion;
  h["ambient_dimension"] = d;
  h["manifold_dimension"] = m;
  h["key_words"] = cc.stratified() ? stratum_key_words(d) : packed_words(d);
  h["domains"] = cc.domain_count;
  h["interior"] = nlohmann::json::array();
  h["boundary"] = nlohmann::json::array();
  for (const CellLevel& l : cc.interior) h["interior"].push_back(level_json(l));
  for (const CellLevel& l : cc.boundary) h["boundary"].push_back(level_json(l));
  h["vertices"] = cc.vertices.size() / std::max(d, 1);
  h["boundary_vertices"] = cc.boundary_vertices.size() / std::max(d, 1);
  h["info"] = {{"source", info.source},   {"complete", info.complete},
               {"message", info.message}, {"matrix", info.matrix},
               {"offset", info.offset},   {"function_evaluations", info.function_evaluations}};
  std::string line = h.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  line.append((8 - (line.size() + 1) % 8) % 8, ' ');
  line += '\n';
  os.write(line.data(), static_cast<std::streamsize>(line.size()));
  for (const auto* levels : {&cc.interior, &cc.boundary})
    for (const CellLevel& l : *levels) {
      if (l.simplices.words() != h["key_words"]) throw InputError("write_native: a level has keys of the wrong width");
      if (l.size()) write_array(os, l.simplices.key(0), static_cast<std::size_t>(l.size()) * l.simplices.words());
      write_array(os, l.facet_offsets.data(), l.facet_offsets.size());
      write_array(os, l.facet_ids.data(), l.facet_ids.size());
      write_array(os, l.boundary_facet.data(), l.boundary_facet.size());
      write_array(os, l.domains.data(), l.domains.size());
    }
  write_array(os, cc.vertices.data(), cc.vertices.size());
  write_array(os, cc.boundary_vertices.data(), cc.boundary_vertices.size());
}

NativeFile read_native(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + path);
  NativeFile pieces;
  if (read_native_manifest(in, path, pieces)) return pieces;  // (written by several processes)
  return read_native(in, path);
}

NativeFile read_native(std::istream& in, const std::string& name) {
  Reader r{in, name};
  // Header: one line, at most 16 MiB (the matrix of a large d is the largest part).
  std::string line;
  for (char c; in.get(c) && c != '\n';) {
    line += c;
    if (line.size() > (16u << 20)) r.fail("not a .cxm file (no header line)");
  }
  if (!in) r.fail("not a .cxm file (no header line)");
  const std::streamoff data_start = in.tellg();
  nlohmann::json h = nlohmann::json::parse(line, nullptr, false);
  if (h.is_object() && h.contains("format") && h["format"] == "coxmesh-cxm-piece")
    r.fail("a piece of a .cxm file written by several processes: read its manifest (NAME.cxm for NAME_<rank>.cxm)");
  if (h.is_discarded() || !h.is_object() || !h.contains("format") || h["format"] != kMagic)
    r.fail("not a .cxm file (bad header)");
  if (!h.contains("version") || (h["version"] != 1 && h["version"] != kVersion))
    r.fail("unsupported .cxm version " + h["version"].dump() + " (this build reads versions 1 and 2)");

  NativeFile out;
  CellComplex& cc = out.cells;
  std::uint64_t expected = 0;                           // bytes of the binary part, from the header
  std::vector<std::array<std::uint64_t, 2>> shapes[2];  // per level: cells, facet entries
  std::vector<bool> has_bf[2], has_domains[2];
  int d = 0, m = 0, words = 0, domain_count = 0;
  std::uint64_t n0 = 0, nb0 = 0;
  try {
    d = static_cast<int>(header_integer(h.at("ambient_dimension"), kMaxDimension, r, "ambient_dimension"));
    m = static_cast<int>(header_integer(h.at("manifold_dimension"), kMaxDimension, r, "manifold_dimension"));
    words = static_cast<int>(header_integer(h.at("key_words"), packed_words(kMaxDimension), r, "key_words"));
    if (h.contains("domains"))
      domain_count = static_cast<int>(header_integer(h.at("domains"), kMaxDomains, r, "domains"));
    if (d < 1 || d > kMaxDimension || m < 0 || m >= d ||
        words != (domain_count ? stratum_key_words(d) : packed_words(d)))
      r.fail("inconsistent dimensions in the header");
    const auto& levels_in = h.at("interior");
    const auto& levels_bd = h.at("boundary");
    if (levels_in.size() != static_cast<std::size_t>(m + 1) ||
        levels_bd.size() != static_cast<std::size_t>(m >= 1 ? m : 0))
      r.fail("the header must list m + 1 interior and m boundary levels");
    int kind = 0;
    for (const auto* levels : {&levels_in, &levels_bd}) {
      for (const auto& l : *levels) {
        const std::uint64_t n = header_integer(l.at("cells"), PackedKeyIndex::kAbsent, r, "cells");
        const std::uint64_t f = header_integer(l.at("facet_entries"), 1ull << 32, r, "facet_entries");
        const bool bf = l.at("boundary_facet").get<bool>();
        const bool masks = l.contains("domains") && l.at("domains").get<bool>();
        if (masks != (domain_count > 0 && kind == 0)) r.fail("bad header: domain bitmasks on the wrong levels");
        has_domains[kind].push_back(masks);
        if (n >= PackedKeyIndex::kAbsent || f >= (1ull << 32)) r.fail("too many cells in a level");
        shapes[kind].push_back({n, f});
        has_bf[kind].push_back(bf);
        expected += 4 * (n * words + n + 1 + f + (bf ? n : 0)) + (masks ? 8 * n : 0);
      }
      ++kind;
    }
    n0 = header_integer(h.at("vertices"), PackedKeyIndex::kAbsent, r, "vertices");
    nb0 = header_integer(h.at("boundary_vertices"), PackedKeyIndex::kAbsent, r, "boundary_vertices");
    if (n0 != shapes[0][0][0] || (m >= 1 && nb0 != shapes[1][0][0]) || (m == 0 && nb0 != 0))
      r.fail("vertex counts do not match the vertex cells");
    expected += 8 * (n0 + nb0) * static_cast<std::uint64_t>(d);
    if (h.contains("info") && h["info"].is_object()) {
      const auto& i = h["info"];
      out.info.source = i.value("source", "");
      out.info.complete = i.value("complete", true);
      out.info.message = i.value("message", "");
      out.info.matrix = i.value("matrix", std::vector<double>{});
      out.info.offset = i.value("offset", std::vector<double>{});
      if (i.contains("function_evaluations"))
        out.info.function_evaluations =
            header_integer(i["function_evaluations"], ~std::uint64_t{0}, r, "function_evaluations");
    }
  } catch (const nlohmann::json::exception& e) {
    r.fail(std::string("bad header: ") + e.what());
  }
  in.seekg(0, std::ios::end);
  const std::uint64_t available = static_cast<std::uint64_t>(in.tellg() - data_start);
  if (available != expected)
    r.fail(available < expected
               ? "truncated file (" + std::to_string(available) + " of " + std::to_string(expected) + " data bytes)"
               : "trailing bytes after the arrays");
  in.seekg(data_start);

  cc.ambient_dimension = d;
  cc.manifold_dimension = m;
  cc.domain_count = domain_count;
  const int k = d - m;
  for (int kind = 0; kind < 2; ++kind) {
    auto& levels = kind == 0 ? cc.interior : cc.boundary;
    for (std::size_t j = 0; j < shapes[kind].size(); ++j) {
      const auto [n, f] = shapes[kind][j];
      CellLevel level;
      level.simplices = PackedKeyIndex(words);
      level.simplices.reserve(n);
      const auto keys = r.array<std::uint32_t>(n * words, "keys");
      const int dim = k + static_cast<int>(j) + kind;  // interior: k + j; boundary: k + 1 + j
      for (std::uint64_t c = 0; c < n; ++c) {
        const std::uint32_t* key = keys.data() + c * words;
        // (a stratified cell of stratum J lies on a simplex of dimension k + |J| + j)
        const std::uint64_t stratum = domain_count ? stratum_of_key(key, d) : 0;
        if ((domain_count < 64 && stratum >> domain_count != 0) || std::popcount(stratum) > m - static_cast<int>(j))
          r.fail("cell " + std::to_string(c) + " of a level lies on domains that do not exist or meet too often");
        if (!valid_key(key, d, dim + std::popcount(stratum)))
          r.fail("cell " + std::to_string(c) + " of a level has an invalid simplex key");
        if (!level.simplices.insert(key).second) r.fail("a simplex key appears twice in one level");
      }
      level.facet_offsets = r.array<std::uint32_t>(n + 1, "facet offsets");
      level.facet_ids = r.array<std::uint32_t>(f, "facet ids");
      if (has_bf[kind][j]) level.boundary_facet = r.array<std::uint32_t>(n, "boundary facets");
      if (has_domains[kind][j]) {
        const auto masks = r.array<std::uint64_t>(n, "domain bitmasks");
        level.domains.assign(masks.begin(), masks.end());
        for (std::uint64_t c = 0; c < n; ++c)
          if (level.domains[c] != stratum_of_key(level.simplices.key(static_cast<std::uint32_t>(c)), d))
            r.fail("cell " + std::to_string(c) + " of a level has domains that do not match its key");
      }
      if (level.facet_offsets[0] != 0 || level.facet_offsets[n] != f)
        r.fail("facet offsets do not match the facet count");
      for (std::uint64_t c = 0; c < n; ++c)
        if (level.facet_offsets[c] > level.facet_offsets[c + 1]) r.fail("facet offsets are not increasing");
      const std::uint64_t below = j == 0 ? 0 : levels[j - 1].size();
      for (std::uint32_t id : level.facet_ids)
        if (id >= below) r.fail("a facet id is out of range");
      // Every incidence must be one of the face relation: distinct facets, each the cell of a facet
      // of the cell's simplex (anything else would make the topology meaningless, or its reduction loop).
      for (std::uint64_t c = 0; j > 0 && c < n; ++c) {
        const auto facets = level.facets(static_cast<std::uint32_t>(c));
        for (std::size_t a = 0; a < facets.size(); ++a) {
          if (std::find(facets.begin(), facets.begin() + a, facets[a]) != facets.begin() + a)
            r.fail("cell " + std::to_string(c) + " of a level lists the same facet twice");
          if (!is_stratified_facet(levels[j - 1], facets[a], level, static_cast<std::uint32_t>(c), d))
            r.fail("cell " + std::to_string(c) + " of a level lists a facet that is not a face of it");
        }
      }
      if (!level.boundary_facet.empty() && (kind != 0 || j == 0))
        r.fail("boundary facets are only allowed on interior levels j >= 1");
      levels.push_back(std::move(level));
    }
  }
  // The boundary facet of an interior cell is the boundary cell on the same simplex.
  for (std::size_t j = 1; j < cc.interior.size(); ++j) {
    const CellLevel& level = cc.interior[j];
    for (std::uint32_t c = 0; c < level.boundary_facet.size(); ++c) {
      const std::uint32_t id = level.boundary_facet[c];
      if (id == CellLevel::kNone) continue;
      if (j - 1 >= cc.boundary.size() || id >= cc.boundary[j - 1].size()) r.fail("a boundary facet id is out of range");
      const std::uint32_t* key = cc.boundary[j - 1].simplices.key(id);
      if (!std::equal(key, key + words, level.simplices.key(c)))
        r.fail("cell " + std::to_string(c) + " of a level has a boundary facet on another simplex");
    }
  }
  cc.vertices = r.array<double>(n0 * d, "vertices");
  cc.boundary_vertices = r.array<double>(nb0 * d, "boundary vertices");
  for (const auto* xs : {&cc.vertices, &cc.boundary_vertices})
    for (double x : *xs)
      if (!std::isfinite(x)) r.fail("a vertex coordinate is NaN or infinite");
  return out;
}

}  // namespace coxmesh
