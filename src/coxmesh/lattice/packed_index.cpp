#include "coxmesh/lattice/packed_index.h"

namespace coxmesh {

namespace {

// Least significant digit radix sort of 64-bit entries by their bits from `from` to the top, 11 bits
// (a histogram that fits the L1 cache) a pass, the histograms of every pass counted in one pass
// first; stable.
void radix_sort_from_bit(UninitializedHugeVector<std::uint64_t>& entries, int from) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  constexpr std::uint64_t kMask = kBuckets - 1;
  const int passes = (64 - from + kDigit - 1) / kDigit;
  if (passes == 0) return;
  std::vector<std::size_t> start(static_cast<std::size_t>(passes) * (kBuckets + 1), 0);
  for (const std::uint64_t e : entries)
    for (int p = 0; p < passes; ++p) ++start[p * (kBuckets + 1) + ((e >> (from + p * kDigit)) & kMask) + 1];
  UninitializedHugeVector<std::uint64_t> sorted(entries.size());
  for (int p = 0; p < passes; ++p) {
    std::size_t* bucket = start.data() + p * (kBuckets + 1);
    for (std::size_t b = 1; b <= kBuckets; ++b) bucket[b] += bucket[b - 1];
    const int shift = from + p * kDigit;
    for (const std::uint64_t e : entries) sorted[bucket[(e >> shift) & kMask]++] = e;
    entries.swap(sorted);
  }
}

}  // namespace

std::uint32_t PackedKeyIndex::index_appended() {
  if (unindexed_.empty()) return kAbsent;
  std::size_t capacity = slots_.size();
  while (2 * static_cast<std::size_t>(size_) > capacity) capacity *= 2;  // load ≤ 1/2, as insert_at
  if (capacity != slots_.size()) rehash(capacity);
  // Least significant digit radix sort of the entries by home slot (the leading bits of the tag):
  // then every insertion below probes next to the previous one, in one sweep over the table.
  radix_sort_from_bit(unindexed_, 64 - probe_.bits());
  std::uint32_t duplicate = kAbsent;
  for (const std::uint64_t entry : unindexed_) {
    const std::uint32_t id = LinearProbe::payload(entry) - 1;
    const std::size_t s = probe_.find(LinearProbe::tag_of(entry), slot_loader(),
                                      [&](std::uint32_t payload) { return equal(payload - 1, key(id)); });
    if (slots_[s] == 0)
      slots_[s] = entry;
    else if (duplicate == kAbsent || id < duplicate)
      duplicate = id;
  }
  unindexed_.clear();
  return duplicate;
}

std::uint32_t PackedKeyIndex::repeated_key() const {
  UninitializedHugeVector<std::uint64_t> entries(size_);
  for (std::uint32_t id = 0; id < size_; ++id) entries[id] = repeat_entry(key(id), words_, id);
  return repeated_key(std::move(entries));
}

std::uint32_t PackedKeyIndex::repeated_key(UninitializedHugeVector<std::uint64_t>&& entries) const {
  if (entries.size() != size_) throw std::logic_error("PackedKeyIndex::repeated_key: an entry per key needed");
  // Equal keys have equal hashes, so after the sort they sit in one run of equal tags (ids
  // increasing: the entries come in id order and the sort is stable).
  radix_sort_from_bit(entries, 32);
  std::uint32_t repeated = kAbsent;
  std::vector<std::uint32_t> run;
  for (std::size_t a = 0, b; a < entries.size(); a = b) {
    for (b = a + 1; b < entries.size() && entries[b] >> 32 == entries[a] >> 32;) ++b;
    if (b - a == 1) continue;
    // Tags collide by chance too (about n^2 / 2^33 pairs): sort the run by key, stably, so that
    // equal keys are neighbours with increasing ids. (A run of many equal tags, as a hostile file
    // could make, costs a sort, not a comparison of every pair.)
    run.clear();
    for (std::size_t e = a; e < b; ++e) run.push_back(static_cast<std::uint32_t>(entries[e]));
    std::stable_sort(run.begin(), run.end(), [&](std::uint32_t x, std::uint32_t y) {
      return std::lexicographical_compare(key(x), key(x) + words_, key(y), key(y) + words_);
    });
    for (std::size_t i = 1; i < run.size(); ++i)
      if (equal(run[i - 1], key(run[i]))) repeated = std::min(repeated, run[i]);
  }
  return repeated;
}

void PackedKeyIndex::truncate(std::uint32_t n) {
  if (n >= size_) return;
  std::vector<std::uint32_t> kept(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(n) * words_);
  clear();
  for (std::uint32_t id = 0; id < n; ++id) insert(kept.data() + static_cast<std::size_t>(id) * words_);
}

}  // namespace coxmesh
