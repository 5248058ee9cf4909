// The command line parsed and run: main() of the tool, callable in-process (the CLI fuzz target).
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.h"
#include "common.h"

namespace coxmesh::cli {

int run_cli(int argc, char** argv) {
  CLI::App app{"coxmesh: mesh submanifolds of any dimension with Coxeter triangulations"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "coxmesh 0.1.0");
  int status = 0;
  register_locate(app, status);
  register_faces(app, status);
  register_trace(app, status);
  register_quality(app, status);
  register_io(app, status);
  if (argc > 1 && argv[1][0] != '-') {  // CLI11 would only say that a subcommand is required
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      found |= sub->get_name() == argv[1];
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found) {
      std::cerr << "coxmesh: error: unknown subcommand '" << printable(argv[1]) << "' (known: " << known << ")\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A usage error: one line, exit status 2 (docs/cli.md).
    std::cerr << "coxmesh: error: " << printable(e.what()) << " (see coxmesh --help)\n";
    return 2;
  } catch (const std::exception& e) {  // (subcommands catch their own; this is the last resort)
    std::cerr << "coxmesh: error: " << printable(e.what()) << "\n";
    return 1;
  }
  return status;
}

}  // namespace coxmesh::cli
