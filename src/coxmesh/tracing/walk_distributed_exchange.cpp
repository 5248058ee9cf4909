// Thesis §4.2 over several processes: what the ranks of the distributed walk exchange, i.e. the
// vertex values, the discoveries of a level, the order of the next level, the failures and, at
// the end, S itself (gathered on rank 0 in the order of the sequential walk).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <sstream>

#include "coxmesh/tracing/walk_distributed.h"

namespace coxmesh {

int owner_rank(const std::int32_t* v, int d, int ranks) {
  if (ranks == 1) return 0;
  std::uint32_t block[kMaxDimension];
  const int bits = owner_block_bits(d);
  for (int i = 0; i < d; ++i) block[i] = static_cast<std::uint32_t>(v[i] >> bits);  // (floor)
  return static_cast<int>(hash_words(block, d) % static_cast<std::uint64_t>(ranks));
}

namespace walk {

namespace {

enum class ErrorKind : std::uint8_t { other, input, seed, evaluation, memory };

}  // namespace

void DistributedWalk::agree(std::exception_ptr failure) { agree_on_failure(comm_, failure); }

}  // namespace walk

void agree_on_failure(Communicator& comm, std::exception_ptr failure) {
  using walk::ErrorKind;
  std::uint64_t failed = failure ? 1 : 0;
  comm.sum(&failed, 1);
  if (failed == 0) return;
  std::vector<std::byte> mine;
  if (failure) {
    ErrorKind kind = ErrorKind::other;
    std::string message = "unknown error";
    try {
      std::rethrow_exception(failure);
    } catch (const InputError& e) {
      kind = ErrorKind::input, message = e.what();
    } catch (const SeedError& e) {
      kind = ErrorKind::seed, message = e.what();
    } catch (const EvaluationError& e) {
      kind = ErrorKind::evaluation, message = e.what();
    } catch (const std::bad_alloc&) {
      kind = ErrorKind::memory;
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
    }
    put(mine, &kind, 1);
    put(mine, message.data(), message.size());
  }
  std::vector<std::size_t> counts;
  const std::vector<std::byte> all = comm.all_gather(mine, counts);
  // Every rank throws the failure of the first rank that failed.
  std::size_t at = 0;
  int r = 0;
  while (counts[r] == 0) at += counts[r++];
  const auto kind = static_cast<ErrorKind>(all[at]);
  const std::string message(reinterpret_cast<const char*>(all.data() + at + 1), counts[r] - 1);
  switch (kind) {
    case ErrorKind::input:
      throw InputError(message);
    case ErrorKind::seed:
      throw SeedError(message);
    case ErrorKind::evaluation:
      throw EvaluationError(message);
    case ErrorKind::memory:
      throw std::bad_alloc();
    default:
      throw std::runtime_error(message);
  }
}

namespace walk {

// The values of F (and D) at a vertex this rank owns, evaluated now if no one has.
void DistributedWalk::evaluate_here(const std::int32_t* v, double* out) {
  const auto* key = reinterpret_cast<const std::uint32_t*>(v);
  const std::uint64_t h = hash_words(key, d_);
  values_.get(v, h, out, [&](double* values) {
    evaluate_(v, values);
    ++evaluations_;
    for (int i = 0; i < values_.stride(); ++i)
      if (!std::isfinite(values[i])) {
        double x[kMaxDimension];
        t_.cartesian(v, x);
        std::ostringstream os;
        os.precision(17);
        os << (i < k_ ? "the function" : "the domain function") << " is not finite (" << values[i] << ") at (";
        for (int j = 0; j < d_; ++j) os << (j ? "," : "") << x[j];
        os << ")";
        throw EvaluationError(os.str());
      }
  });
  known_vertices_.insert(key, h);
}

// Makes the values at `vertices` (d coordinates each, repeats allowed) readable from values_: the
// vertices owned here are evaluated here, the others asked from their owners in one exchange.
void DistributedWalk::fetch_vertex_values(const std::vector<std::int32_t>& vertices) {
  const int stride = values_.stride();
  std::vector<double> scratch(stride);
  std::vector<std::vector<std::byte>> requests(ranks_), replies(ranks_);
  PackedKeyIndex asked(d_);
  std::exception_ptr failure;
  try {
    // Hashed first, so that the look-ups (mostly of vertices known already: a level lists each
    // vertex many times) fetch their slots ahead.
    constexpr std::size_t kAhead = 16;
    const std::size_t n = vertices.size() / d_;
    std::vector<std::uint64_t> hashes(n);
    for (std::size_t i = 0; i < n; ++i)
      hashes[i] = hash_words(reinterpret_cast<const std::uint32_t*>(vertices.data() + i * d_), d_);
    for (std::size_t i = 0; i < n; ++i) {
      if (i + kAhead < n) known_vertices_.prefetch(hashes[i + kAhead]);
      if (i + kAhead / 2 < n) known_vertices_.prefetch_key(hashes[i + kAhead / 2]);
      const std::int32_t* v = vertices.data() + i * d_;
      const auto* key = reinterpret_cast<const std::uint32_t*>(v);
      const std::uint64_t h = hashes[i];
      if (known_vertices_.find(key, h) != PackedKeyIndex::kAbsent) continue;
      const int owner = last_owner_.of(v);
      if (owner == rank_)
        evaluate_here(v, scratch.data());
      else if (asked.insert(key, h).second)
        put(requests[owner], v, d_);
    }
  } catch (...) {
    failure = std::current_exception();
  }
  // A failure here is agreed on after the requests are answered, in one agreement: the requests
  // of a rank that failed are cut short, and nothing reads their answers.
  std::vector<std::size_t> counts;
  const std::vector<std::byte> asked_here = comm_.exchange(requests, counts);
  if (!failure) {  // (a rank that failed answers nothing: every rank throws below)
    try {
      const std::byte* in = asked_here.data();
      std::int32_t v[kMaxDimension];
      for (int r = 0; r < ranks_; ++r)
        for (std::size_t n = counts[r] / (sizeof(std::int32_t) * d_); n > 0; --n) {
          take(in, v, d_);
          evaluate_here(v, scratch.data());
          put(replies[r], scratch.data(), stride);
          ++vertex_values_sent_;
        }
    } catch (...) {
      failure = std::current_exception();
    }
  }
  agree(failure);
  const std::vector<std::byte> answers = comm_.exchange(replies, counts);
  const std::byte* in = answers.data();
  for (int r = 0; r < ranks_; ++r) {
    const auto* v = reinterpret_cast<const std::int32_t*>(requests[r].data());
    for (std::size_t n = requests[r].size() / (sizeof(std::int32_t) * d_); n > 0; --n, v += d_) {
      const auto* key = reinterpret_cast<const std::uint32_t*>(v);
      const std::uint64_t h = hash_words(key, d_);
      // (the answer is passed over even where the values are stored already: the next is at a fixed place)
      const std::byte* answer = in;
      in += sizeof(double) * stride;
      values_.get(v, h, scratch.data(), [&](double* values) { take(answer, values, stride); });
      known_vertices_.insert(key, h);
    }
  }
}

// fetch_vertex_values when every rank reads every one of `vertices` (a seed's ring, which every
// rank goes through): each owner sends the values of its vertices to every other rank unasked, in
// one exchange instead of two and an agreement (2000 seeds make most of the meetings of a --box
// run). Returns the failure here (nullptr: none), for the caller to agree on; the values that did
// arrive are kept.
std::exception_ptr DistributedWalk::push_vertex_values(const std::vector<std::int32_t>& vertices) {
  std::exception_ptr failure;
  const int stride = values_.stride();
  std::vector<double> scratch(stride);
  std::vector<std::vector<std::byte>> pushed(ranks_);
  try {
    PackedKeyIndex sent(d_);
    for (std::size_t i = 0; i < vertices.size(); i += d_) {
      const std::int32_t* v = vertices.data() + i;
      const auto* key = reinterpret_cast<const std::uint32_t*>(v);
      if (last_owner_.of(v) != rank_ || !sent.insert(key, hash_words(key, d_)).second) continue;
      evaluate_here(v, scratch.data());
      for (int r = 0; r < ranks_; ++r)
        if (r != rank_) put(pushed[r], v, d_), put(pushed[r], scratch.data(), stride), ++vertex_values_sent_;
    }
  } catch (...) {
    failure = std::current_exception();
  }
  std::vector<std::size_t> counts;
  const std::vector<std::byte> arrived = comm_.exchange(pushed, counts);
  const std::size_t record = sizeof(std::int32_t) * d_ + sizeof(double) * stride;
  std::int32_t v[kMaxDimension];
  for (std::size_t n = arrived.size() / record, i = 0; i < n; ++i) {  // (counted: no pointer past the end)
    const std::byte* in = arrived.data() + i * record;
    take(in, v, d_);
    const auto* key = reinterpret_cast<const std::uint32_t*>(v);
    const std::uint64_t h = hash_words(key, d_);
    values_.get(v, h, scratch.data(), [&](double* values) { std::memcpy(values, in, sizeof(double) * stride); });
    known_vertices_.insert(key, h);
  }
  return failure;
}

// The level's discoveries to their owners (the smallest discovery key of a simplex wins, as the
// first discovery does in the sequential walk), and the tests of other ranks' simplices, counted
// by the owner once.
void DistributedWalk::exchange_candidates() {
  std::vector<std::size_t> counts;
  const std::vector<std::byte> found = comm_.exchange(candidates_out_, counts);
  for (auto& out : candidates_out_) out.clear();
  const std::size_t record = sizeof(std::uint32_t) * words_ + 2 * sizeof(std::uint64_t) + sizeof(double) * (d_ + 1);
  std::uint32_t key[packed_words(kMaxDimension)];
  std::uint64_t discovery, settled;
  // (the bytes left, not in + record: past the end, or from an empty buffer's null pointer, that is
  // undefined, and clang's UBSan reports it)
  const std::byte* const end = found.data() + found.size();
  for (const std::byte* in = found.data(); static_cast<std::size_t>(end - in) >= record;) {
    take(in, key, words_);
    take(in, &discovery, 1);
    take(in, &settled, 1);
    const std::uint64_t h = hash_words(key, words_);
    if (mine_.find(key, h) != PackedKeyIndex::kAbsent) {
      in += sizeof(double) * (d_ + 1);
      continue;
    }
    if (const std::uint32_t id = next_.find(key, h); id != PackedKeyIndex::kAbsent) {
      next_keys_[id] = std::min(next_keys_[id], discovery);
      next_settled_[id] |= settled;
      in += sizeof(double) * (d_ + 1);
      continue;
    }
    ++calls_;  // (tested by the sender only)
    next_.insert(key, h);
    next_keys_.push_back(discovery);
    next_settled_.push_back(settled);
    const std::size_t at = next_data_.size();
    next_data_.resize(at + d_ + 1);
    take(in, next_data_.data() + at, d_ + 1);
  }
  const std::vector<std::byte> tested = comm_.exchange(tested_out_, counts);
  for (auto& out : tested_out_) out.clear();
  for (const std::byte* in = tested.data(); in < tested.data() + tested.size();) {
    take(in, key, words_);
    const std::uint64_t h = hash_words(key, words_);
    if (mine_.find(key, h) != PackedKeyIndex::kAbsent || next_.find(key, h) != PackedKeyIndex::kAbsent) continue;
    if (others_.insert(key, h).second) {
      ++calls_;
      other_payload_.push_back(kUntested);
    }
  }
}

// The next level's discovery keys owned here, increasing (`order`: their simplices in next_).
std::vector<std::uint64_t> DistributedWalk::next_keys_in_order(std::vector<std::uint32_t>& order) const {
  order.resize(next_.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return next_keys_[a] < next_keys_[b]; });
  std::vector<std::uint64_t> keys(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) keys[i] = next_keys_[order[i]];
  return keys;
}

// The next level joins S: its global order is that of the discovery keys of all ranks.
void DistributedWalk::append_level() {
  std::vector<std::uint32_t> order;
  const std::vector<std::uint64_t> keys = next_keys_in_order(order);
  std::vector<std::byte> mine;
  put(mine, keys.data(), keys.size());
  std::vector<std::size_t> counts;
  const std::vector<std::byte> all_bytes = comm_.all_gather(mine, counts);
  std::vector<std::uint64_t> all(all_bytes.size() / sizeof(std::uint64_t));
  if (!all_bytes.empty()) std::memcpy(all.data(), all_bytes.data(), all_bytes.size());
  std::vector<std::size_t> run_begin(ranks_ + 1, 0);
  for (int r = 0; r < ranks_; ++r) run_begin[r + 1] = run_begin[r] + counts[r] / sizeof(std::uint64_t);
  join_level(order, all, run_begin);
}

// The next level joins S from every rank's keys: `all` holds one increasing run per rank (distinct
// keys), rank r's from run_begin[r]; `order` lists this rank's simplices in next_ in its run's order.
void DistributedWalk::join_level(const std::vector<std::uint32_t>& order, const std::vector<std::uint64_t>& all,
                                 const std::vector<std::size_t>& run_begin) {
  // A key's place in the level is its place in this rank's run plus, per other run, the keys below
  // it, counted by a pointer that only moves on (a merge, not a sort of the level on every rank).
  std::vector<std::size_t> below(ranks_, 0);
  level_begin_ = mine_.size();
  std::size_t place_here = 0;
  for (const std::uint32_t j : order) {
    const std::uint64_t key = next_keys_[j];
    std::size_t position = place_here++;
    for (int r = 0; r < ranks_; ++r) {
      if (r == rank_) continue;
      const std::size_t length = run_begin[r + 1] - run_begin[r];
      const std::uint64_t* run = all.data() + run_begin[r];
      while (below[r] < length && run[below[r]] < key) ++below[r];
      position += below[r];
    }
    mine_.insert(next_.key(j));
    global_ids_.push_back(static_cast<std::uint32_t>(global_size_ + position));
    const double* data = next_data_.data() + static_cast<std::size_t>(j) * (d_ + 1);
    points_.insert(points_.end(), data, data + d_);
    domain_values_.push_back(data[d_]);
    settled_.push_back(next_settled_[j]);
  }
  level_end_ = mine_.size();
  global_size_ += run_begin[ranks_];
  level_global_size_ = run_begin[ranks_];
  next_.clear();
  next_keys_.clear(), next_settled_.clear(), next_data_.clear();
}

void DistributedWalk::sum_counts(std::uint64_t& oracle_calls, std::uint64_t& function_evaluations,
                                 DistributedTraceStats* stats) {
  std::vector<std::size_t> counts;
  std::uint64_t sums[] = {
      calls_, evaluations_ + oracle_.function_evaluations(), comm_.bytes_sent(), vertex_values_sent_, candidates_sent_,
      tests_};
  comm_.sum(sums, 6);
  // The largest share of S (the balance of the split by lattice blocks).
  std::vector<std::byte> share;
  const std::uint64_t owned = mine_.size();
  put(share, &owned, 1);
  const std::vector<std::byte> shares = comm_.all_gather(share, counts);
  std::uint64_t largest = 0;
  for (int r = 0; r < ranks_; ++r) {
    std::uint64_t x;
    std::memcpy(&x, shares.data() + r * sizeof x, sizeof x);
    largest = std::max(largest, x);
  }
  if (stats) *stats = {ranks_, levels_, sums[2], sums[3], sums[4], largest, sums[5]};
  oracle_calls = sums[0], function_evaluations = sums[1];
}

// This rank's share as it stands: S's simplices owned here and the meetings with S_∂ walked here.
TracePart DistributedWalk::finish_part(DistributedTraceStats* stats) {
  TracePart part;
  sum_counts(part.oracle_calls, part.function_evaluations, stats);
  part.ambient_dimension = d_;
  part.codimension = k_;
  part.status = stopped_ ? TraceStatus::max_simplices_reached : TraceStatus::complete;
  part.simplices = std::move(mine_);
  part.points.assign(points_.begin(), points_.end());
  part.ids = std::move(global_ids_);
  part.size = global_size_;
  part.boundary_discoveries = std::move(boundary_keys_);
  part.boundary_keys = std::move(boundary_simplices_);
  part.boundary_points.assign(boundary_points_.begin(), boundary_points_.end());
  return part;
}

// S and S_∂ gathered on rank 0, each simplex at its global place; the counts summed.
TraceResult DistributedWalk::finish(DistributedTraceStats* stats) {
  std::vector<std::byte> simplices, boundary;
  for (std::uint32_t i = 0; i < mine_.size(); ++i) {
    put(simplices, &global_ids_[i], 1);
    put(simplices, mine_.key(i), words_);
    put(simplices, points_.data() + static_cast<std::size_t>(i) * d_, d_);
  }
  for (std::size_t i = 0; i < boundary_keys_.size(); ++i) {
    put(boundary, &boundary_keys_[i], 1);
    put(boundary, boundary_simplices_.data() + i * words_, words_);
    put(boundary, boundary_points_.data() + i * d_, d_);
  }
  std::vector<std::size_t> counts;
  const std::vector<std::byte> all_simplices = comm_.gather_to_root(simplices, counts);
  const std::vector<std::byte> all_boundary = comm_.gather_to_root(boundary, counts);
  std::uint64_t oracle_calls = 0, function_evaluations = 0;
  sum_counts(oracle_calls, function_evaluations, stats);

  TraceResult result;
  result.ambient_dimension = d_;
  result.codimension = k_;
  result.simplices = PackedKeyIndex(words_);
  result.boundary_simplices = PackedKeyIndex(words_);
  result.status = stopped_ ? TraceStatus::max_simplices_reached : TraceStatus::complete;
  if (rank_ != 0) return result;
  result.oracle_calls = oracle_calls;
  result.function_evaluations = function_evaluations;
  const std::size_t n = global_size_;
  std::vector<std::uint32_t> keys(n * words_);
  std::vector<double> points(n * d_);
  std::uint32_t id;
  for (const std::byte* in = all_simplices.data(); in < all_simplices.data() + all_simplices.size();) {
    take(in, &id, 1);
    take(in, keys.data() + static_cast<std::size_t>(id) * words_, words_);
    take(in, points.data() + static_cast<std::size_t>(id) * d_, d_);
  }
  // Grown one simplex at a time as the sequential walk grows them (the report counts the bytes held).
  for (std::size_t i = 0; i < n; ++i) {
    result.simplices.insert(keys.data() + i * words_);
    result.points.insert(result.points.end(), points.data() + i * d_, points.data() + (i + 1) * d_);
  }
  // S_∂ in the order the sequential walk met it: by τ's id, then cofacet.
  const std::size_t record = sizeof(std::uint64_t) + sizeof(std::uint32_t) * words_ + sizeof(double) * d_;
  const std::size_t m = all_boundary.size() / record;
  std::vector<std::pair<std::uint64_t, std::size_t>> order(m);
  for (std::size_t i = 0; i < m; ++i) {
    std::memcpy(&order[i].first, all_boundary.data() + i * record, sizeof(std::uint64_t));
    order[i].second = i;
  }
  std::sort(order.begin(), order.end());
  std::uint32_t key[packed_words(kMaxDimension)];
  double point[kMaxDimension];
  for (const auto& [discovery, i] : order) {
    const std::byte* in = all_boundary.data() + i * record + sizeof(std::uint64_t);
    take(in, key, words_);
    take(in, point, d_);
    if (result.boundary_simplices.insert(key).second)
      for (int j = 0; j < d_; ++j) result.boundary_points.push_back(point[j]);
  }
  return result;
}

}  // namespace walk

