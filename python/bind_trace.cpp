// coxmesh.trace(): the `coxmesh trace` command as a function (thesis Ch. 4; docs/cli.md). The
// manifold is an expression, a Python callable (evaluated a breadth-first level per call), a
// preset or samples (trace_points.cpp); the walk, the cell complex and the topology run in C++
// without the GIL.
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "bindings.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/presets.h"
#include "mesh.h"
#include "python_function.h"
#include "trace_arguments.h"

namespace py = pybind11;

namespace coxmesh::python {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

template <class T>
std::optional<T> optional_arg(const py::object& o) {
  return o.is_none() ? std::nullopt : std::optional<T>(o.cast<T>());
}

std::vector<double> point(const py::handle& p, int d, const std::string& what) {
  const auto rows = point_rows(p, d, what);
  if (rows.shape(0) != 1) throw InputError(what + " must have " + std::to_string(d) + " coordinates");
  return {rows.data(), rows.data() + d};
}

// The ambient dimension the arguments show, for a callable (which does not tell it).
std::optional<int> dimension_shown(const py::object& dim, const py::object& seeds, const py::object& box,
                                   const py::object& matrix, const py::object& triangulation) {
  if (!dim.is_none()) return dim.cast<int>();
  if (py::isinstance<Triangulation>(triangulation)) return triangulation.cast<const Triangulation&>().dimension();
  if (!seeds.is_none() && py::len(seeds) > 0) return static_cast<int>(py::len(seeds[py::int_(0)]));
  if (!matrix.is_none()) return static_cast<int>(py::len(matrix));
  if (!box.is_none()) {
    const auto b = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(box);
    if (b && b.size() % 2 == 0) return static_cast<int>(b.size() / 2);
  }
  return std::nullopt;
}

std::unique_ptr<Mesh> trace(const TraceArguments& a) {
  auto mesh = std::make_unique<Mesh>();
  const bool from_function = !a.function.is_none();
  if (from_function && !a.preset.is_none()) throw InputError("give function or preset, not both");
  const std::string preset_name = a.preset.is_none() ? "torus" : a.preset.cast<std::string>();
  bool python_code = false;  // a callable among F and the domains: one thread, the GIL per batch

  // F: built once here; expressions again per worker.
  std::function<FunctionPtr()> make_f;
  std::optional<Preset> preset;
  if (from_function) {
    for (const auto& [name, value] :
         {std::pair{"m", &a.m}, {"radius", &a.radius}, {"minor_radius", &a.minor_radius}, {"center", &a.center}})
      if (!value->is_none())
        throw InputError(std::string(name) + " is a preset parameter; it does not apply to a function");
    if (py::isinstance<py::str>(a.function)) {
      const std::string text = a.function.cast<std::string>();
      const std::optional<int> dim = optional_arg<int>(a.dim);
      make_f = [text, dim] { return expression_function(text, dim); };
      mesh->function = text;
      mesh->info.source = "function " + text;
    } else {
      const std::optional<int> d = dimension_shown(a.dim, a.seeds, a.box, a.matrix, a.triangulation);
      if (!d) throw InputError("give dim (the ambient dimension) with a callable function");
      std::vector<double> probe(std::max(*d, 1), 0.0);
      if (!a.seeds.is_none() && py::len(a.seeds) > 0) probe = point(a.seeds[py::int_(0)], *d, "a seed");
      FunctionPtr f = std::make_shared<PythonFunction>(a.function, *d, probe, "the function", *d - 1);
      make_f = [f] { return f; };
      python_code = true;
      mesh->function = py::repr(a.function);
      mesh->info.source = "python function";
    }
  } else {
    PresetParameters p;
    if (!a.m.is_none()) p.m = a.m.cast<int>();
    p.dim = optional_arg<int>(a.dim);
    p.radius = optional_arg<double>(a.radius);
    p.minor_radius = optional_arg<double>(a.minor_radius);
    if (!a.center.is_none()) p.center = a.center.cast<std::vector<double>>();
    preset = make_preset(preset_name, p);
    make_f = [f = preset->function] { return f; };
    mesh->preset = preset_name;
    mesh->info.source = "preset " + preset_name;
  }
  const FunctionPtr f = make_f();
  const int d = f->ambient_dimension();

  // Domains: the preset's, then each given one (an expression or a callable), each its own face.
  const DomainArguments domains = domain_arguments(a.domain, d);
  python_code = python_code || domains.python_code();
  mesh->info.source += domains.source;
  const FunctionPtr preset_domain = preset ? preset->domain : nullptr;

  // The box (searching seeds; bounding the walk when given, or for a function) and the default
  // scale, as `coxmesh trace` chooses them.
  const double extent = preset ? preset->extent * 1.25 : 2.0;
  Box search_box{std::vector<double>(d, -extent), std::vector<double>(d, extent)};
  MeshOptions mo;
  mo.trace.max_simplices = a.max_simplices;
  if (!a.box.is_none()) search_box = box_argument(a.box, d);
  // The box bounds the walk as a domain (its cells closed) when given, and for a function whose
  // seeds are searched in the default box; seeds given by hand: their whole components.
  mo.bounded_by_box = !a.box.is_none() || (from_function && a.seeds.is_none());
  mo.search_box = search_box;
  mo.auto_seed = a.auto_seed;
  double default_edge = preset ? preset->edge_length : 0;
  if (from_function) {  // 40 edges across the narrowest side of the box
    default_edge = search_box.hi[0] - search_box.lo[0];
    for (int i = 1; i < d; ++i) default_edge = std::min(default_edge, search_box.hi[i] - search_box.lo[i]);
    default_edge /= 40;
  }

  const Triangulation t = ambient_triangulation(a, d, default_edge);

  mo.seeds = seed_arguments(a.seeds, d);

  mo.trace.progress_interval = 2048;
  mo.trace.progress = progress_callback(a);
  mo.trace.threads = python_code ? 1 : a.threads;
  mo.refine = a.refine;

  {
    py::gil_scoped_release release;
    bool first = true;  // expressions are not thread-safe: every worker but the first gets its own
    MeshReport r = mesh_manifold(
        t,
        [&]() -> ManifoldFunctions {
          if (first) return first = false, ManifoldFunctions{f, preset_domain, domains.faces()};
          return {make_f(), preset_domain, domains.faces()};
        },
        mo);
    mesh->cells = std::move(r.cells);
    mesh->topology = std::move(r.topology);
    mesh->seeds = r.seeds;
    mesh->automatic_seeds = r.automatic_seeds;
    mesh->oracle_calls = r.oracle_calls;
    mesh->warnings = std::move(r.warnings);
    mesh->refinement = r.refinement;
    mesh->info.function_evaluations = r.function_evaluations;
    mesh->info.complete = r.status == TraceStatus::complete;
    mesh->info.message = r.message;
    mesh->timings = {{"trace_seconds", r.trace_seconds},
                     {"cell_complex_seconds", r.cell_complex_seconds},
                     {"topology_seconds", r.topology_seconds}};
    if (r.refinement) mesh->timings["refine_seconds"] = r.refinement->seconds;
  }
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) mesh->info.matrix.push_back(t.matrix()(r, c));
  mesh->info.offset.assign(t.offset().data(), t.offset().data() + d);
  return mesh;
}

}  // namespace

