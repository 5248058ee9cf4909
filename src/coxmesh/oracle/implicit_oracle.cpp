// Thesis §4.3: M(τ)·λ = (1, 0, …, 0)ᵀ with the exact lexicographic rule; D̂ interpolated at the point.
#include "coxmesh/oracle/implicit_oracle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/oracle/transversality.h"
#include "coxmesh/util/fixed_dimension.h"

namespace coxmesh {

ImplicitOracle::ImplicitOracle(const Triangulation& triangulation, FunctionPtr f, FunctionPtr domain,
                               std::shared_ptr<SharedVertexValues> shared)
    : triangulation_(triangulation),
      f_(std::move(f)),
      domain_(std::move(domain)),
      shared_(std::move(shared)),
      cache_(1) {
  d_ = triangulation_.dimension();
  check_manifold_function(f_, d_);
  k_ = f_->codimension();
  if (domain_ && (domain_->ambient_dimension() != d_ || domain_->codimension() != 1))
    throw InputError("the domain function must map R^" + std::to_string(d_) + " to R");
  stride_ = k_ + (domain_ ? 1 : 0);
  scratch_.resize(stride_ + d_);
  if (shared_) {
    if (shared_->dimension() != d_ || shared_->stride() != stride_)
      throw InputError("the shared vertex values hold " + std::to_string(shared_->stride()) +
                       " values per vertex of R^" + std::to_string(shared_->dimension()) + ", this oracle needs " +
                       std::to_string(stride_) + " per vertex of R^" + std::to_string(d_));
  } else {
    cache_ = PackedKeyIndex(d_);
  }
  batches_ = !shared_ && (f_->prefers_batches() || (domain_ && domain_->prefers_batches()));
  front_keys_.resize(kFrontSlots * d_);
  front_values_.resize(kFrontSlots * stride_);
  front_used_.assign(kFrontSlots, 0);
}

namespace {

// Odd constants from splitmix64, one per coordinate, for ImplicitOracle::front_slot.
constexpr auto kSlotMultipliers = [] {
  std::array<std::uint64_t, kMaxDimension> m{};
  std::uint64_t x = 0;
  for (auto& c : m) {
    std::uint64_t z = x += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    c = (z ^ (z >> 31)) | 1;
  }
  return m;
}();

// The dimensions the oracle's hot paths are compiled for (D = 0: any other d, read at run time).
template <class F>
void with_oracle_dimension(int d, F&& f) {
  with_fixed_dimension<3, 4, 6, 9>(d, std::forward<F>(f));
}

}  // namespace

// The slot of v among the recent vertices: a sum of independent products, cheaper than the chain of
// hash_words (the big table's hash, needed only when the slot holds another vertex). Two coordinates
// per 64-bit word: half the products (each coordinate still moves the top bits, the slot).
template <int D>
[[gnu::always_inline]] inline std::size_t ImplicitOracle::front_slot(const std::int32_t* v) const {
  const int d = D ? D : d_;
  std::uint64_t h = 0;
  int i = 0;
  for (; i + 1 < d; i += 2) {
    std::uint64_t pair;
    std::memcpy(&pair, v + i, sizeof pair);
    h += pair * kSlotMultipliers[i / 2];
  }
  if (i < d) h += static_cast<std::uint64_t>(static_cast<std::uint32_t>(v[i])) * kSlotMultipliers[i / 2];
  return h >> (64 - kFrontBits);
}

template <int D>
[[gnu::always_inline]] inline bool ImplicitOracle::front_holds(std::size_t slot, const std::int32_t* v) const {
  if (!front_used_[slot]) return false;
  const int d = D ? D : d_;
  const std::int32_t* front_key = front_keys_.data() + slot * d;
  std::uint64_t diff = 0;  // (std::equal would call memcmp for a few ints), two coordinates at a time
  int i = 0;
  for (; i + 1 < d; i += 2) {
    std::uint64_t a, b;
    std::memcpy(&a, v + i, sizeof a);
    std::memcpy(&b, front_key + i, sizeof b);
    diff |= a ^ b;
  }
  if (i < d) diff |= static_cast<std::uint32_t>(v[i] ^ front_key[i]);
  return diff == 0;
}

template <int D>
const double* ImplicitOracle::values_at(const std::int32_t* v) {
  const int d = D ? D : d_;
  if (!cache_enabled_) {
    evaluate(v, scratch_.data());
    return scratch_.data();
  }
  // The walk meets each vertex many times within a short while: a small direct-mapped cache of
  // recent vertices (a few cache lines per probe) answers most lookups before the big table.
  const std::size_t slot = front_slot<D>(v);
  std::int32_t* front_key = front_keys_.data() + slot * d;
  double* front = front_values_.data() + slot * stride_;
  if (front_holds<D>(slot, v)) return front;
  const auto* key = reinterpret_cast<const std::uint32_t*>(v);
  const std::uint64_t h = hash_words(key, d);
  front_used_[slot] = 0;
  if (shared_) {
    shared_->get(v, h, front, [&](double* out) { evaluate(v, out); });
    for (int i = 0; i < stride_; ++i)  // NaN stored by a worker whose evaluation failed
      if (!std::isfinite(front[i])) throw EvaluationError(not_finite_message(v, i, front[i]));
  } else {
    auto [found, inserted] = cache_.insert(key, h);
    double* stored;
    if (inserted) {
      values_.resize(values_.size() + stride_);
      stored = values_.data() + static_cast<std::size_t>(found) * stride_;
      evaluate(v, stored);
    } else {
      stored = values_.data() + static_cast<std::size_t>(found) * stride_;
    }
    std::copy(stored, stored + stride_, front);
  }
  std::copy(v, v + d, front_key);
  front_used_[slot] = 1;
  return front;
}

void ImplicitOracle::evaluate(const std::int32_t* v, double* out) {
  double* x = scratch_.data() + stride_;
  triangulation_.cartesian(v, x);
  f_->evaluate(x, out);
  if (domain_) domain_->evaluate(x, out + k_);
  ++evaluations_;
  for (int i = 0; i < stride_; ++i)
    if (!std::isfinite(out[i])) throw EvaluationError(not_finite_message(v, i, out[i]));
}

// Every cofacet μ of τ ∈ S adds one vertex to τ's; the walk reads F there (pivot_exit, or intersect
// on μ's other facets, which all contain it), so evaluating it now adds no evaluation.
void ImplicitOracle::prefetch(std::span<const std::uint32_t> packed_simplices) {
  if (!batches_ || !cache_enabled_) return;
  const int words = packed_words(d_);
  const std::uint32_t cached = cache_.size();  // the new vertices get the ids cached, cached + 1, ...
  CofaceEnumerator cofacets;
  std::int32_t v[kMaxDimension];
  for (std::size_t i = 0; i + words <= packed_simplices.size(); i += words) {
    const Simplex tau = unpack(packed_simplices.data() + i, d_);
    cofacets.reset(tau, tau.k + 1);
    while (const Simplex* mu = cofacets.next()) {
      mu->vertex(extra_vertex_index(tau, *mu), v);
      cache_.insert(reinterpret_cast<const std::uint32_t*>(v));
    }
  }
  const int n = static_cast<int>(cache_.size() - cached);
  if (n == 0) return;
  const auto vertex = [&](int i) { return reinterpret_cast<const std::int32_t*>(cache_.key(cached + i)); };
  batch_points_.resize(static_cast<std::size_t>(n) * d_);
  for (int i = 0; i < n; ++i)
    triangulation_.cartesian(vertex(i), batch_points_.data() + static_cast<std::size_t>(i) * d_);
  values_.resize(static_cast<std::size_t>(cached + n) * stride_);
  double* out = values_.data() + static_cast<std::size_t>(cached) * stride_;
  try {
    if (!domain_) {
      f_->evaluate_batch(batch_points_.data(), n, out);
    } else {  // F's k values and D's one, interleaved per vertex
      batch_values_.resize(static_cast<std::size_t>(n) * (k_ + 1));
      f_->evaluate_batch(batch_points_.data(), n, batch_values_.data());
      domain_->evaluate_batch(batch_points_.data(), n, batch_values_.data() + static_cast<std::size_t>(n) * k_);
      for (int i = 0; i < n; ++i) {
        std::copy_n(batch_values_.data() + static_cast<std::size_t>(i) * k_, k_,
                    out + static_cast<std::size_t>(i) * stride_);
        out[static_cast<std::size_t>(i) * stride_ + k_] = batch_values_[static_cast<std::size_t>(n) * k_ + i];
      }
    }
    evaluations_ += n;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < stride_; ++j)
        if (const double x = out[static_cast<std::size_t>(i) * stride_ + j]; !std::isfinite(x))
          throw EvaluationError(not_finite_message(vertex(i), j, x));
  } catch (...) {  // the cache keeps only evaluated vertices
    cache_.truncate(cached);
    values_.resize(static_cast<std::size_t>(cached) * stride_);
    throw;
  }
}

