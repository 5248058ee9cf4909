#include "common.h"
#include "coxmesh/io/number_rows.h"
#include "coxmesh/util/parse_number.h"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <iostream>

namespace coxmesh::cli {

void TriangulationOptions::add_to(CLI::App& app) {
  app.add_option("--triangulation", kind, "ambient triangulation: coxeter (A~_d, unit heights) or freudenthal")
      ->check(CLI::IsMember({"coxeter", "freudenthal"}))
      ->capture_default_str();
  app.add_option("--matrix", matrix_file,
                 "file with d rows of d numbers: lattice point y sits at matrix*y + offset (replaces "
                 "--triangulation and --scale)");
  auto* s = app.add_option("--scale", scale, "multiply the linear part by S (larger S, larger simplices)");
  auto* h = app.add_option("--edge-length", edge_length, "scale so that the longest edge of every d-simplex is H");
  s->excludes(h);
  app.add_option("--offset", offset,
                 "translation b1,...,bd of the triangulation (default 0; --points: the centre of the samples)");
  app.add_option("--rotate", rotation_seed, "apply a random rotation drawn from this seed (deterministic)")
      ->check(unsigned_integer());
}

Triangulation TriangulationOptions::build(int d) const {
  check_dimension(d);
  std::optional<Triangulation> t;
  if (!matrix_file.empty()) {
    if (scale) throw InputError("--scale cannot be combined with --matrix (the matrix is the whole linear part)");
    Eigen::MatrixXd m = read_matrix_file(matrix_file);
    if (m.rows() != d)
      throw InputError("the matrix is " + std::to_string(m.rows()) + "x" + std::to_string(m.cols()) +
                       " but the dimension is " + std::to_string(d));
    t.emplace(m, Eigen::VectorXd::Zero(d));
  } else {
    t.emplace(kind == "freudenthal" ? Triangulation::freudenthal(d) : Triangulation::coxeter(d));
    if (scale) t = t->scaled(*scale);
  }
  if (rotation_seed) t = t->rotated(*rotation_seed);
  if (edge_length) t = t->with_longest_edge(*edge_length);
  if (!offset.empty()) {
    std::vector<double> b = parse_point(offset, "--offset");
    if (static_cast<int>(b.size()) != d)
      throw InputError("--offset has " + std::to_string(b.size()) + " coordinates, expected " + std::to_string(d));
    t = t->with_offset(Eigen::Map<const Eigen::VectorXd>(b.data(), d));
  }
  return *t;
}

std::vector<double> parse_point(const std::string& text, const std::string& what) {
  // Fields are separated by one comma or by whitespace; an empty field ("1,,2", "1,") is an error.
  std::vector<double> out;
  std::size_t i = 0;
  const auto space = [&text](std::size_t at) { return std::isspace(static_cast<unsigned char>(text[at])) != 0; };
  while (true) {
    while (i < text.size() && space(i)) ++i;
    if (i >= text.size()) break;
    std::size_t j = i;
    while (j < text.size() && text[j] != ',' && !space(j)) ++j;
    if (j == i) throw InputError(what + ": an empty field in '" + printable(text) + "'");
    const std::string tok = text.substr(i, j - i);
    const std::optional<double> v = parse_double(tok);
    if (!v) throw InputError(what + ": '" + printable(tok) + "' is not a number");
    if (!std::isfinite(*v)) throw InputError(what + ": NaN or infinite coordinate '" + tok + "'");
    out.push_back(*v);
    while (j < text.size() && space(j)) ++j;
    if (j < text.size() && text[j] == ',') {
      ++j;
      std::size_t k = j;
      while (k < text.size() && space(k)) ++k;
      if (k >= text.size() || text[k] == ',') throw InputError(what + ": an empty field in '" + printable(text) + "'");
    }
    i = j;
  }
  if (out.empty()) throw InputError(what + ": no coordinates in '" + printable(text) + "'");
  return out;
}

std::string printable(const std::string& text, std::size_t max_length) {
  std::string out;
  for (unsigned char c : text) {
    if (out.size() >= max_length) return out + "...";
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c < 0x20 || c == 0x7f)
      out += '?';
    else
      out += static_cast<char>(c);
  }
  return out;
}

std::uint64_t parse_bytes(const std::string& text, const std::string& what) {
  std::string digits = text;
  int shift = 0;
  if (!digits.empty()) {
    const std::string suffixes = "KMGT";
    if (const auto at = suffixes.find(static_cast<char>(std::toupper(static_cast<unsigned char>(digits.back()))));
        at != std::string::npos) {
      shift = 10 * static_cast<int>(at + 1);
      digits.pop_back();
    }
  }
  const std::optional<std::uint64_t> v = parse_unsigned(digits);
  if (!v || *v == 0 || *v > (~std::uint64_t{0} >> shift))
    throw InputError(what + ": '" + printable(text) +
                     "' is not a positive size (bytes, or a number with K, M, G or T)");
  return *v << shift;
}

std::uint64_t default_memory_limit() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t{16} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 4 * 3;
}

const CLI::Validator& unsigned_integer() {
  static const CLI::Validator v(
      [](std::string& text) {
        return parse_unsigned(text) ? std::string()
                                    : "'" + printable(text) + "' is not a non-negative integer below 2^64";
      },
      "UINT");
  return v;
}

nlohmann::json simplex_json(const Simplex& s) {
  nlohmann::json j;
  j["dimension"] = s.dimension();
  j["vertex"] = std::vector<int>(s.y.begin(), s.y.begin() + s.d);
  j["partition"] = s.partition();
  return j;
}

nlohmann::json simplex_json(const Simplex& s, const Triangulation& t) {
  nlohmann::json j = simplex_json(s);
  std::vector<double> xs((s.k + 1) * s.d);
  t.vertex_coordinates(s, xs.data());
  nlohmann::json pts = nlohmann::json::array();
  for (int v = 0; v <= s.k; ++v) pts.push_back(std::vector<double>(xs.begin() + v * s.d, xs.begin() + (v + 1) * s.d));
  j["cartesian"] = pts;
  return j;
}

int run_guarded(const std::function<void()>& body) {
  try {
    body();
    return 0;
  } catch (const InputError& e) {
    std::cerr << "coxmesh: error: " << printable(e.what(), 400) << "\n";
  } catch (const std::ios_base::failure& e) {
    std::cerr << "coxmesh: error: " << printable(e.what()) << "\n";
  } catch (const std::runtime_error& e) {
    std::cerr << "coxmesh: error: " << printable(e.what()) << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "coxmesh: error: out of memory (give a larger --edge-length or a smaller --max-simplices)\n";
  } catch (const std::exception& e) {
    std::cerr << "coxmesh: error: " << printable(e.what()) << "\n";
  }
  return 1;
}

}  // namespace coxmesh::cli
