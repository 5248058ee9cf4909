// The io layer: exact round trip of the native .cxm format, polygon cycles and polyhedron faces,
// surface orientation, every writer read back and counted (OFF, nOFF, PLY, OBJ, medit), atomic
// writes that leave the previous file untouched, and projections.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/atomic_file.h"
#include "coxmesh/io/native_pieces.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

using namespace coxmesh;
namespace fs = std::filesystem;

namespace {

struct Case {
  std::string name;
  FunctionPtr f, domain;
  double edge;
};

CellComplex trace(const Case& c) {
  const Triangulation t = Triangulation::coxeter(c.f->ambient_dimension()).with_longest_edge(c.edge);
  ImplicitOracle oracle(t, c.f, c.domain);
  TraceResult r = trace_manifold(t, oracle, {c.f->seed()});
  EXPECT_EQ(r.status, TraceStatus::complete) << c.name;
  return build_cell_complex(std::move(r));
}

// Curves, surfaces with and without boundary, 3-manifolds with and without boundary, in d = 2..5.
std::vector<Case> catalogue() {
  return {
      {"circle in R^2", sphere(1, 2, 1.0), nullptr, 0.2},
      {"arc in R^3", sphere(1, 3, 1.0), ball_domain({1, 0, 0}, 0.8), 0.2},
      {"sphere in R^3", sphere(2, 3, 1.0), nullptr, 0.3},
      {"torus in R^3", torus(1.0, 0.4), nullptr, 0.15},
      {"cap in R^3", sphere(2, 3, 1.0), ball_domain({1, 0, 0}, 0.9), 0.25},
      {"flat torus in R^4", product(sphere(1, 2, 1.0), sphere(1, 2, 1.0)), nullptr, 0.5},
      {"S^3 in R^4", sphere(3, 4, 1.0), nullptr, 0.6},
      {"cap of S^3 in R^4", sphere(3, 4, 1.0), ball_domain({1, 0, 0, 0}, 1.0), 0.6},
      {"S^3 in R^5 with boundary", sphere(3, 5, 1.0), half_space_domain({-1, 0, 0, 0, 0}, 0.3), 0.8},
      {"S^4 in R^5", sphere(4, 5, 1.0), nullptr, 0.9},
      {"cap of S^4 in R^5", sphere(4, 5, 1.0), ball_domain({1, 0, 0, 0, 0}, 1.0), 0.9},
  };
}

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / ("coxmesh_test_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_levels_equal(const CellLevel& a, const CellLevel& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.simplices.words(), b.simplices.words()) << what;
  if (a.size()) {
    EXPECT_EQ(0, std::memcmp(a.simplices.key(0), b.simplices.key(0), 4ull * a.size() * a.simplices.words())) << what;
  }
  // (read back without a hash table, as build_cell_complex leaves a level: indexed, every key is found at its id)
  PackedKeyIndex index = b.simplices;
  index.reindex();
  for (std::uint32_t c = 0; c < b.size(); ++c) ASSERT_EQ(index.find(index.key(c)), c) << what;
  EXPECT_EQ(a.facet_offsets, b.facet_offsets) << what;
  EXPECT_EQ(a.facet_ids, b.facet_ids) << what;
  EXPECT_EQ(a.boundary_facet, b.boundary_facet) << what;
}

void expect_complexes_equal(const CellComplex& a, const CellComplex& b, const std::string& name) {
  EXPECT_EQ(a.ambient_dimension, b.ambient_dimension);
  EXPECT_EQ(a.manifold_dimension, b.manifold_dimension);
  ASSERT_EQ(a.interior.size(), b.interior.size());
  ASSERT_EQ(a.boundary.size(), b.boundary.size());
  for (std::size_t j = 0; j < a.interior.size(); ++j)
    expect_levels_equal(a.interior[j], b.interior[j], name + " interior " + std::to_string(j));
  for (std::size_t j = 0; j < a.boundary.size(); ++j)
    expect_levels_equal(a.boundary[j], b.boundary[j], name + " boundary " + std::to_string(j));
  EXPECT_EQ(a.vertices, b.vertices);  // bit-exact doubles
  EXPECT_EQ(a.boundary_vertices, b.boundary_vertices);
}

// Tokens of a text file, for the parsers below.
std::vector<std::string> tokens(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

std::size_t complete_count(const Ragged& r) {
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < r.size(); ++i) n += !r[i].empty();
  return n;
}

}  // namespace

// ---- Native format ------------------------------------------------------------------------------

TEST(NativeFormat, RoundTripIsExact) {
  for (const Case& c : catalogue()) {
    const CellComplex cc = trace(c);
    NativeInfo info;
    info.source = "test " + c.name;
    info.complete = false;
    info.message = "a message";
    info.matrix = {1.5, 0.1, -2.25};
    info.offset = {0.3};
    info.function_evaluations = 123456789012ull;
    std::stringstream buffer;
    write_native(buffer, cc, info);
    const std::string bytes = buffer.str();
    const std::size_t header_end = bytes.find('\n') + 1;
    EXPECT_EQ(header_end % 8, 0u) << c.name << ": the arrays start 8-byte aligned";
    const NativeFile back = read_native(buffer, c.name);
    expect_complexes_equal(cc, back.cells, c.name);
    EXPECT_EQ(back.info.source, info.source);
    EXPECT_EQ(back.info.complete, false);
    EXPECT_EQ(back.info.message, info.message);
    EXPECT_EQ(back.info.matrix, info.matrix);
    EXPECT_EQ(back.info.offset, info.offset);
    EXPECT_EQ(back.info.function_evaluations, info.function_evaluations);
    // The same topology, and a second write gives the same bytes.
    const TopologyReport t1 = analyze_topology(cc), t2 = analyze_topology(back.cells);
    EXPECT_EQ(t1.cells, t2.cells);
    EXPECT_EQ(t1.betti, t2.betti);
    EXPECT_EQ(t1.euler_characteristic, t2.euler_characteristic);
    std::stringstream again;
    write_native(again, back.cells, back.info);
    EXPECT_EQ(again.str(), bytes) << c.name;
  }
}

