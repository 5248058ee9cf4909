#include "distributed.h"

#include <malloc.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include "common.h"
#include "coxmesh/mesh/mesh_distributed.h"

#ifdef COXMESH_MPI
#include <mpi.h>
#endif

namespace coxmesh::cli {

namespace {

#ifdef COXMESH_MPI
[[noreturn]] void abort_job(const std::string& message) {
  std::cerr << "coxmesh: error: " << message << "\n";
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();
}

int checked_int(std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    abort_job("more than 2 GiB in one message between processes: use more processes or a coarser triangulation");
  return static_cast<int>(n);
}

class MpiCommunicator final : public Communicator {
  static constexpr int kExchangeTag = 2, kAllGatherTag = 3;  // (gather_to_root's pieces have tag 1)

 public:
  MpiCommunicator() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::byte> exchange(const std::vector<std::vector<std::byte>>& outgoing,
                                  std::vector<std::size_t>& counts) override {
    std::vector<const std::byte*> parts(size_);
    std::vector<std::size_t> sizes(size_);
    for (int r = 0; r < size_; ++r) parts[r] = outgoing[r].data(), sizes[r] = outgoing[r].size();
    return swap_parts(kExchangeTag, parts, sizes, counts);
  }

  std::vector<std::byte> all_gather(const std::vector<std::byte>& mine, std::vector<std::size_t>& counts) override {
    return swap_parts(kAllGatherTag, std::vector<const std::byte*>(size_, mine.data()),
                      std::vector<std::size_t>(size_, mine.size()), counts);
  }

