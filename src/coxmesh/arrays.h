// The flat arrays in the library's results (TraceResult, CellComplex): what they hold, not how they
// are allocated. Use them as std::vectors (data(), size(), indexing, iteration); growing them
// leaves new elements uninitialised and big arrays get huge pages (util/huge_page_allocator.h),
// which only matters to the code that fills them.
#pragma once

#include <cstdint>

#include "coxmesh/util/huge_page_allocator.h"

namespace coxmesh {

/// Points of R^d, one row of d coordinates after another.
using PointArray = UninitializedHugeVector<double>;

/// 32-bit ids and offsets (cells, facets, CSR offsets).
using IndexArray = UninitializedHugeVector<std::uint32_t>;

}  // namespace coxmesh