TEST(NativeFormat, FileRoundTripThroughWriteMesh) {
  const fs::path dir = temp_dir();
  const CellComplex cc = trace(catalogue()[4]);
  write_mesh((dir / "cap.cxm").string(), format_of_path("cap.CXM"), cc);
  expect_complexes_equal(cc, read_native((dir / "cap.cxm").string()).cells, "cap");
  fs::remove_all(dir);
}

TEST(NativeFormat, RejectsDamagedFiles) {
  const CellComplex cc = trace(catalogue()[2]);
  std::stringstream buffer;
  write_native(buffer, cc);
  const std::string bytes = buffer.str();
  auto read = [](const std::string& s) {
    std::stringstream in(s);
    return read_native(in, "damaged.cxm");
  };
  EXPECT_THROW(read(bytes.substr(0, bytes.size() - 1)), InputError);                        // truncated
  EXPECT_THROW(read(bytes + "x"), InputError);                                              // trailing bytes
  EXPECT_THROW(read("not a cxm file\n" + bytes.substr(bytes.find('\n') + 1)), InputError);  // bad header
  EXPECT_THROW(read(""), InputError);
  // Header fields of another type than they should have: an error, not an uncaught exception of
  // the JSON library (found by fuzzing a piece's header whose "format" was an array).
  for (const char* header : {R"({"format":[1],"version":1})", R"({"format":"coxmesh-cxm-piece","version":[1]})",
                             R"({"format":"coxmesh-cxm-pieces","version":{}})", R"({"format":null})"}) {
    const std::string text = std::string(header) + "\n";
    EXPECT_THROW(read(text), InputError) << header;
    std::stringstream piece(text), manifest(text);
    EXPECT_THROW(read_native_piece(piece, "damaged_0.cxm"), InputError) << header;
    NativeFile file;
    try {
      EXPECT_FALSE(read_native_manifest(manifest, "damaged.cxm", file)) << header;
    } catch (const InputError&) {  // (a manifest's own header, damaged)
    }
  }
  // A facet id out of range: the first facet id of level 1 (after the level-0 keys and offsets).
  std::string bad = bytes;
  const std::size_t header_end = bytes.find('\n') + 1;
  const std::size_t words = packed_words(3), n0 = cc.interior[0].size(), n1 = cc.interior[1].size();
  const std::size_t first_facet = header_end + 4 * (n0 * words + n0 + 1) + 4 * (n1 * words + n1 + 1);
  const std::uint32_t huge = 0xFFFFFFF0u;
  std::memcpy(bad.data() + first_facet, &huge, 4);
  try {
    read(bad);
    FAIL() << "no error for a facet id out of range";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damaged.cxm"), std::string::npos) << e.what();
  }
  // Incidences that contradict the face relation: an edge whose two end points are the same vertex
  // (a reduction over it never ends), and an edge listing a vertex cell that is not a face of it.
  std::uint32_t f0, f1;
  std::memcpy(&f0, bytes.data() + first_facet, 4);
  std::memcpy(&f1, bytes.data() + first_facet + 4, 4);
  bad = bytes;
  std::memcpy(bad.data() + first_facet + 4, &f0, 4);
  EXPECT_THROW(read(bad), InputError) << "an edge with the same end point twice";
  for (std::uint32_t other = 0; other < n0; ++other) {
    if (other == f0 || other == f1) continue;
    bad = bytes;
    std::memcpy(bad.data() + first_facet + 4, &other, 4);
    try {
      read(bad);
    } catch (const InputError&) {
      continue;  // a vertex cell that is not a face of the edge's simplex
    }
    ADD_FAILURE() << "an edge accepted with end point " << other;
    break;
  }
  // A key that is not a simplex (a block label beyond k).
  bad = bytes;
  bad[header_end + 4 * 3] = 7;
  EXPECT_THROW(read(bad), InputError);
  // A key twice in a level (vertex cell 0's key over vertex cell n0 − 1's), and an edge cell's key
  // over another's: found by the sort of the keys' hashes, which builds no table.
  for (const std::size_t level_start : {header_end, header_end + 4 * (n0 * words + n0 + 1)}) {
    const std::size_t n = level_start == header_end ? n0 : n1;
    bad = bytes;
    std::memcpy(bad.data() + level_start + 4 * words * (n - 1), bytes.data() + level_start, 4 * words);
    try {
      read(bad);
      ADD_FAILURE() << "a repeated key accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("twice"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_native("/nonexistent/file.cxm"), InputError);
}

// A complex cut into pieces as several processes write it (cell c of a level to piece c mod P,
// facet ids global): the manifest reads as the whole complex, and pieces that share cells, miss
// some or disagree are refused with one error.
TEST(NativePieces, ManifestReadsAsTheWholeComplex) {
  const CellComplex cc = trace(catalogue()[4]);  // (a cap: boundary cells and boundary facets)
  const int d = cc.ambient_dimension, words = packed_words(d);
  const auto cut = [&](int pieces) {
    std::vector<CellComplexPart> parts(pieces);
    for (int r = 0; r < pieces; ++r) {
      CellComplexPart& p = parts[r];
      p.cells.ambient_dimension = d;
      p.cells.manifold_dimension = cc.manifold_dimension;
      for (int kind = 0; kind < 2; ++kind)
        for (const CellLevel& l : kind ? cc.boundary : cc.interior) {
          CellLevel mine;
          mine.simplices = PackedKeyIndex(words);
          std::vector<std::uint32_t> ids;
          const bool first_level = &l == &(kind ? cc.boundary : cc.interior)[0];
          for (std::uint32_t c = r; c < l.size(); c += pieces) {
            mine.simplices.insert(l.simplices.key(c));
            for (const std::uint32_t f : l.facets(c)) mine.facet_ids.push_back(f);
            mine.facet_offsets.push_back(static_cast<std::uint32_t>(mine.facet_ids.size()));
            if (!l.boundary_facet.empty()) mine.boundary_facet.push_back(l.boundary_facet[c]);
            ids.push_back(c);
            if (first_level) {
              PointArray& rows = kind ? p.cells.boundary_vertices : p.cells.vertices;
              const PointArray& all = kind ? cc.boundary_vertices : cc.vertices;
              rows.insert(rows.end(), all.begin() + std::size_t{c} * d, all.begin() + std::size_t{c + 1} * d);
            }
          }
          (kind ? p.cells.boundary : p.cells.interior).push_back(std::move(mine));
          (kind ? p.boundary_ids : p.interior_ids).push_back(std::move(ids));
          (kind ? p.boundary_sizes : p.interior_sizes).push_back(l.size());
        }
    }
    return parts;
  };
  const fs::path dir = temp_dir();
  const std::string path = (dir / "cap.cxm").string();
  const auto write = [&](const std::vector<CellComplexPart>& parts) {
    for (std::size_t r = 0; r < parts.size(); ++r) write_native_piece_file(path, static_cast<int>(r), parts[r]);
    write_file_atomically(
        path, [&](std::ostream& os) { write_native_manifest(os, path, static_cast<int>(parts.size()), NativeInfo{}); });
  };
  std::stringstream whole;
  write_native(whole, cc);
  for (const int pieces : {1, 2, 3}) {
    write(cut(pieces));
    const NativeFile back = read_native(path);
    expect_complexes_equal(cc, back.cells, std::to_string(pieces) + " pieces");
    std::stringstream again;
    write_native(again, back.cells);
    EXPECT_EQ(again.str(), whole.str()) << pieces << " pieces";
  }
  const auto refused = [&](std::vector<CellComplexPart> parts, const std::string& why, const std::string& what) {
    write(parts);
    try {
      read_native(path);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << what << ": " << e.what();
    }
  };
  std::vector<CellComplexPart> parts = cut(2);
  parts[1].interior_ids[1][0] = parts[0].interior_ids[1][0];
  refused(parts, "once each", "a cell in two pieces");
  parts = cut(2);
  parts[1].interior_ids[2].back() = static_cast<std::uint32_t>(cc.interior[2].size());
  refused(parts, "once each", "a global id out of range");
  parts = cut(2);
  parts[1].interior_sizes[1] += 1;
  refused(parts, "agree", "pieces of different shapes");
  parts = cut(2);
  for (CellComplexPart& p : parts) p.interior_sizes[1] += 1;
  refused(parts, "once each", "a cell in no piece");
  // A key of one piece repeated in the other (the pieces are right on their own).
  parts = cut(2);
  {
    CellLevel& l = parts[1].cells.interior[1];
    UninitializedHugeVector<std::uint32_t> keys(l.simplices.key(0), l.simplices.key(0) + l.size() * words);
    std::copy_n(parts[0].cells.interior[1].simplices.key(0), words, keys.data());
    l.simplices = PackedKeyIndex::from_keys(words, std::move(keys));
  }
  refused(parts, "twice", "a key in two pieces");
  fs::remove_all(dir);
}

// Header numbers that are not integers in range, found by fuzzing: a count of 3e69 was cast to an
// integer (undefined behaviour), a negative one wrapped around.
TEST(NativeFormat, RejectsHeaderNumbersThatAreNotCounts) {
  const CellComplex cc = trace(catalogue()[2]);
  std::stringstream buffer;
  write_native(buffer, cc);
  const std::string bytes = buffer.str();
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = bytes;
    const std::size_t at = s.find(from);
    EXPECT_LT(at, s.find('\n')) << from;
    return s.replace(at, from.size(), to);
  };
  const auto expect_refused = [](const std::string& s, const std::string& why) {
    std::stringstream in(s);
    try {
      read_native(in, "header.cxm");
      ADD_FAILURE() << "accepted: " << why;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("not an integer"), std::string::npos) << why << ": " << e.what();
    }
  };
  expect_refused(replaced("\"facet_entries\":0", "\"facet_entries\":3088888888888888888888888888888888e40"),
                 "3e69 facets");
  expect_refused(replaced("\"facet_entries\":0", "\"facet_entries\":0.5"), "half a facet");
  expect_refused(replaced("\"ambient_dimension\":3", "\"ambient_dimension\":3.0"), "d = 3.0");
  expect_refused(replaced("\"ambient_dimension\":3", "\"ambient_dimension\":4294967299"), "d = 2^32 + 3");
  expect_refused(replaced("\"vertices\":", "\"vertices\":-1,\"x\":"), "-1 vertices");
  expect_refused(replaced("\"function_evaluations\":", "\"function_evaluations\":1e300,\"x\":"), "1e300 evaluations");
}

