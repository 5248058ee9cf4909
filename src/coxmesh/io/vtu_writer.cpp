// VTK XML UnstructuredGrid writer (raw appended data); see mesh_formats.h and docs/formats.md.
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "coxmesh/errors.h"
#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/simplices.h"
#include "coxmesh/util/huge_page_allocator.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

static_assert(std::endian::native == std::endian::little, "the VTU writer declares LittleEndian data");

namespace {

constexpr std::uint8_t kVertex = 1, kLine = 3, kTriangle = 5, kPolygon = 7, kTetrahedron = 10, kPolyhedron = 42;

// The pages of a big block (from HugePageAllocator: 2 MiB-aligned, whole 2 MiB pages) that its
// vector's end is about to reach, written kFaultInChunk bytes at a time in one call, up front:
// written one by one they cost a page fault each (the face stream of T³: 23,000 of them). A chunk
// of 256 KiB keeps what is faulted in beyond the end small in each of the pieces the workers fill.
// `ready`: the bytes written so far.
constexpr std::size_t kFaultInChunk = std::size_t{256} << 10;

template <class T>
void fault_in_ahead(const UninitializedHugeVector<T>& v, std::size_t& ready) {
#if defined(MADV_POPULATE_WRITE) && !defined(__SANITIZE_ADDRESS__)
  using Allocator = HugePageAllocator<T>;
  const std::size_t held = v.capacity() * sizeof(T);
  // (a small block: operator new's; half a chunk ahead, so that the array's end never waits)
  if (v.size() * sizeof(T) + kFaultInChunk / 2 < ready || held < Allocator::kPage) return;
  const std::size_t end = std::min(ready + kFaultInChunk, Allocator::round_up(held));
  if (end > ready) madvise(reinterpret_cast<char*>(const_cast<T*>(v.data())) + ready, end - ready, MADV_POPULATE_WRITE);
  ready = end;
#else
  (void)v, (void)ready;
#endif
}

// The cells of the grid, built up cell by cell; Index is the type of the connectivity, offsets and
// faces arrays (Int32 where every number fits: half the bytes to build, copy and store).
template <class Index>
struct Grid {
  // (faces: resized, then written, a cell at a time; big arrays mapped, not zeroed)
  UninitializedHugeVector<Index> connectivity, offsets, faces, faceoffsets;
  std::vector<std::uint8_t> types, dimension, is_boundary;
  std::vector<std::uint64_t> domains;  // bit i: the cell lies on D_{i+1} = 0 (a boundary cell of one domain: 1)
  bool has_polyhedra = false;
  std::size_t connectivity_ready = 0, faces_ready = 0;  // (fault_in_ahead)
  // With global ids (a piece of a larger mesh): the id of each cell added, `source` when it is added.
  const VtuGlobalIds* ids = nullptr;
  std::vector<std::uint64_t> global;
  std::uint64_t source = 0;

  // The cell c of level j of a kind is the next to be added.
  void from(CellKind kind, int j, std::uint32_t c) {
    if (ids) source = (kind == CellKind::boundary ? ids->boundary : ids->interior)[j][c];
  }

  void add(std::uint8_t type, int dim, std::uint64_t on_domains, std::span<const std::uint32_t> points) {
    if (ids) global.push_back(source);
    connectivity.insert(connectivity.end(), points.begin(), points.end());
    offsets.push_back(static_cast<Index>(connectivity.size()));
    types.push_back(type);
    dimension.push_back(static_cast<std::uint8_t>(dim));
    is_boundary.push_back(on_domains != 0 ? 1 : 0);
    domains.push_back(on_domains);
    faceoffsets.push_back(-1);
  }

