// Compact storage of lattice objects (vertices, packed simplices): a hash index from fixed-width
// keys of 32-bit words to dense ids 0, 1, 2, … in insertion order (deterministic output order).
// Open addressing with linear probing (util/linear_probe.h); each slot holds the top 32 bits of the
// hash and the id + 1, so probes compare keys only on a hash match. A key's home slot is given by
// the top bits of its hash, so growing the table moves slots without reading or rehashing a single
// key (the price: neighbouring slots share the leading bits of their tags, so with 2^b slots a tag
// tells apart 32 − b bits, and one probe in 2^(32−b) compares a key needlessly). Keys live
// contiguously in one array: no node per entry.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/huge_page_allocator.h"
#include "coxmesh/util/linear_probe.h"

namespace coxmesh {

/// A run of keys to insert in order, e.g. what one task of a parallel loop produced: `size` keys of
/// words() words each, their hash_words, and where insert_runs writes each key's id.
struct KeyRun {
  const std::uint32_t* keys;
  const std::uint64_t* hashes;
  std::size_t size;
  std::uint32_t* ids;
};

class PackedKeyIndex {
 public:
  static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;
  static constexpr std::uint32_t kMaxEntries =
      (1u << 31) - 1;                                 ///< at load ≤ 1/2, ≤ 2^32 slots: tags give every home bit
  static constexpr std::uint32_t kNewBit = 1u << 31;  ///< insert_runs: marks the occurrence that inserted a key

  /// `words` = key width in 32-bit words (e.g. d for lattice vertices, packed_words(d) for simplices).
  explicit PackedKeyIndex(int words = 1) : words_(words) { rehash(16); }

  int words() const { return words_; }
  std::uint32_t size() const { return size_; }
  const std::uint32_t* key(std::uint32_t id) const { return keys_.data() + static_cast<std::size_t>(id) * words_; }

  /// Id of the key, or kAbsent.
  std::uint32_t find(const std::uint32_t* key, std::uint64_t hash) const {
    std::size_t slot;
    return find(key, hash, slot);
  }
  std::uint32_t find(const std::uint32_t* key) const { return find(key, hash_words(key, words_)); }

  /// find() that also reports where an absent key would go, for insert_at().
  std::uint32_t find(const std::uint32_t* key, std::uint64_t hash, std::size_t& slot) const {
    if (!indexed()) [[unlikely]]
      throw std::logic_error("PackedKeyIndex: look-up after release_index() (call reindex() first)");
    slot = probe_.find(LinearProbe::tag_of(hash), slot_loader(),
                       [&](std::uint32_t payload) { return equal(payload - 1, key); });
    const std::uint64_t entry = slots_[slot];
    return entry == 0 ? kAbsent : LinearProbe::payload(entry) - 1;
  }
  /// Inserts an absent key at the slot find() reported, with no insert in between; returns its id.
  std::uint32_t insert_at(std::size_t slot, const std::uint32_t* key, std::uint64_t hash) {
    COXMESH_DEBUG_ASSERT(slot < slots_.size() && slots_[slot] == 0);
    COXMESH_PARANOID_ASSERT(find(key, hash) == kAbsent);
    if (size_ >= kMaxEntries) throw InputError("more than 2^31 - 1 entries in one index");
    const std::uint32_t id = size_++;
    append_few(keys_, key, static_cast<std::size_t>(words_));
    slots_[slot] = LinearProbe::entry(hash, id + 1);
    if (2 * static_cast<std::size_t>(size_) > slots_.size()) rehash(2 * slots_.size());  // load ≤ 1/2
    return id;
  }

  /// {id, true} if the key was inserted, {existing id, false} if it was there.
  std::pair<std::uint32_t, bool> insert(const std::uint32_t* key, std::uint64_t hash) {
    std::size_t slot;
    if (const std::uint32_t id = find(key, hash, slot); id != kAbsent) return {id, false};
    return {insert_at(slot, key, hash), true};
  }
  std::pair<std::uint32_t, bool> insert(const std::uint32_t* key) { return insert(key, hash_words(key, words_)); }

