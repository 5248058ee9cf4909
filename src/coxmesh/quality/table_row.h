// One row of the quality table of the Coxeter triangulations (thesis Ch. 2): every measure by name,
// in one fixed column order, shared by `coxmesh quality` and the Python package's coxmesh.quality().
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coxmesh/quality/measures.h"

namespace coxmesh::quality {

/// The numeric measures by name (nullopt for "not defined") and the Delaunay answers.
struct QualityRow {
  Family family = Family::A;
  int dimension = 0;
  std::vector<std::pair<std::string, std::optional<double>>> numbers;  ///< in numeric_keys() order
  std::string delaunay, delaunay_direct;  ///< "yes", "degenerate", "no" ("" when not computed)
};

/// The names of the numeric columns, in order (also the JSON keys of `coxmesh quality --json`).
const std::vector<std::string>& numeric_keys();

/// The row of one triangulation; protection_direct is nullopt when the direct check did not run.
QualityRow table_row(const CoxeterQuality& q);

}  // namespace coxmesh::quality
