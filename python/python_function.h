// A Python callable as an ImplicitFunction: f(X) -> Y with X an (n, d) float64 array of points and
// Y an (n, k) array of values ((n,) when k = 1). It prefers batches, so the tracer hands it a
// whole breadth-first level of lattice vertices per call (ImplicitOracle::prefetch).
#pragma once

#include <pybind11/pybind11.h>

#include <span>
#include <string>

#include "coxmesh/oracle/implicit_function.h"

namespace coxmesh::python {

class PythonFunction final : public ImplicitFunction {
 public:
  /// Calls fn once at `probe` (d numbers) to learn k, which must be in 1..max_k. Needs the GIL.
  /// Throws InputError (naming `what`, e.g. "the function") when fn does not return numbers of a
  /// valid shape.
  PythonFunction(pybind11::object fn, int d, std::span<const double> probe, std::string what, int max_k);
  ~PythonFunction() override;

  int ambient_dimension() const override { return d_; }
  int codimension() const override { return k_; }
  void evaluate(const double* x, double* value) const override { evaluate_batch(x, 1, value); }
  /// Takes the GIL, raises KeyboardInterrupt (as pybind11::error_already_set) on a pending Ctrl-C,
  /// calls fn once for the n points. An exception raised by fn propagates unchanged.
  void evaluate_batch(const double* xs, int n, double* values) const override;
  bool prefers_batches() const override { return true; }

 private:
  void call(const double* xs, int n, double* values) const;  // with the GIL held

  pybind11::object fn_;
  int d_, k_ = 0;
  std::string what_;
};

}  // namespace coxmesh::python