  /// Inserts the keys of the runs, run after run and in order within each run (the ids of insert()
  /// on each in turn), with the table slots prefetched a few keys ahead: ids[r] = the key's id,
  /// | kNewBit where this occurrence inserted it.
  void insert_runs(std::span<const KeyRun> runs) {
    if (!indexed()) throw std::logic_error("PackedKeyIndex: insert after release_index() (call reindex() first)");
    // Two distances, across the ends of runs (runs may be short): the home slot of the key kAhead
    // keys ahead; then, kAhead / 2 keys ahead, the stored key that home slot names if the tags match
    // (a key met before, which the insertion compares: otherwise a second, unprefetched miss).
    // Far ahead: a new key's slot is a TLB miss as a rule, and a page walk on a virtual machine
    // takes long (16 → 64: the cell complex of S² 6–7 % faster, docs/benchmarks.md).
    constexpr std::size_t kAhead = 64;
    struct Cursor {
      std::size_t run = 0, i = 0;
    };
    const auto next_hash = [&](Cursor& c, std::uint64_t& hash) {
      while (c.run < runs.size() && c.i >= runs[c.run].size) ++c.run, c.i = 0;
      if (c.run == runs.size()) return false;
      hash = runs[c.run].hashes[c.i++];
      return true;
    };
    Cursor far, near;
    std::uint64_t hash;
    for (std::size_t k = 0; k < kAhead; ++k)
      if (next_hash(far, hash)) prefetch(hash);
    for (std::size_t k = 0; k < kAhead / 2; ++k)
      if (next_hash(near, hash)) prefetch_key(hash);
    for (const KeyRun& run : runs)
      for (std::size_t i = 0; i < run.size; ++i) {
        if (next_hash(far, hash)) prefetch(hash);
        if (next_hash(near, hash)) prefetch_key(hash);
        const auto [id, fresh] = insert(run.keys + i * words_, run.hashes[i]);
        run.ids[i] = fresh ? id | kNewBit : id;
      }
  }

  /// Appends n keys that the caller knows to be absent, without indexing them yet: they get the
  /// next ids, to be written with set_appended() before any other use of the index (by several
  /// threads at once if they write different ids: nothing else is touched); then key(id) works,
  /// but find() and insert() do not see them until index_appended(). For loads of keys
  /// deduplicated elsewhere (the parallel walk's levels): one pass over the table in slot order
  /// instead of a random access per key. Returns the first of their ids.
  std::uint32_t append_unindexed(std::size_t n) {
    if (size_ + n > kMaxEntries) throw InputError("more than 2^31 - 1 entries in one index");
    const std::uint32_t first = size_;
    size_ += static_cast<std::uint32_t>(n);
    grow_with_headroom(keys_, static_cast<std::size_t>(size_) * words_);
    grow_with_headroom(unindexed_, unindexed_.size() + n);
    return first;
  }
  /// Writes key `id` of the last append_unindexed(n).
  void set_appended(std::uint32_t id, const std::uint32_t* key, std::uint64_t hash) {
    COXMESH_DEBUG_ASSERT(id < size_ && size_ - id <= unindexed_.size());
    std::copy_n(key, words_, keys_.data() + static_cast<std::size_t>(id) * words_);
    unindexed_[unindexed_.size() - (size_ - id)] = LinearProbe::entry(hash, id + 1);
  }
  /// Keys appended and not indexed yet.
  std::size_t unindexed() const { return unindexed_.size(); }
  /// Indexes the appended keys, sorted by home slot so that the insertions sweep the table once
  /// (growing it first if needed). Returns the id of an appended key that was in the index already,
  /// which the caller claimed it was not (that key stays unindexed), else kAbsent.
  std::uint32_t index_appended();
  /// Keeps the keys of ids < n and forgets the others (rebuilds the table: not for hot paths).
  void truncate(std::uint32_t n);

