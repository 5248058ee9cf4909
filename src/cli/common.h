// Shared pieces of the subcommands: triangulation options, number parsing, JSON for simplices.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coxmesh/triangulation/triangulation.h"

namespace coxmesh::cli {

/// The options that choose the ambient triangulation, shared by locate, trace, ...
struct TriangulationOptions {
  std::string kind = "coxeter";  // coxeter | freudenthal
  std::string matrix_file;       // replaces the whole linear part
  std::optional<double> scale, edge_length;
  std::string offset;  // "b1,...,bd"
  std::optional<std::uint64_t> rotation_seed;

  void add_to(CLI::App& app);
  /// Builds the triangulation of R^d; throws InputError on inconsistent options.
  Triangulation build(int d) const;
};

/// Parses "x1,...,xn" (whitespace or commas), every token fully consumed, finite; throws InputError.
std::vector<double> parse_point(const std::string& text, const std::string& what);

/// `text` fit for one line of a message: control characters shown as '?' (newlines as \\n), cut
/// at max_length bytes. Bytes that are not UTF-8 are for the JSON writer to replace (error_handler).
std::string printable(const std::string& text, std::size_t max_length = 200);

/// "8G", "500M", "1048576": bytes, with an optional suffix K, M, G or T (powers of 1024); > 0.
std::uint64_t parse_bytes(const std::string& text, const std::string& what);
/// Three quarters of the machine's physical memory (16 GiB when it cannot be read).
std::uint64_t default_memory_limit();

/// CLI11 check of an unsigned option: all digits, below 2^64 (CLI11 itself wraps "-5" around).
const CLI::Validator& unsigned_integer();

nlohmann::json simplex_json(const Simplex& s);
nlohmann::json simplex_json(const Simplex& s, const Triangulation& t);  // with "cartesian"

/// Runs a subcommand body, turning InputError and I/O errors into one line on stderr and exit 1.
int run_guarded(const std::function<void()>& body);

}  // namespace coxmesh::cli
