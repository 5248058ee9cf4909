// Thesis §3.3: canonical form, order, packing, hashing and the text form of a simplex.
#include "coxmesh/lattice/simplex.h"

#include <algorithm>
#include <charconv>
#include <ostream>
#include <sstream>

namespace coxmesh {

void check_dimension(int d) {
  if (d < 1 || d > kMaxDimension)
    throw InputError("dimension " + std::to_string(d) +
                     " is not supported (1 <= d <= " + std::to_string(kMaxDimension) + ")");
}

void check_lattice_range(std::span<const std::int32_t> y) {
  for (std::int32_t v : y)
    if (v > kMaxLatticeCoordinate || v < -kMaxLatticeCoordinate)
      throw InputError("lattice coordinate " + std::to_string(v) + " is out of range (|y_i| <= 2^30)");
}

int Simplex::block_size(int j) const {
  int n = 0;
  for (int i = 0; i <= d; ++i) n += (block[i] == j);
  return n;
}

std::vector<std::vector<int>> Simplex::partition() const {
  std::vector<std::vector<int>> parts(k + 1);
  for (int i = 0; i <= d; ++i) parts[block[i]].push_back(i);
  return parts;
}

Simplex Simplex::from_partition(std::span<const std::int32_t> y, const std::vector<std::vector<int>>& blocks) {
  const int d = static_cast<int>(y.size());
  check_dimension(d);
  check_lattice_range(y);
  if (blocks.empty() || blocks.size() > static_cast<std::size_t>(d + 1))
    throw InputError("a simplex in dimension " + std::to_string(d) + " needs 1 to " + std::to_string(d + 1) +
                     " blocks, got " + std::to_string(blocks.size()));
  Simplex s;
  s.d = static_cast<std::uint8_t>(d);
  s.k = static_cast<std::uint8_t>(blocks.size() - 1);
  std::copy(y.begin(), y.end(), s.y.begin());
  std::array<bool, kMaxDimension + 1> seen{};
  for (std::size_t j = 0; j < blocks.size(); ++j) {
    if (blocks[j].empty()) throw InputError("block " + std::to_string(j) + " of the partition is empty");
    for (int i : blocks[j]) {
      if (i < 0 || i > d) throw InputError("index " + std::to_string(i) + " is outside {0.." + std::to_string(d) + "}");
      if (seen[i]) throw InputError("index " + std::to_string(i) + " appears in two blocks");
      seen[i] = true;
      s.block[i] = static_cast<std::uint8_t>(j);
    }
  }
  for (int i = 0; i <= d; ++i)
    if (!seen[i]) throw InputError("index " + std::to_string(i) + " is missing from the partition");
  if (s.block[d] != s.k)
    throw InputError("the special index " + std::to_string(d) + " must be in the last block (canonical form)");
  return s;
}

Simplex Simplex::vertex_simplex(std::span<const std::int32_t> y) {
  const int d = static_cast<int>(y.size());
  check_dimension(d);
  check_lattice_range(y);
  Simplex s;
  s.d = static_cast<std::uint8_t>(d);
  std::copy(y.begin(), y.end(), s.y.begin());
  return s;
}

bool operator<(const Simplex& a, const Simplex& b) {
  if (a.d != b.d) return a.d < b.d;
  for (int i = 0; i < a.d; ++i)
    if (a.y[i] != b.y[i]) return a.y[i] < b.y[i];
  if (a.k != b.k) return a.k > b.k;
  // Compare the sorted blocks as sequences of sequences.
  for (int j = 0; j <= a.k; ++j) {
    int ia = 0, ib = 0;
    while (true) {
      while (ia <= a.d && a.block[ia] != j) ++ia;
      while (ib <= b.d && b.block[ib] != j) ++ib;
      if (ia > a.d || ib > b.d) {
        if (ia > a.d && ib > b.d) break;  // equal blocks
        return ia > a.d;                  // the shorter (a prefix) is smaller
      }
      if (ia != ib) return ia < ib;
      ++ia, ++ib;
    }
  }
  return false;
}

const Simplex kBlankSimplex{};

bool is_packed_simplex(const std::uint32_t* words, int d, int k) {
  if (d < 1 || d > kMaxDimension || k < 0 || k > d) return false;
  // (branch-free over the coordinates: a valid key, the common case, reads them all anyway)
  bool in_range = true;
  for (int i = 0; i < d; ++i)
    in_range &= static_cast<std::uint32_t>(words[i]) + std::uint32_t{kMaxLatticeCoordinate} <=
                2 * std::uint32_t{kMaxLatticeCoordinate};
  const auto* labels = reinterpret_cast<const unsigned char*>(words + d);  // (in memory order, as pack() copies them)
  const int label_bytes = 4 * ((d + 1 + 3) / 4);
  std::uint32_t seen = 0, beyond_k = 0;
  for (int i = 0; i <= d; ++i) {
    beyond_k |= labels[i] > k;
    seen |= std::uint32_t{1} << (labels[i] & 31);
  }
  unsigned char padding = 0;
  for (int i = d + 1; i < label_bytes; ++i) padding |= labels[i];
  const std::uint32_t all = k == 31 ? ~0u : (std::uint32_t{1} << (k + 1)) - 1;
  return in_range && !beyond_k && padding == 0 && labels[d] == k && seen == all;
}

std::uint64_t hash_value(const Simplex& s) {
  std::array<std::uint32_t, packed_words(kMaxDimension)> w;
  pack(s, w.data());
  return hash_words(w.data(), packed_words(s.d));
}

std::string to_string(const Simplex& s) {
  std::string out = "(";
  for (int i = 0; i < s.d; ++i) {
    if (i) out += ',';
    out += std::to_string(s.y[i]);
  }
  out += ") [";
  for (int j = 0; j <= s.k; ++j) {
    if (j) out += ',';
    out += '{';
    bool first = true;
    for (int i = 0; i <= s.d; ++i)
      if (s.block[i] == j) {
        if (!first) out += ',';
        out += std::to_string(i);
        first = false;
      }
    out += '}';
  }
  out += ']';
  return out;
}

std::ostream& operator<<(std::ostream& os, const Simplex& s) { return os << to_string(s); }

namespace {

// A tiny cursor over the text with precise error messages.
struct Cursor {
  std::string_view text;
  std::size_t pos = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("malformed simplex \"" + std::string(text) + "\" at position " + std::to_string(pos) + ": " +
                     what);
  }
  void skip_space() {
    while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
  }
  bool accept(char c) {
    skip_space();
    if (pos < text.size() && text[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!accept(c)) fail(std::string("expected '") + c + "'");
  }
  long long integer() {
    skip_space();
    long long v = 0;
    const char* b = text.data() + pos;
    const char* e = text.data() + text.size();
    if (b != e && *b == '+') ++b;
    auto [ptr, ec] = std::from_chars(b, e, v);
    if (ec == std::errc::result_out_of_range) fail("integer out of range");
    if (ec != std::errc()) fail("expected an integer");
    pos = static_cast<std::size_t>(ptr - text.data());
    return v;
  }
};

}  // namespace

Simplex parse_simplex(std::string_view text) {
  Cursor c{text};
  c.expect('(');
  std::vector<std::int32_t> y;
  if (!c.accept(')')) {
    do {
      long long v = c.integer();
      if (v > kMaxLatticeCoordinate || v < -kMaxLatticeCoordinate)
        c.fail("lattice coordinate out of range (|y_i| <= 2^30)");
      y.push_back(static_cast<std::int32_t>(v));
      if (y.size() > static_cast<std::size_t>(kMaxDimension)) c.fail("more than 31 coordinates");
    } while (c.accept(','));
    c.expect(')');
  }
  if (y.empty()) c.fail("the vertex has no coordinates");
  c.expect('[');
  std::vector<std::vector<int>> blocks;
  do {
    c.expect('{');
    std::vector<int> b;
    if (!c.accept('}')) {
      do {
        long long v = c.integer();
        if (v < 0 || v > static_cast<long long>(y.size()))
          c.fail("index " + std::to_string(v) + " is outside {0.." + std::to_string(y.size()) + "}");
        if (!b.empty() && v <= b.back()) c.fail("block indices must be strictly increasing");
        b.push_back(static_cast<int>(v));
      } while (c.accept(','));
      c.expect('}');
    }
    blocks.push_back(std::move(b));
  } while (c.accept(','));
  c.expect(']');
  c.skip_space();
  if (c.pos != text.size()) c.fail("unexpected trailing text");
  return Simplex::from_partition(y, blocks);
}

}  // namespace coxmesh
