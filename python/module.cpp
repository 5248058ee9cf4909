// The Python module `coxmesh`: the library's errors become Python exceptions (subclasses of
// ValueError), then each topic adds its part (bindings.h).
#include "bindings.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/oracle/intersection_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace py = pybind11;

PYBIND11_MODULE(coxmesh, m) {
  m.doc() =
      "coxmesh: meshing submanifolds of any dimension with Coxeter triangulations (S. Kachanovich,\n"
      "2019).\n\n"
      "    import coxmesh\n"
      "    mesh = coxmesh.trace(function=lambda X: (X**2).sum(axis=1) - 1, dim=3, seeds=[[1, 0, 0]])\n"
      "    mesh.betti, mesh.points.shape      # [1, 0, 1], (n, 3)\n"
      "    mesh.write('sphere.vtu')\n\n"
      "trace() meshes a manifold; Triangulation locates points and walks simplices; read() loads\n"
      ".cxm files; quality() tabulates the quality of the Coxeter triangulations.";
  m.attr("__version__") = "0.1.0";
  py::module_::import("numpy");
  // Errors raised by the library, with its messages; all are ValueErrors.
  static py::exception<coxmesh::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<coxmesh::SeedError> seed_error(m, "SeedError", PyExc_ValueError);
  static py::exception<coxmesh::EvaluationError> evaluation_error(m, "EvaluationError", PyExc_ValueError);
  input_error.doc() = "Invalid input: dimensions, NaN/Inf, malformed text, singular matrices, bad files.";
  seed_error.doc() = "A seed reaches nothing: no simplex near it meets the manifold, or it is outside the domain.";
  evaluation_error.doc() =
      "The function (or the domain) is not finite at a lattice vertex; the message names the point.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const coxmesh::SeedError& e) {
      PyErr_SetString(seed_error.ptr(), e.what());
    } catch (const coxmesh::EvaluationError& e) {
      PyErr_SetString(evaluation_error.ptr(), e.what());
    } catch (const coxmesh::InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });
  coxmesh::python::bind_triangulation(m);
  coxmesh::python::bind_mesh(m);
  coxmesh::python::bind_trace(m);
  coxmesh::python::bind_quality(m);
}