std::string ImplicitOracle::not_finite_message(const std::int32_t* v, int i, double value) const {
  double x[kMaxDimension];
  triangulation_.cartesian(v, x);
  std::ostringstream os;
  os.precision(17);
  os << (i < k_ ? "the function" : "the domain function") << " is not finite (" << value << ") at (";
  for (int j = 0; j < d_; ++j) os << (j ? "," : "") << x[j];
  os << ")";
  return os.str();
}

// M(τ) of thesis §4.3, column-major: column j = (1, F(v_j)); and D at the vertices when asked.
void ImplicitOracle::system_matrix(const Simplex& tau, double* m, double* domain_values) {
  with_oracle_dimension(d_, [&](auto fixed_d) {
    constexpr int D = decltype(fixed_d)::value;
    const int n = k_ + 1, d = D ? D : d_;
    std::int32_t v[kMaxDimension];
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < d; ++i) v[i] = tau.vertex_coordinate(j, i);
      const double* val = values_at<D>(v);
      m[j * n] = 1.0;
      for (int i = 0; i < k_; ++i) m[j * n + 1 + i] = val[i];
      if (domain_ && domain_values) domain_values[j] = val[k_];
    }
  });
}

Intersection ImplicitOracle::intersect(const Simplex& tau, double* point) {
  const int n = k_ + 1;
  double m[SmallLu::kMaxN * SmallLu::kMaxN];
  double dval[SmallLu::kMaxN];
  system_matrix(tau, m, dval);
  double lambda[SmallLu::kMaxN];
  bool factored = false;
  if (!lexicographic_solve(n, m, lambda, &intersect_lu_, &factored)) return {};
  Intersection r{true, -1.0};
  double xs[32 * kMaxDimension];
  triangulation_.vertex_coordinates(tau, xs);
  with_oracle_dimension(d_, [&](auto fixed_d) {
    const int d = decltype(fixed_d)::value ? decltype(fixed_d)::value : d_;
    for (int i = 0; i < d; ++i) point[i] = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < d; ++i) point[i] += lambda[j] * xs[j * d + i];
  });
  if (domain_) {
    r.domain = 0;
    for (int j = 0; j < n; ++j) r.domain += lambda[j] * dval[j];
  }
  if (keep_factors_ && r.domain < 0) {    // (the walk's test for S)
    const double ends[2] = {m[1], m[3]};  // k = 1: pivot_enter needs F at τ's ends alone
    keep_factors(tau, n == 2 || factored, n == 2 ? ends : lambda);
  }
  return r;
}

