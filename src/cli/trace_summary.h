// The summary that `coxmesh trace` prints: one JSON object (--json) or the human lines.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <utility>

#include "coxmesh/io/mesh_formats.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/mesh/mesh_manifold.h"
#include "points.h"

namespace coxmesh::cli {

struct TraceSummary {
  TraceSummary(std::string what, int d, const MeshReport& r, const PreparedPointCloud* samples)
      : name(std::move(what)), ambient_dimension(d), report(r), cloud(samples) {}

  std::string name;  ///< what was meshed, for the first human line
  int ambient_dimension;
  const MeshReport& report;
  const PreparedPointCloud* cloud;             ///< samples, if the manifold came from them
  std::pair<std::string, std::string> source;  ///< ("preset", name) or ("function", text); empty for samples
  SampleOracleCounts oracle_counts;            ///< of --oracle local-pca or winding
  std::size_t automatic_seeds = 0;
  struct Output {
    std::string path;
    MeshFormat format;
    WrittenCounts written;
    double seconds;
  };
  std::optional<Output> output;  ///< the file written, if any
};

void print_trace_json(std::ostream& out, const TraceSummary& s);
void print_trace_lines(std::ostream& out, const TraceSummary& s);

}  // namespace coxmesh::cli
