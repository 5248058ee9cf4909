// coxmesh faces / cofaces: faces and cofaces of a simplex given in text form (thesis §3.5).
#include <iostream>

#include "commands.h"
#include "common.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"

namespace coxmesh::cli {

namespace {

struct FacesOptions {
  std::string simplex;
  std::optional<int> dim;
  bool json = false;
};

template <class Enumerator>
void list(const FacesOptions& o, bool faces) {
  const Simplex s = parse_simplex(o.simplex);
  int lo = faces ? 0 : s.k, hi = faces ? s.k : s.d;
  if (o.dim) {
    if (*o.dim < lo || *o.dim > hi)
      throw InputError("--dim " + std::to_string(*o.dim) + " is outside " + std::to_string(lo) + ".." +
                       std::to_string(hi) + " for this simplex");
    lo = hi = *o.dim;
  }
  // Streamed, JSON too: the cofaces of a simplex number up to (d+1)!, millions for d = 9.
  const char* separator = "[";
  for (int k = lo; k <= hi; ++k) {
    Enumerator e(s, k);
    for (Simplex f; e.next(f);) {
      if (o.json)
        std::cout << separator << simplex_json(f).dump(), separator = ",";
      else
        std::cout << to_string(f) << "\n";
    }
  }
  if (o.json) std::cout << (*separator == '[' ? "[]" : "]") << "\n";
}

void add(CLI::App& app, int& status, bool faces) {
  auto o = std::make_shared<FacesOptions>();
  CLI::App* cmd = app.add_subcommand(faces ? "faces" : "cofaces",
                                     faces ? "list the faces of a simplex" : "list the cofaces of a simplex");
  cmd->add_option("--simplex", o->simplex, "the simplex, e.g. \"(0,0,0) [{0},{1,2},{3}]\"")->required();
  cmd->add_option("--dim", o->dim, faces ? "face dimension (default: all)" : "coface dimension (default: all)");
  cmd->add_flag("--json", o->json, "print a JSON array");
  cmd->callback([o, &status, faces] {
    status = run_guarded([&] { faces ? list<FaceEnumerator>(*o, true) : list<CofaceEnumerator>(*o, false); });
  });
}

}  // namespace

void register_faces(CLI::App& app, int& status) {
  add(app, status, true);
  add(app, status, false);
}

}  // namespace coxmesh::cli