void ImplicitOracle::keep_factors(const Simplex& tau, bool factored, const double* lambda) {
  const int n = k_ + 1, words = packed_words(d_), entry = n * n + n;
  if (kept_tail_ - kept_head_ == kept_capacity_) {  // full: twice the room, the entries first
    if (kept_capacity_ >= kMaxKeptFactors) {        // not a walk's front (intersect alone): off
      keep_factors_ = false;
      kept_keys_ = {}, kept_factors_ = {}, kept_rows_ = {};
      return;
    }
    const std::size_t capacity = std::max<std::size_t>(64, 2 * kept_capacity_);
    std::vector<std::uint32_t> keys(capacity * words);
    std::vector<double> factors(capacity * entry);
    std::vector<int> rows(capacity * n);
    for (std::size_t i = kept_head_; i < kept_tail_; ++i) {
      const std::size_t from = i & (kept_capacity_ - 1), to = i - kept_head_;
      std::copy_n(kept_keys_.data() + from * words, words, keys.data() + to * words);
      std::copy_n(kept_factors_.data() + from * entry, entry, factors.data() + to * entry);
      std::copy_n(kept_rows_.data() + from * n, n, rows.data() + to * n);
    }
    kept_keys_ = std::move(keys), kept_factors_ = std::move(factors), kept_rows_ = std::move(rows);
    kept_tail_ -= kept_head_, kept_head_ = 0, kept_capacity_ = capacity;
  }
  const std::size_t at = kept_tail_++ & (kept_capacity_ - 1);
  pack(tau, kept_keys_.data() + at * words);
  int* rows = kept_rows_.data() + at * n;
  rows[0] = -1;
  if (!factored) return;
  double* factors = kept_factors_.data() + at * entry;
  rows[0] = 0;
  if (n > 2) intersect_lu_.save(factors, rows);
  for (int i = 0; i < n; ++i) factors[n * n + i] = lambda[i];
}

