// Point clouds in one call; see mesh_point_cloud.h and docs/point_clouds.md.
#include "coxmesh/mesh/mesh_point_cloud.h"

#include "coxmesh/mesh/mesh_local_pca.h"
#include "coxmesh/mesh/mesh_winding.h"
#include "coxmesh/util/stopwatch.h"

namespace coxmesh {

namespace {

// A result of the winding or local-PCA pipeline as a MeshReport.
template <class Result>
MeshReport as_report(Result& r, const PreparedPointCloud& cloud) {
  MeshReport report;
  report.cells = std::move(r.cells);
  report.topology = std::move(r.topology);
  report.status = r.status;
  report.message = r.message;
  report.function_evaluations = r.function_evaluations;
  report.oracle_calls = r.oracle_calls;
  report.seeds = cloud.problem.seeds.size();
  report.trace_seconds = r.trace_seconds;
  report.cell_complex_seconds = r.cell_complex_seconds;
  report.topology_seconds = r.topology_seconds;
  return report;
}

}  // namespace

SampleOracle sample_oracle_named(const std::string& name) {
  if (name == "auto") return SampleOracle::automatic;
  if (name == "vertex") return SampleOracle::vertex;
  if (name == "winding") return SampleOracle::winding;
  if (name == "local-pca") return SampleOracle::local_pca;
  throw InputError("the oracle must be auto, vertex, winding or local-pca, not \"" + name + "\"");
}

std::string sample_oracle_name(SampleOracle oracle) {
  switch (oracle) {
    case SampleOracle::automatic:
      return "auto";
    case SampleOracle::vertex:
      return "vertex";
    case SampleOracle::winding:
      return "winding";
    case SampleOracle::local_pca:
      return "local-pca";
  }
  return "vertex";
}

PreparedPointCloud prepare_samples(std::vector<double> samples, int d, SampleSource source,
                                   const PointCloudMeshOptions& options) {
  const auto t0 = Clock::now();
  PreparedPointCloud pc;
  pc.source = std::move(source);
  const int m = options.m.value_or(d - 1);
  if (pc.source.duplicates > 0 && d > 0 && samples.size() / d < static_cast<std::size_t>(m) + 2)
    throw InputError(std::to_string(pc.source.read) + " samples are only " + std::to_string(samples.size() / d) +
                     (samples.size() / d == 1 ? " distinct point" : " distinct points") + ": too few for a " +
                     std::to_string(m) + "-manifold (at least m + 2 = " + std::to_string(m + 2) + ")");
  pc.problem = make_point_cloud_problem(std::move(samples), d, m, options.preparation);
  if (options.oracle == SampleOracle::automatic) {
    pc.oracle = wants_winding_oracle(pc.problem.diagnostics) && !options.other_bounds ? SampleOracle::winding
                                                                                      : SampleOracle::vertex;
    pc.oracle_chosen = pc.oracle == SampleOracle::winding;
  } else {
    pc.oracle = options.oracle;
  }
  pc.seconds = seconds_since(t0);
  return pc;
}

PointCloudMeshReport mesh_point_cloud(const Triangulation& t, const PreparedPointCloud& cloud, MeshOptions options,
                                      const DomainMaker& make_domains, const WhileTopology& while_topology) {
  PointCloudMeshReport out;
  const PointCloudProblem& p = cloud.problem;
  // (a component that no sample is near lies outside the tube, which bounds every walk)
  if (options.auto_seed) throw InputError("automatic seeds do not apply to samples: every sample is a seed");
  if (cloud.oracle == SampleOracle::winding || cloud.oracle == SampleOracle::local_pca) {
    // Their walks are bounded by the tube alone, and they have no F to refine on.
    if (make_domains || !options.search_box.lo.empty() || options.bounded_by_box || options.refine ||
        !options.seeds.empty())
      throw InputError("the " + cloud.oracle_name() +
                       " oracle takes no domain, box, seeds or refinement: only the tube and the samples");
    if (cloud.oracle == SampleOracle::winding) {
      WindingMeshResult w = mesh_normal_winding(t, p, options.trace);
      out.counts.winding_odd_tetrahedra = w.odd_tetrahedra;
      out.counts.winding_uncertain_triangles = w.uncertain_triangles;
      w.trace_seconds += w.check_seconds;
      out.mesh = as_report(w, cloud);
      if (w.odd_tetrahedra)
        out.mesh.warnings.push_back(std::to_string(w.odd_tetrahedra) +
                                    " tetrahedra next to the trace see an odd number of hit triangles (where the "
                                    "normal planes of their vertices are far apart: too few samples?): the mesh is "
                                    "not closed there");
    } else {
      LocalPcaResult lp = mesh_local_pca(t, p, options.trace);
      out.counts.local_pca_defects = lp.defects;
      out.mesh = as_report(lp, cloud);
    }
    if (while_topology) while_topology(out.mesh);
  } else {
    // The samples, spread over every component of the neighbour graph, are the seeds as they are.
    if (options.search_box.lo.empty()) options.search_box = p.box;
    options.seeds.insert(options.seeds.end(), p.seeds.begin(), p.seeds.end());
    options.project_seeds = false;
    options.trace.skip_unusable_seeds = true;
    options.check_regularity = false;  // (the samples have their own diagnostics)
    const auto make = [&]() -> ManifoldFunctions {
      if (!make_domains) return {p.function, p.domain};
      ManifoldFunctions given = make_domains(p.domain);
      return {p.function, std::move(given.domain), std::move(given.domains)};
    };
    out.mesh = mesh_manifold(t, make, options, while_topology);
  }
  out.mesh.automatic_seeds = p.seeds.size();
  return out;
}

}  // namespace coxmesh
