// coxmesh: the command-line tool. Each subcommand lives in its own cmd_*.cpp file.
#include <CLI/CLI.hpp>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"coxmesh: mesh submanifolds of any dimension with Coxeter triangulations"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "coxmesh 0.1.0");
  int status = 0;
  coxmesh::cli::register_locate(app, status);
  coxmesh::cli::register_faces(app, status);
  coxmesh::cli::register_trace(app, status);
  coxmesh::cli::register_quality(app, status);
  coxmesh::cli::register_io(app, status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return status;
}