  // Point to point in pieces of at most 1 GiB: rank 0 may receive more than an int counts.
  std::vector<std::byte> gather_to_root(const std::vector<std::byte>& mine, std::vector<std::size_t>& counts) override {
    constexpr std::size_t kPiece = std::size_t{1} << 30;
    std::uint64_t n = mine.size();
    std::vector<std::uint64_t> all_counts(size_);
    MPI_Request request;
    MPI_Igather(&n, 1, MPI_UINT64_T, all_counts.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
    wait(request);
    if (rank_ != 0) {
      for (std::size_t at = 0; at < mine.size(); at += kPiece)
        MPI_Send(mine.data() + at, static_cast<int>(std::min(kPiece, mine.size() - at)), MPI_BYTE, 0, 1,
                 MPI_COMM_WORLD);
      bytes_sent_ += mine.size();
      counts.clear();
      return {};
    }
    std::size_t total = 0;
    for (const std::uint64_t c : all_counts) total += c;
    std::vector<std::byte> all(total);
    std::size_t at = 0;
    for (int r = 0; r < size_; ++r) {
      if (r == 0) {
        if (!mine.empty()) std::memcpy(all.data(), mine.data(), mine.size());
      } else {
        for (std::size_t done = 0; done < all_counts[r]; done += kPiece)
          MPI_Recv(all.data() + at + done, static_cast<int>(std::min(kPiece, all_counts[r] - done)), MPI_BYTE, r, 1,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
      at += all_counts[r];
    }
    counts.assign(all_counts.begin(), all_counts.end());
    return all;
  }

  void broadcast(std::vector<std::byte>& bytes) override {
    std::uint64_t n = bytes.size();
    MPI_Request request;
    MPI_Ibcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
    wait(request);
    bytes.resize(n);
    MPI_Bcast(bytes.data(), checked_int(n), MPI_BYTE, 0, MPI_COMM_WORLD);
    if (rank_ == 0) bytes_sent_ += n * (size_ - 1);
  }

  void sum(std::uint64_t* values, int n) override {
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, values, n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD, &request);
    wait(request);
  }

 private:
  // Sends parts[r] (sizes[r] bytes) to each rank r and returns what every rank sent here,
  // concatenated in rank order (parts[rank_] copied): one message per pair of ranks, empty ones too,
  // each received once probed, at its size. So the ranks meet once per exchange, not twice (an
  // all-to-all of the sizes, then the data), and wait in wait_until, not spinning in MPI_Waitall:
  // a rank whose data was in a nap made the other spin until it woke (8 % of a rank's CPU time on
  // T3 at P = 2). Messages of one tag between two ranks arrive in the order sent, so consecutive
  // exchanges do not mix.
  std::vector<std::byte> swap_parts(int tag, const std::vector<const std::byte*>& parts,
                                    const std::vector<std::size_t>& sizes, std::vector<std::size_t>& counts) {
    std::vector<MPI_Request> sends;
    sends.reserve(size_);
    for (int r = 0; r < size_; ++r)
      if (r != rank_) {
        MPI_Isend(parts[r], checked_int(sizes[r]), MPI_BYTE, r, tag, MPI_COMM_WORLD, &sends.emplace_back());
        bytes_sent_ += sizes[r];
      }
    std::vector<MPI_Message> messages(size_, MPI_MESSAGE_NULL);
    std::vector<bool> probed(size_, false);
    counts.assign(size_, 0);
    counts[rank_] = sizes[rank_];
    int waiting = size_ - 1;
    wait_until([&] {
      for (int r = 0; r < size_; ++r) {
        if (r == rank_ || probed[r]) continue;
        int found = 0, n = 0;
        MPI_Status status;
        MPI_Improbe(r, tag, MPI_COMM_WORLD, &found, &messages[r], &status);
        if (!found) continue;
        MPI_Get_count(&status, MPI_BYTE, &n);
        counts[r] = static_cast<std::size_t>(n), probed[r] = true, --waiting;
      }
      return waiting == 0;
    });
    std::size_t total = 0;
    for (const std::size_t c : counts) total += c;
    std::vector<std::byte> in(total);
    std::size_t at = 0;
    for (int r = 0; r < size_; at += counts[r++])
      if (r == rank_) {
        if (sizes[r] > 0) std::memcpy(in.data() + at, parts[r], sizes[r]);
      } else {
        MPI_Mrecv(in.data() + at, static_cast<int>(counts[r]), MPI_BYTE, &messages[r], MPI_STATUS_IGNORE);
      }
    wait_until([&] {
      int done = 0;
      MPI_Testall(static_cast<int>(sends.size()), sends.data(), &done, MPI_STATUSES_IGNORE);
      return done != 0;
    });
    return in;
  }

  static void wait(MPI_Request& request) {
    wait_until([&] {
      int done = 0;
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }
  // Until done() (which drives MPI's progress), where a rank waits for the slowest: polled for a
  // while (the others are usually close), then asleep between polls, so that a waiting rank does
  // not take the core of a working one (or, after the walk, rank 0's while it builds the mesh).
  // Naps of at most 0.16 ms: a rank wakes soon after the others arrive (T3 at P = 2, whose walk has
  // some 600 collectives, took 0.1-0.15 s less wall time than with naps of up to 2 ms).
  template <class Done>
  static void wait_until(Done&& done) {
    const auto start = std::chrono::steady_clock::now();
    bool finished = false;
    while (!(finished = done()))
      if (std::chrono::steady_clock::now() - start > std::chrono::microseconds(200)) break;
    for (int pause_us = 20; !finished; pause_us = std::min(2 * pause_us, 160)) {
      std::this_thread::sleep_for(std::chrono::microseconds(pause_us));
      finished = done();
    }
  }

  int rank_ = 0, size_ = 1;
};

// A launcher started this process: OpenMPI's mpirun, or a PMI/PMIx one (Slurm's srun, MPICH).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

// Every rank of an OpenMPI job on this one node: the shared-memory transport of the ob1 layer
// serves them, and OpenMPI's default choice of UCX, which probes its network transports first,
// cost 0.2 s more to start (0.33 s against 0.13 s for mpirun -n 2 on a small run; the messages
// are as fast). A transport chosen by the user (OMPI_MCA_pml) is left as it is.
void prefer_shared_memory_on_one_node() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (size && local && std::strcmp(size, local) == 0) setenv("OMPI_MCA_pml", "ob1", 0);
}

// A rank builds each level of its part of the complex (and of the topology's ranges) in arrays
// and messages of tens of MB that it frees once the level is settled. glibc maps such blocks
// afresh each time and unmaps them when freed, so each level faulted its pages in again (a rank
// of T3 at P = 2 took 90 % of one process's page faults for half its cells). Kept in the heap
// instead, the next level's arrays reuse them: a rank's CPU time -6 %, its peak memory +6 %.
// (One process is left as it is: its big arrays are few, and it does not free them level by level.)
void keep_freed_memory() {
  constexpr int kKept = 256 << 20;
  mallopt(M_MMAP_THRESHOLD, kKept);  // (blocks below this from the heap; glibc's own bound grows to 32 MB)
  mallopt(M_TRIM_THRESHOLD, kKept);  // (the heap's free top given back beyond this)
}
#endif

std::unique_ptr<Communicator> session_communicator;
[[maybe_unused]] bool session_initialised = false;  // (read only with COXMESH_MPI)
std::streambuf* error_stream = nullptr;             // std::cerr's, which ranks other than 0 keep for themselves

}  // namespace

MpiSession::MpiSession([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
#ifdef COXMESH_MPI
  if (!launched_by_mpi()) return;
  prefer_shared_memory_on_one_node();
  MPI_Init(&argc, &argv);
  session_initialised = true;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) {
    session_communicator = std::make_unique<MpiCommunicator>();
    keep_freed_memory();
  }
  // Rank 0 speaks for the job (usage errors, progress, the summary): the others are silent.
  if (session_communicator && session_communicator->rank() != 0) {
    std::cout.rdbuf(nullptr);
    error_stream = std::cerr.rdbuf(nullptr);
  }
#endif
}

MpiSession::~MpiSession() {
  session_communicator.reset();
  if (error_stream) std::cout.rdbuf(nullptr), std::cerr.rdbuf(error_stream);
#ifdef COXMESH_MPI
  if (session_initialised) MPI_Finalize();
#endif
}

Communicator* MpiSession::communicator() { return session_communicator.get(); }

// Every rank ends in one broadcast of rank 0's status: rank 0 after reporting, the others after
// their part of the walk (DistributedPartDone) or after the failure that every rank met at once
// (errors in the walk are agreed by all ranks; those before it come from the same input).
int run_distributed_guarded(Communicator& comm, const std::function<void()>& body) {
  if (comm.rank() == 0) {
    const int status = run_guarded(body);
    std::vector<std::byte> outcome{static_cast<std::byte>(status)};
    comm.broadcast(outcome);
    return status;
  }
  std::string error;
  try {
    body();
  } catch (const DistributedPartDone&) {
  } catch (const std::bad_alloc&) {
    error = "out of memory";
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<std::byte> outcome;
  comm.broadcast(outcome);
  const int status = outcome.empty() ? 1 : static_cast<int>(outcome[0]);
  if (status == 0 && !error.empty()) {  // (met here only: say it)
    std::ostream err(error_stream ? error_stream : std::cerr.rdbuf());
    err << "coxmesh: error: " << printable(error) << "\n";
    return 1;
  }
  return status;
}

void print_distributed_stats(std::ostream& out, const DistributedTraceStats& s, std::size_t traced,
                             const DistributedTopologyStats& topology) {
  out << "coxmesh: " << s.ranks << " processes: " << s.levels << " levels, " << s.bytes_sent << " bytes exchanged ("
      << (traced ? s.bytes_sent / traced : 0) << " per traced simplex), " << s.candidates_sent << " simplices and "
      << s.vertex_values_sent << " vertex values sent to their owners; the largest share " << s.largest_share << " of "
      << traced << " simplices; " << s.oracle_tests << " oracle tests in all";
  if (topology.cells)
    out << "; topology: " << topology.cells_to_rank0 << " of " << topology.cells
        << " cells left by the ranks' reductions, " << topology.cells_left << " by rank 0's";
  out << "\n";
}

}  // namespace coxmesh::cli
