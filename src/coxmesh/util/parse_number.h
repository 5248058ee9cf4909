// Strict number parsing for user input: a token is a number only if all of it is consumed.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace coxmesh {

/// The value of `token` if the whole token is a number (NaN and ±Inf included: callers decide
/// whether those are allowed; subnormals such as 1e-320 are numbers), otherwise nothing: also
/// for values beyond the range of double.
inline std::optional<double> parse_double(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);  // from_chars takes no '+'
  double v = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return v;
}

/// A non-negative integer that fits 64 bits, all of `token` consumed (no sign, no wrap-around).
inline std::optional<std::uint64_t> parse_unsigned(std::string_view token) {
  std::uint64_t v = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return v;
}

}  // namespace coxmesh