  /// Simplex convenience: packs and hashes once.
  std::uint32_t find(const Simplex& s) const {
    std::uint32_t w[packed_words(kMaxDimension)];
    pack(s, w);
    return find(w);
  }
  std::pair<std::uint32_t, bool> insert(const Simplex& s) {
    std::uint32_t w[packed_words(kMaxDimension)];
    pack(s, w);
    return insert(w);
  }
  Simplex simplex(std::uint32_t id, int d) const { return unpack(key(id), d); }

  /// Hints the cache to load the first slot probed for this hash (batched inserts with hashes
  /// computed ahead).
  void prefetch(std::uint64_t hash) const {
    __builtin_prefetch(slots_.data() + probe_.home(LinearProbe::tag_of(hash)));
  }
  /// Hints the cache to load the stored key that the home slot of this hash names, if the tags match.
  void prefetch_key(std::uint64_t hash) const {
    const std::uint32_t tag = LinearProbe::tag_of(hash);
    const std::uint64_t slot = slots_[probe_.home(tag)];
    if (slot != 0 && LinearProbe::tag_of(slot) == tag)
      __builtin_prefetch(keys_.data() + static_cast<std::size_t>(LinearProbe::payload(slot) - 1) * words_);
  }

  /// Removes every key; keeps the memory for reuse.
  void clear() {
    unindexed_.clear();
    if (size_ == 0) return;
    keys_.clear();
    size_ = 0;
    std::fill(slots_.begin(), slots_.end(), 0);
  }

  /// Frees the hash table and keeps the keys: size(), key() and simplex() still work, find() and
  /// the inserts throw until reindex(). (A cell complex, once built, needs its keys only.)
  void release_index() {
    COXMESH_ASSERT(unindexed_.empty());
    UninitializedHugeVector<std::uint64_t>().swap(slots_);  // (= {} would keep the capacity)
    UninitializedHugeVector<std::uint64_t>().swap(unindexed_);
    probe_ = LinearProbe();
  }
  bool indexed() const { return !slots_.empty(); }
  /// The keys of `from` in the order given (ids 0, 1, … of the copy), without a hash table: as after
  /// release_index(), key() works and reindex() builds the table. (Reordering a level's keys
  /// costs a copy, not an insertion per key.)
  static PackedKeyIndex unindexed_copy(const PackedKeyIndex& from, std::span<const std::uint32_t> order) {
    if (order.size() > kMaxEntries) throw InputError("more than 2^31 - 1 entries in one index");
    PackedKeyIndex copy(from.words_);
    copy.release_index();
    const std::size_t w = static_cast<std::size_t>(from.words_);
    copy.keys_.resize(order.size() * w);
    for (std::size_t i = 0; i < order.size(); ++i) std::copy_n(from.key(order[i]), w, copy.keys_.data() + i * w);
    copy.size_ = static_cast<std::uint32_t>(order.size());
    return copy;
  }
  /// An index of `keys` (words() words each, back to back: ids 0, 1, … in that order) without a
  /// hash table, as after release_index(): the array becomes the index's own (no copy, no insert).
  /// For keys read in bulk, e.g. a level of a .cxm file; repeated_key() tells whether they are
  /// distinct, reindex() builds the table if look-ups are needed.
  static PackedKeyIndex from_keys(int words, UninitializedHugeVector<std::uint32_t>&& keys) {
    if (words < 1 || keys.size() % static_cast<std::size_t>(words) != 0)
      throw std::logic_error("PackedKeyIndex::from_keys: not a whole number of keys");
    if (keys.size() / static_cast<std::size_t>(words) > kMaxEntries)
      throw InputError("more than 2^31 - 1 entries in one index");
    PackedKeyIndex index(words);
    index.release_index();
    index.size_ = static_cast<std::uint32_t>(keys.size() / static_cast<std::size_t>(words));
    index.keys_ = std::move(keys);
    return index;
  }
  /// The smallest id whose key equals the key of a smaller id, or kAbsent when all keys are
  /// distinct. Indexed or not; no hash table: the (hash, id) pairs are radix sorted by hash, and
  /// keys are compared only where hashes are equal. A few sequential passes over n 8-byte pairs,
  /// where inserting into a table costs a cache (and TLB) miss per key.
  std::uint32_t repeated_key() const;
  /// The same from the entries of ids 0, 1, … in order (repeat_entry), made by a caller that reads
  /// the keys anyway: one pass over the keys less. The vector is used as scratch.
  std::uint32_t repeated_key(UninitializedHugeVector<std::uint64_t>&& entries) const;
  /// The entry of a key for repeated_key(): the top 32 bits of its hash, then its id.
  static std::uint64_t repeat_entry(const std::uint32_t* key, int words, std::uint32_t id) {
    return hash_words(key, words) >> 32 << 32 | id;
  }
  /// n ids whose keys are not kept (words() = 0): size() counts them; there is no key to read and
  /// no look-up. (A complex handed to a mesh writer: the writers read its levels' sizes, never keys.)
  static PackedKeyIndex without_keys(std::uint32_t n) {
    if (n > kMaxEntries) throw InputError("more than 2^31 - 1 entries in one index");
    PackedKeyIndex index(0);
    index.release_index();
    index.size_ = n;
    return index;
  }
  /// Builds the hash table again after release_index().
  void reindex() {
    if (indexed()) return;
    std::size_t cap = 16;
    while (cap < 2 * static_cast<std::size_t>(size_) + 2) cap *= 2;
    slots_ = zeroed_huge_vector<std::uint64_t>(cap);
    probe_ = LinearProbe(cap);
    for (std::uint32_t id = 0; id < size_; ++id) {
      const std::uint64_t h = hash_words(key(id), words_);
      slots_[probe_.find_empty(LinearProbe::tag_of(h), slot_loader())] = LinearProbe::entry(h, id + 1);
    }
  }