bool DomainArguments::python_code() const {
  return std::any_of(given.begin(), given.end(), [](const Face& face) { return face.callable != nullptr; });
}

std::vector<FunctionPtr> DomainArguments::faces() const {
  std::vector<FunctionPtr> faces;
  for (const Face& face : given) faces.push_back(face.callable ? face.callable : expression_domain(face.text, d));
  return faces;
}

DomainArguments domain_arguments(const py::object& domain, int d) {
  DomainArguments out;
  out.d = d;
  py::list domains;
  if (!domain.is_none()) {
    if (py::isinstance<py::str>(domain) || PyCallable_Check(domain.ptr()))
      domains.append(domain);
    else
      domains = py::list(domain);
  }
  for (const py::handle& dom : domains) {
    if (py::isinstance<py::str>(dom)) {
      out.given.push_back({dom.cast<std::string>(), nullptr});
      expression_domain(out.given.back().text, d);  // checked now, before any work
      out.source += "; domain " + out.given.back().text;
    } else {
      out.given.push_back({"", std::make_shared<PythonFunction>(py::reinterpret_borrow<py::object>(dom), d,
                                                                std::vector<double>(d, 0.0), "the domain", 1)});
      out.source += "; domain (python function)";
    }
  }
  return out;
}

Box box_argument(const py::object& box, int d) {
  const auto b = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(box);
  if (!b || b.size() != 2 * d)
    throw InputError("box needs 2d = " + std::to_string(2 * d) + " numbers: (lo, hi) with d coordinates each");
  Box out{std::vector<double>(b.data(), b.data() + d), std::vector<double>(b.data() + d, b.data() + 2 * d)};
  for (int i = 0; i < d; ++i)
    if (!(out.lo[i] < out.hi[i])) throw InputError("box: lo must be below hi in every coordinate");
  return out;
}

std::vector<std::vector<double>> seed_arguments(const py::object& seeds, int d) {
  std::vector<std::vector<double>> out;
  if (!seeds.is_none())
    for (const py::handle& s : seeds) out.push_back(point(s, d, "a seed"));
  return out;
}

