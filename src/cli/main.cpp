// coxmesh: the command-line tool. Each subcommand lives in its own cmd_*.cpp file; run_cli.cpp
// parses the command line.
#include "commands.h"
#include "distributed.h"

int main(int argc, char** argv) {
  coxmesh::cli::MpiSession mpi(argc, argv);  // (under mpirun or srun only)
  return coxmesh::cli::run_cli(argc, argv);
}
