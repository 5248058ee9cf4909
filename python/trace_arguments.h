// The arguments of coxmesh.trace() (named after the options of `coxmesh trace`) and what the
// manifolds given by equations and by samples share: the ambient triangulation and the progress
// callback.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/triangulation/triangulation.h"
#include "mesh.h"

namespace coxmesh::python {

struct TraceArguments {
  pybind11::object function, preset, m, dim, radius, minor_radius, center, domain, seeds, box, edge_length, scale,
      matrix, offset, triangulation, progress;
  bool auto_seed, refine;
  int threads;
  std::size_t max_simplices;
  // Samples (thesis Ch. 4): an (n, d) array or a file name, and the options of `--points`.
  pybind11::object points, normals, neighbourhood, tube, blend_width;
  std::string oracle, pc_function;
  bool use_normals;
};

/// The domains of `domain` (an expression, a callable X -> (n,) or a list of them) in R^d, for a
/// function and for samples alike: each its own face (two or more: a manifold with corners,
/// mesh_manifold.h), as --domain for `coxmesh trace`.
struct DomainArguments {
  struct Face {
    std::string text;      ///< an expression: made again for every worker (not thread-safe), or
    FunctionPtr callable;  ///< a Python callable (PythonFunction): the walk runs on one thread
  };
  int d = 0;
  std::vector<Face> given;  ///< in the order given (their order in the strata and Mesh.domains(j))
  std::string source;       ///< "; domain TEXT" for each, for Mesh.info.source

  bool empty() const { return given.empty(); }
  bool python_code() const;
  /// The faces, new expressions each time (for one worker; needs no GIL).
  std::vector<FunctionPtr> faces() const;
};

/// Converts `domain` (None: none), parsing the expressions now, before any work. Needs the GIL.
/// Throws InputError.
DomainArguments domain_arguments(const pybind11::object& domain, int d);

/// `box`: (lo, hi), 2d numbers with lo below hi in every coordinate. Throws InputError.
Box box_argument(const pybind11::object& box, int d);

/// `seeds`: points of R^d (None: none). Throws InputError.
std::vector<std::vector<double>> seed_arguments(const pybind11::object& seeds, int d);

/// The ambient triangulation of R^d from triangulation, matrix, scale, edge_length and offset
/// (default_edge: the longest edge when none of them sizes it). Throws InputError.
Triangulation ambient_triangulation(const TraceArguments& a, int d, double default_edge);

/// The walk's progress callback for a.progress (True, False or a callable): it also lets Ctrl-C
/// stop the trace (KeyboardInterrupt). Throws InputError for anything else.
std::function<void(std::size_t)> progress_callback(const TraceArguments& a);

/// coxmesh.trace(points=...): meshes samples with the library's one call (mesh_point_cloud.h).
std::unique_ptr<Mesh> trace_points(const TraceArguments& a);

}  // namespace coxmesh::python
