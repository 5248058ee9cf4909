// The quality table's row; see table_row.h.
#include "coxmesh/quality/table_row.h"

namespace coxmesh::quality {

const std::vector<std::string>& numeric_keys() {
  static const std::vector<std::string> keys{"longest_edge",
                                             "shortest_edge",
                                             "edge_ratio",
                                             "min_height",
                                             "circumradius",
                                             "inradius",
                                             "volume",
                                             "thickness",
                                             "thickness_normalized",
                                             "radius_ratio",
                                             "fatness",
                                             "aspect_ratio",
                                             "thickness_relative",
                                             "radius_ratio_relative",
                                             "fatness_relative",
                                             "aspect_ratio_relative",
                                             "circumcentre_min_barycentric",
                                             "protection",
                                             "protection_direct"};
  return keys;
}

QualityRow table_row(const CoxeterQuality& q) {
  const auto& m = q.measures;
  QualityRow r{q.family,
               q.dimension,
               {},
               to_string(q.delaunay.status),
               q.delaunay_direct ? to_string(q.delaunay_direct->status) : std::string()};
  const std::vector<std::optional<double>> values{m.longest_edge,
                                                  m.shortest_edge,
                                                  m.edge_ratio,
                                                  m.min_height,
                                                  m.circumradius,
                                                  m.inradius,
                                                  m.volume,
                                                  m.thickness,
                                                  m.thickness_normalized,
                                                  m.radius_ratio,
                                                  m.fatness,
                                                  m.aspect_ratio,
                                                  q.relative.thickness,
                                                  q.relative.radius_ratio,
                                                  q.relative.fatness,
                                                  q.relative.aspect_ratio,
                                                  m.circumcentre_barycentric.minCoeff(),
                                                  q.delaunay.protection,
                                                  q.delaunay_direct ? q.delaunay_direct->protection : std::nullopt};
  for (std::size_t k = 0; k < values.size(); ++k) r.numbers.emplace_back(numeric_keys()[k], values[k]);
  return r;
}

}  // namespace coxmesh::quality
