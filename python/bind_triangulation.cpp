// Triangulation (the affine image of Freudenthal–Kuhn, Ã_d; thesis §3.1–3.3) and Simplex (the
// permutahedral representation; thesis §3): point location in bulk, faces and cofaces.
#include <pybind11/stl.h>

#include <cstring>
#include <sstream>

#include "bindings.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/triangulation/triangulation.h"

namespace py = pybind11;

namespace coxmesh::python {

py::array_t<double, py::array::c_style> point_rows(const py::handle& points, int d, const std::string& what) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a) throw InputError(what + " must be an array of numbers");
  if (a.ndim() == 1 && a.shape(0) != d)
    throw InputError(what + " has " + std::to_string(a.shape(0)) + " coordinates, expected " + std::to_string(d));
  if (a.ndim() == 1) a = a.reshape({py::ssize_t{1}, py::ssize_t{d}});
  if (a.ndim() != 2 || a.shape(1) != d)
    throw InputError(
        what + " must have shape (n, " + std::to_string(d) + "), got " +
        std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))));
  return a;
}

Eigen::MatrixXd square_matrix(const py::handle& m, int d, const std::string& what) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(m);
  if (!a || a.ndim() != 2 || a.shape(0) != a.shape(1) || (d > 0 && a.shape(0) != d))
    throw InputError(what + " must be a square matrix" + (d > 0 ? " of size " + std::to_string(d) : std::string()));
  const int n = static_cast<int>(a.shape(0));
  Eigen::MatrixXd out(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) out(r, c) = a.at(r, c);
  return out;
}

namespace {

Eigen::VectorXd to_vector(const py::handle& v, int d, const std::string& what) {
  const auto rows = point_rows(v, d, what);
  if (rows.shape(0) != 1) throw InputError(what + " must have " + std::to_string(d) + " coordinates");
  return Eigen::Map<const Eigen::VectorXd>(rows.data(), d);
}

py::array_t<double> matrix_array(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.mutable_at(r, c) = m(r, c);
  return out;
}

std::vector<Simplex> faces_of(const Simplex& s, int k) {
  std::vector<Simplex> out;
  FaceEnumerator faces(s, k);
  for (Simplex f; faces.next(f);) out.push_back(f);
  return out;
}

std::vector<Simplex> cofaces_of(const Simplex& s, int l) {
  std::vector<Simplex> out;
  CofaceEnumerator cofaces(s, l);
  for (Simplex c; cofaces.next(c);) out.push_back(c);
  return out;
}

// The simplices found by locate as arrays: minimal vertex y, block of each index 0..d, barycentric
// coordinates (zero beyond the simplex's k + 1 vertices).
py::tuple locate_points(const Triangulation& t, const py::handle& points) {
  const int d = t.dimension();
  const auto given = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  const bool single = given && given.ndim() == 1;  // one point: one row, not a table
  const auto x = point_rows(given ? py::handle(given) : points, d, "points");
  const py::ssize_t n = x.shape(0);
  py::array_t<std::int32_t> vertex({n, py::ssize_t{d}});
  py::array_t<std::uint8_t> blocks({n, py::ssize_t{d + 1}});
  py::array_t<double> barycentric({n, py::ssize_t{d + 1}});
  {
    const double* xs = x.data();
    std::int32_t* y = vertex.mutable_data();
    std::uint8_t* b = blocks.mutable_data();
    double* lambda = barycentric.mutable_data();
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i, xs += d, y += d, b += d + 1, lambda += d + 1) {
      const Simplex s = t.locate(xs);
      std::memcpy(y, s.y.data(), sizeof(std::int32_t) * d);
      std::memcpy(b, s.block.data(), d + 1);
      t.barycentric(s, xs, lambda);
      std::fill(lambda + s.k + 1, lambda + d + 1, 0.0);
    }
  }
  if (single) return py::make_tuple(vertex[py::int_(0)], blocks[py::int_(0)], barycentric[py::int_(0)]);
  return py::make_tuple(vertex, blocks, barycentric);
}

}  // namespace

