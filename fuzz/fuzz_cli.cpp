// The command line, run in-process: the input is split into argv tokens at newlines (at most 12).
// Only cheap commands that read and write no file are run: locate, faces, cofaces (when the
// simplex has few faces or cofaces), presets, and trace with --no-output -q --threads 1
// --max-simplices 2000, ambient dimension ≤ 5 and --edge-length ≥ 0.05. Inputs outside these
// bounds are skipped, not run. Output goes nowhere.
#include <cstdint>
#include <iostream>
#include <optional>
#include <streambuf>
#include <string>
#include <vector>

#include "commands.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/util/parse_number.h"

using namespace coxmesh;

namespace {

struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
};

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// The value of option `name` ("--name value" or "--name=value"), if given.
std::optional<std::string> option_value(const std::vector<std::string>& args, const std::string& name) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == name && i + 1 < args.size()) return args[i + 1];
    if (starts_with(args[i], (name + "=").c_str())) return args[i].substr(name.size() + 1);
  }
  return std::nullopt;
}

// Options that name files or set the limits the harness fixes itself.
bool forbidden(const std::string& a) {
  for (const char* name :
       {"--points", "--matrix", "--output", "--project", "--plot", "--format", "--threads", "--max-simplices"})
    if (starts_with(a, name)) return true;
  // Short options, alone or bundled ("-qo"): only -q is harmless; "-1,0" is a value.
  if (a.size() >= 2 && a[0] == '-' && a[1] != '-' && !(a[1] >= '0' && a[1] <= '9') && a[1] != '.')
    return a.find_first_not_of("-q") != std::string::npos;
  return false;
}

// A variable x<i> of an expression with i beyond 5 (the dimension an expression implies).
bool high_variable(const std::string& a) {
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    if (a[i] == 'x' && a[i + 1] >= '0' && a[i + 1] <= '9') {
      std::size_t j = i + 1;
      while (j < a.size() && a[j] >= '0' && a[j] <= '9') ++j;
      if (j - i - 1 > 1 || a[i + 1] > '5') return true;
    }
  return false;
}

bool cheap(const std::vector<std::string>& args) {
  const std::string& command = args[0];
  if (command == "convert" || command == "check" || command == "quality") return false;  // files, long tables
  for (const std::string& a : args)
    if (forbidden(a)) return false;
  if (command == "faces" || command == "cofaces") {
    const auto text = option_value(args, "--simplex");
    if (!text) return true;
    Simplex s;
    try {
      s = parse_simplex(*text);
    } catch (const InputError&) {
      return true;  // the command reports it
    }
    if (command == "faces") return s.k <= 12;
    std::uint64_t total = 0;
    for (int l = s.k; l <= s.d; ++l) try {
        total += coface_count(s, l);
      } catch (const InputError&) {
        return false;
      }
    return total <= 20000;
  }
  if (command == "trace") {
    for (const std::string& a : args)
      if (high_variable(a)) return false;
    if (const auto dim = option_value(args, "--dim")) {
      const auto v = parse_unsigned(*dim);
      if (v && *v > 5) return false;  // (m = 5 in R^6: seconds for the cell complex alone)
    }
    for (const char* name : {"--edge-length", "--scale"})
      if (const auto h = option_value(args, name)) {
        const auto v = parse_double(*h);
        if (v && !(*v >= 0.05)) return false;
      }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  static NullBuffer null;
  std::cout.rdbuf(&null);
  std::cerr.rdbuf(&null);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n' || data[i] == '\0') {
      if (args.size() == 12) return 0;
      args.emplace_back();
    } else {
      args.back() += static_cast<char>(data[i]);
    }
  }
  if (!cheap(args)) return 0;
  if (args[0] == "trace")
    for (const char* a : {"--no-output", "-q", "--threads", "1", "--max-simplices", "2000"}) args.emplace_back(a);
  std::vector<char*> argv{const_cast<char*>("coxmesh")};
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  coxmesh::cli::run_cli(static_cast<int>(argv.size()) - 1, argv.data());
  return 0;
}