// ---- Polygons and polyhedra ---------------------------------------------------------------------

TEST(Polygons, CyclesFollowEdgeCells) {
  for (const Case& c : catalogue()) {
    const CellComplex cc = trace(c);
    if (cc.manifold_dimension < 2) continue;
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
      const Ragged ends = edge_ends(cc, kind);
      for (std::uint32_t e = 0; e < ends.size(); ++e) {
        ASSERT_EQ(ends[e].size(), 2u) << c.name << ": a complete trace has edges with two ends";
        edges.insert(std::minmax(ends[e][0], ends[e][1]));
      }
    }
    const Ragged polygons = polygon_cycles(cc);
    ASSERT_EQ(polygons.size(), cell_count(cc, CellKind::interior, 2) + cell_count(cc, CellKind::boundary, 2));
    const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2), nv = vertex_count(cc);
    for (std::uint32_t p = 0; p < polygons.size(); ++p) {
      const auto cycle = polygons[p];
      ASSERT_GE(cycle.size(), 3u) << c.name << " polygon " << p;
      // As many vertices as edge cells, all distinct, consecutive ones joined by an edge cell.
      const CellLevel& level = p < n2 ? cc.interior[2] : cc.boundary[2];
      const std::uint32_t id = p < n2 ? p : p - n2;
      std::size_t edge_cells = level.facets(id).size();
      if (p < n2 && !level.boundary_facet.empty() && level.boundary_facet[id] != CellLevel::kNone) ++edge_cells;
      EXPECT_EQ(cycle.size(), edge_cells) << c.name;
      EXPECT_EQ(std::set<std::uint32_t>(cycle.begin(), cycle.end()).size(), cycle.size()) << c.name;
      for (std::size_t i = 0; i < cycle.size(); ++i) {
        ASSERT_LT(cycle[i], nv);
        EXPECT_TRUE(edges.count(std::minmax(cycle[i], cycle[(i + 1) % cycle.size()]))) << c.name << " polygon " << p;
      }
    }
  }
}

