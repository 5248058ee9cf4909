// The parts of the Python module `coxmesh`, one per topic; each adds its classes and functions.
// The bindings only convert: the work is the library's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <string>

namespace coxmesh::python {

void bind_triangulation(pybind11::module_& m);  // Triangulation, Simplex, locate, faces, cofaces
void bind_mesh(pybind11::module_& m);           // Mesh (a cell complex with its report), read
void bind_trace(pybind11::module_& m);          // trace
void bind_quality(pybind11::module_& m);        // quality

/// An (n, d) C-contiguous float64 array of `points` (a sequence of points, or one point: n = 1),
/// without a copy when it already is one. Throws InputError unless every row has d coordinates.
pybind11::array_t<double, pybind11::array::c_style> point_rows(const pybind11::handle& points, int d,
                                                               const std::string& what);

/// A square matrix (of size d when d > 0) from any 2-D array of numbers; throws InputError otherwise.
Eigen::MatrixXd square_matrix(const pybind11::handle& m, int d, const std::string& what);

}  // namespace coxmesh::python
