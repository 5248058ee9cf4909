#include "trace_summary.h"

#include <algorithm>

#include "coxmesh/io/point_cloud_report.h"
#include "report.h"

namespace coxmesh::cli {

void print_trace_json(std::ostream& out, const TraceSummary& s) {
  const MeshReport& report = s.report;
  nlohmann::json j = topology_json(report.cells, report.topology);
  if (s.cloud) {
    j["point_cloud"] = point_cloud_json(*s.cloud, s.oracle_counts);
  } else {
    j[s.source.first] = s.source.second;
  }
  j["function_evaluations"] = report.function_evaluations;
  j["oracle_calls"] = report.oracle_calls;
  j["seeds"] = report.seeds;
  j["automatic_seeds"] = s.automatic_seeds;
  j["complete"] = report.status == TraceStatus::complete;
  if (!report.message.empty()) j["message"] = report.message;
  if (!report.warnings.empty()) j["warnings"] = report.warnings;
  j["timings"] = {{"trace_seconds", report.trace_seconds},
                  {"cell_complex_seconds", report.cell_complex_seconds},
                  {"topology_seconds", report.topology_seconds}};
  if (report.refinement) {
    j["refinement"] = {{"max_abs_f_before", report.refinement->max_abs_f_before},
                       {"max_abs_f_after", report.refinement->max_abs_f_after},
                       {"vertices", report.refinement->vertices},
                       {"not_refined", report.refinement->not_refined}};
    j["timings"]["refine_seconds"] = report.refinement->seconds;
  }
  if (s.output) {
    j["timings"]["write_seconds"] = s.output->seconds;
    j["output"] = {{"path", s.output->path},
                   {"format", format_name(s.output->format)},
                   {"points", s.output->written.points},
                   {"cells", s.output->written.cells},
                   {"skipped_cells", s.output->written.skipped}};
  }
  j["peak_memory_bytes"] = peak_memory_bytes();
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

void print_trace_lines(std::ostream& out, const TraceSummary& s) {
  const MeshReport& report = s.report;
  const CellComplex& cc = report.cells;
  out << s.name << ": " << cc.manifold_dimension << "-manifold in R^" << s.ambient_dimension << "\n";
  if (s.cloud) print_point_cloud(out, *s.cloud);
  const SampleOracleCounts& c = s.oracle_counts;
  if (c.winding_odd_tetrahedra)
    out << "  oracle             winding (" << s.cloud->oracle_reason() << "): " << *c.winding_odd_tetrahedra
        << " tetrahedra next to the trace see an odd number of hit triangles (0: a manifold), "
        << c.winding_uncertain_triangles << " uncertain triangles\n";
  if (c.local_pca_defects)
    out << "  local-pca defects  " << *c.local_pca_defects
        << " cofacets of traced simplices see an odd number of intersected facets (0: a manifold)\n";
  print_topology(out, cc, report.topology);
  if (s.automatic_seeds)
    out << "  seeds              " << s.automatic_seeds << (s.cloud ? " samples" : " found automatically in the box")
        << "\n";
  out << "  F evaluations      " << report.function_evaluations << " (" << report.oracle_calls << " oracle calls)\n"
      << "  time               trace " << report.trace_seconds << " s ("
      << static_cast<long long>(static_cast<double>(report.topology.cells.empty() ? 0 : report.topology.cells[0]) /
                                std::max(report.trace_seconds, 1e-9))
      << " simplices/s), cell complex " << report.cell_complex_seconds << " s, topology " << report.topology_seconds
      << " s";
  if (report.refinement) out << ", refine " << report.refinement->seconds << " s";
  if (s.output) out << ", write " << s.output->seconds << " s";
  out << "\n  peak memory        " << peak_memory_bytes() / (1 << 20) << " MiB\n";
  if (s.output) {
    const auto& w = s.output->written;
    out << "  output             " << s.output->path << " (" << format_name(s.output->format) << ", " << w.points
        << " points, " << w.cells << " cells";
    if (w.skipped) out << "; " << w.skipped << " open cells at the cut not written";
    out << ")\n";
  }
  if (report.refinement)
    out << "  refinement         max |F| " << report.refinement->max_abs_f_before << " -> "
        << report.refinement->max_abs_f_after << " (" << report.refinement->not_refined << " of "
        << report.refinement->vertices << " vertices not refined)\n";
  if (!report.message.empty()) out << "  note: " << report.message << "\n";
}

}  // namespace coxmesh::cli
