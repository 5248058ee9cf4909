// The collective operations that the walk of several processes needs (tracing/walk_distributed.h),
// behind an interface: the library does not depend on MPI, and the command-line tool supplies an
// MPI implementation when it is built with one (cli/mpi_session.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace coxmesh {

/// Every call is collective: all ranks make the same calls in the same order.
class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Sends outgoing[r] to rank r; returns what the ranks sent here, concatenated in rank order, with
  /// the byte count from each rank in `counts` (one all-to-all of counts, one of the data).
  virtual std::vector<std::byte> exchange(const std::vector<std::vector<std::byte>>& outgoing,
                                          std::vector<std::size_t>& counts) = 0;
  /// Every rank's bytes, concatenated in rank order, on every rank (counts per rank in `counts`).
  virtual std::vector<std::byte> all_gather(const std::vector<std::byte>& mine, std::vector<std::size_t>& counts) = 0;
  /// Every rank's bytes, in rank order, on rank 0 only (empty elsewhere).
  virtual std::vector<std::byte> gather_to_root(const std::vector<std::byte>& mine,
                                                std::vector<std::size_t>& counts) = 0;
  /// Rank 0's bytes on every rank.
  virtual void broadcast(std::vector<std::byte>& bytes) = 0;
  /// Element-wise sums over the ranks, in place.
  virtual void sum(std::uint64_t* values, int n) = 0;

  /// Bytes this rank has sent to other ranks so far (its own share not counted).
  std::uint64_t bytes_sent() const { return bytes_sent_; }

 protected:
  std::uint64_t bytes_sent_ = 0;
};

/// Appends n values to a message, and reads them back (raw bytes: every rank is the same program).
template <class T>
void put(std::vector<std::byte>& out, const T* x, std::size_t n) {
  if (n == 0) return;  // (x may be the null data() of an empty vector, which memcpy must not get)
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  std::memcpy(out.data() + at, x, n * sizeof(T));
}
template <class T>
void take(const std::byte*& in, T* x, std::size_t n) {
  if (n == 0) return;
  std::memcpy(x, in, n * sizeof(T));
  in += n * sizeof(T);
}

}  // namespace coxmesh
