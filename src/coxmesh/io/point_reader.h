// Reading point clouds (samples of a manifold, thesis Ch. 4) from the common files: rows of numbers
// (.xyz, .txt, .csv), the vertices of .off / nOFF and .ply meshes, and NumPy .npy arrays.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace coxmesh {

/// n points of R^d, row-major, with optional normals (n × d, when the file has them).
struct PointSet {
  int dimension = 0;
  std::vector<double> points;
  std::vector<double> normals;  ///< empty, or one per point
  std::size_t duplicates = 0;   ///< exact duplicates removed (the first occurrence kept)
  std::string format;           ///< "xyz", "txt", "csv", "off", "ply", "npy"
  std::size_t size() const { return dimension ? points.size() / dimension : 0; }
};

struct PointReadOptions {
  /// The expected d (0: from the file). For .xyz, rows of 6 numbers are 3 coordinates and a
  /// normal unless dimension = 6 is asked for.
  int dimension = 0;
};

/// Reads the points of `path`; the format comes from the extension:
///   .xyz .txt   one point per line, numbers separated by white space, '#' starts a comment;
///               every row the same length d (.xyz: 6 numbers = x y z nx ny nz)
///   .csv        the same with commas; a first line that is not numbers is a header and skipped
///   .off        the vertices of OFF / NOFF / COFF / nOFF (any d) files; faces are skipped
///   .ply        the x, y, z (and nx, ny, nz) properties of the vertex element; ascii and
///               binary_little_endian; other elements and properties are skipped
///   .npy        a float64 or float32 array ('<f8', '<f4'), C order, of shape (n, d)
/// Exact duplicate points are removed (counted in `duplicates`). Throws InputError, naming the
/// file and the place, on: an unknown extension, a directory or unreadable file, malformed
/// numbers, NaN or infinite values, rows of different lengths, headers announcing more data than
/// the file holds, no points, or d outside 1..31.
PointSet read_points(const std::string& path, const PointReadOptions& options = {});

/// The samples of an n × d array (row-major) with optional normals (empty or n × d), checked as a
/// file's are (d in 1..31, finite values, at least one point), duplicates removed; format "array".
/// Throws InputError.
PointSet point_set_from_rows(std::vector<double> points, int d, std::vector<double> normals = {});

/// Removes exact duplicates in place (first occurrence kept, order otherwise unchanged); returns
/// how many were removed.
std::size_t remove_duplicate_points(PointSet& set);

}  // namespace coxmesh