// The factors intersect(τ) kept, when they are next in the queue (see keep_factors_).
bool ImplicitOracle::take_kept_factors(const Simplex& tau) {
  if (!keep_factors_) return false;
  const int n = k_ + 1, words = packed_words(d_), entry = n * n + n;
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(tau, key);
  const std::size_t at = kept_head_ & (kept_capacity_ - 1);
  if (kept_head_ == kept_tail_ || !std::equal(key, key + words, kept_keys_.data() + at * words)) {
    keep_factors_ = false;  // not the sequential walk's order
    kept_keys_ = {}, kept_factors_ = {}, kept_rows_ = {};
    return false;
  }
  ++kept_head_;
  if (kept_head_ != kept_tail_) {  // the next τ's entry, written a level ago and out of the caches by now
    const std::size_t next = kept_head_ & (kept_capacity_ - 1);
    const char* f = reinterpret_cast<const char*>(kept_factors_.data() + next * entry);
    for (std::size_t b = 0; b < entry * sizeof(double); b += 64) __builtin_prefetch(f + b);
    __builtin_prefetch(kept_keys_.data() + next * words);
    __builtin_prefetch(kept_rows_.data() + next * n);
  }
  const int* rows = kept_rows_.data() + at * n;
  if (rows[0] < 0) return false;
  const double* factors = kept_factors_.data() + at * entry;
  if (n > 2) pivot_lu_.restore(n, factors, rows);
  for (int i = 0; i < n; ++i) pivot_lambda_[i] = factors[n * n + i];
  pivot_rows_ready_ = 0;
  ++factorizations_reused_;
  return true;
}

// values_at(v)'s reads: its slot of the recent vertices, and its slot in the big table.
void ImplicitOracle::prefetch_pivot(const std::int32_t* v) {
  if (!cache_enabled_) return;
  with_oracle_dimension(d_, [&](auto fixed_d) { prefetch_pivot_d<decltype(fixed_d)::value>(v); });
}

template <int D>
void ImplicitOracle::prefetch_pivot_d(const std::int32_t* v) {
  const std::size_t slot = front_slot<D>(v);
  __builtin_prefetch(front_keys_.data() + slot * (D ? D : d_));
  __builtin_prefetch(front_values_.data() + slot * stride_);
  if (front_holds<D>(slot, v)) return;  // met lately, as a rule: no hash, no slot of the big table to fetch
  const std::uint64_t h = hash_words(reinterpret_cast<const std::uint32_t*>(v), D ? D : d_);
  if (shared_)
    shared_->prefetch(h);
  else if (cache_.indexed())
    cache_.prefetch(h);
}

// Door-in/door-out: on μ = τ ∪ {v}, the points of M̂ are λ(t) = (λ_τ − t·w, t) with M(τ)·w = (1, F(v)),
// a segment leaving τ at t = 0; it leaves μ where the first coordinate λ_j − t·w_j reaches 0.
bool ImplicitOracle::pivot_enter(const Simplex& tau) {
  const int n = k_ + 1;
  if (take_kept_factors(tau)) {  // (n > 2: no vertex of τ on M then, intersect decided otherwise)
    if (n > 2) pivot_lu_.keep_reciprocals();
    return true;
  }
  double m[SmallLu::kMaxN * SmallLu::kMaxN];
  system_matrix(tau, m, nullptr);
  if (n == 2) {  // k = 1: signs decide (see pivot_exit)
    pivot_lambda_[0] = m[1], pivot_lambda_[1] = m[3];
    return true;
  }
  if (!pivot_lu_.factor(n, m)) return false;
  pivot_lu_.keep_reciprocals();
  pivot_lu_.solve_unit(0, pivot_lambda_.data());
  pivot_rows_ready_ = 0;
  for (int j = 0; j < n; ++j) {  // a vertex on M: λ_τ is exactly e_j (rounding would blur the ties)
    bool zero = true;
    for (int i = 1; i < n && zero; ++i) zero = m[j * n + i] == 0;
    if (!zero) continue;
    for (int r = 0; r < n; ++r) pivot_lambda_[r] = r == j ? 1.0 : 0.0;
    break;
  }
  return true;
}

