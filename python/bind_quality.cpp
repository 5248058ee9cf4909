// coxmesh.quality(): the quality table of the Coxeter triangulations (thesis Ch. 2), the rows of
// `coxmesh quality --json` as dicts.
#include <pybind11/stl.h>

#include <algorithm>

#include "bindings.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/quality/table_row.h"

namespace py = pybind11;

namespace coxmesh::python {

namespace {

py::list quality(const py::object& types, const py::object& dim, int max_dim, int direct_depth) {
  using namespace quality;
  std::vector<Family> families;
  if (types.is_none()) {
    families.assign(std::begin(kAllFamilies), std::end(kAllFamilies));
  } else {
    std::vector<std::string> names;
    if (py::isinstance<py::str>(types)) {
      const std::string text = types.cast<std::string>();
      for (std::size_t i = 0, j; i <= text.size(); i = j + 1) {  // "A,B" or "A"
        j = std::min(text.find(',', i), text.size());
        names.push_back(text.substr(i, j - i));
      }
    } else {
      names = types.cast<std::vector<std::string>>();
    }
    for (const std::string& name : names) families.push_back(parse_family(name));
  }
  if (max_dim < 1 || max_dim > kMaxRank) throw InputError("max_dim must be in 1.." + std::to_string(kMaxRank));
  int lo = 1, hi = max_dim;
  if (!dim.is_none()) {
    if (py::isinstance<py::int_>(dim)) {
      lo = hi = dim.cast<int>();
    } else {
      std::tie(lo, hi) = dim.cast<std::pair<int, int>>();
    }
    if (lo < 1 || hi < lo || hi > kMaxRank)
      throw InputError("dim must be D or (D, D2) with 1 <= D <= D2 <= " + std::to_string(kMaxRank));
  }
  // Every supported pair in the range; a single explicit (family, dimension) must exist.
  std::vector<std::pair<Family, int>> pairs;
  for (Family f : families)
    for (int d : supported_affine_ranks(f, hi))
      if (d >= lo) pairs.emplace_back(f, d);
  if (pairs.empty() && families.size() == 1 && lo == hi) check_affine_type(families[0], lo);
  if (pairs.empty()) throw InputError("no supported (type, dimension) pair in the request");

  std::vector<QualityRow> rows;
  {
    py::gil_scoped_release release;
    for (const auto& [f, d] : pairs) rows.push_back(table_row(coxeter_quality(f, d, direct_depth)));
  }
  py::list out;
  for (const QualityRow& r : rows) {
    py::dict row;
    row["type"] = family_name(r.family);
    row["dimension"] = r.dimension;
    for (const auto& [key, value] : r.numbers)
      row[py::str(key)] = value ? py::object(py::float_(*value)) : py::object(py::none());
    row["delaunay"] = r.delaunay;
    row["delaunay_direct"] =
        r.delaunay_direct.empty() ? py::object(py::none()) : py::object(py::str(r.delaunay_direct));
    out.append(row);
  }
  return out;
}

}  // namespace

void bind_quality(py::module_& m) {
  m.def("quality", &quality, py::kw_only(), py::arg("types") = py::none(), py::arg("dim") = py::none(),
        py::arg("max_dim") = 8, py::arg("direct_depth") = 2, R"doc(
The quality of the Coxeter triangulations (thesis Ch. 2), one dict per (type, dimension) with the
keys of `coxmesh quality --json`: "type", "dimension", the measures (longest_edge, thickness,
radius_ratio, fatness, aspect_ratio, their _relative versions, protection, ...; None where not
defined), "delaunay" and "delaunay_direct" ("yes", "degenerate" or "no").

  types         family letters "A".."G": "A", "A,B" or ["A", "B"] (default: all)
  dim           one dimension D or a range (D, D2) (default: every supported one up to max_dim)
  max_dim       the largest dimension without dim (default 8)
  direct_depth  depth of the generated neighbourhood of the direct Delaunay check (0 skips it)

    rows = coxmesh.quality(types="A", dim=(2, 6))
    [(r["dimension"], r["thickness"]) for r in rows]
)doc");
}

}  // namespace coxmesh::python