TEST(Polygons, PolyhedraAreClosed) {
  for (const Case& c : catalogue()) {
    const CellComplex cc = trace(c);
    if (cc.manifold_dimension < 3) continue;
    const Ragged polygons = polygon_cycles(cc);
    for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
      const Ragged faces = polyhedron_faces(cc, kind, polygons);
      ASSERT_EQ(faces.size(), cell_count(cc, kind, 3));
      for (std::uint32_t p = 0; p < faces.size(); ++p) {
        ASSERT_FALSE(faces[p].empty()) << c.name << ": 3-cell " << p << " is not closed";
        // Euler's formula for a convex polyhedron: V − E + F = 2.
        std::set<std::uint32_t> vertices;
        std::size_t edge_uses = 0;
        for (std::uint32_t f : faces[p]) {
          vertices.insert(polygons[f].begin(), polygons[f].end());
          edge_uses += polygons[f].size();
        }
        EXPECT_EQ(
            static_cast<long>(vertices.size()) - static_cast<long>(edge_uses / 2) + static_cast<long>(faces[p].size()),
            2)
            << c.name;
      }
    }
  }
}

// The reference for PolyhedronCursor: at least four faces, none empty, and every edge (pair of
// consecutive vertices of a cycle) counted in exactly two of them.
bool closed_by_counting(std::span<const std::uint32_t> faces, const Ragged& polygons) {
  if (faces.size() < 4) return false;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::uint32_t f : faces) {
    const auto cycle = polygons[f];
    if (cycle.empty()) return false;
    for (std::size_t i = 0; i < cycle.size(); ++i) ++uses[std::minmax(cycle[i], cycle[(i + 1) % cycle.size()])];
  }
  return std::all_of(uses.begin(), uses.end(), [](const auto& u) { return u.second == 2; });
}

// S³ ⊂ R⁴ traced until it reaches 300 simplices: open cells at the edge of the trace.
CellComplex sphere3_stopped_at_300() {
  const Triangulation t = Triangulation::coxeter(4).with_longest_edge(0.6);
  const FunctionPtr f = sphere(3, 4, 1.0);
  ImplicitOracle oracle(t, f, nullptr);
  TraceOptions limit;
  limit.max_simplices = 300;
  TraceResult r = trace_manifold(t, oracle, {f->seed()}, limit);
  EXPECT_EQ(r.status, TraceStatus::max_simplices_reached);
  return build_cell_complex(std::move(r));
}

// The complex with the first face of every seventh interior 3-cell taken away: open 3-cells whose
// polygons are all closed (each a proper part of a convex polyhedron's boundary).
CellComplex with_faces_taken_away(CellComplex cc) {
  CellLevel& level = cc.interior[3];
  IndexArray offsets, ids;
  offsets.push_back(0);
  for (std::uint32_t c = 0; c < level.size(); ++c) {
    const auto facets = level.facets(c);
    for (std::size_t i = c % 7 == 0 ? 1 : 0; i < facets.size(); ++i) ids.push_back(facets[i]);
    offsets.push_back(static_cast<std::uint32_t>(ids.size()));
  }
  level.facet_offsets = std::move(offsets), level.facet_ids = std::move(ids);
  return cc;
}

// Every cell of every 3-level against the reference, with its corners. With `traced` (the cycles of
// a traced complex, complete or cut at a limit: convex cells with some of their faces), the cursor
// told the complex is complete too (Euler's count first) must give the same answers.
void expect_cursor_agrees(const CellComplex& cc, const Ragged& polygons, const std::string& what, int* open = nullptr,
                          bool traced = true) {
  for (CellKind kind : {CellKind::interior, CellKind::boundary})
    for (bool complete : {false, true}) {
      if (complete && !traced) continue;
      PolyhedronCursor cell(cc, kind, polygons, nullptr, complete);
      ASSERT_EQ(cell.size(), cell_count(cc, kind, 3)) << what;
      for (std::uint32_t c = 0; c < cell.size(); ++c) {
        const bool closed = cell.load(c);
        ASSERT_EQ(closed, closed_by_counting(cell.faces(), polygons)) << what << ": 3-cell " << c << ", " << complete;
        if (open && !complete) *open += closed ? 0 : 1;
        if (!closed) continue;
        std::set<std::uint32_t> corners;
        for (std::uint32_t f : cell.faces()) corners.insert(polygons[f].begin(), polygons[f].end());
        ASSERT_EQ(std::vector<std::uint32_t>(corners.begin(), corners.end()),
                  std::vector<std::uint32_t>(cell.corners().begin(), cell.corners().end()))
            << what;
      }
    }
}

TEST(Polygons, PolyhedronCursorMatchesEdgeCounting) {
  for (const Case& c : catalogue()) {
    const CellComplex cc = trace(c);
    if (cc.manifold_dimension < 3) continue;
    Ragged polygons = polygon_cycles(cc);
    expect_cursor_agrees(cc, polygons, c.name);
    // Damaged cycles: one emptied, one missing a vertex, one with a vertex repeated.
    const std::uint32_t n = polygons.size();
    for (std::uint32_t p : {0u, n / 3, n / 2, n - 1}) {
      Ragged damaged;
      for (std::uint32_t q = 0; q < n; ++q) {
        std::vector<std::uint32_t> cycle(polygons[q].begin(), polygons[q].end());
        if (q == p) cycle.clear();
        if (q == p + 1) cycle.pop_back();
        if (q == p + 2) cycle.push_back(cycle[0]);
        damaged.push(cycle);
      }
      int open = 0;
      expect_cursor_agrees(cc, damaged, c.name + ", damaged cycles", &open, false);
      if (cc.manifold_dimension == 3) {
        EXPECT_GT(open, 0) << c.name;
      }
    }
  }
  // A trace stopped at a limit leaves open cells at its edge.
  const CellComplex cut = sphere3_stopped_at_300();
  int open = 0;
  expect_cursor_agrees(cut, polygon_cycles(cut), "S^3 stopped at 300 simplices", &open);
  EXPECT_GT(open, 0);
  const CellComplex opened = with_faces_taken_away(trace(catalogue()[6]));
  open = 0;
  expect_cursor_agrees(opened, polygon_cycles(opened), "S^3 with faces taken away", &open);
  EXPECT_GT(open, 0);
}

