#include "python_function.h"

#include <pybind11/numpy.h>

#include <algorithm>

#include "coxmesh/lattice/simplex.h"

namespace py = pybind11;

namespace coxmesh::python {

namespace {

using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

Values call_on(const py::object& fn, const double* xs, int n, int d, const std::string& what) {
  py::array_t<double> x({py::ssize_t{n}, py::ssize_t{d}});
  std::copy(xs, xs + static_cast<std::size_t>(n) * d, x.mutable_data());
  const py::object result = fn(x);
  Values y = Values::ensure(result);
  if (!y)
    throw InputError(what + " must return an array of numbers, got " + std::string(py::str(py::type::of(result))));
  if (y.ndim() == 0 || y.ndim() > 2 || y.shape(0) != n)
    throw InputError(what + " must return an array of shape (n, k) or (n,) for n points, got shape " +
                     std::string(py::str(py::getattr(y, "shape"))) + " for n = " + std::to_string(n));
  return y;
}

}  // namespace

PythonFunction::PythonFunction(py::object fn, int d, std::span<const double> probe, std::string what, int max_k)
    : fn_(std::move(fn)), d_(d), what_(std::move(what)) {
  check_dimension(d);
  if (!PyCallable_Check(fn_.ptr())) throw InputError(what_ + " must be a string or a callable");
  const Values y = call_on(fn_, probe.data(), 1, d_, what_);
  k_ = y.ndim() == 1 ? 1 : static_cast<int>(y.shape(1));
  if (k_ < 1 || k_ > max_k)
    throw InputError(what_ + " returns " + std::to_string(k_) + " values per point; it must return 1.." +
                     std::to_string(max_k) + " in R^" + std::to_string(d_));
}

PythonFunction::~PythonFunction() {
  py::gil_scoped_acquire gil;  // the last reference may go in a thread without it
  fn_ = py::object();
}

void PythonFunction::evaluate_batch(const double* xs, int n, double* values) const {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  call(xs, n, values);
}

void PythonFunction::call(const double* xs, int n, double* values) const {
  const Values y = call_on(fn_, xs, n, d_, what_);
  if ((y.ndim() == 1 && k_ != 1) || (y.ndim() == 2 && y.shape(1) != k_))
    throw InputError(what_ + " returned " + std::string(py::str(py::getattr(y, "shape"))) + " for " +
                     std::to_string(n) + " points; it returned " + std::to_string(k_) + " values per point before");
  std::copy(y.data(), y.data() + static_cast<std::size_t>(n) * k_, values);
}

}  // namespace coxmesh::python
