// coxmesh: the command-line tool. Each subcommand lives in its own cmd_*.cpp file; run_cli.cpp
// parses the command line.
#include <malloc.h>

#include "commands.h"
#include "distributed.h"

int main(int argc, char** argv) {
  // glibc maps a block of more than 128 KiB afresh (the bound grows up to 32 MiB as such blocks are
  // freed) and unmaps it when freed, so each phase's arrays fault their pages in anew. From the heap,
  // with its free top kept up to 64 MiB, the next phase reuses them: S² at edge 0.012 and SO(3) at
  // edge 1.1 about 2 % less CPU, peak memory +1 % (docs/benchmarks.md, "Page faults and memory").
  // mpirun's ranks keep more (distributed.cpp).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  coxmesh::cli::MpiSession mpi(argc, argv);  // (under mpirun or srun only)
  return coxmesh::cli::run_cli(argc, argv);
}