TEST(Polygons, PolyhedronCursorWithManyCorners) {
  // Cells of S^3 in R^4 given synthetic faces: two "pillows" (two faces on one cycle each), closed
  // by the edge count, with 64 incidences (a bit mask per corner) and 160 (sorted edge keys); then
  // one face of a pillow replaced by another cycle.
  const CellComplex cc = trace({"S^3 in R^4", sphere(3, 4, 1.0), nullptr, 0.6});
  const Ragged real = polygon_cycles(cc);
  PolyhedronCursor probe(cc, CellKind::interior, real);
  std::uint32_t cell = 0;
  while (cell < probe.size() && (probe.load(cell), probe.faces().size() != 4)) ++cell;
  ASSERT_LT(cell, probe.size());
  const std::vector<std::uint32_t> faces(probe.faces().begin(), probe.faces().end());
  for (std::uint32_t half : {16u, 40u})
    for (bool broken : {false, true}) {
      std::vector<std::vector<std::uint32_t>> cycles(real.size());
      std::vector<std::uint32_t> a(half), b(half);
      ASSERT_GE(vertex_count(cc), 2 * half);
      for (std::uint32_t i = 0; i < half; ++i) a[i] = 2 * i, b[i] = 2 * i + 1;
      cycles[faces[0]] = a, cycles[faces[1]] = a, cycles[faces[2]] = b, cycles[faces[3]] = b;
      if (broken) std::swap(cycles[faces[3]][0], cycles[faces[3]][1]);
      for (auto& cy : cycles)
        if (cy.empty()) cy = {0, 1, 2};
      Ragged polygons;
      for (const auto& cy : cycles) polygons.push(cy);
      for (bool complete : {false, true}) {  // (two pillows: V − E + F = 4, counted edge by edge)
        PolyhedronCursor cursor(cc, CellKind::interior, polygons, nullptr, complete);
        EXPECT_EQ(cursor.load(cell), !broken) << half << " " << broken << " " << complete;
        EXPECT_EQ(closed_by_counting(cursor.faces(), polygons), !broken);
        if (!broken) {
          EXPECT_EQ(cursor.corners().size(), 2 * half);
        }
      }
    }
}

TEST(Polygons, SurfacesAreConsistentlyOrientedOutwards) {
  for (int i : {2, 3, 4}) {
    const Case c = catalogue()[i];
    const CellComplex cc = trace(c);
    const std::vector<double> xs = vertex_coordinates(cc);
    const Ragged polygons = oriented_polygon_cycles(cc, xs.data());
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    double volume = 0;
    for (std::uint32_t p = 0; p < polygons.size(); ++p) {
      const auto cy = polygons[p];
      for (std::size_t k = 0; k < cy.size(); ++k) ++directed[{cy[k], cy[(k + 1) % cy.size()]}];
      const double* a = &xs[3 * cy[0]];
      for (std::size_t k = 1; k + 1 < cy.size(); ++k) {
        const double *b = &xs[3 * cy[k]], *d = &xs[3 * cy[k + 1]];
        volume += a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                  a[2] * (b[0] * d[1] - b[1] * d[0]);
      }
    }
    for (const auto& [e, n] : directed) {
      EXPECT_EQ(n, 1) << c.name << ": an edge is traversed twice in the same direction";
      const auto reverse = directed.find({e.second, e.first});
      if (c.domain == nullptr) {
        EXPECT_TRUE(reverse != directed.end() && reverse->second == 1) << c.name;
      }
    }
    if (c.domain == nullptr) {
      EXPECT_GT(volume, 0) << c.name << ": outward normals enclose a positive volume";
    }
  }
}

// ---- Writers read back --------------------------------------------------------------------------