Triangulation ambient_triangulation(const TraceArguments& a, int d, double default_edge) {
  if (!a.scale.is_none() && !a.edge_length.is_none()) throw InputError("give scale or edge_length, not both");
  std::optional<Triangulation> t;
  bool sized = false;  // the linear part is given: no default scale
  if (py::isinstance<Triangulation>(a.triangulation)) {
    t = a.triangulation.cast<const Triangulation&>();
    sized = true;
  } else if (!a.matrix.is_none()) {
    t = Triangulation(square_matrix(a.matrix, d, "matrix"), Eigen::VectorXd::Zero(d));
    sized = true;
  } else {
    const std::string kind = a.triangulation.cast<std::string>();
    if (kind != "coxeter" && kind != "freudenthal")
      throw InputError("triangulation must be \"coxeter\", \"freudenthal\" or a coxmesh.Triangulation, got \"" + kind +
                       "\"");
    t = kind == "coxeter" ? Triangulation::coxeter(d) : Triangulation::freudenthal(d);
  }
  if (t->dimension() != d)
    throw InputError("the triangulation is of R^" + std::to_string(t->dimension()) + " but the manifold is in R^" +
                     std::to_string(d));
  if (!a.scale.is_none()) t = t->scaled(a.scale.cast<double>());
  if (!a.edge_length.is_none())
    t = t->with_longest_edge(a.edge_length.cast<double>());
  else if (a.scale.is_none() && !sized)
    t = t->with_longest_edge(default_edge);
  if (!a.offset.is_none()) {
    const std::vector<double> b = point(a.offset, d, "offset");
    t = t->with_offset(Eigen::Map<const Eigen::VectorXd>(b.data(), d));
  }
  return *t;
}

std::function<void(std::size_t)> progress_callback(const TraceArguments& a) {
  // Ctrl-C and progress: the walk calls back every few thousand simplices; at most every 50 ms the
  // callback takes the GIL to run Python's signal handlers (KeyboardInterrupt stops the trace) and
  // to report progress. Python callables check signals at every batch too.
  const bool show = py::isinstance<py::bool_>(a.progress) && a.progress.cast<bool>();
  const bool report = !show && !a.progress.is_none() && !py::isinstance<py::bool_>(a.progress);
  if (report && !PyCallable_Check(a.progress.ptr()))
    throw InputError("progress must be True, False or a callable f(traced_simplices)");
  // (The state is shared by the copies the walk makes; the callable is borrowed from `a`, which
  // outlives the walk, so that copying the callback needs no GIL.)
  struct State {
    Clock::time_point start = Clock::now(), last = start, last_shown = start;
  };
  auto state = std::make_shared<State>();
  const py::handle progress = a.progress;
  return [state, progress, show, report](std::size_t traced) {
    if (seconds_since(state->last) < 0.05) return;
    state->last = Clock::now();
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (report) progress(traced);
    if (show && seconds_since(state->last_shown) >= 1.0) {  // a line a second, as the command line does
      state->last_shown = Clock::now();
      std::fprintf(stderr, "coxmesh: tracing: %zu simplices, %.1f s\n", traced, seconds_since(state->start));
    }
  };
}

