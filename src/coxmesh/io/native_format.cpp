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

// The checks of a complex read from a file (or assembled from pieces), in one pass per level over
// arrays in memory: the keys on their words, repeated keys by a sort of their hashes, the incidences
// by the facet test on packed keys. No hash table, no unpacked simplex, no allocation per cell.
class ComplexChecker {
 public:
  ComplexChecker(const CellComplex& cc, const std::string& name) : cc_(cc), name_(name) {}

  void check() const {
    const int d = cc_.ambient_dimension, m = cc_.manifold_dimension;
    if (d < 1 || d > kMaxDimension || m < 0 || m >= d || cc_.domain_count < 0 || cc_.domain_count > kMaxDomains ||
        cc_.interior.size() != static_cast<std::size_t>(m + 1) ||
        cc_.boundary.size() != static_cast<std::size_t>(m >= 1 ? m : 0))
      fail("inconsistent dimensions");
    for (int kind = 0; kind < 2; ++kind) {
      const auto& levels = kind == 0 ? cc_.interior : cc_.boundary;
      for (std::size_t j = 0; j < levels.size(); ++j) check_level(levels, j, kind);
    }
    check_boundary_facets();
    const std::uint64_t n0 = cc_.interior[0].size(), nb0 = m >= 1 ? cc_.boundary[0].size() : 0;
    if (cc_.vertices.size() != n0 * d || cc_.boundary_vertices.size() != nb0 * d)
      fail("vertex counts do not match the vertex cells");
    for (const auto* xs : {&cc_.vertices, &cc_.boundary_vertices}) {
      bool finite = true;  // (branch-free: all are read anyway)
      for (const double x : *xs) finite &= std::isfinite(x);
      if (!finite) fail("a vertex coordinate is NaN or infinite");
    }
  }

 private:
  void check_level(const std::vector<CellLevel>& levels, std::size_t j, int kind) const {
    const int d = cc_.ambient_dimension, m = cc_.manifold_dimension, domains = cc_.domain_count;
    const int words = domains ? stratum_key_words(d) : packed_words(d);
    const CellLevel& level = levels[j];
    const std::uint64_t n = level.size();
    if (level.simplices.words() != words) fail("a level has keys of the wrong width");
    const int dim = d - m + static_cast<int>(j) + kind;  // interior: k + j; boundary: k + 1 + j
    UninitializedHugeVector<std::uint64_t> entries(n);   // (hashed here, while the key is in the cache)
    for (std::uint32_t c = 0; c < n; ++c) {
      const std::uint32_t* key = level.simplices.key(c);
      // (a stratified cell of stratum J lies on a simplex of dimension k + |J| + j)
      int on_domains = 0;
      if (domains) {
        const std::uint64_t stratum = stratum_of_key(key, d);
        on_domains = std::popcount(stratum);
        if ((domains < 64 && stratum >> domains != 0) || on_domains > m - static_cast<int>(j))
          fail("cell " + std::to_string(c) + " of a level lies on domains that do not exist or meet too often");
      }
      if (!is_packed_simplex(key, d, dim + on_domains))
        fail("cell " + std::to_string(c) + " of a level has an invalid simplex key");
      entries[c] = PackedKeyIndex::repeat_entry(key, words, c);
    }
    if (level.simplices.repeated_key(std::move(entries)) != PackedKeyIndex::kAbsent)
      fail("a simplex key appears twice in one level");
    if (level.domains.size() != (domains > 0 && kind == 0 ? n : 0)) fail("domain bitmasks on the wrong levels");
    for (std::uint64_t c = 0; c < level.domains.size(); ++c)
      if (level.domains[c] != stratum_of_key(level.simplices.key(static_cast<std::uint32_t>(c)), d))
        fail("cell " + std::to_string(c) + " of a level has domains that do not match its key");
    if (level.facet_offsets.size() != n + 1 || level.facet_offsets[0] != 0 ||
        level.facet_offsets[n] != level.facet_ids.size())
      fail("facet offsets do not match the facet count");
    for (std::uint64_t c = 0; c < n; ++c)
      if (level.facet_offsets[c] > level.facet_offsets[c + 1]) fail("facet offsets are not increasing");
    const std::uint64_t below = j == 0 ? 0 : levels[j - 1].size();
    std::uint32_t largest = 0;
    for (const std::uint32_t id : level.facet_ids) largest = std::max(largest, id);
    if (!level.facet_ids.empty() && largest >= below) fail("a facet id is out of range");
    if (j > 0) check_incidences(levels[j - 1], level);
    if (!level.boundary_facet.empty() && (kind != 0 || j == 0 || level.boundary_facet.size() != n))
      fail("boundary facets are only allowed on interior levels j >= 1");
  }

