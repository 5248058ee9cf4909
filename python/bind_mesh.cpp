// Mesh: the cell complex of a traced manifold (thesis §4.3) as numpy arrays (zero-copy views of
// the library's own), its topology report under the keys of `coxmesh trace --json`, writers of
// every output format, triangles for plotting; and read() of .cxm files.
#include <pybind11/stl.h>

#include <algorithm>
#include <sstream>

#include "bindings.h"
#include "coxmesh/io/polygons.h"
#include "coxmesh/io/projection.h"
#include "coxmesh/io/simplices.h"
#include "coxmesh/io/topology_json.h"
#include "coxmesh/io/write_mesh.h"
#include "mesh.h"

namespace py = pybind11;

namespace coxmesh::python {

namespace {

// A read-only array over memory that `owner` (the Python Mesh) keeps alive.
template <class T>
py::array_t<T> view(const T* data, std::vector<py::ssize_t> shape, const py::object& owner) {
  py::array_t<T> a(shape, data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

const CellLevel& level(const Mesh& m, int j, bool boundary) {
  const auto& levels = boundary ? m.cells.boundary : m.cells.interior;
  if (j < 0 || j >= static_cast<int>(levels.size()))
    throw InputError(std::string(boundary ? "boundary" : "interior") + " cells exist in dimensions 0.." +
                     std::to_string(static_cast<int>(levels.size()) - 1) + ", not " + std::to_string(j));
  return levels[j];
}

// trace(refine=True)'s report, with the keys of `coxmesh trace --refine --json`.
py::object refinement(const Mesh& m) {
  if (!m.refinement) return py::none();
  py::dict r;
  r["max_abs_f_before"] = m.refinement->max_abs_f_before;
  r["max_abs_f_after"] = m.refinement->max_abs_f_after;
  r["vertices"] = m.refinement->vertices;
  r["not_refined"] = m.refinement->not_refined;
  return r;
}

py::dict summary(const Mesh& m) {
  // The library's topology keys (shared with the command line), then what this run adds.
  const py::object loads = py::module_::import("json").attr("loads");
  const auto dump = [](const nlohmann::json& x) {
    return x.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  };
  py::dict j = loads(dump(topology_json(m.cells, m.topology)));
  if (m.point_cloud) j["point_cloud"] = loads(dump(*m.point_cloud));
  if (!m.preset.empty()) j["preset"] = m.preset;
  if (!m.function.empty()) j["function"] = m.function;
  j["function_evaluations"] = m.info.function_evaluations;
  j["oracle_calls"] = m.oracle_calls;
  j["seeds"] = m.seeds;
  j["automatic_seeds"] = m.automatic_seeds;
  j["complete"] = m.info.complete;
  if (!m.info.message.empty()) j["message"] = m.info.message;
  if (!m.warnings.empty()) j["warnings"] = m.warnings;
  if (m.refinement) j["refinement"] = refinement(m);
  j["timings"] = m.timings;
  return j;
}

// Triangles of a surface's polygons, fanned from their smallest vertex (simplices.h), over the global vertex
// numbering (polygons.h); the points projected to R^3 when d != 3 or a projection is given.
py::tuple triangles(const Mesh& m, const std::string& project) {
  const CellComplex& cc = m.cells;
  if (cc.manifold_dimension != 2)
    throw InputError("triangles() needs a surface (m = 2); this manifold has m = " +
                     std::to_string(cc.manifold_dimension));
  const std::vector<double> coords = vertex_coordinates(cc);
  const Projection p = make_projection(project, cc.ambient_dimension, coords);
  const std::vector<double> points3 = p.changes_points ? project_points(p, coords) : coords;
  const Ragged polygons = oriented_polygon_cycles(cc, points3.data());
  std::vector<std::int32_t> tri;
  for (std::uint32_t i = 0; i < polygons.size(); ++i)
    for_each_fan_triangle(polygons[i], [&tri](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      tri.insert(tri.end(), {static_cast<std::int32_t>(a), static_cast<std::int32_t>(b), static_cast<std::int32_t>(c)});
    });
  const py::ssize_t n = static_cast<py::ssize_t>(points3.size() / 3), t = static_cast<py::ssize_t>(tri.size() / 3);
  py::array_t<double> v({n, py::ssize_t{3}});
  std::copy(points3.begin(), points3.end(), v.mutable_data());
  py::array_t<std::int32_t> f({t, py::ssize_t{3}});
  std::copy(tri.begin(), tri.end(), f.mutable_data());
  return py::make_tuple(v, f);
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<Mesh>(m, "Mesh", R"doc(
A meshed manifold: the cell complex of its piecewise-linear approximation (thesis §4.3) with its
topology, as returned by coxmesh.trace() and coxmesh.read().

Cells of dimension j are numbered 0..cells[j]-1; cell 0..traced_simplices-1 of dimension 0 is the
point points[i]. Boundary cells (with a domain) have their own numbering and boundary_points.
The summary attributes carry the keys of `coxmesh trace --json`; summary() returns them as a dict.

    mesh = coxmesh.trace(preset="torus")
    mesh.betti, mesh.euler_characteristic      # [1, 2, 1], 0
    offsets, ids = mesh.facets(2)              # the edges of polygon c: ids[offsets[c]:offsets[c+1]]
    V, T = mesh.triangles()                    # for matplotlib's plot_trisurf
    mesh.write("torus.ply")
)doc")
      .def_property_readonly(
          "ambient_dimension", [](const Mesh& x) { return x.cells.ambient_dimension; }, "d")
      .def_property_readonly(
          "manifold_dimension", [](const Mesh& x) { return x.cells.manifold_dimension; }, "m")
      .def_property_readonly(
          "traced_simplices", [](const Mesh& x) { return x.cells.interior.empty() ? 0u : x.cells.interior[0].size(); },
          "|S|: the k-simplices meeting the manifold (= interior vertices)")
      .def_property_readonly(
          "boundary_simplices",
          [](const Mesh& x) { return x.cells.boundary.empty() ? 0u : x.cells.boundary[0].size(); },
          "|S_boundary|: the (k+1)-simplices meeting its boundary (= boundary vertices)")
      .def_property_readonly(
          "cells", [](const Mesh& x) { return x.topology.cells; }, "interior cells per dimension 0..m")
      .def_property_readonly(
          "boundary_cells", [](const Mesh& x) { return x.topology.boundary_cells; },
          "boundary cells per dimension 0..m-1")
      .def_property_readonly(
          "closed", [](const Mesh& x) { return x.topology.closed; },
          "every cell's boundary closes up; False when a limit stopped the trace (then no topology)")
      .def_property_readonly(
          "euler_characteristic",
          [](const Mesh& x) {
            return x.topology.closed ? py::cast(x.topology.euler_characteristic) : py::object(py::none());
          },
          "of the whole complex (None when not closed)")
      .def_property_readonly(
          "betti",
          [](const Mesh& x) { return x.topology.closed ? py::cast(x.topology.betti) : py::object(py::none()); },
          "Z/2 Betti numbers 0..m (None when not closed)")
      .def_property_readonly(
          "components",
          [](const Mesh& x) { return x.topology.closed ? py::cast(x.topology.betti[0]) : py::object(py::none()); },
          "betti[0] (None when not closed)")
      .def_property_readonly(
          "is_manifold", [](const Mesh& x) { return x.topology.is_manifold; }, "the manifold check passed")
      .def_property_readonly(
          "manifold_problem",
          [](const Mesh& x) {
            return x.topology.is_manifold ? py::object(py::none()) : py::str(x.topology.manifold_problem);
          },
          "the first violation of the manifold check, or None")
      .def_property_readonly(
          "cell_complex_bytes", [](const Mesh& x) { return x.cells.bytes(); }, "memory held by the complex")
      .def_property_readonly(
          "function_evaluations", [](const Mesh& x) { return x.info.function_evaluations; },
          "evaluations of F by the tracer: one per lattice vertex it met")
      .def_property_readonly(
          "oracle_calls", [](const Mesh& x) { return x.oracle_calls; }, "k-simplices tested")
      .def_property_readonly(
          "seeds", [](const Mesh& x) { return x.seeds; }, "number of seeds used")
      .def_property_readonly(
          "automatic_seeds", [](const Mesh& x) { return x.automatic_seeds; }, "seeds found automatically in the box")
      .def_property_readonly(
          "complete", [](const Mesh& x) { return x.info.complete; },
          "False when max_simplices or the box stopped the trace")
      .def_property_readonly(
          "message", [](const Mesh& x) { return x.info.message; }, "why the trace stopped early ('' when complete)")
      .def_property_readonly(
          "warnings", [](const Mesh& x) { return x.warnings; },
          "what the user should know to trust the result (e.g. 0 is not a regular value of F)")
      .def_property_readonly("refinement", &refinement,
                             "trace(refine=True): max_abs_f_before, max_abs_f_after, vertices, not_refined (else None)")
      .def_property_readonly(
          "source", [](const Mesh& x) { return x.info.source; }, "how the manifold was given")
      .def_property_readonly(
          "timings", [](const Mesh& x) { return x.timings; }, "seconds per phase: trace, cell complex, topology")
      .def("summary", &summary, "The summary as a dict, with the keys of `coxmesh trace --json`.")
      .def_property_readonly(
          "points",
          [](py::object self) {
            const Mesh& x = self.cast<const Mesh&>();
            const py::ssize_t d = x.cells.ambient_dimension;
            return view<double>(x.cells.vertices.data(),
                                {static_cast<py::ssize_t>(x.cells.vertices.size()) / std::max<py::ssize_t>(d, 1), d},
                                self);
          },
          "The intersection points (interior vertices), an (n, d) read-only array sharing the mesh's memory.")
      .def_property_readonly(
          "boundary_points",
          [](py::object self) {
            const Mesh& x = self.cast<const Mesh&>();
            const py::ssize_t d = x.cells.ambient_dimension;
            return view<double>(
                x.cells.boundary_vertices.data(),
                {static_cast<py::ssize_t>(x.cells.boundary_vertices.size()) / std::max<py::ssize_t>(d, 1), d}, self);
          },
          "The points on the boundary (boundary vertices), an (n, d) read-only array; empty for a manifold with "
          "corners, whose boundary points are among `points` (see vertex_domains).")
      .def_property_readonly(
          "vertex_domains",
          [](py::object self) -> py::array_t<std::uint64_t> {
            const Mesh& x = self.cast<const Mesh&>();
            const CellLevel& vertices = level(x, 0, false);
            if (x.cells.stratified())
              return view<std::uint64_t>(vertices.domains.data(), {static_cast<py::ssize_t>(vertices.size())}, self);
            // (no corners: every row of `points` is inside; the boundary ones are boundary_points)
            py::array_t<std::uint64_t> inside(static_cast<py::ssize_t>(vertices.size()));
            std::fill_n(inside.mutable_data(), vertices.size(), std::uint64_t{0});
            inside.attr("setflags")(py::arg("write") = false);
            return inside;
          },
          R"doc(
For each row of `points`, the domains whose boundaries it lies on as a bitmask (bit i: domain
i + 1; 0 inside), a read-only uint64 array: a vertex with b bits set lies on a stratum of
dimension m - b (b = m: a corner). Nonzero only for a manifold with corners (several domains);
with one domain the boundary vertices are boundary_points instead.)doc")
      .def(
          "facets",
          [](py::object self, int j, bool boundary) {
            const Mesh& x = self.cast<const Mesh&>();
            const CellLevel& l = level(x, j, boundary);
            return py::make_tuple(
                view<std::uint32_t>(l.facet_offsets.data(), {static_cast<py::ssize_t>(l.facet_offsets.size())}, self),
                view<std::uint32_t>(l.facet_ids.data(), {static_cast<py::ssize_t>(l.facet_ids.size())}, self));
          },
          py::arg("j"), py::arg("boundary") = false, R"doc(
The facets of the cells of dimension j >= 1 in CSR form: (offsets, ids), read-only uint32 arrays;
the facets of cell c are ids[offsets[c]:offsets[c+1]], cells of dimension j - 1 of the same kind.
(An interior cell cut by the domain's boundary also has a boundary facet: boundary_facet(j).)
Dimension 0 has no facets: both arrays are empty.)doc")
      .def(
          "boundary_facet",
          [](py::object self, int j) {
            const Mesh& x = self.cast<const Mesh&>();
            const CellLevel& l = level(x, j, false);
            return view<std::uint32_t>(l.boundary_facet.data(), {static_cast<py::ssize_t>(l.boundary_facet.size())},
                                       self);
          },
          py::arg("j"),
          "For each interior cell of dimension j >= 1: the boundary cell of dimension j - 1 closing it where the "
          "domain "
          "cuts it, or 0xFFFFFFFF; an empty array without a domain.")
      .def(
          "domains",
          [](py::object self, int j) {
            const Mesh& x = self.cast<const Mesh&>();
            const CellLevel& l = level(x, j, false);
            return view<std::uint64_t>(l.domains.data(), {static_cast<py::ssize_t>(l.domains.size())}, self);
          },
          py::arg("j"), R"doc(
With several domains (a manifold with corners): for each cell of dimension j, the domains whose
boundaries it lies on, as a bitmask (bit i: domain i + 1; 0 inside), a read-only uint64 array. Such
a mesh keeps the cells of every stratum among the interior cells (the boundary levels are empty);
summary()["strata"] counts them. An empty array with at most one domain.)doc")
      .def(
          "simplex",
          [](const Mesh& x, int j, std::uint32_t c, bool boundary) {
            const CellLevel& l = level(x, j, boundary);
            if (c >= l.size()) throw InputError("no cell " + std::to_string(c) + " of dimension " + std::to_string(j));
            return l.simplices.simplex(c, x.cells.ambient_dimension);
          },
          py::arg("j"), py::arg("cell"), py::arg("boundary") = false,
          "The ambient simplex of a cell (the cell is the simplex's intersection with the manifold).")
      .def(
          "triangles",
          [](const Mesh& x, const py::object& project) {
            return triangles(x, project.is_none() ? std::string() : project.cast<std::string>());
          },
          py::arg("project") = py::none(), R"doc(
A surface (m = 2) as triangles, for matplotlib:  V, T = mesh.triangles();
ax.plot_trisurf(V[:, 0], V[:, 1], V[:, 2], triangles=T). V: (n, 3) points (interior then boundary
vertices); T: (t, 3) int32 vertex ids, each polygon fanned from its smallest vertex, consistently
oriented (outwards for closed surfaces). For d != 3 the points are projected: project is "i,j,k"
(coordinates, 1-based), "pca", or a file with 3 rows of d numbers, as for write().)doc")
      .def(
          "write",
          [](const Mesh& x, const std::string& path, const py::object& format, const py::object& project,
             bool simplices) {
            const MeshFormat f = format.is_none() ? format_of_path(path) : parse_format(format.cast<std::string>());
            WriteOptions options;
            options.projection = project.is_none() ? std::string() : project.cast<std::string>();
            options.native = x.info;
            options.simplices = simplices;
            WrittenCounts written;
            {
              py::gil_scoped_release release;
              written = write_mesh(path, f, x.cells, options);
            }
            py::dict out;
            out["path"] = path, out["format"] = format_name(f), out["points"] = written.points;
            out["cells"] = written.cells, out["skipped_cells"] = written.skipped;
            return out;
          },
          py::arg("path"), py::arg("format") = py::none(), py::arg("project") = py::none(),
          py::arg("simplices") = false, R"doc(
Writes the mesh, atomically, in the format of the extension (.vtu .off .ply .obj .mesh .cxm .stl
.msh) or of `format` (vtu, off, noff, ply, obj, mesh, cxm, stl, msh); simplices=True writes
polygons as triangles and polyhedra as tetrahedra. .cxm keeps every cell in R^d (coxmesh.read() loads
it back exactly); the others hold 3D points: for d != 3 give project ("i,j,k", "pca" or a file of
3 rows of d numbers; default the first three coordinates). Returns the counts written, as a dict.
Raises InputError when the format cannot hold the mesh or the path is not writable.)doc")
      .def("__repr__", [](const Mesh& x) {
        std::ostringstream os;
        os << "<coxmesh.Mesh: " << x.cells.manifold_dimension << "-manifold in R^" << x.cells.ambient_dimension
           << ", cells [";
        for (std::size_t i = 0; i < x.topology.cells.size(); ++i) os << (i ? ", " : "") << x.topology.cells[i];
        os << "], betti [";
        for (std::size_t i = 0; i < x.topology.betti.size(); ++i) os << (i ? ", " : "") << x.topology.betti[i];
        os << "], euler " << x.topology.euler_characteristic << (x.info.complete ? "" : ", incomplete") << ">";
        return os.str();
      });

  m.def(
      "read",
      [](const std::string& path) {
        auto mesh = std::make_unique<Mesh>();
        {
          py::gil_scoped_release release;
          NativeFile file = read_native(path);
          mesh->cells = std::move(file.cells);
          mesh->info = std::move(file.info);
          mesh->topology = analyze_topology(mesh->cells);
        }
        return mesh;
      },
      py::arg("path"),
      "Reads a .cxm file written by Mesh.write() or `coxmesh trace -o FILE.cxm` into a Mesh (exactly: "
      "every cell keeps its id). Raises InputError naming the file for anything wrong.");
}

}  // namespace coxmesh::python