TEST(Writers, OffPlyObjMeditReadBack) {
  const fs::path dir = temp_dir();
  for (const Case& c : catalogue()) {
    const CellComplex cc = trace(c);
    const int m = cc.manifold_dimension, d = cc.ambient_dimension;
    const std::size_t nv = vertex_count(cc);
    const Ragged polygons = polygon_cycles(cc);
    const std::size_t faces = complete_count(polygons);
    WriteOptions options;
    if (d > 3) options.projection = "pca";

    if (m >= 2) {
      // OFF (3D) or nOFF (R^d): header, counts, vertex ids in range.
      write_mesh((dir / "a.off").string(), MeshFormat::off, cc);
      const auto off = tokens(read_text(dir / "a.off"));
      std::size_t i = 0;
      if (d == 3) {
        ASSERT_EQ(off[i++], "OFF") << c.name;
      } else {
        ASSERT_EQ(off[i++], "nOFF") << c.name;
        ASSERT_EQ(std::stoi(off[i++]), d);
      }
      ASSERT_EQ(std::stoul(off[i++]), nv) << c.name;
      ASSERT_EQ(std::stoul(off[i++]), faces) << c.name;
      ++i;
      i += nv * static_cast<std::size_t>(d);
      for (std::size_t f = 0; f < faces; ++f) {
        const std::size_t n = std::stoul(off[i++]);
        ASSERT_GE(n, 3u);
        for (std::size_t k = 0; k < n; ++k) ASSERT_LT(std::stoul(off[i++]), nv);
      }
      EXPECT_EQ(i, off.size()) << c.name;

      // PLY, binary: header counts, then exactly the bytes they announce.
      write_mesh((dir / "a.ply").string(), MeshFormat::ply, cc, options);
      const std::string ply = read_text(dir / "a.ply");
      const std::size_t body = ply.find("end_header\n") + 11;
      const auto head = tokens(ply.substr(0, body));
      ASSERT_EQ(head[0], "ply");
      EXPECT_EQ(head[2], "binary_little_endian");
      std::size_t nv_ply = 0, nf_ply = 0;
      for (std::size_t t = 0; t + 2 < head.size(); ++t)
        if (head[t] == "element") (head[t + 1] == "vertex" ? nv_ply : nf_ply) = std::stoul(head[t + 2]);
      EXPECT_EQ(nv_ply, nv);
      EXPECT_EQ(nf_ply, faces);
      std::size_t pos = body + 24 * nv;
      for (std::size_t f = 0; f < nf_ply; ++f) {
        const unsigned n = static_cast<unsigned char>(ply[pos]);
        ASSERT_GE(n, 3u);
        for (unsigned k = 0; k < n; ++k) {
          std::int32_t v;
          std::memcpy(&v, ply.data() + pos + 1 + 4 * k, 4);
          ASSERT_LT(static_cast<std::size_t>(v), nv);
        }
        pos += 1 + 4 * n;
      }
      EXPECT_EQ(pos, ply.size()) << c.name;
    } else {
      EXPECT_THROW(write_mesh((dir / "a.off").string(), MeshFormat::off, cc), InputError);
      EXPECT_THROW(write_mesh((dir / "a.ply").string(), MeshFormat::ply, cc), InputError);
    }

    // OBJ: v lines, then f (surfaces) or l (curves) lines with 1-based ids.
    write_mesh((dir / "a.obj").string(), MeshFormat::obj, cc, options);
    std::istringstream obj(read_text(dir / "a.obj"));
    std::size_t v_lines = 0, elements = 0;
    for (std::string line; std::getline(obj, line);) {
      if (line.rfind("v ", 0) == 0) ++v_lines;
      if (line.rfind(m == 1 ? "l " : "f ", 0) == 0) {
        ++elements;
        for (std::size_t k = 1; k < tokens(line).size(); ++k) {
          const std::size_t id = std::stoul(tokens(line)[k]);
          ASSERT_TRUE(id >= 1 && id <= nv);
        }
      }
    }
    EXPECT_EQ(v_lines, nv);
    EXPECT_EQ(elements, m == 1 ? cell_count(cc, CellKind::interior, 1) : faces) << c.name;

    // medit: section counts match the fans and cones built from the cells.
    write_mesh((dir / "a.mesh").string(), MeshFormat::medit, cc, options);
    const auto mesh = tokens(read_text(dir / "a.mesh"));
    std::map<std::string, std::size_t> sections;
    for (std::size_t t = 0; t + 1 < mesh.size(); ++t)
      if (mesh[t] == "Vertices" || mesh[t] == "Edges" || mesh[t] == "Triangles" || mesh[t] == "Tetrahedra") {
        sections[mesh[t]] = std::stoul(mesh[t + 1]);
        const std::size_t arity = mesh[t] == "Vertices" ? 0 : mesh[t] == "Edges" ? 2 : mesh[t] == "Triangles" ? 3 : 4;
        for (std::size_t e = 0; arity && e < sections[mesh[t]]; ++e)
          for (std::size_t k = 0; k < arity; ++k) {
            const std::size_t id = std::stoul(mesh[t + 2 + e * (arity + 1) + k]);
            ASSERT_TRUE(id >= 1 && id <= nv) << c.name;
          }
      }
    EXPECT_EQ(mesh.back(), "End");
    EXPECT_EQ(sections["Vertices"], nv);
    std::size_t triangles = 0, tets = 0;
    const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2);
    if (m == 2 || m == 3)
      for (std::uint32_t p = m == 2 ? 0 : n2; p < polygons.size(); ++p) triangles += polygons[p].size() - 2;
    if (m >= 3)
      for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
        const Ragged cells3 = polyhedron_faces(cc, kind, polygons);
        for (std::uint32_t p = 0; p < cells3.size(); ++p) {
          const std::uint32_t apex = polygons[cells3[p][0]][0];
          for (std::uint32_t f : cells3[p]) {
            const auto cy = polygons[f];
            if (std::find(cy.begin(), cy.end(), apex) == cy.end()) tets += cy.size() - 2;
          }
        }
      }
    EXPECT_EQ(sections["Triangles"], triangles) << c.name;
    EXPECT_EQ(sections["Tetrahedra"], tets) << c.name;
    EXPECT_EQ(sections["Edges"], m == 1   ? cell_count(cc, CellKind::interior, 1)
                                 : m == 2 ? cell_count(cc, CellKind::boundary, 1)
                                          : 0u)
        << c.name;
  }
  fs::remove_all(dir);
}

TEST(Writers, MeditTetrahedraFillTheBallPositively) {
  // The 3-ball {x4 = 0, |x| < 1} in R^4, projected on its first three coordinates: the
  // tetrahedra are positively oriented and their volumes add up to the polyhedral ball's.
  Eigen::MatrixXd n = Eigen::MatrixXd::Zero(4, 1);
  n(3, 0) = 1;
  const Case c{"3-ball", affine_plane(n, Eigen::VectorXd::Zero(4)), ball_domain({0, 0, 0, 0}, 1.0), 0.3};
  const Triangulation t =
      Triangulation::coxeter(4).with_longest_edge(c.edge).with_offset(Eigen::Vector4d(0.01, 0.02, 0.03, 0.0123));
  ImplicitOracle oracle(t, c.f, c.domain);
  const CellComplex cc = build_cell_complex(trace_manifold(t, oracle, {{0.1, 0.1, 0.1, 0.0}}));
  std::stringstream out;
  WriteOptions options;
  const Projection p = make_projection("1,2,3", 4, {});
  write_medit(out, cc, p);
  const auto mesh = tokens(out.str());
  const auto at = std::find(mesh.begin(), mesh.end(), "Vertices") - mesh.begin();
  const std::size_t nv = std::stoul(mesh[at + 1]);
  const auto tt = std::find(mesh.begin(), mesh.end(), "Tetrahedra") - mesh.begin();
  const std::size_t nt = std::stoul(mesh[tt + 1]);
  double total = 0, smallest = 1;
  for (std::size_t e = 0; e < nt; ++e) {
    double v[4][3];
    for (int k = 0; k < 4; ++k) {
      const std::size_t id = std::stoul(mesh[tt + 2 + e * 5 + k]) - 1;
      for (int i = 0; i < 3; ++i) v[k][i] = std::stod(mesh[at + 2 + id * 4 + i]);
    }
    double a[3], b[3], w[3];
    for (int i = 0; i < 3; ++i) a[i] = v[1][i] - v[0][i], b[i] = v[2][i] - v[0][i], w[i] = v[3][i] - v[0][i];
    const double vol =
        (a[0] * (b[1] * w[2] - b[2] * w[1]) - a[1] * (b[0] * w[2] - b[2] * w[0]) + a[2] * (b[0] * w[1] - b[1] * w[0])) /
        6;
    total += vol;
    smallest = std::min(smallest, vol);
  }
  EXPECT_GT(nv, 0u);
  EXPECT_GE(smallest, 0.0);
  EXPECT_NEAR(total, 4.0 / 3.0 * M_PI, 0.3);  // the polyhedral ball is a little smaller
}

