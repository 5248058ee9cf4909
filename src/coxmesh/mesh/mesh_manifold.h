// The whole pipeline in one call: seeds, tracing (thesis §4.2), the cell complex, its topology and
// the diagnostics a user needs to trust them. The command line and the Python package are thin
// front ends over it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/mesh/refine.h"
#include "coxmesh/oracle/implicit_function.h"
#include "coxmesh/tracing/trace_manifold.h"

namespace coxmesh {

/// M = F⁻¹(0) ∩ {D < 0}: F: R^d → R^k and the domain D (null: none). With `domains`, each of
/// them (after `domain`, if any) bounds M with its own face: M ∩ {D_1 < 0, …, D_p < 0} is then a
/// manifold with corners whose strata are traced one by one (trace_strata.h) when p ≥ 2.
struct ManifoldFunctions {
  ManifoldFunctions(FunctionPtr f_ = nullptr, FunctionPtr domain_ = nullptr, std::vector<FunctionPtr> domains_ = {})
      : f(std::move(f_)), domain(std::move(domain_)), domains(std::move(domains_)) {}
  FunctionPtr f, domain;
  std::vector<FunctionPtr> domains;
};
/// Makes the functions once per worker thread: a function that is not thread-safe (an expression
/// typed as text) must come fresh each time; thread-safe ones may be the same objects every time.
using ManifoldMaker = std::function<ManifoldFunctions()>;
/// A walk in place of trace_manifold, e.g. one split between processes (mesh_distributed.h): it
/// gets F and D (the box included), the seeds and the trace options.
using Tracer = std::function<TraceResult(const Triangulation&, const ManifoldFunctions&,
                                         const std::vector<std::vector<double>>& seeds, const TraceOptions&)>;

/// What a ComplexTracer returns: the complex, or, when it is split between processes, its
/// topology and the regularity verdicts over its vertices, computed where its cells are, with
/// `cells` holding only the dimensions.
struct TracedComplex {
  CellComplex cells;
  std::optional<TopologyReport> topology;
  /// singular_on over the vertex cells (F), and over the boundary vertex cells (F and D).
  std::optional<bool> singular_vertices, singular_boundary_vertices;
  /// When asked to refine: the vertices were moved onto M where they are (refine_vertices), with
  /// what one refinement of the whole complex reports.
  std::optional<RefinementReport> refinement;
};

/// The walk and the cell complex in place of trace_manifold and build_cell_complex, e.g. both split
/// between processes (mesh_distributed.h): returns the complex, and the trace's status, message and
/// counts in `traced` (whose S and S_∂ may stay empty). With `refine` it also moves the vertices onto
/// M (MeshOptions::refine) after the regularity verdicts and reports it in TracedComplex::refinement.
using ComplexTracer = std::function<TracedComplex(const Triangulation&, const ManifoldFunctions&,
                                                  const std::vector<std::vector<double>>& seeds, const TraceOptions&,
                                                  bool refine, TraceResult& traced)>;

struct MeshOptions {
  std::vector<std::vector<double>> seeds;  ///< points near M, d coordinates each
  bool project_seeds = true;               ///< move them onto M first (Gauss–Newton on F)
  bool auto_seed = false;                  ///< also search seeds in search_box (always when no seed is known)
  Box search_box;                          ///< where seeds are searched; empty: [−2, 2]^d
  bool bounded_by_box = false;             ///< search_box also bounds the walk, as a domain
  std::uint64_t max_memory = 0;            ///< bytes for trace, complex and topology (0: no limit)
  bool check_regularity = true;            ///< warn where 0 is not a regular value of F (regularity.h)
  bool refine = false;                     ///< move the vertices onto M at the end (refine.h)
  bool keep_keys = true;                   ///< keep the cells' keys (build_cell_complex): the native format reads them
  /// Limits (max_simplices, also derived from max_memory), threads, progress; skip_unusable_seeds
  /// is set when seeds were found automatically.
  TraceOptions trace;
  std::function<void(const std::string& phase)> on_phase;  ///< "building the cell complex", …
  Tracer tracer;                                           ///< replaces trace_manifold when set
  ComplexTracer complex_tracer;                            ///< replaces trace_manifold and build_cell_complex when set
};

struct MeshReport;

/// Work on the finished mesh that does not need its topology, e.g. writing it to a file: it gets
/// the report with everything but `topology` and `topology_seconds` filled in.
using WhileTopology = std::function<void(const MeshReport&)>;

struct MeshReport {
  CellComplex cells;
  TopologyReport topology;
  TraceStatus status = TraceStatus::complete;
  std::string message;                ///< why the run stopped early (empty when complete)
  std::vector<std::string> warnings;  ///< one sentence each
  std::uint64_t function_evaluations = 0, oracle_calls = 0;
  std::size_t seeds = 0, automatic_seeds = 0;
  double trace_seconds = 0, cell_complex_seconds = 0, topology_seconds = 0;
  std::optional<RefinementReport> refinement;  ///< with options.refine
};

/// Meshes M on the triangulation t (several domain functions: a stratified complex, cell_complex.h,
/// traced on one thread, a box bounding the walk being one more domain, last): seeds (given, F's own, or searched in
/// the box), the walk from them with options.trace.threads workers (F once per lattice vertex in all), the cell
/// complex, with options.refine the vertices moved onto M (refine_vertices: onto the boundary of the domains of their
/// stratum; one domain includes the box when it bounds the walk), and the topology (none when the run was stopped by a
/// limit: the complex is then open).
///   Throws InputError when no seed is found or none reaches M (saying whether F is not finite, or
///   its differential singular, there), SeedError, EvaluationError.
///
/// `while_topology` runs on the calling thread once the mesh is final (refined), while the topology
/// is computed on another thread when options.trace.threads is not 1 (both only read the mesh;
/// the memory of both is then held at once), after it otherwise.
///
///   MeshReport r = mesh_manifold(Triangulation::coxeter(3).with_longest_edge(0.1),
///                                [] { return ManifoldFunctions{sphere(2, 3, 1.0), nullptr}; }, {});
MeshReport mesh_manifold(const Triangulation& t, const ManifoldMaker& make, const MeshOptions& options,
                         const WhileTopology& while_topology = {});

}  // namespace coxmesh
