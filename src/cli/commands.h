// Registration of the subcommands; `status` receives the exit code of the one that ran.
#pragma once

#include <CLI/CLI.hpp>

namespace coxmesh::cli {
void register_locate(CLI::App& app, int& status);
void register_faces(CLI::App& app, int& status);  // faces and cofaces
}  // namespace coxmesh::cli