// ---- Formats, projections, atomic files ---------------------------------------------------------

TEST(WriteMesh, FormatsByNameAndExtension) {
  EXPECT_EQ(format_of_path("a/b.VTU"), MeshFormat::vtu);
  EXPECT_EQ(format_of_path("x.mesh"), MeshFormat::medit);
  EXPECT_EQ(parse_format("medit"), MeshFormat::medit);
  EXPECT_EQ(parse_format("noff"), MeshFormat::noff);
  EXPECT_THROW(format_of_path("x.step"), InputError);
  EXPECT_THROW(format_of_path("noextension"), InputError);
  EXPECT_THROW(parse_format("step"), InputError);
}

TEST(Projection, SpecsAndErrors) {
  const std::vector<double> pts = {1, 2, 3, 4, 5, 6, 7, 8};  // two points of R^4
  EXPECT_EQ(project_points(make_projection("", 4, pts), pts), (std::vector<double>{1, 2, 3, 5, 6, 7}));
  EXPECT_EQ(project_points(make_projection("4,1", 4, pts), pts), (std::vector<double>{4, 1, 0, 8, 5, 0}));
  EXPECT_FALSE(make_projection("", 3, {}).changes_points);
  EXPECT_TRUE(make_projection("", 2, {}).changes_points);
  EXPECT_THROW(make_projection("1,2,5", 4, pts), InputError);
  EXPECT_THROW(make_projection("0,1,2", 4, pts), InputError);
  EXPECT_THROW(make_projection("1,2,3,4", 4, pts), InputError);
  EXPECT_THROW(make_projection("no-such-file.txt", 4, pts), InputError);
  // PCA: points on a line along (1,1,0,0) project onto the first axis only.
  const std::vector<double> line = {0, 0, 5, 5, 1, 1, 5, 5, 2, 2, 5, 5};
  const std::vector<double> p = project_points(make_projection("pca", 4, line), line);
  EXPECT_NEAR(p[0], -std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(p[6], std::sqrt(2.0), 1e-12);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(std::abs(p[3 * v + 1]) + std::abs(p[3 * v + 2]), 0, 1e-12);
  // Matrix files: 3 rows of d numbers.
  const fs::path dir = temp_dir();
  std::ofstream(dir / "p.txt") << "# projection\n1 0 0 0\n0 1 0 0\n0 0 0 1\n";
  EXPECT_EQ(project_points(make_projection((dir / "p.txt").string(), 4, pts), pts),
            (std::vector<double>{1, 2, 4, 5, 6, 8}));
  EXPECT_THROW(make_projection((dir / "p.txt").string(), 3, pts), InputError);
  std::ofstream(dir / "q.txt") << "1 0 0 0\n0 1 0 0\n";
  EXPECT_THROW(make_projection((dir / "q.txt").string(), 4, pts), InputError);
  fs::remove_all(dir);
}

// The PLY writer reads the vertices where they are only when projecting them would give the same
// bytes: the identity of R³, no boundary vertices, no −0 (which the projection writes as +0).
TEST(Projection, VerticesServeAsTheirOwnProjectionOnlyWhenUnchanged) {
  CellComplex cc;
  cc.ambient_dimension = 3;
  cc.vertices = {1.5, 0.0, -2.0, 3.0, -4.0, 0.25};
  const Projection identity = make_projection("", 3, {});
  EXPECT_EQ(ProjectedVertices(identity, cc).points().data(), cc.vertices.data());
  const ProjectedVertices swapped(make_projection("1,3,2", 3, {}), cc);
  ASSERT_EQ(swapped.points().size(), 6u);
  EXPECT_NE(swapped.points().data(), cc.vertices.data());
  EXPECT_EQ(swapped.points()[1], -2.0);
  cc.vertices[1] = -0.0;
  const ProjectedVertices signed_zero(identity, cc);
  EXPECT_NE(signed_zero.points().data(), cc.vertices.data());
  EXPECT_FALSE(std::signbit(signed_zero.points()[1]));
  EXPECT_EQ(std::vector<double>(signed_zero.points().begin(), signed_zero.points().end()),
            (std::vector<double>{1.5, 0.0, -2.0, 3.0, -4.0, 0.25}));
  cc.vertices[1] = 0.0;
  cc.boundary_vertices = {1, 2, 3};
  const ProjectedVertices with_boundary(identity, cc);
  ASSERT_EQ(with_boundary.points().size(), 9u);
  EXPECT_EQ(with_boundary.points()[6], 1.0);
}

TEST(AtomicFile, ErrorsLeaveThePreviousFileUntouched) {
  const fs::path dir = temp_dir();
  const fs::path target = dir / "out.txt";
  std::ofstream(target) << "previous content";
  EXPECT_THROW(write_file_atomically(target.string(),
                                     [](std::ostream& os) {
                                       os << std::string(1 << 20, 'x');  // more than the buffer: really on disk
                                       throw InputError("writer failed");
                                     }),
               InputError);
  EXPECT_EQ(read_text(target), "previous content");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "the temporary file is removed";
  // A missing directory: an error naming the path.
  try {
    write_file_atomically((dir / "missing" / "out.txt").string(), [](std::ostream& os) { os << "x"; });
    FAIL() << "no error for a missing directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing/out.txt"), std::string::npos) << e.what();
  }
  // A directory in the way: rename fails, nothing is left behind.
  fs::create_directory(dir / "sub");
  EXPECT_THROW(write_file_atomically((dir / "sub").string(), [](std::ostream& os) { os << "x"; }), InputError);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
  // The early check agrees.
  EXPECT_NO_THROW(check_writable(target.string()));
  EXPECT_NO_THROW(check_writable((dir / "new.txt").string()));
  EXPECT_THROW(check_writable((dir / "missing" / "out.txt").string()), InputError);
  EXPECT_THROW(check_writable((dir / "sub").string()), InputError);
  EXPECT_THROW(check_writable((target / "x").string()), InputError);
  // A block bigger than a few slices of writeback (8 MiB) arrives whole, after what came before.
  std::string big(20 * (1 << 20) + 12345, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 2654435761u >> 24);
  write_file_atomically(target.string(), [&](std::ostream& os) { os << "head" << big << "tail"; });
  EXPECT_TRUE(read_text(target) == "head" + big + "tail");
  // Past its first 4 MiB a file goes out with direct I/O in whole 4 KiB blocks: every size around
  // those, written in one block, in pieces that straddle them, or flushed at an odd offset, arrives
  // whole (a lost or doubled tail would show here).
  constexpr std::size_t kMiB = std::size_t{1} << 20;
  for (const std::size_t size : {std::size_t{0}, std::size_t{4095}, std::size_t{4097}, 4 * kMiB - 1, 4 * kMiB,
                                 4 * kMiB + 1, 4 * kMiB + 4096, 9 * kMiB + 123}) {
    const std::string_view data(big.data(), size);
    write_file_atomically(target.string(), [&](std::ostream& os) { os.write(data.data(), data.size()); });
    EXPECT_TRUE(read_text(target) == data) << size << " bytes in one block";
    write_file_atomically(target.string(), [&](std::ostream& os) {
      for (std::size_t at = 0; at < size; at += 1000003) {
        os.write(data.data() + at, std::min<std::size_t>(1000003, size - at));
        if (at % 3 == 0) os.flush();
      }
      for (std::size_t i = 0; i < 5000 && size > 0; ++i) os.put(data[i % size]);
    });
    std::string pieces(data);
    for (std::size_t i = 0; i < 5000 && size > 0; ++i) pieces += data[i % size];
    EXPECT_TRUE(read_text(target) == pieces) << size << " bytes in pieces";
  }
  // Success replaces the content.
  write_file_atomically(target.string(), [](std::ostream& os) { os << "new"; });
  EXPECT_EQ(read_text(target), "new");
  // write_mesh validates the projection before touching the file.
  const CellComplex cc = trace(catalogue()[5]);  // d = 4
  WriteOptions bad;
  bad.projection = "1,2,7";
  EXPECT_THROW(write_mesh(target.string(), MeshFormat::vtu, cc, bad), InputError);
  EXPECT_EQ(read_text(target), "new");
  fs::remove_all(dir);
}

