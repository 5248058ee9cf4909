// The arguments of coxmesh.trace() (named after the options of `coxmesh trace`) and what the
// manifolds given by equations and by samples share: the ambient triangulation and the progress
// callback.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <functional>
#include <memory>

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

/// The ambient triangulation of R^d from triangulation, matrix, scale, edge_length and offset
/// (default_edge: the longest edge when none of them sizes it). Throws InputError.
Triangulation ambient_triangulation(const TraceArguments& a, int d, double default_edge);

/// The walk's progress callback for a.progress (True, False or a callable): it also lets Ctrl-C
/// stop the trace (KeyboardInterrupt). Throws InputError for anything else.
std::function<void(std::size_t)> progress_callback(const TraceArguments& a);

/// coxmesh.trace(points=...): meshes samples with the library's one call (mesh_point_cloud.h).
std::unique_ptr<Mesh> trace_points(const TraceArguments& a);

}  // namespace coxmesh::python