  /// Bytes held (keys and slots), for memory reports.
  std::size_t bytes() const { return held_bytes(keys_) + held_bytes(slots_); }
  void reserve(std::size_t n) {
    reserve_keys(n);
    reserve_table(n);
  }
  /// Room for n keys, without a table for them.
  void reserve_keys(std::size_t n) {
    if (n > kMaxEntries) throw InputError("more than 2^31 - 1 entries in one index");
    keys_.reserve(n * words_);
  }
  /// Room for keys in one big block at least (reserve_big_block, util/huge_page_allocator.h).
  void reserve_key_block() { reserve_big_block(keys_); }
  /// A table for n keys (load ≤ 1/2), without room for the keys themselves.
  void reserve_table(std::size_t n) {
    std::size_t cap = slots_.size();
    while (cap < 2 * n + 2) cap *= 2;
    if (cap != slots_.size()) rehash(cap);
  }

 private:
  bool equal(std::uint32_t id, const std::uint32_t* key) const {  // inline: keys are a few words
    const std::uint32_t* a = keys_.data() + static_cast<std::size_t>(id) * words_;
    std::uint32_t diff = 0;
    for (int i = 0; i < words_; ++i) diff |= a[i] ^ key[i];
    return diff == 0;
  }
  struct SlotLoad {
    const std::uint64_t* slots;
    std::uint64_t operator()(std::size_t s) const { return slots[s]; }
  };
  SlotLoad slot_loader() const { return {slots_.data()}; }
  // Slots are moved by their tags alone (see linear_probe.h), almost sequentially.
  void rehash(std::size_t capacity) {
    UninitializedHugeVector<std::uint64_t> old = zeroed_huge_vector<std::uint64_t>(capacity);
    old.swap(slots_);
    probe_ = LinearProbe(capacity);
    for (const std::uint64_t slot : old)
      if (slot != 0) slots_[probe_.find_empty(LinearProbe::tag_of(slot), slot_loader())] = slot;
  }

  int words_;
  std::uint32_t size_ = 0;
  LinearProbe probe_;
  UninitializedHugeVector<std::uint32_t> keys_;
  UninitializedHugeVector<std::uint64_t> slots_;
  UninitializedHugeVector<std::uint64_t> unindexed_;  // slot entries of appended keys, in id order
};

}  // namespace coxmesh
