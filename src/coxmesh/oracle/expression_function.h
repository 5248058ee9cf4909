// Implicit functions typed as text: F: R^d → R^k given by k expressions in muparser syntax, one
// per equation, separated by ';' (e.g. "x^2+y^2+z^2-1" or "x1^2+x2^2-1; x3-x4"), and domains
// given the same way (inside where the expression is < 0). Backed by muparser (libmuparser-dev).
//
// Syntax: the variables are x1 … xd, with x, y, z, w as aliases of x1 … x4 when d ≤ 4; the
// constants pi (also _pi) and _e; muparser's operators (+ − * / ^, comparisons, &&, ||, ?:) and
// functions (sin, cos, tan, asin, …, atan2, sinh, …, exp, log = ln, log2, log10, sqrt, abs, sign,
// rint, min, max, sum, avg). An equation may be written "lhs = rhs", meaning lhs − (rhs). The full
// list is in docs/formats.md.
//
// Not thread-safe: each object owns one muparser parser per equation bound to one array of
// variables, so evaluate() writes into the object. Use one object per thread: the multi-threaded
// tracer asks for one per worker (ManifoldMaker in mesh/mesh_manifold.h, OracleFactory in
// tracing/trace_manifold.h), and separate objects share nothing.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "coxmesh/oracle/implicit_function.h"

namespace coxmesh {

class ExpressionFunction final : public ImplicitFunction {
 public:
  /// Parses `equations` (k expressions separated by ';'). d = `dim` when given, otherwise the
  /// largest variable index used (x → 1, y → 2, z → 3, w → 4, xi → i).
  ///   Throws InputError, with the expression and the position, on a syntax error, an unknown
  ///   variable, a variable beyond d, an alias with d > 4, an empty equation, a ',' between
  ///   equations; and when k ≥ d (no manifold) or d is outside 1..31. `max_equations` (default d − 1)
  ///   lowers the limit on k (1 for domains).
  ExpressionFunction(std::string_view equations, std::optional<int> dim = {}, std::optional<int> max_equations = {});
  ~ExpressionFunction() override;
  ExpressionFunction(const ExpressionFunction&) = delete;
  ExpressionFunction& operator=(const ExpressionFunction&) = delete;

  int ambient_dimension() const override;
  int codimension() const override;
  /// value[0..k) = the k expressions at x[0..d). Not thread-safe (see the file comment).
  void evaluate(const double* x, double* value) const override;
  /// The text it was parsed from.
  const std::string& text() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// F: R^d → R^k from text (see ExpressionFunction); d inferred unless `dim` is given.
///   FunctionPtr f = expression_function("x^2+y^2+z^2-1");           // S² in R³
///   FunctionPtr g = expression_function("x1^2+x2^2-1; x3", 4);       // a circle in R⁴
FunctionPtr expression_function(std::string_view equations, std::optional<int> dim = {});

/// A domain D: R^d → R (inside where D < 0) from one expression over the variables of R^d.
///   Throws InputError as above, also for more than one equation or a variable beyond d.
FunctionPtr expression_domain(std::string_view expression, int dim);

}  // namespace coxmesh
