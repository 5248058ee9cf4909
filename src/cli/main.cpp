// coxmesh: the command-line tool. Each subcommand lives in its own cmd_*.cpp file; run_cli.cpp
// parses the command line.
#include "commands.h"

int main(int argc, char** argv) { return coxmesh::cli::run_cli(argc, argv); }
