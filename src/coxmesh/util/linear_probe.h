// The one probing scheme of coxmesh's hash tables (PackedKeyIndex, SharedVertexValues, the parallel
// walk's merge): open addressing with linear probing over 2^b 64-bit slots, each 0 (empty) or
// tag << 32 | payload, where the tag is the top 32 bits of the key's 64-bit hash and the payload
// names where the key is stored (never 0). A key's home slot is the leading b bits of its tag, so
// home slots keep their order when the table doubles: growing moves slots by their tags alone,
// without reading a key, in one mostly sequential pass.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

namespace coxmesh {

class LinearProbe {
 public:
  /// A table of `capacity` slots, a power of two ≤ 2^32.
  explicit LinearProbe(std::size_t capacity = 1) : mask_(capacity - 1), shift_(32 - std::countr_zero(capacity)) {}

  std::size_t capacity() const { return mask_ + 1; }
  int bits() const { return 32 - shift_; }  ///< b: capacity = 2^b
  std::size_t home(std::uint32_t tag) const { return static_cast<std::size_t>(tag) >> shift_; }
  std::size_t next(std::size_t slot) const { return (slot + 1) & mask_; }

  static std::uint32_t tag_of(std::uint64_t hash) { return static_cast<std::uint32_t>(hash >> 32); }
  static std::uint32_t payload(std::uint64_t entry) { return static_cast<std::uint32_t>(entry); }
  static std::uint64_t entry(std::uint64_t hash, std::uint32_t payload) { return (hash >> 32 << 32) | payload; }

  /// The first slot from the tag's home on for which stop(slot) is true.
  template <class Stop>
  std::size_t walk(std::uint32_t tag, Stop&& stop) const {
    std::size_t s = home(tag);
    while (!stop(s)) s = next(s);
    return s;
  }

  /// Where the key with this tag is, or where it would go: the first slot from its home on that is
  /// empty or holds the tag with a payload of which same_key(payload) is true. load(slot) reads a
  /// slot (an atomic table loads with the order it needs); keys are compared on a tag match only.
  template <class Load, class SameKey>
  std::size_t find(std::uint32_t tag, Load&& load, SameKey&& same_key) const {
    return walk(tag, [&](std::size_t s) {
      const std::uint64_t e = load(s);
      return e == 0 || (static_cast<std::uint32_t>(e >> 32) == tag && same_key(payload(e)));
    });
  }

  /// The first empty slot from the tag's home on: where a key known to be absent goes.
  template <class Load>
  std::size_t find_empty(std::uint32_t tag, Load&& load) const {
    return walk(tag, [&](std::size_t s) { return load(s) == 0; });
  }

 private:
  std::size_t mask_;
  int shift_;
};

}  // namespace coxmesh