  // Room for the cells of the complex (an estimate when cells are split into simplices), so that
  // the arrays grow once instead of being copied into fresh memory again and again.
  void reserve(const CellComplex& cc, int p, bool simplices) {
    std::size_t cells = 0, corners = 0;
    for (CellKind kind : {CellKind::interior, CellKind::boundary})
      for (int j = 0; j <= p; ++j)
        if (const CellLevel* level = cell_level(cc, kind, j)) {
          const std::size_t n = level->size(), incidences = level->facet_ids.size() + level->boundary_facet.size();
          const std::size_t per_cell = j == 2 ? 2 : 3;  // (s sides: s − 2 triangles)
          const std::size_t split = simplices && j >= 2 ? std::max(incidences, per_cell * n) - per_cell * n : n;
          cells += split, corners += j == 0 ? n : (simplices && j >= 2 ? (j + 1) * split : incidences);
        }
    connectivity.reserve(corners), offsets.reserve(cells), types.reserve(cells), dimension.reserve(cells);
    is_boundary.reserve(cells), domains.reserve(cells), faceoffsets.reserve(cells);
  }
};

// Two doubles in one SSE2 register (a GCC/Clang vector): one division instruction for both.
using Pair = double __attribute__((vector_size(16)));

// Adds the closed 3-cell at `cell` as a VTK polyhedron with faces turned outwards (Newell normal
// against the direction from the cell's centroid to the face's centroid). The face stream is
// written in place, one resize per cell (its room is reserved by the caller).
template <class Index>
void add_polyhedron(Grid<Index>& g, std::uint64_t domains, const PolyhedronCursor& cell, const Ragged& polygons,
                    const double* p3) {
  const auto corners = cell.corners();
  const auto faces = cell.faces();
  // The centroids as sums of quotients, x and y in one packed division (the quotients are the
  // same, bit for bit, as one at a time).
  const double n = static_cast<double>(corners.size());
  Pair centre_xy{0, 0};
  double centre_z = 0;
  for (std::uint32_t v : corners) {
    const double* p = p3 + 3 * std::size_t{v};
    centre_xy += Pair{p[0], p[1]} / Pair{n, n};
    centre_z += p[2] / n;
  }
  g.add(kPolyhedron, 3, domains, corners);
  g.has_polyhedra = true;
  const std::size_t at = g.faces.size();
  g.faces.resize(at + 1 + faces.size() + cell.incidences());
  Index* out = g.faces.data() + at;
  *out++ = static_cast<Index>(faces.size());
  for (std::uint32_t f : faces) {
    const auto cycle = polygons[f];
    const std::size_t k = cycle.size();
    // (the divisions as they are: a projected cell can be flat, and its faces' orientation then
    // hangs on the last bit, which the file must keep)
    std::array<double, 3> normal{0, 0, 0};
    const double kd = static_cast<double>(k);
    Pair mid_xy{0, 0};
    double mid_z = 0;
    // (each corner read once: the end b of one side is the start a of the next)
    const double* first = p3 + 3 * std::size_t{cycle[0]};
    double a[3] = {first[0], first[1], first[2]};
    for (std::size_t i = 0; i < k; ++i) {
      const double* next = p3 + 3 * std::size_t{cycle[i + 1 < k ? i + 1 : 0]};
      const double b[3] = {next[0], next[1], next[2]};
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
      mid_xy += Pair{a[0], a[1]} / Pair{kd, kd};
      mid_z += a[2] / kd;
      a[0] = b[0], a[1] = b[1], a[2] = b[2];
    }
    double dot = 0;  // (summed in the order x, y, z)
    dot += normal[0] * (mid_xy[0] - centre_xy[0]);
    dot += normal[1] * (mid_xy[1] - centre_xy[1]);
    dot += normal[2] * (mid_z - centre_z);
    // Reversed when dot < 0: c0, c(k−1), …, c1, corner j read from k − j instead of j. (An index,
    // not a branch: the sign follows the geometry, and a branch on it is mispredicted half the time.)
    const std::size_t reversed = -static_cast<std::size_t>(dot < 0);
    *out++ = static_cast<Index>(k);
    *out++ = static_cast<Index>(cycle[0]);
    for (std::size_t j = 1; j < k; ++j) *out++ = static_cast<Index>(cycle[j + (reversed & (k - 2 * j))]);
  }
  g.faceoffsets.back() = static_cast<Index>(g.faces.size());
  fault_in_ahead(g.faces, g.faces_ready);
  fault_in_ahead(g.connectivity, g.connectivity_ready);
}

// One appended-data block: UInt64 byte count, then the bytes, those of one array or of several one
// after the other (written from where they are: no copy joins them).
struct Block {
  std::string xml;  // the DataArray element, without its offset attribute
  std::vector<std::span<const std::byte>> parts;
  std::uint64_t bytes() const {
    std::uint64_t n = 0;
    for (const auto& part : parts) n += part.size();
    return n;
  }
};

template <class V>
Block block(std::string xml, const V& v, const V& then = {}) {
  return {std::move(xml),
          {std::as_bytes(std::span(v.data(), v.size())), std::as_bytes(std::span(then.data(), then.size()))}};
}

// The block of one array of the grid, made of the pieces' arrays in order.
template <class Index, class V>
Block block(std::string xml, const std::deque<Grid<Index>>& pieces, V Grid<Index>::*array) {
  Block b{std::move(xml), {}};
  for (const Grid<Index>& piece : pieces)
    b.parts.push_back(std::as_bytes(std::span((piece.*array).data(), (piece.*array).size())));
  return b;
}

// Where a piece's connectivity and face stream start in the whole arrays, added to its offsets
// (the faceoffsets of cells without faces stay −1).
template <class Index>
void join_offsets(std::deque<Grid<Index>>& pieces) {
  std::size_t corners = 0, faces = 0;
  for (Grid<Index>& piece : pieces) {
    if (corners > 0)
      for (Index& o : piece.offsets) o += static_cast<Index>(corners);
    if (faces > 0)
      for (Index& o : piece.faceoffsets)
        if (o != -1) o += static_cast<Index>(faces);
    corners += piece.connectivity.size(), faces += piece.faces.size();
  }
}

// A bound on the length of the face stream of 3-cells begin .. end − 1 of one kind.
std::size_t face_stream_bound(const CellLevel& level, CellKind kind, const Ragged& polygons, std::uint32_t n2,
                              std::uint32_t begin, std::uint32_t end) {
  const bool closing = kind == CellKind::interior && !level.boundary_facet.empty();  // (a boundary face too)
  const std::uint32_t shift = kind == CellKind::boundary ? n2 : 0;
  std::size_t n = 0;
  for (std::uint32_t c = begin; c < end; ++c) {
    n += 1 + level.facet_offsets[c + 1] - level.facet_offsets[c];
    for (std::uint32_t f : level.facets(c)) n += polygons.offsets[shift + f + 1] - polygons.offsets[shift + f];
    if (closing && level.boundary_facet[c] != CellLevel::kNone)
      n += 1 + polygons.offsets[n2 + level.boundary_facet[c] + 1] - polygons.offsets[n2 + level.boundary_facet[c]];
  }
  return n;
}

// Polygons of at most kShortCycle corners (as a rule they have 3 to 6): the face stream is bounded
// from the cells' facet counts alone, without reading every face's length, and the room it
// reserves beyond the stream is address space only, never written.
constexpr std::uint32_t kShortCycle = 8;

// A bound on the length of the face stream of 3-cells begin .. end − 1 of one kind when no polygon
// has more than `longest` corners.
std::size_t short_face_stream_bound(const CellLevel& level, CellKind kind, std::uint32_t longest, std::uint32_t begin,
                                    std::uint32_t end) {
  const bool closing = kind == CellKind::interior && !level.boundary_facet.empty();  // (a boundary face too)
  const std::size_t cells = end - begin;
  const std::size_t faces = level.facet_offsets[end] - level.facet_offsets[begin] + (closing ? cells : 0);
  return cells + faces * (1 + std::size_t{longest});
}

// Whether every number of the connectivity, offsets and faces arrays fits in Int32: a bound from
// the cells written (dimension ≤ p) and their incidences. A polygon is a face of at most two
// polyhedra, and a polygon or polyhedron split into simplices has fewer corners than 4 × its
// incidences, so 8 × (cells + incidences) + vertices bounds every count, id and offset.
bool fits_int32(const CellComplex& cc, int p) {
  std::uint64_t total = vertex_count(cc);
  for (CellKind kind : {CellKind::interior, CellKind::boundary})
    for (int j = 0; j <= p; ++j)
      if (const CellLevel* level = cell_level(cc, kind, j))
        total += 8 * (level->size() + level->facet_ids.size() + level->boundary_facet.size());
  return total <= static_cast<std::uint64_t>(INT32_MAX);
}

template <class Index>
WrittenCounts write_vtu_as(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices,
                           const VtuGlobalIds* ids, int threads, bool complete) {
  const std::string index_type = sizeof(Index) == 4 ? "Int32" : "Int64";
  const int d = cc.ambient_dimension, m = cc.manifold_dimension;
  const ProjectedVertices projected(projection, cc);
  const std::span<const double> p3 = projected.points();
  const std::uint32_t n0 = cell_count(cc, CellKind::interior, 0), nv = vertex_count(cc);
  WrittenCounts counts;
  counts.points = nv;

  // The grid in pieces, written one after the other: the 3-cells' in order, then the rest's (g).
  std::deque<Grid<Index>> pieces(1);
  Grid<Index>& g = pieces.back();
  g.ids = ids;
  const int p = std::min(m, 3);
  g.reserve(cc, p == 3 ? 2 : p, simplices);  // (3-cells: in pieces of their own)
  auto add_level = [&](CellKind kind, int dim) {
    const bool boundary = kind == CellKind::boundary;
    if (dim == 0) {
      for (std::uint32_t c = 0; c < cell_count(cc, kind, 0); ++c) {
        const std::uint32_t v = boundary ? n0 + c : c;
        g.from(kind, 0, c);
        g.add(kVertex, 0, boundary, std::span(&v, 1));
      }
    } else if (dim == 1) {
      const Ragged ends = edge_ends(cc, kind);
      for (std::uint32_t c = 0; c < ends.size(); ++c)
        if (ends[c].size() == 2) {
          g.from(kind, 1, c);
          g.add(kLine, 1, boundary, ends[c]);
        } else {
          ++counts.skipped;
        }
    }
  };
  // A polygon as itself, or (simplices) as its fan triangles.
  auto add_polygon = [&](std::uint64_t domains, std::span<const std::uint32_t> cycle) {
    if (!simplices) return g.add(kPolygon, 2, domains, cycle);
    for_each_fan_triangle(cycle, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      const std::array<std::uint32_t, 3> t{a, b, c};
      g.add(kTriangle, 2, domains, t);
    });
  };
  // A stratified complex keeps every stratum in the interior levels: below the top dimension, each
  // stratum's own cells are written with their bitmasks (the faces' (m−1)-cells, the edges where
  // two faces meet, the corners).
  const auto domains_of = [&](int j, std::uint32_t c) { return cc.stratified() ? cc.interior[j].domains[c] : 0; };
  auto add_strata = [&](const Ragged* polygons) {
    if (!cc.stratified() || m > 3) return;
    for (int j = 0; j < m; ++j) {
      const CellLevel& level = cc.interior[j];
      const Ragged ends = j == 1 ? edge_ends(cc, CellKind::interior) : Ragged{};
      for (std::uint32_t c = 0; c < level.size(); ++c) {
        const std::uint64_t on = level.domains[c];
        if (std::popcount(on) != m - j) continue;
        if (j == 0) {
          g.add(kVertex, 0, on, std::span(&c, 1));
        } else if (j == 1 && ends[c].size() == 2) {
          g.add(kLine, 1, on, ends[c]);
        } else if (j == 2 && !(*polygons)[c].empty()) {
          add_polygon(on, (*polygons)[c]);
        }
      }
    }
  };
  if (p <= 1) {
    add_level(CellKind::interior, p);
    if (m == 1) add_level(CellKind::boundary, 0);
    add_strata(nullptr);
  } else {
    const Ragged polygons = oriented_polygon_cycles(cc, p3.data());
    const std::uint32_t n2 = cell_count(cc, CellKind::interior, 2);
    if (p == 2) {
      for (std::uint32_t c = 0; c < polygons.size(); ++c)
        if (!polygons[c].empty()) {
          c >= n2 ? g.from(CellKind::boundary, 2, c - n2) : g.from(CellKind::interior, 2, c);
          add_polygon(c >= n2 ? 1 : domains_of(2, c), polygons[c]);
        } else {
          ++counts.skipped;
        }
      add_level(CellKind::boundary, 1);
      add_strata(&polygons);
    } else {
      // The 3-cells in ranges, each into its own piece of the grid, on several workers at once.
      const int workers = resolve_threads(threads);
      std::deque<Grid<Index>> cells3;
      std::vector<std::uint64_t> skipped;
      struct Range {
        CellKind kind;
        std::uint32_t begin, end;
      };
      std::vector<Range> ranges;
      for (CellKind kind : {CellKind::interior, CellKind::boundary}) {
        const std::uint32_t n = cell_count(cc, kind, 3);
        // (one range with one worker: no piece is joined; otherwise a few per worker, to even them out)
        const std::uint32_t step = workers == 1 ? n : std::max<std::uint32_t>(1 << 12, n / (8 * workers) + 1);
        for (std::uint64_t begin = 0; begin < n; begin += step)
          ranges.push_back({kind, static_cast<std::uint32_t>(begin),
                            static_cast<std::uint32_t>(std::min<std::uint64_t>(n, begin + step))});
      }
      for (std::size_t i = 0; i < ranges.size(); ++i) cells3.emplace_back().ids = ids;
      skipped.assign(ranges.size(), 0);
      std::vector<PolyhedronCursor> cursors;
      std::uint32_t longest = 0;
      for (std::uint32_t c = 0; c < polygons.size(); ++c)
        longest = std::max(longest, polygons.offsets[c + 1] - polygons.offsets[c]);
      const auto add_range = [&](std::size_t r, int worker) {
        const auto [kind, begin, end] = ranges[r];
        Grid<Index>& piece = cells3[r];
        const std::uint64_t on_boundary = kind == CellKind::boundary ? 1 : 0;
        const CellLevel& level = *cell_level(cc, kind, 3);
        const std::size_t cells = end - begin;
        piece.offsets.reserve(cells), piece.types.reserve(cells), piece.dimension.reserve(cells);
        piece.is_boundary.reserve(cells), piece.domains.reserve(cells), piece.faceoffsets.reserve(cells);
        if (ids) piece.global.reserve(cells);
        if (!simplices) {  // (a corner of a closed polyhedron is in 3 faces or more: ≤ stream / 3 corners)
          const std::size_t stream = longest <= kShortCycle ? short_face_stream_bound(level, kind, longest, begin, end)
                                                            : face_stream_bound(level, kind, polygons, n2, begin, end);
          piece.faces.reserve(stream);
          piece.connectivity.reserve(stream / 3);
        }
        PolyhedronCursor& cell = cursors[kind == CellKind::interior ? 2 * worker : 2 * worker + 1];
        for (std::uint32_t c = begin; c < end; ++c) {
          piece.from(kind, 3, c);
          if (!cell.load(c)) {
            ++skipped[r];
          } else if (simplices) {
            for_each_cone_tetrahedron(cell.faces(), polygons, p3.data(),
                                      [&](std::uint32_t a, std::uint32_t b, std::uint32_t c2, std::uint32_t e) {
                                        const std::array<std::uint32_t, 4> t{a, b, c2, e};
                                        piece.add(kTetrahedron, 3, on_boundary ? 1 : domains_of(3, c), t);
                                      });
          } else {
            add_polyhedron(piece, on_boundary ? 1 : domains_of(3, c), cell, polygons, p3.data());
          }
        }
      };
      cursors.reserve(2 * static_cast<std::size_t>(workers));
      for (int w = 0; w < workers; ++w)
        for (CellKind kind : {CellKind::interior, CellKind::boundary})
          cursors.emplace_back(cc, kind, polygons, p3.data(), complete);
      if (workers == 1 || ranges.size() <= 1) {
        for (std::size_t r = 0; r < ranges.size(); ++r) add_range(r, 0);
      } else {
        WorkerPool pool(workers);
        pool.run(ranges.size(), add_range);
      }
      for (std::uint64_t n : skipped) counts.skipped += n;
      // (g, still empty, goes last)
      for (auto piece = cells3.rbegin(); piece != cells3.rend(); ++piece) pieces.push_front(std::move(*piece));
      for (std::uint32_t c = n2; m == 3 && c < polygons.size(); ++c) {
        if (!polygons[c].empty()) {
          g.from(CellKind::boundary, 2, c - n2);
          add_polygon(1, polygons[c]);
        } else {
          ++counts.skipped;
        }
      }
      add_strata(&polygons);
    }
  }
  join_offsets(pieces);
  bool has_polyhedra = false;
  for (const Grid<Index>& piece : pieces) counts.cells += piece.types.size(), has_polyhedra |= piece.has_polyhedra;

