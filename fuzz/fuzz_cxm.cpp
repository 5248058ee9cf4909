// The .cxm reader on arbitrary bytes. Whatever it accepts must go through the topology, the
// writers' geometry and a write/read round trip without a crash, a sanitizer report or a hang.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/native_format.h"
#include "coxmesh/io/polygons.h"

using namespace coxmesh;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  NativeFile file;
  try {
    file = read_native(in, "fuzz.cxm");
  } catch (const InputError&) {
    return 0;  // refused: the expected outcome for most inputs
  }
  analyze_topology(file.cells);
  edge_ends(file.cells, CellKind::interior);
  edge_ends(file.cells, CellKind::boundary);
  polygon_cycles(file.cells);
  // What was accepted must be written back in a form the reader accepts again, identically.
  std::stringstream once, twice;
  write_native(once, file.cells, file.info);
  const std::string first = once.str();
  const NativeFile again = read_native(once, "rewritten.cxm");
  write_native(twice, again.cells, again.info);
  if (twice.str() != first) std::abort();
  return 0;
}