void bind_triangulation(py::module_& m) {
  py::class_<Simplex>(m, "Simplex", R"doc(
A simplex of the Freudenthal–Kuhn triangulation in permutahedral representation (thesis §3): its
minimal lattice vertex y (d integers) and an ordered partition of {0, ..., d} into k + 1 blocks,
d in the last one. Vertex j is y + (sum of e_i over the indices i in blocks before j). Simplices
are immutable values: comparable, hashable, printed in the text form of the command line tool.

    s = coxmesh.Simplex([0, 0], [[0], [1], [2]])      # a triangle of R^2
    s = coxmesh.Simplex.parse("(0,0) [{0},{1},{2}]")  # the same
    s.dimension, s.vertex, s.partition                # 2, (0, 0), [[0], [1], [2]]
)doc")
      .def(py::init([](const std::vector<std::int32_t>& vertex, const std::vector<std::vector<int>>& partition) {
             return Simplex::from_partition(vertex, partition);
           }),
           py::arg("vertex"), py::arg("partition"),
           "Builds a simplex from its minimal vertex (d integers) and its blocks (lists of indices in 0..d, "
           "d in the last). Raises InputError (a ValueError) unless the blocks partition {0..d}.")
      .def_static(
          "parse", [](const std::string& text) { return parse_simplex(text); }, py::arg("text"),
          "Parses the text form \"(y_0,...,y_{d-1}) [{..},{..},...]\" (as printed by coxmesh locate).")
      .def_property_readonly("dimension", &Simplex::dimension, "k: the number of blocks minus one")
      .def_property_readonly("ambient_dimension", &Simplex::ambient_dimension, "d")
      .def_property_readonly(
          "vertex",
          [](const Simplex& s) { return py::tuple(py::cast(std::vector<int>(s.y.begin(), s.y.begin() + s.d))); },
          "the minimal vertex y, a tuple of d integers")
      .def_property_readonly("partition", &Simplex::partition, "the blocks, each a sorted list of indices in 0..d")
      .def(
          "vertices",
          [](const Simplex& s) {
            py::array_t<std::int32_t> out({s.k + 1, static_cast<int>(s.d)});
            for (int j = 0; j <= s.k; ++j) s.vertex(j, out.mutable_data(j));
            return out;
          },
          "The lattice coordinates of the k + 1 vertices, a (k + 1, d) int32 array (Cartesian: "
          "Triangulation.vertices).")
      .def("faces", &faces_of, py::arg("k"), "The k-faces, in lexicographic order of their vertex indices.")
      .def("cofaces", &cofaces_of, py::arg("l"), "The l-cofaces (dimension <= l <= d), each once.")
      .def("__repr__", [](const Simplex& s) { return to_string(s); })
      .def("__str__", [](const Simplex& s) { return to_string(s); })
      .def("__eq__", [](const Simplex& a, const Simplex& b) { return a == b; })
      .def("__lt__", [](const Simplex& a, const Simplex& b) { return a < b; })
      .def("__hash__", [](const Simplex& s) { return static_cast<std::size_t>(hash_value(s)); });

  py::class_<Triangulation>(m, "Triangulation", R"doc(
The ambient triangulation: the Freudenthal–Kuhn triangulation of R^d under x = matrix @ y + offset
(thesis §3.1–3.3). Immutable; the methods that change it return a new one.

    T = coxmesh.Triangulation.coxeter(3).with_longest_edge(0.1)   # Ã_3, longest edge 0.1
    vertex, blocks, bary = T.locate(numpy.random.rand(10**6, 3))   # in one call, without the GIL
    s = T.simplex_at([0.1, 0.2, 0.3]); T.vertices(s); T.cofaces(s, 3)
)doc")
      .def(py::init([](const py::handle& matrix, const py::object& offset) {
             const Eigen::MatrixXd a = square_matrix(matrix, 0, "matrix");
             const int d = static_cast<int>(a.rows());
             return Triangulation(a, offset.is_none() ? Eigen::VectorXd::Zero(d) : to_vector(offset, d, "offset"));
           }),
           py::arg("matrix"), py::arg("offset") = py::none(),
           "From a (d, d) matrix (the lattice point y sits at matrix @ y + offset) and an offset (d numbers, "
           "default 0). Raises InputError for a singular or ill-conditioned matrix.")
      .def_static("coxeter", &Triangulation::coxeter, py::arg("d"), "The Coxeter triangulation Ã_d with unit heights.")
      .def_static("freudenthal", &Triangulation::freudenthal, py::arg("d"),
                  "Freudenthal–Kuhn itself (matrix I, offset 0).")
      .def("scaled", &Triangulation::scaled, py::arg("s"), "The matrix multiplied by s > 0 (the offset kept).")
      .def("with_longest_edge", &Triangulation::with_longest_edge, py::arg("h"),
           "Scaled so that the longest edge of every d-simplex is h.")
      .def(
          "with_offset",
          [](const Triangulation& t, const py::handle& b) {
            return t.with_offset(to_vector(b, t.dimension(), "offset"));
          },
          py::arg("offset"), "The same matrix with this offset (d numbers).")
      .def("rotated", &Triangulation::rotated, py::arg("seed"),
           "Turned by a random orthogonal matrix drawn from the seed (deterministic).")
      .def_property_readonly("dimension", &Triangulation::dimension, "d")
      .def_property_readonly(
          "matrix", [](const Triangulation& t) { return matrix_array(t.matrix()); }, "the (d, d) matrix (a copy)")
      .def_property_readonly(
          "offset", [](const Triangulation& t) { return matrix_array(t.offset()).reshape({t.dimension()}); },
          "the offset, d numbers (a copy)")
      .def("longest_edge", &Triangulation::longest_edge, "The length of the longest edge of the d-simplices.")
      .def("locate", &locate_points, py::arg("points"), R"doc(
The minimal simplex containing each point (thesis §3.2). points: an (n, d) array (or one point of d
numbers). Returns three arrays (vertex, blocks, barycentric):
  vertex       (n, d) int32: the minimal vertex y of each simplex;
  blocks       (n, d + 1) uint8: the block of each index 0..d (blocks[:, d] is the simplex's dimension);
  barycentric  (n, d + 1) float64: the barycentric coordinates of the point in its simplex (columns
               beyond the dimension are 0).
Runs in C++ without the GIL, with no Python work per point. Raises InputError for NaN/Inf.)doc")
      .def(
          "simplex_at",
          [](const Triangulation& t, const py::handle& x) {
            return t.locate(point_rows(x, t.dimension(), "the point").data());
          },
          py::arg("point"), "The minimal simplex containing one point, as a Simplex.")
      .def(
          "vertices",
          [](const Triangulation& t, const Simplex& s) {
            if (s.d != t.dimension())
              throw InputError("the simplex is in R^" + std::to_string(s.d) + ", the triangulation of R^" +
                               std::to_string(t.dimension()));
            py::array_t<double> out({s.k + 1, static_cast<int>(s.d)});
            t.vertex_coordinates(s, out.mutable_data());
            return out;
          },
          py::arg("simplex"), "The Cartesian coordinates of the simplex's k + 1 vertices, a (k + 1, d) array.")
      .def(
          "faces", [](const Triangulation&, const Simplex& s, int k) { return faces_of(s, k); }, py::arg("simplex"),
          py::arg("k"), "The k-faces of a simplex (0 <= k <= its dimension).")
      .def(
          "cofaces", [](const Triangulation&, const Simplex& s, int l) { return cofaces_of(s, l); }, py::arg("simplex"),
          py::arg("l"), "The l-cofaces of a simplex (its dimension <= l <= d).")
      .def("__repr__", [](const Triangulation& t) {
        std::ostringstream os;
        os << "Triangulation(d=" << t.dimension() << (t.is_freudenthal() ? ", freudenthal" : "") << ")";
        return os.str();
      });
}

}  // namespace coxmesh::python