  std::vector<std::uint8_t> on_boundary(nv, 0);
  std::fill(on_boundary.begin() + n0, on_boundary.end(), 1);
  for (std::uint32_t v = 0; cc.stratified() && v < n0; ++v) on_boundary[v] = cc.interior[0].domains[v] != 0;
  std::vector<Block> point_data, cell_data, points, cells;
  point_data.push_back(block(R"(<DataArray type="UInt8" Name="on_boundary" format="appended")", on_boundary));
  if (projection.changes_points)
    point_data.push_back(block(R"(<DataArray type="Float64" Name="coordinates" NumberOfComponents=")" +
                                   std::to_string(d) + R"(" format="appended")",
                               cc.vertices, cc.boundary_vertices));
  cell_data.push_back(
      block(R"(<DataArray type="UInt8" Name="dimension" format="appended")", pieces, &Grid<Index>::dimension));
  cell_data.push_back(
      block(R"(<DataArray type="UInt8" Name="is_boundary" format="appended")", pieces, &Grid<Index>::is_boundary));
  cell_data.push_back(
      block(R"(<DataArray type="UInt64" Name="domains" format="appended")", pieces, &Grid<Index>::domains));
  if (ids) {
    if (ids->points.size() != nv) throw InputError("write_vtu: a global id is needed for every point");
    point_data.push_back(block(R"(<DataArray type="UInt64" Name="global_id" format="appended")", ids->points));
    cell_data.push_back(
        block(R"(<DataArray type="UInt64" Name="global_id" format="appended")", pieces, &Grid<Index>::global));
  }
  points.push_back(block(R"(<DataArray type="Float64" Name="Points" NumberOfComponents="3" format="appended")", p3));
  cells.push_back(block(R"(<DataArray type=")" + index_type + R"(" Name="connectivity" format="appended")", pieces,
                        &Grid<Index>::connectivity));
  cells.push_back(block(R"(<DataArray type=")" + index_type + R"(" Name="offsets" format="appended")", pieces,
                        &Grid<Index>::offsets));
  cells.push_back(block(R"(<DataArray type="UInt8" Name="types" format="appended")", pieces, &Grid<Index>::types));
  if (has_polyhedra) {
    cells.push_back(block(R"(<DataArray type=")" + index_type + R"(" Name="faces" format="appended")", pieces,
                          &Grid<Index>::faces));
    cells.push_back(block(R"(<DataArray type=")" + index_type + R"(" Name="faceoffsets" format="appended")", pieces,
                          &Grid<Index>::faceoffsets));
  }

  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"" +
      std::to_string(nv) + "\" NumberOfCells=\"" + std::to_string(counts.cells) + "\">\n";
  std::uint64_t offset = 0;
  std::vector<const Block*> order;
  auto section = [&](const char* name, const std::vector<Block>& blocks) {
    xml += std::string("      <") + name + ">\n";
    for (const Block& b : blocks) {
      xml += "        " + b.xml + " offset=\"" + std::to_string(offset) + "\"/>\n";
      offset += 8 + b.bytes();
      order.push_back(&b);
    }
    xml += std::string("      </") + name + ">\n";
  };
  section("PointData", point_data);
  section("CellData", cell_data);
  section("Points", points);
  section("Cells", cells);
  xml += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_";
  os.write(xml.data(), static_cast<std::streamsize>(xml.size()));
  for (const Block* b : order) {
    const std::uint64_t bytes = b->bytes();
    os.write(reinterpret_cast<const char*>(&bytes), 8);
    for (const std::span<const std::byte> part : b->parts)
      if (!part.empty())
        os.write(reinterpret_cast<const char*>(part.data()), static_cast<std::streamsize>(part.size()));
  }
  const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
  os.write(tail.data(), static_cast<std::streamsize>(tail.size()));
  return counts;
}

}  // namespace

WrittenCounts write_vtu(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices,
                        int threads, bool complete) {
  return fits_int32(cc, std::min(cc.manifold_dimension, 3))
             ? write_vtu_as<std::int32_t>(os, cc, projection, simplices, nullptr, threads, complete)
             : write_vtu_as<std::int64_t>(os, cc, projection, simplices, nullptr, threads, complete);
}

WrittenCounts write_vtu(std::ostream& os, const CellComplex& cc, const Projection& projection, bool simplices,
                        const VtuGlobalIds& ids, int threads) {
  return fits_int32(cc, std::min(cc.manifold_dimension, 3))
             ? write_vtu_as<std::int32_t>(os, cc, projection, simplices, &ids, threads, false)
             : write_vtu_as<std::int64_t>(os, cc, projection, simplices, &ids, threads, false);
}

}  // namespace coxmesh
