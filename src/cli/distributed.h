// `coxmesh trace` run by several processes (mpirun, srun): the MPI session of the tool and the
// error protocol of its ranks. Without a launcher MPI is never initialised.
#pragma once

#include <functional>
#include <iosfwd>

#include "coxmesh/cell_complex/topology_distributed.h"
#include "coxmesh/tracing/trace_distributed.h"
#include "coxmesh/util/communicator.h"

namespace coxmesh::cli {

/// Lives in main(): initialises MPI when a launcher started this process (and the tool was built
/// with MPI), finalises it at the end.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  /// The processes of the job when there are several, else null (work as one process).
  static Communicator* communicator();
};

/// run_guarded for a subcommand body run by every rank: rank 0 prints the error, if any, and the
/// other ranks (which end in DistributedPartDone) exit with rank 0's status.
int run_distributed_guarded(Communicator& comm, const std::function<void()>& body);

/// One line on what the ranks exchanged, for the user who wonders what several processes cost.
void print_distributed_stats(std::ostream& out, const DistributedTraceStats& stats, std::size_t traced,
                             const DistributedTopologyStats& topology);

}  // namespace coxmesh::cli
