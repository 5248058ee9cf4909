// Thesis §4.2: one level of the cell complex from the one below, plainly (cell_complex.cpp) and as
// the pipeline over many workers that build_cell_complex runs (cell_complex_pipeline.cpp). The two
// give the same level, numbering included (tests/cell_complex/test_cell_complex.cpp). Internal to
// the cell complex layer (not installed).
#pragma once

#include "coxmesh/cell_complex/cell_complex.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh::cells {

/// The cells whose ambient simplices are the l-cofaces (in R^d) of those of `prev`, numbered in
/// order of discovery, cell by cell of prev, each with the cells of prev it was found from as facets
/// (in increasing order).
CellLevel next_level_plain(const CellLevel& prev, int d, int l);
/// The same level, by the workers of `pool`.
CellLevel next_level_pipelined(const CellLevel& prev, int d, int l, WorkerPool& pool);

/// Level 1 from the cofacets of level 0 (S) that the walk met (TraceOptions::keep_cofacets): the
/// same level as next_level_pipelined's, their keys made by the workers of `pool`.
CellLevel level_from_walk(WalkedCofacets&& walked, const CellLevel& vertices, int d, WorkerPool& pool);

}  // namespace coxmesh::cells
