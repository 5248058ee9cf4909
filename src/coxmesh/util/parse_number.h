// Strict number parsing for user input: a token is a number only if all of it is consumed.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace coxmesh {

/// The value of `token` if the whole token is a number (NaN and ±Inf included: callers decide
/// whether those are allowed), otherwise nothing.
inline std::optional<double> parse_double(const std::string& token) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(token, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (token.empty() || used != token.size()) return std::nullopt;
  return v;
}

}  // namespace coxmesh
