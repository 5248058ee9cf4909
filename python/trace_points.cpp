// coxmesh.trace(points=...): samples of a manifold (thesis Ch. 4), from an array or a file, meshed by
// the library's one call (mesh_point_cloud.h); this file only converts the arguments and the result.
#include <pybind11/numpy.h>

#include "coxmesh/io/point_cloud_report.h"
#include "coxmesh/mesh/mesh_point_cloud.h"
#include "trace_arguments.h"

namespace py = pybind11;

namespace coxmesh::python {

namespace {

// An (n, d) array of numbers as rows (d = 0: an empty argument).
std::vector<double> rows(const py::object& x, const std::string& what, int& d) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(x);
  if (!a || a.ndim() != 2)
    throw InputError(what + " must be an (n, d) array of numbers" + (what == "points" ? " or a file name" : ""));
  d = static_cast<int>(a.shape(1));
  return {a.data(), a.data() + a.size()};
}

}  // namespace

std::unique_ptr<Mesh> trace_points(const TraceArguments& a) {
  if (!a.function.is_none() || !a.preset.is_none()) throw InputError("give points, function or preset: one of them");
  for (const auto& [name, value] :
       {std::pair{"radius", &a.radius}, {"minor_radius", &a.minor_radius}, {"center", &a.center}})
    if (!value->is_none()) throw InputError(std::string(name) + " is a preset parameter; it does not apply to points");
  if (a.auto_seed)
    throw InputError("auto_seed does not apply to points: the samples are the seeds (add more with seeds)");
  if (a.pc_function != "blended" && a.pc_function != "nearest")
    throw InputError("pc_function must be \"blended\" or \"nearest\", not \"" + a.pc_function + "\"");

  PointCloudMeshOptions po;
  if (!a.m.is_none()) po.m = a.m.cast<int>();
  po.oracle = sample_oracle_named(a.oracle);
  PointCloudOptions& prep = po.preparation;
  if (!a.edge_length.is_none()) prep.edge_length = a.edge_length.cast<double>();
  if (!a.neighbourhood.is_none()) prep.radius = a.neighbourhood.cast<double>();
  if (!a.tube.is_none()) prep.tube = a.tube.cast<double>();
  if (!a.blend_width.is_none()) prep.blend_width = a.blend_width.cast<double>();
  prep.function = a.pc_function == "nearest" ? PointCloudFunction::nearest : PointCloudFunction::blended;
  prep.threads = a.threads;
  const int expected_d = a.dim.is_none() ? 0 : a.dim.cast<int>();

  // The samples: read by the library's reader, or taken from the array (checked as a file's).
  std::string file;
  PointSet set;
  if (py::isinstance<py::str>(a.points) || py::isinstance(a.points, py::module_::import("pathlib").attr("PurePath"))) {
    file = py::str(a.points).cast<std::string>();
    if (!a.normals.is_none()) throw InputError("normals: give them in the file, or the samples as an array");
    PointReadOptions ro;
    ro.dimension = expected_d;
    py::gil_scoped_release release;
    set = read_points(file, ro);
  } else {
    int d = 0, dn = 0;
    std::vector<double> points = rows(a.points, "points", d), normals;
    if (!a.normals.is_none()) {
      normals = rows(a.normals, "normals", dn);
      if (dn != d || normals.size() != points.size())
        throw InputError("normals must have the shape of points, (n, " + std::to_string(d) + ")");
    }
    if (expected_d && d != expected_d)
      throw InputError("the points are in R^" + std::to_string(d) + ", expected R^" + std::to_string(expected_d));
    set = point_set_from_rows(std::move(points), d, std::move(normals));
  }

  // As `coxmesh trace --points` (src/cli/cmd_trace.cpp): the tube bounds the walk, each domain is
  // a further face, a box bounds it too, seeds join the samples, refine works on F; only the
  // per-vertex function allows them (mesh_point_cloud.h), so the automatic oracle keeps to it.
  const int d_given = set.dimension;
  const DomainArguments domains = domain_arguments(a.domain, d_given);
  MeshOptions mo;
  if (!a.box.is_none()) {
    mo.search_box = box_argument(a.box, d_given);
    mo.bounded_by_box = true;
  }
  mo.seeds = seed_arguments(a.seeds, d_given);
  mo.refine = a.refine;
  po.other_bounds = !domains.empty() || !a.box.is_none() || a.refine;
  DomainMaker make_domains;  // the tube still bounds the walk; each domain its own face
  if (!domains.empty())
    make_domains = [&domains](const FunctionPtr& tube) { return ManifoldFunctions{nullptr, tube, domains.faces()}; };

  auto mesh = std::make_unique<Mesh>();
  mesh->info.source = (file.empty() ? "points (array)" : "points " + file) + domains.source;
  mo.trace.max_simplices = a.max_simplices;
  mo.trace.threads = domains.python_code() ? 1 : a.threads;
  mo.trace.progress_interval = 2048;
  mo.trace.progress = progress_callback(a);
  {
    py::gil_scoped_release release;
    // (normals given as an array are there to be used)
    const PreparedPointCloud cloud = prepare_point_set(std::move(set), file, po, a.use_normals || !a.normals.is_none());
    if (cloud.oracle != SampleOracle::vertex) {  // (the command line's messages, in the argument names)
      if (!domains.empty() || !a.box.is_none())
        throw InputError("oracle " + cloud.oracle_name() + " takes no domain or box (only the tube)");
      if (a.refine) throw InputError("refine needs the function F; oracle " + cloud.oracle_name() + " has none");
    }
    const int d = cloud.problem.diagnostics.ambient_dimension;
    const Triangulation t = [&] {
      py::gil_scoped_acquire gil;  // (reads the Python arguments)
      const Triangulation given = ambient_triangulation(a, d, cloud.problem.edge_length);
      return a.offset.is_none() ? given.with_offset(cloud.problem.centre()) : given;
    }();
    PointCloudMeshReport r = mesh_point_cloud(t, cloud, mo, make_domains);
    mesh->point_cloud = point_cloud_json(cloud, r.counts);
    mesh->cells = std::move(r.mesh.cells);
    mesh->topology = std::move(r.mesh.topology);
    mesh->seeds = r.mesh.seeds;
    mesh->automatic_seeds = r.mesh.automatic_seeds;
    mesh->oracle_calls = r.mesh.oracle_calls;
    mesh->warnings = cloud.warnings();  // (the samples' first, as the command line prints them)
    mesh->warnings.insert(mesh->warnings.end(), r.mesh.warnings.begin(), r.mesh.warnings.end());
    mesh->refinement = r.mesh.refinement;
    mesh->info.function_evaluations = r.mesh.function_evaluations;
    mesh->info.complete = r.mesh.status == TraceStatus::complete;
    mesh->info.message = r.mesh.message;
    mesh->timings = {{"trace_seconds", r.mesh.trace_seconds},
                     {"cell_complex_seconds", r.mesh.cell_complex_seconds},
                     {"topology_seconds", r.mesh.topology_seconds}};
    if (r.mesh.refinement) mesh->timings["refine_seconds"] = r.mesh.refinement->seconds;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) mesh->info.matrix.push_back(t.matrix()(i, j));
    mesh->info.offset.assign(t.offset().data(), t.offset().data() + d);
  }
  return mesh;
}

}  // namespace coxmesh::python
