// The built-in manifolds by name (thesis §4.4), with their parameters and defaults: shared by
// `coxmesh trace --preset NAME` and the Python package's `coxmesh.trace(preset=NAME)`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "coxmesh/oracle/implicit_function.h"

namespace coxmesh {

struct PresetParameters {
  int m = 2;               ///< --m: intrinsic dimension (sphere, plane)
  std::optional<int> dim;  ///< --dim: ambient dimension
  std::optional<double> radius, minor_radius;
  std::vector<double> center;
};

struct Preset {
  FunctionPtr function;
  FunctionPtr domain;  ///< built-in domain for unbounded manifolds (may be null)
  double edge_length;  ///< default longest edge of the ambient triangulation
  double extent;       ///< half-width of the default box around the origin
};

struct PresetInfo {
  std::string name, summary;
  std::vector<std::string> parameters;  ///< the options it reads (any other preset option is refused)
};

/// The catalogue, one line each (for `coxmesh presets` and --help).
const std::vector<PresetInfo>& preset_catalogue();
/// Builds the preset; throws InputError for unknown names or bad parameters.
Preset make_preset(const std::string& name, const PresetParameters& p);

}  // namespace coxmesh