namespace {

// The walk over every seed, with rank 0's seeds and limits; `finish` ends it (gathered or not).
template <class Finish>
auto walk_distributed(const Triangulation& triangulation, IntersectionOracle& oracle, SharedVertexValues& values,
                      const VertexEvaluator& evaluate, const std::vector<std::vector<double>>& seeds,
                      const TraceOptions& options, Communicator& comm, Finish&& finish) {
  if (oracle.ambient_dimension() != triangulation.dimension())
    throw InputError("the oracle works in R^" + std::to_string(oracle.ambient_dimension()) +
                     " but the triangulation is of R^" + std::to_string(triangulation.dimension()));
  if (seeds.empty()) throw SeedError("no seed given");
  // Rank 0's seeds and limits for all: a default derived from a node's memory must not make the
  // ranks of different nodes stop at different levels.
  TraceOptions agreed = options;
  std::vector<std::vector<double>> agreed_seeds;
  {
    std::vector<std::byte> bytes;
    const std::uint64_t header[] = {options.max_simplices, static_cast<std::uint64_t>(options.seed_search_rings),
                                    options.skip_unusable_seeds ? 1u : 0u, seeds.size()};
    put(bytes, header, 4);
    for (const auto& seed : seeds) {
      const std::uint64_t n = seed.size();
      put(bytes, &n, 1);
      put(bytes, seed.data(), seed.size());
    }
    comm.broadcast(bytes);
    const std::byte* in = bytes.data();
    std::uint64_t h[4];
    take(in, h, 4);
    agreed.max_simplices = h[0], agreed.seed_search_rings = static_cast<int>(h[1]), agreed.skip_unusable_seeds = h[2];
    agreed_seeds.resize(h[3]);
    for (auto& seed : agreed_seeds) {
      std::uint64_t n;
      take(in, &n, 1);
      seed.resize(n);
      take(in, seed.data(), n);
    }
  }
  walk::DistributedWalk walk(triangulation, oracle, values, evaluate, agreed, comm);
  for (const auto& seed : agreed_seeds) {
    if (walk.stopped()) break;
    walk.add_seed(seed, !agreed.skip_unusable_seeds);
    walk.walk();
  }
  auto result = finish(walk);
  if (result.status == TraceStatus::max_simplices_reached) result.message = simplex_limit_message(agreed.max_simplices);
  return result;
}

}  // namespace

TraceResult trace_manifold_distributed(const Triangulation& triangulation, IntersectionOracle& oracle,
                                       SharedVertexValues& values, const VertexEvaluator& evaluate,
                                       const std::vector<std::vector<double>>& seeds, const TraceOptions& options,
                                       Communicator& comm, DistributedTraceStats* stats) {
  return walk_distributed(triangulation, oracle, values, evaluate, seeds, options, comm,
                          [&](walk::DistributedWalk& w) { return w.finish(stats); });
}

TracePart trace_part_distributed(const Triangulation& triangulation, IntersectionOracle& oracle,
                                 SharedVertexValues& values, const VertexEvaluator& evaluate,
                                 const std::vector<std::vector<double>>& seeds, const TraceOptions& options,
                                 Communicator& comm, DistributedTraceStats* stats) {
  return walk_distributed(triangulation, oracle, values, evaluate, seeds, options, comm,
                          [&](walk::DistributedWalk& w) { return w.finish_part(stats); });
}

}  // namespace coxmesh
