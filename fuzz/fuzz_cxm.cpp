// The .cxm reader on arbitrary bytes. Whatever it accepts must go through the topology, the
// writers' geometry and a write/read round trip without a crash, a sanitizer report or a hang.
// The same bytes as one piece of a file written by several processes (native_pieces.h), assembled
// alone, must be refused or assembled into a complex the reader accepts, never a crash.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/native_format.h"
#include "coxmesh/io/native_pieces.h"
#include "coxmesh/io/polygons.h"

using namespace coxmesh;

namespace {

void assemble_as_piece(const std::string& bytes) {
  std::istringstream in(bytes);
  try {
    std::vector<CellComplexPart> parts;
    parts.push_back(read_native_piece(in, "fuzz_0.cxm"));
    std::stringstream whole;
    write_native(whole, assemble_cell_complex(std::move(parts)), NativeInfo{});
    read_native(whole, "assembled.cxm");
  } catch (const InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  assemble_as_piece(bytes);
  std::istringstream in(bytes);
  NativeFile file;
  try {
    file = read_native(in, "fuzz.cxm");
  } catch (const InputError&) {
    return 0;  // refused: the expected outcome for most inputs
  }
  analyze_topology(file.cells);
  edge_ends(file.cells, CellKind::interior);
  edge_ends(file.cells, CellKind::boundary);
  const Ragged polygons = polygon_cycles(file.cells);
  for (CellKind kind : {CellKind::interior, CellKind::boundary}) polyhedron_faces(file.cells, kind, polygons);
  // What was accepted must be written back in a form the reader accepts again, identically.
  std::stringstream once, twice;
  write_native(once, file.cells, file.info);
  const std::string first = once.str();
  const NativeFile again = read_native(once, "rewritten.cxm");
  write_native(twice, again.cells, again.info);
  if (twice.str() != first) std::abort();
  return 0;
}
