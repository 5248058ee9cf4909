// What the Python package returns for a traced (or read) manifold: the cell complex, its topology
// report and the context the summary and the .cxm files carry.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/native_format.h"
#include "coxmesh/mesh/refine.h"

namespace coxmesh::python {

struct Mesh {
  CellComplex cells;
  TopologyReport topology;
  NativeInfo info;               // source, complete, message, triangulation, evaluations
  std::string preset, function;  // how the manifold was given (at most one is set)
  std::uint64_t oracle_calls = 0;
  std::size_t seeds = 0, automatic_seeds = 0;
  std::map<std::string, double> timings;       // trace_seconds, cell_complex_seconds, topology_seconds
  std::vector<std::string> warnings;           // one sentence each (mesh_manifold)
  std::optional<RefinementReport> refinement;  // trace(refine=True)
  std::optional<nlohmann::json> point_cloud;   // trace(points=...): the summary's "point_cloud" object
};

}  // namespace coxmesh::python
