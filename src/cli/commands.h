// Registration of the subcommands; `status` receives the exit code of the one that ran.
#pragma once

#include <CLI/CLI.hpp>

namespace coxmesh::cli {
/// The whole tool: parses argv, runs the subcommand, returns the exit status (main() of coxmesh).
int run_cli(int argc, char** argv);

void register_locate(CLI::App& app, int& status);
void register_faces(CLI::App& app, int& status);  // faces and cofaces
void register_trace(CLI::App& app, int& status);  // trace and presets
void register_quality(CLI::App& app, int& status);
void register_io(CLI::App& app, int& status);  // convert and check
}  // namespace coxmesh::cli
