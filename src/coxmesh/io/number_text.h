// Shortest round-trip decimal text of numbers, for the text formats (OFF, OBJ, medit).
#pragma once

#include <charconv>
#include <string>

namespace coxmesh {

/// Appends the shortest decimal form of x that reads back as exactly x.
inline void append_number(std::string& out, double x) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, r.ptr);
}

/// Appends an unsigned integer.
inline void append_number(std::string& out, unsigned long long x) {
  char buffer[24];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, r.ptr);
}

}  // namespace coxmesh
