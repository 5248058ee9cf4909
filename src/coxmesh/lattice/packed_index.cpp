#include "coxmesh/lattice/packed_index.h"

namespace coxmesh {

std::uint32_t PackedKeyIndex::index_appended() {
  if (unindexed_.empty()) return kAbsent;
  std::size_t capacity = slots_.size();
  while (2 * static_cast<std::size_t>(size_) > capacity) capacity *= 2;  // load ≤ 1/2, as insert_at
  if (capacity != slots_.size()) rehash(capacity);
  // Least significant digit radix sort of the entries by home slot (the leading bits of the tag):
  // then every insertion below probes next to the previous one, in one sweep over the table.
  const int bits = probe_.bits();
  constexpr int kDigit = 11;
  UninitializedHugeVector<std::uint64_t> sorted(unindexed_.size());
  for (int low = 0; low < bits; low += kDigit) {
    const int width = std::min(kDigit, bits - low), from = 64 - bits + low;
    std::vector<std::uint32_t> start((std::size_t{1} << width) + 1, 0);
    for (const std::uint64_t e : unindexed_) ++start[((e >> from) & ((1u << width) - 1)) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    for (const std::uint64_t e : unindexed_) sorted[start[(e >> from) & ((1u << width) - 1)]++] = e;
    unindexed_.swap(sorted);
  }
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

void PackedKeyIndex::truncate(std::uint32_t n) {
  if (n >= size_) return;
  std::vector<std::uint32_t> kept(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(n) * words_);
  clear();
  for (std::uint32_t id = 0; id < n; ++id) insert(kept.data() + static_cast<std::size_t>(id) * words_);
}

}  // namespace coxmesh