TEST(Vtu, SameBytesForAnyNumberOfWorkers) {
  // 3-cells enough for several ranges per worker (ranges of 4096 cells at least), interior and
  // boundary ones (a cap of S^4 has boundary 3-cells), as polyhedra and as tetrahedra, with global ids.
  for (const Case& c : {Case{"S^3 in R^4", sphere(3, 4, 1.0), nullptr, 0.2},
                        Case{"cap of S^4 in R^5", sphere(4, 5, 1.0), ball_domain({1, 0, 0, 0, 0}, 1.0), 0.45}}) {
    const CellComplex cc = trace(c);
    ASSERT_GT(cell_count(cc, CellKind::interior, 3), 3u * 4096) << c.name;
    const Projection projection = make_projection("", cc.ambient_dimension, {}, {});
    VtuGlobalIds ids;
    for (int j = 0; j < static_cast<int>(cc.interior.size()); ++j)
      ids.interior.push_back(
          std::span<const std::uint32_t>(cc.interior[j].facet_offsets.data(), cc.interior[j].size()));
    for (int j = 0; j < static_cast<int>(cc.boundary.size()); ++j)
      ids.boundary.push_back(
          std::span<const std::uint32_t>(cc.boundary[j].facet_offsets.data(), cc.boundary[j].size()));
    for (std::uint32_t v = 0; v < vertex_count(cc); ++v) ids.points.push_back(3 * v + 1);
    for (bool simplices : {false, true}) {
      std::ostringstream one, with_ids;
      write_vtu(one, cc, projection, simplices, 1);
      write_vtu(with_ids, cc, projection, simplices, ids, 1);
      for (int workers = 2; workers <= 4; ++workers) {
        std::ostringstream several, several_ids;
        write_vtu(several, cc, projection, simplices, workers);
        write_vtu(several_ids, cc, projection, simplices, ids, workers);
        EXPECT_TRUE(several.str() == one.str()) << c.name << ", " << workers << " workers, simplices " << simplices;
        EXPECT_TRUE(several_ids.str() == with_ids.str()) << c.name << ", " << workers << " workers, with ids";
      }
    }
  }
}

TEST(Vtu, CompleteTraceGivesTheSameBytesAsCheckingEveryCell) {
  // Told that the trace is complete, the writer checks a 3-cell by Euler's count instead of edge by
  // edge: the same file, for closed cells with and without boundary, and for a trace stopped at a
  // limit or 3-cells with a face taken away, whose open cells are skipped either way.
  const CellComplex cut = sphere3_stopped_at_300();
  const CellComplex whole = trace(catalogue()[6]), cap = trace(catalogue()[7]);
  const CellComplex opened = with_faces_taken_away(whole);
  for (const auto& [name, cc] : {std::pair<const char*, const CellComplex*>{"S^3 in R^4", &whole},
                                 {"cap of S^3 in R^4", &cap},
                                 {"S^3 stopped at 300 simplices", &cut},
                                 {"S^3 with faces taken away", &opened}}) {
    const Projection projection = make_projection("", cc->ambient_dimension, {}, {});
    for (bool simplices : {false, true}) {
      std::ostringstream checked, trusted;
      const WrittenCounts a = write_vtu(checked, *cc, projection, simplices, 1, false);
      const WrittenCounts b = write_vtu(trusted, *cc, projection, simplices, 2, true);
      EXPECT_TRUE(checked.str() == trusted.str()) << name << ", simplices " << simplices;
      EXPECT_EQ(a.skipped, b.skipped) << name;
      EXPECT_EQ(a.skipped > 0, cc == &cut || cc == &opened) << name;
    }
  }
}