int ImplicitOracle::pivot_exit(const std::int32_t* v) {
  const double* val;
  with_oracle_dimension(d_, [&](auto fixed_d) { val = values_at<decltype(fixed_d)::value>(v); });
  // k = 1, exact: an edge is transverse iff exactly one end has F > 0 (lexicographic_solve), so
  // the other transverse edge of the triangle joins v to the end of τ whose sign differs from v's.
  if (k_ == 1) return (val[0] > 0) == (pivot_lambda_[0] > 0) ? 0 : 1;
  return with_small_size(k_ + 1, [&]<int N>() { return pivot_exit_n<N>(val); });
}

// pivot_exit for n = N (N = 0: n read at run time), F(v) = val: loops of constant length, unrolled.
template <int N>
int ImplicitOracle::pivot_exit_n(const double* val) {
  const int n = N ? N : k_ + 1;
  double a[SmallLu::kMaxN], w[SmallLu::kMaxN];
  a[0] = 1.0;
  for (int i = 1; i < n; ++i) a[i] = val[i - 1];
  pivot_lu_.solve_guess(a, w);  // (a guess: intersect checks it)
  // The least ratio λ_j / w_j over w_j > 0, then the j that reach it. The signs of w and the order
  // of the ratios are as good as random: minima and masks, not branches. A w_j ≤ 0 (−0 and NaN
  // included) divides by +0: its ratio is +∞, or NaN, which std::min passes over.
  double ratio[SmallLu::kMaxN];
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    ratio[j] = std::max(pivot_lambda_[j], 0.0) / std::max(0.0, w[j]);
    best = std::min(best, ratio[j]);
  }
  std::uint32_t tied = 0;
  for (int j = 0; j < n; ++j) tied |= static_cast<std::uint32_t>((w[j] > 0) & (ratio[j] == best)) << j;
  if (tied == 0) return -1;
  return (tied & (tied - 1)) == 0 ? std::countr_zero(tied) : pivot_exit_tie(tied, w);
}

// Ties (a vertex of τ on M makes λ_τ = e_j, and every ratio but one 0): the transversality rule
// follows M̂ perturbed to F̂ = (ε, ε², …), where λ_τ(ε) = Σ_c ε^c·(column c of M(τ)⁻¹), so the
// ratio test compares the rows of M(τ)⁻¹ divided by w_j lexicographically (the lexicographic
// pivoting rule of PL continuation). Ties are exact equalities (a tiny λ_j that is not 0 decides
// by itself, and blurring ties with a tolerance made more guesses wrong). Only a guess:
// intersect() checks it.
int ImplicitOracle::pivot_exit_tie(std::uint32_t tied, const double* w) {
  const int n = k_ + 1;
  for (int c = 1; c < n && (tied & (tied - 1)) != 0; ++c) {
    double low = std::numeric_limits<double>::infinity();
    for (int j = 0; j < n; ++j)
      if (tied >> j & 1) {
        if (!(pivot_rows_ready_ >> j & 1)) {
          pivot_lu_.solve_transposed_unit(j, pivot_rows_.data() + j * n);
          pivot_rows_ready_ |= 1u << j;
        }
        low = std::min(low, pivot_rows_[j * n + c] / w[j]);
      }
    for (int j = 0; j < n; ++j)
      if ((tied >> j & 1) && pivot_rows_[j * n + c] / w[j] > low) tied &= ~(1u << j);
  }
  return std::countr_zero(tied);  // the first of those left
}

}  // namespace coxmesh