  // Every incidence must be one of the face relation: distinct facets, each the cell of a facet of
  // the cell's simplex (anything else would make the topology meaningless, or its reduction loop).
  // A facet of a cell (J, σ) is (J, a facet of σ) or, in a stratified complex, (J ∪ {i}, σ). Facet
  // cells of one level have distinct keys (checked before), so they are distinct exactly when the
  // facets of σ they lie on (the j of facet_without) and the domains they add are: a bit each.
  void check_incidences(const CellLevel& below, const CellLevel& level) const {
    const int d = cc_.ambient_dimension, simplex_words = packed_words(d);
    const bool stratified = !level.domains.empty();
    // The facets are cells of the level below, here and there in it: their keys are fetched some
    // incidences ahead (a cache miss each otherwise).
    constexpr std::size_t kAhead = 16;
    const std::uint32_t* ids = level.facet_ids.data();
    const std::size_t entries = level.facet_ids.size();
    for (std::uint32_t c = 0; c < level.size(); ++c) {
      const std::uint32_t* sigma = level.simplices.key(c);
      std::uint64_t faces = 0, added_domains = 0;
      for (std::size_t e = level.facet_offsets[c]; e < level.facet_offsets[c + 1]; ++e) {
        if (e + kAhead < entries) __builtin_prefetch(below.simplices.key(ids[e + kAhead]));
        const std::uint32_t f = ids[e], *tau = below.simplices.key(f);
        bool repeated;
        if (!stratified || below.domains[f] == level.domains[c]) {
          const int j = packed_facet_index(tau, sigma, d);
          if (j < 0) fail_cell(c, "lists a facet that is not a face of it");
          repeated = faces >> j & 1;
          faces |= std::uint64_t{1} << j;
        } else {
          const std::uint64_t mine = level.domains[c], theirs = below.domains[f];
          if ((theirs & mine) != mine || std::popcount(theirs ^ mine) != 1 ||
              !std::equal(tau, tau + simplex_words, sigma))
            fail_cell(c, "lists a facet that is not a face of it");
          repeated = (added_domains & (theirs ^ mine)) != 0;
          added_domains |= theirs ^ mine;
        }
        if (repeated) fail_cell(c, "lists the same facet twice");
      }
    }
  }

  // The boundary facet of an interior cell is the boundary cell on the same simplex.
  void check_boundary_facets() const {
    const int words = cc_.interior[0].simplices.words();
    for (std::size_t j = 1; j < cc_.interior.size(); ++j) {
      const CellLevel& level = cc_.interior[j];
      for (std::uint32_t c = 0; c < level.boundary_facet.size(); ++c) {
        const std::uint32_t id = level.boundary_facet[c];
        if (id == CellLevel::kNone) continue;
        if (j - 1 >= cc_.boundary.size() || id >= cc_.boundary[j - 1].size())
          fail("a boundary facet id is out of range");
        const std::uint32_t* key = cc_.boundary[j - 1].simplices.key(id);
        if (!std::equal(key, key + words, level.simplices.key(c)))
          fail_cell(c, "has a boundary facet on another simplex");
      }
    }
  }

  [[noreturn]] void fail(const std::string& why) const { throw InputError(name_ + ": " + why); }
  [[noreturn]] void fail_cell(std::uint64_t c, const char* what) const {
    fail("cell " + std::to_string(c) + " of a level " + what);
  }

  const CellComplex& cc_;
  const std::string& name_;
};

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

void check_native(const CellComplex& cc, const std::string& name) { ComplexChecker(cc, name).check(); }

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
  // Everything is read first (the sizes are those of the header, checked against the file's), then
  // checked as a whole.
  for (int kind = 0; kind < 2; ++kind) {
    auto& levels = kind == 0 ? cc.interior : cc.boundary;
    for (std::size_t j = 0; j < shapes[kind].size(); ++j) {
      const auto [n, f] = shapes[kind][j];
      CellLevel level;
      level.simplices = PackedKeyIndex::from_keys(words, r.array<std::uint32_t>(n * words, "keys"));
      level.facet_offsets = r.array<std::uint32_t>(n + 1, "facet offsets");
      level.facet_ids = r.array<std::uint32_t>(f, "facet ids");
      if (has_bf[kind][j]) level.boundary_facet = r.array<std::uint32_t>(n, "boundary facets");
      if (has_domains[kind][j]) {
        const auto masks = r.array<std::uint64_t>(n, "domain bitmasks");
        level.domains.assign(masks.begin(), masks.end());
      }
      levels.push_back(std::move(level));
    }
  }
  cc.vertices = r.array<double>(n0 * d, "vertices");
  cc.boundary_vertices = r.array<double>(nb0 * d, "boundary vertices");
  ComplexChecker(cc, name).check();
  return out;
}

}  // namespace coxmesh