void bind_trace(py::module_& m) {
  m.def(
      "trace",
      [](py::object function, py::object preset, py::object m_, py::object dim, py::object radius,
         py::object minor_radius, py::object center, py::object domain, py::object seeds, bool auto_seed,
         py::object box, py::object edge_length, py::object scale, py::object matrix, py::object offset,
         py::object triangulation, bool refine, int threads, std::size_t max_simplices, py::object progress,
         py::object points, py::object normals, std::string oracle, py::object neighbourhood, py::object tube,
         py::object blend_width, bool use_normals, std::string pc_function) {
        const TraceArguments a{
            function,      preset,        m_,        dim,         radius,  minor_radius,  center,
            domain,        seeds,         box,       edge_length, scale,   matrix,        offset,
            triangulation, progress,      auto_seed, refine,      threads, max_simplices, points,
            normals,       neighbourhood, tube,      blend_width, oracle,  pc_function,   use_normals};
        return a.points.is_none() ? trace(a) : trace_points(a);
      },
      py::kw_only(), py::arg("function") = py::none(), py::arg("preset") = py::none(), py::arg("m") = py::none(),
      py::arg("dim") = py::none(), py::arg("radius") = py::none(), py::arg("minor_radius") = py::none(),
      py::arg("center") = py::none(), py::arg("domain") = py::none(), py::arg("seeds") = py::none(),
      py::arg("auto_seed") = false, py::arg("box") = py::none(), py::arg("edge_length") = py::none(),
      py::arg("scale") = py::none(), py::arg("matrix") = py::none(), py::arg("offset") = py::none(),
      py::arg("triangulation") = "coxeter", py::arg("refine") = false, py::arg("threads") = 0,
      py::arg("max_simplices") = 20'000'000, py::arg("progress") = false, py::arg("points") = py::none(),
      py::arg("normals") = py::none(), py::arg("oracle") = "auto", py::arg("neighbourhood") = py::none(),
      py::arg("tube") = py::none(), py::arg("blend_width") = py::none(), py::arg("use_normals") = false,
      py::arg("pc_function") = "blended", R"doc(
Meshes a manifold: traces it through the ambient triangulation (thesis Ch. 4), builds its cell
complex and its topology report. Keyword arguments only; the names follow `coxmesh trace`'s options.

The manifold, one of:
  function      the equations F(x) = 0, either
                  a string "e1; e2; ..." in x1..xd (x, y, z, w when d <= 4), as for --function, or
                  a callable f(X) -> Y: X an (n, d) float64 array of points, Y an (n, k) array
                  ((n,) for one equation). It is called with many lattice vertices at once (a
                  breadth-first level of the walk), each lattice vertex exactly once; vectorise
                  it with numpy. A callable needs dim (or seeds, box, matrix) to tell d.
  preset        a built-in manifold by name (default "torus"; see `coxmesh presets`): torus, sphere,
                flat-torus, chair, iron, lemniscate, whitney-umbrella, moment-curve, so3, plane;
                with its parameters m, dim, radius, minor_radius, center.
  dim           the ambient dimension d (for presets that take it; for expressions when the
                variables do not show it; for callables).
  domain        keep the part where D(x) < 0: a string, a callable X -> (n,), or a list of them
                (intersected; with two or more, each is its own face: a manifold with corners,
                traced on one thread, its strata in summary()["strata"] and Mesh.domains(j)).
  points        samples of the manifold (thesis Ch. 4): an (n, d) array of numbers, or the name of
                a point file (.xyz .txt .csv .off .ply .npy), as for --points; with m (default
                d - 1) and dim (the expected d). Options, as the command line's: oracle ("auto",
                "vertex", "winding", "local-pca"), neighbourhood, tube, blend_width,
                pc_function ("blended", "nearest"), normals (an (n, d) array to orient by) or
                use_normals (orient by the file's), edge_length (and the triangulation options), threads,
                max_simplices, progress. The samples' tube bounds the walk; as with --points,
                domain adds faces (the tube stays), box bounds it too, seeds join the samples and
                refine moves the vertices onto F = 0; these need the per-vertex oracle ("auto"
                then keeps to it). radius, minor_radius, center and auto_seed do not apply.
                summary()["point_cloud"] holds what `coxmesh trace --points FILE --json` reports
                there (file: None for an array).

Where to start and where to stop:
  seeds         points near the manifold (projected onto it); default F's own seed, or points
                found automatically in the box.
  auto_seed     also search seeds for every component inside the box.
  box           (lo, hi): stop the walk at this box and search seeds in it (default for
                functions: [-2, 2]^d; presets: unbounded, seeds searched around their extent).
  max_simplices stop when this many simplices are traced (the result says complete=False).

The ambient triangulation:
  triangulation "coxeter" (Ã_d, default), "freudenthal", or a coxmesh.Triangulation.
  edge_length   the longest edge of every d-simplex (default: the preset's, or 1/40 of the box).
  scale         multiply the linear part by this instead.
  matrix        a (d, d) matrix for the linear part (replaces triangulation and the default scale).
  offset        the translation b (d numbers).

  refine        move every vertex onto M (and a vertex on the boundary of some domains onto
                M ∩ {D_i = 0} for those, inside the others) by a few Gauss–Newton steps; the
                cells do not change. mesh.refinement tells max |F| before
                and after, and how many vertices stayed where they were.

  threads       worker threads (0: all hardware threads); the result is the same for every number.
                Python callables run on one thread.
  progress      True prints the traced count to stderr once a second; a callable f(traced) is
                called with it every ~0.05 s at most.

Returns a coxmesh.Mesh. Raises InputError/SeedError/EvaluationError (ValueErrors) with the
library's messages; an exception raised by a callable propagates unchanged; Ctrl-C raises
KeyboardInterrupt within ~0.1 s. The GIL is released except while a callable runs.

    mesh = coxmesh.trace(preset="sphere", m=2, dim=4)
    mesh = coxmesh.trace(function="x^2+y^2+z^2-1", edge_length=0.05)
    mesh = coxmesh.trace(function=lambda X: (X**2).sum(1) - 1, dim=3, seeds=[[1, 0, 0]])
    mesh = coxmesh.trace(points=X, m=2)             # X: an (n, 3) array of samples of a surface
)doc");
}

}  // namespace coxmesh::python
