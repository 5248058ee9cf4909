// What the point-file readers share, and one reader per format family, each in its own file:
// point_text.cpp (.xyz .txt .csv .off), point_ply.cpp, point_npy.cpp; read_points
// (point_reader.cpp) picks one by the extension and validates what it returns. Internal: not part
// of the library's interface.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "coxmesh/io/point_reader.h"

namespace coxmesh::point_files {

/// Throws InputError "path: what".
[[noreturn]] void fail(const std::string& path, const std::string& what);

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// Lines of text with their 1-based numbers; '#' comments cut off.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    return true;
  }
  std::size_t number() const { return number_; }
  std::size_t position() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, number_ = 0;
};

/// The fields of a line: separated by white space (separator ' ') or by `separator`, trimmed.
std::vector<std::string_view> split(std::string_view line, char separator);
/// split into `out` (cleared first): no allocation once `out` is large enough.
void split_into(std::string_view line, char separator, std::vector<std::string_view>& out);

inline std::string where(std::size_t line) { return "line " + std::to_string(line); }

/// The number in `token`, finite; fails naming the path and the place otherwise.
double checked(std::string_view token, const std::string& path, const std::string& place);

/// The number of PLY type `type` (char, uchar, …, float, double, or int8 … float64) stored
/// little-endian at p (point_ply.cpp; the binary readers assume a little-endian machine).
double ply_value(const char* p, const std::string& type);

/// .xyz .txt (separator ' ') and .csv (','): rows of numbers (point_text.cpp).
PointSet read_rows(const std::string& path, std::string_view text, char separator, bool header_allowed,
                   bool xyz_normals, const PointReadOptions& options);
/// .off: the vertices of OFF / NOFF / COFF / nOFF files (point_text.cpp).
PointSet read_off(const std::string& path, std::string_view text);
/// .ply, ascii and binary little-endian (point_ply.cpp).
PointSet read_ply(const std::string& path, std::string_view text);
/// .npy, float64 or float32 (point_npy.cpp).
PointSet read_npy(const std::string& path, std::string_view text);

}  // namespace coxmesh::point_files
